"""output.constraint_loads: the force and moment a constraint transmits, per sample.

A 1 kg, 1 m rod hinged at its end and released from the horizontal (configs/pendulum.yaml):
the hinge's reaction is m g √(6.25 cos²θ + 0.0625 sin²θ) at angle θ from the vertical (radial
5/2 m g cos θ, tangential 1/4 m g sin θ), m g / 4 straight up at release, so the dynamic factor
over the swing is 10, and a revolute hinge of a planar swing carries no moment. With the joints
in the other order the same load is reported on the ground's side: the opposite force, in the
rod's hinge axes.

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
WEIGHT = 1.0 * 9.81


def run(directory: Path, name: str, modify: str) -> h5py.File:
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    (directory / f"{name}.yaml").write_text(f"base: {SOURCE_DIR / 'configs' / 'pendulum.yaml'}\nmodify: {{{modify}}}\n")
    done = subprocess.run([str(BINARY), "run", f"{name}.yaml", "-o", f"{name}.h5", "--quiet"], cwd=directory,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return h5py.File(directory / f"{name}.h5", "r")


def test_hinge_reaction_of_a_released_rod(tmp_path):
    with run(tmp_path, "hinge", "output.constraint_loads: [hinge], solver.t_end: 3") as f:
        loads = f["constraint_loads/hinge"]
        force, moment = loads["force"][...], loads["moment"][...]
        cos = -f["joints/rod.tip/position"][:, 2]
        sin = np.sqrt(np.clip(1.0 - cos**2, 0.0, None))
        expected = WEIGHT * np.sqrt(6.25 * cos**2 + 0.0625 * sin**2)
        assert force.shape == (len(cos), 3)
        assert np.abs(np.linalg.norm(force, axis=1) - expected).max() < 1e-6 * WEIGHT
        assert np.allclose(force[0], [0.0, 0.0, WEIGHT / 4], atol=1e-9)
        assert np.abs(moment).max() < 1e-9
        assert loads.attrs["dynamic_factor"] == pytest.approx(10.0, rel=1e-6)
        assert loads.attrs["peak_force"] == pytest.approx(2.5 * WEIGHT, rel=1e-6)


def test_the_ground_side_when_the_ground_is_the_second_joint(tmp_path):
    with run(tmp_path, "ground_first", "output.constraint_loads: [hinge], solver.t_end: 1") as a, \
         run(tmp_path, "ground_second", "constraints.hinge.joints: [rod.top, ground.pivot], "
             "output.constraint_loads: [hinge], solver.t_end: 1") as b:
        on_rod = a["constraint_loads/hinge/force"][...]
        on_ground = b["constraint_loads/hinge/force"][...]
        axes = b["joints/rod.top/rotation"][...]  # row-major R: R[i, j]
        assert on_rod.shape == on_ground.shape
        turned = np.einsum("sij,sj->si", axes, on_ground)
        assert np.abs(turned + on_rod).max() < 1e-5 * WEIGHT


def test_tipping_moment_about_a_line_beside_the_hinge(tmp_path):
    # output.tipping_lines: the ground's moment on the rod through the hinge about a line along y
    # half a metre beside it is 0.5 m times the hinge's vertical force (its only moment arm), and
    # the same line directed the other way gives the opposite.
    line = "[[0.5, -1, 0], [0.5, 1, 0]]"
    with run(tmp_path, "tipping", "output.constraint_loads: [hinge], output.tipping_lines: "
             f"[{{name: edge, supports: [hinge], line: {line}}}, {{name: back, supports: [hinge], line: [[0.5, 1, 0], [0.5, -1, 0]]}}], "
             "solver.t_end: 2") as f:
        edge, back = f["tipping_moments/edge"][...], f["tipping_moments/back"][...]
        force = f["constraint_loads/hinge/force"][...]
        assert edge.shape == (force.shape[0],)
        assert np.abs(edge - 0.5 * force[:, 2]).max() < 1e-7 * WEIGHT
        assert np.abs(edge + back).max() < 1e-9 * WEIGHT
        assert f["tipping_moments/edge"].attrs["min"] == pytest.approx(edge.min())
        assert f["tipping_moments/edge"].attrs["supports"] == "hinge"
        assert f["tipping_moments/edge"].attrs["sign"].startswith("> 0: the supports hold the structure on its footprint")
        minima = {"edge": edge.min(), "back": back.min()}
    # The report states each line's smallest moment and what its sign means.
    report = subprocess.run(["python3", str(SOURCE_DIR / "scripts" / "report.py"), str(tmp_path / "tipping.h5")],
                            capture_output=True, text=True, timeout=60)
    assert report.returncode == 0, report.stderr
    for name, minimum in minima.items():
        verdict = "held on its footprint" if minimum > 0 else "tips over the line"
        assert f"tipping moment about '{name}': min {minimum:.6g} N·m ({verdict}; > 0 holds it)" in report.stdout
