"""solver.max_step_growth: IDAS' largest step growth after a successful step (IDASetEtaMax).

The undamped Timoshenko cantilever dropped under gravity (configs/cantilever_timoshenko.yaml,
BDF ≤ 5, rtol 1e-6), 2 s: with IDAS' own bound (2) it takes 32 679 steps, 54 658 residuals and
26 Jacobians, with the default 1.5 30 244, 41 057 and 15 (over the full 5 s: 79 373 → 71 918
steps, 331 → 29 Jacobians). The bound must keep the motion within the run's tolerance and save
work.

Environment: CRANESIM_BIN (default <repo>/build/crane-sim) and CRANESIM_SOURCE_DIR.
"""

import os
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()


def run(directory: Path, name: str, modify: str) -> Path:
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    base = SOURCE_DIR / "configs" / "cantilever_timoshenko.yaml"
    (directory / f"{name}.yaml").write_text(f"base: {base}\nmodify: {{{modify}}}\n")
    done = subprocess.run([str(BINARY), "run", f"{name}.yaml", "-o", f"{name}.h5", "--quiet"], cwd=directory,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return directory / f"{name}.h5"


def test_bounded_step_growth_keeps_the_motion_with_fewer_jacobians(tmp_path):
    own = run(tmp_path, "own", "solver.t_end: 2, solver.max_step_growth: 2")
    bounded = run(tmp_path, "bounded", "solver.t_end: 2")
    with h5py.File(own, "r") as a, h5py.File(bounded, "r") as b:
        tip_a, tip_b = a["joints/beam.end/position"][...], b["joints/beam.end/position"][...]
        assert tip_a.shape == tip_b.shape
        swing = np.abs(tip_a - tip_a[0]).max()
        assert swing > 1e-3  # the tip moves
        assert np.abs(tip_a - tip_b).max() < 1e-3 * swing
        work = {key: (a["solver"].attrs[key], b["solver"].attrs[key]) for key in ("jacobian_evaluations", "residual_evaluations")}
        assert work["jacobian_evaluations"][1] < 0.8 * work["jacobian_evaluations"][0], work
        assert work["residual_evaluations"][1] < 0.9 * work["residual_evaluations"][0], work


def test_max_step_growth_belongs_to_bdf(tmp_path):
    (tmp_path / "alpha.yaml").write_text(
        f"base: {SOURCE_DIR / 'configs' / 'cantilever_timoshenko.yaml'}\n"
        "modify: {solver.integrator: generalized_alpha, solver.max_step_growth: 1.5}\n")
    done = subprocess.run([str(BINARY), "run", "alpha.yaml", "-o", "alpha.h5"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 2
    assert "solver.max_step_growth" in done.stderr and "generalized-α" in done.stderr
    assert not (tmp_path / "alpha.h5").exists()
