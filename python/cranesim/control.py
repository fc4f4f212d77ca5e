"""Feedback against the load's sway, for a crane driven step by step (docs/control.md)."""

from __future__ import annotations

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
    command (m/s).

    Each sample, :meth:`command` takes what the crane measures along the axis and returns the
    suspension point's speed command (m/s); mapping it to a drive (°/s of slewing, m/s of
    luffing rope) is the caller's.
    """

    def __init__(self, sample_time: float = 0.02, drive_lag: float = 0.1, gravity: float = 9.81,
                 position: float = 1.0, speed: float = 1.0, angle: float = 0.01,
                 angle_rate: float = 0.01, command: float = 0.5, reschedule: float = 0.005):
        self._core = _core.SwayAxis(sample_time, drive_lag, gravity, position, speed, angle,
                                    angle_rate, command, reschedule)

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
