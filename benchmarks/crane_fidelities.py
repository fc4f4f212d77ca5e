"""The lattice fidelities on the whole thesis crane, against the full-member crane.

For each fidelity of the eight lattice sections (members — every tube a beam, the reference —,
condensed, equivalent beam, super truss, and a mixed crane: the middle main-boom section boom3
tube by tube, the rest condensed) at the thesis' initial controls (configs/crane_combined.yaml
at t = 0):
- the equilibrium (`crane-sim static`): boom-head and hook positions, Newton iterations, time;
- the lowest modes about it (`crane-sim modes`): the load's two sway periods and the first
  elastic frequencies of the crane;
- the 60 s combined motion (8.3.2) at the main scene's integrator setting (BDF order ≤ 2,
  rtol 1e-4, atol 1e-5): the hook's largest distance from the full-member crane's path over the
  whole motion, steps, Jacobians, coordinates, integration wall time (median of --reps runs) and
  the real-time factor; where boom3 is modelled tube by tube (members, mixed), the largest axial
  tension and compression of its tubes over the motion (output.section_forces).
The full-member crane also runs at rtol 1e-5 (the reference path), so that its own rtol 1e-4
run shows the integrator's share of every distance.

Writes benchmarks/results/crane_fidelities.csv (a row per fidelity) and .png (the hook's
distance from the reference along the motion, and wall time against that distance).

    python3 benchmarks/crane_fidelities.py              # ≈ 6 min on 2 cores
    python3 benchmarks/crane_fidelities.py --reps 1 --t-end 10
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
SECTIONS = ["boom1", "boom2", "boom3", "boom4", "boom5", "derrick1", "derrick2", "derrick3"]
FIDELITIES = {
    "members": {s: "members" for s in SECTIONS},
    "condensed": {s: "condensed" for s in SECTIONS},
    "beam": {s: "beam" for s in SECTIONS},
    "super_truss": {s: "super_truss" for s in SECTIONS},
    "mixed": {s: "members" if s == "boom3" else "condensed" for s in SECTIONS},
}
REFERENCE_RTOL = 1e-5
ELASTIC_MODES = 6
FORCES_OF = "boom3"  # the section whose tube forces are compared where it is modelled tube by tube


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "crane-sim"), help="crane-sim binary")
    parser.add_argument("--fidelities", default=",".join(FIDELITIES), help="comma-separated subset of " + ",".join(FIDELITIES))
    parser.add_argument("--reps", type=int, default=3, help="runs of the motion per fidelity; the median wall time is reported")
    parser.add_argument("--t-end", type=float, default=60.0, help="end of the motion, s")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "crane_fidelities.csv"))
    return parser.parse_args()


def scene_text(fidelity: str, t_end: float, rtol: float = 1e-4) -> str:
    tube_forces = [f"  output.section_forces: [{FORCES_OF}]"] if FIDELITIES[fidelity][FORCES_OF] == "members" else []
    lines = [f"base: {ROOT / 'configs' / 'crane_combined.yaml'}", "modify:",
             *(f"  members.{s}.fidelity: {f}" for s, f in FIDELITIES[fidelity].items()), *tube_forces,
             f"  solver.t_end: {t_end:g}", f"  solver.rtol: {rtol:g}", f"  solver.atol: {rtol / 10:g}"]
    return "\n".join(lines) + "\n"


def crane_sim(binary: str, verb: str, scene: Path, out: Path, *extra: str) -> str:
    done = subprocess.run([binary, verb, str(scene), "-o", str(out), *extra], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{scene.name}: crane-sim {verb} exited with {done.returncode}: {done.stderr.strip()}")
    return done.stderr


def statics(binary: str, scene: Path, workdir: Path) -> dict:
    out = workdir / "static.h5"
    log = crane_sim(binary, "static", scene, out)
    found = re.search(r"static equilibrium: (\d+) Newton iterations.* in ([0-9.e+-]+) s", log)
    with h5py.File(out, "r") as f:
        head, hook = f["bodies/head/position"][0], f["bodies/load/position"][0]
    return {"newton_iterations": int(found[1]), "statics_s": float(found[2]),
            **{f"head_{a}_m": head[k] for k, a in enumerate("xyz")}, **{f"hook_{a}_m": hook[k] for k, a in enumerate("xyz")}}


def modes(binary: str, scene: Path, workdir: Path) -> dict:
    out = workdir / "modes.h5"
    crane_sim(binary, "modes", scene, out, "--count", str(ELASTIC_MODES + 6))
    with h5py.File(out, "r") as f:
        frequency = f["modes/frequency"][()]
    elastic = frequency[frequency > 1e-6]
    row = {"sway_period_1_s": 1.0 / elastic[0], "sway_period_2_s": 1.0 / elastic[1]}
    row.update({f"mode_{k + 3}_hz": elastic[k + 2] for k in range(ELASTIC_MODES - 2)})
    return row


def motion(binary: str, scene: Path, workdir: Path) -> tuple[np.ndarray, np.ndarray, dict]:
    out = workdir / "run.h5"
    crane_sim(binary, "run", scene, out, "--quiet")
    with h5py.File(out, "r") as f:
        stats = {k: f["solver"].attrs[k] for k in f["solver"].attrs}
        t, hook = f["time"][()], f["bodies/load/position"][()]
        coordinates = f["q"].shape[1]
        forces = f[f"section_forces/{FORCES_OF}/forces"][()] if "section_forces" in f else None
    out.unlink()
    row = {"steps": int(stats["steps"]), "jacobians": int(stats["jacobian_evaluations"]), "wall_s": float(stats["wall_time_s"]),
           "coordinates": int(coordinates)}
    if forces is not None:  # axial forces at both ends of every tube: the largest pull and push over the motion
        axial = forces[:, :, [0, 6]]
        row.update({f"{FORCES_OF}_max_tension_N": float(axial.max()), f"{FORCES_OF}_max_compression_N": float(-axial.min())})
    return t, hook, row


def plot(rows: list[dict], paths: dict, reference: tuple[np.ndarray, np.ndarray], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.5))
    t_ref, p_ref = reference
    for name, (t, p) in paths.items():
        label = "members (the integrator's own share)" if name == "members" else name.replace("_", " ")
        left.semilogy(t, np.maximum(np.linalg.norm(p - p_ref, axis=1), 1e-7), label=label)
    left.set_xlabel("time [s]")
    left.set_ylabel("hook distance from the full-member crane [m]")
    left.set_title(f"combined motion (8.3.2), BDF ≤ 2, rtol 1e-4; reference: members at rtol {REFERENCE_RTOL:g}")
    left.grid(True, which="both", alpha=0.3)
    left.legend()
    for r in rows:
        right.loglog(r["wall_median_s"], max(r["hook_distance_max_m"], 1e-7), "o")
        right.annotate(r["fidelity"].replace("_", " "), (r["wall_median_s"], max(r["hook_distance_max_m"], 1e-7)),
                       textcoords="offset points", xytext=(5, 5))
    right.set_xlabel("integration wall time, 60 s motion [s]")
    right.set_ylabel("max hook distance from the full-member crane [m]")
    right.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main() -> None:
    args = parse_arguments()
    fidelities = args.fidelities.split(",")
    for f in fidelities:
        if f not in FIDELITIES:
            raise SystemExit(f"unknown fidelity '{f}' (known: {', '.join(FIDELITIES)})")
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    rows, paths = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(tmp)
        reference_scene = workdir / "reference.yaml"
        reference_scene.write_text(scene_text("members", args.t_end, REFERENCE_RTOL), encoding="utf-8")
        t_ref, p_ref, _ = motion(args.bin, reference_scene, workdir)
        print(f"reference: full-member crane at rtol {REFERENCE_RTOL:g}", flush=True)
        for fidelity in fidelities:
            scene = workdir / f"{fidelity}.yaml"
            scene.write_text(scene_text(fidelity, args.t_end), encoding="utf-8")
            row = {"fidelity": fidelity, **statics(args.bin, scene, workdir), **modes(args.bin, scene, workdir)}
            walls = []
            for _ in range(args.reps):
                t, p, stats = motion(args.bin, scene, workdir)
                walls.append(stats["wall_s"])
            if t.shape != t_ref.shape or not np.allclose(t, t_ref):
                raise RuntimeError(f"{fidelity}: output times differ from the reference's")
            paths[fidelity] = (t, p)
            wall = statistics.median(walls)
            row.update({"coordinates": stats["coordinates"], "steps": stats["steps"], "jacobians": stats["jacobians"],
                        "wall_median_s": wall, "realtime_factor": float(t[-1] - t[0]) / wall, "reps": len(walls),
                        "hook_distance_max_m": float(np.max(np.linalg.norm(p - p_ref, axis=1))),
                        f"{FORCES_OF}_max_tension_N": stats.get(f"{FORCES_OF}_max_tension_N", float("nan")),
                        f"{FORCES_OF}_max_compression_N": stats.get(f"{FORCES_OF}_max_compression_N", float("nan"))})
            rows.append(row)
            print(", ".join(f"{k} {v:.6g}" if isinstance(v, float) else f"{k} {v}" for k, v in row.items()), flush=True)
    with out.open("w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        for r in rows:
            writer.writerow({k: f"{v:.7g}" if isinstance(v, float) else v for k, v in r.items()})
    plot(rows, paths, (t_ref, p_ref), out.with_suffix(".png"))
    print(f"written: {out}, {out.with_suffix('.png')}")


if __name__ == "__main__":
    main()
