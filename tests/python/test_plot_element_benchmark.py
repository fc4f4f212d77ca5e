"""Command-line behaviour of benchmarks/plot_element_benchmark.py and scripts/plot_beam_tip.py on
small synthetic inputs."""

import subprocess
import sys

import h5py
import numpy as np

from conftest import SCRIPTS

BENCHMARKS = SCRIPTS.parent / "benchmarks"

HEADER = ("case,element,segments,rtol,damping,wall_time_s_median,cpu_time_s,steps,residual_evals,"
          "jacobian_evals,error_test_failures,tip_error_m,tip_error_cross_m,completed")
ROWS = [
    "vibration,timoshenko,3,0.0001,0.0001,0.5,0.6,900,2000,100,20,0.003,0.004,1",
    "vibration,timoshenko,3,1e-06,0.0001,1.5,1.6,3000,6000,200,30,2e-05,0.001,1",
    "vibration,spline_beam,3,1e-06,0.0001,2.5,2.6,5000,9000,300,40,4e-05,0.001,1",
    "rotation,timoshenko,1,1e-06,0,0.2,0.2,800,1500,90,10,0.1,0.2,1",
    "rotation,spline_beam,1,1e-06,0,900,900,90000,200000,9000,9000,nan,nan,0",
]


def run(script, *arguments):
    directory = BENCHMARKS if script == "plot_element_benchmark.py" else SCRIPTS
    return subprocess.run([sys.executable, str(directory / script), *map(str, arguments)],
                          capture_output=True, text=True, timeout=60)


def assert_png(path):
    assert path.is_file() and path.stat().st_size > 1000
    assert path.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_work_precision_plot_with_a_failed_case(tmp_path):
    data = tmp_path / "vibration.csv"
    data.write_text("\n".join([HEADER, *ROWS]) + "\n")
    result = run("plot_element_benchmark.py", data)
    assert result.returncode == 0, result.stderr
    assert_png(tmp_path / "vibration.png")


def test_malformed_benchmark_csv_is_a_clean_error(tmp_path):
    missing_column = tmp_path / "missing.csv"
    missing_column.write_text("case,element\nvibration,timoshenko\n")
    bad_value = tmp_path / "bad.csv"
    bad_value.write_text("\n".join([HEADER, ROWS[0].replace(",900,", ",many,")]) + "\n")
    nothing_completed = tmp_path / "failed.csv"
    nothing_completed.write_text("\n".join([HEADER, ROWS[-1]]) + "\n")
    for path, fragment in ((missing_column, "missing column(s)"), (bad_value, "column 'steps'"),
                           (nothing_completed, "no completed case"), (tmp_path / "absent.csv", "cannot read")):
        result = run("plot_element_benchmark.py", path)
        assert result.returncode == 2, path
        assert "Traceback" not in result.stderr and fragment in result.stderr, result.stderr


def beam_results(path, spin_rate):
    """A 15 m beam turning rigidly about y at `spin_rate` rad/s, tip bent by 0.1 m in its root frame."""
    t = np.linspace(0.0, 2.0, 51)
    angle = spin_rate * t
    c, s, zero, one = np.cos(angle), np.sin(angle), np.zeros_like(t), np.ones_like(t)
    rotation = np.stack([np.stack([c, zero, s], -1), np.stack([zero, one, zero], -1),
                         np.stack([-s, zero, c], -1)], -2)
    tip = np.einsum("nij,j->ni", rotation, np.array([15.0, 0.0, 0.1]))
    with h5py.File(path, "w") as f:
        f.attrs["status"] = "complete"
        f["time"] = t
        f["joints/beam.start/position"] = np.zeros((t.size, 3))
        f["joints/beam.start/rotation"] = rotation
        f["joints/beam.end/position"] = tip


def test_beam_tip_plot_of_two_runs(tmp_path):
    beam_results(tmp_path / "slow.h5", 0.5)
    beam_results(tmp_path / "fast.h5", 2.0)
    image = tmp_path / "tip.png"
    result = run("plot_beam_tip.py", tmp_path / "slow.h5", tmp_path / "fast.h5", "--labels", "slow,fast",
                 "-o", image)
    assert result.returncode == 0, result.stderr
    assert_png(image)
    wrong_member = run("plot_beam_tip.py", tmp_path / "slow.h5", "--member", "boom", "-o", image)
    assert wrong_member.returncode == 2 and "boom.start" in wrong_member.stderr
    assert "Traceback" not in wrong_member.stderr


def test_help_has_usage_and_example():
    for script in ("plot_element_benchmark.py", "plot_beam_tip.py"):
        result = run(script, "--help")
        assert result.returncode == 0, script
        assert "usage:" in result.stdout and "Example" in result.stdout, script
