"""The tools' input contract on a fixed sample of mutated scenes and targets (tests/fuzz/input_mutants.py).

Every mutant must end by itself, not by a signal, with exit 0 or 2 for `check` (0, 1 or 2 for a
short `run`), and exit 2 must name the scene file and the defect's line. The campaign script runs
the same judge over 10 000 and more mutants; this sample keeps CI at ~10 s.
"""

import os
import random
import sys
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()
OPT_BINARY = Path(os.environ.get("CRANEOPT_BIN", SOURCE_DIR / "build" / "crane-opt")).resolve()
sys.path.insert(0, str(SOURCE_DIR / "tests" / "fuzz"))

import input_mutants  # noqa: E402

SAMPLE = range(1, 601)  # seeds; the campaign found no violation among them after its fixes
TARGET_SAMPLE = range(1, 301)  # target mutants through `crane-opt map` (~5 s)


@pytest.fixture(scope="module")
def workdir():
    with input_mutants.workspace() as tmp:
        yield Path(tmp)


def test_mutants_keep_the_input_contract(workdir: Path):
    violations = []
    for seed in SAMPLE:
        mutant = input_mutants.make_mutant(seed)
        runs = [False] + ([True] if mutant.scene in input_mutants.RUNNABLE and random.Random(seed).random() < 0.2 else [])
        for run in runs:
            verdict = input_mutants.check_contract(BINARY, mutant, workdir, run, time_limit=20.0)
            if verdict.violation:
                violations.append(f"seed {seed} ({mutant.scene}: {mutant.mutation}): {verdict.violation}: {verdict.message}")
    assert not violations, "\n".join(violations)


def test_target_mutants_keep_the_input_contract(workdir: Path):
    violations = []
    for seed in TARGET_SAMPLE:
        mutant = input_mutants.make_mutant(seed, of_targets=True)
        verdict = input_mutants.check_contract(OPT_BINARY, mutant, workdir, run=False, time_limit=20.0)
        if verdict.violation:
            violations.append(f"seed {seed} ({mutant.scene}: {mutant.mutation}): {verdict.violation}: {verdict.message}")
    assert not violations, "\n".join(violations)


def test_the_judge_catches_a_broken_contract(workdir: Path, tmp_path: Path):
    """A stand-in binary that crashes, one that hangs, one that exits 2 without a line: all caught."""
    mutant = input_mutants.make_mutant(1)
    cases = {"kill -SEGV $$": "crash", "sleep 5": "hang", "echo 'error: something' >&2; exit 2": "without"}
    for script, expected in cases.items():
        fake = tmp_path / "fake-crane-sim"
        fake.write_text(f"#!/bin/sh\n{script}\n")
        fake.chmod(0o755)
        verdict = input_mutants.check_contract(fake, mutant, workdir, run=False, time_limit=1.0)
        assert expected in verdict.violation, (script, verdict)
