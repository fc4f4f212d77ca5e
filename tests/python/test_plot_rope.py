"""scripts/plot_rope.py on a real run: crane-sim drops the ball of configs/rope_drop.yaml on
its slack rope (shortened to the first catch) and the script plots the load and the tension.

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
SCRIPT = SOURCE_DIR / "scripts" / "plot_rope.py"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def drop_results(tmp_path_factory) -> Path:
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    directory = tmp_path_factory.mktemp("rope")
    scene = (SOURCE_DIR / "configs" / "rope_drop.yaml").read_text()
    scene = scene.replace("t_end: 2\n", "t_end: 0.7\n").replace("interval: 0.001", "interval: 0.002")
    (directory / "drop.yaml").write_text(scene)
    run = subprocess.run([str(BINARY), "run", "drop.yaml", "-o", "drop.h5", "--quiet"], cwd=directory,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    return directory / "drop.h5"


def plot(*arguments) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, arguments)], capture_output=True,
                          text=True, timeout=60)


def test_plot_of_the_rope_catching_the_ball(drop_results, tmp_path):
    output = tmp_path / "rope.png"
    result = plot(drop_results, "-o", output)
    assert result.returncode == 0, result.stderr
    assert output.read_bytes().startswith(PNG_SIGNATURE) and output.stat().st_size > 1000
    peak = float(re.search(r"peak tension at ball\.origin: (\S+) N", result.stdout).group(1))
    # Massless Kelvin–Voigt rope (η = 1e-3 s): 346 kN; the energy estimate (undamped): 361 kN.
    assert 300e3 < peak < 380e3
    lowest = float(re.search(r"ball\.origin height: (\S+) \.\.", result.stdout).group(1))
    assert -10.13 < lowest < -10.09  # 10 m rope stretched by about 0.11 m


def test_unknown_rope_is_a_clean_error(drop_results):
    result = plot(drop_results, "--rope", "hoist")
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert "no member 'hoist'" in result.stderr and "rope" in result.stderr
