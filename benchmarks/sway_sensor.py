"""What the anti-sway feedback tolerates of its sensor: Table 8-2 (configs/target.yaml) planned
by crane-opt on the condensed crane, its load let go 0.5 m out of plumb at the start, tracked by
the feedback while the hoist rope's angles reach it late (0 … 1 s) and with white noise (0 …
10 mrad on each angle, as many mrad/s on each rate). For each sensor: the load's largest sway in
the 5 s after the planned arrival and from 5 s after it, the settling time within 5 cm and the
dynamic factor; the plan alone (open loop) beside. Writes benchmarks/results/sway_sensor.csv and
sway_sensor.png.

    python3 benchmarks/sway_sensor.py            # ≈ 45 s on 2 cores
"""

import argparse
import subprocess
import tempfile
from pathlib import Path

import h5py

from benchmark_csv import machine, pyplot, write_rows

ROOT = Path(__file__).resolve().parents[1]
DELAYS = (0.0, 0.1, 0.2, 0.3, 0.5, 1.0)  # s
NOISES = (0.0, 0.002, 0.005, 0.01)  # rad and rad/s


def target_text() -> str:
    text = (ROOT / "configs" / "target.yaml").read_text(encoding="utf-8")
    assert "scene: crane.yaml" in text and "\n  cases:" in text
    text = text.replace("scene: crane.yaml", f"scene: {ROOT / 'configs' / 'crane_condensed.yaml'}", 1)
    cases = "".join(f"    - {{name: 'delay {d} s, noise {n}', initial_sway: 0.5, "
                    f"sensor: {{angle_noise: {n}, rate_noise: {n}, delay: {d}, seed: 1}}}}\n"
                    for d in DELAYS for n in NOISES)
    return text.split("\n  cases:")[0] + "\n  cases:\n" + cases


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crane-opt", default=str(ROOT / "build" / "crane-opt"))
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results" / "sway_sensor.csv"))
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        target = Path(work) / "target.yaml"
        target.write_text(target_text(), encoding="utf-8")
        plan = Path(work) / "plan.h5"
        subprocess.run([args.crane_opt, "plan", str(target), "-o", str(plan), "--quiet"], check=True)
        with h5py.File(plan) as f:
            g = f["feedback"]
            cases, loops = g["case"].asstr()[...], g["loop"].asstr()[...]
            for k, (case, loop) in enumerate(zip(cases, loops)):
                if loop == "open" and rows:
                    continue  # the plan alone does not read the sensor: one open-loop row
                delay, noise = DELAYS[k // 2 // len(NOISES)], NOISES[k // 2 % len(NOISES)]
                rows.append({"loop": loop, "delay_s": "" if loop == "open" else delay,
                             "noise": "" if loop == "open" else noise,
                             "sway_0_5_s_m": f"{g['sway_at_arrival'][k]:.4f}",
                             "sway_from_5_s_m": f"{g['sway_after_5_s'][k]:.4f}",
                             "settling_time_s": f"{g['settling_time'][k]:.1f}",
                             "dynamic_factor": f"{g['dynamic_factor'][k]:.4f}",
                             "controller_us_per_sample": f"{1e6 * g['controller_s_per_sample'][k]:.1f}",
                             "real_time_factor": f"{g['t_reached'][k] / g['wall_time_s'][k]:.1f}",
                             "machine": machine()})
    write_rows(args.out, rows)

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for noise in NOISES:
        chosen = [r for r in rows if r["loop"] == "closed" and r["noise"] == noise]
        ax.plot([r["delay_s"] for r in chosen], [float(r["sway_from_5_s_m"]) for r in chosen], "o-",
                label=f"noise {1e3 * noise:g} mrad, mrad/s")
    open_loop = float(next(r["sway_from_5_s_m"] for r in rows if r["loop"] == "open"))
    ax.axhline(open_loop, color="black", linewidth=0.8, label="the plan alone")
    ax.axhline(0.05, color="grey", linewidth=0.8, linestyle="--")
    ax.set_yscale("log")
    ax.set_ylim(0.01, 1.0)
    ax.set_xlabel("sensor delay [s]")
    ax.set_ylabel("largest sway from 5 s after arrival [m]")
    ax.set_title("Table 8-2, condensed crane, 0.5 m initial sway", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(Path(args.out).with_suffix(".png"), dpi=100)
    for r in rows:
        print(f"{r['loop']:<6} delay {r['delay_s']!s:<4} noise {r['noise']!s:<6} from 5 s {r['sway_from_5_s_m']} m, "
              f"settled {r['settling_time_s']} s")
    print(f"results: {args.out}")


if __name__ == "__main__":
    main()
