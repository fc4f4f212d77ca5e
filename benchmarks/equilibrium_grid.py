"""Statics over the thesis crane's working range: success, Newton iterations and time per point.

For each lattice fidelity (configs/crane_condensed.yaml, configs/crane.yaml) runs
`crane-sim static` on a grid of control pairs (unstretched luffing rope × hoist rope, slewing 0,
the thesis' 390 t load), on a row of loads at the thesis' controls (luffing 7.0608 m, hoist
53.9937 m) and on a random sample of all four together (luffing and hoist rope uniform over the
grid's ranges, the load log-uniform over the loads' range, the slewing angle uniform in ±180°;
fixed seed), every point from the drawn geometry with the same solver settings. Records whether
the equilibrium was found, its Newton iterations and path steps, the statics' own wall time
(printed by crane-sim: model compilation and file output excluded) and the process's.

Writes benchmarks/results/equilibrium_grid.csv (one row per point, flushed as it goes) and
equilibrium_grid.png (iterations over the control plane and against the load, the mixed cases
beside the load row, failures as ×).

    python3 benchmarks/equilibrium_grid.py                                  # both fidelities, 210 pairs + 12 loads + 60 mixed each
    python3 benchmarks/equilibrium_grid.py --fidelities condensed --luffing 6,21.5,4 --hoist 30,56,3
"""

import argparse
import csv
import math
import random
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCENES = {"condensed": "crane_condensed.yaml", "super_truss": "crane.yaml"}
THESIS_LUFFING, THESIS_HOIST, THESIS_LOAD = 7.0608, 53.9937, 390000.6
SUMMARY = re.compile(r"static equilibrium: (\d+) Newton iterations in (\d+) load steps and (\d+) path steps.* in ([\d.]+) s")


def grid(spec: str) -> np.ndarray:
    start, stop, count = spec.split(",")
    return np.linspace(float(start), float(stop), int(count))


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "crane-sim"), help="crane-sim binary")
    parser.add_argument("--fidelities", default="condensed,super_truss", help="comma-separated: " + ",".join(SCENES))
    parser.add_argument("--luffing", default="6.0,21.5,15", help="unstretched luffing rope: from,to,count (m)")
    parser.add_argument("--hoist", default="30,56,14", help="unstretched hoist rope: from,to,count (m)")
    parser.add_argument("--loads", default="1,2,5,10,20,50,100,200,390.0006,500,700,1000", help="load masses (t)")
    parser.add_argument("--mixed", type=int, default=60, help="random cases of controls, load and slewing angle")
    parser.add_argument("--seed", type=int, default=25, help="seed of the mixed cases")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "equilibrium_grid.csv"))
    return parser.parse_args()


def solve(binary: str, fidelity: str, luffing: float, hoist: float, load_kg: float, slewing_deg: float,
          workdir: Path) -> dict:
    scene = workdir / "point.yaml"
    scene.write_text(f"base: {ROOT / 'configs' / SCENES[fidelity]}\nmodify:\n"
                     f"  members.luffing_rope.length: {luffing!r}\n  members.hoist_rope.length: {hoist!r}\n"
                     f"  bodies.load.mass: {load_kg!r}\n"
                     f"  constraints.slewing.drive: {math.radians(slewing_deg)!r}\n", encoding="utf-8")
    start = time.perf_counter()
    done = subprocess.run([binary, "static", str(scene), "-o", str(workdir / "point.h5")], capture_output=True, text=True)
    process = time.perf_counter() - start
    found = SUMMARY.search(done.stderr)
    row = {"fidelity": fidelity, "luffing_m": luffing, "hoist_m": hoist, "load_kg": load_kg, "slewing_deg": slewing_deg,
           "converged": int(done.returncode == 0 and found is not None), "newton_iterations": "", "load_steps": "",
           "path_steps": "", "statics_s": "", "process_s": f"{process:.3f}", "message": ""}
    if found:
        row.update(newton_iterations=int(found[1]), load_steps=int(found[2]), path_steps=int(found[3]),
                   statics_s=float(found[4]))
    if done.returncode != 0:
        row["message"] = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"exit {done.returncode}"
    return row


def plot(rows: list[dict], fidelities: list[str], path: Path) -> None:
    fig, axes = plt.subplots(2, len(fidelities), figsize=(6 * len(fidelities), 9), squeeze=False)
    for column, fidelity in enumerate(fidelities):
        controls = [r for r in rows if r["fidelity"] == fidelity and r["kind"] == "controls"]
        ax = axes[0][column]
        ok = [r for r in controls if r["converged"]]
        failed = [r for r in controls if not r["converged"]]
        points = ax.scatter([r["luffing_m"] for r in ok], [r["hoist_m"] for r in ok],
                            c=[r["newton_iterations"] for r in ok], cmap="viridis", s=60)
        ax.scatter([r["luffing_m"] for r in failed], [r["hoist_m"] for r in failed], marker="x", c="red", s=60,
                   label=f"failed ({len(failed)})")
        fig.colorbar(points, ax=ax, label="Newton iterations")
        ax.set_xlabel("luffing rope (unstretched) [m]")
        ax.set_ylabel("hoist rope (unstretched) [m]")
        ax.set_title(f"{fidelity}: {len(ok)}/{len(controls)} equilibria")
        if failed:
            ax.legend()
        loads = [r for r in rows if r["fidelity"] == fidelity and r["kind"] == "load"]
        mixed = [r for r in rows if r["fidelity"] == fidelity and r["kind"] == "mixed"]
        ax = axes[1][column]
        ax.semilogx([r["load_kg"] / 1e3 for r in loads if r["converged"]],
                    [r["newton_iterations"] for r in loads if r["converged"]], "o-", label="thesis controls")
        failed_loads = [r for r in loads + mixed if not r["converged"]]
        if failed_loads:
            ax.semilogx([r["load_kg"] / 1e3 for r in failed_loads], [0] * len(failed_loads), "rx", label="failed")
        ax.semilogx([r["load_kg"] / 1e3 for r in mixed if r["converged"]],
                    [r["newton_iterations"] for r in mixed if r["converged"]], ".", color="gray",
                    label="mixed: random controls and slewing")
        ax.legend()
        ax.set_xlabel("load [t] (line: luffing 7.0608 m, hoist 53.9937 m)")
        ax.set_ylabel("Newton iterations")
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main() -> None:
    args = parse_arguments()
    fidelities = [f for f in args.fidelities.split(",") if f]
    for f in fidelities:
        if f not in SCENES:
            sys.exit(f"unknown fidelity '{f}' (known: {', '.join(SCENES)})")
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fields = ["fidelity", "kind", "luffing_m", "hoist_m", "load_kg", "slewing_deg", "converged", "newton_iterations", "load_steps",
              "path_steps", "statics_s", "process_s", "message"]
    rows = []
    with out.open("w", newline="", encoding="utf-8") as handle, tempfile.TemporaryDirectory() as tmp:
        writer = csv.DictWriter(handle, fieldnames=fields)
        writer.writeheader()
        for fidelity in fidelities:
            luffing_range, hoist_range = grid(args.luffing), grid(args.hoist)
            loads = [1e3 * float(m) for m in args.loads.split(",")]
            cases = [("controls", float(l), float(h), THESIS_LOAD, 0.0) for l in luffing_range for h in hoist_range]
            cases += [("load", THESIS_LUFFING, THESIS_HOIST, round(m, 3), 0.0) for m in loads]
            draw = random.Random(args.seed)  # the same cases for every fidelity
            cases += [("mixed", draw.uniform(luffing_range[0], luffing_range[-1]), draw.uniform(hoist_range[0], hoist_range[-1]),
                       round(math.exp(draw.uniform(math.log(min(loads)), math.log(max(loads)))), 3),
                       round(draw.uniform(-180.0, 180.0), 3)) for _ in range(args.mixed)]
            for kind, luffing, hoist, load, slewing in cases:
                row = {"kind": kind, **solve(args.bin, fidelity, round(luffing, 6), round(hoist, 6), load, slewing, Path(tmp))}
                writer.writerow(row)
                handle.flush()
                rows.append(row)
            for kind in ("controls", "load", "mixed"):
                mine = [r for r in rows if r["fidelity"] == fidelity and r["kind"] == kind]
                ok = [r for r in mine if r["converged"]]
                if ok:
                    print(f"{fidelity} {kind}: {len(ok)}/{len(mine)} converged; Newton iterations median "
                          f"{statistics.median(r['newton_iterations'] for r in ok):g}, max "
                          f"{max(r['newton_iterations'] for r in ok)}; statics time median "
                          f"{statistics.median(r['statics_s'] for r in ok):.3f} s, max {max(r['statics_s'] for r in ok):.3f} s",
                          file=sys.stderr)
                else:
                    print(f"{fidelity} {kind}: none of {len(mine)} converged", file=sys.stderr)
    plot(rows, fidelities, out.with_suffix(".png"))


if __name__ == "__main__":
    main()
