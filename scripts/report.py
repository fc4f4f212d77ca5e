"""Plain-text summary of a cranesim run, for CI logs.

Prints status, message, time span, sample count, solver statistics, the
maximum constraint residuals and the relative energy drift
max|balance - balance[0]| over the run's energy scale, max(kinetic +
|potential - potential[0]| + |drive_work| + |load_work| + |winch_work| +
dissipated), as crane-sim run reports it (files without winch_work and
dissipated count them as 0).

Example:

    python scripts/report.py run.h5
"""

import argparse
import sys

import numpy as np

from cranesim.results import Results, run_command

NOT_AVAILABLE = "n/a (no samples)"


def relative_energy_drift(results: Results) -> float:
    balance = results.get("energy/balance")
    potential = results.get("energy/potential")
    scale = results.get("energy/kinetic") + np.abs(potential - potential[0])
    for work in ("drive_work", "load_work", "winch_work", "dissipated"):
        if results.has(f"energy/{work}"):
            scale = scale + np.abs(results.get(f"energy/{work}"))
    scale = np.max(scale)
    drift = np.max(np.abs(balance - balance[0]))
    return drift / scale if scale > 0 else float("nan")


def summary_lines(results: Results) -> list[str]:
    time = results.time()
    lines = [
        f"file: {results.path}",
        f"status: {results.status}",
        f"message: {results.message}",
        f"formulation: {results.attribute('formulation')}",
        f"engine_version: {results.attribute('engine_version')}",
        f"scene_path: {results.attribute('scene_path')}",
        f"samples: {time.size}",
    ]
    requested = results.attribute("t_end_requested")
    if time.size == 0:
        lines += [
            f"time span: {NOT_AVAILABLE} (requested end {requested:g} s)",
            f"max position residual: {NOT_AVAILABLE}",
            f"max velocity residual: {NOT_AVAILABLE}",
            f"relative energy drift: {NOT_AVAILABLE}",
        ]
    else:
        lines += [
            f"time span: {time[0]:g} .. {time[-1]:g} s (requested end {requested:g} s)",
            f"max position residual: {np.max(results.get('residual/position')):.6e}",
            f"max velocity residual: {np.max(results.get('residual/velocity')):.6e}",
            f"relative energy drift: {relative_energy_drift(results):.6e}",
        ]
    for name, moment in results.tipping_moments().items():
        lines.append(f"tipping moment about '{name}': min {np.min(moment):.6g} N·m "
                     f"({'held on its footprint' if np.min(moment) > 0 else 'tips over the line'}; > 0 holds it)")
    lines.append("solver:")
    lines += [f"  {name}: {value}" for name, value in results.solver_statistics().items()]
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("results", help="results file (.h5)")
    args = parser.parse_args()
    with Results(args.results) as results:
        print("\n".join(summary_lines(results)))


if __name__ == "__main__":
    sys.exit(run_command(main))
