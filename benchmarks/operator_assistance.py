"""Operator assistance on the flexible thesis crane: a joystick's stop-and-go slew with a
reversal and a hoist, the load's swing after each stop, assisted and not.

The condensed crane (configs/crane_inputs.yaml) stepped at 50 Hz from Python. The lever:

- slews at +3 °/s from 0 to 8 s while it hoists the load 2.4 m (0.3 m/s, 2–10 s);
- slews back at −3 °/s from 26 to 32 s while it lowers the load 2.4 m (28–34 s); then rests.

Three ways to drive the crane with it:

- lever: the lever's speeds are the drives' commands (no assistance);
- following: cranesim.control.AntiSway follows the lever's speeds and damps the swing;
- shaped: AntiSway(shaping=17.1, boom_period=1.4): the boom head follows the lever's path
  shaped for the crane's 17.1 s sway period, the hoist's speed is spread over the boom's 1.4 s
  period, and the feedback acts on what the crane does differently. The crane stops half a
  period later than the lever.

For each stop of the crane (its drives' references at rest; the lever's stop plus the drives'
ramps, plus the shaper's delay when shaped) the largest swing of the hook about the boom head from
5 s after it until the crane moves again (at most 15 s). Writes
benchmarks/results/operator_assistance.csv and operator_assistance.png (the swing over time).

    python3 benchmarks/operator_assistance.py            # ≈ 10 s on 2 cores
"""

import argparse
import math
import time
from pathlib import Path

import numpy as np

import cranesim
from cranesim.control import AntiSway
from benchmark_csv import machine, pyplot, write_rows

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "configs" / "crane_inputs.yaml"
DT, T_END = 0.02, 60.0
SWAY_PERIOD, BOOM_PERIOD = 17.1, 1.4  # s: the crane's sway across the boom; the boom's luffing-plane bending
SLEWING_RAMP, HOIST_RAMP = 1.5, 0.6   # s: 3 °/s at 2 °/s², 0.3 m/s at 0.5 m/s² (the scene's drive limits)


def lever(t):
    """(slewing °/s, hoist rope m/s; < 0 lifts)"""
    slewing = 3.0 if t < 8.0 else -3.0 if 26.0 <= t < 32.0 else 0.0
    hoist = -0.3 if 2.0 <= t < 10.0 else 0.3 if 28.0 <= t < 34.0 else 0.0
    return slewing, hoist


def stops(delay, hoist_spread):
    """The crane's two stops and when it moves again (s)."""
    first = max(8.0 + SLEWING_RAMP + delay, 10.0 + HOIST_RAMP + hoist_spread)
    second = max(32.0 + SLEWING_RAMP + delay, 34.0 + HOIST_RAMP + hoist_spread)
    return [(first, 26.0), (second, T_END)]


# name: (AntiSway keyword arguments or None for the lever alone, shaper delay s, hoist spread s)
CASES = {
    "lever": (None, 0.0, 0.0),
    "following": ({}, 0.0, 0.0),
    "shaped": ({"shaping": SWAY_PERIOD, "boom_period": BOOM_PERIOD}, SWAY_PERIOD / 2, BOOM_PERIOD),
}


def run(assistance):
    sim = cranesim.Simulation({"base": str(SCENE), "name": "operator assistance"})
    hook, head = sim.joint("load.origin"), sim.joint("head.sheave")
    controller = None if assistance is None else AntiSway(sim, **assistance)
    swing, controller_s = [], 0.0
    for k in range(int(round(T_END / DT))):
        slewing, hoist = lever(k * DT)
        if controller is None:
            sim.set_inputs({"slewing": slewing, "hoist_rope": hoist})
        else:
            started = time.perf_counter()
            controller.apply(slewing=slewing, hoist=hoist)
            controller_s += time.perf_counter() - started
        if not sim.advance_to((k + 1) * DT):
            raise RuntimeError(sim.message)
        offset = sim.joint_position(hook) - sim.joint_position(head)
        swing.append(math.hypot(offset[0], offset[1]))
    return np.array(swing), sim.statistics(), controller_s / (T_END / DT)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results" / "operator_assistance.csv"))
    args = parser.parse_args()
    t = np.arange(1, int(round(T_END / DT)) + 1) * DT
    rows, curves = [], {}
    for name, (assistance, delay, spread) in CASES.items():
        swing, stats, per_sample = run(assistance)
        curves[name] = swing
        row = {"case": name}
        for k, (stop, restart) in enumerate(stops(delay, spread), 1):
            window = (t > stop + 5.0) & (t <= min(restart, stop + 20.0))
            row[f"stop{k}_s"] = f"{stop:.2f}"
            row[f"stop{k}_from_5_s_m"] = f"{swing[window].max():.4f}"
        row["largest_m"] = f"{swing.max():.4f}"
        row["real_time_factor"] = f"{T_END / stats['wall_time_s']:.0f}"
        row["controller_us_per_sample"] = f"{1e6 * per_sample:.1f}"
        row["machine"] = machine()
        rows.append(row)
        print(f"{name:10} stops at {row['stop1_s']} s and {row['stop2_s']} s; largest swing from 5 s after each: "
              f"{row['stop1_from_5_s_m']} m, {row['stop2_from_5_s_m']} m  ({row['real_time_factor']}× real time)")
    write_rows(args.out, rows)
    plt = pyplot()
    figure, axis = plt.subplots(figsize=(8, 3.2))
    for name, swing in curves.items():
        axis.plot(t, swing, label=name)
    axis.axhline(0.05, color="grey", linestyle=":", label="5 cm")
    axis.set_yscale("log")
    axis.set_ylim(1e-3, 10.0)
    axis.set_xlabel("t [s]")
    axis.set_ylabel("swing of the hook about the head [m]")
    axis.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(Path(args.out).with_suffix(".png"), dpi=110)
    print(f"results: {args.out}")


if __name__ == "__main__":
    main()
