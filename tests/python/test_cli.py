"""Command-line behaviour of crane-sim: input validation, exit codes and the results file.

Exit codes: 0 success, 1 solver failure (results kept, marked incomplete), 2 bad input.

Every tests/data/bad_scenes/*.yaml is a near-copy of a valid scene with one defect. Its first two
lines say what the error must contain and which YAML path it must name:

    # expect: <substring of the error message>
    # path: <YAML path the error is reported at, e.g. bodies[0].mass or <document>>

Environment: CRANESIM_BIN (default <repo>/build/crane-sim) and CRANESIM_SOURCE_DIR
(default: two levels up from this file).
"""

import math
import os
import re
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

from bad_input import EXIT_BAD_INPUT, assert_collection, assert_reported, expectations

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()
BAD_SCENES = sorted((SOURCE_DIR / "tests" / "data" / "bad_scenes").glob("*.yaml"))
PENDULUM = SOURCE_DIR / "configs" / "pendulum.yaml"

EXIT_SOLVER_FAILURE = 1

# A slider on a rail along x, held by a rope from an anchor 1 m above the rail whose length is
# wound in at 1 m/s from 1.1 m. At t = 0.1 s the rope is vertical; after that no position of the
# slider satisfies both constraints, so the integration must stop there: a solver failure that
# no solver improvement can remove.
LOCKUP_SCENE = """\
name: slider pulled off its rail
gravity: [0, 0, -9.81]
ground:
  joints:
    - {name: rail, position: [0, 0, 0]}
    - {name: anchor, position: [0, 0, 1]}
bodies:
  - name: slider
    mass: 1.0
    inertia: [0.01, 0.01, 0.01]
    position: [0.45825756949558405, 0, 0]   # sqrt(1.1² - 1)
constraints:
  - name: rail
    type: prismatic
    joints: [ground.rail, slider.origin]
    axis: x
  - name: rope
    type: distance
    joints: [ground.anchor, slider.origin]
    length: {type: ramp, value: 1.1, rate: -1}
solver:
  formulation: ggl
  t_end: 1
  rtol: 1.0e-6
  atol: 1.0e-8
  newton_coefficient: 0.05
output:
  interval: 0.01
"""
LOCKUP_TIME = 0.1


@pytest.fixture(scope="session", autouse=True)
def binary() -> Path:
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    return BINARY


def crane_sim(*arguments, cwd: Path, timeout: float = 30) -> subprocess.CompletedProcess:
    return subprocess.run([str(BINARY), *map(str, arguments)], capture_output=True, text=True,
                          cwd=cwd, timeout=timeout)


def results_attributes(path: Path) -> dict:
    with h5py.File(path, "r") as f:
        return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}


def test_bad_scene_collection_is_complete():
    assert_collection(BAD_SCENES, 14)


@pytest.mark.parametrize("scene", BAD_SCENES, ids=[s.stem for s in BAD_SCENES])
def test_bad_scene_is_rejected(scene: Path, tmp_path: Path):
    expect, path = expectations(scene)
    out = tmp_path / "out.h5"

    result = crane_sim("run", scene, "-o", out, "--quiet", cwd=tmp_path)
    assert_reported(result, scene, expect, path)
    assert not out.exists()
    assert not Path(f"{out}.partial").exists()
    assert list(tmp_path.iterdir()) == []

    result = crane_sim("check", scene, cwd=tmp_path)
    assert_reported(result, scene, expect, path)
    assert list(tmp_path.iterdir()) == []


def test_bad_scene_writes_no_default_output(tmp_path: Path):
    scene = SOURCE_DIR / "tests" / "data" / "bad_scenes" / "negative_mass.yaml"
    result = crane_sim("run", scene, cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert list(tmp_path.iterdir()) == []


def test_check_valid_scene(tmp_path: Path):
    result = crane_sim("check", PENDULUM, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "degrees of freedom: 1" in result.stdout
    assert "initial state: consistent" in result.stdout
    assert list(tmp_path.iterdir()) == []


@pytest.fixture(scope="module")
def short_pendulum(tmp_path_factory) -> Path:
    """configs/pendulum.yaml cut to 0.5 s."""
    text, count = re.subn(r"^(\s+t_end:).*$", r"\1 0.5", PENDULUM.read_text(encoding="utf-8"),
                          flags=re.MULTILINE)
    assert count == 1
    scene = tmp_path_factory.mktemp("pendulum") / "pendulum.yaml"
    scene.write_text(text, encoding="utf-8")
    return scene


def test_run_writes_complete_results(short_pendulum: Path, tmp_path: Path):
    out = tmp_path / "pendulum.h5"
    result = crane_sim("run", short_pendulum, "-o", out, "--quiet", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert out.is_file()
    assert not Path(f"{out}.partial").exists()
    attributes = results_attributes(out)
    assert attributes["status"] == "complete"
    assert attributes["message"] == ""
    assert attributes["t_reached"] == pytest.approx(0.5)
    with h5py.File(out, "r") as f:
        assert f["time"][0] == 0.0 and f["time"][-1] == pytest.approx(0.5)

    info = crane_sim("info", out, cwd=tmp_path)
    assert info.returncode == 0, info.stderr
    assert re.search(r"^\s+/time\s", info.stdout, re.MULTILINE), info.stdout


def test_info_shows_string_attributes(short_pendulum: Path, tmp_path: Path):
    out = tmp_path / "pendulum.h5"
    assert crane_sim("run", short_pendulum, "-o", out, "--quiet", cwd=tmp_path).returncode == 0
    info = crane_sim("info", out, cwd=tmp_path)
    assert info.returncode == 0, info.stderr
    assert re.search(r"^\s+status\s+complete$", info.stdout, re.MULTILINE), info.stdout


def test_run_default_output_is_named_after_the_scene(short_pendulum: Path, tmp_path: Path):
    result = crane_sim("run", short_pendulum, "--quiet", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pendulum.h5"]


def test_info_missing_file(tmp_path: Path):
    result = crane_sim("info", tmp_path / "missing.h5", cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert "does not exist" in result.stderr


def test_info_not_hdf5(tmp_path: Path):
    text = tmp_path / "notes.h5"
    text.write_text("this is not an HDF5 file\n", encoding="utf-8")
    result = crane_sim("info", text, cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert "not an HDF5 file" in result.stderr


def test_info_foreign_hdf5(tmp_path: Path):
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as f:
        f["x"] = [1, 2, 3]
    result = crane_sim("info", foreign, cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert "not one cranesim wrote" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("command", ["run", "check"])
def test_missing_scene(command: str, tmp_path: Path):
    scene = tmp_path / "no_such_scene.yaml"
    result = crane_sim(command, scene, cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert str(scene) in result.stderr and "cannot open the scene file" in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_solver_failure_keeps_incomplete_results(tmp_path: Path):
    scene = tmp_path / "lockup.yaml"
    scene.write_text(LOCKUP_SCENE, encoding="utf-8")
    out = tmp_path / "lockup.h5"

    check = crane_sim("check", scene, cwd=tmp_path)
    assert check.returncode == 0, check.stderr

    try:
        result = crane_sim("run", scene, "-o", out, "--quiet", cwd=tmp_path, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("the solver did not stop at the lock-up within 60 s (stalled at t = 0.1 s?)")
    assert result.returncode == EXIT_SOLVER_FAILURE, result.stderr
    assert "error: solver failure at t = " in result.stderr
    assert out.is_file()
    assert not Path(f"{out}.partial").exists()

    attributes = results_attributes(out)
    assert attributes["status"] == "incomplete"
    message = attributes["message"]
    assert message and message in result.stderr
    failed_at = re.search(r"\bt = ([-+0-9.eE]+) s", message)
    assert failed_at, message
    assert float(failed_at[1]) == pytest.approx(LOCKUP_TIME, abs=1e-3)
    assert attributes["t_reached"] == pytest.approx(LOCKUP_TIME, abs=1e-3)
    with h5py.File(out, "r") as f:
        time = f["time"][:]
    assert 0 < len(time) and time[-1] <= LOCKUP_TIME + 1e-9

    info = crane_sim("info", out, cwd=tmp_path)
    assert info.returncode == 0, info.stderr
    assert re.search(r"^\s+/time\s", info.stdout, re.MULTILINE), info.stdout


def test_modes_of_the_pendulum(tmp_path: Path):
    """configs/pendulum.yaml hanging (from its 90° start Newton may reach the upright equilibrium):
    a 1 m, 1 kg rod hinged at one end, f = √(g d / (I_c/m + d²)) / 2π."""
    text = PENDULUM.read_text(encoding="utf-8")
    text, n_position = re.subn(r"^(\s+position:) \[-0.5, 0, 0\]", r"\1 [0, 0, -0.5]", text, flags=re.MULTILINE)
    text, n_rotation = re.subn(r"angle_deg: 90\}", "angle_deg: 0}", text)
    assert n_position == 1 and n_rotation == 1
    scene = tmp_path / "hanging.yaml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "modes.h5"
    result = crane_sim("modes", scene, "--count", 3, "-o", out, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert out.is_file() and not Path(f"{out}.partial").exists()
    expected = math.sqrt(9.81 * 0.5 / (1 / 12 + 0.25)) / (2 * math.pi)
    assert "degrees of freedom: 1, rigid-body modes: 0," in result.stdout
    assert re.search(rf"^\s+1\s+{expected:.6f}\s+{1 / expected:.6g}\s", result.stdout, re.MULTILINE), result.stdout

    assert results_attributes(out)["analysis"] == "modes"
    with h5py.File(out, "r") as f:
        frequency = f["modes/frequency"][:]
        shapes = f["modes/shapes"][:]
        labels = [s.decode() for s in f["model/velocity_labels"][:]]
        assert f["equilibrium/q"].shape == (6,) and f["equilibrium/lambda"].shape == (5,)
        tip = [s.decode() for s in f["model/joints"][:]].index("rod.tip")
        tip_displacement = f["modes/joint_displacements"][0, tip]
    assert frequency == pytest.approx([expected], rel=1e-9)
    assert shapes.shape == (1, 6)
    assert labels == [f"rod.{c}" for c in ("r_x", "r_y", "r_z", "theta_x", "theta_y", "theta_z")]
    # Mass-normalised: a turn δθ about the hinge with I_pivot δθ² = 1, the tip moving along x.
    turn = 1 / math.sqrt(1 / 12 + 0.25)
    assert abs(shapes[0, labels.index("rod.theta_y")]) == pytest.approx(turn, rel=1e-9)
    assert abs(tip_displacement[0]) == pytest.approx(turn, rel=1e-9)
    assert tip_displacement[1:] == pytest.approx([0, 0], abs=1e-9)

    info = crane_sim("info", out, cwd=tmp_path)
    assert info.returncode == 0, info.stderr
    assert re.search(r"^\s+/modes/frequency\s", info.stdout, re.MULTILINE), info.stdout


@pytest.mark.parametrize("arguments", [["--count", "-1"], ["--count", "many"]])
def test_modes_rejects_bad_arguments(arguments: list, tmp_path: Path):
    result = crane_sim("modes", PENDULUM, *arguments, cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert list(tmp_path.iterdir()) == []


def test_modes_bad_scene_and_missing_equilibrium(tmp_path: Path):
    bad = SOURCE_DIR / "tests" / "data" / "bad_scenes" / "negative_mass.yaml"
    assert_reported(crane_sim("modes", bad, cwd=tmp_path), bad, *expectations(bad))
    # A body without supports falls: there is no equilibrium to vibrate about.
    falling = tmp_path / "falling.yaml"
    falling.write_text("name: falling body\ngravity: [0, 0, -9.81]\n"
                       "bodies:\n  - {name: box, mass: 1.0, inertia: [0.1, 0.1, 0.1]}\n"
                       "solver: {t_end: 1}\n", encoding="utf-8")
    result = crane_sim("modes", falling, cwd=tmp_path)
    assert result.returncode == EXIT_SOLVER_FAILURE, result.stderr
    assert "static equilibrium not found" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["falling.yaml"]


def test_static_reports_bodies_and_joint_forces(tmp_path: Path):
    """The pendulum hangs from its hinge: the hinge carries its weight m g = 9.81 N."""
    out = tmp_path / "static.h5"
    result = crane_sim("static", PENDULUM, "-o", out, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    rows = {line.split()[0]: line.split()[1:] for line in result.stdout.splitlines() if line.strip()}
    assert rows["body"] == ["x", "[m]", "y", "[m]", "z", "[m]"]
    assert float(rows["hinge"][0]) == pytest.approx(9.81, rel=1e-6)
    assert float(rows["rod"][2]) < 0.0  # hangs below the pivot
    assert out.is_file()


@pytest.mark.parametrize("slewing_deg", [0, 180])
def test_static_slews_the_crane_by_its_drive(slewing_deg: int, tmp_path: Path):
    """The slewing drive's value turns the whole crane: at 180° the load hangs on the other side
    (the old angle equation had a false root there and left the crane unturned)."""
    scene = tmp_path / "slewed.yaml"
    scene.write_text(f"base: {SOURCE_DIR / 'configs' / 'crane_condensed.yaml'}\nmodify:\n"
                     f"  members.luffing_rope.length: 7.0608\n  members.hoist_rope.length: 53.9937\n"
                     f"  constraints.slewing.drive: {{type: constant, value: {slewing_deg}, unit: deg}}\n",
                     encoding="utf-8")
    result = crane_sim("static", scene, "-o", tmp_path / "slewed.h5", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    load = [float(v) for v in next(line.split()[1:] for line in result.stdout.splitlines() if line.startswith("load "))]
    sign = 1 if slewing_deg == 180 else -1
    assert load[0] == pytest.approx(sign * 10.0434, abs=1e-3)
    assert "path steps" in result.stderr


def test_run_refuses_to_start_from_an_unstable_equilibrium(tmp_path: Path):
    """`initial_state: equilibrium` from the pendulum drawn 170° up: Newton's equilibrium is the
    inverted one; the run stops before integrating, exit 1, naming the instability."""
    scene = tmp_path / "upright.yaml"
    scene.write_text(f"base: {PENDULUM}\nmodify:\n"
                     "  bodies.rod.position: [-0.0868241, 0, 0.4924039]\n"
                     "  bodies.rod.rotation: {axis: [0, 1, 0], angle_deg: 170}\n"
                     "  solver.initial_state: equilibrium\n", encoding="utf-8")
    result = crane_sim("run", scene, "-o", tmp_path / "upright.h5", cwd=tmp_path)
    assert result.returncode == EXIT_SOLVER_FAILURE, result.stderr
    assert "error: initial_state: equilibrium: the equilibrium found is unstable" in result.stderr
    assert "completed" not in result.stderr


@pytest.mark.parametrize("method,code", [("newton", EXIT_SOLVER_FAILURE), ("relaxation", 0)])
def test_static_refuses_an_unstable_equilibrium(method: str, code: int, tmp_path: Path):
    """The pendulum drawn 170° up: Newton finds the inverted equilibrium, which is unstable and
    is reported as a failure (results kept, incomplete); relaxation settles into the hanging one."""
    scene = tmp_path / "upright.yaml"
    scene.write_text(f"base: {PENDULUM}\nmodify:\n"
                     "  bodies.rod.position: [-0.0868241, 0, 0.4924039]\n"   # −R_y(170°)·(0, 0, 0.5)
                     "  bodies.rod.rotation: {axis: [0, 1, 0], angle_deg: 170}\n"
                     f"  solver.statics: {{method: {method}, damping: 3.0}}\n", encoding="utf-8")
    out = tmp_path / "upright.h5"
    result = crane_sim("static", scene, "-o", out, cwd=tmp_path)
    assert result.returncode == code, result.stderr
    assert out.is_file()
    with h5py.File(out, "r") as f:
        status = f.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else status
    if code:
        assert "unstable" in result.stderr
        assert status == "incomplete"
    else:
        assert "stability: stable" in result.stderr
        assert status == "complete"


# Output and signals : the output path is checked before any work, a failed write never
# replaces an older result, and SIGTERM / SIGHUP end a run as Ctrl-C does, results kept.

def test_output_that_is_the_scene_is_refused(short_pendulum: Path, tmp_path: Path):
    scene = tmp_path / "scene.yaml"
    scene.write_text(short_pendulum.read_text(encoding="utf-8"), encoding="utf-8")
    result = crane_sim("run", scene, "-o", scene, "--quiet", cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert "-o" in result.stderr and "input file itself" in result.stderr
    assert scene.read_text(encoding="utf-8") == short_pendulum.read_text(encoding="utf-8")


def test_output_that_is_a_directory_is_refused(short_pendulum: Path, tmp_path: Path):
    (tmp_path / "results").mkdir()
    result = crane_sim("run", short_pendulum, "-o", tmp_path / "results", "--quiet", cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT
    assert "is a directory" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


def test_output_that_cannot_be_written_is_refused_before_the_run(short_pendulum: Path, tmp_path: Path):
    # /proc takes no new files, not even from root.
    result = crane_sim("static", short_pendulum, "-o", "/proc/cranesim_results.h5", cwd=tmp_path)
    assert result.returncode == EXIT_BAD_INPUT, result.stderr
    assert "cannot write the results next to '/proc/cranesim_results.h5'" in result.stderr
    assert "static equilibrium" not in result.stderr  # refused before any work


def test_a_failed_write_keeps_the_older_results(short_pendulum: Path, tmp_path: Path):
    import resource
    import signal

    out = tmp_path / "pendulum.h5"
    assert crane_sim("run", short_pendulum, "-o", out, "--quiet", cwd=tmp_path).returncode == 0
    good = out.read_bytes()

    def small_disk():  # writes beyond 4 KiB fail with EFBIG, as on a full disk
        resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)

    result = subprocess.run([str(BINARY), "run", str(short_pendulum), "-o", str(out), "--quiet"], capture_output=True,
                            text=True, cwd=tmp_path, timeout=30, preexec_fn=small_disk)
    assert result.returncode == EXIT_SOLVER_FAILURE, result.stderr
    assert f"cannot write '{out}'" in result.stderr and "older file there is kept" in result.stderr
    assert out.read_bytes() == good
    assert not Path(f"{out}.partial").exists()


def cpu_seconds(pid: int) -> float:
    """The CPU time a process has used (user + system), from /proc: unlike the wall clock, it does not
    depend on how loaded the machine is."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def signalled_long_run(tmp_path: Path, number: int, ready) -> tuple[int, str, Path]:
    """configs/pendulum.yaml run for 1e4 s (about a minute), sent signal `number` once `ready(pid, out)`
    holds (polled; at most 120 s): the exit code, stderr and the results path."""
    import time

    text, count = re.subn(r"^(\s+t_end:).*$", r"\1 1.0e4", PENDULUM.read_text(encoding="utf-8"), flags=re.MULTILINE)
    assert count == 1
    scene = tmp_path / "long.yaml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "long.h5"
    process = subprocess.Popen([str(BINARY), "run", str(scene), "-o", str(out), "--quiet"], stderr=subprocess.PIPE,
                               text=True, cwd=tmp_path)
    deadline = time.monotonic() + 120.0
    while not ready(process.pid, out):
        assert process.poll() is None, "the run ended before it was signalled"
        assert time.monotonic() < deadline, "the run never got ready to be signalled"
        time.sleep(0.05)
    process.send_signal(number)
    _, stderr = process.communicate(timeout=60)
    return process.returncode, stderr, out


@pytest.mark.parametrize("signal_name", ["SIGTERM", "SIGHUP", "SIGINT"])
def test_a_signal_ends_the_run_with_its_results(signal_name: str, tmp_path: Path):
    import signal

    number = getattr(signal, signal_name)
    # After a second of CPU time the run has integrated far more than 10 output intervals.
    returncode, stderr, out = signalled_long_run(tmp_path, number, lambda pid, _: cpu_seconds(pid) >= 1.0)
    assert returncode == 128 + number, stderr
    attributes = results_attributes(out)
    assert attributes["status"] == "incomplete"
    assert attributes["message"].startswith("interrupted at t = ")
    with h5py.File(out, "r") as f:
        assert f["time"].shape[0] > 10 and 0.0 <= attributes["t_reached"] - f["time"][-1] <= 0.01  # one output interval


def test_a_run_killed_outright_leaves_its_last_checkpoint(tmp_path: Path):
    import signal
    import sys

    # Killed as soon as its first checkpoint (10 s of wall time in) is in place.
    _, _, out = signalled_long_run(tmp_path, signal.SIGKILL, lambda _, out: out.exists())
    attributes = results_attributes(out)
    assert attributes["status"] == "incomplete"
    assert attributes["message"].startswith("checkpoint at t = ")
    with h5py.File(out, "r") as f:
        assert f["time"].shape[0] > 100 and f["time"][-1] == pytest.approx(attributes["t_reached"])
    report = subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "report.py"), str(out)], capture_output=True,
                            text=True, timeout=60)
    assert report.returncode == 0, report.stderr
    assert "status: incomplete" in report.stdout


def test_rope_tensions_are_recorded_along_the_rope(tmp_path: Path):
    """A rope under output.section_forces records its tension at 9 points of every element:
    rope_pendulum.yaml's ball (1 t) hanging still below its 10 m steel rope as two cables, then as
    the spline rope: (m + ρA s) g at s m of unstretched rope above the ball, read and plotted."""
    for element in ("cable", "spline"):
        scene = tmp_path / f"hanging_{element}.yaml"
        scene.write_text(f"""base: {SOURCE_DIR / 'configs' / 'rope_pendulum.yaml'}
name: ball hanging still
modify:
  bodies.ball.position: [0, 0, -10.0079]
  members.rope.end: [0, 0, -10.0079]
  members.rope.element: {element}
  members.rope.segments: 2
  solver.t_end: 0.1
  solver.initial_state: equilibrium
  output.interval: 0.05
  output.section_forces: [rope]
""", encoding="utf-8")
        out = tmp_path / f"hanging_{element}.h5"
        result = subprocess.run([str(BINARY), "run", str(scene), "-o", str(out), "--quiet"], capture_output=True, text=True,
                                timeout=120)
        assert result.returncode == 0, result.stderr
        with h5py.File(out, "r") as f:
            tension = f["section_forces/rope/tension"][...]
            nodes = f["section_forces/rope/element_nodes"][...].astype(str)
        assert tension.shape == (3, 2, 9)
        assert [list(n) for n in nodes] == [["rope.n0", "rope.n1"], ["rope.n1", "rope.n2"]]
        rope_mass_per_m, g = 7800 * math.pi * 0.01**2, 9.81
        top = (1000 + rope_mass_per_m * (7.5 if element == "cable" else 10.0)) * g   # cables: below the top element's middle
        bottom = (1000 + rope_mass_per_m * (2.5 if element == "cable" else 0.0)) * g
        assert tension[-1, 0, 0] == pytest.approx(top, rel=1e-6)
        assert tension[-1, -1, -1] == pytest.approx(bottom, rel=1e-6)
        plot = subprocess.run(["python3", str(SOURCE_DIR / "scripts" / "plot_section_forces.py"), str(out), "--member", "rope",
                               "-o", str(tmp_path / f"{element}.png")], capture_output=True, text=True, timeout=120)
        assert plot.returncode == 0, plot.stderr
        assert "slack somewhere along rope for 0 s" in plot.stdout


def test_reeved_rope_part_tensions_are_recorded(tmp_path: Path):
    """A reeved rope records its parts' tensions, winch to dead end: hook_block.yaml's 10 t hook
    block on four falls over sheaves of efficiency 0.98 shares W equally at rest, and while
    hoisting steadily each sheave passes 0.98 of the tension on, the line pull that of the
    reeving-efficiency formula W (1 − η)/(η (1 − η⁴))."""
    out = tmp_path / "hook_block.h5"
    result = crane_sim("run", SOURCE_DIR / "configs" / "hook_block.yaml", "-o", out, "--quiet", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        time = f["time"][...]
        tension = f["ropes/hoist/part_tension"][...]
    assert tension.shape == (len(time), 5)
    weight, eta = 10000 * 9.81, 0.98
    at_rest = tension[0]
    assert max(at_rest) / min(at_rest) - 1 < 1e-9
    assert at_rest[0] == pytest.approx(weight / 4, rel=1e-4)    # the falls lean 0.1 m over 10 m
    steady = tension[(time > 5.0) & (time < 8.5)]
    assert len(steady) > 50
    assert steady[:, 1:] / steady[:, :-1] == pytest.approx(eta, rel=1e-9)
    # The falls lean 0.1 m over 10 m: the line pull is 5e-5 above the formula's for vertical falls.
    assert steady[:, 0] == pytest.approx(weight * (1 - eta) / (eta * (1 - eta**4)), rel=2e-4)


def test_static_reports_the_crane_in_an_engineers_terms(tmp_path: Path):
    """The thesis crane's `crane:` block: boom angle, head height, hook and load radius and height,
    and each rope's tensions, on stdout and under /crane in the results file. The hoist rope
    carries the 390 t load at the hook: W = 390000.6 kg × 9.8 m/s²."""
    out = tmp_path / "crane_static.h5"
    result = crane_sim("static", SOURCE_DIR / "configs" / "crane.yaml", "-o", out, cwd=tmp_path, timeout=120)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert "crane" in lines
    figures = {" ".join(line.split()[:3]): float(line.split()[3]) for line in lines
               if line.startswith("  ") and "[" in line and len(line.split()) >= 4}
    assert 84.0 < figures["boom angle [deg]"] < 85.0  # drawn at 85°, lowered by the luffing system's stretch
    load = [float(v) for v in next(line.split()[1:] for line in lines if line.startswith("load "))]
    assert figures["hook radius [m]"] == pytest.approx(math.hypot(load[0], load[1]), abs=1e-4)
    assert figures["load height [m]"] == pytest.approx(figures["hook height [m]"] - 1.0, abs=1e-3)
    hoist = next(line.split() for line in lines if line.startswith("  hoist_rope "))
    assert float(hoist[2]) == pytest.approx(390000.6 * 9.8, rel=1e-5)
    with h5py.File(out, "r") as f:
        assert f["/crane"].attrs["boom_angle_deg"] == pytest.approx(figures["boom angle [deg]"], abs=1e-4)
        assert f["/crane"].attrs["head_height"] == pytest.approx(figures["head height [m]"], abs=1e-4)
        assert f["/crane/ropes/hoist_rope"].attrs["tension_end"] == pytest.approx(float(hoist[2]), rel=1e-5)


def test_check_lists_each_truss_sections_fidelity(tmp_path: Path):
    """A section that leaves out its fidelity takes defaults.truss_fidelity, and check says so."""
    scene = tmp_path / "defaulted.yaml"
    scene.write_text(f"base: {SOURCE_DIR / 'configs' / 'crane.yaml'}\n"
                     "defaults: {truss_fidelity: condensed}\n"
                     "remove: [constraints.boom12, constraints.boom23, members.boom2]\n"
                     "insert_after:\n"
                     "  members.boom1:\n"
                     "    - {name: boom2, type: truss, truss: type2, damping: 1.0e-3, start: [-0.435779, 0, 4.980973],\n"
                     "       end: [-1.743115, 0, 19.923894], z_axis: [-0.9961947, 0, -0.0871557]}\n"
                     "add:\n"
                     "  constraints:\n"
                     "    - {name: boom12, type: fixed, joints: [boom1.end, boom2.start]}\n"
                     "    - {name: boom23, type: fixed, joints: [boom2.end, boom3.start]}\n", encoding="utf-8")
    result = crane_sim("check", scene, cwd=tmp_path, timeout=120)
    assert result.returncode == 0, result.stderr
    sections = {line.split()[0]: line.split()[1:] for line in result.stdout.splitlines()
                if line.startswith(("boom", "derrick"))}
    assert sections["boom1"] == ["type1", "super_truss"]
    assert sections["boom2"] == ["type2", "condensed", "(defaults.truss_fidelity)"]
    assert sections["derrick3"] == ["type6", "super_truss"]


def test_check_draws_a_stated_equilibrium_where_static_draws_it(tmp_path: Path):
    """A scene stating its hook's radius and height: `check` searches the boom angle and the hoist
    rope's length as `static` does (the same drawing reported on stderr), and `static`'s
    equilibrium meets both figures to 1 mm."""
    scene = tmp_path / "stated.yaml"
    scene.write_text(f"base: {SOURCE_DIR / 'configs' / 'crane_configured.yaml'}\n"
                     "modify:\n"
                     "  booms.boom.angle_deg: from_equilibrium\n"
                     "  booms.boom.hoist.hanging_length: from_equilibrium\n"
                     "  booms.boom.equilibrium: {hook_radius: 25, hook_height: 8}\n"
                     "  bodies.load.mass: 100000\n", encoding="utf-8")
    drawn = re.compile(r"boom 'boom' drawn at (\d+\.\d+)°, its hoist rope (\d+\.\d+) m long: its equilibrium holds "
                       r"the hook at a radius of [\d.]+ m and a height of [\d.]+ m \(stated 25 and 8; \d+ equilibria\)")
    checked = crane_sim("check", scene, cwd=tmp_path, timeout=120)
    assert checked.returncode == 0, checked.stderr
    static = crane_sim("static", scene, "-o", tmp_path / "stated_static.h5", cwd=tmp_path, timeout=120)
    assert static.returncode == 0, static.stderr
    in_check, in_static = drawn.search(checked.stderr), drawn.search(static.stderr)
    assert in_check and in_static, (checked.stderr, static.stderr)
    assert in_check.groups() == in_static.groups()
    assert 60 < float(in_check.group(1)) < 80
    figures = {" ".join(line.split()[:3]): float(line.split()[3]) for line in static.stdout.splitlines()
               if line.startswith("  ") and "[" in line and len(line.split()) >= 4}
    assert figures["hook radius [m]"] == pytest.approx(25, abs=1e-3)
    assert figures["hook height [m]"] == pytest.approx(8, abs=1e-3)


def test_a_run_reports_leaving_the_envelope_and_can_stop_there(tmp_path: Path):
    """The hard case's first 2.5 s: the hoist rope's snatch above its breaking force is named with
    its time and force on stderr and under /envelope; with solver.outside_envelope: stop the run
    ends at the first sample outside, marked incomplete, exit 1."""
    base = SOURCE_DIR / "configs" / "crane_hoist_payout.yaml"
    warned = tmp_path / "warned.yaml"
    warned.write_text(f"base: {base}\nmodify:\n  solver.t_end: 2.5\n", encoding="utf-8")
    result = crane_sim("run", warned, "-o", tmp_path / "warned.h5", cwd=tmp_path, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "completed, leaving the crane's envelope" in result.stderr
    assert re.search(r"rope overload: hoist_rope carried 1[3-9]\.\d+ MN at t = 2\.\d+ s, above its breaking force 13\.08 MN",
                     result.stderr), result.stderr
    assert "boom on its backstop: from t = 1.5 s" in result.stderr
    with h5py.File(tmp_path / "warned.h5") as f:
        assert f["/envelope"].attrs["left_envelope"] == 1
        events = [dict(f[f"/envelope/events/{k}"].attrs) for k in f["/envelope/events"]]
        snap = next(e for e in events if e["what"] == "rope overload")
        assert snap["part"] == "hoist_rope" and snap["peak"] > snap["limit"] == 13.08e6
        tension = f["/envelope/rope_tension/hoist_rope"][:]
        assert max(tension) == snap["peak"]

    stopped = tmp_path / "stopped.yaml"
    stopped.write_text(f"base: {base}\nmodify:\n  solver.t_end: 2.5\n  solver.outside_envelope: stop\n", encoding="utf-8")
    result = crane_sim("run", stopped, "-o", tmp_path / "stopped.h5", cwd=tmp_path, timeout=120)
    assert result.returncode == 1, result.stderr
    assert "the run left the crane's envelope (solver.outside_envelope: stop)" in result.stderr
    with h5py.File(tmp_path / "stopped.h5") as f:
        assert f.attrs["status"] == "incomplete"
        assert 1.8 <= f["/time"][-1] <= 2.1


def slewed_deg(hook: np.ndarray) -> float:
    """The angle about the slewing axis from the hook's first sample to its last, in degrees."""
    turned = math.atan2(hook[-1, 1], hook[-1, 0]) - math.atan2(hook[0, 1], hook[0, 0])
    return math.remainder(math.degrees(turned), 360.0)


# What each motion does to the hook, in metres or degrees where the configured crane's hook
# differs from the drawn one's by micrometres.
MOTIONS = {
    "lifting": (1e-5, lambda hook: hook[-1, 2] - hook[0, 2] > 19.0),   # the 20 m hoisted
    "luffing": (1e-4, lambda hook: hook[-1, 2] - hook[0, 2] < -9.0),   # the boom luffed down
    "slewing": (1e-4, lambda hook: abs(abs(slewed_deg(hook)) - 90.0) < 10.0),  # the load swinging at the end
    "combined": (1e-3, lambda hook: hook[-1, 2] - hook[0, 2] > 15.0 and abs(abs(slewed_deg(hook)) - 45.0) < 5.0),
}


@pytest.mark.parametrize("motion", MOTIONS)
def test_configured_crane_moves_as_the_drawn_one(motion: str, tmp_path: Path):
    """The thesis' motions (8.3.1 lifting, luffing and slewing, 8.3.2 combined) on the configured
    crane (crane_configured_<motion>.yaml: the boom at the angle the motions' 7.0608 m luffing rope
    gives, ropes reeled by profiles) follow crane_<motion>.yaml, which draws every coordinate by
    hand: the hook within 10 µm (lifting), 0.1 mm (luffing and slewing; 30 µm measured) and 1 mm
    (combined, at its rtol 1e-4; 0.23 mm measured) at every sample, where the motion shows in
    metres. What is left is crane.yaml's rounding of its drawing (1.5 µm at rest), grown by the
    integrator's different steps."""
    tolerance, moved = MOTIONS[motion]
    hooks = []
    for scene in (f"crane_{motion}.yaml", f"crane_configured_{motion}.yaml"):
        out = tmp_path / scene.replace(".yaml", ".h5")
        result = crane_sim("run", SOURCE_DIR / "configs" / scene, "-o", out, cwd=tmp_path, timeout=300)
        assert result.returncode == 0, result.stderr
        with h5py.File(out, "r") as f:
            hooks.append(f["joints/load.origin/position"][...])
    drawn, configured = hooks
    assert drawn.shape == configured.shape
    assert np.max(np.linalg.norm(drawn - configured, axis=1)) < tolerance
    assert moved(drawn)


@pytest.mark.parametrize("configuration", ["crane_configured_long.yaml", "crane_configured_short.yaml"])
def test_a_boom_one_insert_longer_or_shorter_runs(tmp_path: Path, configuration: str):
    """The configured crane with one 15 m insert more or fewer, drawn by the tool, slews 20° in
    8 s from its equilibrium: the run completes, the pedestal turns by the drive's 20°, and the load
    hangs on (its height within 5 cm, its radius within 1 m of where it started)."""
    scene = tmp_path / "slewing.yaml"
    scene.write_text(f"base: {SOURCE_DIR / 'configs' / configuration}\n"
                     "modify:\n"
                     "  constraints.slewing.drive: {type: trapezoid, from: 0, distance: 20, t_start: 0, duration: 8,"
                     " t_accel: 2, t_decel: 2, unit: deg}\n"
                     "  solver.t_end: 10\n", encoding="utf-8")
    out = tmp_path / "slewing.h5"
    result = crane_sim("run", scene, "-o", out, cwd=tmp_path, timeout=300)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        turn = f["/bodies/pedestal/rotation"][-1] @ f["/bodies/pedestal/rotation"][0].T
        load = f["/bodies/load/position"][()]
    assert np.degrees(np.arctan2(turn[1, 0], turn[0, 0])) == pytest.approx(20.0, abs=1e-6)
    assert np.abs(load[:, 2] - load[0, 2]).max() < 0.05
    radius = np.hypot(load[:, 0], load[:, 1])
    assert np.abs(radius - radius[0]).max() < 1.0
