"""cranesim: dynamics and control of lattice boom cranes as rigid-flexible multibody systems.

Drive a crane step by step from Python::

    import cranesim

    sim = cranesim.Simulation("configs/crane_inputs.yaml")
    print(sim.inputs)                        # ('luffing_rope', 'hoist_rope', 'slewing')
    hook = sim.joint("load.origin")
    for _ in range(500):                     # 10 s at 50 Hz
        sim.set_inputs({"hoist_rope": -0.3, "slewing": 2.0})
        sim.step(0.02)
        position, velocity = sim.joint_position(hook), sim.joint_velocity(hook)

Whole analyses, as the command line runs them, return their results files as numpy arrays::

    results = cranesim.run("configs/crane_condensed.yaml", "crane.h5")
    hook = results.get("joints/load.origin/position")     # (samples, 3)

``help(cranesim.Simulation)`` lists what a run offers; docs/python.md in the repository says
more, and docs/session.md what inputs are and what they cost.
"""

import importlib

from ._core import __version__
from .errors import SceneError
from .simulation import Simulation

__all__ = ["Simulation", "run", "static", "modes", "study", "Results", "ResultsError", "SceneError",
           "__version__"]

# Loaded on first use: the results reader (and h5py with it) only when asked for, and
# `python3 -m cranesim.results FILE` runs the reader's module once, not twice.
_LAZY = {"run": "analyses", "static": "analyses", "modes": "analyses", "study": "analyses",
         "Results": "results", "ResultsError": "results"}


def __getattr__(name: str):
    if name in _LAZY:
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module 'cranesim' has no attribute '{name}'")


def __dir__():
    return sorted(set(globals()) | set(__all__))
