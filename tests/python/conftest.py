"""Synthetic cranesim results files following docs/results-format.md.

The mechanism is a 2-link planar pendulum swinging in the x-z plane (gravity -z)
with a prescribed, analytic motion. The energy balance is built with a known
relative drift (ENERGY_DRIFT) and the residuals with known maxima, so the
report numbers can be checked exactly.
"""

import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

SCRIPTS = Path(__file__).resolve().parents[2] / "scripts"
sys.path.insert(0, str(SCRIPTS))

LINK_LENGTH = 2.0
LINK_MASS = 10.0
GRAVITY = 9.81
T_END = 2.0
SAMPLES = 41
ENERGY_DRIFT = 2.5e-3
MAX_POSITION_RESIDUAL = 3.0e-10
MAX_VELOCITY_RESIDUAL = 4.0e-9
SOLVER_STEPS = 1234
INCOMPLETE_MESSAGE = "solver failed at t = 0.7 s: repeated error test failures"

BODIES = ["link1", "link2"]
JOINTS = ["ground.pivot", "ground.anchor", "link1.base", "link1.tip", "link2.base", "link2.tip"]
CONSTRAINT_JOINTS = [
    ("pivot", "ground.pivot", "link1.base"),
    ("elbow", "link1.tip", "link2.base"),
    ("drive", "ground.pivot", "link1.base"),
]
CONSTRAINT_ROWS = (
    [f"pivot/{c}" for c in ("x", "y", "z", "rx", "rz")]
    + [f"elbow/{c}" for c in ("x", "y", "z", "rx", "rz")]
    + ["drive/angle"]
)


def rotation_about_y(angle: np.ndarray) -> np.ndarray:
    c, s, zero, one = np.cos(angle), np.sin(angle), np.zeros_like(angle), np.ones_like(angle)
    return np.stack([np.stack([c, zero, s], -1), np.stack([zero, one, zero], -1),
                     np.stack([-s, zero, c], -1)], -2)


def link_direction(angle: np.ndarray) -> np.ndarray:
    """Body axis -z rotated about y: where the link hangs."""
    return np.stack([-np.sin(angle), np.zeros_like(angle), -np.cos(angle)], -1)


def link_direction_rate(angle: np.ndarray, rate: np.ndarray) -> np.ndarray:
    return rate[:, None] * np.stack([-np.cos(angle), np.zeros_like(angle), np.sin(angle)], -1)


def pendulum(time: np.ndarray) -> dict:
    """Absolute link angles, positions and velocities of the prescribed motion."""
    angle1 = 0.6 * np.sin(np.pi * time)
    rate1 = 0.6 * np.pi * np.cos(np.pi * time)
    angle2 = angle1 + 0.4 * np.sin(1.6 * np.pi * time + 0.3)
    rate2 = rate1 + 0.4 * 1.6 * np.pi * np.cos(1.6 * np.pi * time + 0.3)
    elbow = LINK_LENGTH * link_direction(angle1)
    elbow_velocity = LINK_LENGTH * link_direction_rate(angle1, rate1)
    return {
        "angle": [angle1, angle2],
        "rate": [rate1, rate2],
        "origin": [elbow / 2, elbow + LINK_LENGTH / 2 * link_direction(angle2)],
        "velocity": [elbow_velocity / 2,
                     elbow_velocity + LINK_LENGTH / 2 * link_direction_rate(angle2, rate2)],
        "elbow": elbow,
        "tip": elbow + LINK_LENGTH * link_direction(angle2),
    }


def write_results(path: Path, samples: int = SAMPLES, status: str = "complete",
                  message: str = "") -> Path:
    time = np.linspace(0.0, T_END, SAMPLES)[:samples]
    motion = pendulum(time)
    zeros = np.zeros((samples, 3))
    identity = np.broadcast_to(np.eye(3), (samples, 3, 3))
    rotations = [rotation_about_y(angle) for angle in motion["angle"]]
    joint_frames = {
        "ground.pivot": (zeros, identity),
        "ground.anchor": (zeros + [1.5, 0.0, 0.0], identity),
        "link1.base": (zeros, rotations[0]),
        "link1.tip": (motion["elbow"], rotations[0]),
        "link2.base": (motion["elbow"], rotations[1]),
        "link2.tip": (motion["tip"], rotations[1]),
    }

    inertia = LINK_MASS * LINK_LENGTH**2 / 12
    kinetic = sum(0.5 * LINK_MASS * np.sum(v**2, axis=1) + 0.5 * inertia * w**2
                  for v, w in zip(motion["velocity"], motion["rate"]))
    potential = sum(LINK_MASS * GRAVITY * origin[:, 2] for origin in motion["origin"])
    # The drive does the work that changes T + V; the drift is booked as load work, which the
    # energy scale counts too: S = max(T + |V - V0| + |drive| + |load|), load = -δ S (t/T)².
    drive_work = kinetic + potential - kinetic[0] - potential[0]
    unloaded = kinetic + np.abs(potential - potential[0]) + np.abs(drive_work)
    scale = np.max(unloaded)
    for _ in range(50):
        scale = np.max(unloaded + ENERGY_DRIFT * scale * (time / T_END) ** 2)
    load_work = -ENERGY_DRIFT * scale * (time / T_END) ** 2
    balance = kinetic + potential - drive_work - load_work

    with h5py.File(path, "w") as f:
        f.attrs.update({
            "engine_version": "0.0.0-test",
            "scene_path": "scenes/double_pendulum.yaml",
            "scene_text": "bodies: [link1, link2]\n",
            "status": status,
            "message": message,
            "formulation": "ggl",
            "t_end_requested": T_END,
        })
        f["time"] = time
        f["q"] = np.concatenate([np.column_stack([origin, 0 * angle, angle, 0 * angle])
                                 for origin, angle in zip(motion["origin"], motion["angle"])], 1)
        f["v"] = np.concatenate([np.column_stack([velocity, 0 * rate, rate, 0 * rate])
                                 for velocity, rate in zip(motion["velocity"], motion["rate"])], 1)
        f["lambda"] = np.outer(np.cos(time), 100.0 * np.arange(1, len(CONSTRAINT_ROWS) + 1))
        for body, origin, velocity, rotation, rate in zip(
                BODIES, motion["origin"], motion["velocity"], rotations, motion["rate"]):
            f[f"bodies/{body}/position"] = origin
            f[f"bodies/{body}/rotation"] = rotation
            f[f"bodies/{body}/velocity"] = velocity
            f[f"bodies/{body}/angular_velocity"] = np.column_stack([0 * rate, rate, 0 * rate])
        for joint, (position, rotation) in joint_frames.items():
            f[f"joints/{joint}/position"] = position
            f[f"joints/{joint}/rotation"] = rotation
        f["energy/kinetic"] = kinetic
        f["energy/potential"] = potential
        f["energy/drive_work"] = drive_work
        f["energy/load_work"] = load_work
        f["energy/balance"] = balance
        f["residual/position"] = MAX_POSITION_RESIDUAL * time / T_END
        f["residual/velocity"] = MAX_VELOCITY_RESIDUAL * np.sin(np.pi / 2 * time / T_END)
        strings = h5py.string_dtype()
        f.create_dataset("model/bodies", data=BODIES, dtype=strings)
        f.create_dataset("model/joints", data=JOINTS, dtype=strings)
        f.create_dataset("model/constraint_rows", data=CONSTRAINT_ROWS, dtype=strings)
        f.create_dataset("model/constraints", data=[c[0] for c in CONSTRAINT_JOINTS], dtype=strings)
        f.create_dataset("model/constraint_joints", data=[c[1:] for c in CONSTRAINT_JOINTS],
                         dtype=strings)
        f.create_group("solver").attrs.update({
            "steps": SOLVER_STEPS, "residual_evaluations": 5000, "jacobian_evaluations": 300,
            "linear_setups": 310, "nonlinear_iterations": 2500, "nonlinear_failures": 2,
            "error_test_failures": 7, "reparameterisations": 1, "wall_time_s": 0.42,
            "rtol": 1e-6, "atol": 1e-8, "last_step_size": 1e-3, "last_order": 3,
        })
    return path


@pytest.fixture(scope="session")
def results_file(tmp_path_factory) -> Path:
    return write_results(tmp_path_factory.mktemp("complete") / "pendulum.h5")


@pytest.fixture(scope="session")
def incomplete_results_file(tmp_path_factory) -> Path:
    return write_results(tmp_path_factory.mktemp("incomplete") / "pendulum_failed.h5",
                         samples=15, status="incomplete", message=INCOMPLETE_MESSAGE)
