"""Time series of recorded quantities from one or more cranesim runs.

QUANTITY is a dataset path with an optional component selector, e.g.
energy/balance, lambda[0], joints/link2.tip/position[2],
bodies/link1/velocity[norm] (see cranesim.results). Vector quantities
without a selector are drawn one line per component. Several runs are compared
by giving RESULTS as a comma-separated list; lines are labelled by file stem.

Example:

    python scripts/plot_timeseries.py ggl.h5,baumgarte.h5 energy/balance \\
        joints/link2.tip/position[2] --subplots -o compare.png
"""

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from cranesim.results import Results, ResultsError, guess_unit, run_command


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "results", help="results file, or comma-separated list of files to compare"
    )
    parser.add_argument("quantities", nargs="+", metavar="QUANTITY", help="quantity path[selector]")
    parser.add_argument(
        "-o", "--output", help="output image (default: <first results>_timeseries.png)"
    )
    parser.add_argument("--title", help="figure title (default: the results file names)")
    parser.add_argument("--subplots", action="store_true", help="one subplot per quantity")
    return parser.parse_args()


def read_runs(paths: list[Path], quantities: list[str]) -> list[tuple[str, np.ndarray, dict]]:
    """(legend name, time, {quantity: values as (N, columns)}) for each results file."""
    runs = []
    for path in paths:
        with Results(path) as results:
            time = results.sampled_time()
            values = {}
            for quantity in quantities:
                data = results.get(quantity)
                if data.shape[0] != time.size:
                    raise ResultsError(
                        f"'{quantity}' in {path} has {data.shape[0]} samples, /time has {time.size}"
                    )
                values[quantity] = data.reshape(time.size, -1)
            name = path.stem if results.status == "complete" else f"{path.stem} ({results.status})"
        runs.append((name, time, values))
    return runs


def plot_on(axes, runs, quantities: list[str]) -> None:
    for name, time, values in runs:
        for quantity in quantities:
            data = values[quantity]
            label = name if len(quantities) == 1 else f"{name} {quantity}"
            for column in range(data.shape[1]):
                suffix = f"[{column}]" if data.shape[1] > 1 else ""
                axes.plot(time, data[:, column], label=label + suffix)
    units = "; ".join(dict.fromkeys(guess_unit(quantity) for quantity in quantities))
    axes.set_ylabel(f"{', '.join(quantities)} [{units}]")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")


def main() -> None:
    args = parse_arguments()
    paths = [Path(name) for name in args.results.split(",") if name]
    if not paths:
        raise ResultsError("no results file given")
    output = args.output or paths[0].with_name(f"{paths[0].stem}_timeseries.png")
    runs = read_runs(paths, args.quantities)

    groups = [[quantity] for quantity in args.quantities] if args.subplots else [args.quantities]
    figure, axes_list = plt.subplots(
        len(groups), 1, sharex=True, squeeze=False, figsize=(9, 1.5 + 2.5 * len(groups))
    )
    for axes, group in zip(axes_list[:, 0], groups):
        plot_on(axes, runs, group)
    axes_list[-1, 0].set_xlabel("time [s]")
    figure.suptitle(args.title or ", ".join(path.name for path in paths))
    figure.tight_layout()
    figure.savefig(output, dpi=100)
    print(f"wrote {output}")


if __name__ == "__main__":
    sys.exit(run_command(main))
