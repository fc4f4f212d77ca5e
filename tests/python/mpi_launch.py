"""Running a tool under mpirun in the tests (test_study.py, test_crane_opt.py)."""

import os
import subprocess
from pathlib import Path


def mpirun(binary: Path, ranks: int, *arguments, cwd: Path) -> subprocess.CompletedProcess:
    """`mpirun -n ranks binary arguments…` (oversubscribed: the test machine may have fewer cores)."""
    launcher = ["mpirun", "--oversubscribe", "-n", str(ranks)]
    if os.geteuid() == 0:
        launcher.insert(1, "--allow-run-as-root")
    return subprocess.run(launcher + [str(binary), *map(str, arguments)], capture_output=True, text=True, cwd=cwd,
                          timeout=300)
