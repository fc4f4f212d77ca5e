"""What the planning tables' scripts share: plan a target with crane-opt several times and keep
the NLP's and the whole plan's wall times; the verified load's sway after the arrival; the
machine's load."""

import os
import statistics
import subprocess
import time
from pathlib import Path

import h5py
import numpy as np


def timed_plans(crane_opt: str, target: Path, out: Path, runs: int) -> tuple[list[float], list[float]]:
    """Plans `target` into `out` `runs` times; the NLP's times (the plan file's /path nlp_time_s)
    and crane-opt's wall times, s. The last plan stays in `out`."""
    nlp, whole = [], []
    for _ in range(runs):
        started = time.perf_counter()
        subprocess.run([crane_opt, "plan", str(target), "-o", str(out), "--quiet"], check=True, capture_output=True)
        whole.append(time.perf_counter() - started)
        with h5py.File(out, "r") as plan:
            nlp.append(float(plan["path"].attrs["nlp_time_s"]))
    return nlp, whole


def sway(plan: h5py.File) -> tuple[float, float]:
    """The load's largest horizontal distance from the target in the 5 s after the planned
    arrival, and after those to the end of the run, m."""
    v = plan["verification"]
    arrival = plan["controls"].attrs["lead_time"] + plan["path"].attrs["motion_time"]
    t, off = v["t"][()], np.linalg.norm((v["simulated"][()] - v["planned"][-1])[:, :2], axis=1)
    return float(off[(t >= arrival) & (t <= arrival + 5)].max()), float(off[t > arrival + 5].max())


def median(values: list[float]) -> float:
    return statistics.median(values)


def load_average() -> str:
    """The machine's 1-minute load average, for the table's caption."""
    return f"{os.getloadavg()[0]:.1f}"
