"""Position and velocity of a body (the crane's load) against time, like the thesis' Figures
8-10 … 8-13: one row per axis x, y, z; position on the left, velocity on the right.

With --sway-after T it also measures the sway period after time T (when the drives have
stopped): the horizontal velocity is projected on its principal direction, and the period is
twice the mean spacing of its zero crossings. With --pivot JOINT (the rope's upper end, e.g.
head.sheave) it compares that period with the pendulum period 2π√(L/g) of the mean distance L
from the pivot to the body's origin after T.

Example:

    crane-sim run configs/crane_slewing.yaml -o slewing.h5
    python scripts/plot_load.py slewing.h5 --sway-after 45 --pivot head.sheave -o slewing_load.png
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
    parser.add_argument("--body", default="load", help="body to plot (default: load)")
    parser.add_argument("--sway-after", type=float, metavar="T", help="measure the sway period after time T [s]")
    parser.add_argument("--pivot", metavar="JOINT", help="upper end of the pendulum, for --sway-after")
    parser.add_argument("--gravity", type=float, default=9.8, help="g for the pendulum period (default 9.8)")
    parser.add_argument("-o", "--output", help="output image (default: <results>_<body>.png)")
    return parser.parse_args()


def sway_period(time: np.ndarray, horizontal_velocity: np.ndarray) -> tuple[float, int]:
    """(period, number of zero crossings used) of the horizontal velocity's main component."""
    centred = horizontal_velocity - horizontal_velocity.mean(axis=0)
    _, _, axes = np.linalg.svd(centred, full_matrices=False)
    component = centred @ axes[0]
    crossings = np.flatnonzero(np.sign(component[:-1]) * np.sign(component[1:]) < 0)
    if crossings.size < 3:
        raise ResultsError("fewer than 3 zero crossings of the sway velocity: run longer to measure the period")
    # Linear interpolation of each crossing time.
    t0, t1 = time[crossings], time[crossings + 1]
    c0, c1 = component[crossings], component[crossings + 1]
    times = t0 - c0 * (t1 - t0) / (c1 - c0)
    return 2.0 * float(np.mean(np.diff(times))), int(crossings.size)


def main() -> None:
    args = parse_arguments()
    path = Path(args.results)
    with Results(path) as results:
        if not results.has(f"bodies/{args.body}/position"):
            raise ResultsError(f"no body '{args.body}' in {path}")
        time = results.time()
        if time.size < 2:
            raise ResultsError(f"{path} holds fewer than 2 samples")
        position = results.get(f"bodies/{args.body}/position")
        pivot = None
        if args.pivot is not None:
            if not results.has(f"joints/{args.pivot}/position"):
                raise ResultsError(f"no joint '{args.pivot}' in {path}")
            pivot = results.get(f"joints/{args.pivot}/position")
        velocity = results.get(f"bodies/{args.body}/velocity")
        status = results.status

    figure, axes = plt.subplots(3, 2, sharex=True, figsize=(11, 7.5))
    for row, axis in enumerate("xyz"):
        axes[row, 0].plot(time, position[:, row])
        axes[row, 0].set_ylabel(f"{axis} [m]")
        axes[row, 1].plot(time, velocity[:, row])
        axes[row, 1].set_ylabel(f"v{axis} [m/s]")
    axes[0, 0].set_title(f"{args.body} position")
    axes[0, 1].set_title(f"{args.body} velocity")
    for ax in axes.ravel():
        ax.grid(True, alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    figure.suptitle(path.name if status == "complete" else f"{path.name} ({status})")
    figure.tight_layout()
    output = Path(args.output) if args.output else path.with_name(f"{path.stem}_{args.body}.png")
    figure.savefig(output, dpi=100)

    start, end = position[0], position[-1]
    print(f"{args.body} at t = {time[0]:g} s: [{start[0]:.4f}, {start[1]:.4f}, {start[2]:.4f}] m; "
          f"at t = {time[-1]:g} s: [{end[0]:.4f}, {end[1]:.4f}, {end[2]:.4f}] m")
    print(f"max |y - y0|: {np.max(np.abs(position[:, 1] - start[1])):.3e} m; "
          f"max |v|: {np.max(np.linalg.norm(velocity, axis=1)):.4f} m/s")
    if args.pivot is not None and args.sway_after is None:
        raise ResultsError("--pivot needs --sway-after")
    if args.sway_after is not None:
        after = time >= args.sway_after
        period, crossings = sway_period(time[after], velocity[after, :2])
        print(f"sway period after t = {args.sway_after:g} s: {period:.4f} s ({crossings} zero crossings)")
        if pivot is not None:
            length = float(np.mean(np.linalg.norm(pivot[after] - position[after], axis=1)))
            pendulum = 2.0 * np.pi * np.sqrt(length / args.gravity)
            print(f"pendulum of length {length:.4f} m ({args.pivot} to {args.body}): {pendulum:.4f} s; "
                  f"sway / pendulum - 1 = {period / pendulum - 1:+.2%}")
    print(f"wrote {output}")


if __name__ == "__main__":
    sys.exit(run_command(main))
