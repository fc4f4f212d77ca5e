"""Command-line behaviour of the plotting and report scripts in scripts/."""

import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import (
    ENERGY_DRIFT, INCOMPLETE_MESSAGE, LINK_LENGTH, MAX_POSITION_RESIDUAL, MAX_VELOCITY_RESIDUAL,
    SAMPLES, SCRIPTS, SOLVER_STEPS, pendulum,
)
from cranesim.results import Results, ResultsError, guess_unit

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
GIF_SIGNATURE = b"GIF8"


def run(script: str, *arguments, env=None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPTS / script), *map(str, arguments)],
                          capture_output=True, text=True, timeout=60, env=env)


def assert_image(path, signature: bytes) -> None:
    assert path.is_file() and path.stat().st_size > 1000
    assert path.read_bytes().startswith(signature)


def assert_clean_error(result: subprocess.CompletedProcess, *fragments: str) -> None:
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    for fragment in fragments:
        assert fragment in result.stderr


def test_reader_selects_components_and_norm(results_file):
    with Results(results_file) as results:
        tip = pendulum(results.time())["tip"]
        np.testing.assert_allclose(results.get("joints/link2.tip/position[2]"), tip[:, 2])
        np.testing.assert_allclose(results.get("/joints/link2.tip/position[norm]"),
                                   np.linalg.norm(tip, axis=1))
        np.testing.assert_allclose(results.get("joints/link1.tip/position[norm]"), LINK_LENGTH)
        assert results.get("lambda[0]").shape == (SAMPLES,)
        assert results.get("bodies/link1/angular_velocity[1]").shape == (SAMPLES,)
        with pytest.raises(ResultsError, match=r"component 3 .* out of range"):
            results.get("bodies/link1/position[3]")


def test_units_are_guessed_from_the_path():
    assert guess_unit("joints/link3.tip/position[2]") == "m"
    assert guess_unit("bodies/link1/velocity") == "m/s"
    assert guess_unit("bodies/link1/angular_velocity[1]") == "rad/s"
    assert guess_unit("energy/balance") == "J"
    assert guess_unit("lambda[0]") == "N, N·m"
    assert guess_unit("residual/position") == "-"
    assert guess_unit("supports/tracks/left/peak_pressure") == "Pa"
    assert guess_unit("supports/pads/front_left/force") == "N"
    assert guess_unit("supports/tracks/left/peak_at") == "m"
    assert guess_unit("supports/margin") == "N·m"


def test_reader_lists_contents(results_file):
    result = subprocess.run([sys.executable, "-m", "cranesim.results", str(results_file)],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0 and result.stderr == "", result.stderr  # no warning about a module run twice
    assert "/joints/link2.tip/position  (41, 3)" in result.stdout
    assert "@status = 'complete'" in result.stdout


def test_timeseries_compares_files_and_warns_on_incomplete(results_file, incomplete_results_file,
                                                          tmp_path):
    output = tmp_path / "compare.png"
    result = run("plot_timeseries.py", f"{results_file},{incomplete_results_file}",
                 "energy/balance", "joints/link2.tip/position[2]", "-o", output,
                 "--title", "comparison")
    assert result.returncode == 0, result.stderr
    assert_image(output, PNG_SIGNATURE)
    assert "warning" in result.stderr and "INCOMPLETE" in result.stderr
    assert INCOMPLETE_MESSAGE in result.stderr


def test_timeseries_subplots_with_default_output_name(results_file):
    result = run("plot_timeseries.py", results_file, "lambda", "bodies/link1/velocity[norm]",
                 "residual/position", "--subplots")
    assert result.returncode == 0, result.stderr
    assert_image(results_file.with_name("pendulum_timeseries.png"), PNG_SIGNATURE)


def test_timeseries_unknown_quantity_names_it_and_suggests(results_file, tmp_path):
    result = run("plot_timeseries.py", results_file, "joints/link3.tip/position[2]",
                 "-o", tmp_path / "never.png")
    assert_clean_error(result, "joints/link3.tip/position", "did you mean",
                       "joints/link2.tip/position")
    assert len(result.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "never.png").exists()


def test_snapshot_at_requested_time(results_file, tmp_path):
    output = tmp_path / "snapshot.png"
    result = run("plot_snapshot.py", results_file, "--time", 1.01, "-o", output)
    assert result.returncode == 0, result.stderr
    assert "t = 1 s" in result.stdout
    assert_image(output, PNG_SIGNATURE)


def test_animation_gif(results_file, tmp_path):
    output = tmp_path / "pendulum.gif"
    result = run("animate.py", results_file, "-o", output, "--every", 15, "--fps", 5,
                 "--view", 10, -80)
    assert result.returncode == 0, result.stderr
    assert "4 frames" in result.stdout  # samples 0, 15, 30 and the last one
    assert_image(output, GIF_SIGNATURE)


def test_animation_mp4_without_ffmpeg_is_refused(results_file, tmp_path):
    environment = {**os.environ, "PATH": str(tmp_path)}
    result = run("animate.py", results_file, "-o", tmp_path / "movie.mp4", env=environment)
    assert_clean_error(result, ".mp4", "ffmpeg")


def test_report_numbers(results_file):
    result = run("report.py", results_file)
    assert result.returncode == 0, result.stderr
    lines = dict(line.strip().partition(":")[::2] for line in result.stdout.splitlines())
    lines = {key: value.strip() for key, value in lines.items()}
    assert lines["status"] == "complete"
    assert lines["samples"] == str(SAMPLES)
    assert lines["time span"].startswith("0 .. 2 s")
    assert lines["steps"] == str(SOLVER_STEPS)
    assert float(lines["relative energy drift"]) == pytest.approx(ENERGY_DRIFT, rel=1e-6)
    assert float(lines["max position residual"]) == pytest.approx(MAX_POSITION_RESIDUAL)
    assert float(lines["max velocity residual"]) == pytest.approx(MAX_VELOCITY_RESIDUAL)


def test_report_of_incomplete_run(incomplete_results_file):
    result = run("report.py", incomplete_results_file)
    assert result.returncode == 0, result.stderr
    assert "status: incomplete" in result.stdout
    assert INCOMPLETE_MESSAGE in result.stdout
    assert "warning" in result.stderr


def test_missing_and_non_hdf5_files_are_clean_errors(tmp_path):
    not_hdf5 = tmp_path / "notes.h5"
    not_hdf5.write_text("not a results file")
    assert_clean_error(run("report.py", tmp_path / "absent.h5"), "no such results file",
                       "absent.h5")
    assert_clean_error(run("report.py", not_hdf5), "not an HDF5 file", "notes.h5")


def test_every_script_has_help_with_example():
    commands = {script: [str(SCRIPTS / script)] for script in
                ["plot_timeseries.py", "plot_snapshot.py", "animate.py", "report.py"]}
    commands["cranesim.results"] = ["-m", "cranesim.results"]
    scripts = list(commands)
    # Started together: each one pays the matplotlib import on its own.
    processes = [subprocess.Popen([sys.executable, *commands[script], "--help"],
                                  stdout=subprocess.PIPE, text=True) for script in scripts]
    for script, process in zip(scripts, processes):
        help_text, _ = process.communicate(timeout=60)
        assert process.returncode == 0, script
        assert "usage:" in help_text and "Example" in help_text, script


def test_load_plot_and_sway_period(results_file, tmp_path):
    from plot_load import sway_period
    time = np.linspace(0.0, 60.0, 601)
    direction = np.array([0.6, 0.8])
    velocity = np.outer(0.3 * np.sin(2 * np.pi * time / 15.0 + 0.4), direction) + [0.01, -0.02]
    period, crossings = sway_period(time, velocity)
    assert period == pytest.approx(15.0, rel=1e-3)
    assert crossings == 8

    out = tmp_path / "link.png"
    result = run("plot_load.py", results_file, "--body", "link1", "-o", out)
    assert result.returncode == 0, result.stderr
    assert_image(out, PNG_SIGNATURE)
    assert "max |y - y0|" in result.stdout

    assert_clean_error(run("plot_load.py", results_file, "--body", "hook"), "no body 'hook'")
    assert_clean_error(run("plot_load.py", results_file, "--body", "link1", "--pivot", "link1.tip"),
                       "--pivot needs --sway-after")
    assert_clean_error(run("plot_load.py", results_file, "--body", "link1", "--sway-after", "0"),
                       "fewer than 3 zero crossings")
