"""scripts/study_table.py on a small synthetic case table (the layout of docs/study-format.md), in process."""

import csv
import importlib.util
import os
from pathlib import Path

import h5py
import numpy as np
import pytest

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()


@pytest.fixture(scope="module")
def study_table():
    spec = importlib.util.spec_from_file_location("study_table", SOURCE_DIR / "scripts" / "study_table.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def write_table(path: Path) -> Path:
    """Three cases of a load study with one criterion: admissible, violated, and a failed case."""
    strings = h5py.string_dtype()
    with h5py.File(path, "w") as f:
        f.attrs.update({"contents": "study", "cases": 3, "status": "complete"})
        f["parameters/bodies.load.mass"] = [1.0e4, 2.0e4, 3.0e4]
        f["figures/hook_tension_max"] = [1.0e5, 2.5e5, np.nan]
        f["criteria/0"] = [1.0, 0.0, np.nan]
        f["cases/admissible"] = [1.0, 0.0, np.nan]
        f.create_dataset("cases/status", data=["complete", "complete", "failed"], dtype=strings)
        f.create_dataset("cases/message", data=["", "", "solver failure at t = 1 s"], dtype=strings)
    return path


def test_prints_one_row_per_case_with_parameters_figures_and_status(study_table, tmp_path, capsys):
    assert study_table.main([str(write_table(tmp_path / "table.h5"))]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split() == ["case", "bodies.load.mass", "hook_tension_max", "admissible", "status", "message"]
    assert lines[1].split() == ["0", "10000", "100000", "1", "complete"]
    assert lines[2].split() == ["1", "20000", "250000", "0", "complete"]
    assert lines[3].split() == ["2", "30000", "nan", "nan", "failed", "solver", "failure", "at", "t", "=", "1", "s"]


def test_status_filter_and_csv(study_table, tmp_path):
    output = tmp_path / "complete.csv"
    assert study_table.main([str(write_table(tmp_path / "table.h5")), "--status", "complete", "--csv", str(output)]) == 0
    with open(output, newline="") as f:
        rows = list(csv.DictReader(f))
    assert [row["case"] for row in rows] == ["0", "1"]
    assert [float(row["hook_tension_max"]) for row in rows] == [1.0e5, 2.5e5]


def test_a_file_that_is_not_a_study_is_refused(study_table, tmp_path, capsys):
    with h5py.File(tmp_path / "results.h5", "w") as f:
        f["time"] = [0.0]
    assert study_table.main([str(tmp_path / "results.h5")]) == 2
    assert study_table.main([str(tmp_path / "absent.h5")]) == 2
    assert capsys.readouterr().err.count("study_table.py: error:") == 2


def test_the_least_stable_angle_columns(study_table, tmp_path, capsys):
    path = write_table(tmp_path / "table.h5")
    with h5py.File(path, "a") as f:
        f["least_stable/angle"] = [14.04, 0.0, np.nan]
        f["least_stable/grid_angle"] = [22.5, 0.0, 45.0]
        f["least_stable/value"] = [0.52, 0.61, np.nan]
    assert study_table.main([str(path)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split()[4:6] == ["least_stable_angle", "worst_grid_angle"]
    assert lines[1].split()[4:6] == ["14.04", "22.5"]
    assert lines[3].split()[4:6] == ["nan", "45"]
