"""scripts/view.py: the 3-D replay page, rendered in a real browser (headless Chromium).

A short run of configs/pendulum.yaml becomes a page; Chromium opens it at two times given in
the URL's fragment, once for the DOM (--dump-dom) and once for a screenshot. The page must load
without a JavaScript error, draw something, show the rod where the results file has it (the
screen position the page reports, from three.js' projection, against the projection of the
HDF5 value through the camera matrices the page reports, and the load marker's colour in the
screenshot at that place), and the two moments must look different where the rod moved.

Needs Debian's chromium and libjs-three (scripts/install_deps.sh installs both); a missing
browser fails the test. Environment: CRANESIM_BIN (default <repo>/build/crane-sim), CRANEOPT_BIN
(default <repo>/build/crane-opt) and CRANESIM_SOURCE_DIR.
"""

import base64
import html.parser
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import INCOMPLETE_MESSAGE

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BINARY = Path(os.environ.get("CRANESIM_BIN", SOURCE_DIR / "build" / "crane-sim")).resolve()
OPT_BINARY = Path(os.environ.get("CRANEOPT_BIN", SOURCE_DIR / "build" / "crane-opt")).resolve()
VIEW = SOURCE_DIR / "scripts" / "view.py"
WINDOW = (1000, 700)
VIEW_SIZE = (640, 480)  # fixed in the URL: the DOM dump and the screenshot see one camera
TIMES = (0.3, 0.8)
LOAD_COLOUR = np.array([0xE4, 0x57, 0x2E])  # the page's load marker, drawn over everything
BACKGROUND = np.array([0xEE, 0xF2, 0xF6])


def chromium() -> str:
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    if path is None:
        pytest.fail("chromium not found on PATH: the replay page is tested in a real browser; "
                    "install Debian's package chromium (scripts/install_deps.sh does)")
    return path


def browser_command(profile: Path, url: str, *mode: str) -> list[str]:
    return [chromium(), "--headless", "--no-sandbox", "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader", "--force-device-scale-factor=1", "--hide-scrollbars",
            f"--window-size={WINDOW[0]},{WINDOW[1]}", f"--user-data-dir={profile}",
            "--virtual-time-budget=5000", *mode, url]


def run_browsers(commands: list[list[str]]) -> list[str]:
    """Run the browser commands two at a time; their standard outputs."""
    outputs = []
    for pair in (commands[i:i + 2] for i in range(0, len(commands), 2)):
        processes = [subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                      text=True) for command in pair]
        for process in processes:
            stdout, stderr = process.communicate(timeout=60)
            assert process.returncode == 0, stderr[-2000:]
            outputs.append(stdout)
    return outputs


class StatusParser(html.parser.HTMLParser):
    """The page's <title>, the attributes of its #status and #incomplete elements, and the
    text of its play button."""

    def __init__(self):
        super().__init__()
        self.title, self.status, self.incomplete, self._in = "", {}, None, None
        self.play_button = ""

    def handle_starttag(self, tag, attrs):
        attributes = dict(attrs)
        if tag == "title":
            self._in = "title"
        elif attributes.get("id") == "status":
            self.status = attributes
        elif attributes.get("id") == "incomplete":
            self.incomplete = {"hidden": "hidden" in attributes, "text": ""}
            self._in = "incomplete"
        elif attributes.get("id") == "play":
            self._in = "play"

    def handle_endtag(self, tag):
        self._in = None

    def handle_data(self, text):
        if self._in == "title":
            self.title += text
        elif self._in == "incomplete":
            self.incomplete["text"] += text
        elif self._in == "play":
            self.play_button += text


def parse_dom(dom: str) -> StatusParser:
    parser = StatusParser()
    parser.feed(dom)
    return parser


def numbers(text: str) -> np.ndarray:
    return np.array([float(value) for value in text.split(",")])


def read_png(path: Path) -> np.ndarray:
    from PIL import Image  # matplotlib's dependency
    with Image.open(path) as image:
        return np.asarray(image.convert("RGB")).astype(int)


def make_page(tmp_path: Path, results: Path, *options: str) -> Path:
    page = tmp_path / (results.stem + ".html")
    run = subprocess.run([sys.executable, str(VIEW), str(results), "-o", str(page), *options],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    assert "wrote" in run.stdout
    return page


def data_of(results: Path, frames: int = 1000) -> dict:
    """What view.py embeds in a page, computed in this process (no page, no browser)."""
    import view
    with view.Results(results) as opened:
        return view.page_data(opened, frames, None)


def page_data(page: Path) -> dict:
    match = re.search(r'<script type="application/json" id="cranesim-data">(.*?)</script>',
                      page.read_text(encoding="utf-8"), flags=re.DOTALL)
    return json.loads(match[1])


def decode(text: str) -> np.ndarray:
    return np.frombuffer(base64.b64decode(text), dtype="<f4")


@pytest.fixture(scope="module")
def pendulum_page(pendulum_run) -> Path:
    return make_page(pendulum_run.parent, pendulum_run)


@pytest.fixture(scope="module")
def pendulum_run(tmp_path_factory) -> Path:
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    directory = tmp_path_factory.mktemp("view")
    base = SOURCE_DIR / "configs" / "pendulum.yaml"
    (directory / "short.yaml").write_text(f"base: {base}\nmodify:\n  solver.t_end: 1.0\n")
    run = subprocess.run([str(BINARY), "run", "short.yaml", "-o", "pendulum.h5", "--quiet"],
                         cwd=directory, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    return directory / "pendulum.h5"


def test_page_shows_the_pendulum_where_the_results_have_it(pendulum_run, pendulum_page, tmp_path):
    page = pendulum_page
    text = page.read_text(encoding="utf-8")
    assert "<script src" not in text and "<link" not in text  # self-contained
    with h5py.File(pendulum_run, "r") as results:
        time = results["time"][()]
        rod = results["bodies/rod/position"][()]

    commands, shots = [], []
    for k, t in enumerate(TIMES):
        url = f"{page.as_uri()}#t={t}&size={VIEW_SIZE[0]}x{VIEW_SIZE[1]}"
        shots.append(tmp_path / f"shot{k}.png")
        commands.append(browser_command(tmp_path / f"dom{k}", url, "--dump-dom"))
        commands.append(browser_command(tmp_path / f"png{k}", url, f"--screenshot={shots[-1]}"))
    outputs = run_browsers(commands)

    images, load_pixels = [], []
    for k, t in enumerate(TIMES):
        dom = parse_dom(outputs[2 * k])
        assert dom.status.get("data-state") == "ready", (dom.title, dom.status.get("data-error"))
        assert dom.title.startswith("cranesim replay: ready"), dom.title
        assert float(dom.status["data-t"]) == pytest.approx(t)

        # The rod's origin (the load: the run's last body) from the file, at t …
        sample = int(np.argmin(np.abs(time - t)))
        assert time[sample] == pytest.approx(t)
        world = rod[sample]
        np.testing.assert_allclose(numbers(dom.status["data-load-world"]), world, atol=1e-5)
        # … through the page's camera (three.js stores matrices column by column) …
        view = numbers(dom.status["data-view-matrix"]).reshape(4, 4).T
        projection = numbers(dom.status["data-projection-matrix"]).reshape(4, 4).T
        clip = projection @ view @ np.append(world, 1.0)
        ndc = clip[:3] / clip[3]
        left, top, width, height = numbers(dom.status["data-canvas"])
        assert (width, height) == VIEW_SIZE
        expected = np.array([left + (ndc[0] + 1) / 2 * width, top + (1 - ndc[1]) / 2 * height])
        # … is where the page says it drew it,
        reported = numbers(dom.status["data-load-px"])
        np.testing.assert_allclose(reported, expected, atol=2.0)
        assert 0 < expected[0] < width and 0 < expected[1] < height

        # and the screenshot has the load marker's colour there.
        image = read_png(shots[k])
        assert image.shape[:2] == (WINDOW[1], WINDOW[0])
        x, y = np.round(expected).astype(int)
        assert np.abs(image[y, x] - LOAD_COLOUR).max() < 40, (image[y, x], (x, y))
        # The 3-D view is not blank: well beyond the background colour's share.
        canvas = image[int(top):int(top + height), int(left):int(left + width)]
        drawn = np.abs(canvas - BACKGROUND).max(axis=-1) > 30
        assert drawn.mean() > 0.01, f"only {drawn.mean():.2%} of the canvas is drawn"
        images.append(image)
        load_pixels.append((x, y))

    # The two moments differ, and where the load was at one time it is not at the other.
    assert np.linalg.norm(np.subtract(*load_pixels)) > 20
    for k, (x, y) in enumerate(load_pixels):
        other = images[1 - k]
        assert np.abs(other[y, x] - LOAD_COLOUR).max() > 60, "the load did not move on screen"
        patch = (slice(y - 10, y + 11), slice(x - 10, x + 11))
        assert np.abs(images[0][patch] - images[1][patch]).max() > 60


def test_follow_camera_and_camera_from_the_link(pendulum_page, tmp_path):
    # #bench=N draws N frames from the start to the end of the run, as playing does.
    page = pendulum_page
    size = f"size={VIEW_SIZE[0]}x{VIEW_SIZE[1]}"
    # Without following, the camera of the link: at (2, -3, 1) looking at (0, 0, -0.5).
    camera, target = np.array([2.0, -3.0, 1.0]), np.array([0.0, 0.0, -0.5])
    link = "&cam=" + ",".join(map(str, [*camera, *target]))
    outputs = run_browsers([
        browser_command(tmp_path / f"profile{k}", f"{page.as_uri()}#t=0.2&{size}&bench=12{extra}",
                        "--dump-dom") for k, extra in enumerate(("&follow=1", link))])
    middle = np.array(VIEW_SIZE) / 2
    for output, following in zip(outputs, (True, False)):
        dom = parse_dom(output)
        assert dom.status.get("data-state") == "ready", dom.status.get("data-error")
        assert float(dom.status["data-t"]) == pytest.approx(1.0)
        assert float(dom.status["data-bench-fps"]) > 0
        distance = np.linalg.norm(numbers(dom.status["data-load-px"]) - middle)
        if following:
            assert distance < 1.0
        else:
            assert distance > 20
            view = numbers(dom.status["data-view-matrix"]).reshape(4, 4).T
            np.testing.assert_allclose(-view[:3, :3].T @ view[:3, 3], camera, atol=1e-6)
            looking = -view[2, :3]  # the camera looks along its −z axis
            np.testing.assert_allclose(looking, (target - camera) / np.linalg.norm(target - camera),
                                       atol=1e-6)


def test_modes_and_plan_files_become_pages(tmp_path):
    for binary in (BINARY, OPT_BINARY):
        if not binary.is_file():
            pytest.fail(f"{binary.name} not found at {binary}: build it first or set "
                        "CRANESIM_BIN / CRANEOPT_BIN")
    modes_file, plan_file = tmp_path / "rope_modes.h5", tmp_path / "jib_plan.h5"
    for command in ([BINARY, "modes", SOURCE_DIR / "configs" / "rope_pendulum.yaml", "-n", "6",
                     "-o", modes_file],
                    [OPT_BINARY, "plan", SOURCE_DIR / "configs" / "target_luffing_jib.yaml",
                     "-o", plan_file, "--quiet"]):
        run = subprocess.run(list(map(str, command)), capture_output=True, text=True, timeout=120)
        assert run.returncode == 0, run.stderr
    modes_page, plan_page = make_page(tmp_path, modes_file), make_page(tmp_path, plan_file)
    assert page_data(modes_page)["kind"] == "modes"
    assert page_data(plan_page)["plan"]["file"] == plan_file.name
    size = f"size={VIEW_SIZE[0]}x{VIEW_SIZE[1]}"
    # Mode 4 (the swing) at a quarter cycle, where the joint that moves most is 0.5 m away;
    # the plan's verification run at 12 s.
    outputs = run_browsers([
        browser_command(tmp_path / "modes", f"{modes_page.as_uri()}#t=0.25&mode=4&amp=0.5&{size}",
                        "--dump-dom"),
        browser_command(tmp_path / "plan", f"{plan_page.as_uri()}#t=12&{size}", "--dump-dom")])
    modes_dom, plan_dom = map(parse_dom, outputs)
    for dom in (modes_dom, plan_dom):
        assert dom.status.get("data-state") == "ready", dom.status.get("data-error")

    with h5py.File(modes_file, "r") as modes:
        joints = list(modes["model/joints"].asstr()[()])
        ball = joints.index("ball.origin")
        equilibrium = modes["equilibrium/joint_positions"][ball]
        swing = modes["modes/joint_displacements"][3]
    shape = swing / np.linalg.norm(swing, axis=-1).max()
    np.testing.assert_allclose(numbers(modes_dom.status["data-load-world"]),
                               equilibrium + 0.5 * shape[ball], atol=1e-4)
    assert np.linalg.norm(0.5 * shape[ball]) > 0.1  # the swing moves the ball, visibly

    with h5py.File(plan_file, "r") as plan:
        t = plan["verification/t"][()]
        planned = plan["verification/planned"][()]
        simulated = plan["verification/simulated"][()]
    k = int(np.argmin(np.abs(t - 12)))
    assert t[k] == pytest.approx(12)
    np.testing.assert_allclose(numbers(plan_dom.status["data-planned-world"]), planned[k], atol=1e-4)
    # The load's origin is the hook here, whose path the plan calls the simulated end point.
    np.testing.assert_allclose(numbers(plan_dom.status["data-load-world"]), simulated[k], atol=1e-4)
    # Its ropes are coloured by their end forces, over the range the page data holds.
    np.testing.assert_allclose(numbers(plan_dom.status["data-force-range"]),
                               page_data(plan_page)["member_forces"]["range"])


# A bar hanging from a spherical hinge at its top, its centroid off its axis, drawn tilted: at
# the equilibrium its rotation is not about the vertical, so a share that used the wrong frame
# for the centroid's velocity would not add up.
OFFSET_BAR = """name: tilted bar with an offset centroid
ground:
  joints: [{name: pivot, position: [0, 0, 0]}]
bodies:
  - name: bar
    mass: 2.0
    centroid: [0.3, 0.1, 0.5]
    inertia: [0.2, 0.15, 0.07]
    position: [-0.3535533905932737, 0.3535533905932737, -0.8660254037844387]
    rotation: {axis: [1, 1, 0], angle_deg: 30}
    joints: [{name: top, position: [0, 0, 1]}]
constraints:
  - {name: hinge, type: spherical, joints: [ground.pivot, bar.top]}
solver:
  t_end: 1
"""


def test_modes_kinetic_energy_shares_add_up(tmp_path):
    """Mass-normalised shapes: the parts' shares of a mode's kinetic energy add up to 1, and
    scenes of rigid bodies only leave nothing to the members."""
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    (tmp_path / "offset_bar.yaml").write_text(OFFSET_BAR)
    shares = {}
    for scene in (tmp_path / "offset_bar.yaml", SOURCE_DIR / "configs" / "double_jib_pendulum.yaml",
                  SOURCE_DIR / "configs" / "rope_pendulum.yaml"):
        modes_file = tmp_path / f"{scene.stem}.h5"
        run = subprocess.run([str(BINARY), "modes", str(scene), "-n", "6", "-o", str(modes_file)],
                             capture_output=True, text=True, timeout=60)
        assert run.returncode == 0, run.stderr
        shares[scene.stem] = data_of(modes_file)["modes"]["energy_shares"]
    for scene, bodies in (("offset_bar", {"bar"}), ("double_jib_pendulum", {"jib", "link1", "link2"})):
        assert len(shares[scene]) >= 3
        for mode in shares[scene]:
            assert {name for name, _ in mode} == bodies
            assert sum(share for _, share in mode) == pytest.approx(1.0, abs=1e-9)
    # The swing of the 1000 kg ball on its 24.5 kg rope: the rope takes about a third of its
    # mass' share, ρAL/3 / (m + ρAL/3) = 0.8 %.
    swing = dict(shares["rope_pendulum"][3])
    assert swing["ball"] + swing["flexible members"] == pytest.approx(1.0, abs=1e-9)
    assert swing["flexible members"] == pytest.approx(24.5 / 3 / (1000 + 24.5 / 3), rel=0.05)


def test_incomplete_run_is_shown_with_its_status_and_plays_to_its_end(incomplete_results_file,
                                                                      tmp_path):
    page = make_page(tmp_path, incomplete_results_file)
    data = page_data(page)
    with h5py.File(incomplete_results_file, "r") as results:
        last = results["time"][-1]
    assert data["status"] == "incomplete" and data["message"] == INCOMPLETE_MESSAGE
    assert decode(data["time"])[-1] == pytest.approx(last)
    # Opened after its end; and opened playing (#play=1) at ×10 from 0.1 s, which reaches the
    # last sample within the browser's 5 s of virtual time and pauses there.
    outputs = run_browsers([browser_command(tmp_path / f"profile{k}", page.as_uri() + fragment,
                                            "--dump-dom")
                            for k, fragment in enumerate(("#t=100", "#t=0.1&play=1&speed=10"))])
    dom, played = map(parse_dom, outputs)
    assert played.status.get("data-state") == "ready", played.status.get("data-error")
    assert played.title.startswith("cranesim replay: ready · t = 0.100 s")  # when it opened
    assert float(played.status["data-t"]) == pytest.approx(last, rel=1e-6)
    assert played.play_button.strip() == "Play"  # paused at the end
    assert dom.status.get("data-state") == "ready", dom.status.get("data-error")
    assert float(dom.status["data-t"]) == pytest.approx(last, rel=1e-6)  # clamped to the last
    assert dom.incomplete is not None and not dom.incomplete["hidden"]
    assert "INCOMPLETE" in dom.incomplete["text"] and INCOMPLETE_MESSAGE in dom.incomplete["text"]


def test_frames_are_decimated_evenly_with_the_last_sample(pendulum_run, tmp_path):
    data = data_of(pendulum_run, frames=25)
    with h5py.File(pendulum_run, "r") as results:
        time = results["time"][()]
        rod = results["bodies/rod/position"][()]
    frames = decode(data["time"])
    assert len(frames) == 25 == data["frame_count"] and data["sample_count"] == len(time)
    assert frames[0] == pytest.approx(time[0]) and frames[-1] == pytest.approx(time[-1])
    samples = np.searchsorted(time, frames - 1e-6)
    np.testing.assert_allclose(time[samples], frames, atol=1e-6)
    points = decode(data["points"]).reshape(25, data["point_count"], 3)
    np.testing.assert_allclose(points[:, data["load"]], rod[samples], atol=1e-5)


def test_rope_colour_is_the_force_at_its_ends(tmp_path):
    if not BINARY.is_file():
        pytest.fail(f"crane-sim not found at {BINARY}: build it first or set CRANESIM_BIN")
    base = SOURCE_DIR / "configs" / "rope_pendulum.yaml"
    (tmp_path / "short.yaml").write_text(f"base: {base}\nmodify:\n  solver.t_end: 0.5\n")
    run = subprocess.run([str(BINARY), "run", "short.yaml", "-o", "rope.h5", "--quiet"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    data = data_of(tmp_path / "rope.h5")
    forces = data["member_forces"]
    assert forces["members"] == ["rope"]
    with h5py.File(tmp_path / "rope.h5", "r") as results:
        rows = list(results["model/constraint_rows"].asstr()[()])
        lambdas = results["lambda"][()]
    # The rope hangs from 'top' and holds the ball at 'hook' (spherical constraints).
    ends = [np.linalg.norm(lambdas[:, [rows.index(f"{c}/{a}") for a in "xyz"]], axis=1)
            for c in ("top", "hook")]
    values = decode(forces["values"]).reshape(data["frame_count"], 1)[:, 0]
    np.testing.assert_allclose(values, (ends[0] + ends[1]) / 2, rtol=1e-6)
    assert forces["range"] == pytest.approx([values.min(), values.max()], rel=1e-6)
    assert values.min() > 5e3  # the 1 t ball's weight, and more while it swings
    assert all(rope[2] == 0 for rope in data["ropes"]) and len(data["ropes"]) == 4


def test_a_file_that_is_not_a_results_file_is_refused(tmp_path):
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as file:
        file["x"] = [1.0, 2.0]
    text = tmp_path / "text.h5"
    text.write_text("not hdf5\n")
    crane_opt_files = []
    for contents in ("map", "plan"):  # a map holds no run; this plan has no verification run
        crane_opt_files.append(tmp_path / f"lonely_{contents}.h5")
        with h5py.File(crane_opt_files[-1], "w") as file:
            file.attrs.update({"engine_version": "0.1.0", "contents": contents})
    for path in (other, text, tmp_path / "missing.h5", *crane_opt_files):
        run = subprocess.run([sys.executable, str(VIEW), str(path), "-o", str(tmp_path / "x.html")],
                             capture_output=True, text=True, timeout=60)
        assert run.returncode == 2, run.stderr
        assert len(run.stderr.strip().splitlines()) == 1 and "Traceback" not in run.stderr
        assert path.name in run.stderr
        assert not (tmp_path / "x.html").exists()


def test_plan_page_draws_the_obstacles_and_their_clearance(tmp_path):
    """The luffing jib's plan over a wall and beside a silo: the page data holds each obstacle as
    the target gives it (yaw in radians) with its smallest verified clearance from /clearance, and
    the page draws a mesh for each."""
    if not OPT_BINARY.is_file():
        pytest.fail(f"{OPT_BINARY.name} not found at {OPT_BINARY}: build it first or set CRANEOPT_BIN")
    jib = SOURCE_DIR / "configs" / "target_luffing_jib.yaml"
    target = tmp_path / "target.yaml"
    target.write_text(jib.read_text(encoding="utf-8").replace("scene: luffing_jib.yaml", f"scene: {jib.parent / 'luffing_jib.yaml'}")
                      + "obstacles:\n  - {name: wall, shape: box, centre: [-12, 0, 2.5], size: [0.4, 10, 5], yaw: 30}\n"
                        "  - {name: silo, shape: cylinder, base: [-12, 8, 0], radius: 2, height: 6}\n",
                      encoding="utf-8")
    plan_file = tmp_path / "plan.h5"
    run = subprocess.run([str(OPT_BINARY), "plan", str(target), "-o", str(plan_file), "--quiet"], capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    page = make_page(tmp_path, plan_file)
    plan = page_data(page)["plan"]
    with h5py.File(plan_file, "r") as f:
        minimum = f["clearance/minimum"][...]
        assert list(f["clearance/obstacle"].asstr()[...]) == ["wall", "silo"]
    wall, silo = plan["obstacles"]
    assert wall["shape"] == "box" and wall["centre"] == [-12, 0, 2.5] and wall["yaw"] == pytest.approx(np.pi / 6)
    assert silo["shape"] == "cylinder" and silo["radius"] == 2 and silo["height"] == 6
    assert [wall["clearance"], silo["clearance"]] == pytest.approx(minimum.min(axis=1).tolist())
    assert plan["clearance"]["closest_obstacle"] == ("wall" if minimum[0].min() < minimum[1].min() else "silo")
    dom = parse_dom(run_browsers([browser_command(tmp_path / "profile", f"{page.as_uri()}#t=5", "--dump-dom")])[0])
    assert dom.status.get("data-state") == "ready", dom.status.get("data-error")
    assert dom.status["data-obstacles"] == "obstacle wall,obstacle silo"
