"""Whole analyses of a scene, as the command line runs them: each writes the file `crane-sim`
writes and returns it opened, its datasets as numpy arrays."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Optional, Union

from . import _core
from .results import Results
from .simulation import Scene, Simulation, scene_source

Output = Optional[Union[str, os.PathLike]]


def _output(scene: Scene, output: Output, suffix: str) -> str:
    """The file to write: `output`, or as crane-sim names it, <scene stem><suffix> here."""
    if output is not None:
        return os.fspath(output)
    if not isinstance(scene, (str, os.PathLike)):
        raise ValueError("a scene given as a dict needs an output path: output='run.h5'")
    return Path(scene).stem + suffix


def run(scene: Scene, output: Output = None) -> Results:
    """Simulates the scene from its starting state to ``solver.t_end`` and writes its results
    file (default: ``<scene stem>.h5`` in the working directory), as ``crane-sim run`` does;
    returns it opened. A run the solver stops early is written marked incomplete (its
    ``status`` and ``message`` say why) and a warning goes to stderr.

    A scene's inputs hold their scene values: to command them, use :class:`Simulation`. Ctrl-C
    ends the run, writes what it computed marked interrupted, and raises KeyboardInterrupt.
    """
    path = _output(scene, output, ".h5")
    simulation = Simulation(scene, record=True)
    try:
        simulation.advance_to(simulation.t_end)
    except KeyboardInterrupt:
        simulation.write_results(path)
        raise
    return simulation.write_results(path)


def static(scene: Scene, output: Output = None) -> Results:
    """Solves the scene's static equilibrium (its ``solver.statics`` method) and writes it as a
    one-sample results file (default: ``<scene stem>_static.h5``), as ``crane-sim static``
    does; returns it opened. An unstable equilibrium is written marked incomplete, its
    ``message`` saying why."""
    path = _output(scene, output, "_static.h5")
    _core.write_static(*scene_source(scene), path)
    return Results(path)


def modes(scene: Scene, count: int = 10, output: Output = None) -> Results:
    """The ``count`` lowest small-vibration modes about the scene's static equilibrium (0: all),
    written as ``crane-sim modes`` writes them (default: ``<scene stem>_modes.h5``); returns the
    file opened: ``modes/frequency`` (Hz), ``modes/shapes``, ``modes/joint_displacements``."""
    path = _output(scene, output, "_modes.h5")
    _core.write_modes(*scene_source(scene), count, path)
    return Results(path)


def study(study_file: Union[str, os.PathLike], output: Output = None, jobs: int = 1,
          resume: bool = False) -> Results:
    """Runs a study file as ``crane-sim study`` does — its cases on ``jobs`` threads, finished
    rows kept in a checkpoint, ``resume`` going on from it — and returns its case table opened
    (default: ``<study stem>.h5`` in the working directory; docs/study-format.md). A bad study
    raises :class:`cranesim.SceneError`; a case that fails is a row that says why, not an
    exception. Ctrl-C stops it as it stops ``crane-sim study``: the rows finished so far are
    kept for ``resume=True``, and KeyboardInterrupt is raised."""
    path = os.fspath(study_file)
    out = os.fspath(output) if output is not None else Path(path).stem + ".h5"
    code = _core.run_study(path, out, jobs, resume)
    if code != 0:
        raise RuntimeError(f"the study {path} stopped (exit code {code}): its table {out} could not be written")
    return Results(out)
