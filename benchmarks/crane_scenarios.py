"""Wall time, real-time factor and accuracy of the thesis crane's motions (8.3).

For every scenario scene (configs/crane_*.yaml) and every tolerance, runs crane-sim on a scene
derived with `base:` (solver.rtol, solver.atol changed), `--reps` times, and records the median
wall time of the integration (the results' solver/wall_time_s: equilibrium excluded, reported
apart) and the load's position error against a reference run at --ref-rtol (max over the output
samples of the distance between the two hook positions). Also measures the sway period after
the last drive stops and, for lifting, the load's motion across the crane's plane.

Writes a CSV (default benchmarks/results/crane_scenarios.csv), one row per scenario and
tolerance, flushed after every row.

    python3 benchmarks/crane_scenarios.py --bin build/crane-sim            # all, ≈ 1 h on 2 cores
    python3 benchmarks/crane_scenarios.py --scenarios lifting --rtols 1e-4 --reps 1
"""

import argparse
import csv
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
from cranesim.results import ResultsError  # noqa: E402
from plot_load import sway_period  # noqa: E402

# scenario → time after which every drive has stopped (the scene files' profiles)
SCENARIOS = {"lifting": 40.0, "luffing": 40.0, "slewing": 40.0, "combined": 40.0}


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "crane-sim"), help="crane-sim binary")
    parser.add_argument("--scenarios", default=",".join(SCENARIOS), help="comma-separated subset of " + ",".join(SCENARIOS))
    parser.add_argument("--rtols", default="1e-4,1e-5", help="tolerances to time (atol = rtol/10)")
    parser.add_argument("--ref-rtol", type=float, default=1e-7, help="tolerance of the reference run")
    parser.add_argument("--reps", type=int, default=3, help="runs per case; the median wall time is reported")
    parser.add_argument("--t-end", type=float, help="end time of every run (default: the scene's)")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "crane_scenarios.csv"))
    return parser.parse_args()


def run(binary: str, scenario: str, rtol: float, t_end: float | None, workdir: Path) -> tuple[Path, float]:
    """Runs the scenario at rtol; returns the results path and the process wall time."""
    scene = workdir / f"{scenario}_{rtol:g}.yaml"
    base = ROOT / "configs" / f"crane_{scenario}.yaml"
    end = f"  solver.t_end: {t_end}\n" if t_end is not None else ""
    scene.write_text(f"base: {base}\nmodify:\n  solver.rtol: {rtol}\n  solver.atol: {rtol / 10}\n{end}", encoding="utf-8")
    out = workdir / f"{scenario}_{rtol:g}.h5"
    start = time.perf_counter()
    done = subprocess.run([binary, "run", str(scene), "-o", str(out), "--quiet"], capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f"{scene.name}: crane-sim exited with {done.returncode}: {done.stderr.strip()}")
    return out, wall


def load_track(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict]:
    with h5py.File(path, "r") as f:
        stats = {k: f["solver"].attrs[k] for k in f["solver"].attrs}
        return f["time"][()], f["bodies/load/position"][()], f["bodies/load/velocity"][()], stats


def main() -> None:
    args = parse_arguments()
    scenarios = [s for s in args.scenarios.split(",") if s]
    for s in scenarios:
        if s not in SCENARIOS:
            sys.exit(f"unknown scenario '{s}' (known: {', '.join(SCENARIOS)})")
    rtols = [float(r) for r in args.rtols.split(",")]
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("w", newline="", encoding="utf-8") as handle, tempfile.TemporaryDirectory() as tmp:
        writer = csv.writer(handle)
        writer.writerow(["scenario", "rtol", "t_end_s", "wall_median_s", "process_median_s", "realtime_factor",
                         "steps", "jacobians", "load_error_max_m", "sway_period_s", "max_abs_y_m", "reps"])
        for scenario in scenarios:
            reference, _ = run(args.bin, scenario, args.ref_rtol, args.t_end, Path(tmp))
            t_ref, p_ref, _, _ = load_track(reference)
            for rtol in rtols:
                walls, processes = [], []
                for _ in range(args.reps):
                    path, process = run(args.bin, scenario, rtol, args.t_end, Path(tmp))
                    t, p, v, stats = load_track(path)
                    walls.append(float(stats["wall_time_s"]))
                    processes.append(process)
                if t.shape != t_ref.shape or np.max(np.abs(t - t_ref)) > 1e-9:
                    raise RuntimeError(f"{scenario}: output times differ from the reference's")
                error = float(np.max(np.linalg.norm(p - p_ref, axis=1)))
                after = t >= SCENARIOS[scenario] + 5.0
                period = float("nan")
                if np.count_nonzero(after) > 10:
                    try:
                        period = sway_period(t[after], v[after, :2])[0]
                    except ResultsError:  # no sway to measure (lifting)
                        pass
                wall = statistics.median(walls)
                writer.writerow([scenario, f"{rtol:g}", f"{t[-1]:g}", f"{wall:.3f}", f"{statistics.median(processes):.3f}",
                                 f"{t[-1] / wall:.3f}", int(stats["steps"]), int(stats["jacobian_evaluations"]),
                                 f"{error:.3e}", f"{period:.4f}", f"{np.max(np.abs(p[:, 1] - p[0, 1])):.3e}", args.reps])
                handle.flush()
                print(f"{scenario} rtol {rtol:g}: wall {wall:.1f} s, error {error:.2e} m, sway period {period:.3f} s",
                      file=sys.stderr)


if __name__ == "__main__":
    main()
