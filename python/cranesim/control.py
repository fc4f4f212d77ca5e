"""Feedback against the load's sway, for a crane driven step by step (docs/control.md)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _core


class SwayAxis:
    """Anti-sway feedback along one horizontal axis of a crane: across the boom (slewing) or
    along it (luffing).

    The design model is the load as a pendulum of the rope's length under the suspension point
    (the boom head's sheave), whose speed follows its command through a lag (``drive_lag``, s):
    an LQR, sampled every ``sample_time`` s, that brings the suspension point to its reference
    while it damps the swing, designed anew when the rope's length changes by more than
    ``reschedule`` (a fraction). The weights are Bryson's: the largest deviations accepted of
    the position (m), the speed (m/s), the rope's angle (rad) and its rate (rad/s), and of the
    command (m/s). ``measurement_cutoff`` (Hz; 0: none) passes the measured angle and its rate
    through a second-order low-pass filter first, to keep a flexible boom's own modes out of the
    feedback (:class:`AntiSway` uses 0.3 Hz on both axes). ``steady_angle_time`` (s; 0: none)
    takes the angle's steady part — where a steady wind holds the load — out of the feedback: a
    first-order low-pass of the angle with that time constant is subtracted from it, so that the
    feedback damps the swing about that offset instead of moving the head downwind.

    Each sample, :meth:`command` takes what the crane measures along the axis and returns the
    suspension point's speed command (m/s); mapping it to a drive (°/s of slewing, m/s of
    luffing rope) is the caller's.
    """

    def __init__(self, sample_time: float = 0.02, drive_lag: float = 0.1, gravity: float = 9.81,
                 position: float = 1.0, speed: float = 1.0, angle: float = 0.01,
                 angle_rate: float = 0.01, command: float = 0.5, reschedule: float = 0.005,
                 measurement_cutoff: float = 0.0, steady_angle_time: float = 0.0):
        self._core = _core.SwayAxis(sample_time, drive_lag, gravity, position, speed, angle,
                                    angle_rate, command, reschedule, measurement_cutoff, steady_angle_time)

    def command(self, rope_length: float, position_error: float, speed: float, angle: float,
                angle_rate: float, reference_speed: float = 0.0) -> float:
        """The suspension point's speed command (m/s) for the next sample: the reference speed
        less the feedback on the position's error from its reference (m), the speed's from the
        reference speed (m/s), the rope's angle from the vertical (rad, > 0 where the load is
        ahead along the axis) and its rate (rad/s)."""
        return self._core.command(rope_length, position_error, speed, reference_speed, angle,
                                  angle_rate)

    @property
    def gain(self) -> np.ndarray:
        """The gain on [position error, speed error, angle, angle rate] in use."""
        return self._core.gain

    @property
    def design_length(self) -> float:
        """The rope length the gain was designed for (0 before the first command)."""
        return self._core.design_length

    @property
    def closed_loop_spectral_radius(self) -> float:
        """The largest |eigenvalue| of the sampled closed loop of the design model (< 1: stable;
        per sample)."""
        return self._core.closed_loop_spectral_radius


@dataclass(frozen=True)
class SwaySensor:
    """How the hoist rope's angles reach :class:`AntiSway`: ``delay`` s late (interpolated
    between samples) and with white Gaussian noise of standard deviation ``angle_noise`` (rad)
    on each angle and ``rate_noise`` (rad/s) on each angular rate, drawn from a generator seeded
    with ``seed``. The drives' encoders and the rope's length stay exact. The default is the
    exact sensor."""

    angle_noise: float = 0.0
    rate_noise: float = 0.0
    delay: float = 0.0
    seed: int = 0


class AntiSway:
    """Anti-sway feedback on a crane driven step by step: a :class:`SwayAxis` across the boom
    (by the slewing drive) and one along it (by the luffing winch), in the loop of a
    :class:`cranesim.Simulation`.

    The operator's (or a plan's) speeds are references the boom head follows; the feedback adds
    what damps the swing. It reads what a crane measures: the drives' encoders, the hoist rope's
    angles at the boom head and its length. The boom head's radius per metre of luffing rope is
    tabulated at construction from the scene's equilibria over the luffing input's range (about
    a second on the thesis crane).

    Each sample, call :meth:`apply` with the reference speeds instead of
    :meth:`Simulation.set_inputs`, then step the simulation by ``sample_time``.

    ``shaping`` (s): for operator assistance, the crane's sway period with the hoist rope as it is
    now. The boom head then follows the lever's path shaped in the horizontal plane (half of each
    change of its velocity at once, half a sway half-period later, within the drives'
    acceleration limits) so that it leaves a pendulum of that period still, and the swing that
    path gives the pendulum is the feedback's reference: the head reaches the lever's position
    half a period late, and the feedback corrects only what the crane does differently from the
    pendulum. The period follows the hoist (a pendulum longer than the rope by a constant).

    ``boom_period`` (s): the period of the boom's mode that the hoist's load changes excite (its
    bending in the luffing plane). The hoist speed is then averaged over it, so that each change
    is a ramp of that duration and leaves the boom still.

    ``sensor``: how the rope's angles reach the feedback (:class:`SwaySensor`); exact by default.
    """

    def __init__(self, sim, across: SwayAxis | None = None, along: SwayAxis | None = None,
                 slewing: str = "slewing", luffing_rope: str = "luffing_rope",
                 hoist_rope: str = "hoist_rope", hook: str = "load.origin",
                 sheave: str = "head.sheave", shaping: float | None = None, boom_period: float | None = None,
                 sensor: SwaySensor | None = None):
        across = across or SwayAxis(measurement_cutoff=0.3)
        along = along or SwayAxis(angle=0.02, angle_rate=0.02, measurement_cutoff=0.3)
        sensor = sensor or SwaySensor()
        self._sim = sim
        self._core = _core.CraneSway(sim._core, slewing, luffing_rope, hoist_rope, hook, sheave,
                                     across._core, along._core, shaping or 0.0, boom_period or 0.0,
                                     sensor.angle_noise, sensor.rate_noise, sensor.delay, sensor.seed)

    def apply(self, slewing: float = 0.0, luffing: float = 0.0, hoist: float = 0.0) -> np.ndarray:
        """Sets the simulation's inputs for the next sample from the reference speeds: the
        slewing rate (the slewing input's unit per s), the luffing and hoist ropes' speeds (m/s);
        returns the commands as held, in the order of ``sim.inputs``."""
        held = self._core.apply(slewing, luffing, hoist)
        self._sim._commands = held.copy()
        return held

    def head_per_luff(self, length: float) -> float:
        """The boom head's radius per metre of luffing rope at that luffing rope length."""
        return self._core.head_per_luff(length)
