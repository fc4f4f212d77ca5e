#!/usr/bin/env python3
"""Work-precision plot of the pendulum-chain benchmark, bench_pendulum_chain (benchmarks/README.md).

usage: plot_benchmark_chain.py CSV [-o out.png]

Left panel: tip error of the last link (log) against median wall time (log), one line per
(formulation, N) with a marker per rtol. Right panel: wall time against N at rtol 1e-6 for
both formulations. Runs that did not complete (completed = 0) are left out of the lines and
marked with a cross on the right panel. Exits with status 2 on a missing or malformed CSV.
"""

import argparse
import math
import os
import sys

import benchmark_csv
from benchmark_csv import BadFile

COLUMNS = [
    "n_links", "formulation", "rtol", "wall_time_s_median", "steps", "residual_evals",
    "jacobian_evals", "tip_error_m", "max_constraint_residual", "energy_drift_rel", "completed",
]
INTEGER_COLUMNS = {"n_links", "steps", "residual_evals", "jacobian_evals", "completed"}
TEXT_COLUMNS = {"formulation"}
STYLE = {"ggl": ("tab:blue", "-"), "baumgarte": ("tab:red", "--")}
RTOL_MARKERS = {1e-3: "o", 1e-4: "s", 1e-5: "^", 1e-6: "D", 1e-7: "v"}
PANEL_RTOL = 1e-6


def read_rows(path):
    return benchmark_csv.read_rows(path, COLUMNS, "bench_pendulum_chain", INTEGER_COLUMNS, TEXT_COLUMNS)



def usable(row):
    return (row["completed"] == 1 and math.isfinite(row["wall_time_s_median"]) and row["wall_time_s_median"] > 0
            and math.isfinite(row["tip_error_m"]) and row["tip_error_m"] > 0)


def marker_for(rtol):
    for r, m in RTOL_MARKERS.items():
        if math.isclose(rtol, r, rel_tol=1e-6):
            return m
    return "x"


def plot(rows, out):
    plt = benchmark_csv.pyplot()
    import matplotlib.ticker
    import numpy as np

    formulations = [f for f in STYLE if any(r["formulation"] == f for r in rows)]
    formulations += sorted({r["formulation"] for r in rows} - set(formulations))
    sizes = sorted({r["n_links"] for r in rows})
    # Line width and shade encode N within a formulation's colour.
    shade = {n: 0.35 + 0.65 * (i / max(1, len(sizes) - 1)) for i, n in enumerate(sizes)}

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(14, 7.5), gridspec_kw={"width_ratios": [1.6, 1]})
    for form in formulations:
        color, dash = STYLE.get(form, ("tab:gray", ":"))
        for n in sizes:
            pts = sorted((r for r in rows if r["formulation"] == form and r["n_links"] == n and usable(r)),
                         key=lambda r: -r["rtol"])
            if not pts:
                continue
            x = np.array([r["wall_time_s_median"] for r in pts])
            y = np.array([r["tip_error_m"] for r in pts])
            ax1.plot(x, y, dash, color=color, alpha=shade[n], lw=1.0 + 1.5 * shade[n], label=f"{form} N={n}")
            for r, xi, yi in zip(pts, x, y):
                ax1.plot(xi, yi, marker_for(r["rtol"]), color=color, alpha=shade[n], ms=6, mec="k", mew=0.5)
    ax1.set_xscale("log")
    ax1.set_yscale("log")
    ax1.set_xlabel("wall time per 5 s run (s, median)")
    ax1.set_ylabel("max tip error of the last link vs reference (m)")
    ax1.set_title("Work-precision: planar pendulum chains")
    ax1.grid(True, which="both", alpha=0.3)
    # Legends below the panel, clear of the data.
    line_handles, line_labels = ax1.get_legend_handles_labels()
    leg1 = ax1.legend(line_handles, line_labels, fontsize=7, ncol=max(1, len(sizes)), loc="upper center",
                      bbox_to_anchor=(0.5, -0.12), title="formulation, links", title_fontsize=8)
    ax1.add_artist(leg1)
    handles = [plt.Line2D([], [], ls="", marker=m, color="gray", mec="k", label=f"rtol {r:g}")
               for r, m in RTOL_MARKERS.items() if any(math.isclose(x["rtol"], r, rel_tol=1e-6) for x in rows)]
    if handles:
        ax1.legend(handles=handles, fontsize=7, ncol=len(handles), loc="upper center", bbox_to_anchor=(0.5, -0.29),
                   title="markers", title_fontsize=8)

    any_panel = False
    for form in formulations:
        color, dash = STYLE.get(form, ("tab:gray", ":"))
        sel = sorted((r for r in rows if r["formulation"] == form and math.isclose(r["rtol"], PANEL_RTOL, rel_tol=1e-6)),
                     key=lambda r: r["n_links"])
        ok = [r for r in sel if r["completed"] == 1 and r["wall_time_s_median"] > 0]
        bad = [r for r in sel if r["completed"] != 1 and r["wall_time_s_median"] > 0]
        if ok:
            any_panel = True
            ax2.plot([r["n_links"] for r in ok], [r["wall_time_s_median"] for r in ok], dash, marker="D",
                     color=color, label=form)
        if bad:
            ax2.plot([r["n_links"] for r in bad], [r["wall_time_s_median"] for r in bad], "x", color=color, ms=10,
                     label=f"{form} (failed)")
    if any_panel:
        ax2.set_xscale("log", base=2)
        ax2.set_yscale("log")
        ticks = sorted({r["n_links"] for r in rows if math.isclose(r["rtol"], PANEL_RTOL, rel_tol=1e-6)})
        ax2.set_xticks(ticks, [str(t) for t in ticks])
        ax2.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        ax2.legend(fontsize=8)
    else:
        ax2.text(0.5, 0.5, f"no completed runs at rtol {PANEL_RTOL:g}", ha="center", va="center",
                 transform=ax2.transAxes)
    ax2.set_xlabel("number of links N")
    ax2.set_ylabel("wall time per 5 s run (s, median)")
    ax2.set_title(f"Cost vs chain size at rtol {PANEL_RTOL:g}")
    ax2.grid(True, which="both", alpha=0.3)

    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description="Work-precision plot of bench_pendulum_chain results.",
                                epilog="Example: python3 benchmarks/plot_benchmark_chain.py "
                                       "benchmarks/results/pendulum_chain.csv")
    p.add_argument("csv", help="CSV written by bench_pendulum_chain")
    p.add_argument("-o", "--output", help="image to write (default: CSV with .png)")
    args = p.parse_args(argv)
    out = args.output or os.path.splitext(args.csv)[0] + ".png"
    try:
        rows = read_rows(args.csv)
    except BadFile as e:
        return benchmark_csv.fail("plot_benchmark_chain.py", e)
    if not any(usable(r) for r in rows):
        return benchmark_csv.fail("plot_benchmark_chain.py", f"{args.csv}: no completed run with a finite tip error to plot")
    plot(rows, out)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
