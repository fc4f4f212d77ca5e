"""What every bad-input file (tests/data/bad_scenes, bad_targets, bad_studies) declares and what its
rejection must look like. Each file's first two lines say what the error must contain and which
YAML path it must name:

    # expect: <substring of the error message>
    # path: <YAML path the error is reported at, e.g. bodies[0].mass or <document>>
"""

import re
import subprocess
from pathlib import Path

EXIT_BAD_INPUT = 2


def expectations(bad_file: Path) -> tuple[str, str]:
    lines = bad_file.read_text(encoding="utf-8").splitlines()
    expect = re.fullmatch(r"# expect: (.+)", lines[0])
    path = re.fullmatch(r"# path: (.+)", lines[1])
    assert expect and path, f"{bad_file.name} must start with '# expect: ...' and '# path: ...' lines"
    return expect[1].strip(), path[1].strip()


def assert_collection(bad_files: list[Path], minimum: int) -> None:
    """The collection holds at least `minimum` files, each declaring its expectations."""
    assert len(bad_files) >= minimum
    for bad_file in bad_files:
        expectations(bad_file)


def assert_reported(result: subprocess.CompletedProcess, bad_file: Path, expect: str, path: str) -> None:
    """Exit 2, and an error naming the file, the YAML path with its line and column, and the problem."""
    assert result.returncode == EXIT_BAD_INPUT, result.stderr
    assert expect in result.stderr
    location = re.escape(f"error: {bad_file}: {path} (line ") + r"\d+, column \d+\): "
    assert re.search(location, result.stderr), f"path '{path}' not reported in:\n{result.stderr}"
    assert "Traceback" not in result.stderr and "terminate called" not in result.stderr
