#!/usr/bin/env python3
"""The minimum-time lift's table in docs/planning.md: configs/target_minimum_time.yaml planned
on the thesis crane (super truss) and the condensed crane, each `--runs` times; prints a Markdown
row per crane with the medians of the times.

    python3 scripts/minimum_time_table.py [--crane-opt build/crane-opt] [--runs 3]
"""

import argparse
import tempfile
from pathlib import Path

import h5py

from plan_tables import load_average, median, sway, timed_plans

SOURCE_DIR = Path(__file__).resolve().parents[1]
TARGET = SOURCE_DIR / "configs" / "target_minimum_time.yaml"
CRANES = {"thesis crane (super truss)": "crane.yaml", "condensed crane": "crane_condensed.yaml"}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crane-opt", default=str(SOURCE_DIR / "build" / "crane-opt"))
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    print(f"load average {load_average()} at the start")
    print("| crane | motion (flatness) | sway 0–5 s / after | hoist peaks m/s, m/s² | luffing peak m/s | limit factor | NLP | whole plan |")
    print("|---|---|---|---|---|---|---|---|")
    for name, scene in CRANES.items():
        with tempfile.TemporaryDirectory() as tmp:
            target = Path(tmp) / "target.yaml"
            target.write_text(TARGET.read_text().replace("scene: crane.yaml", f"scene: {SOURCE_DIR / 'configs' / scene}"))
            out = Path(tmp) / "plan.h5"
            nlp, whole = timed_plans(args.crane_opt, target, out, args.runs)
            with h5py.File(out, "r") as plan:
                path, controls = plan["path"].attrs, plan["controls"].attrs
                arrival, after = sway(plan)
                print(f"| {name} | {path['motion_time']:.2f} s ({path['flatness_duration']:.1f} s) | ±{arrival * 100:.1f} / "
                      f"±{after * 100:.1f} cm | {controls['hoist_peak_speed']:.3f}, {controls['hoist_peak_acceleration']:.4f} | "
                      f"{controls['luffing_peak_speed']:.3f} | {controls['drive_limit_factor']:.4f} | "
                      f"{median(nlp):.2f} s | {median(whole):.1f} s |")


if __name__ == "__main__":
    main()
