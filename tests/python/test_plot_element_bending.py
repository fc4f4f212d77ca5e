"""Command-line behaviour of benchmarks/plot_element_bending.py on small synthetic CSV files."""

import subprocess
import sys

from conftest import SCRIPTS

BENCHMARKS = SCRIPTS.parent / "benchmarks"

HEADER = ("type,segments,K,bend_per_segment_deg,strategy,converged,newton_iterations,load_steps,"
          "wall_time_s_median,cpu_time_s_median,tip_error_rel,rotation_error_rad")
ROWS = [
    "timoshenko,3,0.1,12,direct,1,25,1,0.3,0.2,0.0018,5e-12",
    "timoshenko,3,0.5,60,direct,1,150,2,1.9,1.2,0.030,0",
    "timoshenko,3,0.5,60,continuation,1,131,2,1.6,1.1,0.030,2.6e-11",
    "spline_beam,3,0.1,12,direct,1,27,1,0.11,0.1,3.9e-06,5.3e-06",
    "spline_beam,3,0.5,60,direct,1,136,2,0.57,0.5,0.013,0.033",
    "spline_beam,1,1,360,direct,0,800,0,2.0,1.9,nan,nan",
]


def run(*arguments):
    return subprocess.run([sys.executable, str(BENCHMARKS / "plot_element_bending.py"), *map(str, arguments)],
                          capture_output=True, text=True, timeout=60)


def test_plots_a_study_with_failed_cases_and_zero_errors(tmp_path):
    data = tmp_path / "bending.csv"
    data.write_text("\n".join([HEADER, *ROWS]) + "\n")
    for arguments, image in (((data,), tmp_path / "bending.png"),
                             ((data, "--time", "cpu", "-o", tmp_path / "cpu.png"), tmp_path / "cpu.png")):
        result = run(*arguments)
        assert result.returncode == 0, result.stderr
        assert image.is_file() and image.stat().st_size > 1000
        assert image.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_malformed_csv_is_a_clean_error(tmp_path):
    missing_column = tmp_path / "missing.csv"
    missing_column.write_text("type,segments,K\ntimoshenko,3,0.1\n")
    bad_value = tmp_path / "bad.csv"
    bad_value.write_text("\n".join([HEADER, ROWS[0].replace(",25,", ",many,")]) + "\n")
    nothing_converged = tmp_path / "failed.csv"
    nothing_converged.write_text("\n".join([HEADER, ROWS[-1]]) + "\n")
    for path, fragment in ((missing_column, "missing column(s)"), (bad_value, "column 'newton_iterations'"),
                           (nothing_converged, "no converged case"), (tmp_path / "absent.csv", "cannot read")):
        result = run(path)
        assert result.returncode == 2, path
        assert "Traceback" not in result.stderr and fragment in result.stderr, result.stderr


def test_help_has_usage_and_example():
    result = run("--help")
    assert result.returncode == 0
    assert "usage:" in result.stdout and "Example" in result.stdout
