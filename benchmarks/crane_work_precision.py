"""Work-precision of the thesis crane's combined motion (8.3.2) for each integrator setting.

For the super truss and the condensed crane (configs/crane_combined.yaml, and the same scene
with the eight lattice sections `fidelity: condensed`), runs crane-sim at every integrator
setting of the grid (integrator × rtol, atol = rtol · --atol-ratio; integrators: IDAS' BDF with
a maximum order, `bdf2`, optionally with a bound on its step growth other than the scene's,
`bdf2g2`, and the generalized-α method with its ρ∞, `ga0.8`), `--reps` times (fewer when the
runs so far took over --rep-budget seconds; the integrators' runs at one rtol alternate, so
their ratios are measured side by side), and records the median
integration wall time (results' solver/wall_time_s: the equilibrium excluded) against the maximum hook-position error over the whole motion, measured
against the same model at --ref-rtol (order --ref-order). Also records how much sway the
integrator damps away: the load's sway amplitude after the drives stop (half the peak-to-peak
horizontal excursion about its mean over [--settle, t_end]) relative to the reference's.

Writes a CSV (default benchmarks/results/crane_work_precision.csv, flushed after every row)
and a plot of wall time against error (same name, .png).

    python3 benchmarks/crane_work_precision.py                                # ≈ 1.5 h on 2 cores
    python3 benchmarks/crane_work_precision.py --fidelities condensed --integrators bdf2,ga0.8 --rtols 1e-4 --reps 1
    python3 benchmarks/crane_work_precision.py --merge a.csv b.csv --out all.csv   # one table and plot
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
SECTIONS = ["boom1", "boom2", "boom3", "boom4", "boom5", "derrick1", "derrick2", "derrick3"]
FIDELITIES = {"super_truss": [], "condensed": [f"  members.{s}.fidelity: condensed" for s in SECTIONS]}
DRIVES_STOP = 40.0  # s: the last drive of crane_combined.yaml stops here


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "crane-sim"), help="crane-sim binary")
    parser.add_argument("--fidelities", default=",".join(FIDELITIES), help="comma-separated subset of " + ",".join(FIDELITIES))
    parser.add_argument("--integrators", default="bdf5,bdf2",
                        help="comma-separated: bdf<maximum order> (IDAS), ga<ρ∞> (generalized-α), e.g. bdf2,ga0.8")
    parser.add_argument("--rtols", default="1e-3,1e-4,1e-5", help="relative tolerances")
    parser.add_argument("--atol-ratio", type=float, default=0.1, help="atol = rtol × this (coordinates and velocities)")
    parser.add_argument("--ref-rtol", type=float, default=1e-8, help="tolerance of the reference run")
    parser.add_argument("--ref-order", type=int, default=5, help="maximum order of the reference run")
    parser.add_argument("--reps", type=int, default=3, help="runs per setting; the median wall time is reported")
    parser.add_argument("--rep-budget", type=float, default=120.0,
                        help="repeat a setting only while its runs so far took less than this many seconds (0: always --reps)")
    parser.add_argument("--t-end", type=float, default=60.0, help="end of every run, s")
    parser.add_argument("--settle", type=float, default=DRIVES_STOP + 5.0, help="start of the sway-amplitude window, s")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "crane_work_precision.csv"))
    parser.add_argument("--merge", nargs="+", metavar="CSV",
                        help="run nothing: merge these CSVs of earlier runs into --out and plot them")
    return parser.parse_args()


def integrator_settings(name: str) -> list[str]:
    """Scene lines of an integrator named bdf<order> or ga<ρ∞>."""
    if name.startswith("bdf"):
        order, _, growth = name[3:].partition("g")
        return [f"  solver.max_order: {int(order)}"] + ([f"  solver.max_step_growth: {float(growth):g}"] if growth else [])
    if name.startswith("ga"):
        return ["  solver.integrator: generalized_alpha", f"  solver.rho_inf: {float(name[2:]):g}"]
    raise ValueError(f"unknown integrator '{name}': use bdf<order> or ga<rho_inf>")


def integrator_label(name: str) -> str:
    if name.startswith("bdf"):
        order, _, growth = name[3:].partition("g")
        return f"BDF order ≤ {order}" + (f", step growth ≤ {growth}" if growth else "")
    return f"generalized-α ρ∞ = {name[2:]}"


def scene_text(fidelity: str, integrator: str, rtol: float, atol: float, t_end: float) -> str:
    lines = [f"base: {ROOT / 'configs' / 'crane_combined.yaml'}", "modify:", *FIDELITIES[fidelity],
             *integrator_settings(integrator), f"  solver.rtol: {rtol:g}", f"  solver.atol: {atol:g}", f"  solver.t_end: {t_end:g}"]
    return "\n".join(lines) + "\n"


def run(binary: str, scene: str, workdir: Path, name: str) -> tuple[np.ndarray, np.ndarray, dict, float]:
    """Runs a scene; returns times, load positions, solver statistics and the process wall time."""
    path = workdir / f"{name}.yaml"
    path.write_text(scene, encoding="utf-8")
    out = workdir / f"{name}.h5"
    start = time.perf_counter()
    done = subprocess.run([binary, "run", str(path), "-o", str(out), "--quiet"], capture_output=True, text=True)
    process = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f"{name}: crane-sim exited with {done.returncode}: {done.stderr.strip()}")
    with h5py.File(out, "r") as f:
        stats = {k: f["solver"].attrs[k] for k in f["solver"].attrs}
        t, p = f["time"][()], f["bodies/load/position"][()]
    out.unlink()
    return t, p, stats, process


def sway_amplitude(t: np.ndarray, p: np.ndarray, start: float) -> float:
    """Half the peak-to-peak horizontal excursion of the load about its mean after `start`."""
    horizontal = p[t >= start, :2]
    centred = horizontal - horizontal.mean(axis=0)
    _, _, axes = np.linalg.svd(centred, full_matrices=False)
    component = centred @ axes[0]
    return 0.5 * float(component.max() - component.min())


def plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 5))
    colours = {"super_truss": "tab:blue", "condensed": "tab:orange"}
    markers = {"bdf1": "v", "bdf2": "o", "bdf3": "s", "bdf4": "D", "bdf5": "^", "ga1": "P", "ga0.8": "X", "ga0.5": "*", "ga0": "d"}
    for fidelity in dict.fromkeys(r["fidelity"] for r in rows):
        for integrator in dict.fromkeys(r["integrator"] for r in rows if r["fidelity"] == fidelity):
            sel = sorted((r for r in rows if r["fidelity"] == fidelity and r["integrator"] == integrator), key=lambda r: r["rtol"])
            ax.loglog([max(r["hook_error_max_m"], 1e-7) for r in sel], [r["wall_median_s"] for r in sel],
                      (":" if "g" in integrator else "-") if integrator.startswith("bdf") else "--",
                      marker=markers.get(integrator.partition("g")[0], "P"),
                      color=colours.get(fidelity), label=f"{fidelity.replace('_', ' ')}, {integrator_label(integrator)}")
            for r in sel:
                ax.annotate(f"{r['rtol']:g}", (max(r["hook_error_max_m"], 1e-7), r["wall_median_s"]), fontsize=7,
                            textcoords="offset points", xytext=(4, 3))
    t_end = rows[0]["t_end_s"]
    for factor, style in ((1, ":"), (10, "--"), (100, "-.")):
        ax.axhline(t_end / factor, color="grey", linestyle=style, linewidth=0.8)
        ax.text(ax.get_xlim()[0], t_end / factor, f" {factor}× real time", fontsize=7, va="bottom", color="grey")
    ax.axvline(0.01, color="red", linestyle=":", linewidth=0.8)
    ax.text(0.01, ax.get_ylim()[1], " 1 cm", fontsize=7, va="top", color="red")
    ax.set_xlabel("max hook-position error over the motion [m] (vs same model at tight rtol)")
    ax.set_ylabel("integration wall time [s], median")
    ax.set_title(f"Thesis crane, combined motion 8.3.2 ({t_end:g} s simulated): work against precision", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=130)


COLUMNS = ["fidelity", "integrator", "rtol", "atol", "t_end_s", "wall_median_s", "process_median_s", "realtime_factor",
           "steps", "residuals", "jacobians", "hook_error_max_m", "hook_error_end_m", "sway_amplitude_ratio", "reps"]


def formatted(row: dict) -> dict:
    """A row as the CSV writes it: floats to 4 significant digits."""
    return {k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()}


def merge(paths: list[str], out: Path) -> None:
    rows = []
    for path in paths:
        with open(path, newline="", encoding="utf-8") as handle:
            for row in csv.DictReader(handle):
                if "integrator" not in row:  # written before the generalized-α method existed
                    row["integrator"] = f"bdf{row['max_order']}"
                rows.append({k: (row[k] if k in ("fidelity", "integrator") else int(row[k]) if k in ("steps", "residuals", "jacobians", "reps")
                                 else float(row[k])) for k in COLUMNS})
    with out.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(formatted(row) for row in rows)
    plot(rows, out.with_suffix(".png"))


def main() -> None:
    args = parse_arguments()
    if args.merge:
        merge(args.merge, Path(args.out))
        return
    fidelities = [f for f in args.fidelities.split(",") if f]
    for f in fidelities:
        if f not in FIDELITIES:
            sys.exit(f"unknown fidelity '{f}' (known: {', '.join(FIDELITIES)})")
    integrators = [i for i in args.integrators.split(",") if i]
    for i in integrators:
        integrator_settings(i)
    rtols = [float(r) for r in args.rtols.split(",")]
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    rows = []
    with out.open("w", newline="", encoding="utf-8") as handle, tempfile.TemporaryDirectory() as tmp:
        writer = csv.DictWriter(handle, fieldnames=COLUMNS)
        writer.writeheader()
        for fidelity in fidelities:
            ref_atol = args.ref_rtol * args.atol_ratio
            start = time.perf_counter()
            t_ref, p_ref, _, _ = run(args.bin, scene_text(fidelity, f"bdf{args.ref_order}", args.ref_rtol, ref_atol, args.t_end), Path(tmp), "reference")
            print(f"{fidelity}: reference (order {args.ref_order}, rtol {args.ref_rtol:g}) in {time.perf_counter() - start:.0f} s",
                  file=sys.stderr)
            amplitude_ref = sway_amplitude(t_ref, p_ref, args.settle)
            for rtol in rtols:
                walls = {i: [] for i in integrators}
                processes = {i: [] for i in integrators}
                last = {}
                for _ in range(args.reps):
                    for integrator in integrators:
                        if walls[integrator] and args.rep_budget > 0 and sum(processes[integrator]) >= args.rep_budget:
                            continue
                        t, p, stats, process = run(args.bin, scene_text(fidelity, integrator, rtol, rtol * args.atol_ratio, args.t_end), Path(tmp), "case")
                        walls[integrator].append(float(stats["wall_time_s"]))
                        processes[integrator].append(process)
                        last[integrator] = (t, p, stats)
                for integrator in integrators:
                    t, p, stats = last[integrator]
                    if t.shape != t_ref.shape or np.max(np.abs(t - t_ref)) > 1e-9:
                        raise RuntimeError(f"{fidelity}: output times differ from the reference's")
                    error = np.linalg.norm(p - p_ref, axis=1)
                    wall = statistics.median(walls[integrator])
                    row = {"fidelity": fidelity, "integrator": integrator, "rtol": rtol, "atol": rtol * args.atol_ratio, "t_end_s": float(t[-1]),
                           "wall_median_s": wall, "process_median_s": statistics.median(processes[integrator]), "realtime_factor": t[-1] / wall,
                           "steps": int(stats["steps"]), "residuals": int(stats["residual_evaluations"]),
                           "jacobians": int(stats["jacobian_evaluations"]), "hook_error_max_m": float(error.max()),
                           "hook_error_end_m": float(error[-1]),
                           "sway_amplitude_ratio": sway_amplitude(t, p, args.settle) / amplitude_ref, "reps": len(walls[integrator])}
                    rows.append(row)
                    writer.writerow(formatted(row))
                    handle.flush()
                    print(f"{fidelity} {integrator} rtol {rtol:g}: wall {wall:.2f} s ({t[-1] / wall:.2f}× real time), "
                          f"{row['steps']} steps, {row['jacobians']} Jacobians, hook error {row['hook_error_max_m']:.2e} m, "
                          f"sway amplitude {row['sway_amplitude_ratio']:.4f} of the reference's", file=sys.stderr)
    plot(rows, out.with_suffix(".png"))


if __name__ == "__main__":
    main()
