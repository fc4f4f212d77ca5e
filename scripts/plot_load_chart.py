"""A load chart from a crane-sim study's case table: per crane configuration (e.g. luffing rope
length, or a stated radius), the largest load such that it and every lighter load of the grid are
admissible (every criterion of the study holds: /cases/admissible), with the radius of that case.
Prints the chart as a table, with each criterion's utilisation at that load (figure / max, or
min / figure for a lower bound: 100 % is the limit), the criterion that the next heavier load
violates, and the load at which that criterion's figure, interpolated linearly between the two
grid loads, reaches its limit; plots load over radius. A study over several scenes (`scenes:`)
gives one chart per scene (--group, default: the scene parameter when the table has it).

Examples:

    crane-sim study configs/study_load_chart.yaml -o chart.h5 --jobs 2
    python scripts/plot_load_chart.py chart.h5 -o chart.png
    crane-sim study configs/study_load_chart_by_radius.yaml -o by_radius.h5 --jobs 2
    python scripts/plot_load_chart.py by_radius.h5 --configuration booms.boom.equilibrium.hook_radius

A chart that must hold in every slewing direction takes the direction as a parameter of the
study and names it with --direction: a load is then admissible only when it is in every
direction, and the table names the direction in which the next heavier load fails first
(configs/study_load_chart_outriggers.yaml, the slewing drive's angle).

The "load" may be any parameter whose larger values are harder on the crane: with
`--load wind.speed --configuration bodies.load.mass` it gives, per load, the permitted wind speed
of a lift (configs/study_permitted_wind.yaml).
"""

import argparse
import sys
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from cranesim.results import ResultsError, run_command


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("table", help="a study's results file (crane-sim study)")
    parser.add_argument("--load", default="bodies.load.mass", help="the parameter that is the load (default: %(default)s)")
    parser.add_argument("--configuration", default="members.luffing_rope.length",
                        help="the parameter that sets the crane's configuration (default: %(default)s)")
    parser.add_argument("--radius", default="radius", help="the figure that is the radius (default: %(default)s)")
    parser.add_argument("--direction", help="a parameter the chart must hold over, e.g. the slewing angle: a load counts "
                        "only when admissible at every value of it")
    parser.add_argument("--group", help="a parameter with one chart per value (default: scene, when the table has it)")
    parser.add_argument("-o", "--output", help="output image (default: <table>_chart.png)")
    return parser.parse_args()


def dataset(table: h5py.File, path: str) -> np.ndarray:
    if path not in table:
        group = path.rsplit("/", 1)[0]
        known = ", ".join(table[group]) if group in table else "none"
        raise ResultsError(f"{table.filename} has no {path} (in {group}: {known})")
    return table[path][...]


def utilisation(table: h5py.File, criterion: h5py.Dataset, case: int) -> float:
    """How much of a criterion's limit a case uses: figure / max, or min / figure (1 at the limit)."""
    value = table[f"figures/{criterion.attrs['figure']}"][case]
    upper, lower = criterion.attrs["max"], criterion.attrs["min"]
    if np.isfinite(upper) and upper > 0:
        return value / upper
    if np.isfinite(lower) and lower > 0 and value > 0:
        return lower / value
    return np.nan


def load_at_limit(table: h5py.File, criterion: h5py.Dataset, load: np.ndarray, last: int, beyond: int) -> float:
    """The load at which the criterion's figure, linear in the load between the cases `last`
    (admissible) and `beyond` (violating it), reaches its bound."""
    value = table[f"figures/{criterion.attrs['figure']}"]
    v0, v1 = value[last], value[beyond]
    bound = criterion.attrs["max"] if v1 > criterion.attrs["max"] else criterion.attrs["min"]
    if not (np.isfinite(bound) and np.isfinite(v0) and np.isfinite(v1)) or v1 == v0:
        return np.nan
    return load[last] + (bound - v0) / (v1 - v0) * (load[beyond] - load[last])


def load_chart(table: h5py.File, load_name: str, configuration_name: str, radius_name: str,
               group_name: str | None = None, direction_name: str | None = None) -> list[dict]:
    """One row per group and configuration: its largest admissible load (in every direction when
    `direction_name` names one), the radius there and what limits it (and in which direction)."""
    if table.attrs.get("contents") != "study":
        raise ResultsError(f"{table.filename} is not a study's case table")
    load = dataset(table, f"parameters/{load_name}")
    configuration = dataset(table, f"parameters/{configuration_name}")
    group = dataset(table, f"parameters/{group_name}") if group_name else np.zeros_like(load)
    direction = dataset(table, f"parameters/{direction_name}") if direction_name else np.zeros_like(load)
    radius = dataset(table, f"figures/{radius_name}")
    admissible = dataset(table, "cases/admissible") == 1.0  # NaN (not computed) is not admissible
    criteria = [table[f"criteria/{k}"] for k in sorted(table["criteria"], key=int)]
    chart = []
    for group_value, value in sorted({(g, c) for g, c in zip(group, configuration)}):
        mine = (configuration == value) & (group == group_value)
        loads = np.unique(load[mine])
        at = [np.flatnonzero(mine & (load == w)) for w in loads]  # each load's cases: one per direction
        held = np.cumprod([admissible[cases].all() for cases in at]).astype(bool)  # every lighter load too
        row = {"group": group_value, "configuration": value, "load": np.nan, "radius": np.nan,
               "limit": "none in the grid", "at_limit": np.nan, "direction": "",
               "utilisation": {c.attrs["figure"]: np.nan for c in criteria}}
        count = int(held.sum())
        if count:
            last = at[count - 1]
            row.update(load=loads[count - 1], radius=radius[last].max())
            row["utilisation"] = {c.attrs["figure"]: max(utilisation(table, c, k) for k in last) for c in criteria}
        if count < len(loads):
            failing = [k for k in at[count] if not admissible[k]]
            violated = [c for c in criteria if any(c[k] == 0.0 for k in failing)]
            statuses = {table["cases/status"].asstr()[k] for k in failing}
            row["limit"] = (", ".join(c.attrs["figure"] for c in violated) if violated
                            else f"case {failing[0]} {', '.join(sorted(statuses))}")
            row["direction"] = ", ".join(f"{d:g}" for d in sorted({direction[k] for k in failing}))
            if count and violated:
                same_direction = {direction[k]: k for k in at[count - 1]}
                row["at_limit"] = min(load_at_limit(table, c, load, same_direction[direction[k]], k)
                                      for c in violated for k in failing if c[k] == 0.0)
        elif count:
            row["limit"] = "the grid's heaviest load"
        chart.append(row)
    return chart


def group_labels(table: h5py.File, group_name: str | None) -> dict:
    """A name for each value of the group parameter: a scene's file stem, or the value."""
    if not group_name:
        return {0.0: ""}
    values = np.unique(table[f"parameters/{group_name}"][...])
    description = table[f"parameters/{group_name}"].attrs.get("values", "")
    description = description.decode() if isinstance(description, bytes) else str(description)
    named = {}
    if group_name == "scene":
        words = description.split(":", 1)[-1].split()
        named = {float(words[k]): Path(words[k + 2]).stem for k in range(0, len(words) - 2, 3) if words[k + 1] == "="}
    return {value: named.get(value, f"{group_name} = {value:g}") for value in values}


def main() -> None:
    args = parse_arguments()
    path = Path(args.table)
    with h5py.File(path, "r") as table:
        group_name = args.group if args.group else ("scene" if "parameters/scene" in table else None)
        chart = load_chart(table, args.load, args.configuration, args.radius, group_name, args.direction)
        labels = group_labels(table, group_name)
        title = table.attrs.get("study_path", path.name)
        title = Path(title.decode() if isinstance(title, bytes) else str(title)).name
    names = list(chart[0]["utilisation"]) if chart else []
    width = max([len(name) for name in names] + [5])
    group_width = max([len(label) for label in labels.values()] + [0])
    print((f"{'':<{group_width}} " if group_width else "") + f"{args.configuration:>28} {args.radius + ' [m]':>12} "
          f"{args.load:>20} " + "".join(f" {name:>{width}}" for name in names) + "   limited by (at its limit)"
          + (f" in {args.direction}" if args.direction else ""))
    for row in chart:
        used = "".join(f" {row['utilisation'][name]:>{width}.0%}" if np.isfinite(row['utilisation'][name])
                       else f" {'-':>{width}}" for name in names)
        at_limit = f" ({row['at_limit']:.6g})" if np.isfinite(row["at_limit"]) else ""
        print((f"{labels[row['group']]:<{group_width}} " if group_width else "")
              + f"{row['configuration']:>28.6g} {row['radius']:>12.2f} {row['load']:>20.6g} {used}   {row['limit']}{at_limit}"
              + (f" in {row['direction']}" if args.direction and row["direction"] else ""))
    figure, (axes, used_axes) = plt.subplots(1, 2, figsize=(13, 5))
    radius = np.array([row["radius"] for row in chart])
    load = np.array([row["load"] for row in chart])
    groups = np.array([row["group"] for row in chart])
    order = np.argsort(radius)
    scale, unit = (1e3, "t") if args.load.endswith(".mass") else (1.0, "SI")  # a mass in tonnes
    markers = iter("osD^v<>")
    at_limit = np.array([row["at_limit"] for row in chart])
    for value, label in labels.items():
        mine = order[groups[order] == value]
        axes.plot(radius[mine], load[mine] / scale, "-", color="0.6", zorder=1)
        reached = mine[np.isfinite(at_limit[mine])]
        if len(reached):
            axes.plot(radius[reached], at_limit[reached] / scale, "--", zorder=1,
                      label=f"{label}{': ' if label else ''}where the limit is reached (interpolated)")
        marker = next(markers, "o")
        for limit in sorted({chart[k]["limit"] for k in mine}):
            limited = [k for k in mine if chart[k]["limit"] == limit]
            axes.plot(radius[limited], load[limited] / scale, marker, label=f"{label}{': ' if label else ''}limited by {limit}",
                      zorder=2)
    axes.set_xlabel(f"{args.radius} [m]")
    axes.set_ylabel(f"largest admissible {args.load} [{unit}]")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="x-small" if len(labels) > 1 else None)
    axes.set_title(f"{title}: load chart")
    for name in names:
        used = np.array([row["utilisation"][name] for row in chart])
        for value, label in labels.items():
            mine = order[groups[order] == value]
            used_axes.plot(radius[mine], 100 * used[mine], "o-", label=f"{label}{': ' if label else ''}{name}")
    used_axes.axhline(100, color="k", linewidth=1)
    used_axes.set_xlabel(f"{args.radius} [m]")
    used_axes.set_ylabel("utilisation at the chart's load [% of the limit]")
    used_axes.set_ylim(0, 130)
    used_axes.grid(True, alpha=0.3)
    used_axes.legend(loc="upper center", ncol=2, fontsize="x-small" if len(labels) > 1 else None)
    used_axes.set_title("each criterion at the chart's load")
    figure.tight_layout()
    output = Path(args.output) if args.output else path.with_name(f"{path.stem}_chart.png")
    figure.savefig(output, dpi=100)
    print(f"wrote {output}")


if __name__ == "__main__":
    sys.exit(run_command(main))
