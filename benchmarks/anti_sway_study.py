"""Robustness of the anti-sway feedback: configs/study_anti_sway.yaml and
configs/study_anti_sway_wind.yaml run by crane-sim study.

The operator's slew and hoist of configs/crane_anti_sway.yaml, then the lever's release, on the
load's mass (390 t ± 20 %) × the hoist rope's length (−5 %, as planned, +3 %) — and in the second
study × the mean wind across the boom (still, 10 m/s, 15 m/s at 10 m, with a gust of 1.4 times
from 30 to 38 s) — each with the feedback holding the boom head from the release and open loop.
For each case: the hook's largest swing about the boom head (in wind, about its mean offset
there) from 5 s after the release on and over the last 10 s, open and closed loop, the reduction,
and the hoist rope's largest tension. Writes benchmarks/results/anti_sway_study.csv and
anti_sway_wind_study.csv, each with its plot.

    python3 benchmarks/anti_sway_study.py            # ≈ 80 s on 2 cores
"""

import argparse
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np

from benchmark_csv import machine, pyplot, write_rows

ROOT = Path(__file__).resolve().parents[1]
# study file: the results' name
STUDIES = {"study_anti_sway.yaml": "anti_sway_study.csv", "study_anti_sway_wind.yaml": "anti_sway_wind_study.csv"}
CLOSED_FROM = 20.0  # feedback.start of the closed-loop cases; the open loop's lies past the run


def run_study(crane_sim, study, jobs, out):
    with tempfile.TemporaryDirectory() as work:
        table = Path(work) / "study.h5"
        subprocess.run([crane_sim, "study", str(study), "-o", str(table), "--jobs", str(jobs), "--quiet"], check=True)
        with h5py.File(table) as f:
            status = f["cases/status"].asstr()[...]
            if not np.all(status == "complete"):
                raise SystemExit(f"error: cases did not complete: {sorted(set(status))}")
            mass = f["parameters/bodies.load.mass"][...]
            rope = f["parameters/members.hoist_rope.length.value"][...]
            wind = f["parameters/wind.speed"][...] if "wind.speed" in f["parameters"] else None
            closed = f["parameters/feedback.start"][...] == CLOSED_FROM
            figures = {name: f[f"figures/{name}"][...] for name in ("sway_from_25_s", "sway_last_10_s", "hoist_tension_max")}
    rows = []
    for speed in ([None] if wind is None else np.unique(wind)):
        for m in np.unique(mass):
            for length in np.unique(rope):
                case = (mass == m) & (rope == length) & (True if speed is None else wind == speed)
                c, o = np.flatnonzero(case & closed)[0], np.flatnonzero(case & ~closed)[0]
                row = {} if speed is None else {"wind_m_s": f"{speed:g}"}
                row.update({"load_t": f"{m / 1000:.0f}", "hoist_rope_m": f"{length:.3f}",
                            "open_from_25_s_m": f"{figures['sway_from_25_s'][o]:.4f}",
                            "closed_from_25_s_m": f"{figures['sway_from_25_s'][c]:.4f}",
                            "open_last_10_s_m": f"{figures['sway_last_10_s'][o]:.4f}",
                            "closed_last_10_s_m": f"{figures['sway_last_10_s'][c]:.4f}",
                            "reduction_last_10_s": f"{1 - figures['sway_last_10_s'][c] / figures['sway_last_10_s'][o]:.3f}",
                            "open_tension_max_n": f"{figures['hoist_tension_max'][o]:.4g}",
                            "closed_tension_max_n": f"{figures['hoist_tension_max'][c]:.4g}",
                            "machine": machine()})
                rows.append(row)
    write_rows(out, rows)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(9 if wind is None else 14, 4))
    labels = [("" if wind is None else f"{r['wind_m_s']} m/s\n") + f"{r['load_t']} t\n{r['hoist_rope_m']} m" for r in rows]
    x = np.arange(len(rows))
    ax.bar(x - 0.2, [float(r["open_last_10_s_m"]) for r in rows], 0.4, label="open loop")
    ax.bar(x + 0.2, [float(r["closed_last_10_s_m"]) for r in rows], 0.4, label="anti-sway from the release")
    ax.set_yscale("log")
    ax.set_ylim(0.005, 10.0)  # room above the bars for the legend
    ax.set_xticks(x, labels, fontsize=6 if wind is not None else 8)
    ax.set_ylabel("largest swing, last 10 s [m]")
    ax.set_title("load mass × hoist rope length" + ("" if wind is None else " × mean wind (gust 30–38 s)"), fontsize=10)
    ax.legend(loc="upper right", ncol=2)
    fig.tight_layout()
    fig.savefig(Path(out).with_suffix(".png"), dpi=100)
    for r in rows:
        print(f"{r.get('wind_m_s', '-'):>3} m/s {r['load_t']:>4} t  {r['hoist_rope_m']:>7} m   last 10 s: open "
              f"{r['open_last_10_s_m']} m, closed {r['closed_last_10_s_m']} m "
              f"({100 * float(r['reduction_last_10_s']):.0f} % less)")
    print(f"results: {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crane-sim", default=str(ROOT / "build" / "crane-sim"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results"), help="the results' directory")
    args = parser.parse_args()
    for study, name in STUDIES.items():
        run_study(args.crane_sim, ROOT / "configs" / study, args.jobs, Path(args.out) / name)


if __name__ == "__main__":
    main()
