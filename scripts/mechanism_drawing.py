"""3-D line drawing of the mechanism in a results file, shared by plot_snapshot.py and animate.py.

Each body is drawn as segments from its origin to each of its joints, joints as
dots, ground joints as triangles and constraints as crosses midway between the
two joints they connect.
"""

from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import to_rgba
from mpl_toolkits.mplot3d.art3d import Line3DCollection

from cranesim.results import Results, ResultsError

GROUND = "ground"


def body_of(joint: str) -> str:
    return joint.split(".", 1)[0]


@dataclass
class MechanismGeometry:
    time: np.ndarray  # (N,)
    body_origins: np.ndarray  # (N, bodies, 3)
    joint_positions: np.ndarray  # (N, joints, 3)
    segment_ends: np.ndarray  # (segments, 2): body index, joint index
    member_segments: np.ndarray  # (segments, 2): joint indices of the element ends of members
    ground_joints: np.ndarray  # joint indices
    body_joints: np.ndarray  # joint indices of the other joints
    constraint_joints: np.ndarray  # (constraints, 2) joint indices

    @classmethod
    def load(cls, results: Results) -> "MechanismGeometry":
        time = results.sampled_time()
        bodies = list(results.names("model/bodies"))
        joints = list(results.names("model/joints"))
        joint_bodies = [body_of(joint) for joint in joints]
        constraint_ends = results.names("model/constraint_joints").reshape(-1, 2)
        unknown = sorted(set(constraint_ends.flat) - set(joints))
        if unknown:
            raise ResultsError(
                "/model/constraint_joints refers to joints missing from /model/joints: "
                + ", ".join(unknown)
            )
        segment_ends = [
            (bodies.index(body), joint) for joint, body in enumerate(joint_bodies) if body in bodies
        ]
        member_ends = (
            results.names("model/member_segments").reshape(-1, 2)
            if results.has("model/member_segments")
            else np.empty((0, 2), dtype=str)
        )
        return cls(
            time=time,
            body_origins=read_positions(results, "bodies/{}/position", bodies, time.size),
            joint_positions=read_positions(results, "joints/{}/position", joints, time.size),
            segment_ends=index_array(segment_ends, columns=2),
            member_segments=index_array(
                [[joints.index(a), joints.index(b)] for a, b in member_ends], columns=2
            ),
            ground_joints=index_array([j for j, body in enumerate(joint_bodies) if body == GROUND]),
            body_joints=index_array([j for j, body in enumerate(joint_bodies) if body != GROUND]),
            constraint_joints=index_array(
                [[joints.index(a), joints.index(b)] for a, b in constraint_ends], columns=2
            ),
        )

    def nearest_sample(self, time: float) -> int:
        return int(np.argmin(np.abs(self.time - time)))

    def segments(self, sample: int) -> np.ndarray:
        """(segments, 2, 3) start and end points of the body segments."""
        bodies, joints = self.segment_ends.T
        rigid = np.stack(
            [self.body_origins[sample, bodies], self.joint_positions[sample, joints]], axis=1
        )
        first, second = self.member_segments.T
        flexible = np.stack(
            [self.joint_positions[sample, first], self.joint_positions[sample, second]], axis=1
        )
        return np.concatenate([rigid, flexible], axis=0)

    def constraint_points(self, sample: int) -> np.ndarray:
        return self.joint_positions[sample, self.constraint_joints].mean(axis=1)

    def all_points(self, samples: slice | int = slice(None)) -> np.ndarray:
        origins = self.body_origins[samples].reshape(-1, 3)
        return np.concatenate([origins, self.joint_positions[samples].reshape(-1, 3)])


def read_positions(results: Results, path_pattern: str, names: list[str], samples: int):
    """(samples, names, 3) positions of the datasets path_pattern.format(name)."""
    if not names:
        return np.empty((samples, 0, 3))
    return np.stack([results.get(path_pattern.format(name)) for name in names], axis=1)


def index_array(indices: list, columns: int | None = None) -> np.ndarray:
    array = np.array(indices, dtype=int)
    return array if columns is None else array.reshape(-1, columns)


def set_equal_limits(axes, points: np.ndarray) -> None:
    """Same scale on x, y and z: a cube around all points, with a small margin."""
    low, high = np.nanmin(points, axis=0), np.nanmax(points, axis=0)
    centre = (low + high) / 2
    half_width = 0.55 * np.max(high - low) or 1.0
    axes.set_xlim(centre[0] - half_width, centre[0] + half_width)
    axes.set_ylim(centre[1] - half_width, centre[1] + half_width)
    axes.set_zlim(centre[2] - half_width, centre[2] + half_width)
    axes.set_box_aspect((1, 1, 1))


def create_figure(view: tuple[float, float] | None = None):
    figure = plt.figure(figsize=(7, 7))
    axes = figure.add_subplot(projection="3d")
    axes.set_xlabel("x [m]")
    axes.set_ylabel("y [m]")
    axes.set_zlabel("z [m]")
    if view is not None:
        axes.view_init(elev=view[0], azim=view[1])
    return figure, axes


class MechanismDrawing:
    """The artists for one mechanism; update() moves them to another sample."""

    def __init__(self, axes, geometry: MechanismGeometry, title: str):
        self.axes = axes
        self.geometry = geometry
        self.title = title
        # Rigid segments coloured by body, flexible members grey (segments() orders them so).
        colours = np.concatenate(
            [
                plt.get_cmap("tab10")(geometry.segment_ends[:, 0] % 10).reshape(-1, 4),
                np.tile(to_rgba("dimgray"), (len(geometry.member_segments), 1)),
            ]
        )
        self.segments = Line3DCollection(
            [], colors=colours if len(colours) else "dimgray", linewidths=2.5, label="body → joint"
        )
        axes.add_collection3d(self.segments)
        (self.joints,) = axes.plot([], [], [], "o", color="black", markersize=4, label="joint")
        (self.ground,) = axes.plot(
            [], [], [], "^", color="saddlebrown", markersize=11, label="ground joint"
        )
        (self.constraints,) = axes.plot(
            [], [], [], "x", color="red", markersize=7, markeredgewidth=1.5, label="constraint"
        )
        axes.legend(loc="upper left", fontsize="small")

    def update(self, sample: int) -> None:
        geometry = self.geometry
        self.segments.set_segments(geometry.segments(sample))
        self.joints.set_data_3d(*geometry.joint_positions[sample, geometry.body_joints].T)
        self.ground.set_data_3d(*geometry.joint_positions[sample, geometry.ground_joints].T)
        self.constraints.set_data_3d(*geometry.constraint_points(sample).T)
        self.axes.set_title(f"{self.title}   t = {geometry.time[sample]:.3f} s")
