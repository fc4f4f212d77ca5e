"""docs/performance.md is what benchmarks/performance_doc.py makes of benchmarks/results/, and
--check notices a result file the page quotes going missing."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GENERATOR = ROOT / "benchmarks" / "performance_doc.py"
RESULTS = ROOT / "benchmarks" / "results"
PAGE = ROOT / "docs" / "performance.md"


def generator():
    spec = importlib.util.spec_from_file_location("performance_doc", GENERATOR)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def check(results: Path, output: Path):
    return subprocess.run([sys.executable, str(GENERATOR), "--check", "--results", str(results), "--output", str(output)],
                          capture_output=True, text=True, timeout=30)


def quoted_results() -> list[str]:
    """Every file of benchmarks/results/ that the page names, in the order the page names them."""
    if not PAGE.is_file():
        return []
    text = PAGE.read_text(encoding="utf-8")
    names = [path.name for path in RESULTS.iterdir() if f"../benchmarks/results/{path.name})" in text]
    return sorted(names, key=lambda name: text.index(f"../benchmarks/results/{name})"))


def test_page_is_the_generators_output():
    module = generator()
    results = module.Results(RESULTS)
    text = module.render(results)
    assert results.missing == []
    assert PAGE.read_text(encoding="utf-8") == text, "docs/performance.md is stale: run python3 benchmarks/performance_doc.py"
    run = check(RESULTS, PAGE)
    assert run.returncode == 0, run.stderr


def test_check_fails_on_an_edited_page(tmp_path):
    page = tmp_path / "performance.md"
    page.write_text(PAGE.read_text(encoding="utf-8").replace("| super truss |", "| super-truss |", 1), encoding="utf-8")
    run = check(RESULTS, page)
    assert run.returncode == 1
    assert "performance_doc.py" in run.stderr and "super-truss" in run.stderr


def test_page_quotes_every_benchmark_csv():
    quoted = quoted_results()
    for name in ("crane_work_precision.csv", "crane_fidelities.csv", "equilibrium_grid.csv", "map_parallel.csv",
                 "jacobian_ratio.csv", "truss_reduction.csv", "element_bending.csv", "slender_statics.csv",
                 "element_vibration.csv", "pendulum_chain.csv"):
        assert name in quoted


@pytest.mark.parametrize("missing", quoted_results())
def test_check_names_a_missing_result(tmp_path, missing):
    copy = tmp_path / "results"
    copy.mkdir()
    for path in RESULTS.iterdir():
        if path.name != missing:
            (copy / path.name).symlink_to(path)
    run = check(copy, PAGE)
    assert run.returncode == 1
    assert missing in run.stderr and "missing" in run.stderr
    assert not (copy / "performance.md").exists()
