"""Plans tracked by feedback on cranes that differ from the planned one: crane-opt plan on the
shipped targets (configs/target.yaml, Table 8-2; configs/target_slewing.yaml, with 45° of
slewing), each with its eight feedback cases (the load ±20 %, the hoist rope ±5 % longer than its
encoder says, a 0.5 m initial swing seen by an exact and by a late noisy sensor, a 50 kN gust
across the boom, a 3 s gust of wind to 9.8 m/s), on the super truss crane (as shipped) and the condensed crane. For each case, open loop and tracked: the load's sway in the
5 s after the planned arrival and from 5 s after it, the settling time within 5 cm, the dynamic
factor of the hoist rope, the drives' peaks and work, the controller's time per sample and the
run's real-time factor. Writes benchmarks/results/plan_tracking.csv and plan_tracking.png.

    python3 benchmarks/plan_tracking.py            # ≈ 8 min on 2 cores
"""

import argparse
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np

from benchmark_csv import machine, pyplot, write_rows

ROOT = Path(__file__).resolve().parents[1]
TARGETS = {"Table 8-2": ROOT / "configs" / "target.yaml", "45° slewing": ROOT / "configs" / "target_slewing.yaml"}
CRANES = {"super truss": ROOT / "configs" / "crane.yaml", "condensed": ROOT / "configs" / "crane_condensed.yaml"}


def plan(crane_opt: str, target: Path, scene: Path, work: Path) -> Path:
    text = target.read_text(encoding="utf-8")
    assert "scene: crane.yaml" in text
    path = work / f"{target.stem}_{scene.stem}.yaml"
    path.write_text(text.replace("scene: crane.yaml", f"scene: {scene}", 1), encoding="utf-8")
    out = path.with_suffix(".h5")
    subprocess.run([crane_opt, "plan", str(path), "-o", str(out), "--quiet"], check=True)
    return out


def rows_of(plan_file: Path, target: str, crane: str) -> list[dict]:
    with h5py.File(plan_file) as f:
        g = f["feedback"]
        cases, loops = g["case"].asstr()[...], g["loop"].asstr()[...]
        rows = []
        for k, (case, loop) in enumerate(zip(cases, loops)):
            peaks = g["drive_peaks"][k]
            rows.append({"target": target, "crane": crane, "case": case, "loop": loop,
                         "sway_0_5_s_m": f"{g['sway_at_arrival'][k]:.4f}",
                         "sway_from_5_s_m": f"{g['sway_after_5_s'][k]:.4f}",
                         "settling_time_s": f"{g['settling_time'][k]:.1f}",
                         "dynamic_factor": f"{g['dynamic_factor'][k]:.4f}",
                         "luffing_peak_speed": f"{peaks[0, 0]:.4g}", "hoist_peak_speed": f"{peaks[1, 0]:.4g}",
                         "slewing_peak_speed": f"{peaks[2, 0]:.4g}",
                         "drive_energy_MJ": f"{1e-6 * g['drive_energy'][k].sum():.3f}",
                         "controller_us_per_sample": f"{1e6 * g['controller_s_per_sample'][k]:.1f}",
                         "real_time_factor": f"{g['t_reached'][k] / g['wall_time_s'][k]:.1f}",
                         "machine": machine()})
        return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crane-opt", default=str(ROOT / "build" / "crane-opt"))
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results" / "plan_tracking.csv"))
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for crane, scene in CRANES.items():
            for target, path in TARGETS.items():
                rows += rows_of(plan(args.crane_opt, path, scene, Path(work)), target, crane)
    write_rows(args.out, rows)

    plt = pyplot()
    fig, axes = plt.subplots(1, len(TARGETS), figsize=(11, 4), sharey=True)
    for ax, target in zip(axes, TARGETS):
        chosen = [r for r in rows if r["target"] == target and r["crane"] == "super truss"]
        cases = list(dict.fromkeys(r["case"] for r in chosen))
        x = np.arange(len(cases))
        for offset, loop, label in ((-0.2, "open", "the plan alone"), (0.2, "closed", "tracked by feedback")):
            ax.bar(x + offset, [float(next(r["sway_from_5_s_m"] for r in chosen if r["case"] == c and r["loop"] == loop))
                                for c in cases], 0.4, label=label)
        ax.axhline(0.05, color="grey", linewidth=0.8, linestyle="--")
        ax.set_yscale("log")
        ax.set_ylim(0.005, 2.0)
        ax.set_xticks(x, cases, fontsize=8, rotation=20)
        ax.set_title(f"{target}, super truss crane", fontsize=10)
    axes[0].set_ylabel("largest sway from 5 s after arrival [m]")
    axes[0].legend(loc="upper left")
    fig.tight_layout()
    fig.savefig(Path(args.out).with_suffix(".png"), dpi=100)
    for r in rows:
        print(f"{r['target']:<12} {r['crane']:<12} {r['case']:<20} {r['loop']:<6} from 5 s {r['sway_from_5_s_m']} m, "
              f"{r['real_time_factor']}× real time")
    print(f"results: {args.out}")


if __name__ == "__main__":
    main()
