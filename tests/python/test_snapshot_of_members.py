"""scripts/plot_snapshot.py on a real run whose mechanism is drawn by flexible members only (a
condensed truss cantilever, no rigid body): no body segments to colour, one grey line per
member segment.

Environment: CRANESIM_BIN (default <repo>/build/crane-sim) and CRANESIM_SOURCE_DIR.
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()
SCRIPT = SOURCE_DIR / "scripts" / "plot_snapshot.py"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def test_snapshot_of_a_truss_without_rigid_bodies(tmp_path):
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    base = SOURCE_DIR / "configs" / "truss_type2_condensed.yaml"
    (tmp_path / "short.yaml").write_text(f"base: {base}\nmodify:\n  solver.t_end: 0.05\n")
    run = subprocess.run([str(BINARY), "run", "short.yaml", "-o", "truss.h5", "--quiet"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    plot = subprocess.run([sys.executable, str(SCRIPT), "truss.h5", "-o", "truss.png"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert plot.returncode == 0, plot.stderr
    assert "t = 0.05 s" in plot.stdout
    assert (tmp_path / "truss.png").read_bytes().startswith(PNG_SIGNATURE)
