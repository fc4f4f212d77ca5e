"""scripts/plot_section_forces.py on a real run: crane-sim slews configs/jib_fidelities.yaml (a
15 m lattice jib, tube by tube, 10 t on an 8 m rope) with the jib's section forces recorded, and
the script plots every tube's axial force and their ranges.

Environment: CRANESIM_BIN (default <repo>/build/crane-sim) and CRANESIM_SOURCE_DIR.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()
SCRIPT = SOURCE_DIR / "scripts" / "plot_section_forces.py"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def crane_sim(directory: Path, name: str, modify: str) -> Path:
    (directory / f"{name}.yaml").write_text(f"base: {SOURCE_DIR / 'configs' / 'jib_fidelities.yaml'}\nmodify: {{{modify}}}\n")
    run = subprocess.run([str(BINARY), "run", f"{name}.yaml", "-o", f"{name}.h5", "--quiet"], cwd=directory,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    return directory / f"{name}.h5"


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> dict:
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    directory = tmp_path_factory.mktemp("section_forces")
    return {"forces": crane_sim(directory, "forces", "output.section_forces: [jib], solver.t_end: 1"),
            "none": crane_sim(directory, "none", "members.jib.fidelity: condensed, solver.t_end: 0.2")}


def plot(*arguments) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, arguments)], capture_output=True, text=True, timeout=60)


def test_plot_of_the_jib_tubes(runs, tmp_path):
    output = tmp_path / "jib.png"
    result = plot(runs["forces"], "-o", output)
    assert result.returncode == 0, result.stderr
    assert output.read_bytes().startswith(PNG_SIGNATURE) and output.stat().st_size > 10000
    pulled = re.search(r"largest tension: (\S+) N in (\S+) – (\S+) at", result.stdout)
    pressed = re.search(r"largest compression: (\S+) N in (\S+) – (\S+) at", result.stdout)
    # The root chords: about half the root moment (2.17 MN·m) over the 2.8 m between them, each
    # of the two top ones pulled and the two bottom ones pressed (tests/elements/test_section_forces.cpp).
    assert pulled and pressed, result.stdout
    assert 3.0e5 < float(pulled.group(1)) < 6.0e5 and pulled.group(2).startswith("jib.s1n")
    assert 3.0e5 < float(pressed.group(1)) < 6.0e5 and pressed.group(2).startswith("jib.s1n")


def test_missing_forces_are_clean_errors(runs):
    for arguments, expected in [((runs["forces"], "--member", "rope"), "no section forces of 'rope'"),
                                ((runs["none"],), "records no section forces")]:
        result = plot(*arguments)
        assert result.returncode == 2, result.stderr
        assert expected in result.stderr and "Traceback" not in result.stderr
