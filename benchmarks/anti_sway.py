"""Anti-sway feedback against open loop on the flexible thesis crane, case by case.

The condensed crane (configs/crane_inputs.yaml) stepped at 50 Hz from Python, each case once open
loop and once with cranesim.control.AntiSway:

- release: the lever slews at 3 °/s for 15 s and hoists at 0.3 m/s for 20 s, then lets go; the
  feedback holds the boom head from the release on. Also with the load 20 % heavier and lighter
  than the scene's 390 t (the controller's design does not know the load).
- gust across / along: 50 kN on the load across or along the boom, rising and falling over 3 s
  (2-5 s); the feedback holds the head from the start.

Operator assistance (an operator's lever with stops and a reversal) is benchmarks/operator_assistance.py.

For each case: the largest swing of the hook about the boom head (m) from 5 to 10 s after the
last stop (or the gust's end) and over the last 10 s of the run, open loop and closed loop, and
the reduction. Writes benchmarks/results/anti_sway.csv and anti_sway.png (the swing over time).

    python3 benchmarks/anti_sway.py            # ≈ 15 s on 2 cores
"""

import argparse
import math
from pathlib import Path

import numpy as np

import cranesim
from cranesim.control import AntiSway
from benchmark_csv import machine, pyplot, write_rows

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "configs" / "crane_inputs.yaml"
DT = 0.02


def gust(direction):
    return [{"name": "gust", "joint": "load.origin", "force": [5e4 * direction[0], 5e4 * direction[1], 0.0],
             "scale": {"type": "cosine_full", "base": 0, "peak": 1, "t_start": 2, "t_end": 5}}]


def release_lever(t):
    return 3.0 if t < 15.0 else 0.0, -0.3 if t < 20.0 else 0.0


# name: (scene changes, lever(t) -> (slewing °/s, hoist m/s), the feedback from (s), the last stop (s), t_end (s))
CASES = {
    "release": ({}, release_lever, 20.0, 20.0, 60.0),
    "release, load +20 %": ({"modify": {"bodies.load.mass": 1.2 * 390000.6}}, release_lever, 20.0, 20.0, 60.0),
    "release, load -20 %": ({"modify": {"bodies.load.mass": 0.8 * 390000.6}}, release_lever, 20.0, 20.0, 60.0),
    "gust across": ({"loads": gust((0, 1))}, lambda t: (0.0, 0.0), 0.0, 5.0, 40.0),
    "gust along": ({"loads": gust((1, 0))}, lambda t: (0.0, 0.0), 0.0, 5.0, 40.0),
}


def run(changes, lever, feedback_from, t_end, feedback):
    """The swing of the hook about the head (m) at every sample, and the solver statistics."""
    sim = cranesim.Simulation({"base": str(SCENE), "name": "anti-sway case", **changes})
    hook, head = sim.joint("load.origin"), sim.joint("head.sheave")
    controller = None
    swing = []
    for k in range(int(round(t_end / DT))):
        t = k * DT
        slewing, hoist = lever(t)
        if feedback and t >= feedback_from and controller is None:
            controller = AntiSway(sim)
        if controller is None:
            sim.set_inputs({"slewing": slewing, "hoist_rope": hoist})
        else:
            controller.apply(slewing=slewing, hoist=hoist)
        if not sim.advance_to((k + 1) * DT):
            raise RuntimeError(sim.message)
        offset = sim.joint_position(hook) - sim.joint_position(head)
        swing.append(math.hypot(offset[0], offset[1]))
    return np.array(swing), sim.statistics()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results" / "anti_sway.csv"))
    args = parser.parse_args()
    rows, curves = [], {}
    for name, (changes, lever, feedback_from, last_stop, t_end) in CASES.items():
        t = np.arange(1, int(round(t_end / DT)) + 1) * DT
        after = (t > last_stop + 5.0) & (t <= last_stop + 10.0)
        last = t > t_end - 10.0
        row = {"case": name}
        for label, feedback in (("open", False), ("closed", True)):
            swing, stats = run(changes, lever, feedback_from, t_end, feedback)
            curves[(name, label)] = (t, swing)
            row[f"{label}_5_10_s_m"] = f"{swing[after].max():.4f}"
            row[f"{label}_last_10_s_m"] = f"{swing[last].max():.4f}"
            row[f"{label}_real_time_factor"] = f"{t_end / stats['wall_time_s']:.0f}"
        row["reduction_last_10_s"] = f"{1.0 - float(row['closed_last_10_s_m']) / float(row['open_last_10_s_m']):.3f}"
        row["machine"] = machine()
        rows.append(row)
        print(f"{name:22} 5-10 s after: open {row['open_5_10_s_m']} m, closed {row['closed_5_10_s_m']} m;  "
              f"last 10 s: open {row['open_last_10_s_m']} m, closed {row['closed_last_10_s_m']} m "
              f"({100 * float(row['reduction_last_10_s']):.0f} % less)")
    write_rows(args.out, rows)
    plt = pyplot()
    figure, axes = plt.subplots(len(CASES), 1, figsize=(8, 2.0 * len(CASES)), sharex=False)
    for axis, name in zip(axes, CASES):
        for label, style in (("open", "--"), ("closed", "-")):
            t, swing = curves[(name, label)]
            axis.plot(t, swing, style, label=f"{label} loop")
        axis.set_title(name, fontsize=9)
        axis.set_ylabel("swing [m]")
    axes[0].legend()
    axes[-1].set_xlabel("t [s]")
    figure.tight_layout()
    figure.savefig(Path(args.out).with_suffix(".png"), dpi=110)
    print(f"results: {args.out}")


if __name__ == "__main__":
    main()
