"""Slew and hoist the thesis crane's load from Python, with and without anti-sway feedback.

An operator's lever slews the crane at 3 °/s for 15 s and reels the hoist rope in at 0.3 m/s for
20 s; then the lever is released and the load swings, across the boom and in and out. Three runs:

- open loop: it keeps swinging;
- hold: from the release on, cranesim.control.AntiSway holds the boom head where it was and
  damps the swing, across the boom by slewing and along it by the luffing winch;
- assisted: AntiSway from the start, the lever's speeds its references: the head follows the
  operator while the feedback damps the swing the lever excites.

The controller reads what a crane measures: the drives' encoders (the inputs' values and rates),
the hoist rope's angles at the boom head and its length (docs/control.md).

    python3 examples/sway_damping.py [--seconds 60] [--scene configs/crane_inputs.yaml]
"""

import argparse
import math
from pathlib import Path

import cranesim
from cranesim.control import AntiSway

SCENE = Path(__file__).resolve().parents[1] / "configs" / "crane_inputs.yaml"
RELEASE = 20.0  # s: the operator lets go of the lever


def lever(t: float) -> dict:
    """The operator's speeds: slewing (°/s) and hoist rope (m/s)."""
    return {"slewing": 3.0 if t < 15.0 else 0.0, "hoist_rope": -0.3 if t < RELEASE else 0.0}


def lift(scene, mode: str, seconds: float, dt: float = 0.02):
    """Runs the lift open loop, holding from the release, or assisted; returns the largest swing of
    the hook about the boom head (m) in each 10 s after the release and the solver statistics."""
    sim = cranesim.Simulation(scene)
    hook, head = sim.joint("load.origin"), sim.joint("head.sheave")
    controller = AntiSway(sim) if mode == "assisted" else None
    swings = [0.0] * int(math.ceil((seconds - RELEASE) / 10.0 - 1e-9))
    while sim.time < seconds - 1e-9:
        t = sim.time
        if t >= RELEASE:
            (out, across), _ = sim.sway(hook, head)
            length = math.dist(sim.joint_position(hook), sim.joint_position(head))
            window = int((t - RELEASE) / 10.0)
            swings[window] = max(swings[window], length * math.hypot(math.sin(out), math.sin(across)))
        if controller is None and mode == "hold" and t >= RELEASE:
            controller = AntiSway(sim)  # the head's reference: where it is at the release
        speeds = lever(t)
        if controller is None:
            sim.set_inputs(speeds)
        else:
            controller.apply(slewing=speeds["slewing"], hoist=speeds["hoist_rope"])
        if not sim.step(dt):
            raise RuntimeError(sim.message)
    return swings, sim.statistics()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated time (s), at least 30")
    parser.add_argument("--scene", default=str(SCENE),
                        help="a scene whose inputs include slewing, luffing_rope and hoist_rope")
    args = parser.parse_args()
    for mode in ("open loop", "hold", "assisted"):
        swings, stats = lift(args.scene, mode, args.seconds)
        print(f"{mode:10} largest swing per 10 s after the release: {' '.join(f'{s:.3f}' for s in swings)} m   "
              f"({args.seconds / stats['wall_time_s']:.0f}× real time, {stats['steps']} steps, "
              f"{stats['restarts']} restarts)")


if __name__ == "__main__":
    main()
