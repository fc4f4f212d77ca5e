"""The crane driven step by step from Python, against the same run driven from C++.

The 60 s combined motion of 8.3.2 on the condensed thesis crane (configs/crane_inputs.yaml),
commanded at 50 Hz: each drive's speed is its trapezoid's speed at the sample and the slewing
rate adds the sway-damping feedback of bench_session_stepping, so every command differs from the
last. In one run, alternating, --reps times each:
- C++: bench_session_stepping's `inputs` row (second-order lags, as the scene), the same law in C++;
- Python: the same law in a Python loop over cranesim.Simulation.
Reports the median wall times, the real-time factors and the Python loop's overhead; the
Gymnasium environment's throughput is measured by gym_throughput.py.

Writes benchmarks/results/python_stepping.csv.

    python3 benchmarks/python_stepping.py            # ≈ 10 s on 2 cores
"""

import argparse
import csv
import math
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import cranesim
from benchmark_csv import machine, write_rows

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "configs" / "crane_inputs.yaml"


def trapezoid_speed(t, distance, t_start, duration, t_accel, t_decel):
    """The speed of a trapezoid profile (E-1..E-5) at t, rounded as the C++ benchmark's (the
    derivative of the profile, left limits at its corners), so that both runs get the same
    commands to the last bit."""
    t1, t3, t0 = t_accel, t_decel, duration
    t2 = t0 - t1 - t3
    a1 = 2.0 * distance / (t1 * (2.0 * t0 - t1 - t3))
    a3 = -2.0 * distance / (t3 * (2.0 * t0 - t1 - t3))
    vmax = a1 * t1
    tau = t - t_start
    if tau <= 0.0:
        return 0.0
    if tau <= t1:
        return a1 * tau
    if tau <= t1 + t2:
        return vmax
    if tau <= t0:
        return vmax + a3 * (tau - (t1 + t2))
    return 0.0


def python_run(t_end, dt=0.02):
    sim = cranesim.Simulation(SCENE)
    hook, head = sim.joint("load.origin"), sim.joint("head.sheave")
    order = [sim.inputs.index(n) for n in ("slewing", "hoist_rope", "luffing_rope")]
    commands = np.zeros(len(sim.inputs))
    start = time.perf_counter()
    for k in range(int(round(t_end / dt))):
        t = sim.time
        r, hook_r = sim.joint_position(head), sim.joint_position(hook)
        radius = math.sqrt(r[0] * r[0] + r[1] * r[1])  # as the C++ loop rounds it (not hypot)
        across = (-r[1] / radius, r[0] / radius)
        sway = (hook_r[0] - r[0]) * across[0] + (hook_r[1] - r[1]) * across[1]  # across the boom
        commands[order[0]] = trapezoid_speed(t, 45, 10, 20, 5, 5) + 0.44 * sway / radius * 180.0 / math.pi
        commands[order[1]] = trapezoid_speed(t, -20, 0, 40, 5, 5)
        commands[order[2]] = trapezoid_speed(t, 5, 20, 20, 5, 5)
        sim.set_inputs(commands)
        if not sim.advance_to((k + 1) * dt):  # the C++ loop's sample times, to the bit
            raise RuntimeError(sim.message)
    wall = time.perf_counter() - start
    return wall, sim.statistics(), sim.joint_position(hook)


def cpp_run(binary, t_end):
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "session.csv"
        subprocess.run([str(binary), "--configs", str(ROOT / "configs"), "--out", str(out), "--t-end", str(t_end),
                        "--reps", "1", "--only", "inputs2", "--no-reference"], check=True, capture_output=True, text=True)
        rows = list(csv.DictReader(out.open()))
    row = next(r for r in rows if r["method"] == "inputs" and r["order"] == "2")
    return float(row["wall_s"]), int(row["steps"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", default=str(ROOT / "build" / "benchmarks" / "bench_session_stepping"))
    parser.add_argument("--t-end", type=float, default=60.0)
    parser.add_argument("--reps", type=int, default=5)
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results" / "python_stepping.csv"))
    args = parser.parse_args()
    cpp, python, steps = [], [], {}
    for _ in range(args.reps):
        wall, steps["C++"] = cpp_run(args.bin, args.t_end)
        cpp.append(wall)
        wall, stats, _ = python_run(args.t_end)
        python.append(wall)
        steps["Python"] = stats["steps"]
    rows = []
    for name, walls in (("C++", cpp), ("Python", python)):
        wall = statistics.median(walls)
        rows.append({"driver": name, "t_end": args.t_end, "sample_interval": 0.02, "reps": args.reps,
                     "wall_s": f"{wall:.4f}", "real_time_factor": f"{args.t_end / wall:.1f}", "steps": steps[name],
                     "machine": machine()})
    overhead = statistics.median(python) / statistics.median(cpp) - 1.0
    for row in rows:
        row["python_overhead"] = f"{overhead:.4f}"
    write_rows(args.out, rows)
    for row in rows:
        print(f"{row['driver']:7} {row['wall_s']} s  {row['real_time_factor']}× real time  {row['steps']} steps")
    print(f"Python loop overhead: {100 * overhead:.1f} %   results: {args.out}")


if __name__ == "__main__":
    main()
