"""Robustness of the anti-sway feedback: configs/study_anti_sway.yaml run by crane-sim study.

The operator's slew and hoist of configs/crane_anti_sway.yaml, then the lever's release, on the
load's mass (390 t ± 20 %) × the hoist rope's length (−5 %, as planned, +3 %), each with the
feedback holding the boom head from the release and open loop. For each pair: the hook's largest
swing about the boom head from 5 s after the release on and over the last 10 s, open and closed
loop, the reduction, and the hoist rope's largest tension. Writes
benchmarks/results/anti_sway_study.csv and anti_sway_study.png.

    python3 benchmarks/anti_sway_study.py            # ≈ 15 s on 2 cores
"""

import argparse
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np

from benchmark_csv import machine, pyplot, write_rows

ROOT = Path(__file__).resolve().parents[1]
STUDY = ROOT / "configs" / "study_anti_sway.yaml"
CLOSED_FROM = 20.0  # feedback.start of the closed-loop cases; the open loop's lies past the run


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crane-sim", default=str(ROOT / "build" / "crane-sim"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results" / "anti_sway_study.csv"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        table = Path(work) / "study.h5"
        subprocess.run([args.crane_sim, "study", str(STUDY), "-o", str(table), "--jobs", str(args.jobs), "--quiet"],
                       check=True)
        with h5py.File(table) as f:
            status = f["cases/status"].asstr()[...]
            if not np.all(status == "complete"):
                raise SystemExit(f"error: cases did not complete: {sorted(set(status))}")
            mass = f["parameters/bodies.load.mass"][...]
            rope = f["parameters/members.hoist_rope.length.value"][...]
            closed = f["parameters/feedback.start"][...] == CLOSED_FROM
            figures = {name: f[f"figures/{name}"][...] for name in ("sway_from_25_s", "sway_last_10_s", "hoist_tension_max")}
    rows = []
    for m in np.unique(mass):
        for length in np.unique(rope):
            case = (mass == m) & (rope == length)
            c, o = np.flatnonzero(case & closed)[0], np.flatnonzero(case & ~closed)[0]
            rows.append({"load_t": f"{m / 1000:.0f}", "hoist_rope_m": f"{length:.3f}",
                         "open_from_25_s_m": f"{figures['sway_from_25_s'][o]:.4f}",
                         "closed_from_25_s_m": f"{figures['sway_from_25_s'][c]:.4f}",
                         "open_last_10_s_m": f"{figures['sway_last_10_s'][o]:.4f}",
                         "closed_last_10_s_m": f"{figures['sway_last_10_s'][c]:.4f}",
                         "reduction_last_10_s": f"{1 - figures['sway_last_10_s'][c] / figures['sway_last_10_s'][o]:.3f}",
                         "open_tension_max_n": f"{figures['hoist_tension_max'][o]:.4g}",
                         "closed_tension_max_n": f"{figures['hoist_tension_max'][c]:.4g}",
                         "machine": machine()})
    write_rows(args.out, rows)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9, 4))
    labels = [f"{r['load_t']} t\n{r['hoist_rope_m']} m" for r in rows]
    x = np.arange(len(rows))
    ax.bar(x - 0.2, [float(r["open_last_10_s_m"]) for r in rows], 0.4, label="open loop")
    ax.bar(x + 0.2, [float(r["closed_last_10_s_m"]) for r in rows], 0.4, label="anti-sway from the release")
    ax.set_yscale("log")
    ax.set_ylim(0.005, 10.0)  # room above the bars for the legend
    ax.set_xticks(x, labels, fontsize=8)
    ax.set_ylabel("largest swing, last 10 s [m]")
    ax.set_title("load mass × hoist rope length", fontsize=10)
    ax.legend(loc="upper right", ncol=2)
    fig.tight_layout()
    fig.savefig(Path(args.out).with_suffix(".png"), dpi=100)
    for r in rows:
        print(f"{r['load_t']:>4} t  {r['hoist_rope_m']:>7} m   last 10 s: open {r['open_last_10_s_m']} m, closed "
              f"{r['closed_last_10_s_m']} m ({100 * float(r['reduction_last_10_s']):.0f} % less)")
    print(f"results: {args.out}")


if __name__ == "__main__":
    main()
