"""crane-sim study: the case table, its determinism over threads and MPI ranks, failed cases,
interruption and --resume, and bad study files.

Every tests/data/bad_studies/*.yaml is a study with one defect. Its first two lines say what the error
must contain and which YAML path of the study file it names:

    # expect: <substring of the error message>
    # path: <YAML path the error is reported at>

Environment: CRANESIM_BIN (default <repo>/build/crane-sim) and CRANESIM_SOURCE_DIR. The MPI
comparisons run when mpirun is on PATH and crane-sim was built with MPI.
"""

import math
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

from bad_input import EXIT_BAD_INPUT, assert_collection, assert_reported, expectations
from mpi_launch import mpirun

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()
BAD_STUDIES = sorted((SOURCE_DIR / "tests" / "data" / "bad_studies").glob("*.yaml"))
RUN_STUDY = SOURCE_DIR / "configs" / "study_rope_pendulum.yaml"
ROPE_PENDULUM = SOURCE_DIR / "configs" / "rope_pendulum.yaml"

GRAVITY = 9.81
# rope_pendulum.yaml: a 10 m steel rope of radius 1 cm, E = 1e11 Pa, ρ = 7800 kg/m³.
ROPE_LENGTH = 10.0
ROPE_AREA = math.pi * 0.01**2
ROPE_MASS = 7800 * ROPE_AREA * ROPE_LENGTH
ROPE_EA = 1.0e11 * ROPE_AREA
# Where the ball is drawn: 30° out, on the rope's stretched chord.
BALL_DRAWN_X = 5.001368700748983

STATIC_STUDY = f"""\
scene: {ROPE_PENDULUM}
analysis: static
parameters:
  - {{path: bodies.ball.mass, range: {{from: 500, to: 3000, count: 6}}}}
figures:
  - {{name: hook_tension, quantity: rope_tension, rope: rope}}
  - {{name: top_tension, quantity: rope_tension, rope: rope, end: start}}
  - {{name: ball_z, quantity: position, body: ball, component: z}}
  - {{name: ball_x, quantity: position, joint: ball.origin, component: x}}
keep_results: true
"""


def crane_sim(*arguments, cwd: Path, timeout: float = 120) -> subprocess.CompletedProcess:
    return subprocess.run([str(BINARY), *map(str, arguments)], capture_output=True, text=True, cwd=cwd,
                          timeout=timeout)


def computed_study(directory: Path, name: str, text: str) -> Path:
    """The study `text` written to <name>.yaml in `directory` and computed there (exit 0 asserted):
    its case table <name>.h5."""
    study = directory / f"{name}.yaml"
    study.write_text(text)
    table = directory / f"{name}.h5"
    result = crane_sim("study", study, "-o", table, cwd=directory)
    assert result.returncode == 0, result.stderr
    return table


def case_table(path: Path) -> dict:
    """Everything of a case table that must not depend on who computed it: all but wall times."""
    with h5py.File(path, "r") as f:
        table = {f"parameters/{k}": f["parameters"][k][...] for k in f["parameters"]}
        table.update({f"figures/{k}": f["figures"][k][...] for k in f["figures"]})
        for k in ("status", "message", "steps"):
            table[f"cases/{k}"] = f["cases"][k][...]
    return table


def workers(path: Path) -> list[str]:
    with h5py.File(path, "r") as f:
        return list(f["cases/worker"].asstr()[...])


def assert_bitwise_equal(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for key in a:
        assert a[key].dtype == b[key].dtype, key
        if a[key].dtype.kind == "f":
            assert a[key].tobytes() == b[key].tobytes(), key
        else:
            assert np.array_equal(a[key], b[key]), key


def test_bad_study_collection_is_complete():
    assert_collection(BAD_STUDIES, 10)


@pytest.mark.parametrize("study", BAD_STUDIES, ids=[s.stem for s in BAD_STUDIES])
def test_bad_study_is_rejected(study: Path, tmp_path: Path):
    expect, path = expectations(study)
    result = crane_sim("study", study, "-o", tmp_path / "study.h5", cwd=tmp_path)
    assert_reported(result, study, expect, path)
    assert list(tmp_path.iterdir()) == []  # no table, no partial file, no checkpoint


@pytest.fixture(scope="module")
def static_study(tmp_path_factory) -> Path:
    return computed_study(tmp_path_factory.mktemp("static_study"), "masses", STATIC_STUDY)


def test_static_study_figures_match_the_hanging_rope(static_study: Path):
    """At rest the hook carries the ball's weight, the suspension the ball's and the rope's, and the
    ball hangs below the suspension by the rope's length plus its stretch under the linearly
    varying tension, ∫ T/EA ds = (m g L + ρ A g L²/2)/EA."""
    with h5py.File(static_study, "r") as f:
        mass = f["parameters/bodies.ball.mass"][...]
        assert np.array_equal(mass, [500, 1000, 1500, 2000, 2500, 3000])
        assert list(f["cases/status"].asstr()[...]) == ["complete"] * 6
        assert f.attrs["contents"] == "study" and f.attrs["status"] == "complete"
        assert "bodies.ball.mass" in f.attrs["study_text"]
        np.testing.assert_allclose(f["figures/hook_tension"][...], mass * GRAVITY, rtol=1e-9)
        np.testing.assert_allclose(f["figures/top_tension"][...], (mass + ROPE_MASS) * GRAVITY, rtol=1e-9)
        stretch = (mass * GRAVITY * ROPE_LENGTH + ROPE_MASS * GRAVITY * ROPE_LENGTH / 2) / ROPE_EA
        np.testing.assert_allclose(f["figures/ball_z"][...], -(ROPE_LENGTH + stretch), atol=1e-7)
        np.testing.assert_allclose(f["figures/ball_x"][...], 0.0, atol=1e-9)
        assert np.all(f["cases/steps"][...] > 0)


def test_static_study_keeps_each_case_results(static_study: Path):
    cases = sorted((static_study.parent / "masses_cases").iterdir())
    assert [c.name for c in cases] == [f"case_{i:05d}.h5" for i in range(6)]
    with h5py.File(cases[3], "r") as f:
        assert f.attrs["status"] == "complete"
        assert "case 3: bodies.ball.mass = 2000" in f.attrs["scene_text"]
        assert f["bodies/ball/position"][0, 2] < -ROPE_LENGTH


@pytest.fixture(scope="module")
def run_study(tmp_path_factory) -> dict:
    """The example study (a grid of masses × random rope stiffnesses, 2 s swings) computed by
    one thread, two threads, one MPI rank and two MPI ranks."""
    directory = tmp_path_factory.mktemp("run_study")
    tables, who = {}, {}
    for jobs in (1, 2):
        out = directory / f"jobs{jobs}.h5"
        result = crane_sim("study", RUN_STUDY, "-o", out, "--jobs", jobs, cwd=directory)
        assert result.returncode == 0, result.stderr
        tables[f"jobs {jobs}"], who[f"jobs {jobs}"] = case_table(out), workers(out)
    if shutil.which("mpirun"):
        for ranks in (1, 2):
            out = directory / f"ranks{ranks}.h5"
            result = mpirun(BINARY, ranks, "study", RUN_STUDY, "-o", out, cwd=directory)
            assert result.returncode == 0, result.stdout + result.stderr
            tables[f"ranks {ranks}"], who[f"ranks {ranks}"] = case_table(out), workers(out)
    return {"tables": tables, "workers": who}


# A hook block guided vertically 10 m under a fixed head sheave on 4 falls over sheaves of
# efficiency 0.96 (tests/elements/test_reeving.cpp's guided hook): its falls are vertical.
REEVED_HOOK = """\
name: guided hook block on four falls
gravity: [0, 0, -9.81]
ground:
  joints: [{name: winch, position: [-8, 0, 20]}, {name: head, position: [0, 0, 20]}, {name: guide, position: [0, 0, 10]}]
bodies:
  - {name: hook, mass: 10000, inertia: [1000, 1000, 1000], position: [0, 0, 10], joints: [{name: sheaves, position: [0, 0, 0]}]}
members:
  - name: hoist
    type: rope
    element: reeved
    falls: 4
    winch: ground.winch
    head: {joint: ground.head, radius: 0.3}
    hook: {joint: hook.sheaves, radius: 0.3}
    efficiency: 0.96
    section: {radius: 0.01}
    material: {density: 7800, youngs_modulus: 1.0e11, poisson_ratio: 0.3}
    length: 47.9
constraints:
  - {name: guide, type: prismatic, joints: [ground.guide, hook.origin], axis: z}
solver: {t_end: 1}
"""

REEVED_STUDY = """\
scene: hook.yaml
analysis: static
parameters:
  - {path: bodies.hook.mass, range: {from: 5000, to: 20000, count: 4}}
figures:
  - {name: part, quantity: part_tension, rope: hoist}
  - {name: pull, quantity: line_pull, rope: hoist}
"""


def test_static_study_of_a_reeved_rope(tmp_path: Path):
    """At rest every part of n falls carries W/n; the winch hoisting W over n sheaves of
    efficiency η pulls W (1 − η) / (η (1 − ηⁿ)) (DIN 15020-1: W / (n η_S η))."""
    (tmp_path / "hook.yaml").write_text(REEVED_HOOK)
    with h5py.File(computed_study(tmp_path, "reeved", REEVED_STUDY), "r") as f:
        weight = f["parameters/bodies.hook.mass"][...] * GRAVITY
        assert list(f["cases/status"].asstr()[...]) == ["complete"] * 4
        np.testing.assert_allclose(f["figures/part"][...], weight / 4, rtol=1e-9)
        eta = 0.96
        np.testing.assert_allclose(f["figures/pull"][...], weight * (1 - eta) / (eta * (1 - eta**4)), rtol=1e-9)


def test_the_thesis_lift_is_inside_the_chart_of_the_crane_reeved_for_it(tmp_path: Path):
    """configs/study_load_chart_reeved_390t.yaml at the thesis' 390 t lift (24 luffing parts of
    12.0608 m): the load hangs 22.1 m out and every criterion holds (measured: hoist line pull
    89 %, luffing 82 %, pendant 86 %, slewing ring 98 %); the hoist's line pull is the 18 falls'
    W (1 − η) / (η (1 − η¹⁸)) for the load and the 12 t hook block, to the falls' 0.15 m lean over
    52 m. 10 t more is beyond the ring, which limits the chart there."""
    text = (SOURCE_DIR / "configs" / "study_load_chart_reeved_390t.yaml").read_text(encoding="utf-8")
    text = text.replace("scene: crane_reeved_390t.yaml", f"scene: {SOURCE_DIR / 'configs' / 'crane_reeved_390t.yaml'}", 1)
    parameters = text[text.index("parameters:"):text.index("figures:")]
    text = text.replace(parameters, "parameters:\n  - {path: members.luffing_rope.length, values: [313.7473]}\n"
                                     "  - {path: bodies.load.mass, values: [390000, 400000]}\n", 1)
    with h5py.File(computed_study(tmp_path, "lift_390t", text), "r") as f:
        assert list(f["cases/status"].asstr()[...]) == ["complete"] * 2
        assert list(f["cases/admissible"][...]) == [1, 0]
        assert f["figures/radius"][0] == pytest.approx(22.10, abs=0.01)
        eta, weight = 0.98, (390000 + 12000) * 9.8  # crane.yaml's gravity
        assert f["figures/hoist_line_pull"][0] == pytest.approx(weight * (1 - eta) / (eta * (1 - eta**18)), rel=3e-4)
        limits = {"hoist_line_pull": 2.978e5, "luffing_line_pull": 2.412e5, "sub_cable": 9.421e6,
                  "slewing_ring_moment": 9.15e7}
        used = {name: f[f"figures/{name}"][0] / limit for name, limit in limits.items()}
        assert max(used.values()) == used["slewing_ring_moment"] and 0.95 < used["slewing_ring_moment"] < 1.0, used
        assert all(u < 0.9 for name, u in used.items() if name != "slewing_ring_moment"), used
        assert f["figures/slewing_ring_moment"][1] > 9.15e7


def test_run_study_figures(run_study: dict):
    table = run_study["tables"]["jobs 1"]
    mass = table["parameters/bodies.ball.mass"]
    assert np.array_equal(mass, [500, 500, 1000, 1000, 2000, 2000])
    stiffness = table["parameters/members.rope.material.youngs_modulus"]
    assert np.all((stiffness >= 8e10) & (stiffness <= 1.2e11)) and len(set(stiffness)) == 6
    assert list(table["cases/status"].astype(str)) == ["complete"] * 6
    # Released at rest 30° out, the ball is farthest from the vertical at the start, where the
    # rope holds it at its drawn place: its sway over the whole run is that distance.
    swing_start = table["figures/ball_sway"]
    assert np.all(swing_start < BALL_DRAWN_X)
    # The rope pulls the ball up and in: the tension at the hook peaks above the weight at the
    # lowest point, and never pushes.
    assert np.all(table["figures/hook_tension_max"] > mass * GRAVITY)
    assert np.all(table["figures/hook_tension_min"] >= 0.0)


def test_run_study_is_bitwise_identical_on_threads_and_ranks(run_study: dict):
    if not shutil.which("mpirun"):
        pytest.skip("mpirun not installed: threads compared only")
    tables = run_study["tables"]
    for table in tables.values():
        assert_bitwise_equal(tables["jobs 1"], table)
    assert len(tables) == 4


def test_every_worker_takes_part(run_study: dict):
    """Each case was computed by one of the workers there were; with two of them, by both."""
    who = run_study["workers"]
    assert set(who["jobs 1"]) == {"thread 0"}
    assert set(who["jobs 2"]) == {"thread 0", "thread 1"}
    if "ranks 2" in who:
        assert set(who["ranks 1"]) == {"rank 0 thread 0"}
        assert set(who["ranks 2"]) == {"rank 0 thread 0", "rank 1"}


def test_sway_of_a_released_pendulum(tmp_path: Path):
    """The sway relative to the suspension, over a run that starts at rest at the drawn 30°, is
    the drawn horizontal distance; after 1 s it is less."""
    table = computed_study(tmp_path, "sway", f"""\
scene: {ROPE_PENDULUM}
analysis: run
parameters:
  - {{path: solver.t_end, values: [1.5]}}
figures:
  - {{name: sway, quantity: horizontal_sway, body: ball, relative_to: ground.suspension}}
  - {{name: sway_late, quantity: horizontal_sway, body: ball, relative_to: ground.suspension, after: 1.0}}
  - {{name: sway_too_late, quantity: horizontal_sway, body: ball, after: 100}}
""")
    with h5py.File(table, "r") as f:
        assert abs(f["figures/sway"][0] - BALL_DRAWN_X) < 1e-6
        assert f["figures/sway_late"][0] < BALL_DRAWN_X - 0.1
        assert math.isnan(f["figures/sway_too_late"][0])  # no sample after 100 s


def test_sway_about_the_mean_offset(tmp_path: Path):
    """With about_mean the sway is the ball's horizontal offset from the suspension less that
    offset's mean over the window (a steady wind's offset taken out): the same figure computed
    from the run's results by hand."""
    table = computed_study(tmp_path, "sway_mean", f"""\
scene: {ROPE_PENDULUM}
analysis: run
parameters:
  - {{path: solver.t_end, values: [1.5]}}
figures:
  - {{name: sway, quantity: horizontal_sway, body: ball, relative_to: ground.suspension, about_mean: true, after: 0.5}}
""")
    scene = tmp_path / "short.yaml"
    scene.write_text(f"base: {ROPE_PENDULUM}\nmodify: {{solver.t_end: 1.5}}\n")
    crane_sim("run", scene, "-o", tmp_path / "run.h5", "--quiet", cwd=tmp_path)
    with h5py.File(tmp_path / "run.h5", "r") as f, h5py.File(table, "r") as study:
        late = f["time"][()] >= 0.5
        offset = (f["bodies/ball/position"][()] - f["joints/ground.suspension/position"][()])[late, :2]
        expected = np.linalg.norm(offset - offset.mean(axis=0), axis=1).max()
        assert study["figures/sway"][0] == pytest.approx(expected, rel=1e-12)
        assert expected < 0.9 * np.linalg.norm(offset, axis=1).max()  # the mean is not nothing


def test_tipping_moment_and_dynamic_factor(tmp_path: Path):
    """The ground's reaction on the hanging pendulum at rest is its whole weight W, up, at the
    suspension (0, 0, 0): about the line through (2, ·, −3) along +y its moment is 2 W, and the
    other way round −2 W. Released at rest 30° out, the rope's pull at the hook grows from
    m g cos 30° to m g (3 − 2 cos 30°) at the lowest point: φ2 = 1.464 for a rigid massless rope
    (the rope's mass and stretch change it by a few per mille)."""
    def study(analysis: str) -> str:
        return f"""\
scene: {ROPE_PENDULUM}
analysis: {analysis}
parameters:
  - {{path: solver.t_end, values: [3.5]}}
figures:
  - {{name: tipping, quantity: tipping_moment, supports: [top], line: [[2, -1, -3], [2, 1, -3]]}}
  - {{name: tipping_back, quantity: tipping_moment, supports: [top], line: [[2, 1, -3], [2, -1, -3]]}}
  - {{name: phi2, quantity: dynamic_factor, constraint: hook}}
"""

    weight = (1000 + ROPE_MASS) * GRAVITY
    with h5py.File(computed_study(tmp_path, "static", study("static")), "r") as f:
        assert f["figures/tipping"][0] == pytest.approx(2 * weight, rel=1e-9)
        assert f["figures/tipping_back"][0] == pytest.approx(-2 * weight, rel=1e-9)
        assert f["figures/phi2"][0] == 1.0  # one sample: the static force itself
    cos30 = math.cos(math.radians(30))
    with h5py.File(computed_study(tmp_path, "run", study("run")), "r") as f:
        assert f["figures/phi2"][0] == pytest.approx((3 - 2 * cos30) / cos30, rel=0.01)


def test_rope_slack_time(tmp_path: Path):
    """Taut at its drawn length, the rope is never slack; 0.5 m too long, it is slack until the
    ball has fallen freely onto it: √(2 Δz/g) = 0.3408 s (the output samples are 0.01 s apart)."""
    table = computed_study(tmp_path, "slack", f"""\
scene: {ROPE_PENDULUM}
analysis: run
parameters:
  - {{path: members.rope.length, values: [10.0, 10.5]}}
  - {{path: solver.t_end, values: [0.36]}}
figures:
  - {{name: slack, quantity: rope_slack, rope: rope}}
""")
    drop = math.sqrt(10.5**2 - BALL_DRAWN_X**2) - 8.662624697081984
    with h5py.File(table, "r") as f:
        taut, long = f["figures/slack"][...]
        assert taut == 0.0
        assert long == pytest.approx(math.sqrt(2 * drop / GRAVITY), abs=0.011)


def test_failed_case_is_a_row_and_the_study_goes_on(tmp_path: Path):
    study = tmp_path / "failing.yaml"
    study.write_text(f"""\
scene: {ROPE_PENDULUM}
analysis: static
parameters:
  - {{path: bodies.ball.mass, values: [-1, 1000]}}
figures:
  - {{name: hook_tension, quantity: rope_tension, rope: rope}}
""")
    result = crane_sim("study", study, "-o", tmp_path / "failing.h5", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "case 0: bad_input: bodies[0].mass: must be positive, found -1" in result.stderr
    with h5py.File(tmp_path / "failing.h5", "r") as f:
        assert list(f["cases/status"].asstr()[...]) == ["bad_input", "complete"]
        assert "must be positive" in f["cases/message"].asstr()[0]
        tension = f["figures/hook_tension"][...]
        assert math.isnan(tension[0]) and tension[1] == pytest.approx(1000 * GRAVITY, rel=1e-9)


def test_interrupted_study_resumes_without_recomputing(tmp_path: Path):
    """SIGINT stops the study with its finished rows written and checkpointed; --resume computes
    only the others, and the table is bitwise the one of an uninterrupted study."""
    study = tmp_path / "long.yaml"
    study.write_text(RUN_STUDY.read_text().replace("scene: rope_pendulum.yaml", f"scene: {ROPE_PENDULUM}")
                     .replace("values: [2]", "values: [8]"))
    reference = tmp_path / "reference.h5"
    assert crane_sim("study", study, "-o", reference, "-q", cwd=tmp_path).returncode == 0

    out, checkpoint = tmp_path / "long.h5", tmp_path / "long.h5.checkpoint"
    process = subprocess.Popen([str(BINARY), "study", str(study), "-o", str(out)], cwd=tmp_path,
                               stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not (checkpoint.exists() and len(checkpoint.read_text().splitlines()) >= 2):  # header + a row
        assert time.monotonic() < deadline and process.poll() is None
        time.sleep(0.01)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == 128 + signal.SIGINT, stderr
    with h5py.File(out, "r") as f:
        assert f.attrs["status"] == "incomplete" and "--resume" in f.attrs["message"]
        statuses = list(f["cases/status"].asstr()[...])
        finished = statuses.count("complete")
        assert 1 <= finished < 6 and statuses.count("not_run") == 6 - finished
        wall_before = f["cases/wall_time_s"][...]
    assert checkpoint.exists()

    again = crane_sim("study", study, "-o", out, cwd=tmp_path)
    assert again.returncode == EXIT_BAD_INPUT and "--resume" in again.stderr

    resumed = crane_sim("study", study, "-o", out, "--resume", cwd=tmp_path)
    assert resumed.returncode == 0, resumed.stderr
    assert f"resuming: {finished} of 6 cases finished before" in resumed.stderr
    assert f"{6 - finished} computed" in resumed.stderr
    assert not checkpoint.exists()
    assert_bitwise_equal(case_table(reference), case_table(out))
    with h5py.File(out, "r") as f:
        done = np.array(statuses) == "complete"
        assert np.array_equal(f["cases/wall_time_s"][...][done], wall_before[done])  # not computed again


def test_modes_study_gives_the_frequencies_of_crane_sim_modes(tmp_path: Path):
    """A modes case is `crane-sim modes` of the case's scene: the same frequencies, bit for bit."""
    table = computed_study(tmp_path, "modes_study", f"""\
scene: {ROPE_PENDULUM}
analysis: modes
modes: 6
parameters:
  - {{path: bodies.ball.mass, values: [1000]}}
figures:
  - {{name: f4, quantity: frequency, mode: 4}}
  - {{name: f6, quantity: frequency, mode: 6}}
  - {{name: hook_tension, quantity: rope_tension, rope: rope}}
""")
    modes = crane_sim("modes", ROPE_PENDULUM, "-n", 6, "-o", tmp_path / "modes.h5", cwd=tmp_path)
    assert modes.returncode == 0, modes.stderr
    with h5py.File(table, "r") as s, h5py.File(tmp_path / "modes.h5", "r") as m:
        frequency = m["modes/frequency"][...]
        assert s["figures/f4"][0] == frequency[3] and s["figures/f6"][0] == frequency[5]
        assert frequency[3] > 0.1  # the swing, ≈ √(g/ℓ)/2π = 0.158 Hz, not a rigid mode
        assert s["figures/hook_tension"][0] == pytest.approx(1000 * GRAVITY, rel=1e-9)


def test_criteria_and_load_chart(tmp_path: Path):
    """A case is admissible when its figures are within the study's criteria; the load chart of
    scripts/plot_load_chart.py is, per configuration, the largest load whose lighter loads are all
    admissible: a hook tension limit of 15 kN admits m g ≤ 15 kN, m ≤ 1529 kg, so 1500 kg, and
    the limit is reached at 1529 kg."""
    table = computed_study(tmp_path, "chart", f"""\
scene: {ROPE_PENDULUM}
analysis: static
parameters:
  - {{path: members.rope.length, values: [9.5, 10]}}
  - {{path: bodies.ball.mass, range: {{from: 500, to: 3000, count: 6}}}}
figures:
  - {{name: radius, quantity: horizontal_distance, body: ball, relative_to: ground.suspension}}
  - {{name: hook_tension, quantity: rope_tension, rope: rope}}
criteria:
  - {{figure: hook_tension, max: 15000, source: a test limit}}
  - {{figure: radius, max: 1.0, source: hangs straight down}}
""")
    with h5py.File(table, "r") as f:
        mass = f["parameters/bodies.ball.mass"][...]
        assert np.array_equal(f["criteria/0"][...], (mass * GRAVITY <= 15000).astype(float))
        assert np.all(f["criteria/1"][...] == 1.0)
        assert np.array_equal(f["cases/admissible"][...], f["criteria/0"][...])
        assert f["criteria/0"].attrs["source"] == "a test limit" and f["criteria/0"].attrs["figure"] == "hook_tension"

    chart = subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "plot_load_chart.py"), str(table),
                            "--load", "bodies.ball.mass", "--configuration", "members.rope.length",
                            "-o", str(tmp_path / "chart.png")], capture_output=True, text=True)
    assert chart.returncode == 0, chart.stderr
    rows = [line.split() for line in chart.stdout.splitlines()[1:3]]
    assert [row[0] for row in rows] == ["9.5", "10"]
    assert all(row[2] == "1500" and row[-2] == "hook_tension" for row in rows), chart.stdout
    # where the hook tension, linear in the mass between 1500 and 2000 kg, reaches 15 kN
    assert all(float(row[-1].strip("()")) == pytest.approx(15000 / GRAVITY, rel=1e-5) for row in rows), chart.stdout
    # utilisation at the chart's load: hook tension 1500 kg g / 15 kN = 98 %, radius 0 / 1 m = 0 %
    assert all(row[3:5] == ["98%", "0%"] for row in rows), chart.stdout
    assert all(float(row[1]) < 1e-6 for row in rows)  # hanging under the suspension
    assert (tmp_path / "chart.png").stat().st_size > 0


def test_load_chart_by_boom_angle_of_a_configured_crane(tmp_path: Path):
    """A study varies a configured boom's angle (booms.boom.angle_deg): each case is drawn and its
    luffing rope sized by the tool at that angle. The 40 m main boom of
    configs/crane_configured_short.yaml puts the sheave, and the load under it, at the radius
    (L + 2.2) cos β + 1.7 sin β of the head's sheave joint (2.2 m along the boom's axis past its
    top, 1.7 m off it) as drawn; in equilibrium the ropes' stretch lowers the boom by less than 1°."""
    table = computed_study(tmp_path, "angles", f"""\
scene: {SOURCE_DIR / "configs" / "crane_configured_short.yaml"}
analysis: static
parameters:
  - {{path: booms.boom.angle_deg, values: [85, 60]}}
  - {{path: bodies.load.mass, values: [50000]}}
figures:
  - {{name: radius, quantity: horizontal_distance, body: load, relative_to: ground.slewing_ring}}
""")
    with h5py.File(table, "r") as f:
        angles = f["parameters/booms.boom.angle_deg"][...]
        radius = f["figures/radius"][...]
    for angle, r in zip(angles, radius):
        drawn = [42.2 * math.cos(math.radians(a)) + 1.7 * math.sin(math.radians(a)) for a in (angle, angle - 1.0)]
        assert drawn[0] < r < drawn[1], (angle, r, drawn)


def test_capacity_by_bisection_and_what_limits_it(tmp_path: Path):
    """Each case bisects the ball's mass to where the rope's top tension reaches 20 kN: the rope
    carries the ball and its own weight, (m + ρ A L) g, so the capacity is 20 kN / g − ρ A L for
    each rope density, found from below to the 1 kg tolerance; the table names what limits it and
    study_table.py prints it."""
    table = computed_study(tmp_path, "capacity", f"""\
scene: {ROPE_PENDULUM}
analysis: static
parameters:
  - {{path: members.rope.material.density, values: [7800, 15600]}}
capacity: {{load: bodies.ball.mass, from: 500, to: 5000, tolerance: 1, scales: [bodies.ball.inertia]}}
figures:
  - {{name: top, quantity: rope_tension, rope: rope, end: start}}
criteria:
  - {{figure: top, max: 20000, source: a test limit}}
""")
    with h5py.File(table, "r") as f:
        density = f["parameters/members.rope.material.density"][...]
        capacity = f["capacity/load"][...]
        inadmissible = f["capacity/inadmissible_load"][...]
        assert list(f["capacity/limited_by"].asstr()[...]) == ["top", "top"]
        assert f["capacity"].attrs["load_path"] == "bodies.ball.mass" and f["capacity"].attrs["tolerance"] == 1
        assert np.all(f["figures/top"][...] <= 20000)
        steps = f["cases/steps"][...]
    hand = 20000 / GRAVITY - density * ROPE_AREA * ROPE_LENGTH
    assert np.all(capacity <= hand * (1 + 1e-9)) and np.all(inadmissible >= hand * (1 - 1e-9))
    assert np.all(inadmissible - capacity <= 1)
    assert np.all(steps > 14)  # ⌈log2(4500)⌉ + 2 = 15 equilibria, each a few Newton iterations

    printed = subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "study_table.py"), str(table)],
                             capture_output=True, text=True)
    assert printed.returncode == 0, printed.stderr
    header, *rows = [line.split() for line in printed.stdout.splitlines()]
    assert header[-5:] == ["capacity", "inadmissible_load", "limited_by", "status", "message"]
    assert [float(row[header.index("capacity")]) for row in rows] == pytest.approx(list(capacity), rel=1e-5)  # 6 digits
