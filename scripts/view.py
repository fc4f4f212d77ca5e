"""Interactive 3-D replay of a cranesim run as ONE self-contained HTML page.

The page opens offline in any current browser (no server, no network): three.js with its
OrbitControls and Lut (Debian's package libjs-three, revision 111, MIT licence) is inlined, and
the run rides along as float32 arrays in base64, decimated to --frames frames.

It shows the rigid bodies (each as a translucent box of the body's mass and inertia when the
scene gives them, and always as its joint skeleton: origin → joints), the flexible members
along their nodes (ropes as lines, beams and truss tubes as tubes; ropes and strut ties
coloured by their end force), the load and its trace, a ground grid with its spacing, orbit /
pan / zoom, a time slider with play, pause and speed, a camera that follows the load, and side
plots (load position, energies, rope end forces) whose cursor follows the time. Time, camera
and follow mode live in the URL's fragment, e.g. crane.html#t=12.5, so a link opens the page
at a moment.

A modes file (crane-sim modes) becomes a page that animates each mode shape about the
equilibrium; a plan file (crane-opt plan) one that replays its verification run
(<plan>_simulation.h5 beside it) with the planned and simulated paths, start and target.

Examples:

    python scripts/view.py run.h5 -o run.html --frames 600
    python scripts/view.py modes.h5 -o modes.html
    python scripts/view.py plan.h5 -o plan.html
"""

import argparse
import base64
import html
import json
import re
import sys
from pathlib import Path

import numpy as np

from cranesim.results import Results, ResultsError, run_command
from mechanism_drawing import MechanismGeometry, body_of

HERE = Path(__file__).resolve().parent
PAGE_TEMPLATE = HERE / "view_page" / "page.html"
PAGE_SCRIPT = HERE / "view_page" / "replay.js"
THREE_DIRECTORIES = (Path("/usr/share/javascript/three"),)
THREE_FILES = ("three.min.js", "examples/js/controls/OrbitControls.js", "examples/js/math/Lut.js")
THREE_REVISION = "111"  # Debian bookworm's libjs-three 111+dfsg1; the page is written for it
DEFAULT_FRAMES = 1000
LARGE_PAGE = 20e6  # bytes: above this a page takes many seconds to open; view.py says so


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("results", help="results (crane-sim run), modes (crane-sim modes) or plan "
                                        "(crane-opt plan) file, .h5")
    parser.add_argument("-o", "--output", help="output page (default: <results>.html)")
    parser.add_argument(
        "--frames", type=int, default=DEFAULT_FRAMES,
        help=f"at most this many frames, evenly spread over the run (default: {DEFAULT_FRAMES})",
    )
    parser.add_argument(
        "--load", metavar="BODY",
        help="body whose origin is the load (traced, followed, plotted; default: 'load' if the "
             "run has it, else the last body)",
    )
    args = parser.parse_args()
    if args.frames < 2:
        parser.error("--frames must be at least 2")
    return args


# ---------------------------------------------------------------------------------------------
# What the scene text says about shapes (best effort: the engine validated the scene already)

def scene_description(scene_text: str) -> dict:
    """The scene with its `base` scenes and `modify` paths resolved, as plain data.

    scene_text is the scene followed by its base scenes (each after a line
    '# ---- base scene: PATH ----'). Returns {} when it cannot be read.
    """
    try:
        import yaml
    except ImportError:
        return {}
    parts = re.split(r"^# ---- base scene: .* ----$", scene_text, flags=re.MULTILINE)
    try:
        documents = [yaml.safe_load(part) or {} for part in parts]
    except yaml.YAMLError:
        return {}
    scene: dict = {}
    for document in reversed(documents):  # the deepest base first
        if not isinstance(document, dict):
            return {}
        scene.update({k: v for k, v in document.items() if k not in ("base", "modify")})
        for path, value in (document.get("modify") or {}).items():
            apply_modification(scene, str(path).split("."), value)
    return scene


def apply_modification(node, keys: list[str], value) -> None:
    """Set node[k1][k2]… = value, where a list's item is named by its `name` field."""
    for i, key in enumerate(keys):
        last = i == len(keys) - 1
        if isinstance(node, list):
            items = [item for item in node if isinstance(item, dict) and item.get("name") == key]
            if not items:
                return
            if last:
                node[node.index(items[0])] = value
                return
            node = items[0]
        elif isinstance(node, dict):
            if last:
                node[key] = value
                return
            node = node.get(key)
        else:
            return


def named_items(scene: dict, key: str) -> dict:
    items = scene.get(key) or []
    if not isinstance(items, list):
        return {}
    return {str(item["name"]): item for item in items if isinstance(item, dict) and "name" in item}


def inertia_box(body: dict) -> dict | None:
    """Edges and placement of the uniform box with the body's mass and inertia about its centroid.

    A box of edges a, b, c has I = m/12 (b² + c², …), so a² = 6 (I2 + I3 − I1) / m. Returns
    {"centroid": [3], "axes": 3×3 (columns: principal axes in body axes), "edges": [3]} or None.
    """
    try:
        mass = float(body["mass"])
        inertia = np.asarray(body["inertia"], dtype=float)
        centroid = np.asarray(body.get("centroid", [0, 0, 0]), dtype=float).reshape(3)
    except (KeyError, TypeError, ValueError):
        return None
    if inertia.shape == (3,):
        tensor = np.diag(inertia)
    elif inertia.shape == (6,):
        xx, yy, zz, xy, xz, yz = inertia
        tensor = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    elif inertia.shape == (3, 3):
        tensor = inertia
    else:
        return None
    if mass <= 0 or not np.all(np.isfinite(tensor)):
        return None
    principal, axes = np.linalg.eigh((tensor + tensor.T) / 2)
    squares = 6.0 / mass * (principal.sum() - 2.0 * principal)
    edges = np.sqrt(np.clip(squares, 0.0, None))
    if not np.all(np.isfinite(edges)) or edges.max() <= 0:
        return None
    edges = np.maximum(edges, 0.02 * edges.max())  # a rod or a plate stays visible
    return {"centroid": centroid.tolist(), "axes": axes.tolist(), "edges": edges.tolist()}


def member_radius(member: dict, trusses: dict) -> float | None:
    """Outer radius of a member's tube: its section's, or its truss' main tubes'."""
    section = member.get("section")
    if member.get("type") == "truss":
        truss = trusses.get(str(member.get("truss")), {})
        section = ((truss.get("tubes") or {}).get("main")) if isinstance(truss, dict) else None
    if not isinstance(section, dict):
        return None
    for key in ("outer_radius", "radius"):
        if isinstance(section.get(key), (int, float)):
            return float(section[key])
    if isinstance(section.get("area"), (int, float)) and section["area"] > 0:
        return float(np.sqrt(section["area"] / np.pi))
    return None


# ---------------------------------------------------------------------------------------------
# Reading the run

def check_results_file(results: Results) -> None:
    """One-line refusal of an HDF5 file that is not a cranesim results, modes or plan file."""
    analysis = results.attribute("analysis")
    contents = results.attribute("contents")
    if contents == "map":
        raise ResultsError(f"{results.path} is a map file (crane-opt map): it holds no run to "
                           "show; plot it with scripts/plot_plan.py")
    if contents == "plan":
        return
    if analysis == "modes" and results.attribute("engine_version") is not None:
        return
    missing = [path for path in ("time", "model/bodies", "model/joints") if not results.has(path)]
    if results.attribute("engine_version") is None or missing:
        what = f"no {', '.join('/' + path for path in missing)}" if missing else "no engine_version"
        raise ResultsError(f"{results.path} is not a cranesim results file ({what})")


def frame_samples(sample_count: int, frames: int) -> np.ndarray:
    """At most `frames` sample indices evenly spread over the run, first and last included."""
    if sample_count <= frames:
        return np.arange(sample_count)
    return np.unique(np.round(np.linspace(0, sample_count - 1, frames)).astype(int))


def encode(array) -> str:
    """float32, little-endian, base64: what the page decodes into a Float32Array."""
    return base64.b64encode(np.ascontiguousarray(array, dtype="<f4").tobytes()).decode("ascii")


def nice_spacing(length: float) -> float:
    """1, 2 or 5 × 10^k near length / 10: the ground grid's spacing."""
    raw = max(length, 1e-9) / 10
    power = 10.0 ** np.floor(np.log10(raw))
    return float(min((step * power for step in (1, 2, 5, 10)), key=lambda s: abs(s - raw)))


def choose_load(bodies: list[str], requested: str | None) -> int:
    if requested is not None:
        if requested not in bodies:
            raise ResultsError(f"--load {requested}: no such body; bodies: {', '.join(bodies)}")
        return bodies.index(requested)
    if "load" in bodies:
        return bodies.index("load")
    return len(bodies) - 1  # -1: no body at all


def constraint_forces(results: Results, samples: np.ndarray) -> dict:
    """{constraint: (its two joints, |force| per sample)} for every constraint with x, y, z rows
    (spherical, revolute, fixed, …): the magnitude of the force it transmits."""
    if not results.has("lambda") or not results.has("model/constraint_rows"):
        return {}
    rows = {name: i for i, name in enumerate(results.names("model/constraint_rows"))}
    names = results.names("model/constraints")
    ends = results.names("model/constraint_joints").reshape(-1, 2)
    lambdas = results.get("lambda")[samples]
    forces = {}
    for name, joints in zip(names, ends):
        columns = [rows.get(f"{name}/{c}") for c in "xyz"]
        if None not in columns:
            forces[name] = (tuple(joints), np.linalg.norm(lambdas[:, columns], axis=1))
    return forces


def holds_end_of(joints: tuple, members: set[str]) -> list[str]:
    """The members of `members` whose start or end is one of the joints."""
    return [body_of(j) for j in joints
            if body_of(j) in members and j.split(".", 1)[1] in ("start", "end")]


JOINT_INDEX = re.compile(r"^(?P<member>[^.]+)\.(?:n(?P<node>\d+)|s(?P<section>\d+)n(?P<end>\d+)|"
                         r"c(?P<chord>\d+)k(?P<station>\d+))$")


def segments_from_names(joints: list[str], scene: dict) -> tuple[list, list, list, list]:
    """(bodies, skeleton [origin, joint, body index], ropes [a, b], tubes [a, b, radius]) from
    joint names: the bodies are the owners of the joints <body>.origin.

    For files without /model/member_segments (modes files): a body's origin joins each of its
    joints; a member's nodes n0, n1, … join in order; a truss' chords run from end section 1
    through the internal nodes c<chord>k1, k2, … to end section 2 (its main_beams say which
    end nodes), and each end section's cross beams join its nodes (as the scene's truss says,
    else in a ring).
    """
    index = {name: i for i, name in enumerate(joints)}
    members = named_items(scene, "members")
    trusses = named_items(scene, "trusses")
    bodies = [name[: -len(".origin")] for name in joints
              if name.endswith(".origin") and not name.startswith("ground.")]
    skeleton = [[index[f"{body}.origin"], i, b] for b, body in enumerate(bodies)
                for i, name in enumerate(joints)
                if body_of(name) == body and name != f"{body}.origin"]
    nodes, ends, chords = {}, {}, {}
    for i, name in enumerate(joints):
        match = JOINT_INDEX.match(name)
        if match is None:
            continue
        member = match["member"]
        if match["node"] is not None:
            nodes.setdefault(member, []).append((int(match["node"]), i))
        elif match["section"] is not None:
            ends.setdefault(member, {})[(int(match["section"]), int(match["end"]))] = i
        else:
            chords.setdefault(member, {}).setdefault(int(match["chord"]), []).append(
                (int(match["station"]), i))
    ropes, tubes = [], []

    def add(member: str, a: int, b: int) -> None:
        spec = members.get(member, {})
        if spec.get("type") == "rope":
            ropes.append([a, b, -1])
        else:
            tubes.append([a, b, member_radius(spec, trusses) or 0.0, -1])

    for member, chain in nodes.items():
        chain = [i for _, i in sorted(chain)]
        for a, b in zip(chain, chain[1:]):
            add(member, a, b)
    for member, section_nodes in ends.items():
        truss = trusses.get(str(members.get(member, {}).get("truss")), {})
        sections = truss.get("sections") if isinstance(truss, dict) else None
        for section in (1, 2):
            numbers = sorted(k for s_, k in section_nodes if s_ == section)
            try:
                pairs = sections[section - 1]["cross_beams"]
            except (TypeError, IndexError, KeyError):
                pairs = list(zip(numbers, numbers[1:] + numbers[:1])) if len(numbers) > 2 else (
                    [numbers] if len(numbers) == 2 else [])
            for a, b in pairs:
                if (section, a) in section_nodes and (section, b) in section_nodes:
                    add(member, section_nodes[(section, a)], section_nodes[(section, b)])
        main_beams = truss.get("main_beams") if isinstance(truss, dict) else None
        if not main_beams:
            main_beams = [[k, k] for s_, k in section_nodes if s_ == 1 and (2, k) in section_nodes]
        for chord, (a, b) in enumerate(main_beams, start=1):
            if (1, a) not in section_nodes or (2, b) not in section_nodes:
                continue
            inside = [i for _, i in sorted(chords.get(member, {}).get(chord, []))]
            chain = [section_nodes[(1, a)], *inside, section_nodes[(2, b)]]
            for p, q in zip(chain, chain[1:]):
                add(member, p, q)
    return bodies, skeleton, ropes, tubes


def bounds_of(points: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    finite = points.reshape(-1, 3)
    finite = finite[np.all(np.isfinite(finite), axis=-1)]
    low, high = (finite.min(axis=0), finite.max(axis=0)) if finite.size else (np.zeros(3),) * 2
    return low, high, float(np.linalg.norm(high - low)) or 1.0


def up_direction(scene: dict) -> list[float]:
    gravity = np.asarray(scene.get("gravity", [0, 0, -9.81]), dtype=float).reshape(-1)
    if gravity.size == 3 and np.any(gravity):
        return list(map(float, -gravity / np.linalg.norm(gravity)))
    return [0.0, 0.0, 1.0]


def file_fields(results: Results, scene: dict) -> dict:
    """What every page says about the file it shows."""
    return {
        "file": results.path.name,
        "scene": str(scene.get("name") or results.attribute("scene_path") or ""),
        "status": results.status,
        "message": results.message,
        "engine_version": results.attribute("engine_version"),
    }


def view_fields(low: np.ndarray, high: np.ndarray, size: float, scene: dict) -> dict:
    """The extent of what a page shows, its grid and which way is up."""
    return {
        "bounds": [low.tolist(), high.tolist()],
        "size": size,
        "grid_spacing": nice_spacing(float(np.max(high - low))),
        "up": up_direction(scene),
    }


def rotation_matrix(rotation_vector: np.ndarray) -> np.ndarray:
    """Rodrigues' formula: the rotation by |φ| about φ/|φ| (the rotation vector of /q)."""
    angle = float(np.linalg.norm(rotation_vector))
    if angle < 1e-12:
        return np.eye(3)
    x, y, z = rotation_vector / angle
    axis = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + np.sin(angle) * axis + (1 - np.cos(angle)) * axis @ axis


def inertia_tensor(inertia) -> np.ndarray | None:
    values = np.asarray(inertia, dtype=float)
    if values.shape == (3,):
        return np.diag(values)
    if values.shape == (6,):
        xx, yy, zz, xy, xz, yz = values
        return np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    return values if values.shape == (3, 3) else None


def kinetic_energy_shares(results: Results, scene: dict) -> list | None:
    """Per mode, [[part, share of the mode's kinetic energy], …], largest first.

    The shapes are mass-normalised (φᵀMφ = 1) and each body has its own coordinates, so a rigid
    body's share is m |v + R (ω × c)|² + ωᵀ I ω, with v, ω the shape's origin velocity
    (inertial) and angular velocity (body axes), R the body's rotation at the equilibrium, c its
    centroid and I its inertia about the centroid (from the scene); the flexible members share
    the rest. None when the file or the scene does not give what this needs.
    """
    if not (results.has("modes/shapes") and results.has("model/velocity_labels")
            and results.has("equilibrium/q")):
        return None
    labels = {name: i for i, name in enumerate(results.names("model/velocity_labels"))}
    q = results.get("equilibrium/q").reshape(-1)
    shapes = results.get("modes/shapes")
    if len(q) != len(labels) or shapes.ndim != 2 or shapes.shape[1] != len(labels):
        return None
    parts = []
    for name, body in named_items(scene, "bodies").items():
        columns = [labels.get(f"{name}.{c}") for c in ("r_x", "r_y", "r_z", "theta_x", "theta_y",
                                                       "theta_z")]
        try:
            mass = float(body["mass"])
            inertia = inertia_tensor(body["inertia"])
            centroid = np.asarray(body.get("centroid", [0, 0, 0]), dtype=float).reshape(3)
        except (KeyError, TypeError, ValueError):
            return None
        if None in columns or inertia is None:
            return None
        rotation = rotation_matrix(q[columns[3:]])
        velocity, omega = shapes[:, columns[:3]], shapes[:, columns[3:]]
        centroid_velocity = velocity + np.cross(omega, centroid) @ rotation.T
        parts.append((name, mass * np.sum(centroid_velocity**2, axis=1)
                      + np.einsum("ki,ij,kj->k", omega, inertia, omega)))
    body_columns = 6 * len(parts)
    if len(labels) > body_columns:
        rest = 1.0 - sum(share for _, share in parts)
        parts.append(("flexible members", np.clip(rest, 0.0, None)))
    return [sorted(([name, float(share[k])] for name, share in parts), key=lambda p: -p[1])
            for k in range(shapes.shape[0])]


def modes_page_data(results: Results, load_name: str | None) -> dict:
    """A modes file (crane-sim modes): each mode shape about the equilibrium, to animate."""
    for path in ("model/joints", "equilibrium/joint_positions", "modes/joint_displacements",
                 "modes/frequency"):
        if not results.has(path):
            raise ResultsError(f"{results.path} is a modes file without /{path}")
    joints = list(results.names("model/joints"))
    equilibrium = results.get("equilibrium/joint_positions").reshape(len(joints), 3)
    displacements = results.get("modes/joint_displacements").reshape(-1, len(joints), 3)
    frequency = results.get("modes/frequency").reshape(-1)
    if len(frequency) == 0:
        raise ResultsError(f"{results.path} holds no modes")
    largest = np.linalg.norm(displacements, axis=-1).max(axis=-1)
    shapes = displacements / np.where(largest > 0, largest, 1.0)[:, None, None]
    scene = scene_description(results.attribute("scene_text") or "")
    bodies, skeleton, ropes, tubes = segments_from_names(joints, scene)
    if load_name is not None and f"{load_name}.origin" not in joints:
        raise ResultsError(f"--load {load_name}: no joint '{load_name}.origin' in {results.path}")
    load_body = load_name or ("load" if "load.origin" in joints else (bodies[-1] if bodies else None))
    load = joints.index(f"{load_body}.origin") if load_body else -1
    low, high, size = bounds_of(equilibrium)
    return {
        "kind": "modes",
        **file_fields(results, scene),
        "t_end_requested": None,
        "sample_count": 1,
        "frame_count": 2,
        "body_names": bodies,
        "joint_names": joints,
        "point_count": len(joints),
        "time": encode([0.0, 1.0]),                      # one cycle of the shown mode
        "points": encode(np.stack([equilibrium, equilibrium])),
        "rotations": encode(np.empty((2, 0))),
        "skeleton": skeleton,
        "ground_points": [i for i, name in enumerate(joints) if body_of(name) == "ground"],
        "ropes": ropes,
        "tubes": tubes,
        "boxes": [None] * len(bodies),
        "load": load,
        "load_name": load_body,
        **view_fields(low, high, size, scene),
        "series": [],
        "modes": {
            "frequency": frequency.tolist(),
            "omega_squared": results.get("modes/omega_squared").reshape(-1).tolist()
            if results.has("modes/omega_squared") else None,
            "rigid_modes": results.attribute("rigid_modes"),
            "energy_shares": kinetic_energy_shares(results, scene),
            "shapes": encode(shapes),                    # modes × joints × 3, largest = 1
            "amplitude": 0.05 * size,
        },
    }


def plan_obstacles(target: dict, plan: Results) -> list[dict]:
    """The target's obstacles as the page draws them (world coordinates, yaw in radians), each with
    its smallest verified clearance over the crane's parts (the plan's /clearance), m."""
    obstacles = []
    closest = {}
    if plan.has("clearance/minimum") and plan.has("clearance/obstacle"):
        names = [str(name) for name in plan.names("clearance/obstacle")]
        closest = dict(zip(names, np.atleast_2d(plan.get("clearance/minimum")).min(axis=1)))
    for obstacle in target.get("obstacles") or []:
        shape = obstacle.get("shape")
        drawn = {"name": str(obstacle.get("name", "")), "shape": shape}
        if shape == "box":
            drawn.update(centre=obstacle["centre"], size=obstacle["size"], yaw=np.radians(obstacle.get("yaw", 0.0)))
        elif shape == "cylinder":
            drawn.update(base=obstacle["base"], radius=obstacle["radius"], height=obstacle["height"])
        elif shape == "prism":
            drawn.update(footprint=obstacle["footprint"], bottom=obstacle["bottom"], top=obstacle["top"])
        else:
            continue
        if drawn["name"] in closest:
            drawn["clearance"] = float(closest[drawn["name"]])
        obstacles.append(drawn)
    return obstacles


def plan_page_data(plan: Results, frames: int, load_name: str | None) -> dict:
    """A plan file (crane-opt plan): its verification run replayed, with the planned path, the
    simulated end point's path, the start and the target, and the tracking error."""
    simulation_path = plan.path.with_name(plan.path.stem + "_simulation.h5")
    if not simulation_path.is_file():
        raise ResultsError(f"{plan.path} is a plan file, but its verification run "
                           f"{simulation_path.name} is not beside it")
    for path in ("verification/t", "verification/planned", "verification/simulated"):
        if not plan.has(path):
            raise ResultsError(f"{plan.path} is a plan file without /{path}")
    with Results(simulation_path) as simulation:
        data = page_data(simulation, frames, load_name)
    if data["kind"] != "results":
        raise ResultsError(f"{simulation_path} is not a results file")
    t = plan.get("verification/t")
    simulated = plan.get("verification/simulated").reshape(-1, 3)
    planned = plan.get("verification/planned")
    if planned.size == 2 * len(t):  # files before slewing plans: (x, z) in the crane's plane y = 0
        planned_xz = planned.reshape(-1, 2)
        planned = np.column_stack([planned_xz[:, 0], np.zeros(len(planned_xz)), planned_xz[:, 1]])
    planned = planned.reshape(-1, 3)  # world x, y, z (a slewing plan turns the crane's plane)
    frame_time = np.frombuffer(base64.b64decode(data["time"]), dtype="<f4").astype(float)
    at_frames = np.column_stack([np.interp(frame_time, t, planned[:, i]) for i in range(3)])
    simulated_at_frames = np.column_stack([np.interp(frame_time, t, simulated[:, i])
                                           for i in range(3)])
    start, target = planned[0], planned[-1]
    attributes = {name: plan.attribute(name, "verification")
                  for name in ("max_error", "rms_error", "residual_sway", "final_error",
                               "status", "message")}
    error = np.linalg.norm(simulated_at_frames - at_frames, axis=1)
    axes = (0, 1, 2) if np.ptp(planned[:, 1]) > 1e-6 else (0, 2)  # y only when the plan slews
    curves = []
    for axis in axes:
        name = "xyz"[axis]
        curves += [{"label": f"{name} planned (dashed)", "values": encode(at_frames[:, axis]), "colour": axis,
                    "dashed": True},
                   {"label": f"{name} simulated", "values": encode(simulated_at_frames[:, axis]), "colour": axis}]
    data["series"][:0] = [
        {"title": "end point: planned against simulated", "unit": "m", "curves": curves},
        {"title": "tracking error ‖simulated − planned‖", "unit": "m",
         "curves": [{"label": "error", "values": encode(error)}]},
    ]
    target_file = {}
    try:
        import yaml
        target_file = yaml.safe_load(plan.attribute("target_text") or "") or {}
    except Exception:  # the name and obstacles are decoration; the plan is shown without them
        pass
    clearance = {name: plan.attribute(name, "clearance")
                 for name in ("status", "margin", "distance", "t", "closest_part", "closest_obstacle")} \
        if plan.has("clearance") else None
    data["plan"] = {
        "file": plan.path.name,
        "name": str(target_file.get("name", "")),
        "obstacles": plan_obstacles(target_file, plan),
        "clearance": clearance,
        "planned": encode(at_frames),            # the planned end point at each frame
        "planned_path": encode(planned),
        "simulated_path": encode(simulated),
        "start": [float(v) for v in start],
        "target": [float(v) for v in target],
        "verification": attributes,
    }
    return data


def page_data(results: Results, frames: int, load_name: str | None) -> dict:
    check_results_file(results)
    if results.attribute("analysis") == "modes":
        return modes_page_data(results, load_name)
    if results.attribute("contents") == "plan":
        return plan_page_data(results, frames, load_name)
    geometry = MechanismGeometry.load(results)
    bodies = list(results.names("model/bodies"))
    joints = list(results.names("model/joints"))
    samples = frame_samples(geometry.time.size, frames)
    time = geometry.time[samples]

    scene = scene_description(results.attribute("scene_text") or "")
    body_specs = named_items(scene, "bodies")
    member_specs = named_items(scene, "members")
    trusses = named_items(scene, "trusses")

    # Points: body origins first, then joints; segments index them.
    points = np.concatenate([geometry.body_origins, geometry.joint_positions], axis=1)[samples]
    low, high, size = bounds_of(points)
    body_count = len(bodies)

    # Ropes and strut ties carry only axial force: the force at the constraints that hold
    # their ends is their end tension (or compression), which colours them.
    forces = constraint_forces(results, samples)
    two_force = {name for name, spec in member_specs.items()
                 if spec.get("type") in ("rope", "strut_tie")}
    member_force = {}
    for joints_held, magnitude in forces.values():
        for member in holds_end_of(joints_held, two_force):
            member_force.setdefault(member, []).append(magnitude)
    force_members = sorted(member_force, key=lambda m: list(member_specs).index(m))

    skeleton = [[int(b), body_count + int(j), int(b)] for b, j in geometry.segment_ends]
    ropes, tubes = [], []
    rope_members = set()
    for a, b in geometry.member_segments:
        member = body_of(joints[a])
        spec = member_specs.get(member, {})
        coloured = force_members.index(member) if member in force_members else -1
        if spec.get("type") == "rope":
            rope_members.add(member)
            ropes.append([body_count + int(a), body_count + int(b), coloured])
        else:
            radius = member_radius(spec, trusses)
            tubes.append([body_count + int(a), body_count + int(b), radius or 0.0, coloured])

    rotations = (np.stack([results.get(f"bodies/{name}/rotation") for name in bodies], axis=1)
                 [samples].reshape(len(samples), -1) if bodies else np.empty((len(samples), 0)))
    load = choose_load(bodies, load_name)
    series = []
    if load >= 0:
        origin = geometry.body_origins[samples, load]
        title = "load position" if bodies[load] == "load" else f"load ({bodies[load]}) position"
        series.append({"title": title, "unit": "m", "curves": [
            {"label": axis, "values": encode(origin[:, i])} for i, axis in enumerate("xyz")]})
    energy = {name: results.get(f"energy/{name}")[samples]
              for name in ("kinetic", "potential", "drive_work", "load_work", "winch_work", "dissipated", "balance")
              if results.has(f"energy/{name}")}
    if energy:
        curves = [{"label": "kinetic" if name == "kinetic" else f"Δ{name.replace('_', ' ')}",
                   "values": encode(values - (0 if name == "kinetic" else values[0]))}
                  for name, values in energy.items() if name != "balance"]
        series.append({"title": "energies (changes from the start)", "unit": "J",
                       "curves": curves})
        if "balance" in energy:
            series.append({"title": "energy balance K + P − W + D (change)", "unit": "J",
                           "curves": [{"label": "balance − balance(0)", "values": encode(
                               energy["balance"] - energy["balance"][0])}]})
    rope_ends = [{"label": f"{name} |F|", "values": encode(magnitude)}
                 for name, (joints_held, magnitude) in forces.items()
                 if holds_end_of(joints_held, rope_members)]
    if rope_ends:
        series.append({"title": "rope end forces", "unit": "N", "curves": rope_ends})
    member_forces = None
    if force_members:
        values = np.stack([np.mean(member_force[m], axis=0) for m in force_members], axis=1)
        member_forces = {"members": force_members, "values": encode(values),
                         "range": [float(values.min()), float(values.max())]}

    return {
        "kind": "results",
        **file_fields(results, scene),
        "t_end_requested": results.attribute("t_end_requested"),
        "sample_count": int(geometry.time.size),
        "frame_count": int(len(samples)),
        "body_names": bodies,
        "joint_names": joints,
        "point_count": int(points.shape[1]),
        "time": encode(time),
        "points": encode(points),
        "rotations": encode(rotations),
        "skeleton": skeleton,
        "ground_points": [body_count + int(j) for j in geometry.ground_joints],
        "ropes": ropes,
        "tubes": tubes,
        "boxes": [inertia_box(body_specs.get(name, {})) for name in bodies],
        "load": load,
        "load_name": bodies[load] if load >= 0 else None,
        **view_fields(low, high, size, scene),
        "series": series,
        "member_forces": member_forces,  # frames × members: mean |F| at their ends, N
    }


# ---------------------------------------------------------------------------------------------
# Writing the page

def three_sources() -> tuple[str, list[str]]:
    """(revision, [three.min.js, OrbitControls.js, Lut.js] texts) from Debian's libjs-three."""
    for directory in THREE_DIRECTORIES:
        paths = [directory / name for name in THREE_FILES]
        if all(path.is_file() for path in paths):
            texts = [path.read_text(encoding="utf-8") for path in paths]
            match = re.search(r'REVISION\s*=\s*"(\w+)"', texts[0])
            revision = match[1] if match else "?"
            if revision != THREE_REVISION:
                print(f"warning: three.js revision {revision} in {directory}; the page was "
                      f"written and tested for revision {THREE_REVISION}", file=sys.stderr)
            return revision, texts
    raise ResultsError("three.js not found (" + ", ".join(
        str(d / f) for d in THREE_DIRECTORIES for f in THREE_FILES)
        + "): install Debian's package libjs-three (scripts/install_deps.sh does)")


def inline_script(text: str) -> str:
    """Text safe inside <script>…</script>."""
    return re.sub(r"</(script)", r"<\\/\1", text, flags=re.IGNORECASE)


def write_page(data: dict, output: Path) -> int:
    revision, (three, orbit_controls, colour_map) = three_sources()
    data["three_revision"] = revision
    template = PAGE_TEMPLATE.read_text(encoding="utf-8")
    replacements = {
        "{{TITLE}}": html.escape(f"{data['file']} · cranesim replay"),
        "{{THREE}}": inline_script(three),
        "{{ORBIT_CONTROLS}}": inline_script(orbit_controls),
        "{{COLOUR_MAP}}": inline_script(colour_map),
        "{{REPLAY}}": inline_script(PAGE_SCRIPT.read_text(encoding="utf-8")),
        "{{DATA}}": json.dumps(data, separators=(",", ":")).replace("</", "<\\/"),
    }
    page = re.sub("|".join(map(re.escape, replacements)), lambda m: replacements[m[0]], template)
    output.write_text(page, encoding="utf-8")
    return output.stat().st_size


def main() -> None:
    args = parse_arguments()
    results_path = Path(args.results)
    output = Path(args.output or results_path.with_suffix(".html"))
    with Results(results_path) as results:
        data = page_data(results, args.frames, args.load)
    size = write_page(data, output)
    if size > LARGE_PAGE and data["kind"] == "results":
        per_frame = len(data["points"]) * 0.75 / data["frame_count"]  # base64 → bytes
        fitting = max(2, int((LARGE_PAGE - (size - per_frame * data["frame_count"] / 0.75))
                             * 0.75 / per_frame))
        print(f"warning: {output} is {size / 1e6:.0f} MB, slow to open; --frames {fitting} "
              f"keeps it near {LARGE_PAGE / 1e6:.0f} MB", file=sys.stderr)
    status = "" if data["status"] == "complete" else f", status {data['status']}"
    if "plan" in data:
        status += f", the verification run of {data['plan']['file']}"
    if data["kind"] == "modes":
        print(f"wrote {output} ({size / 1e6:.2f} MB, {len(data['modes']['frequency'])} modes of "
              f"{data['point_count']} joints{status})")
        return
    time = np.frombuffer(base64.b64decode(data["time"]), dtype="<f4")
    print(f"wrote {output} ({size / 1e6:.2f} MB, {data['frame_count']} frames of "
          f"{data['sample_count']} samples, t = {time[0]:.6g} .. {time[-1]:.6g} s{status})")


if __name__ == "__main__":
    sys.exit(run_command(main))
