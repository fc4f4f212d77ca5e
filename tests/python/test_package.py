"""The Python package cranesim as a user installs it (scripts/install_python.sh): a scene's run
driven step by step, its errors, and the Gymnasium environment."""

import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

import cranesim

ROOT = Path(__file__).resolve().parents[2]
CRANE_INPUTS = ROOT / "configs" / "crane_inputs.yaml"


def test_the_package_is_the_projects_version():
    cmake = (ROOT / "CMakeLists.txt").read_text()
    pyproject = (ROOT / "pyproject.toml").read_text()
    version = re.search(r"project\(cranesim VERSION ([0-9.]+)", cmake).group(1)
    assert cranesim.__version__ == version
    assert f'version = "{version}"' in pyproject


def test_help_tells_a_user_what_to_call():
    text = subprocess.run([sys.executable, "-c", "import cranesim; help(cranesim.Simulation)"],
                          capture_output=True, text=True, check=True).stdout
    for method in ("set_inputs", "step", "reset", "joint_position", "inputs"):
        assert method in text


@pytest.fixture(scope="module")
def crane():
    return cranesim.Simulation(CRANE_INPUTS)


def test_a_crane_is_driven_step_by_step(crane):
    crane.reset()
    assert crane.inputs == ("luffing_rope", "hoist_rope", "slewing")
    anchor = crane.joint("pedestal.sub_cable_anchor")  # on the slewing pedestal, 11 m out
    start = crane.joint_position(anchor)
    for _ in range(250):  # 5 s at 50 Hz: slew at 1 °/s after the drive's acceleration limit
        crane.set_inputs({"slewing": 1.0})
        assert crane.step(0.02)
    assert crane.time == pytest.approx(5.0, abs=1e-12)
    angle = crane.input_values()[2]
    assert crane.input_rates()[2] == pytest.approx(1.0, abs=1e-6)
    # The drive's reference ramps to 1 °/s at 2 °/s² (0.5 s: 0.25° short of a jump to 1 °/s), and
    # the speed follows through two lags of τ = 50 ms, each τ behind once settled (e^{−90} later).
    expected = 5.0 - 0.25 - 2 * 0.05
    assert angle == pytest.approx(expected, abs=1e-9)
    moved = crane.joint_position(anchor)
    turned = math.degrees(math.atan2(moved[1], moved[0]) - math.atan2(start[1], start[0]))
    assert turned == pytest.approx(angle, abs=1e-6)  # the pedestal turns with its drive
    assert crane.statistics()["restarts"] == 0


def test_commands_are_clipped_to_the_limits_or_refused(crane):
    crane.reset()
    held = crane.set_inputs([0.0, 5.0, 0.0])  # 5 m/s on the hoist rope: its limit is 1.2 m/s
    assert held[1] == 1.2
    with pytest.raises(ValueError, match="input 'slewing'.*not a finite number"):
        crane.set_inputs({"slewing": float("nan")})
    with pytest.raises(ValueError, match="no input named 'hoist'; the scene's inputs: luffing_rope, hoist_rope, slewing"):
        crane.set_inputs({"hoist": 0.1})
    with pytest.raises(ValueError, match="no input named 'hoist_rop' \\(did you mean 'hoist_rope'\\?\\)"):
        crane.set_inputs({"hoist_rop": 0.1})
    with pytest.raises(ValueError, match="takes 3 commands"):
        crane.set_inputs([0.1, 0.2])
    with pytest.raises(ValueError, match="did you mean 'load.origin'"):
        crane.joint("load.orgin")
    with pytest.raises(IndexError):
        crane.joint_position(10**6)


def test_a_bad_scene_raises_naming_file_path_and_line(tmp_path):
    scene = tmp_path / "winch.yaml"
    scene.write_text(CRANE_INPUTS.read_text().replace("time_constant: 0.05, limits: {speed: 1.2",
                                                      "time_constant: -1, limits: {speed: 1.2"))
    scene_dir_bases = tmp_path / "crane_condensed.yaml"
    scene_dir_bases.write_text((ROOT / "configs" / "crane_condensed.yaml").read_text())
    (tmp_path / "crane.yaml").write_text((ROOT / "configs" / "crane.yaml").read_text())
    with pytest.raises(cranesim.SceneError) as error:
        cranesim.Simulation(scene)
    assert error.value.file == str(scene)
    assert error.value.path == "members[12].length.time_constant"  # the hoist rope in the composed scene
    line = next(k for k, text in enumerate(scene.read_text().splitlines(), 1) if "time_constant: -1" in text)
    assert error.value.line == line
    assert str(error.value).startswith(f"{scene}: members[12].length.time_constant (line {line}")
    with pytest.raises(cranesim.SceneError) as error:
        cranesim.Simulation({"name": "ball", "bodies": [{"name": "ball", "mass": -1}]})
    assert error.value.path == "bodies[0].mass"


def test_a_scene_given_as_a_dict_runs_as_its_file_would():
    scene = {"base": str(CRANE_INPUTS), "name": "from a dict", "modify": {"solver.t_end": 1.0}}
    sim = cranesim.Simulation(scene)
    assert sim.name == "from a dict" and sim.t_end == 1.0
    while sim.step(0.1):
        pass
    assert sim.complete and sim.time == pytest.approx(1.0)
    assert not sim.step(0.1)


gymnasium = pytest.importorskip("gymnasium")


def test_the_lift_environment_passes_gymnasiums_checks():
    from gymnasium.utils.env_checker import check_env
    import cranesim.gym

    env = gymnasium.make("cranesim/CraneLift-v0")
    check_env(env.unwrapped, skip_render_check=True)
    first, info = env.reset(seed=7)
    again, info_again = env.reset(seed=7)
    assert np.array_equal(first, again) and np.array_equal(info["target"], info_again["target"])
    other, info_other = env.reset(seed=8)
    assert not np.array_equal(info["target"], info_other["target"])
    # The load drawn with the target: the thesis' 390 t ± 20 %, its equilibrium solved anew.
    masses = [info["load_mass"], info_other["load_mass"]]
    assert all(0.8 * 390000.6 <= m <= 1.2 * 390000.6 for m in masses) and masses[0] != masses[1]
    assert info_again["load_mass"] == info["load_mass"]
    with pytest.raises(ValueError, match="not finite"):
        env.step(np.array([0.0, np.nan, 0.0], dtype=np.float32))
    observation, reward, terminated, truncated, _ = env.step(np.array([5.0, -5.0, 5.0], dtype=np.float32))
    assert env.observation_space.contains(observation)
    assert np.all(np.abs(env.unwrapped.sim.input_rates()) <= np.array([0.7, 1.2, 6.0]) + 1e-12)


def test_random_actions_run_without_an_exception():
    import cranesim.gym

    env = gymnasium.make("cranesim/CraneLift-v0", episode_time=20.0)
    env.action_space.seed(3)
    env.reset(seed=3)
    episodes = 0
    for _ in range(10_000):
        observation, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert np.all(np.isfinite(observation)) and math.isfinite(reward)
        if terminated or truncated:
            assert "message" not in info, info.get("message")
            episodes += 1
            env.reset()
    assert episodes >= 9


def test_the_lift_environment_keeps_the_load_near_its_path_at_its_tolerance():
    """5 s of random actions at the environment's rtol 1e-3 against the same at 1e-6: the load
    within 2 mm (1.0 mm here; 3.8 mm over 10 s against 1e-8, benchmarks/gym_throughput.py)."""
    from cranesim.gym import CraneLiftEnv

    actions = np.random.default_rng(5).uniform(-1, 1, size=(250, 3)).astype(np.float32)
    paths = []
    for rtol in (None, 1e-6):
        env = CraneLiftEnv(load_mass=(390000.6, 390000.6), **({} if rtol is None else {"rtol": rtol}))
        env.reset(seed=5)
        paths.append(np.array([env.step(a)[0][0:3] for a in actions]))
    error = np.max(np.linalg.norm(paths[0] - paths[1], axis=1))
    assert 1e-6 < error < 2e-3, error


def run_example(name, *args):
    return subprocess.run([sys.executable, str(ROOT / "examples" / name), *args], capture_output=True, text=True,
                          check=True, timeout=600).stdout


def test_the_sway_damping_example_brings_the_load_to_rest():
    out = run_example("sway_damping.py", "--seconds", "60")
    swings = {m.group(1): [float(s) for s in m.group(2).split()] for m in
              re.finditer(r"^(open loop|hold|assisted)\s+largest swing per 10 s after the release: ([0-9. ]+) m",
                          out, re.M)}
    assert set(swings) == {"open loop", "hold", "assisted"} and len(swings["hold"]) == 4, out
    assert min(swings["open loop"]) > 0.8, out
    assert swings["hold"][-1] < 0.06, out       # 30-40 s after the release: 0.045 m
    assert swings["assisted"][-1] < 0.2, out    # 0.138 m


def test_the_rollout_example_brings_the_load_near_its_target():
    out = run_example("gym_rollout.py", "--seed", "1", "--seconds", "60")
    start, closest = map(float, re.search(r"started ([0-9.]+) m from the target, came within ([0-9.]+) m", out).groups())
    assert closest < 0.2 * start, out


def test_a_saved_state_goes_on_alike_here_and_in_another_process(tmp_path):
    sim = cranesim.Simulation(CRANE_INPUTS)
    hook = sim.joint("load.origin")

    def lift(seconds):
        path = []
        for _ in range(int(round(seconds / 0.02))):
            sim.set_inputs({"slewing": 2.0 * math.sin(0.5 * sim.time), "hoist_rope": -0.3})
            sim.step(0.02)
            path.append(sim.joint_position(hook))
        return np.array(path)

    lift(2.0)
    state = sim.save_state()
    assert state.time == pytest.approx(2.0)
    first = lift(2.0)
    sim.restore_state(state)
    assert np.array_equal(lift(2.0), first)

    sim.restore_state(state)
    sim.save_state(tmp_path / "state.h5")
    script = (f"import cranesim, numpy as np, math\n"
              f"sim = cranesim.Simulation({str(CRANE_INPUTS)!r})\n"
              f"sim.restore_state({str(tmp_path / 'state.h5')!r})\n"
              f"hook = sim.joint('load.origin')\n"
              f"path = []\n"
              f"for _ in range(100):\n"
              f"    sim.set_inputs({{'slewing': 2.0 * math.sin(0.5 * sim.time), 'hoist_rope': -0.3}})\n"
              f"    sim.step(0.02)\n"
              f"    path.append(sim.joint_position(hook))\n"
              f"np.save({str(tmp_path / 'path.npy')!r}, np.array(path))\n")
    subprocess.run([sys.executable, "-c", script], check=True, timeout=300)
    # In another process the same to rounding: the linear solver's pivot history is not saved.
    assert np.abs(np.load(tmp_path / "path.npy") - first).max() < 1e-9
    with pytest.raises(RuntimeError, match="state.h5.*inputs"):
        cranesim.Simulation(ROOT / "configs" / "crane_condensed.yaml").restore_state(tmp_path / "state.h5")


PRECISE_LIFT = f"""
import math, sys
import numpy as np
import cranesim

# The crane at rtol 1e-9 rests until 29 s (cheap steps) and then slews and hoists with commands
# that depend on time only, so that every run of it gets the same ones.
sim = cranesim.Simulation({{"base": {str(CRANE_INPUTS)!r}, "name": "precise",
                           "modify": {{"solver.rtol": 1.0e-9, "solver.atol": 1.0e-10}}}})
hook = sim.joint("load.origin")
restore, save, until, out = sys.argv[1:5]
if restore != "-":
    sim.restore_state(restore)
path = []
k = int(round(sim.time / 0.02))
while k < int(round(float(until) / 0.02)):
    t = max(sim.time - 29.0, 0.0)
    sim.set_inputs({{"slewing": 3.0 * math.sin(0.5 * t), "hoist_rope": -0.3 * math.sin(0.7 * t)}})
    k += 1
    assert sim.advance_to(k * 0.02), sim.message
    if sim.time > 30.0 + 1e-9:
        path.append(sim.joint_position(hook))
if save != "-":
    sim.save_state(save)
np.save(out, np.array(path))
"""


def test_a_state_saved_at_30_s_goes_on_in_another_process_within_the_integrators_error(tmp_path):
    script = tmp_path / "precise_lift.py"
    script.write_text(PRECISE_LIFT)

    def run(*args):
        return subprocess.Popen([sys.executable, str(script), *map(str, args)])

    state = tmp_path / "state_30s.h5"
    # The uninterrupted run to 31 s and the run that saves at 30 s, on both cores at once.
    whole, first = run("-", "-", 31.0, tmp_path / "whole.npy"), run("-", state, 30.0, tmp_path / "first.npy")
    assert first.wait(timeout=600) == 0
    continued = run(state, "-", 31.0, tmp_path / "continued.npy")
    assert whole.wait(timeout=600) == 0 and continued.wait(timeout=600) == 0
    uninterrupted, restored = np.load(tmp_path / "whole.npy"), np.load(tmp_path / "continued.npy")
    assert uninterrupted.shape == restored.shape == (50, 3)
    distance = np.linalg.norm(restored - uninterrupted, axis=1).max()
    print(f"largest hook distance after the restore: {distance:.3g} m")
    assert 0.0 < distance < 1e-6  # a restart within the tolerance, not a copy of the history
    assert np.linalg.norm(uninterrupted[-1] - uninterrupted[0]) > 0.01  # the load moves

CRANE_SIM = ROOT / "build" / "crane-sim"
LUFFING_JIB = ROOT / "configs" / "luffing_jib.yaml"


def crane_sim(*args):
    subprocess.run([str(CRANE_SIM), *map(str, args)], check=True, capture_output=True)


def test_run_static_and_modes_write_the_command_lines_files(tmp_path):
    import h5py

    crane_sim("run", LUFFING_JIB, "-o", tmp_path / "cli.h5", "-q")
    crane_sim("static", LUFFING_JIB, "-o", tmp_path / "cli_static.h5")
    crane_sim("modes", LUFFING_JIB, "-n", 6, "-o", tmp_path / "cli_modes.h5")
    analyses = {
        "cli.h5": (cranesim.run(LUFFING_JIB, tmp_path / "py.h5"), ["time", "q", "v", "lambda", "energy/balance"]),
        "cli_static.h5": (cranesim.static(LUFFING_JIB, tmp_path / "py_static.h5"), ["q", "lambda"]),
        "cli_modes.h5": (cranesim.modes(LUFFING_JIB, 6, tmp_path / "py_modes.h5"),
                         ["modes/frequency", "modes/shapes", "equilibrium/q"]),
    }
    for cli_file, (results, paths) in analyses.items():
        with h5py.File(tmp_path / cli_file) as cli, results:
            for path in paths:
                assert np.array_equal(results.get(path), cli[path][()]), (cli_file, path)
    run = cranesim.Results(tmp_path / "py.h5")
    assert run.status == "complete" and run.attribute("t_reached") == run.time()[-1] == 10.0
    assert run.get("joints/boom.tip/position").shape == (run.time().size, 3)


def test_a_stated_equilibrium_is_drawn_as_the_command_line_draws_it(tmp_path):
    """A scene stating its hook's radius: the package's scenes are drawn at the boom angle the
    command line's search finds, not at the search's first angle; its equilibrium is the same."""
    import h5py

    scene = tmp_path / "stated.yaml"
    scene.write_text(f"base: {ROOT / 'configs' / 'crane_configured.yaml'}\n"
                     "modify:\n"
                     "  booms.boom.angle_deg: from_equilibrium\n"
                     "  booms.boom.equilibrium: {hook_radius: 25}\n"
                     "  bodies.load.mass: 100000\n", encoding="utf-8")
    crane_sim("static", scene, "-o", tmp_path / "cli_static.h5")
    with h5py.File(tmp_path / "cli_static.h5") as cli, cranesim.static(scene, tmp_path / "py_static.h5") as results:
        assert np.array_equal(results.get("q"), cli["q"][()])
        assert cli["/crane"].attrs["hook_radius"] == pytest.approx(25, abs=1e-3)
    simulation = cranesim.Simulation(scene)
    load = simulation.joint_position("load.origin")
    assert math.hypot(load[0], load[1]) == pytest.approx(25, abs=1e-3)


def test_analyses_of_dicts_need_an_output_and_name_errors_in_them(tmp_path):
    scene = yaml.safe_load(LUFFING_JIB.read_text())
    with pytest.raises(ValueError, match="output"):
        cranesim.static(scene)
    scene["bodies"][0]["mass"] = -1
    with pytest.raises(cranesim.SceneError) as error:
        cranesim.run(scene, tmp_path / "bad.h5")
    assert error.value.path == "bodies[0].mass" and error.value.file == "<dict>"
    assert not (tmp_path / "bad.h5").exists()


def test_a_recorded_run_writes_what_it_did_and_takes_back_what_a_restore_undoes(tmp_path):
    sim = cranesim.Simulation(CRANE_INPUTS, record=True)
    assert sim.recording
    for _ in range(50):
        sim.set_inputs({"slewing": 2.0, "hoist_rope": -0.3})
        sim.step(0.02)
    saved = sim.save_state()
    for _ in range(50):
        sim.step(0.02)
    with sim.write_results(tmp_path / "two.h5") as results:
        assert results.status == "complete"
        np.testing.assert_allclose(results.time(), np.arange(21) * 0.1, atol=1e-12)
        hook_at_two = results.get("joints/load.origin/position")[-1]
    sim.restore_state(saved)
    with sim.write_results(tmp_path / "one.h5") as results:
        assert results.time()[-1] == pytest.approx(1.0, abs=1e-12)
    with cranesim.Results(tmp_path / "one.h5") as results:
        np.testing.assert_allclose(results.get("joints/load.origin/position")[-1],
                                   sim.joint_position("load.origin"), rtol=0, atol=1e-12)
    assert np.linalg.norm(hook_at_two - sim.joint_position("load.origin")) > 0.01


def test_loads_and_energies_are_observed(crane):
    crane.reset()
    scene = yaml.safe_load((ROOT / "configs" / "crane.yaml").read_text())
    load = next(b for b in scene["bodies"] if b["name"] == "load")
    force, moment = crane.constraint_load("hook")  # the load's weight, in equilibrium
    assert np.linalg.norm(force) == pytest.approx(load["mass"] * np.linalg.norm(scene["gravity"]), rel=1e-9)
    assert np.linalg.norm(moment) < 1e-3  # a spherical joint carries no moment
    tension = crane.rope_tension("hoist_rope")
    assert tension.shape[1] == 9 and tension[-1, -1] == pytest.approx(np.linalg.norm(force), rel=1e-6)
    assert crane.energy()["kinetic"] == 0.0
    for _ in range(25):
        crane.set_inputs({"hoist_rope": -0.5})
        crane.step(0.02)
    assert crane.energy()["kinetic"] > 0.0
    # Reeling the hoist rope in under the load: the winch's power is the rope's tension times
    # the speed the input has reached (it follows its command through its lag).
    speed = -crane.input_rates()[list(crane.inputs).index("hoist_rope")]
    assert crane.winch_power("hoist_rope") == pytest.approx(crane.rope_tension("hoist_rope").mean() * speed, rel=0.01)
    assert crane.drive_power("slewing") == 0.0  # not slewing
    assert "hook" in crane.constraints and "load.origin" in crane.joints
    with pytest.raises(ValueError, match="did you mean 'hook'"):
        crane.constraint_load("hok")


def test_a_reeved_ropes_parts_and_winch_are_observed():
    """configs/hook_block.yaml: a 10 t hook block on 4 falls over sheaves of efficiency 0.98. At
    rest every part carries W/4 (one row per part, the lead line first, the falls leaning 0.1 m in
    10 m); hoisting steadily at 0.5 m/s the lead line pulls W (1 − η) / (η (1 − η⁴)), 5.2 % more, and
    the winch's power is that pull times the winch's speed (its sheaves' losses included)."""
    sim = cranesim.Simulation(ROOT / "configs" / "hook_block.yaml")
    weight, eta = 1.0e4 * 9.81, 0.98
    tension = sim.rope_tension("hoist")
    assert tension.shape == (5, 9)
    assert np.allclose(tension, weight / 4, rtol=2e-4, atol=0)
    assert np.ptp(tension) < 1e-9 * weight
    sim.advance_to(5.0)  # the winch reels 4 m in from 1 s to 10 s, steadily from 2 s to 9 s
    tension = sim.rope_tension("hoist")
    pull = weight * (1 - eta) / (eta * (1 - eta**4))
    assert tension[0, 0] == pytest.approx(pull, rel=1e-3)
    assert np.all(np.diff(tension[:, 0]) < 0)  # each sheave passed holds back 2 %
    assert sim.winch_power("hoist") == pytest.approx(pull * 0.5, rel=1e-3)


def test_the_threaded_vector_environment_is_the_synchronous_one_bit_for_bit():
    import gymnasium as gym
    import cranesim.gym

    make = [lambda: gym.make("cranesim/CraneLift-v0", episode_time=1.0)] * 3  # truncated every 50 steps
    synchronous, threaded = gym.vector.SyncVectorEnv(make), cranesim.gym.ThreadedVectorEnv(make, threads=2)
    first, _ = synchronous.reset(seed=5)
    assert np.array_equal(first, threaded.reset(seed=5)[0])
    rng = np.random.default_rng(1)
    resets = 0
    for _ in range(120):
        actions = rng.uniform(-1.0, 1.0, (3, 3)).astype(np.float32)
        expected, got = synchronous.step(actions), threaded.step(actions)
        for a, b in zip(expected[:4], got[:4]):
            assert np.array_equal(a, b)
        resets += int(got[3].sum())
    assert resets >= 6  # through the autoresets
    threaded.close()


def test_a_study_writes_the_command_lines_table(tmp_path):
    import h5py

    study = ROOT / "configs" / "study_rope_pendulum.yaml"
    crane_sim("study", study, "-o", tmp_path / "cli.h5", "--jobs", 2, "--quiet")
    with cranesim.study(study, tmp_path / "py.h5", jobs=2) as table, h5py.File(tmp_path / "cli.h5") as cli:
        for path in ("figures/ball_sway", "figures/hook_tension_max", "cases/steps", "parameters/bodies.ball.mass"):
            assert np.array_equal(table.get(path), cli[path][()]), path
    with pytest.raises(cranesim.SceneError) as error:
        cranesim.study(ROOT / "tests" / "data" / "bad_studies" / "criterion_without_bound.yaml", tmp_path / "bad.h5")
    assert error.value.line is not None and not (tmp_path / "bad.h5").exists()


INTERRUPTED_AFTER_1_S = """
import os, signal, sys, threading, time
import cranesim
analysis, source, out = sys.argv[1:4]
threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT)).start()
start = time.monotonic()
try:
    getattr(cranesim, analysis)(source, out)
except KeyboardInterrupt:
    print(time.monotonic() - start)
"""


def interrupted_after_1_s(analysis, source, out):
    """cranesim.<analysis>(source, out) in a new process that sends itself SIGINT after 1 s: the
    wall time from the call to KeyboardInterrupt (fails if it was not raised)."""
    result = subprocess.run([sys.executable, "-c", INTERRUPTED_AFTER_1_S, analysis, str(source), str(out)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0 and result.stdout.strip(), result.stderr
    return float(result.stdout)


def test_ctrl_c_stops_a_run_and_a_study_as_it_stops_the_command_line(tmp_path):
    import h5py

    scene = tmp_path / "long.yaml"  # about a minute of computing
    scene.write_text(re.sub(r"(?m)^(\s+t_end:).*$", r"\1 1.0e4", (ROOT / "configs" / "pendulum.yaml").read_text()))
    assert interrupted_after_1_s("run", scene, tmp_path / "long.h5") < 3.0
    with h5py.File(tmp_path / "long.h5") as f:
        assert f.attrs["status"] == "incomplete" and f.attrs["message"].startswith("interrupted at t = ")
        assert f["time"].shape[0] > 10

    study = tmp_path / "study.yaml"  # 6 cases of 8 s swings: several seconds
    study.write_text((ROOT / "configs" / "study_rope_pendulum.yaml").read_text()
                     .replace("scene: rope_pendulum.yaml", f"scene: {ROOT / 'configs' / 'rope_pendulum.yaml'}")
                     .replace("values: [2]", "values: [8]"))
    out = tmp_path / "study.h5"
    assert interrupted_after_1_s("study", study, out) < 3.0
    with h5py.File(out) as f:
        assert f.attrs["status"] == "incomplete" and "--resume" in f.attrs["message"]
        finished = list(f["cases/status"].asstr()[...]).count("complete")
    assert finished < 6
    cranesim.study(study, out, resume=True).close()
    with h5py.File(out) as f:
        assert list(f["cases/status"].asstr()[...]).count("complete") == 6


def test_the_sway_axis_controller_commands_its_gains_feedback():
    from cranesim.control import SwayAxis

    axis = SwayAxis()
    error = np.array([0.3, -0.1, 0.01, -0.002])  # position, speed, angle, angle rate
    command = axis.command(40.0, *error)
    assert axis.design_length == 40.0 and axis.gain.shape == (4,)
    assert command == pytest.approx(-axis.gain @ error, rel=1e-13)
    assert axis.closed_loop_spectral_radius < 1.0


def cli_and_python_hook_swing(scene, tmp_path, step):
    """Runs `scene` by `crane-sim run` and as a Python loop that calls step(sim, t) at every 20 ms
    sample before advancing; asserts that both give the same hook path bit for bit, and returns
    the sample times and the hook's horizontal swing about the boom head's sheave."""
    import h5py

    crane_sim("run", scene, "-o", tmp_path / "cli.h5", "--quiet")
    sim = cranesim.Simulation(scene, record=True)
    k = 0
    while True:
        step(sim, k * 0.02)
        k += 1
        if not sim.advance_to(min(k * 0.02, sim.t_end)):
            break
    sim.write_results(tmp_path / "py.h5").close()
    with h5py.File(tmp_path / "cli.h5") as cli, h5py.File(tmp_path / "py.h5") as py:
        hook = "joints/load.origin/position"
        assert cli.attrs["status"] == "complete" and np.array_equal(cli[hook][()], py[hook][()])
        swing = np.linalg.norm((cli[hook][()] - cli["joints/head.sheave/position"][()])[:, :2], axis=1)
        return cli["time"][()], swing


def test_a_scenes_feedback_runs_as_the_python_loop_it_stands_for(tmp_path):
    """crane-sim run of configs/crane_anti_sway.yaml — the lever's speeds set on the inputs every
    20 ms until 20 s, then AntiSway holding the head — and the same loop in Python give the same
    hook path bit for bit; the swing is then damped to a few centimetres."""
    from cranesim.control import AntiSway

    controller = None

    def step(sim, t):
        nonlocal controller
        lever = {"slewing": 3.0 if t < 15.0 else 0.0, "hoist_rope": -0.3 if t < 20.0 else 0.0}
        if t >= 20.0:
            controller = controller or AntiSway(sim)
            controller.apply(slewing=lever["slewing"], hoist=lever["hoist_rope"])
        else:
            sim.set_inputs(lever)

    time, swing = cli_and_python_hook_swing(ROOT / "configs" / "crane_anti_sway.yaml", tmp_path, step)
    assert swing[time > 50.0].max() < 0.05  # 0.019 m in the last 10 s (open loop: 1.1 m)


def test_operator_assistance_from_a_scene_runs_as_the_python_loop_and_stops_the_load_within_5_cm(tmp_path):
    """crane-sim run of configs/crane_operator_assist.yaml — a lever's stop-and-go slew and hoist
    with a reversal through AntiSway with shaping — and the same loop in Python give the same
    hook path bit for bit; from 5 s after each of the crane's stops (the lever's stop, its 1.5 s
    ramp and half the 17.1 s sway period later) until it moves again the load is within 5 cm."""
    from cranesim.control import AntiSway

    controller = None

    def step(sim, t):
        nonlocal controller
        controller = controller or AntiSway(sim, shaping=17.1, boom_period=1.4)
        controller.apply(slewing=3.0 if t < 8.0 else -3.0 if 26.0 <= t < 32.0 else 0.0,
                         hoist=-0.3 if 2.0 <= t < 10.0 else 0.3 if 28.0 <= t < 34.0 else 0.0)

    time, swing = cli_and_python_hook_swing(ROOT / "configs" / "crane_operator_assist.yaml", tmp_path, step)
    for stop, restart in ((8.0 + 1.5 + 8.56, 26.0), (32.0 + 1.5 + 8.56, 60.0)):
        after = (time > stop + 5.0) & (time <= restart)
        assert swing[after].max() < 0.05  # 0.024 m and 0.016 m (0.54 m on the way; 2–4 m driven by the lever directly)
    assert swing.max() > 0.3


def test_a_scenes_late_noisy_sensor_runs_as_the_python_loop_and_still_damps_the_swing(tmp_path):
    """configs/crane_anti_sway.yaml with the rope's angles read 0.1 s late with 2 mrad and
    2 mrad/s of noise: crane-sim run and the Python loop with the same SwaySensor give the same
    hook path bit for bit (the same seeded noise), and the swing is still damped to centimetres;
    a sensor with a negative delay is refused as Python's ValueError."""
    from cranesim.control import AntiSway, SwaySensor

    scene = tmp_path / "sensor.yaml"
    sensor = {"angle_noise": 0.002, "rate_noise": 0.002, "delay": 0.1, "seed": 3}
    scene.write_text(f"base: {ROOT / 'configs' / 'crane_anti_sway.yaml'}\n"
                     "feedback:\n"
                     "  type: anti_sway\n"
                     "  start: 20\n"
                     "  sensor: {angle_noise: 0.002, rate_noise: 0.002, delay: 0.1, seed: 3}\n"
                     "  references:\n"
                     "    slewing: {type: table, t: [0, 15], value: [3, 0], interpolation: step}\n"
                     "    hoist_rope: {type: table, t: [0, 20], value: [-0.3, 0], interpolation: step}\n")
    controller = None

    def step(sim, t):
        nonlocal controller
        lever = {"slewing": 3.0 if t < 15.0 else 0.0, "hoist_rope": -0.3 if t < 20.0 else 0.0}
        if t >= 20.0:
            controller = controller or AntiSway(sim, sensor=SwaySensor(**sensor))
            controller.apply(slewing=lever["slewing"], hoist=lever["hoist_rope"])
        else:
            sim.set_inputs(lever)

    time, swing = cli_and_python_hook_swing(scene, tmp_path, step)
    assert swing[time > 50.0].max() < 0.08  # 0.054 m in the last 10 s (exact sensor 0.018 m, open loop 1.1 m)
    with pytest.raises(ValueError, match="delay must be 0 or positive"):
        AntiSway(cranesim.Simulation(scene), sensor=SwaySensor(delay=-0.1))


def test_a_feedback_on_a_joint_the_scene_lacks_is_bad_input(tmp_path):
    scene = tmp_path / "hook.yaml"
    scene.write_text(f"base: {ROOT / 'configs' / 'crane_anti_sway.yaml'}\n"
                     "feedback: {type: anti_sway, hook: load.hok}\n")
    result = subprocess.run([str(ROOT / "build" / "crane-sim"), "run", str(scene), "-o", str(tmp_path / "out.h5")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert f"error: {scene}: feedback (line 2, column 11): no joint named 'load.hok'" in result.stderr, result.stderr
    assert not (tmp_path / "out.h5").exists()
