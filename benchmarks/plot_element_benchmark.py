#!/usr/bin/env python3
"""Work-precision plot of bench_element_vibration (benchmarks/README.md).

One panel per (case, damping): tip error against the converged reference of the same element
type (log) over the median wall time (log), one line per (element, segments) through its rtol
values. Runs that did not complete are left out. Exits with status 2 on a missing or malformed
CSV or when no run completed.

Example:
    python3 benchmarks/plot_element_benchmark.py benchmarks/results/element_vibration.csv \\
        -o benchmarks/results/element_vibration.png
"""

import argparse
import math
import sys
from pathlib import Path

import benchmark_csv
from benchmark_csv import BadFile

COLUMNS = ["case", "element", "segments", "rtol", "damping", "wall_time_s_median", "cpu_time_s", "steps",
           "residual_evals", "jacobian_evals", "error_test_failures", "tip_error_m", "tip_error_cross_m",
           "completed"]
INTEGER_COLUMNS = {"segments", "steps", "residual_evals", "jacobian_evals", "error_test_failures", "completed"}
TEXT_COLUMNS = {"case", "element"}
COLORS = {"timoshenko": "tab:blue", "spline_beam": "tab:red"}
SEGMENT_MARKERS = {1: "o", 3: "s", 5: "^", 10: "D"}


def read_rows(path: Path) -> list[dict]:
    return benchmark_csv.read_rows(path, COLUMNS, "bench_element_vibration", INTEGER_COLUMNS, TEXT_COLUMNS)



def usable(row: dict) -> bool:
    return (row["completed"] == 1 and math.isfinite(row["wall_time_s_median"]) and row["wall_time_s_median"] > 0
            and math.isfinite(row["tip_error_m"]) and row["tip_error_m"] > 0)


def plot(rows: list[dict], output: Path) -> None:
    good = [r for r in rows if usable(r)]
    if not good:
        raise BadFile("no completed case with a finite, positive error and wall time to plot")
    plt = benchmark_csv.pyplot()
    panels = sorted({(r["case"], r["damping"]) for r in good})
    fig, axes = plt.subplots(1, len(panels), figsize=(6.0 * len(panels), 5.0), squeeze=False)
    for ax, (case, damping) in zip(axes[0], panels):
        lines = sorted({(r["element"], r["segments"]) for r in good if (r["case"], r["damping"]) == (case, damping)})
        for element, segments in lines:
            pts = sorted((r["wall_time_s_median"], r["tip_error_m"], r["rtol"]) for r in good
                         if (r["case"], r["damping"], r["element"], r["segments"]) == (case, damping, element, segments))
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=COLORS.get(element, "k"),
                    marker=SEGMENT_MARKERS.get(segments, "x"), label=f"{element}, {segments} seg.")
            for wall, error, rtol in pts:
                ax.annotate(f"{rtol:g}", (wall, error), fontsize=6, textcoords="offset points", xytext=(3, 3))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time (s, median)")
        ax.set_ylabel("max tip error vs 10-segment reference (m)")
        ax.set_title(f"{case}, damping η = {damping:g} s" if damping > 0 else f"{case}, undamped")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(output, dpi=120)
    plt.close(fig)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", type=Path, help="CSV written by bench_element_vibration")
    parser.add_argument("-o", "--output", type=Path, help="image to write (default: CSV name with .png)")
    args = parser.parse_args()
    try:
        plot(read_rows(args.csv), args.output or args.csv.with_suffix(".png"))
    except BadFile as e:
        return benchmark_csv.fail("plot_element_benchmark.py", e)
    return 0


if __name__ == "__main__":
    sys.exit(main())
