#!/usr/bin/env python3
"""The obstacle-clearing minimum-time lifts' table in docs/planning.md: configs/target_wall_minimum_time.yaml
and configs/target_building_minimum_time.yaml planned on the thesis crane (super truss) and the
condensed crane, with their obstacles and without, each `--runs` times; prints a Markdown row per
target and crane with the medians of the times.

    python3 scripts/obstacle_lift_table.py [--crane-opt build/crane-opt] [--runs 3]
"""

import argparse
import tempfile
from pathlib import Path

import h5py

from plan_tables import load_average, median, sway, timed_plans

SOURCE_DIR = Path(__file__).resolve().parents[1]
TARGETS = {"wall": SOURCE_DIR / "configs" / "target_wall_minimum_time.yaml",
           "building": SOURCE_DIR / "configs" / "target_building_minimum_time.yaml"}
CRANES = {"super truss": "crane.yaml", "condensed": "crane_condensed.yaml"}


def plan(crane_opt: str, text: str, tmp: Path, runs: int) -> tuple[dict, list[float], list[float]]:
    """Plans the target text `runs` times; the last plan's attributes and the NLP and whole-plan times."""
    target, out = tmp / "target.yaml", tmp / "plan.h5"
    target.write_text(text)
    nlp, whole = timed_plans(crane_opt, target, out, runs)
    with h5py.File(out, "r") as f:
        arrival, after = sway(f)
        result = {"motion": f["path"].attrs["motion_time"], "arrival": arrival, "after": after,
                  "iterations": int(f["path"].attrs["nlp_iterations"])}
        if "clearance" in f:
            c = f["clearance"].attrs
            result["clearance"], result["part"] = c["distance"], c["closest_part"]
    return result, nlp, whole


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--crane-opt", default=str(SOURCE_DIR / "build" / "crane-opt"))
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    print(f"load average {load_average()} at the start")
    print("| target | crane | motion (without obstacles) | verified clearance | sway 0–5 s / after (without) | "
          "NLP iterations (without) | NLP (without) | whole plan |")
    print("|---|---|---|---|---|---|---|---|")
    for name, path in TARGETS.items():
        for crane, scene in CRANES.items():
            text = path.read_text().replace("scene: crane_condensed.yaml", f"scene: {SOURCE_DIR / 'configs' / scene}")
            free_text = text[:text.index("\nobstacles:")] + "\n"
            with tempfile.TemporaryDirectory() as tmp:
                with_, nlp, whole = plan(args.crane_opt, text, Path(tmp), args.runs)
                without, free_nlp, _ = plan(args.crane_opt, free_text, Path(tmp), args.runs)
            print(f"| {name} | {crane} | {with_['motion']:.1f} s ({without['motion']:.1f} s) | {with_['clearance']:.2f} m "
                  f"({with_['part']}) | ±{with_['arrival'] * 100:.1f} / ±{with_['after'] * 100:.1f} cm "
                  f"(±{without['arrival'] * 100:.1f} / ±{without['after'] * 100:.1f} cm) | "
                  f"{with_['iterations']} ({without['iterations']}) | {median(nlp):.1f} s ({median(free_nlp):.1f} s) | "
                  f"{median(whole):.1f} s |",
                  flush=True)


if __name__ == "__main__":
    main()
