"""A run of a scene that its caller drives step by step."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Mapping, Optional, Sequence, Union

import numpy as np
import yaml

from . import _core

if TYPE_CHECKING:
    from .results import Results

Scene = Union[str, os.PathLike, Mapping]


def scene_source(scene: Scene) -> tuple[str, str, str]:
    """(path, text, name) for the engine: a file's path, or a dict's YAML text named <dict>."""
    if isinstance(scene, Mapping):
        return "", yaml.safe_dump(dict(scene), sort_keys=False), "<dict>"
    return os.fspath(scene), "", ""


class Simulation:
    """A run of a crane scene that you advance step by step, setting its inputs as it goes.

    ``Simulation(scene)`` reads the scene (a YAML file's path, or a dict with the same keys),
    compiles it and puts it in its starting state as ``crane-sim run`` does (its equilibrium
    with ``solver.initial_state: equilibrium``). A bad scene raises :class:`cranesim.SceneError`
    naming the file, the YAML path and the line.

    The scene's **inputs** are its drives of ``type: input`` (a rope's length, a driven joint, a
    load's scale): :attr:`inputs` names them, :meth:`set_inputs` commands them. Each drive follows
    its command through its own dynamics (a lag, within its limits), so commands that change at
    every sample keep the run smooth and fast.

    Typical loop::

        sim.set_inputs({"slewing": 2.0})   # held from now on
        sim.step(0.02)                     # advance 20 ms
        sim.joint_position(hook)           # observe

    Observations besides joints: :meth:`constraint_load` (a joint's force and moment: the hook's
    is the hoist rope's tension), :meth:`rope_tension`, :meth:`energy`, :meth:`drive_power`,
    :meth:`winch_power`, :meth:`input_values`, :meth:`input_rates`. With ``record=True`` the run keeps its samples every
    ``output.interval`` and :meth:`write_results` writes them as ``crane-sim run`` does.

    Other methods: :meth:`advance_to`, :meth:`reset`, :meth:`save_state`, :meth:`restore_state`,
    :meth:`joint_velocity`, :meth:`input_limits`, :meth:`statistics`.
    """

    def __init__(self, scene: Scene, record: bool = False):
        self._core = _core.Session.open(*scene_source(scene), record)
        self._joints: dict[str, int] = {}
        self._constraints: dict[str, int] = {}
        self._inputs = tuple(self._core.input_names)
        self._input_index = {name: k for k, name in enumerate(self._inputs)}
        self._commands = self._core.held_commands()

    # -- what the run is ---------------------------------------------------------------------
    @property
    def name(self) -> str:
        """The scene's name."""
        return self._core.name

    @property
    def time(self) -> float:
        """The simulated time now, s."""
        return self._core.time

    @property
    def t_end(self) -> float:
        """The scene's solver.t_end: the run stops there."""
        return self._core.t_end

    @property
    def inputs(self) -> tuple[str, ...]:
        """The inputs' names (a rope's, a constraint's or a load's), in the order of arrays."""
        return self._inputs

    def input_limits(self, name: str) -> dict[str, float]:
        """An input's limits: speed, acceleration, min, max (math.inf where it has none), and
        whether it takes speed commands (``speed_command``)."""
        k = self._index(name)
        speed, acceleration, low, high = self._core.input_limits(k)
        return {"speed": speed, "acceleration": acceleration, "min": low, "max": high,
                "speed_command": self._core.input_command_is_speed(k)}

    # -- driving it --------------------------------------------------------------------------
    def set_inputs(self, commands: Union[Mapping[str, float], Sequence[float], np.ndarray]) -> np.ndarray:
        """Holds commands from now on: a mapping from input names to commands (the others keep
        theirs), or one command per input in the order of :attr:`inputs`. Speeds for a speed
        input (m/s, or the unit's per second), values for a value input.

        Each command is clipped to its input's limits; returns every input's command as held.
        A command that is not a finite number raises ValueError and changes nothing.
        """
        if isinstance(commands, dict):
            new = self._commands.copy()
            for name, value in commands.items():
                new[self._index(name)] = value
        elif type(commands) is np.ndarray and commands.dtype == np.float64 and commands.ndim == 1:
            new = commands  # a controller's own array: no conversion on the fast path
        elif isinstance(commands, Mapping):
            return self.set_inputs(dict(commands))
        else:
            new = np.asarray(commands, dtype=np.float64).reshape(-1)
        self._commands = self._core.set_inputs(new)  # refuses a command that is not finite
        return self._commands.copy()

    def step(self, dt: float) -> bool:
        """Advances the run by dt seconds. False once it has stopped: at t_end, or for the reason
        in :attr:`message` (a solver failure)."""
        return self._core.advance_to(self._core.time + dt)

    def advance_to(self, t: float) -> bool:
        """Advances the run to time t; see :meth:`step`."""
        return self._core.advance_to(t)

    def reset(self) -> None:
        """Back to the starting state, every input at rest at its scene value."""
        self._core.reset()
        self._commands = self._core.held_commands()

    def save_state(self, path: Optional[Union[str, os.PathLike]] = None) -> Optional[_core.State]:
        """The run's state now, to go on from later (:meth:`restore_state`): the coordinates,
        velocities, each input's drive and command, the energy books. With ``path``, it is
        written to that HDF5 file instead, for a run that goes on in another process.

        The integrator restarts at the saved time (as at a drive breakpoint), so that this run
        and every run restored from the state go on alike, bit for bit.
        """
        if path is None:
            return self._core.save()
        self._core.save_file(os.fspath(path))
        return None

    def restore_state(self, state: Union[_core.State, str, os.PathLike]) -> None:
        """Goes on from a state that :meth:`save_state` saved from a run of the same scene (this
        run or another, or a file: its path). A file of another scene raises RuntimeError
        naming the file."""
        if isinstance(state, (str, os.PathLike)):
            self._core.restore_file(os.fspath(state))
        else:
            self._core.restore(state)
        self._commands = self._core.held_commands()

    @property
    def complete(self) -> bool:
        """Whether the run reached t_end."""
        return self._core.complete

    @property
    def message(self) -> str:
        """Why the run stopped before t_end (empty while it goes on or when it completed)."""
        return self._core.message

    def statistics(self) -> dict:
        """The solver's counters (steps, Jacobian evaluations, restarts, …) and the wall time."""
        return self._core.statistics()

    # -- observing it ------------------------------------------------------------------------
    def joint(self, name: str) -> int:
        """The index of a joint (``"<body>.<joint>"``, ``"<member>.end"``, …), for the fast
        observation calls; ValueError with the nearest name for an unknown one."""
        index = self._joints.get(name)
        if index is None:
            index = self._joints[name] = self._core.joint(name)
        return index

    def joint_position(self, joint: Union[int, str]) -> np.ndarray:
        """A joint's position now, inertial frame, m."""
        return self._core.joint_position(self._joint_index(joint))

    def joint_velocity(self, joint: Union[int, str]) -> np.ndarray:
        """A joint's velocity now, inertial frame, m/s."""
        return self._core.joint_velocity(self._joint_index(joint))

    @property
    def joints(self) -> tuple[str, ...]:
        """Every joint's name."""
        return tuple(self._core.joint_names)

    @property
    def constraints(self) -> tuple[str, ...]:
        """Every constraint's name."""
        return tuple(self._core.constraint_names)

    def constraint_load(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """The force (N) and the moment (N·m, about the second joint) that a constraint carries
        to its second joint now, in its first joint's axes; the multipliers are solved for the
        state now, as in a results file's ``/constraint_loads``. A rope's tension is the force
        of the joint that holds its end (the thesis crane's ``hook``)."""
        index = self._constraints.get(name)
        if index is None:
            index = self._constraints[name] = self._core.constraint(name)
        load = self._core.constraint_load(index)
        return load[:3], load[3:]

    def rope_tension(self, rope: str) -> np.ndarray:
        """A rope's axial force now (N, ≥ 0, 0 where slack), one row per element of the rope,
        at equally spaced points from the element's first node to its second; for a reeved rope
        one row per part, winch to dead end, each row one tension (a massless part's)."""
        return self._core.rope_tensions(rope).reshape(-1, _core.tension_points)

    def drive_power(self, constraint: str) -> float:
        """The power a driven constraint's drive (the slewing drive) delivers to the crane now,
        W: as the energy books count drive work; negative while the crane drives it (braking)."""
        return self._core.drive_power(self._core.constraint(constraint))

    def winch_power(self, rope: str) -> float:
        """The power a rope's winch delivers to the crane now, W: through the change of the
        rope's unstretched length, as the energy books count winch work; positive while it reels
        a rope under tension in, negative while it lowers; a reeved rope's includes what its
        sheaves dissipate."""
        return self._core.winch_power(rope)

    def sway(self, hanging: Union[int, str], pivot: Union[int, str]) -> tuple[np.ndarray, np.ndarray]:
        """How the line from joint ``pivot`` down to joint ``hanging`` swings (the hook below
        the boom head's sheave: ``sway("load.origin", "head.sheave")``): its angles from the
        downward vertical, radial (in the vertical plane through the pivot and the vertical axis
        through the origin, > 0 outward) and across (> 0 in the sense of a positive slew), rad,
        and their rates, rad/s."""
        values = self._core.sway(self._joint_index(hanging), self._joint_index(pivot))
        return values[:2], values[2:]

    def energy(self) -> dict[str, float]:
        """The kinetic energy and the potential energy (gravity and strain) now, J."""
        return {"kinetic": self._core.kinetic_energy(), "potential": self._core.potential_energy()}

    def write_results(self, path: Union[str, os.PathLike]) -> Results:
        """Writes the run's samples so far as a results file (a ``Simulation`` opened with
        ``record=True``), the same file ``crane-sim run`` writes, and returns it opened. The
        file is complete up to :attr:`time` unless the run failed. After a restore, the file
        holds the samples before the state's time and those recorded since."""
        from .results import Results

        self._core.write_results(os.fspath(path))
        return Results(path)

    @property
    def recording(self) -> bool:
        """Whether the run keeps its samples (``record=True``)."""
        return self._core.recording

    def input_values(self) -> np.ndarray:
        """Every input's drive value now (a rope's length, an angle in the scene's unit, …)."""
        return self._core.input_values()

    def input_rates(self) -> np.ndarray:
        """Every input's drive speed now."""
        return self._core.input_rates()

    def _joint_index(self, joint: Union[int, str]) -> int:
        return self.joint(joint) if isinstance(joint, str) else int(joint)

    def _index(self, name: str) -> int:
        try:
            return self._input_index[name]
        except KeyError:
            return self._core.input(name)  # raises ValueError naming the inputs

    def __repr__(self) -> str:
        return f"<cranesim.Simulation '{self.name}' at t = {self.time:g} s, inputs {list(self._inputs)}>"
