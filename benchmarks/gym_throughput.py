"""Throughput of the Gymnasium lift environment (cranesim/CraneLift-v0) on the condensed crane.

Steps the environment with random actions (the roughest commands a learning agent sends: every
drive's speed command jumps at every 20 ms step), on one process (at the environment's rtol 1e-3
and at the scene's 1e-4), in Gymnasium's AsyncVectorEnv on 1 and 2 worker processes, and in
cranesim.gym.ThreadedVectorEnv (2, 4 and 8 environments on 2 threads of one process). Reports
environment steps per second (the median of --reps runs), the scaling from 1 to 2 workers, and
the accuracy: the largest distance of the load from its path at rtol 1e-8 under the same
--error-steps random actions.

Writes benchmarks/results/gym_throughput.csv.

    python3 benchmarks/gym_throughput.py            # ≈ 1 min on 2 cores
"""

import argparse
import statistics
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

import cranesim.gym  # noqa: F401  (registers the environment)
from benchmark_csv import machine, write_rows

ROOT = Path(__file__).resolve().parents[1]
ENV_ID = "cranesim/CraneLift-v0"


def single(steps, seed, **options):
    env = gym.make(ENV_ID, **options)
    env.action_space.seed(seed)
    env.reset(seed=seed)
    start = time.perf_counter()
    for _ in range(steps):
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        if terminated or truncated:
            env.reset()
    return steps / (time.perf_counter() - start)


def vector(workers, steps, seed, threads=None):
    fns = [lambda: gym.make(ENV_ID) for _ in range(workers)]
    envs = cranesim.gym.ThreadedVectorEnv(fns, threads=threads) if threads else gym.vector.AsyncVectorEnv(fns)
    envs.action_space.seed(seed)
    envs.reset(seed=seed)
    envs.step(envs.action_space.sample())  # the workers' first step outside the timing
    start = time.perf_counter()
    for _ in range(steps // workers):
        envs.step(envs.action_space.sample())
    rate = (steps // workers) * workers / (time.perf_counter() - start)
    envs.close()
    return rate


def load_error(steps, rtol):
    """The largest distance of the load from its path at rtol 1e-8 under the same random actions
    (the scene's load, so that both runs start alike)."""
    actions = np.random.default_rng(0).uniform(-1, 1, size=(steps, 3)).astype(np.float32)
    paths = []
    for tolerance in (rtol, 1e-8):
        env = gym.make(ENV_ID, rtol=tolerance, load_mass=(390000.6, 390000.6))
        env.reset(seed=0)
        paths.append(np.array([env.unwrapped.step(a)[0][0:3] for a in actions]))
    return float(np.max(np.linalg.norm(paths[0] - paths[1], axis=1)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=6000, help="environment steps per measurement")
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--error-steps", type=int, default=500, help="random actions of the accuracy check")
    parser.add_argument("-o", "--out", default=str(ROOT / "benchmarks" / "results" / "gym_throughput.csv"))
    args = parser.parse_args()
    results = {"one process": [], "one process, rtol 1e-4": [], "AsyncVectorEnv, 1 worker": [],
               "AsyncVectorEnv, 2 workers": [], "ThreadedVectorEnv, 2 envs, 2 threads": [],
               "ThreadedVectorEnv, 4 envs, 2 threads": [], "ThreadedVectorEnv, 8 envs, 2 threads": []}
    for rep in range(args.reps):
        results["one process"].append(single(args.steps, rep))
        results["one process, rtol 1e-4"].append(single(args.steps, rep, rtol=1e-4))
        results["AsyncVectorEnv, 1 worker"].append(vector(1, args.steps, rep))
        results["AsyncVectorEnv, 2 workers"].append(vector(2, args.steps, rep))
        results["ThreadedVectorEnv, 2 envs, 2 threads"].append(vector(2, args.steps, rep, threads=2))
        results["ThreadedVectorEnv, 4 envs, 2 threads"].append(vector(4, args.steps, rep, threads=2))
        results["ThreadedVectorEnv, 8 envs, 2 threads"].append(vector(8, args.steps, rep, threads=2))
    errors = {rtol: load_error(args.error_steps, rtol) for rtol in (1e-3, 1e-4)}
    rows = []
    for setup, rates in results.items():
        rate = statistics.median(rates)
        rtol = 1e-4 if "1e-4" in setup else 1e-3
        rows.append({"setup": setup, "steps": args.steps, "reps": args.reps, "steps_per_s": f"{rate:.0f}",
                     "real_time_factor": f"{rate * 0.02:.1f}", "rtol": f"{rtol:g}",
                     "load_error_m": f"{errors[rtol]:.2e}", "error_steps": args.error_steps, "machine": machine()})
    scaling = statistics.median(results["AsyncVectorEnv, 2 workers"]) / statistics.median(results["AsyncVectorEnv, 1 worker"])
    for row in rows:
        row["scaling_1_to_2"] = f"{scaling:.2f}"
    write_rows(args.out, rows)
    for row in rows:
        print(f"{row['setup']:38} {row['steps_per_s']:>6} steps/s  ({row['real_time_factor']}× real time)")
    print(f"scaling from 1 to 2 workers: {scaling:.2f}   results: {args.out}")
    for rtol, error in errors.items():
        print(f"rtol {rtol:g}: load within {error * 1000:.2f} mm of its path at 1e-8 over {args.error_steps} random actions")


if __name__ == "__main__":
    main()
