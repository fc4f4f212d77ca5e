#!/usr/bin/env python3
"""Plots of the static bending study (thesis 8.1.1; benchmarks/README.md, bench_element_bending).

usage: plot_element_bending.py CSV [-o out.png] [--time wall|cpu]

Left: tip position error (relative to L) against the moment ratio K, one line per element
type and segment count (direct solves from the straight beam). Middle: tip rotation error
against K. Right: work-precision, tip error against the median wall (or CPU) time of the solve;
filled markers are direct solves, open ones the K continuation. Cases that did not converge
are left out of the lines and marked with a cross at the top of the left panel. Errors below
1e-14 (round-off) are drawn at 1e-14. Exits with status 2 on a missing or malformed CSV.

Example:

    build/benchmarks/bench_element_bending
    python3 benchmarks/plot_element_bending.py benchmarks/results/element_bending.csv
"""

import argparse
import math
import os
import sys

import benchmark_csv
from benchmark_csv import BadFile

COLUMNS = [
    "type", "segments", "K", "bend_per_segment_deg", "strategy", "converged", "newton_iterations",
    "load_steps", "wall_time_s_median", "cpu_time_s_median", "tip_error_rel", "rotation_error_rad",
]
INTEGER_COLUMNS = {"segments", "converged", "newton_iterations", "load_steps"}
TEXT_COLUMNS = {"type", "strategy"}
TYPE_STYLE = {"timoshenko": ("tab:red", "--", "T-beam"), "spline_beam": ("tab:blue", "-", "C-beam")}
FLOOR = 1e-14


def read_rows(path):
    return benchmark_csv.read_rows(path, COLUMNS, "bench_element_bending", INTEGER_COLUMNS, TEXT_COLUMNS)



def usable(row):
    return row["converged"] == 1 and math.isfinite(row["tip_error_rel"]) and math.isfinite(row["rotation_error_rad"])


def floored(x):
    return max(x, FLOOR)


def plot(rows, out, time_column):
    plt = benchmark_csv.pyplot()

    types = [t for t in TYPE_STYLE if any(r["type"] == t for r in rows)]
    types += sorted({r["type"] for r in rows} - set(types))
    sizes = sorted({r["segments"] for r in rows})
    # Marker and shade encode the segment count within a type's colour.
    markers = dict(zip(sizes, "osD^vp*h"))
    shade = {n: 0.35 + 0.65 * (i / max(1, len(sizes) - 1)) for i, n in enumerate(sizes)}

    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(17, 6))
    for t in types:
        color, dash, label = TYPE_STYLE.get(t, ("tab:gray", ":", t))
        for n in sizes:
            line = sorted((r for r in rows if r["type"] == t and r["segments"] == n and r["strategy"] == "direct"),
                          key=lambda r: r["K"])
            ok = [r for r in line if usable(r)]
            style = dict(color=color, alpha=shade[n], marker=markers[n], mec="k", mew=0.5)
            if ok:
                ax1.plot([r["K"] for r in ok], [floored(r["tip_error_rel"]) for r in ok], dash, label=f"{label} n={n}",
                         **style)
                ax2.plot([r["K"] for r in ok], [floored(r["rotation_error_rad"]) for r in ok], dash, **style)
            failed = [r for r in line if not usable(r)]
            if failed:
                ax1.plot([r["K"] for r in failed], [1.0] * len(failed), "x", color=color, ms=10, mew=2)
            for strategy, face in (("direct", color), ("continuation", "none")):
                pts = [r for r in rows if r["type"] == t and r["segments"] == n and r["strategy"] == strategy
                       and usable(r) and r[time_column] > 0]
                ax3.plot([r[time_column] for r in pts], [floored(r["tip_error_rel"]) for r in pts], ls="",
                         marker=markers[n], mfc=face, mec=color, alpha=shade[n], ms=7)
    for ax in (ax1, ax2, ax3):
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    ax1.set_xlabel("K = M / M_circle")
    ax1.set_ylabel("tip position error / L")
    ax1.set_title("Tip error vs K (direct; x: not converged)")
    ax2.set_xlabel("K = M / M_circle")
    ax2.set_ylabel("tip rotation error (rad)")
    ax2.set_title("Tip rotation error vs K")
    ax3.set_xscale("log")
    ax3.set_xlabel(("CPU" if time_column.startswith("cpu") else "wall") + " time of the solve (s, median)")
    ax3.set_ylabel("tip position error / L")
    ax3.set_title("Work-precision (filled: direct, open: continuation)")
    ax1.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description="Plots of bench_element_bending results (thesis 8.1.1).",
                                epilog="Example: python3 benchmarks/plot_element_bending.py "
                                       "benchmarks/results/element_bending.csv -o bending.png")
    p.add_argument("csv", help="CSV written by bench_element_bending")
    p.add_argument("-o", "--output", help="image to write (default: CSV with .png)")
    p.add_argument("--time", choices=["wall", "cpu"], default="wall",
                   help="time axis of the work-precision panel (cpu: steadier on a shared machine)")
    args = p.parse_args(argv)
    out = args.output or os.path.splitext(args.csv)[0] + ".png"
    try:
        rows = read_rows(args.csv)
    except BadFile as e:
        return benchmark_csv.fail("plot_element_bending.py", e)
    if not any(usable(r) for r in rows):
        return benchmark_csv.fail("plot_element_bending.py", f"{args.csv}: no converged case to plot")
    plot(rows, out, f"{args.time}_time_s_median")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
