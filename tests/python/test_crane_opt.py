"""Command-line behaviour of crane-opt: bad targets, the plan file and the map-only file.

Every tests/data/bad_targets/*.yaml is a near-copy of configs/target_luffing_jib.yaml with one
defect. Its first two lines say what the error must contain and which YAML path it names:

    # expect: <substring of the error message>
    # path: <YAML path the error is reported at>

Environment: CRANEOPT_BIN (default <repo>/build/crane-opt), CRANESIM_BIN (default
<repo>/build/crane-sim) and CRANESIM_SOURCE_DIR.
"""

import os
import re
import shutil
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest
import yaml

from bad_input import assert_reported, expectations
from mpi_launch import mpirun

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANEOPT_BIN", SOURCE_DIR / "build" / "crane-opt")).resolve()
CRANE_SIM = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()
BAD_TARGETS = sorted((SOURCE_DIR / "tests" / "data" / "bad_targets").glob("*.yaml"))
JIB_TARGET = SOURCE_DIR / "configs" / "target_luffing_jib.yaml"


def crane_opt(*arguments, cwd: Path, timeout: float = 120) -> subprocess.CompletedProcess:
    return subprocess.run([str(BINARY), *map(str, arguments)], cwd=cwd, capture_output=True, text=True, timeout=timeout)


@pytest.mark.parametrize("target", BAD_TARGETS, ids=lambda p: p.stem)
def test_bad_target_is_rejected(target: Path, tmp_path: Path):
    expect, path = expectations(target)
    result = crane_opt("plan", target, "-o", tmp_path / "plan.h5", "--quiet", cwd=tmp_path)
    assert_reported(result, target, expect, path)
    assert list(tmp_path.iterdir()) == []  # no result file, not even a partial one


@pytest.fixture(scope="module")
def jib_plan(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("plan") / "jib.h5"
    result = crane_opt("plan", JIB_TARGET, "-o", out, cwd=out.parent)
    assert result.returncode == 0, result.stderr
    assert (out.parent / "jib_simulation.h5").exists()
    return out


def test_plan_respects_bounds_and_reaches_target(jib_plan: Path):
    with h5py.File(jib_plan, "r") as f:
        state, control = f["trajectory/state"][...], f["trajectory/control"][...]
        assert f.attrs["contents"] == "plan"
        lower, upper = np.array([-18, 5, -0.5, -0.5]), np.array([-6, 15, 0.5, 0.5])
        assert np.all(state >= lower - 1e-8) and np.all(state <= upper + 1e-8)
        assert np.all(np.abs(control) <= 0.2 + 1e-8)
        assert np.allclose(state[0], [-10, 7.5, 0, 0], atol=1e-9)
        assert np.allclose(state[-1], [-14, 10, 0, 0], atol=0.02)
        # The hoist rope's length is exact (the map's own variable); the fit of the luffing rope
        # and of the end point is good to millimetres on this 5° × 1 m grid.
        assert np.max(f["inversion/error"][...]) < 0.01
        assert f["fit/luffing_length"].attrs["max_residual"] < 0.005


def test_plan_control_splines_start_and_end_at_rest(jib_plan: Path):
    with h5py.File(jib_plan, "r") as f:
        for name in ("luffing_length", "hoist_length"):
            slopes = f[f"controls/spline/{name}/slopes"][...]
            y = f[f"controls/spline/{name}/y"][...]
            assert slopes[0] == 0 and slopes[-1] == 0
            assert y[0] == pytest.approx(f[f"controls/{name}"][0], abs=1e-12)
            assert y[-1] == pytest.approx(f[f"controls/{name}"][-1], abs=1e-12)


def test_plan_verification_tracks_the_plan(jib_plan: Path):
    with h5py.File(jib_plan, "r") as f:
        v = f["verification"]
        assert v.attrs["status"] == "complete"
        planned, simulated = v["planned"][...], v["simulated"][...]
        error = np.linalg.norm(simulated - planned, axis=1)  # (x, y, z); the plan lies in y = 0
        assert np.max(np.abs(planned[:, 1])) < 1e-9
        # The 1 t load sways on its 10 m rope (period 6.3 s) under 0.2 m/s² of planned
        # acceleration: a quasi-static plan tracks it to decimetres, not millimetres.
        assert v.attrs["max_error"] == pytest.approx(np.max(error[(v["t"][...] >= f["controls"].attrs["lead_time"])
                                                                 & (v["t"][...] <= f["controls"].attrs["lead_time"] + 15)]), rel=1e-9)
        assert v.attrs["max_error"] < 0.6
        assert v.attrs["final_error"] < 0.1
        assert np.max(np.abs(simulated[:, 1])) < 1e-6  # the motion stays in the jib's plane


def verification_as_scene(plan: Path, base: Path) -> dict:
    """The plan's verification written as a crane-sim scene: the base scene with its ropes driven
    by the plan's control splines (table profiles: crane-sim computes the same zero-end-slope
    spline from the knots), from the equilibrium at t = 0 to the last knot plus the settle time."""
    with h5py.File(plan, "r") as f:
        settle = yaml.safe_load(f.attrs["target_text"])["verification"]["settle_time"]
        splines = {rope: (f[f"controls/spline/{name}/t"][...], f[f"controls/spline/{name}/y"][...])
                   for rope, name in (("luffing_rope", "luffing_length"), ("hoist_rope", "hoist_length"))}
    modify = {f"members.{rope}.length": {"type": "table", "t": [float(v) for v in t], "value": [float(v) for v in y]}
              for rope, (t, y) in splines.items()}
    end = max(t[-1] for t, _ in splines.values())
    modify.update({"solver.t_start": 0.0, "solver.t_end": float(end + settle), "solver.initial_state": "equilibrium"})
    return {"base": str(base), "name": "crane-opt verification as a scene", "modify": modify}


def test_verification_takes_the_steps_of_crane_sim(jib_plan: Path, tmp_path: Path):
    """The verification inside crane-opt and crane-sim running the same scene and splines are one
    computation: the same steps, Jacobians and error-test failures, the same load path. (The
    splines' slopes used to be computed before the knots were shifted onto the simulation's time
    axis: rounding-level differences, 7779 steps against crane-sim's 7830 here.)"""
    scene = tmp_path / "verification.yaml"
    scene.write_text(yaml.safe_dump(verification_as_scene(jib_plan, SOURCE_DIR / "configs" / "luffing_jib.yaml")))
    results = tmp_path / "verification.h5"
    run = subprocess.run([str(CRANE_SIM), "run", str(scene), "-o", str(results), "--quiet"], capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    with h5py.File(jib_plan.parent / "jib_simulation.h5", "r") as inside, h5py.File(results, "r") as outside:
        counters = ("steps", "residual_evaluations", "jacobian_evaluations", "error_test_failures", "nonlinear_failures")
        assert {c: inside["solver"].attrs[c] for c in counters} == {c: outside["solver"].attrs[c] for c in counters}
        assert inside["solver"].attrs["steps"] > 1000  # a run with something to lose
        assert np.array_equal(inside["time"][...], outside["time"][...])
        hook_inside, hook_outside = inside["joints/load.hook/position"][...], outside["joints/load.hook/position"][...]
        assert np.max(np.abs(hook_inside - hook_outside)) < 1e-12


@pytest.mark.parametrize("method", ["zv", "zvd"])
def test_input_shaping_cuts_the_residual_sway(method: str, jib_plan: Path, tmp_path: Path):
    """The jib's quasi-static plan leaves its load swaying ±0.44 m; shaped for the crane's mean
    sway period (6.44 s at the start, 4.41 s at the end) ZV leaves ±0.011 m and ZVD ±0.029 m
    (measured). The shaper delays the arrival by T/2 (ZV) or T (ZVD)."""
    target = tmp_path / "target.yaml"
    target.write_text(f"method: {method}\n" + JIB_TARGET.read_text().replace("scene: luffing_jib.yaml",
                                                                           f"scene: {JIB_TARGET.parent / 'luffing_jib.yaml'}"))
    out = tmp_path / "plan.h5"
    result = crane_opt("plan", target, "-o", out, "--quiet", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    with h5py.File(jib_plan, "r") as plain, h5py.File(out, "r") as shaped:
        assert plain["path"].attrs["method"] == "quasi_static" and shaped["path"].attrs["method"] == method
        attrs = shaped["path"].attrs
        lengths = [attrs["hanging_length_start"], attrs["hanging_length_end"]]
        assert lengths == pytest.approx([9.82, 4.29], abs=0.01)  # hoist rope's top to the hook
        # The modal periods exceed the simple pendulum's 2π√(L/g) to the hook: the 1 t block hangs
        # 0.5 m below it with its own inertia (the shorter the rope, the more that counts).
        for end, length in zip(("start", "end"), lengths):
            ratio = attrs[f"sway_period_{end}"] / (2 * np.pi * np.sqrt(length / 9.81))
            assert 1.01 < ratio < 1.08, (end, ratio)
        period = attrs["sway_period"]
        assert period == pytest.approx(0.5 * (attrs["sway_period_start"] + attrs["sway_period_end"]), rel=1e-12)
        delay = {"zv": period / 2, "zvd": period}[method]
        assert shaped["path"].attrs["motion_time"] == pytest.approx(plain["path"].attrs["motion_time"] + delay, abs=0.1)
        assert np.allclose(shaped["path/state"][-1], plain["path/state"][-1], atol=1e-9)  # same arrival
        before, after = plain["verification"].attrs["residual_sway"], shaped["verification"].attrs["residual_sway"]
        assert before > 0.3
        assert after < before / 5
        assert shaped["verification"].attrs["final_error"] < 0.02


def test_flatness_leaves_the_jib_still(jib_plan: Path, tmp_path: Path):
    """The load's rest-to-rest path over the QR horizon (15 s, ramps of 7 s for x's 0.5 m/s), carried
    by the map's controls at the point where the load would hang at rest from its suspension:
    measured ±0.0005 m of sway against the quasi-static plan's ±0.435 m, in the same motion time,
    the verified load within 8 mm of its path."""
    target = tmp_path / "target.yaml"
    target.write_text("method: flatness\n" + JIB_TARGET.read_text().replace("scene: luffing_jib.yaml",
                                                                           f"scene: {JIB_TARGET.parent / 'luffing_jib.yaml'}"))
    out = tmp_path / "plan.h5"
    result = crane_opt("plan", target, "-o", out, "--quiet", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    with h5py.File(jib_plan, "r") as plain, h5py.File(out, "r") as flat:
        attrs = flat["path"].attrs
        assert attrs["method"] == "flatness"
        assert attrs["motion_time"] == pytest.approx(plain["path"].attrs["motion_time"], abs=1e-9)
        assert attrs["ramp_time"] == pytest.approx(7.0, abs=1e-9)
        # The pendulum of the flat map swings with the crane's period: g (T / 2π)².
        for end in ("start", "end"):
            assert attrs[f"pendulum_length_{end}"] == pytest.approx(9.81 * (attrs[f"sway_period_{end}"] / (2 * np.pi)) ** 2,
                                                                   rel=1e-3)
            assert attrs[f"pendulum_length_{end}"] > attrs[f"hanging_length_{end}"]
        state = flat["path/state"][()]
        assert np.allclose(state[0], flat["trajectory/start"][0], atol=1e-12)
        assert np.allclose(state[-1], flat["trajectory/target"][0], atol=1e-12)
        assert np.all(np.abs(state[:, 2:]) <= 0.5 + 1e-12)  # the target's speed bounds
        before, after = plain["verification"].attrs["residual_sway"], flat["verification"].attrs["residual_sway"]
        assert before > 0.3
        assert after < before / 100
        assert flat["verification"].attrs["max_error"] < 0.02
        assert flat["verification"].attrs["final_error"] < 0.01


# configs/luffing_jib.yaml with its hoist rope reeved on 2 falls: the winch at the boom's foot
# (its lead line along the boom, so luffing leaves it alone), over a sheave at the tip down to a
# sheave at the load's hook and back to a dead end at the tip; its length the drawn path's 40 m.
REEVED_JIB = """\
name: luffing jib, hoist on two falls
gravity: [0, 0, -9.81]
ground:
  joints: [{name: foot, position: [0, 0, 0]}, {name: mast_top, position: [4, 0, 12]}]
bodies:
  - {name: boom, mass: 2000, centroid: [10, 0, 0], inertia: [100, 66700, 66700], position: [0, 0, 0],
     rotation: {axis: [0, 1, 0], angle_deg: -120}, joints: [{name: foot, position: [0, 0, 0]}, {name: tip, position: [20, 0, 0]}]}
  - {name: load, mass: 1000, centroid: [0, 0, -0.5], inertia: [200, 200, 150], position: [-10, 0, 7.320508],
     joints: [{name: hook, position: [0, 0, 0]}]}
members:
  - {name: luffing_rope, type: rope, start: [4, 0, 12], end: [-10, 0, 17.320508], length: 14.9769, section: {radius: 0.01},
     damping: 1.0e-3, material: {density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.25}}
  - {name: hoist_rope, type: rope, element: reeved, falls: 2, winch: boom.foot, head: {joint: boom.tip, radius: 0.2},
     hook: {joint: load.hook, radius: 0.2}, section: {radius: 0.01}, damping: 1.0e-3,
     material: {density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.25}}
constraints:
  - {name: foot_pin, type: revolute, joints: [ground.foot, boom.foot], axis: y}
  - {name: luffing_on_mast, type: spherical, joints: [ground.mast_top, luffing_rope.start]}
  - {name: luffing_on_boom, type: spherical, joints: [boom.tip, luffing_rope.end]}
solver: {t_end: 10, rtol: 1.0e-6, atol: 1.0e-7, initial_state: equilibrium}
output: {interval: 0.05}
"""


def test_flatness_on_a_reeved_hoist_reels_two_metres_per_metre(jib_plan: Path, tmp_path: Path):
    """configs/target_luffing_jib.yaml by flatness on the jib whose hoist rope runs on 2 falls: the
    map's hoist control is the winch's rope, so the plan reels 2 m of it for every metre the load
    rises under the tip (to the falls' stretch, 1.6e-4), and the load arrives as still as on one
    fall (measured ±0.0005 m there)."""
    (tmp_path / "jib.yaml").write_text(REEVED_JIB)
    text = JIB_TARGET.read_text().replace("scene: luffing_jib.yaml", "scene: jib.yaml")
    text = text.replace("hoist_change: {from: 0, to: 8, step: 1}", "hoist_change: {from: 0, to: 16, step: 2}")
    target = tmp_path / "target.yaml"
    target.write_text("method: flatness\n" + text)
    out = tmp_path / "plan.h5"
    result = crane_opt("plan", target, "-o", out, "--quiet", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    with h5py.File(jib_plan, "r") as plain, h5py.File(out, "r") as f:
        attrs = f["path"].attrs
        assert f["map"].attrs["hoist_length_reference"] == pytest.approx(40.0, abs=1e-6)  # the drawn path, 20 m + 2 × 10 m (drawn to 1e-6 m)
        hoist = f["controls/hoist_length"][...]
        lifted = attrs["hanging_length_start"] - attrs["hanging_length_end"]
        assert lifted == pytest.approx(plain["path"].attrs["hanging_length_start"] - plain["path"].attrs["hanging_length_end"],
                                       abs=0.01)
        assert (hoist[0] - hoist[-1]) / lifted == pytest.approx(2.0, rel=1e-3)
        v = f["verification"].attrs
        assert v["status"] == "complete"
        assert v["residual_sway"] < 0.005 and v["max_error"] < 0.02 and v["final_error"] < 0.01


def test_map_only(tmp_path: Path):
    out = tmp_path / "map.h5"
    result = crane_opt("map", JIB_TARGET, "-o", out, "--threads", "1", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        assert f.attrs["contents"] == "map"
        assert f["map/luffing_length"].shape == (8, 9)
        assert f["map"].attrs["threads"] == 1
        assert "trajectory" not in f
        assert np.all(np.isfinite(f["map/end_z"][...]))


CRANE_TARGET = SOURCE_DIR / "configs" / "target.yaml"
SLEWING_TARGET = SOURCE_DIR / "configs" / "target_slewing.yaml"


def map_datasets(path: Path) -> dict:
    with h5py.File(path, "r") as f:
        return {name: f["map"][name][...] for name in f["map"]}


def coarse_condensed_crane_target(directory: Path) -> Path:
    """The thesis crane's map (configs/target.yaml) on the condensed crane, on a 9 × 14 grid."""
    text = CRANE_TARGET.read_text(encoding="utf-8")
    text = text.replace("scene: crane.yaml", f"scene: {SOURCE_DIR / 'configs' / 'crane_condensed.yaml'}", 1)
    text = text.replace("boom_angle: {from: 45, to: 85, step: 1}", "boom_angle: {from: 45, to: 85, step: 5}", 1)
    text = text.replace("hoist_change: {from: -2, to: 24, step: 1}", "hoist_change: {from: -2, to: 24, step: 2}", 1)
    assert "step: 5}" in text and "step: 2}" in text and "crane_condensed" in text
    path = directory / "target.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_map_is_bitwise_identical_on_threads_and_ranks(tmp_path: Path):
    """Each row of the map starts from its spine point alone, so it is the same whoever computes
    it: 1 thread, 2 threads and (when MPI is installed) 2 MPI ranks give the same bits."""
    target = coarse_condensed_crane_target(tmp_path)
    maps, logs = {}, {}
    for threads in (1, 2):
        out = tmp_path / f"threads_{threads}.h5"
        result = crane_opt("map", target, "-o", out, "--threads", threads, cwd=tmp_path)
        assert result.returncode == 0, result.stderr
        maps[f"{threads} threads"], logs[f"{threads} threads"] = map_datasets(out), result.stderr
    if shutil.which("mpirun"):
        out = tmp_path / "ranks_2.h5"
        result = mpirun(BINARY, 2, "map", target, "-o", out, cwd=tmp_path)
        if "built without MPI" in result.stderr:
            pytest.skip("crane-opt built without MPI: threads compared only")
        assert result.returncode == 0, result.stderr
        maps["2 ranks"], logs["2 ranks"] = map_datasets(out), result.stderr
        with h5py.File(out, "r") as f:
            assert f["map"].attrs["execution"].startswith("2 MPI ranks")
        # Both ranks computed rows (9 rows of about 30 ms each; rank 0 computes on one thread).
        assert "rank 1)" in result.stderr and "rank 0 thread 0)" in result.stderr, result.stderr
    assert "thread 1)" in logs["2 threads"] and "thread 0)" in logs["2 threads"]
    reference = maps["1 threads"]
    assert np.all(np.isfinite(reference["luffing_length"])) and reference["luffing_length"].shape == (9, 14)
    for name, datasets in maps.items():
        for key, values in reference.items():
            assert datasets[key].tobytes() == values.tobytes(), f"{key} differs with {name}"


def test_pick_and_set_by_radius_and_height(tmp_path: Path):
    """Table 8-2 given as a crane engineer reads it: the load picked at a radius of 10 m from the
    thesis crane's slewing axis (the vertical through the origin) at the origin's height, set at
    35 m and 10 m higher, without state bounds. The reader turns them into the plane's start and
    target exactly, the default bounds reach 10 m and 1 m/s beyond them, and the plan reports its
    ends as radius and height back, within the map's inversion (1e-5 m)."""
    target = coarse_condensed_crane_target(tmp_path)
    text = target.read_text(encoding="utf-8")
    for line, replacement in [("  start: [-10, 0, 0, 0]", "  pick: {radius: 10, height: 2.041}"),
                              ("  target: [-35, 10, 0, 0]", "  set: {radius: 35, height: 12.041}"),
                              ("  state_min: [-50, 0, -1, -1]", ""), ("  state_max: [-5, 30, 1, 1]", "")]:
        assert line in text, line
        text = text.replace(line, replacement, 1)
    target.write_text(text, encoding="utf-8")
    out = tmp_path / "plan.h5"
    result = crane_opt("plan", target, "-o", out, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        assert np.allclose(f["trajectory/start"][0], [-10, 0, 0, 0], rtol=0, atol=1e-12)
        assert np.allclose(f["trajectory/target"][0], [-35, 10, 0, 0], rtol=0, atol=1e-12)
        assert np.allclose(f["trajectory/state_bounds"][...], [[-45, -10, -1, -1], [0, 20, 1, 1]], rtol=0, atol=1e-12)
        radius, height = f["controls/radius"][...], f["controls/height"][...]
    assert abs(radius[0] - 10) < 1e-4 and abs(radius[-1] - 35) < 1e-4
    assert abs(height[0] - 2.041) < 1e-4 and abs(height[-1] - 12.041) < 1e-4
    assert np.all(radius >= 10 - 1e-4) and np.all(radius <= 35 + 1e-4)
    line = re.search(r"lift: from a radius of (\S+) m and a height of (\S+) m \(boom (\S+)°\) to (\S+) m and (\S+) m", result.stderr)
    assert line, result.stderr
    assert [float(v) for v in line.groups()[:2]] == pytest.approx([10, 2.041], abs=1e-3)
    assert [float(v) for v in line.groups()[3:]] == pytest.approx([35, 12.041], abs=1e-3)


def test_plan_under_mpirun(tmp_path: Path):
    """Under mpirun the map's rows are farmed out and rank 0 alone plans, verifies and writes; a
    bad target is reported once, with exit code 2."""
    if not shutil.which("mpirun"):
        pytest.skip("mpirun not installed")
    out = tmp_path / "plan.h5"
    result = mpirun(BINARY, 2, "plan", JIB_TARGET, "-o", out, cwd=tmp_path)
    if "built without MPI" in result.stderr:
        pytest.skip("crane-opt built without MPI")
    assert result.returncode == 0, result.stderr
    assert result.stderr.count("plan written to") == 1
    with h5py.File(out, "r") as f:
        assert f["verification"].attrs["status"] == "complete"
        assert f["map"].attrs["execution"].startswith("2 MPI ranks")
    serial_map = tmp_path / "serial.h5"
    serial = crane_opt("map", JIB_TARGET, "-o", serial_map, "--threads", "1", "--quiet", cwd=tmp_path)
    assert serial.returncode == 0, serial.stderr
    for key, values in map_datasets(serial_map).items():
        assert map_datasets(out)[key].tobytes() == values.tobytes(), key

    bad = BAD_TARGETS[0]
    expect, _ = expectations(bad)
    result = mpirun(BINARY, 2, "plan", bad, "-o", tmp_path / "bad.h5", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.count(expect) == 1, result.stderr
    assert not (tmp_path / "bad.h5").exists()


def plan_condensed_crane(tmp_path: Path, target: tuple, method: str = "quasi_static", base: Path = CRANE_TARGET,
                         feedback: bool = False) -> Path:
    """Table 8-2's problem (configs/target.yaml, or another target file of the thesis crane) on the
    condensed crane with another target and method, planned and verified by crane-opt (exit 0
    asserted), its feedback cases run only when `feedback`; returns the plan file."""
    text = base.read_text(encoding="utf-8")
    if not feedback:
        text = text.split("\nfeedback:")[0] + "\n"
    text = text.replace("scene: crane.yaml", f"scene: {SOURCE_DIR / 'configs' / 'crane_condensed.yaml'}", 1)
    text = text.replace("target: [-35, 10, 0, 0]", f"target: [{target[0]}, {target[1]}, 0, 0]", 1)
    text = text.replace("method: flatness\n", f"method: {method}\n", 1)
    assert str(target[0]) in text and "crane_condensed" in text and f"method: {method}" in text
    path = tmp_path / "target.yaml"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / "plan.h5"
    result = crane_opt("plan", path, "-o", out, "--quiet", cwd=tmp_path, timeout=600)
    assert result.returncode == 0, result.stderr
    return out


@pytest.mark.parametrize("target", [(-15, 5), (-20, 10), (-25, 5), (-30, 5), (-30, 15), (-35, 10)],
                         ids=lambda t: f"x{t[0]}_z{t[1]}")
def test_plan_reaches_targets_across_the_map(target: tuple, tmp_path: Path):
    """Table 8-2's problem on the condensed crane with targets spread over the mapped region.
    The four inner ones ended at the inversion with exit 1 when the inversion solved its own
    bordered system from the nearest map point; with the statics of crane-sim they plan."""
    with h5py.File(plan_condensed_crane(tmp_path, target), "r") as f:
        assert np.allclose(f["trajectory/state"][-1][:2], target, atol=0.02)
        assert np.max(f["inversion/error"][...]) < 1e-4
        v = f["verification"]
        assert v.attrs["status"] == "complete"
        # The quasi-static plan leaves the load swaying (±0.4…3.4 m) about a mean
        # that ends within a metre of the target.
        assert v.attrs["final_error"] < 1.0


def test_zvd_leaves_table_8_2_within_five_centimetres(tmp_path: Path):
    """Table 8-2 on the condensed crane shaped by ZVD for the crane's sway period: the mode found
    at the start is the in-plane sway of `crane-sim modes` at the thesis' controls (15.50 s; across
    the plane 16.85 s, the simple pendulum to the hook 14.78 s). The load ends within the
    industry's ±5 cm (measured ±0.020 m) where the quasi-static plan leaves ±1.48 m."""
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "zvd"), "r") as f:
        assert f["path"].attrs["sway_period_start"] == pytest.approx(15.50, abs=0.05)
        assert f["path"].attrs["motion_time"] == pytest.approx(40 + f["path"].attrs["sway_period"], abs=0.1)
        assert f["verification"].attrs["residual_sway"] < 0.05
        assert f["verification"].attrs["final_error"] < 0.05


def test_flatness_leaves_table_8_2_within_five_centimetres_in_the_same_time(tmp_path: Path):
    """configs/target.yaml's method: the load's rest-to-rest path carried by the flat map arrives
    within the industry's ±5 cm (measured ±0.019 m on the condensed crane, ±0.019 m on the thesis'
    super truss crane) in the quasi-static plan's 40 s; the verification runs at the target's own
    tolerances (rtol 1e-6, atol 1e-7), not the scene's 1e-5, at which IDAS failed its error test
    on 79 % of these steps (measured: 3929 failures in 5000 steps, 15 s; now 52 in 3806, 1.0 s).
    With the step growth bounded at 1.5 (the default since): 13 failures in 4145 steps, 0.68 s
    (rtol 1e-5: 194 in 4916)."""
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "flatness"), "r") as f:
        assert f["path"].attrs["motion_time"] == pytest.approx(40.0)
        v = f["verification"].attrs
        assert v["residual_sway"] < 0.05 and v["final_error"] < 0.01 and v["max_error"] < 0.1
        assert v["arrival_sway"] < 0.05  # within 10 s after the planned arrival, before the settle time
    with h5py.File(tmp_path / "plan_simulation.h5", "r") as run:
        solver = run["solver"].attrs
        assert solver["rtol"] == 1e-6 and solver["atol"] == 1e-7
        assert solver["error_test_failures"] < 0.1 * solver["steps"]


def test_slewing_plan_turns_the_crane_and_leaves_the_load_still(tmp_path: Path):
    """configs/target_slewing.yaml on the condensed crane: Table 8-2's luffing and hoisting with 45°
    of slewing, by flatness. The slewing drive follows a third control spline from 0 to 45°; the
    load arrives at Table 8-2's target turned by 45° about the slewing axis (x = y = −35 m·cos 45°
    + …) and sways ±0.022 m there (measured; ±0.021 m on the super truss crane). Without the
    across-plane pendulum (the boom head's sideways give: 17.0 s against 15.5 s along) it swayed
    ±0.41 m. Quasi-static: ±1.44 m."""
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "flatness", SLEWING_TARGET), "r") as f:
        path = f["path"].attrs
        assert path["slewing_constraint"] == "slewing" and path["slewing_turn_deg"] == 45.0
        assert path["sway_period_across_start"] > 1.05 * path["sway_period_start"]
        angles = f["controls/slewing_angle"][...]
        assert angles[0] == pytest.approx(0.0, abs=1e-12) and angles[-1] == pytest.approx(45.0, abs=1e-9)
        spline = f["controls/spline/slewing_angle/y"][...]
        assert spline[0] == pytest.approx(0.0, abs=1e-12) and spline[-1] == pytest.approx(np.pi / 4, abs=1e-12)
        v = f["verification"]
        assert v.attrs["status"] == "complete"
        assert v.attrs["residual_sway"] < 0.05 and v.attrs["final_error"] < 0.01 and v.attrs["arrival_sway"] < 0.05
        planned, simulated = v["planned"][...], v["simulated"][...]
        # The planned target: Table 8-2's end point in the crane's plane (x = −35 m, y = the hook's
        # y at the start, a millimetre off 0), turned by 45° about the slewing axis (the origin).
        x_target, y_plane = f["trajectory/origin"][0] + f["trajectory/target"][0, 0], planned[0, 1]
        assert abs(y_plane) < 0.01
        turn = np.array([[np.cos(np.pi / 4), -np.sin(np.pi / 4)], [np.sin(np.pi / 4), np.cos(np.pi / 4)]])
        assert planned[-1, :2] == pytest.approx(turn @ [x_target, y_plane], abs=1e-9)
        assert np.linalg.norm(simulated[-1] - planned[-1]) < 0.05


def feedback_runs(plan: Path) -> dict:
    """The plan's feedback table: {(case, "open" | "closed"): {quantity: value}}."""
    with h5py.File(plan, "r") as f:
        g = f["feedback"]
        names = [n.decode() if isinstance(n, bytes) else n for n in g["case"][...]]
        loops = [n.decode() if isinstance(n, bytes) else n for n in g["loop"][...]]
        quantities = ("sway_at_arrival", "sway_after_5_s", "settling_time", "dynamic_factor")
        runs = {(name, loop): {q: float(g[q][k]) for q in quantities} for k, (name, loop) in enumerate(zip(names, loops))}
        for k, key in enumerate(zip(names, loops)):
            runs[key]["drive_peaks"] = g["drive_peaks"][k]
            runs[key]["controller_s"] = float(g["controller_s_per_sample"][k])
            runs[key]["drive_energy"] = g["drive_energy"][k]
        return runs


@pytest.mark.parametrize("base", [CRANE_TARGET, SLEWING_TARGET], ids=["table_8_2", "slewing"])
def test_feedback_brings_the_plan_to_rest_on_cranes_that_differ_from_it(base: Path, tmp_path: Path):
    """The shipped targets' feedback cases on the condensed crane: the load 20 % heavier or
    lighter than planned, the hoist rope 5 % longer or shorter than its encoder says, the load
    let go 0.5 m out of plumb (seen by an exact sensor, and by one 0.1 s late with noise), a
    50 kN gust across the boom, a 3 s gust of wind to 9.8 m/s on the load, the ropes and the
    lattice. Tracked by the anti-sway feedback, every case is within 5 cm of plumb from 5 s
    after the planned arrival (measured 1.5–3.2 cm); open loop the initial sway and the gusts
    leave 0.16–0.41 m, and the feedback takes away more than 80 % of them (90–95 %). The drives
    stay within what the speed inputs allow, and the controller costs far less than a
    millisecond per 20 ms sample."""
    runs = feedback_runs(plan_condensed_crane(tmp_path, (-35, 10), "flatness", base, feedback=True))
    cases = {name for name, _ in runs}
    disturbed = ("initial sway 0.5 m", "gust 50 kN", "gust to 9.8 m/s", "sensor 0.1 s late, noisy")
    assert cases == {"load +20 %", "load -20 %", "rope +5 %", "rope -5 %", *disturbed}
    for name in cases:
        closed, open_loop = runs[(name, "closed")], runs[(name, "open")]
        assert closed["sway_after_5_s"] < 0.05, name
        assert closed["settling_time"] <= 5.0, name
        assert closed["controller_s"] < 1e-3, name
        assert 1.0 <= closed["dynamic_factor"] < 1.1, name
        # The drives lift the load 10 m (and more of the hoist rope as the boom luffs down): more
        # work than the load's potential gain, and the feedback adds at most a few tenths of a
        # percent to it (80.27 against 80.56 MJ with the initial sway).
        work = closed["drive_energy"].sum()
        assert work > 0.8 * 390e3 * 9.81 * 10.0, name  # the lightest case's load lifted 10 m
        assert work == pytest.approx(open_loop["drive_energy"].sum(), rel=0.01), name
    for name in disturbed:
        assert runs[(name, "open")]["sway_after_5_s"] > 0.1, name
        assert runs[(name, "closed")]["sway_after_5_s"] < 0.2 * runs[(name, "open")]["sway_after_5_s"], name


REEVED_TARGET = SOURCE_DIR / "configs" / "target_reeved.yaml"


def test_feedback_tracks_the_plan_on_the_reeved_crane(tmp_path: Path):
    """configs/target_reeved.yaml: Table 8-2 by flatness on the reeved thesis crane (hoist 8 falls,
    luffing 12 parts, condensed sections). The plan reels 8 m of the hoist winch's rope for every
    metre the hook block rises, and the load arrives still; its feedback cases run on the reeved
    ropes (their part tensions and winches' powers read step by step): tracked, every case is
    within 5 cm of plumb from 5 s after the arrival, and the feedback takes away most of the
    initial sway and the gust's. The dynamic factor is the most loaded part's: the lead line's
    pull hoisting includes the eight sheaves' losses, 8 (1 − η) / (η (1 − η⁸)) = 1.094."""
    out = tmp_path / "plan.h5"
    result = crane_opt("plan", REEVED_TARGET, "-o", out, "--quiet", cwd=tmp_path, timeout=900)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f, h5py.File(tmp_path / "plan_simulation.h5", "r") as run:
        hoist = f["controls/hoist_length"][...]
        v = f["verification"].attrs
        assert v["status"] == "complete"
        assert v["residual_sway"] < 0.05 and v["final_error"] < 0.05  # measured ±0.030 m and 0.025 m
        # The winch's rope, stretched by ε as at the start, is the lead line and 8 falls: reeling
        # it in lifts the hook block by 1/8 of it, less what the lead line gains as the boom luffs.
        winch, sheave, block = (run[f"joints/{j}/position"][...] for j in ("pedestal.hoist_winch", "head.sheave_1",
                                                                         "hook_block.sheave_1"))
        lead, fall = np.linalg.norm(sheave - winch, axis=1), np.linalg.norm(block - sheave, axis=1)
        strain = run["ropes/hoist_rope/part_tension"][0, 0] / (1.0e11 * np.pi * 0.016**2)
        reeled = (hoist[0] - hoist[-1]) * (1.0 + strain) + lead[-1] - lead[0]
        assert reeled / (fall[0] - fall[-1]) == pytest.approx(8.0, rel=1e-3)  # measured 8.0012
    runs = feedback_runs(out)
    disturbed = ("initial sway 0.5 m", "gust 50 kN")
    assert {name for name, _ in runs} == {"load +20 %", "load -20 %", "rope +5 %", "rope -5 %", *disturbed}
    sheaves = 8 * 0.02 / (0.98 * (1 - 0.98**8))
    for (name, loop), run in runs.items():
        if loop == "closed":
            assert run["sway_after_5_s"] < 0.05, name
            assert sheaves < run["dynamic_factor"] < 1.1 * sheaves, name
        work = run["drive_energy"].sum()
        assert work > 0.8 * 390e3 * 9.8 * 10.0, name  # the lightest case's load lifted 10 m
    for name in disturbed:
        assert runs[(name, "open")]["sway_after_5_s"] > 0.1, name
        assert runs[(name, "closed")]["sway_after_5_s"] < 0.3 * runs[(name, "open")]["sway_after_5_s"], name


def test_flatness_stretches_its_path_to_keep_the_drive_limits(tmp_path: Path):
    """Table 8-2 by flatness asks the hoist winch for 0.95 m/s; limited to 0.8 m/s and 0.1 m/s²
    (and the luffing winch to 0.5 m/s), the path is stretched (measured: 40 → 55.6 s) until the
    control splines keep every limit, and the load still arrives still (±1.2 mm). The
    quasi-static plan keeps its QR path and reports the excess (factor 1.65: the hoist's 1.32 m/s).
    The feedback that tracks the stretched plan commands the drives within the same limits along
    every run (measured: hoist 0.7997 m/s and 0.067 m/s², luffing 0.393 m/s), and still brings a
    0.5 m initial swing and a gust's to rest within 5 cm (measured 1.3 and 2.1 cm)."""
    limits = "drive_limits:\n  hoist: {speed: 0.8, acceleration: 0.1}\n  luffing: {speed: 0.5}\n"
    text = CRANE_TARGET.read_text(encoding="utf-8").replace("\nfeedback:", "\n" + limits + "feedback:", 1)
    assert limits in text
    limited = tmp_path / "limited.yaml"
    limited.write_text(text, encoding="utf-8")
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "flatness", limited, feedback=True), "r") as f:
        path, controls = f["path"].attrs, f["controls"].attrs
        assert path["stretched_from"] == pytest.approx(40.0)
        assert 45.0 < path["motion_time"] < 70.0
        assert controls["hoist_peak_speed"] <= 0.8 * (1 + 1e-9) and controls["hoist_peak_acceleration"] <= 0.1 * (1 + 1e-9)
        assert controls["luffing_peak_speed"] <= 0.5 * (1 + 1e-9)
        assert 0.99 < controls["drive_limit_factor"] <= 1.0  # the shortest duration that keeps them, to 0.1 %
        # The spline's peak speed, checked on its knots' own Hermite cubic at fine steps.
        spline = f["controls/spline/hoist_length"]
        knots, y, slopes = spline["t"][...], spline["y"][...], spline["slopes"][...]
        dense = np.linspace(knots[0], knots[-1], 20001)
        rate = np.gradient(hermite(dense, knots, y, slopes), dense)
        assert np.max(np.abs(rate)) == pytest.approx(controls["hoist_peak_speed"], rel=1e-3)
        assert f["verification"].attrs["residual_sway"] < 0.05
    runs = feedback_runs(tmp_path / "plan.h5")
    for (name, loop), run in runs.items():
        if loop == "closed":
            (luffing_speed, _), (hoist_speed, hoist_acceleration), _ = run["drive_peaks"]
            assert hoist_speed <= 0.8 * (1 + 1e-9) and hoist_acceleration <= 0.1 * (1 + 1e-9), name
            assert luffing_speed <= 0.5 * (1 + 1e-9), name
            assert run["sway_after_5_s"] < 0.05, name
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "quasi_static", limited), "r") as f:
        assert f["path"].attrs["motion_time"] == pytest.approx(40.0) and "stretched_from" not in f["path"].attrs
        assert f["controls"].attrs["drive_limit_factor"] == pytest.approx(1.32 / 0.8, rel=0.01)


MINIMUM_TIME_TARGET = SOURCE_DIR / "configs" / "target_minimum_time.yaml"


def test_minimum_time_lift_beats_the_stretched_flatness_plan(tmp_path: Path):
    """configs/target_minimum_time.yaml on the condensed crane: within the same drive limits that
    stretch the flatness path to 55.6 s, the minimum-time lift takes 36.5 s (measured; ≥ 25 %
    shorter asked), keeps every limit on its control splines (factor 0.996) and leaves the load
    within 5 cm of the target in the 5 s after its arrival (measured 3.5 cm) and after (3.6 cm)."""
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "minimum_time", MINIMUM_TIME_TARGET), "r") as f:
        path, controls, v = f["path"].attrs, f["controls"].attrs, f["verification"]
        assert path["method"] == "minimum_time"
        assert path["flatness_duration"] == pytest.approx(55.6, abs=0.1)
        assert path["motion_time"] <= 0.75 * path["flatness_duration"]
        assert controls["drive_limit_factor"] <= 1.0
        assert controls["hoist_peak_speed"] <= 0.8 and controls["hoist_peak_acceleration"] <= 0.1
        assert controls["luffing_peak_speed"] <= 0.5
        state = f["path/state"][()]
        assert np.allclose(state[0, :2], f["trajectory/start"][0, :2], atol=1e-6)
        assert np.allclose(state[-1, :2], f["trajectory/target"][0, :2], atol=1e-6)
        arrival = controls["lead_time"] + path["motion_time"]
        t, simulated, goal = v["t"][()], v["simulated"][()], v["planned"][-1]
        off = np.linalg.norm((simulated - goal)[:, :2], axis=1)
        assert np.max(off[(t >= arrival) & (t <= arrival + 5)]) < 0.05
        assert np.max(off[t >= arrival + 5]) < 0.05
        assert path["nlp_time_s"] < 5.0


def test_minimum_time_lift_keeps_the_luffing_rope_s_jerk_limit(tmp_path: Path):
    """Table 8-2's minimum-time lift with the luffing rope's jerk limited to 0.01 m/s³: the NLP
    bounds the rope's third time derivative through the map at every node, and the verified
    control spline's exact peak keeps the limit. Measured: 38.35 s instead of 36.51 s (the limit
    binds), peak 0.0100 m/s³, ±2.7 cm after the arrival."""
    text = MINIMUM_TIME_TARGET.read_text(encoding="utf-8")
    limited = tmp_path / "limited.yaml"
    limited.write_text(text.replace("luffing: {speed: 0.5}", "luffing: {speed: 0.5, jerk: 0.01}", 1), encoding="utf-8")
    assert "jerk: 0.01" in limited.read_text(encoding="utf-8")
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "minimum_time", limited), "r") as f:
        path, controls, v = f["path"].attrs, f["controls"].attrs, f["verification"].attrs
        assert controls["luffing_peak_jerk"] <= 0.01
        assert controls["drive_limit_factor"] <= 1.0
        assert 36.6 < path["motion_time"] <= 0.75 * path["flatness_duration"]
        assert v["residual_sway"] < 0.05


def test_minimum_time_lift_slews_within_the_slewing_drive_s_limits(tmp_path: Path):
    """configs/target_slewing.yaml by minimum_time on the condensed crane, the slewing drive
    limited to 1.5°/s and 0.1°/s² besides the ropes: the load sways across the turning plane, so
    the NLP's second swing angle is in play. Measured: 47.3 s against flatness' 60.5 s, every limit
    kept, ±1.7 cm after the arrival, the verified load within 4.5 cm of the planned one."""
    limits = ("drive_limits:\n  hoist: {speed: 0.8, acceleration: 0.1}\n  luffing: {speed: 0.5}\n"
              "  slewing: {speed: 1.5, acceleration: 0.1}\n")
    text = SLEWING_TARGET.read_text(encoding="utf-8").replace("method: flatness\n", "method: minimum_time\n" + limits, 1)
    assert limits in text
    limited = tmp_path / "limited.yaml"
    limited.write_text(text, encoding="utf-8")
    with h5py.File(plan_condensed_crane(tmp_path, (-35, 10), "minimum_time", limited), "r") as f:
        path, controls, v = f["path"].attrs, f["controls"].attrs, f["verification"].attrs
        assert path["motion_time"] <= 0.85 * path["flatness_duration"]
        assert controls["drive_limit_factor"] <= 1.0
        assert controls["slewing_peak_speed"] <= np.radians(1.5) and controls["slewing_peak_acceleration"] <= np.radians(0.1)
        assert f["controls/spline/slewing_angle/y"][-1] == pytest.approx(np.pi / 4, abs=1e-9)
        assert v["arrival_sway"] < 0.05 and v["residual_sway"] < 0.05 and v["max_error"] < 0.1


def hermite(t_query, t, y, slopes):
    """The cubic Hermite spline through (t, y, slopes), as crane-sim evaluates a table."""
    i = np.clip(np.searchsorted(t, t_query, side="right") - 1, 0, len(t) - 2)
    h = t[i + 1] - t[i]
    s = (t_query - t[i]) / h
    return ((2 * s**3 - 3 * s**2 + 1) * y[i] + (s**3 - 2 * s**2 + s) * h * slopes[i] + (-2 * s**3 + 3 * s**2) * y[i + 1]
            + (s**3 - s**2) * h * slopes[i + 1])


WALL_TARGET = SOURCE_DIR / "configs" / "target_wall.yaml"
BUILDING_TARGET = SOURCE_DIR / "configs" / "target_building.yaml"


def plan_jib_with_obstacles(tmp_path: Path, obstacles: str) -> tuple[subprocess.CompletedProcess, Path]:
    """The luffing jib's plan (the load from x = −10, z = 7.5 to x = −14, z = 10) with obstacles."""
    target = tmp_path / "target.yaml"
    text = JIB_TARGET.read_text(encoding="utf-8").replace("scene: luffing_jib.yaml", f"scene: {JIB_TARGET.parent / 'luffing_jib.yaml'}")
    target.write_text(text + obstacles, encoding="utf-8")
    out = tmp_path / "plan.h5"
    return crane_opt("plan", target, "-o", out, "--quiet", cwd=tmp_path), out


def box_distance(points: np.ndarray, centre, size) -> np.ndarray:
    """Signed distance of points [n, 3] from an axis-aligned box (negative inside)."""
    q = np.abs(points - np.asarray(centre)) - 0.5 * np.asarray(size)
    return np.linalg.norm(np.maximum(q, 0.0), axis=1) + np.minimum(q.max(axis=1), 0.0)


def test_jib_passes_over_a_low_wall_with_its_clearance_reported(tmp_path: Path):
    """A 5 m wall between pick (x = −10) and set (x = −14): the load, a 1 m sphere about the hook,
    passes over it. The load's clearance in /clearance is the box distance of the simulated hook
    recomputed here, less the radius; the stdout line names the closest part."""
    wall = {"centre": [-12, 0, 2.5], "size": [0.4, 10, 5]}
    result, out = plan_jib_with_obstacles(
        tmp_path, f"obstacles:\n  - {{name: wall, shape: box, centre: {wall['centre']}, size: {wall['size']}}}\n"
                  "clearance_margin: 0.5\n")
    assert result.returncode == 0, result.stderr
    line = re.fullmatch(r"minimum clearance (\d+\.\d\d) m: (\w+) to wall at t = (\d+\.\d) s\n", result.stdout)
    assert line, result.stdout
    with h5py.File(out, "r") as f:
        c = f["clearance"]
        assert c.attrs["status"] == "clear" and c.attrs["margin"] == 0.5
        parts = list(c["part"].asstr()[...])
        assert parts == ["luffing_rope", "hoist_rope", "load"] and list(c["obstacle"].asstr()[...]) == ["wall"]
        minimum, time = c["minimum"][...], c["time"][...]
        assert c.attrs["distance"] == minimum.min() and c.attrs["closest_part"] == line[2]
        assert float(line[1]) == pytest.approx(minimum.min(), abs=0.005)
        hook = f["verification/simulated"][...]
        load = box_distance(hook, **wall) - 1.0
        assert minimum[0, parts.index("load")] == pytest.approx(load.min(), abs=1e-9)
        assert time[0, parts.index("load")] == f["verification/t"][int(np.argmin(load))]
        assert 1.0 < load.min() < 4.0  # the hook crosses x = −12 about 8.7 m up
        assert c.attrs["samples"] == len(hook) and c.attrs["largest_interval"] <= 0.05 + 1e-9


def test_a_wall_too_high_fails_the_verified_plan(tmp_path: Path):
    """A 12 m wall across the jib's path: the straight path cannot go over it, the verified motion
    runs into it. Exit 3 naming the part, the wall, the time and the depth; the plan is written and
    its /clearance marked failed."""
    result, out = plan_jib_with_obstacles(
        tmp_path, "obstacles:\n  - {name: wall, shape: box, centre: [-12, 0, 6], size: [0.4, 10, 12]}\n")
    assert result.returncode == 3, result.stderr
    failure = re.search(r"error: the verified motion comes closer than the clearance margin 0.5 m: (\w+) is (-[\d.]+) m "
                        r"from obstacle 'wall' at t = ([\d.]+) s", result.stderr)
    assert failure, result.stderr
    with h5py.File(out, "r") as f:
        c = f["clearance"].attrs
        assert c["status"] == "failed" and c["closest_obstacle"] == "wall" and c["closest_part"] == failure[1]
        assert c["distance"] == pytest.approx(float(failure[2]), rel=1e-2) and c["distance"] < -0.1
        assert f["verification"].attrs["status"] == "complete"


@pytest.mark.parametrize("target", [WALL_TARGET, BUILDING_TARGET], ids=["wall", "building"])
def test_shipped_obstacle_targets_plan_clear(target: Path, tmp_path: Path):
    """The shipped targets with obstacles plan and verify clear of them, by more than the margin."""
    out = tmp_path / "plan.h5"
    result = crane_opt("plan", target, "-o", out, "--quiet", cwd=tmp_path, timeout=600)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("minimum clearance ")
    with h5py.File(out, "r") as f:
        c = f["clearance"].attrs
        assert c["status"] == "clear" and c["distance"] > c["margin"]


WALL_MINIMUM_TIME = SOURCE_DIR / "configs" / "target_wall_minimum_time.yaml"
BUILDING_MINIMUM_TIME = SOURCE_DIR / "configs" / "target_building_minimum_time.yaml"


def without_obstacles(target: Path, tmp_path: Path) -> Path:
    """The target with its obstacles taken out (its last keys: obstacles, margin, load radius)."""
    text = target.read_text(encoding="utf-8")
    text = text[:text.index("\nobstacles:")].replace("scene: crane_condensed.yaml", f"scene: {target.parent / 'crane_condensed.yaml'}")
    free = tmp_path / "free.yaml"
    free.write_text(text + "\n", encoding="utf-8")
    return free


@pytest.mark.parametrize(("target", "closest"), [(WALL_MINIMUM_TIME, "load"), (BUILDING_MINIMUM_TIME, "boom")],
                         ids=["wall", "building"])
def test_minimum_time_lift_goes_over_and_around_the_shipped_obstacles(target: Path, closest: str, tmp_path: Path):
    """The shipped minimum-time targets with obstacles: the lift without them runs the load into
    the obstacle; with them the verified flexible crane clears it by the margin, every part, and
    takes longer, the load within 5 cm of the target from its arrival. Measured (condensed crane):
    the wall 40.5 s against 38.5 s, 0.69 m (the load), ±2.0 cm from the arrival; the building
    58.4 s against 49.3 s, 0.66 m (the boom passing its corner), ±4.8 cm."""
    free = tmp_path / "free.h5"
    result = crane_opt("plan", without_obstacles(target, tmp_path), "-o", free, "--quiet", cwd=tmp_path, timeout=600)
    assert result.returncode == 0, result.stderr
    obstacle = yaml.safe_load(target.read_text(encoding="utf-8"))["obstacles"][0]
    with h5py.File(free, "r") as f:
        free_motion = f["path"].attrs["motion_time"]
        load = f["verification/simulated"][...]
    yaw = np.radians(obstacle.get("yaw", 0.0))
    turn = np.array([[np.cos(yaw), np.sin(yaw), 0], [-np.sin(yaw), np.cos(yaw), 0], [0, 0, 1]])
    local = (load - obstacle["centre"]) @ turn.T + obstacle["centre"]
    assert np.min(box_distance(local, obstacle["centre"], obstacle["size"])) - 2.0 < 0.0  # the 2 m load runs into it

    out = tmp_path / "plan.h5"
    result = crane_opt("plan", target, "-o", out, "--quiet", cwd=tmp_path, timeout=600)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        c, path = f["clearance"].attrs, f["path"].attrs
        assert c["status"] == "clear" and c["distance"] >= c["margin"] == 0.5
        assert c["closest_part"].startswith(closest)
        assert np.all(f["clearance/minimum"][...] >= 0.5)  # every part
        assert free_motion < path["motion_time"] < 1.3 * free_motion
        arrival = f["controls"].attrs["lead_time"] + path["motion_time"]
        t, simulated, goal = f["verification/t"][()], f["verification/simulated"][()], f["verification/planned"][-1]
        assert np.max(np.linalg.norm((simulated - goal)[t >= arrival, :2], axis=1)) < 0.05
        assert path["nlp_time_s"] < 30.0  # measured 1.7–8 s; the machine is shared
