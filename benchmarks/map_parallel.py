"""Speed-up of crane-opt's static map from parallelism (thesis 6.2: the map's rows on the
studies' task farm, on threads and across MPI ranks).

Runs `crane-opt map TARGET` for each worker setting — `N` (`--threads N`) or `mpiN` (`mpirun -n
N`, one thread per rank) — `--reps` times, alternating the settings so that load on the shared
machine hits all alike, and records the rows' wall time (the map file's map/sweep_time_s; the
scene's equilibrium and the spine, which are serial, are in map/time_s). The maps must be
bitwise identical between settings (each row starts from its spine point alone): checked.
Optionally coarsens the target's grid (--angle-step, --hoist-step) for a quicker study.

Writes a CSV (default benchmarks/results/map_parallel.csv): one row per run, then the medians.

    python3 benchmarks/map_parallel.py --workers 1,2,mpi2                          # thesis grid, ≈ 1 min
    python3 benchmarks/map_parallel.py --angle-step 5 --hoist-step 4 --reps 3      # 9 × 7 points
"""

import argparse
import csv
import os
import re
import statistics
import subprocess
import tempfile
from pathlib import Path

import h5py

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


def run_map(binary: str, target: Path, workers: str, out: Path) -> dict:
    """One map with `workers`: "N" threads, or "mpiN" MPI ranks."""
    command = [binary, "map", str(target), "-o", str(out), "--quiet"]
    if workers.startswith("mpi"):
        launcher = ["mpirun", "-n", workers[3:]] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
        command = launcher + command
    else:
        command += ["--threads", workers]
    subprocess.run(command, check=True, capture_output=True, text=True)
    with h5py.File(out, "r") as f:
        m = f["map"]
        return {"workers": workers, "points": m["luffing_length"].size, "sweep_s": m.attrs["sweep_time_s"],
                "map_s": m.attrs["time_s"], "jacobians": int(m.attrs["jacobians"]),
                "bytes": b"".join(m[name][...].tobytes() for name in sorted(m))}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "crane-opt"), help="crane-opt binary")
    parser.add_argument("--target", default=str(ROOT / "configs" / "target.yaml"))
    parser.add_argument("--workers", default="1,2", help="comma-separated: N threads or mpiN ranks, e.g. 1,2,mpi2")
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--angle-step", type=float)
    parser.add_argument("--hoist-step", type=float)
    parser.add_argument("-o", "--output", default=str(ROOT / "benchmarks" / "results" / "map_parallel.csv"))
    args = parser.parse_args(argv)
    settings = args.workers.split(",")

    with tempfile.TemporaryDirectory() as tmp:
        directory = Path(tmp)
        target = coarsened_target(Path(args.target), args.angle_step, args.hoist_step, directory)
        runs = []
        for rep in range(args.reps):
            for workers in settings:
                run = run_map(args.bin, target, workers, directory / f"map_{workers}.h5")
                runs.append(run)
                print(f"rep {rep + 1}: {workers}, {run['points']} points: rows {run['sweep_s']:.2f} s, "
                      f"map {run['map_s']:.2f} s, {run['jacobians']} Jacobians", flush=True)
    identical = all(r["bytes"] == runs[0]["bytes"] for r in runs)
    medians = {w: statistics.median(r["sweep_s"] for r in runs if r["workers"] == w) for w in settings}
    map_medians = {w: statistics.median(r["map_s"] for r in runs if r["workers"] == w) for w in settings}
    with open(args.output, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["workers", "points", "rows_s", "map_s", "jacobians"])
        for r in runs:
            writer.writerow([r["workers"], r["points"], f"{r['sweep_s']:.3f}", f"{r['map_s']:.3f}", r["jacobians"]])
        for w in settings:
            writer.writerow([w, runs[0]["points"], f"median {medians[w]:.3f}", f"median {map_medians[w]:.3f}",
                             f"speed-up {medians[settings[0]] / medians[w]:.3f}"])
    for w in settings:
        print(f"{w}: median rows {medians[w]:.2f} s (map {map_medians[w]:.2f} s), "
              f"speed-up of the rows {medians[settings[0]] / medians[w]:.2f}×")
    print("maps bitwise identical across runs and workers:", identical)
    return 0 if identical else 1


if __name__ == "__main__":
    raise SystemExit(main())
