"""One episode of the Gymnasium lift environment under a hand-written policy.

The policy steers each drive towards the target in proportion to how far off it is — slewing by
the angle to the target, luffing by the radius, hoisting by the height — and damps the swing as
examples/sway_damping.py does. It prints the episode's return and how close the load came.

    python3 examples/gym_rollout.py [--seed 1] [--seconds 60]
"""

import argparse
import math

import gymnasium as gym
import numpy as np

import cranesim.gym  # registers cranesim/CraneLift-v0

HEAD_PER_LUFF = 2.95  # m of boom-head radius per m of luffing rope (examples/sway_damping.py)


def policy(env, observation) -> np.ndarray:
    """Actions as fractions of each drive's speed limit (luffing rope, hoist rope, slewing): the
    boom head heads for the target at 0.2 1/s times how far off it is, across the boom by slewing
    and in or out by the luffing winch, plus the swing's damping of examples/sway_damping.py;
    the hoist rope reels at 0.1 1/s times the height still to go."""
    sim, target = env.unwrapped.sim, env.unwrapped.target
    hook = observation[0:3] + target
    head = sim.joint_position("head.sheave")
    radius = math.hypot(head[0], head[1])
    rope = sim.input_values()[1]
    swing_out, swing_across = rope * observation[6], rope * observation[7]  # m: angle × length
    angle_off = math.remainder(math.atan2(target[1], target[0]) - math.atan2(hook[1], hook[0]), 2 * math.pi)
    reach_off = math.hypot(target[0], target[1]) - math.hypot(hook[0], hook[1])
    slewing = math.degrees(0.2 * angle_off + 0.2 * swing_across / radius)         # °/s
    luffing = (0.2 * reach_off + 0.2 * swing_out) / HEAD_PER_LUFF                 # m/s
    hoist = 0.1 * observation[2]                                                  # m/s: reel in while below
    return np.clip(np.array([luffing, hoist, slewing]) / env.unwrapped.speed_limits, -1.0, 1.0).astype(np.float32)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seconds", type=float, default=60.0, help="the episode's length (s)")
    args = parser.parse_args()
    env = gym.make("cranesim/CraneLift-v0", episode_time=args.seconds)
    observation, info = env.reset(seed=args.seed)
    start = float(np.linalg.norm(observation[0:3]))
    total, closest, steps = 0.0, start, 0
    while True:
        observation, reward, terminated, truncated, info = env.step(policy(env, observation))
        total += reward
        steps += 1
        closest = min(closest, float(np.linalg.norm(observation[0:3])))
        if terminated or truncated:
            break
    end = float(np.linalg.norm(observation[0:3]))
    print(f"{steps} steps, return {total:.2f}; the load started {start:.2f} m from the target, "
          f"came within {closest:.2f} m and ended {end:.2f} m from it"
          f"{' at rest (terminated)' if terminated else ''}")


if __name__ == "__main__":
    main()
