"""Gymnasium environments on the flexible crane.

``import cranesim.gym`` registers:

- ``cranesim/CraneLift-v0``: a point-to-point lift on the thesis crane (condensed lattice
  sections, controls as inputs): bring the load to a random target and hold it there at rest.

::

    import gymnasium as gym
    import cranesim.gym

    env = gym.make("cranesim/CraneLift-v0")
    observation, info = env.reset(seed=1)
    observation, reward, terminated, truncated, info = env.step(env.action_space.sample())

Several environments on both cores of one process: :class:`ThreadedVectorEnv`::

    envs = cranesim.gym.ThreadedVectorEnv([lambda: gym.make("cranesim/CraneLift-v0")] * 4)

docs/python.md in the repository describes the spaces, the reward and the speed.
"""

from __future__ import annotations

import copy
import math
import os
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Optional

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, SyncVectorEnv
from gymnasium.vector.utils import iterate

from .simulation import Scene, Simulation

_SCENES = os.path.join(os.path.dirname(__file__), "scenes")


def default_scene() -> str:
    """The thesis crane with its controls as inputs (configs/crane_inputs.yaml)."""
    return os.path.join(_SCENES, "crane_inputs.yaml")


class CraneLiftEnv(gymnasium.Env):
    """Lift the load to a target and hold it there at rest, with little sway.

    **Actions** (Box [-1, 1]^n, float32): each input's speed command as a fraction of its speed
    limit, in the order of ``action_names`` (for the thesis crane: luffing rope, hoist rope,
    slewing). Actions beyond ±1 are clipped; NaN raises ValueError. Every input must take speed
    commands and have a speed limit.

    **Observations** (Box, float32, 10 + 2n): the load's position relative to the target (m, 3)
    and its velocity (m/s, 3); the hoist rope's angles from the vertical at the boom head,
    radial and across the boom (rad, 2), and their rates (rad/s, 2); each input's value and speed.

    **Reward** per step of ``dt``: −dt · (distance / 10 m + (sway / 0.05 rad)²), and +10 when the
    load is within ``tolerance`` of the target, moving slower than 0.05 m/s with less than 0.01 rad
    of sway: the episode then terminates. It also terminates, with −10, if the integrator fails
    (``info["message"]`` says why); it is truncated after ``episode_time`` seconds.

    **Resets** start the crane from its equilibrium; the target is drawn from ``reset``'s seed:
    slewed by up to ±``slew`` degrees, lifted by ``lift`` metres, moved out or in by up to
    ``reach`` metres from the load's starting place. With ``load_mass`` (kg, low and high) each
    reset also draws the mass of the body ``load_body`` (its inertia kept) and solves the
    crane's equilibrium with it (about 0.04 s); on the default scene it is 390 t ± 20 %.

    **Accuracy**: the crane is integrated at relative tolerance ``rtol`` (absolute ``rtol``/10),
    in place of the scene's; ``None`` keeps the scene's. At the default 1e-3 a minute of random
    actions on the default scene moves the load within 4 mm of its path at 1e-8, at 1.7 times the
    speed of the scene's 1e-4.
    """

    metadata = {"render_modes": []}

    def __init__(self, scene: Optional[Scene] = None, *, dt: float = 0.02, episode_time: float = 60.0,
                 hook: str = "load.origin", sheave: str = "head.sheave", slew: float = 40.0,
                 lift: tuple[float, float] = (2.0, 15.0), reach: float = 1.0, tolerance: float = 0.2,
                 load_mass: Optional[tuple[float, float]] = None, load_body: str = "load",
                 rtol: Optional[float] = 1e-3):
        if scene is None:
            scene = default_scene()
            if load_mass is None:
                load_mass = (0.8 * 390000.6, 1.2 * 390000.6)  # the thesis load (Table D-12) ± 20 %
        if load_mass is not None and isinstance(scene, Mapping):
            raise ValueError("load_mass draws the load's mass into a scene file: give the scene as a path")
        self._scene, self._load_mass, self._load_body = scene, load_mass, load_body
        self._mass_now: Optional[float] = None
        self._solver = {} if rtol is None else {"solver.rtol": rtol, "solver.atol": rtol / 10}
        self.sim = Simulation(self._modified({}))
        self.dt, self.episode_time, self.tolerance = dt, episode_time, tolerance
        self.slew, self.lift, self.reach = slew, lift, reach
        self.action_names = self.sim.inputs
        speeds = []
        for name in self.action_names:
            limits = self.sim.input_limits(name)
            if not limits["speed_command"] or not math.isfinite(limits["speed"]):
                raise ValueError(f"input '{name}' must take speed commands and have limits.speed to be an action")
            speeds.append(limits["speed"])
        self._speeds = np.array(speeds)
        self._hook, self._sheave = self.sim.joint(hook), self.sim.joint(sheave)
        n = len(self.action_names)
        self.action_space = spaces.Box(-1.0, 1.0, shape=(n,), dtype=np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(10 + 2 * n,), dtype=np.float32)
        self._start = self.sim.joint_position(self._hook)
        self._target = self._start.copy()

    @property
    def target(self) -> np.ndarray:
        """Where the load is to be brought (m, inertial frame), drawn by the last reset."""
        return self._target.copy()

    @property
    def speed_limits(self) -> np.ndarray:
        """Each input's speed limit: an action of ±1 commands it."""
        return self._speeds.copy()

    # -- the Gymnasium API -------------------------------------------------------------------
    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        rng = self.np_random
        if self._load_mass is not None:
            self._mass_now = float(rng.uniform(*self._load_mass))
            self.sim = Simulation(self._modified({f"bodies.{self._load_body}.mass": self._mass_now}))
            self._start = self.sim.joint_position(self._hook)
        else:
            self.sim.reset()
        angle = math.radians(rng.uniform(-self.slew, self.slew))
        radius = math.hypot(self._start[0], self._start[1])
        scale = (radius + rng.uniform(-self.reach, self.reach)) / radius
        c, s = math.cos(angle), math.sin(angle)
        x, y = self._start[0] * scale, self._start[1] * scale
        self._target = np.array([c * x - s * y, s * x + c * y, self._start[2] + rng.uniform(*self.lift)])
        return self._observation(), {"target": self._target.copy(), "load_mass": self._mass_now}

    def step(self, action):
        action = np.asarray(action, dtype=np.float64).reshape(-1)
        if not np.all(np.isfinite(action)):
            raise ValueError(f"the action {action} is not finite")
        self.sim.set_inputs(np.clip(action, -1.0, 1.0) * self._speeds)
        going = self.sim.step(self.dt)
        observation = self._observation()
        if not going and not self.sim.complete:
            return observation, -10.0, True, False, {"message": self.sim.message, "target": self._target.copy()}
        distance = float(np.linalg.norm(observation[0:3]))
        speed = float(np.linalg.norm(observation[3:6]))
        sway = float(np.hypot(observation[6], observation[7]))
        reward = -self.dt * (distance / 10.0 + (sway / 0.05) ** 2)
        arrived = distance < self.tolerance and speed < 0.05 and sway < 0.01
        if arrived:
            reward += 10.0
        truncated = not arrived and (self.sim.time >= self.episode_time - 1e-9 or not going)
        return observation, float(reward), arrived, truncated, {"target": self._target.copy()}

    def _modified(self, changes: dict) -> Scene:
        """The scene with the environment's tolerances and ``changes`` (``modify`` paths)."""
        changes = {**self._solver, **changes}
        if not changes:
            return self._scene
        if not isinstance(self._scene, Mapping):
            return {"base": os.path.abspath(os.fspath(self._scene)), "modify": changes}
        scene = copy.deepcopy(dict(self._scene))
        if "base" in scene:
            scene["modify"] = {**scene.get("modify", {}), **changes}
        else:
            for path, value in changes.items():  # only the solver's: load_mass needs a file
                section, key = path.split(".", 1)
                scene.setdefault(section, {})[key] = value
        return scene

    # -- observations ------------------------------------------------------------------------
    def _observation(self) -> np.ndarray:
        hook, hook_v = self.sim.joint_position(self._hook), self.sim.joint_velocity(self._hook)
        angles, rates = self.sim.sway(self._hook, self._sheave)
        return np.concatenate([hook - self._target, hook_v, angles, rates, self.sim.input_values(),
                               self.sim.input_rates()]).astype(np.float32)


class _SteppedAhead(gymnasium.Wrapper):
    """An environment whose next step may have been taken already, on another thread."""

    def __init__(self, env: gymnasium.Env):
        super().__init__(env)
        self.ahead = None

    def step(self, action):
        result, self.ahead = self.ahead, None
        return result if result is not None else self.env.step(action)


def _step_share(share):
    """Steps each (environment, action) of ``share``: the environments and their results."""
    return [(env, env.env.step(action)) for env, action in share]


class ThreadedVectorEnv(SyncVectorEnv):
    """Gymnasium's :class:`~gymnasium.vector.SyncVectorEnv`, with the environments' steps taken on
    ``threads`` threads (default: one per core) in the one process.

    The crane's integration releases Python's lock, so the steps of several environments run on
    several cores at once, without the processes, pipes and copies of
    :class:`~gymnasium.vector.AsyncVectorEnv`; resets and the batching are SyncVectorEnv's. The
    results are SyncVectorEnv's, bit for bit (each environment's run does not depend on the
    others')."""

    def __init__(self, env_fns: Sequence[Callable[[], gymnasium.Env]], threads: Optional[int] = None, **kwargs):
        super().__init__([lambda fn=fn: _SteppedAhead(fn()) for fn in env_fns], **kwargs)
        self._threads = threads or os.cpu_count() or 1
        self._pool = ThreadPoolExecutor(self._threads)

    def step(self, actions):
        stepping = [(env, action) for k, (env, action) in enumerate(zip(self.envs, iterate(self.action_space, actions)))
                    if not (self.autoreset_mode == AutoresetMode.NEXT_STEP and self._autoreset_envs[k])]
        # One task per thread, each stepping its share of the environments in turn: every task
        # handed to a thread costs a wake-up, which is dear beside a step of a fifth of a millisecond.
        shares = [stepping[k::self._threads] for k in range(self._threads)]
        for share in self._pool.map(_step_share, shares):
            for env, result in share:
                env.ahead = result
        return super().step(actions)

    def close_extras(self, **kwargs):
        self._pool.shutdown()
        super().close_extras(**kwargs)


gymnasium.register(id="cranesim/CraneLift-v0", entry_point="cranesim.gym:CraneLiftEnv")
