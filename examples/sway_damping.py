"""Slew and hoist the thesis crane's load from Python, then let anti-sway feedback hold it still.

An operator's lever slews the crane at 3 °/s for 15 s and reels the hoist rope in at 0.3 m/s for
20 s; then the lever is released and the load swings, across the boom and in and out. Open loop
it keeps swinging. With feedback (from the release on), two LQR controllers of
cranesim.control.SwayAxis, one across the boom and one along it, move the boom head to damp the
swing and bring it back where it was at the release: across the boom by slewing, in and out by
the luffing winch (2.91 m of head radius per metre of luffing rope at this boom angle, measured
on this crane). They read what a crane measures: the drives' encoders (input values and rates),
the hoist rope's angles at the boom head and the rope's length.

The weights were chosen on this crane (docs/control.md): with stronger ones the flexible crane,
whose boom head is not the rigid suspension point of the design model, keeps swinging.

    python3 examples/sway_damping.py [--seconds 80] [--scene configs/crane_inputs.yaml]
"""

import argparse
import math
from pathlib import Path

import numpy as np

import cranesim
from cranesim.control import SwayAxis

SCENE = Path(__file__).resolve().parents[1] / "configs" / "crane_inputs.yaml"
RELEASE = 20.0        # s: the operator lets go of the lever
HEAD_PER_LUFF = 2.91  # m of boom-head radius per m of luffing rope


def lift(scene, feedback: bool, seconds: float, dt: float = 0.02):
    """Runs the lift, with or without the feedback; returns the largest swing of the hook about the
    boom head (m) in each 10 s after the release and the run's solver statistics."""
    sim = cranesim.Simulation(scene)
    hook, head = sim.joint("load.origin"), sim.joint("head.sheave")
    slew, luff = sim.inputs.index("slewing"), sim.inputs.index("luffing_rope")
    across = SwayAxis(sample_time=dt, angle=0.01, angle_rate=0.01)
    along = SwayAxis(sample_time=dt, angle=0.02, angle_rate=0.02)
    swings = [0.0] * int(math.ceil((seconds - RELEASE) / 10.0 - 1e-9))
    held = None
    while sim.time < seconds - 1e-9:
        t = sim.time
        r = sim.joint_position(head)
        radius = math.hypot(r[0], r[1])
        length = float(np.linalg.norm(sim.joint_position(hook) - r))
        (out_angle, across_angle), (out_rate, across_rate) = sim.sway(hook, head)
        if t >= RELEASE:
            window = int((t - RELEASE) / 10.0)
            swings[window] = max(swings[window], length * math.hypot(math.sin(out_angle), math.sin(across_angle)))
        commands = {"slewing": 3.0 if t < 15.0 else 0.0, "hoist_rope": -0.3 if t < RELEASE else 0.0,
                    "luffing_rope": 0.0}
        if feedback and t >= RELEASE:
            values, rates = sim.input_values(), sim.input_rates()
            if held is None:
                held = values.copy()
            u_across = across.command(length, radius * math.radians(values[slew] - held[slew]),
                                      radius * math.radians(rates[slew]), across_angle, across_rate)
            u_out = along.command(length, HEAD_PER_LUFF * (values[luff] - held[luff]),
                                  HEAD_PER_LUFF * rates[luff], out_angle, out_rate)
            commands["slewing"] = math.degrees(u_across / radius)  # °/s
            commands["luffing_rope"] = u_out / HEAD_PER_LUFF       # m/s
        sim.set_inputs(commands)
        if not sim.step(dt):
            raise RuntimeError(sim.message)
    return swings, sim.statistics()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=80.0, help="simulated time (s), at least 30")
    parser.add_argument("--scene", default=str(SCENE),
                        help="a scene whose inputs include slewing, luffing_rope and hoist_rope")
    args = parser.parse_args()
    for name, feedback in (("open loop", False), ("anti-sway", True)):
        swings, stats = lift(args.scene, feedback, args.seconds)
        print(f"{name:10} largest swing per 10 s after the release: {' '.join(f'{s:.3f}' for s in swings)} m   "
              f"({args.seconds / stats['wall_time_s']:.0f}× real time, {stats['steps']} steps, "
              f"{stats['restarts']} restarts)")


if __name__ == "__main__":
    main()
