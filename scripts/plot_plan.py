"""Overview figure of a crane-opt plan file (static map, fit, trajectory, controls, verification).

Panels (after Figures 8-14 to 8-18 of the thesis):
  (a) static map: end points of the grid coloured by luffing rope length, with the planned path
  (b) luffing rope length over boom angle and hoist change: map data and fitted surface
  (c) optimal trajectory: x, z and vx, vz over time; below it the controls ax, az with bounds
  (d) rope-length controls: discrete points and the cubic Hermite control splines (and the
      slewing angle of a slewing plan)
  (e) planned against simulated end-point path in the x-z plane (seen from above, x-y, for a
      slewing plan)
  (f) tracking error over time, with the verification numbers and the stage times

A map-only file (root attribute contents = "map") gets panels (a) and (b) without the fit.

Several plan files (e.g. the same target planned with method quasi_static, zv and zvd) give one
comparison figure instead: each plan's planned path (the one its controls follow) and verified
path in the x-z plane, and the load's horizontal offset from the target after the planned
arrival (along x; its horizontal distance for a slewing plan), labelled with the motion time and
the residual sway.

Example:

    crane-opt plan configs/target_luffing_jib.yaml -o jib_plan.h5
    python scripts/plot_plan.py jib_plan.h5 -o jib_plan.png
    python scripts/plot_plan.py jib_plan.h5 jib_zv_plan.h5 jib_zvd_plan.h5 -o jib_methods.png
"""

import argparse
import contextlib
import sys
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

STAGES = ("map", "fit", "trajectory", "controls", "inversion", "verification")
ROPES = (("luffing_length", "luffing rope", "C0"), ("hoist_length", "hoist rope", "C1"))


def hermite(t_query, t, y, slopes) -> np.ndarray:
    """Piecewise cubic Hermite interpolation through knots (t, y, slopes); constant outside."""
    t, y, slopes = (np.asarray(a, dtype=float) for a in (t, y, slopes))
    tq = np.clip(np.asarray(t_query, dtype=float), t[0], t[-1])
    i = np.clip(np.searchsorted(t, tq, side="right") - 1, 0, len(t) - 2)
    h = t[i + 1] - t[i]
    s = (tq - t[i]) / h
    h00, h10 = (1 + 2 * s) * (1 - s) ** 2, s * (1 - s) ** 2
    h01, h11 = s**2 * (3 - 2 * s), s**2 * (s - 1)
    return h00 * y[i] + h10 * h * slopes[i] + h01 * y[i + 1] + h11 * h * slopes[i + 1]


def control_bounds(plan: h5py.File):
    """(control_min, control_max) of the QR problem; infinite when the file predates them."""
    if "control_bounds" not in plan["trajectory"]:
        return np.full(2, -np.inf), np.full(2, np.inf)
    bounds = plan["trajectory/control_bounds"][()]
    return bounds[0], bounds[1]


def planned_path(plan: h5py.File):
    """(t, state) of the path the controls follow: /path, or /trajectory in files without it."""
    group = plan["path"] if "path" in plan else plan["trajectory"]
    return group["t"][()], group["state"][()]


def method(plan: h5py.File) -> str:
    return str(plan["path"].attrs.get("method", "quasi_static")) if "path" in plan else "quasi_static"


def slewing(plan: h5py.File) -> bool:
    return "path" in plan and "slewing_turn_deg" in plan["path"].attrs


def planned_points(verification: h5py.Group) -> np.ndarray:
    """The planned end point (x, y, z) per verification sample; files before slewing plans hold (x, z)."""
    planned = verification["planned"][()]
    if planned.shape[1] == 2:
        planned = np.column_stack([planned[:, 0], np.full(len(planned), np.nan), planned[:, 1]])
    return planned


def sway_after_arrival(plan: h5py.File):
    """(time since the planned arrival, offset from the target) of the verification from the arrival
    on: simulated x − target x, or for a slewing plan the horizontal distance from the target."""
    verification = plan["verification"]
    t, simulated = verification["t"][()], verification["simulated"][()]
    arrival = float(plan["controls"].attrs.get("lead_time", 0.0)) + planned_path(plan)[0][-1]
    target = planned_points(verification)[-1]
    after = t >= arrival
    if slewing(plan):
        return t[after] - arrival, np.linalg.norm(simulated[after, :2] - target[:2], axis=1)
    return t[after] - arrival, simulated[after, 0] - target[0]


def plot_comparison(plans: list, names: list) -> plt.Figure:
    """Each plan's planned and verified path, and the sway about the target after arrival."""
    fig, (ax_path, ax_sway) = plt.subplots(1, 2, figsize=(15, 6), layout="constrained")
    for k, (plan, name) in enumerate(zip(plans, names)):
        colour = f"C{k}"
        t, _ = planned_path(plan)
        planned, simulated = planned_points(plan["verification"]), plan["verification/simulated"][()]
        label = method(plan) if name == method(plan) else f"{method(plan)} ({name})"
        ax_path.plot(planned[:, 0], planned[:, 2], "--", color=colour, label=f"{label}: planned")
        ax_path.plot(simulated[:, 0], simulated[:, 2], "-", color=colour, lw=1, label=f"{label}: verified")
        since, offset = sway_after_arrival(plan)
        sway = plan["verification"].attrs.get("residual_sway", np.nan)
        ax_sway.plot(since, offset, color=colour,
                     label=f"{label}: motion {t[-1] - t[0]:.4g} s, residual sway ±{sway:.3g} m")
    first = plans[0]
    ax_path.plot(*(first["trajectory/origin"][()] + first["trajectory/start"][0, :2]), "go", label="start")
    ax_path.plot(*(first["trajectory/origin"][()] + first["trajectory/target"][0, :2]), "ks", label="target")
    ax_path.set(xlabel="x [m]", ylabel="z [m]", title="end-point path: planned and verified")
    ax_path.set_aspect("equal", adjustable="datalim")
    ax_path.legend(loc="best", fontsize="small")
    ax_sway.axhline(0.0, color="0.5", lw=0.8)
    ax_sway.set(xlabel="time since the planned arrival [s]",
                ylabel="horizontal distance from the target [m]" if slewing(first) else "simulated x − target x [m]",
                title="sway after arrival")
    ax_sway.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize="small")
    fig.suptitle("crane-opt plans: " + ", ".join(names))
    return fig


def panel_map(ax, plan: h5py.File) -> None:
    """(a) End points of the grid (mesh lines, coloured by luffing rope length) and the path the controls
    follow, labelled by the plan's method (with the QR trajectory dotted when the method is another)."""
    m = plan["map"]
    x, z, luffing = m["end_x"][()], m["end_z"][()], m["luffing_length"][()]
    ax.plot(x, z, color="0.8", lw=0.6, zorder=1)
    ax.plot(x.T, z.T, color="0.8", lw=0.6, zorder=1)
    failed = np.count_nonzero(~np.isfinite(x + z + luffing))  # no equilibrium found: NaN
    label = "map grid points" + (f" ({failed} of {x.size} failed)" if failed else "")
    points = ax.scatter(x, z, c=luffing, s=14, cmap="viridis", zorder=2, label=label)
    plt.colorbar(points, ax=ax, label="luffing rope length [m]")
    if "trajectory" in plan:
        origin = plan["trajectory/origin"][()]
        if method(plan) != "quasi_static":  # the controls follow another path than the QR trajectory
            qr = origin + plan["trajectory/state"][:, :2]
            ax.plot(qr[:, 0], qr[:, 1], "r:", lw=1, zorder=3, label="QR trajectory (not followed)")
        path = origin + planned_path(plan)[1][:, :2]
        ax.plot(path[:, 0], path[:, 1], "r-", lw=2, zorder=3, label=f"planned path ({method(plan)})")
        ax.plot(*path[0], "go", zorder=4, label="start")
        ax.plot(*path[-1], "ks", zorder=4, label="target")
    ax.set(xlabel="end point x [m]", ylabel="end point z [m]", title="(a) static map: end points")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(loc="best", fontsize="small")


def panel_fit(ax, plan: h5py.File) -> None:
    """(b) Luffing rope length over boom angle × hoist change: data wireframe and fitted surface."""
    m = plan["map"]
    hoist, angle = np.meshgrid(m["hoist_change"][()], m["boom_angle"][()])
    ax.plot_wireframe(hoist, angle, m["luffing_length"][()], color="k", lw=0.7, label="map data")
    title = "(b) luffing rope length"
    if "fit" in plan:
        fit = plan["fit"]
        ax.plot_surface(hoist, angle, fit["luffing_length"][()], color="C1", alpha=0.3)
        residual = fit["luffing_length"].attrs.get("max_residual", fit.attrs.get("max_residual", np.nan))
        kind = fit.attrs.get("type", "fit")
        if kind == "polynomial" and "order_boom_angle" in fit.attrs:
            kind += f" ({fit.attrs['order_boom_angle']}, {fit.attrs['order_hoist_change']})"
        title += f"\n{kind} fit, max residual {residual:.2g} m"
        ax.plot([], [], color="C1", alpha=0.5, lw=6, label="fit")
    ax.set(xlabel="hoist change [m]", ylabel="boom angle [°]", zlabel="luffing rope [m]", title=title)
    ax.legend(loc="upper left", fontsize="small")


def panel_trajectory(axes, plan: h5py.File) -> None:
    """(c) Optimal trajectory over time on three stacked axes: x, z; vx, vz; controls ax, az with bounds."""
    ax_position, ax_velocity, ax_control = axes
    trajectory = plan["trajectory"]
    t, state = trajectory["t"][()], trajectory["state"][()]
    origin = trajectory["origin"][()]
    for column, (name, colour) in enumerate((("x", "C0"), ("z", "C3"))):
        ax_position.plot(t, state[:, column] + origin[column], color=colour, label=name)
        ax_velocity.plot(t, state[:, column + 2], color=colour, ls="--", label="v" + name)
    ax_position.set(ylabel="position [m]",
                    title=f"(c) optimal trajectory (cost {trajectory.attrs.get('cost', np.nan):.4g})")
    ax_velocity.set(ylabel="velocity [m/s]")
    for ax in (ax_position, ax_velocity):
        ax.legend(loc="best", fontsize="small", ncol=2)
        ax.tick_params(labelbottom=False)

    control = trajectory["control"][()]
    for column, (name, colour) in enumerate((("ax", "C0"), ("az", "C3"))):
        ax_control.stairs(control[:, column], t, baseline=None, color=colour, label=name)
    lower, upper = control_bounds(plan)
    for column, colour in enumerate(("C0", "C3")):
        for bound in (lower[column], upper[column]):
            if np.isfinite(bound):
                ax_control.axhline(bound, color=colour, ls="--", lw=0.8)
    ax_control.plot([], [], "k--", lw=0.8, label="bounds")
    ax_control.set(xlabel="trajectory time [s]", ylabel="acceleration [m/s²]")
    ax_control.legend(loc="best", fontsize="small", ncol=3)


def panel_controls(ax, plan: h5py.File) -> None:
    """(d) Luffing and hoist rope length: discrete controls and the Hermite control splines."""
    controls = plan["controls"]
    lead = float(controls.attrs.get("lead_time", 0.0))
    for name, label, colour in ROPES:
        spline = controls[f"spline/{name}"]
        knots = spline["t"][()]
        dense = np.linspace(knots[0], knots[-1], 400)
        ax.plot(dense, hermite(dense, knots, spline["y"][()], spline["slopes"][()]), color=colour,
                label=f"{label}: spline")
        ax.plot(knots, spline["y"][()], "o", color=colour, ms=3, mfc="none")
        ax.plot(controls["t"][()] + lead, controls[name][()], ".", color=colour, ms=2,
                label=f"{label}: discrete")
    ax.axvline(lead, color="0.5", ls=":", label=f"motion start ({lead:.2f} s)")
    ax.plot([], [], "ko", ms=3, mfc="none", label="spline knots")
    ax.set(xlabel="simulation time [s]", ylabel="rope length [m]", title="(d) rope-length controls")
    handles, labels = ax.get_legend_handles_labels()
    if "spline/slewing_angle" in controls:
        spline = controls["spline/slewing_angle"]
        knots = spline["t"][()]
        dense = np.linspace(knots[0], knots[-1], 400)
        twin = ax.twinx()
        twin.plot(dense, np.degrees(hermite(dense, knots, spline["y"][()], spline["slopes"][()])), color="C4",
                  label="slewing angle: spline")
        twin.set_ylabel("slewing angle [°]")
        extra_handles, extra_labels = twin.get_legend_handles_labels()
        handles, labels = handles + extra_handles, labels + extra_labels
    ax.legend(handles, labels, loc="best", fontsize="small")


def panel_paths(ax, plan: h5py.File) -> None:
    """(e) Planned against simulated end-point path in the x-z plane, or seen from above (x-y) for a
    slewing plan."""
    verification = plan["verification"]
    planned, simulated = planned_points(verification), verification["simulated"][()]
    second = 1 if slewing(plan) else 2
    ax.plot(planned[:, 0], planned[:, second], "k--", label="planned")
    ax.plot(simulated[:, 0], simulated[:, second], "C2-", lw=1, label="simulated")
    if "inversion" in plan and not slewing(plan):
        reached = plan["inversion/reached"][()]
        ax.plot(reached[:, 0], reached[:, 1], "C1x", label="inversion checks")
    ax.plot(planned[0, 0], planned[0, second], "go", label="start")
    ax.plot(planned[-1, 0], planned[-1, second], "ks", label="target")
    view = "seen from above, " if slewing(plan) else ""
    ax.set(xlabel="x [m]", ylabel="y [m]" if slewing(plan) else "z [m]",
           title=f"(e) planned vs simulated ({view}{verification.attrs.get('status', '?')})")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(loc="best", fontsize="small")


def panel_error(ax, plan: h5py.File) -> None:
    """(f) Tracking error over simulation time, with the verification numbers and stage times."""
    verification = plan["verification"]
    t = verification["t"][()]
    planned, simulated = planned_points(verification), verification["simulated"][()]
    columns = [0, 1, 2] if np.isfinite(planned[:, 1]).all() else [0, 2]
    ax.plot(t, np.linalg.norm(simulated[:, columns] - planned[:, columns], axis=1), "C2-")
    lead = float(plan["controls"].attrs.get("lead_time", 0.0))
    end = lead + planned_path(plan)[0][-1]
    ax.axvspan(lead, end, color="0.9", label="planned motion")
    ax.set(xlabel="simulation time [s]", ylabel="‖simulated − planned‖ [m]", title="(f) tracking error")
    a = verification.attrs
    lines = [f"max error      {a.get('max_error', np.nan):.3g} m",
             f"RMS error      {a.get('rms_error', np.nan):.3g} m",
             f"residual sway  {a.get('residual_sway', np.nan):.3g} m",
             f"final error    {a.get('final_error', np.nan):.3g} m", "stage times:"]
    timing = plan["timing"].attrs
    lines += [f"  {stage:<13}{timing[stage + '_s']:.3g} s" for stage in STAGES if stage + "_s" in timing]
    ax.set_ylim(top=1.6 * ax.get_ylim()[1])  # room for the text box above the curve
    ax.text(0.98, 0.97, "\n".join(lines), transform=ax.transAxes, ha="right", va="top", ma="left",
            family="monospace", fontsize="x-small", bbox=dict(boxstyle="round", facecolor="white", alpha=0.85))
    ax.legend(loc="upper left", fontsize="small")


def plot_plan(plan: h5py.File) -> plt.Figure:
    if plan.attrs.get("contents", "plan") == "map":
        fig = plt.figure(figsize=(12, 5), layout="constrained")
        panel_map(fig.add_subplot(1, 2, 1), plan)
        panel_fit(fig.add_subplot(1, 2, 2, projection="3d"), plan)
    else:
        fig = plt.figure(figsize=(19, 11), layout="constrained")
        grid = fig.add_gridspec(2, 3)
        panel_map(fig.add_subplot(grid[0, 0]), plan)
        panel_fit(fig.add_subplot(grid[0, 1], projection="3d"), plan)
        trajectory_grid = grid[0, 2].subgridspec(3, 1)
        ax_position = fig.add_subplot(trajectory_grid[0])
        panel_trajectory([ax_position] + [fig.add_subplot(trajectory_grid[row], sharex=ax_position)
                                          for row in (1, 2)], plan)
        panel_controls(fig.add_subplot(grid[1, 0]), plan)
        panel_paths(fig.add_subplot(grid[1, 1]), plan)
        panel_error(fig.add_subplot(grid[1, 2]), plan)
    fig.suptitle(f"crane-opt {plan.attrs.get('contents', 'plan')}: {plan.attrs.get('target_path', '')}")
    return fig


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("plans", type=Path, nargs="+", metavar="plan",
                        help="plan file written by crane-opt plan (HDF5); several: a comparison figure")
    parser.add_argument("-o", "--output", type=Path,
                        help="output image (default: <first plan>_plan.png, or _compare.png for several)")
    args = parser.parse_args(argv)
    first = args.plans[0]
    output = args.output or first.with_name(first.stem + ("_plan.png" if len(args.plans) == 1 else "_compare.png"))
    with contextlib.ExitStack() as stack:
        files = []
        for path in args.plans:
            try:
                files.append(stack.enter_context(h5py.File(path, "r")))
            except OSError as error:
                print(f"plot_plan.py: error: {path}: {error}", file=sys.stderr)
                return 2
        try:
            fig = plot_plan(files[0]) if len(files) == 1 else plot_comparison(files, [p.stem for p in args.plans])
        except KeyError as error:
            print(f"plot_plan.py: error: {', '.join(map(str, args.plans))}: {error}", file=sys.stderr)
            return 2
    fig.savefig(output, dpi=110)
    plt.close(fig)
    print(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
