"""Statics of slender beams bent far: Newton iterations of `crane-sim static` from the straight beam.

Two families, each for Timoshenko and spline beams and several segment counts:
  end moment  configs/end_moment_<type>.yaml (thesis 8.1.1) with M = K·2πEI/L, K = 0.25 … 1
              (K = 1 rolls the beam into a full circle);
  tip force   a 10 m cantilever (solid round r = 0.05 m, steel) with a tip force across it,
              PL²/EI = 2, 5, 10 (at 10 the tip turns by ~80°).
Records whether the equilibrium was found and is stable, its Newton iterations and path steps, the statics' own
wall time and the tip's error against the exact solution (end moment: the circular arc of
curvature 2πK/L; tip force: the inextensible elastica, by shooting).

Writes benchmarks/results/slender_statics.csv (one row per case, flushed as it goes).

    python3 benchmarks/slender_statics.py
    python3 benchmarks/slender_statics.py --bin build/crane-sim --out /tmp/slender.csv
"""

import argparse
import csv
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SUMMARY = re.compile(r"static equilibrium: (\d+) Newton iterations in (\d+) load steps and (\d+) path steps.* in ([\d.]+) s")
TYPES = ("timoshenko", "spline_beam")
E, RADIUS, LENGTH = 2.1e11, 0.05, 10.0
EI = E * math.pi * RADIUS**4 / 4.0

TIP_FORCE_SCENE = """name: slender cantilever with a tip force
gravity: [0, 0, 0]
ground:
  joints: [{{name: wall}}]
members:
  - {{name: beam, type: {type}, start: [0, 0, 0], end: [{length}, 0, 0], segments: {segments},
     section: {{radius: {radius}}}, material: {{density: 7850, youngs_modulus: {E}, poisson_ratio: 0.3}}}}
constraints:
  - {{name: clamp, type: fixed, joints: [ground.wall, beam.start]}}
loads:
  - {{name: tip, joint: beam.end, force: [0, 0, {force!r}]}}
solver: {{t_end: 1}}
"""


def elastica_tip(ratio: float) -> tuple[float, float]:
    """Tip (x, z)/L of the inextensible cantilever under a tip force P across it, PL²/EI = ratio:
    θ'' = −ratio·cos θ on s ∈ [0, 1], θ(0) = 0, θ'(1) = 0, by shooting on θ'(0) (RK4)."""
    def shoot(kappa0: float) -> tuple[float, float, float]:
        n = 4000
        h = 1.0 / n
        y = np.array([0.0, kappa0, 0.0, 0.0])  # θ, θ', x, z

        def f(v):
            return np.array([v[1], -ratio * math.cos(v[0]), math.cos(v[0]), -math.sin(v[0])])

        for _ in range(n):
            k1 = f(y)
            k2 = f(y + 0.5 * h * k1)
            k3 = f(y + 0.5 * h * k2)
            k4 = f(y + h * k3)
            y = y + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        return y[1], y[2], y[3]

    low, high = 0.0, ratio  # θ'(1) is > 0 at θ'(0) = ratio (the linear beam's) and < 0 at 0
    for _ in range(80):
        mid = 0.5 * (low + high)
        if shoot(mid)[0] > 0.0:
            high = mid
        else:
            low = mid
    _, x, z = shoot(0.5 * (low + high))
    return x, z


def solve(binary: str, scene: Path, out: Path) -> tuple[dict, np.ndarray | None]:
    done = subprocess.run([binary, "static", str(scene), "-o", str(out)], capture_output=True, text=True)
    found = SUMMARY.search(done.stderr)
    # An equilibrium found but unstable (the end moment is a dead load: from K = 0.5 on, the rolled
    # beam is unstable) is written and reported with exit 1.
    row = {"converged": int(found is not None), "stable": int(done.returncode == 0), "newton_iterations": "",
           "path_steps": "", "statics_s": ""}
    if not found:
        return row, None
    row.update(newton_iterations=int(found[1]), path_steps=int(found[3]), statics_s=float(found[4]))
    with h5py.File(out, "r") as f:
        tip = f["joints/beam.end/position"][-1]
    return row, np.asarray(tip)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "crane-sim"), help="crane-sim binary")
    parser.add_argument("--segments", default="3,5,10,20", help="segment counts")
    parser.add_argument("--ks", default="0.25,0.5,0.75,1.0", help="end moments K = M/M_circle")
    parser.add_argument("--ratios", default="2,5,10", help="tip forces PL²/EI")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "slender_statics.csv"))
    args = parser.parse_args()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fields = ["case", "type", "segments", "load", "converged", "stable", "newton_iterations", "path_steps", "statics_s",
              "tip_error_rel"]
    rows = []
    with out.open("w", newline="", encoding="utf-8") as handle, tempfile.TemporaryDirectory() as tmp:
        writer = csv.DictWriter(handle, fieldnames=fields)
        writer.writeheader()
        scene, results = Path(tmp) / "case.yaml", Path(tmp) / "case.h5"
        for kind in TYPES:
            for segments in [int(s) for s in args.segments.split(",")]:
                base = (ROOT / "configs" / f"end_moment_{kind}.yaml").read_text(encoding="utf-8")
                for k in [float(v) for v in args.ks.split(",")]:
                    text = re.sub(r"segments: \d+", f"segments: {segments}", base, count=1)
                    text = re.sub(r"scale: [\d.]+ ", f"scale: {k!r} ", text, count=1)
                    scene.write_text(text, encoding="utf-8")
                    row, tip = solve(args.bin, scene, results)
                    length, kappa = 15.0, 2.0 * math.pi * k / 15.0
                    exact = np.array([math.sin(kappa * length) / kappa, 0.0, (1.0 - math.cos(kappa * length)) / kappa])
                    row.update(case="end_moment", type=kind, segments=segments, load=k,
                               tip_error_rel="" if tip is None else f"{np.linalg.norm(tip - exact) / length:.3e}")
                    writer.writerow(row)
                    handle.flush()
                    rows.append(row)
                for ratio in [float(v) for v in args.ratios.split(",")]:
                    force = -ratio * EI / LENGTH**2
                    scene.write_text(TIP_FORCE_SCENE.format(type=kind, length=LENGTH, segments=segments, radius=RADIUS,
                                                            E=E, force=force), encoding="utf-8")
                    row, tip = solve(args.bin, scene, results)
                    x, z = elastica_tip(ratio)
                    exact = LENGTH * np.array([x, 0.0, z])
                    row.update(case="tip_force", type=kind, segments=segments, load=ratio,
                               tip_error_rel="" if tip is None else f"{np.linalg.norm(tip - exact) / LENGTH:.3e}")
                    writer.writerow(row)
                    handle.flush()
                    rows.append(row)
    for case in ("end_moment", "tip_force"):
        mine = [r for r in rows if r["case"] == case]
        ok = [r for r in mine if r["converged"]]
        total = sum(r["newton_iterations"] for r in ok)
        print(f"{case}: {len(ok)}/{len(mine)} found, Newton iterations total {total}, max "
              f"{max((r['newton_iterations'] for r in ok), default=0)}", file=sys.stderr)


if __name__ == "__main__":
    main()
