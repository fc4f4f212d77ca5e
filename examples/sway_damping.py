"""Slew and hoist the thesis crane's load from Python, then let a sway-damping feedback hold it.

An operator's lever slews the crane at 3 °/s for 15 s and reels the hoist rope in at 0.3 m/s for
20 s; then the lever is released and the load swings, across the boom and in and out. Open loop
it keeps swinging. With the feedback (from the release on), the drives move the boom head
towards the hook's offset from it, at c = 0.2 1/s times that offset: across the boom by slewing,
in and out by the luffing winch (2.95 m of head radius per metre of luffing rope, measured on
this crane). Moving the suspension point with a speed proportional to the load's offset makes
the swing a damped oscillation.

This is a demonstration of driving the crane step by step, not an anti-sway controller: it
leaves about a quarter of the swing, an 8 s oscillation of the slewing loop with the flexible
boom that a law this simple does not damp.

    python3 examples/sway_damping.py [--seconds 60] [--scene configs/crane_inputs.yaml]
"""

import argparse
import math
from pathlib import Path

import numpy as np

import cranesim

SCENE = Path(__file__).resolve().parents[1] / "configs" / "crane_inputs.yaml"
RELEASE = 20.0        # s: the operator lets go of the lever
HEAD_PER_LUFF = 2.95  # m of boom-head radius per m of luffing rope


def lift(scene, gain: float, seconds: float, dt: float = 0.02):
    """Runs the lift with the feedback gain (1/s; 0: open loop); returns the largest swing of the
    hook about the boom head (m) in the last 20 s and the run's solver statistics."""
    sim = cranesim.Simulation(scene)
    hook, head = sim.joint("load.origin"), sim.joint("head.sheave")
    largest_at_end = 0.0
    while sim.time < seconds - 1e-9:
        t = sim.time
        r_head = sim.joint_position(head)
        offset = sim.joint_position(hook) - r_head
        radius = math.hypot(r_head[0], r_head[1])
        out = np.array([r_head[0], r_head[1], 0.0]) / radius
        across = np.array([-out[1], out[0], 0.0])
        if t >= seconds - 20.0:
            largest_at_end = max(largest_at_end, math.hypot(offset @ out, offset @ across))
        c = gain if t >= RELEASE else 0.0
        sim.set_inputs({
            "slewing": (3.0 if t < 15.0 else 0.0) + math.degrees(c * (offset @ across) / radius),  # °/s
            "luffing_rope": c * (offset @ out) / HEAD_PER_LUFF,                                   # m/s
            "hoist_rope": -0.3 if t < RELEASE else 0.0,                                           # m/s
        })
        if not sim.step(dt):
            raise RuntimeError(sim.message)
    return largest_at_end, sim.statistics()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated time (s), at least 40")
    parser.add_argument("--scene", default=str(SCENE),
                        help="a scene whose inputs include slewing, luffing_rope and hoist_rope")
    args = parser.parse_args()
    for name, gain in (("open loop", 0.0), ("sway feedback", 0.2)):
        sway, stats = lift(args.scene, gain, args.seconds)
        print(f"{name:14} largest swing in the last 20 s: {sway:.3f} m   "
              f"({args.seconds / stats['wall_time_s']:.0f}× real time, {stats['steps']} steps, "
              f"{stats['restarts']} restarts)")


if __name__ == "__main__":
    main()
