"""What the sheaves' grip costs on the reeved thesis crane against a friction band.

Runs `crane-sim run` on configs/crane_reeved_combined.yaml (60 s combined motion) with condensed
sections and with super truss sections (every boom and derrick section `fidelity: super_truss`),
with --bin (the grip) and --before-bin (a build with the friction band, whose own configs/ are
given by --before-configs), alternating run by run so that both see the same machine load:
steps, nonlinear failures, wall (the integration's) and CPU (the process's) medians of --reps
runs; the load's largest distance from an rtol 1e-7 run of the same build and scene, and between
the two builds' rtol 1e-7 runs (the hook's displacement by the law).

Writes benchmarks/results/sheave_grip.csv, a row per section fidelity and binary.

    python3 benchmarks/sheave_grip.py --before-bin /tmp/main/crane-sim --before-configs /tmp/main/configs
"""

import argparse
import os
import resource
import statistics
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np

from benchmark_csv import write_rows

ROOT = Path(__file__).resolve().parents[1]
SECTIONS = ["boom1", "boom2", "boom3", "boom4", "boom5", "derrick1", "derrick2", "derrick3"]
COLUMNS = ["sections", "binary", "steps", "nonlinear_failures", "wall_median_s", "cpu_median_s", "reps",
           "load_error_m", "load_apart_m", "load_average"]


def parse_arguments() -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bin", default=str(ROOT / "build" / "crane-sim"), help="crane-sim with the grip")
    p.add_argument("--before-bin", required=True, help="crane-sim with the friction band (label 'band')")
    p.add_argument("--before-configs", required=True, type=Path, help="that build's configs/ directory")
    p.add_argument("--reps", type=int, default=3, help="runs per scene and binary; medians are reported")
    p.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "sheave_grip.csv"))
    return p.parse_args()


def scene(workdir: Path, configs: Path, label: str, sections: str, rtol: float | None) -> Path:
    lines = [f"base: {configs / 'crane_reeved_combined.yaml'}", "modify:"]
    if sections == "super truss":
        lines += [f"  members.{m}.fidelity: super_truss" for m in SECTIONS]
    if rtol:
        lines += [f"  solver.rtol: {rtol}", f"  solver.atol: {rtol / 10}"]
    if len(lines) == 2:
        lines[1] = "modify: {}"
    path = workdir / f"{label}_{sections.replace(' ', '_')}_{rtol or 'shipped'}.yaml"
    path.write_text("\n".join(lines) + "\n")
    return path


def run(binary: str, path: Path, out: Path) -> dict:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([binary, "run", str(path), "-o", str(out), "--quiet"], check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    with h5py.File(out, "r") as f:
        stats = f["solver"].attrs
        return {"steps": int(stats["steps"]), "nonlinear_failures": int(stats["nonlinear_failures"]),
                "wall_s": float(stats["wall_time_s"]),
                "cpu_s": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
                "load_path": f["bodies/load/position"][()]}


def apart(a: np.ndarray, b: np.ndarray) -> float:
    n = min(len(a), len(b))
    return float(np.max(np.linalg.norm(a[:n] - b[:n], axis=1)))


def main() -> None:
    args = parse_arguments()
    builds = {"band": (args.before_bin, args.before_configs), "grip": (args.bin, ROOT / "configs")}
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(tmp)
        for sections in ("condensed", "super truss"):
            runs = {label: [] for label in builds}
            for _ in range(args.reps):
                for label, (binary, configs) in builds.items():
                    runs[label].append(run(binary, scene(workdir, configs, label, sections, None), workdir / "run.h5"))
            references = {label: run(binary, scene(workdir, configs, label, sections, 1e-7), workdir / "ref.h5")["load_path"]
                          for label, (binary, configs) in builds.items()}
            for label, rs in runs.items():
                row = {"sections": sections, "binary": label, "steps": rs[0]["steps"],
                       "nonlinear_failures": rs[0]["nonlinear_failures"],
                       "wall_median_s": statistics.median(r["wall_s"] for r in rs),
                       "cpu_median_s": statistics.median(r["cpu_s"] for r in rs), "reps": args.reps,
                       "load_error_m": f"{apart(rs[0]['load_path'], references[label]):.6g}",
                       "load_apart_m": f"{apart(references['band'], references['grip']):.6g}",
                       "load_average": f"{os.getloadavg()[0]:.2f}"}
                print({k: row[k] for k in COLUMNS}, flush=True)
                rows.append(row)
    write_rows(args.out, rows)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
