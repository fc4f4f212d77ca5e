"""Load position and rope tension over time for a rope member of a cranesim run.

The rope's tension at its ends is the force of the constraints that hold them: the norm of
their /lambda columns (recomputed at each sample from the saddle-point system). The load is
the joint the constraint at the rope's end connects it to. Prints the peak tension and the
load's height range.

Example:

    crane-sim run configs/rope_drop.yaml -o drop.h5
    python scripts/plot_rope.py drop.h5 -o drop_rope.png
"""

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from cranesim.results import Results, ResultsError, run_command


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("results", help="results file")
    parser.add_argument("--rope", help="rope member name (default: the only member)")
    parser.add_argument("-o", "--output", help="output image (default: <results>_rope.png)")
    return parser.parse_args()


def rope_name(results: Results, requested: str | None) -> str:
    segments = results.names("/model/member_segments") if results.has("model/member_segments") else []
    members = sorted({joint.split(".")[0] for joint in np.ravel(segments)})
    if requested is not None:
        if requested not in members:
            raise ResultsError(f"no member '{requested}' in {results.path}; members: {', '.join(members) or 'none'}")
        return requested
    if len(members) != 1:
        raise ResultsError(f"{results.path} has members {', '.join(members) or 'none'}: choose one with --rope")
    return members[0]


def end_constraint(results: Results, joint: str) -> tuple[str, str] | None:
    """(constraint name, the other joint) of the first constraint holding `joint`, or None."""
    names = results.names("/model/constraints")
    pairs = results.names("/model/constraint_joints")
    for name, (first, second) in zip(names, pairs):
        if joint in (first, second):
            return name, second if first == joint else first
    return None


def constraint_force(results: Results, constraint: str) -> np.ndarray:
    rows = results.names("/model/constraint_rows")
    columns = [k for k, row in enumerate(rows) if row.split("/")[0] == constraint and row.split("/")[1] in "xyz"]
    return np.linalg.norm(results.get("lambda")[:, columns], axis=1)


def main() -> None:
    args = parse_arguments()
    path = Path(args.results)
    with Results(path) as results:
        rope = rope_name(results, args.rope)
        time = results.sampled_time()
        hook = end_constraint(results, f"{rope}.end")
        if hook is None:
            raise ResultsError(f"no constraint holds {rope}.end in {path}: there is no load to plot")
        constraint, load = hook
        load_position = results.get(f"joints/{load}/position")
        tensions = {f"at {load} ({constraint})": constraint_force(results, constraint)}
        top = end_constraint(results, f"{rope}.start")
        if top is not None:
            tensions[f"at {top[1]} ({top[0]})"] = constraint_force(results, top[0])
        status = results.status

    figure, (position_axes, tension_axes) = plt.subplots(2, 1, sharex=True, figsize=(9, 6.5))
    for column, axis in enumerate("xyz"):
        if np.ptp(load_position[:, column]) > 0.0 or axis == "z":
            position_axes.plot(time, load_position[:, column], label=f"{load} {axis}")
    position_axes.set_ylabel("load position [m]")
    for label, values in tensions.items():
        tension_axes.plot(time, values / 1e3, label=label)
    tension_axes.set_ylabel(f"{rope} tension [kN]")
    tension_axes.set_xlabel("time [s]")
    for axes in (position_axes, tension_axes):
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize="small")
    figure.suptitle(path.name if status == "complete" else f"{path.name} ({status})")
    figure.tight_layout()
    output = Path(args.output) if args.output else path.with_name(f"{path.stem}_rope.png")
    figure.savefig(output, dpi=100)

    end_tension = next(iter(tensions.values()))
    peak = int(np.argmax(end_tension))
    print(f"peak tension at {load}: {end_tension[peak]:.6g} N at t = {time[peak]:.6g} s")
    print(f"{load} height: {load_position[:, 2].min():.6g} .. {load_position[:, 2].max():.6g} m")
    print(f"wrote {output}")


if __name__ == "__main__":
    sys.exit(run_command(main))
