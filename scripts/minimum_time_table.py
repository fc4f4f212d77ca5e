#!/usr/bin/env python3
"""The minimum-time lift's table in docs/planning.md: configs/target_minimum_time.yaml planned
on the thesis crane (super truss) and the condensed crane, each `--runs` times; prints a Markdown
row per crane with the medians of the times.

    python3 scripts/minimum_time_table.py [--crane-opt build/crane-opt] [--runs 3]
"""

import argparse
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

SOURCE_DIR = Path(__file__).resolve().parents[1]
TARGET = SOURCE_DIR / "configs" / "target_minimum_time.yaml"
CRANES = {"thesis crane (super truss)": "crane.yaml", "condensed crane": "crane_condensed.yaml"}


def sway(plan: h5py.File) -> tuple[float, float]:
    """The load's largest horizontal distance from the target in the 5 s after the planned
    arrival, and after those to the end of the run, m."""
    v = plan["verification"]
    arrival = plan["controls"].attrs["lead_time"] + plan["path"].attrs["motion_time"]
    t, off = v["t"][()], np.linalg.norm((v["simulated"][()] - v["planned"][-1])[:, :2], axis=1)
    return float(off[(t >= arrival) & (t <= arrival + 5)].max()), float(off[t > arrival + 5].max())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crane-opt", default=str(SOURCE_DIR / "build" / "crane-opt"))
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    print("| crane | motion (flatness) | sway 0–5 s / after | hoist peaks m/s, m/s² | luffing peak m/s | limit factor | NLP | whole plan |")
    print("|---|---|---|---|---|---|---|---|")
    for name, scene in CRANES.items():
        nlp, whole = [], []
        with tempfile.TemporaryDirectory() as tmp:
            target = Path(tmp) / "target.yaml"
            target.write_text(TARGET.read_text().replace("scene: crane.yaml", f"scene: {SOURCE_DIR / 'configs' / scene}"))
            out = Path(tmp) / "plan.h5"
            for _ in range(args.runs):
                started = time.perf_counter()
                subprocess.run([args.crane_opt, "plan", str(target), "-o", str(out), "--quiet"], check=True, capture_output=True)
                whole.append(time.perf_counter() - started)
                with h5py.File(out, "r") as plan:
                    nlp.append(plan["path"].attrs["nlp_time_s"])
            with h5py.File(out, "r") as plan:
                path, controls = plan["path"].attrs, plan["controls"].attrs
                arrival, after = sway(plan)
                print(f"| {name} | {path['motion_time']:.2f} s ({path['flatness_duration']:.1f} s) | ±{arrival * 100:.1f} / "
                      f"±{after * 100:.1f} cm | {controls['hoist_peak_speed']:.3f}, {controls['hoist_peak_acceleration']:.4f} | "
                      f"{controls['luffing_peak_speed']:.3f} | {controls['drive_limit_factor']:.4f} | "
                      f"{statistics.median(nlp):.2f} s | {statistics.median(whole):.1f} s |")


if __name__ == "__main__":
    main()
