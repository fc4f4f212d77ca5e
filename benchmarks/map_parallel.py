"""Speed-up of crane-opt's static map sweep from parallelism (thesis 6.2, issue: "the map step's
speed-up measured on 2 cores").

Runs `crane-opt map TARGET --threads N` for each thread count, `--reps` times, alternating the
thread counts so that load on the shared machine hits both alike, and records the sweep's wall
time (the map file's map/sweep_time_s: the scene's own equilibrium, which is serial, is
reported apart). The map values must agree between thread counts (same continuation path).
Optionally coarsens the target's grid (--angle-step, --hoist-step) for a quicker study.

Writes a CSV (default benchmarks/results/map_parallel.csv): one row per run, then the medians.

    python3 benchmarks/map_parallel.py --bin build/crane-opt                       # thesis grid, ≈ 15 min
    python3 benchmarks/map_parallel.py --angle-step 5 --hoist-step 4 --reps 3      # 9 × 7 points
"""

import argparse
import csv
import re
import statistics
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def coarsened_target(target: Path, angle_step: float | None, hoist_step: float | None, directory: Path) -> Path:
    """The target with its grid steps replaced, written next to the original's scene reference."""
    text = target.read_text()
    text = re.sub(r"scene: (\S+)", lambda m: f"scene: {(target.parent / m[1]).resolve()}", text, count=1)
    if angle_step:
        text = re.sub(r"(boom_angle: \{from: [-\d.]+, to: [-\d.]+, step: )[\d.]+", rf"\g<1>{angle_step}", text)
    if hoist_step:
        text = re.sub(r"(hoist_change: \{from: [-\d.]+, to: [-\d.]+, step: )[\d.]+", rf"\g<1>{hoist_step}", text)
    out = directory / target.name
    out.write_text(text)
    return out


def run_map(binary: str, target: Path, threads: int, out: Path) -> dict:
    subprocess.run([binary, "map", str(target), "-o", str(out), "--threads", str(threads), "--quiet"], check=True,
                   capture_output=True, text=True)
    with h5py.File(out, "r") as f:
        m = f["map"]
        return {"threads": threads, "points": m["luffing_length"].size, "sweep_s": m.attrs["sweep_time_s"],
                "start_s": m.attrs["start_time_s"], "jacobians": int(m.attrs["jacobians"]),
                "luffing": m["luffing_length"][...], "end_z": m["end_z"][...]}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "crane-opt"), help="crane-opt binary")
    parser.add_argument("--target", default=str(ROOT / "configs" / "target.yaml"))
    parser.add_argument("--threads", default="1,2", help="comma-separated thread counts")
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--angle-step", type=float)
    parser.add_argument("--hoist-step", type=float)
    parser.add_argument("-o", "--output", default=str(ROOT / "benchmarks" / "results" / "map_parallel.csv"))
    args = parser.parse_args(argv)
    thread_counts = [int(t) for t in args.threads.split(",")]

    with tempfile.TemporaryDirectory() as tmp:
        directory = Path(tmp)
        target = coarsened_target(Path(args.target), args.angle_step, args.hoist_step, directory)
        runs = []
        for rep in range(args.reps):
            for threads in thread_counts:
                run = run_map(args.bin, target, threads, directory / f"map_{threads}.h5")
                runs.append(run)
                print(f"rep {rep + 1}: {threads} threads, {run['points']} points: sweep {run['sweep_s']:.2f} s, "
                      f"{run['jacobians']} Jacobians", flush=True)
    reference = runs[0]
    deviation = max(max(np.max(np.abs(r["luffing"] - reference["luffing"])), np.max(np.abs(r["end_z"] - reference["end_z"])))
                    for r in runs)
    medians = {t: statistics.median(r["sweep_s"] for r in runs if r["threads"] == t) for t in thread_counts}
    with open(args.output, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["threads", "points", "sweep_s", "start_s", "jacobians"])
        for r in runs:
            writer.writerow([r["threads"], r["points"], f"{r['sweep_s']:.3f}", f"{r['start_s']:.3f}", r["jacobians"]])
        for t in thread_counts:
            writer.writerow([t, reference["points"], f"median {medians[t]:.3f}", "",
                             f"speed-up {medians[thread_counts[0]] / medians[t]:.3f}"])
    for t in thread_counts:
        print(f"{t} threads: median sweep {medians[t]:.2f} s, speed-up {medians[thread_counts[0]] / medians[t]:.2f}×")
    print(f"largest difference between runs (luffing length, end z): {deviation:.3g} m")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
