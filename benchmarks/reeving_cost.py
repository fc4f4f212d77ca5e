"""What a massive reeved rope costs against a massless one, and how it scales with its cables.

Runs `crane-sim run` (median of --reps runs; CPU time of the process from getrusage) on
- configs/hook_block.yaml (massless) and hook_block_massive.yaml at elements_per_part 4, 8 (the
  file's), 16 and 32;
- configs/crane_reeved_luffing.yaml and crane_reeved_luffing_massive.yaml (the luffing rope
  massless and massive);
- configs/crane_reeved_combined.yaml and crane_reeved_combined_hoist_massive.yaml (the hoist
  rope massless and massive on the combined motion): the load's largest distance between the two
  runs over the motion.
With --before-bin a second crane-sim (an older build) runs the same scenes in the same session,
alternating with --bin run by run, so that both see the same machine load.

Writes benchmarks/results/reeving_cost.csv, a row per scene and binary.

    python3 benchmarks/reeving_cost.py                                   # ≈ 1 min on 2 cores
    python3 benchmarks/reeving_cost.py --before-bin /tmp/old/crane-sim --reps 3
"""

import argparse
import csv
import os
import resource
import statistics
import subprocess
import tempfile
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"
HOOK_ELEMENTS = [4, 8, 16, 32]
COLUMNS = ["case", "binary", "elements_per_part", "coordinates", "simulated_s", "steps", "residual_evaluations",
           "jacobians", "wall_median_s", "cpu_median_s", "reps", "load_distance_max_m", "load_average"]


def parse_arguments() -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bin", default=str(ROOT / "build" / "crane-sim"), help="crane-sim to measure")
    p.add_argument("--before-bin", help="an older crane-sim run beside it (label 'before')")
    p.add_argument("--reps", type=int, default=3, help="runs per scene and binary; medians are reported")
    p.add_argument("--skip-crane", action="store_true", help="the hook block only")
    p.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "reeving_cost.csv"))
    return p.parse_args()


def run(binary: str, scene: Path, out: Path) -> dict:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([binary, "run", str(scene), "-o", str(out), "--quiet"], check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    with h5py.File(out, "r") as f:
        stats = {k: f["solver"].attrs[k] for k in f["solver"].attrs}
        t = f["time"][()]
        row = {"coordinates": int(f["q"].shape[1]), "simulated_s": float(t[-1] - t[0]), "steps": int(stats["steps"]),
               "residual_evaluations": int(stats["residual_evaluations"]), "jacobians": int(stats["jacobian_evaluations"]),
               "wall_s": float(stats["wall_time_s"]),
               "cpu_s": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)}
        load = "load" if "load" in f["bodies"] else "hook_block"
        row["load_path"] = f[f"bodies/{load}/position"][()]
    return row


def measure(binaries: dict, case: str, scene: Path, elements: int, reps: int, workdir: Path) -> dict:
    """Rows per binary label; the runs alternate between the binaries."""
    runs = {label: [] for label in binaries}
    for _ in range(reps):
        for label, binary in binaries.items():
            runs[label].append(run(binary, scene, workdir / f"{label}.h5"))
    rows = {}
    for label, rs in runs.items():
        first = rs[0]
        rows[label] = {"case": case, "binary": label, "elements_per_part": elements,
                       **{k: first[k] for k in ("coordinates", "simulated_s", "steps", "residual_evaluations", "jacobians")},
                       "wall_median_s": statistics.median(r["wall_s"] for r in rs),
                       "cpu_median_s": statistics.median(r["cpu_s"] for r in rs), "reps": reps,
                       "load_distance_max_m": "", "load_average": f"{os.getloadavg()[0]:.2f}", "load_path": first["load_path"]}
        print(f"{case:40s} {label:6s} steps {first['steps']:6d} residuals {first['residual_evaluations']:6d} "
              f"wall {rows[label]['wall_median_s']:8.3f} s cpu {rows[label]['cpu_median_s']:8.3f} s", flush=True)
    return rows


def main() -> None:
    args = parse_arguments()
    binaries = {"after": args.bin}
    if args.before_bin:
        binaries = {"before": args.before_bin, "after": args.bin}
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(tmp)
        rows += measure({"after": args.bin}, "hook_block.yaml", CONFIGS / "hook_block.yaml", 0, args.reps, workdir).values()
        for n in HOOK_ELEMENTS:
            scene = workdir / f"hook_block_{n}.yaml"
            scene.write_text(f"base: {CONFIGS / 'hook_block_massive.yaml'}\n"
                             f"modify: {{members.hoist.elements_per_part: {n}}}\n")
            rows += measure(binaries, f"hook_block_massive.yaml, {n} per part", scene, n, args.reps, workdir).values()
        if not args.skip_crane:
            rows += measure({"after": args.bin}, "crane_reeved_luffing.yaml", CONFIGS / "crane_reeved_luffing.yaml", 0,
                            args.reps, workdir).values()
            rows += measure(binaries, "crane_reeved_luffing_massive.yaml", CONFIGS / "crane_reeved_luffing_massive.yaml", 4,
                            args.reps, workdir).values()
            massless = measure({"after": args.bin}, "crane_reeved_combined.yaml", CONFIGS / "crane_reeved_combined.yaml", 0,
                               args.reps, workdir)["after"]
            massive = measure({"after": args.bin}, "crane_reeved_combined_hoist_massive.yaml",
                              CONFIGS / "crane_reeved_combined_hoist_massive.yaml", 4, args.reps, workdir)["after"]
            a, b = massless["load_path"], massive["load_path"]
            samples = min(len(a), len(b))
            massive["load_distance_max_m"] = f"{float(np.max(np.linalg.norm(a[:samples] - b[:samples], axis=1))):.6g}"
            rows += [massless, massive]
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
