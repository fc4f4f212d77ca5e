"""scripts/plot_plan.py on small synthetic plan files (the layout crane-opt plan writes), run in-process,
and its cubic Hermite evaluator against an exact cubic.

Environment: CRANESIM_SOURCE_DIR (default: two levels up).
"""

import importlib.util
import os
from pathlib import Path

import h5py
import numpy as np
import pytest

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
SCRIPT = SOURCE_DIR / "scripts" / "plot_plan.py"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
TARGET_TEXT = "name: synthetic plan\n"
TIMING = {"map_s": 0.1, "fit_s": 0.001, "trajectory_s": 0.3, "controls_s": 0.001, "inversion_s": 0.05,
          "verification_s": 0.8}


@pytest.fixture(scope="module")
def plot_plan():
    spec = importlib.util.spec_from_file_location("plot_plan", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def write_map(f: h5py.File) -> None:
    """A 4 × 3 grid of a boom (length 20 m) with a hanging rope; one grid point failed (NaN)."""
    angle, change = np.array([40.0, 50.0, 60.0, 70.0]), np.array([0.0, 1.0, 2.0])
    a, c = np.meshgrid(np.radians(angle), change, indexing="ij")
    hoist = 10.0 - c
    m = f.create_group("map")
    m.attrs.update({"hoist_length_reference": 10.0, "jacobians": 12, "threads": 1,
                    "start_time_s": 0.01, "sweep_time_s": 0.09})
    m["boom_angle"], m["hoist_change"] = angle, change
    m["luffing_length"] = 25.0 - 10.0 * np.sin(a) + 0.01 * c
    m["hoist_length"] = hoist
    m["end_x"], m["end_y"], m["end_z"] = -20.0 * np.cos(a), np.zeros_like(a), 20.0 * np.sin(a) - hoist
    m["iterations"] = np.full(a.shape, 4.0)
    for name in ("luffing_length", "end_x", "end_y", "end_z"):
        m[name][3, 2] = np.nan  # a grid point without equilibrium
    f.create_group("timing").attrs.update(TIMING)


def write_plan(path: Path, contents: str = "plan") -> Path:
    with h5py.File(path, "w") as f:
        f.attrs.update({"contents": contents, "target_path": "target_synthetic.yaml", "target_text": TARGET_TEXT})
        write_map(f)
        if contents == "map":
            return path
        m = f["map"]
        fit = f.create_group("fit")
        fit.attrs.update({"type": "polynomial", "order_boom_angle": 3, "order_hoist_change": 2})
        for name in ("end_x", "end_z", "luffing_length"):
            fit[name] = np.nan_to_num(m[name][()], nan=m[name][3, 1]) + 1e-3
            fit[name].attrs.update({"max_residual": 1e-3, "rms_residual": 1e-3})

        steps, dt = 10, 0.5
        t = dt * np.arange(steps + 1)
        s = t / t[-1]
        blend, rate = 3 * s**2 - 2 * s**3, 6 * (s - s**2) / t[-1]
        start, target = np.array([-10.0, 7.5]), np.array([-12.0, 9.0])
        state = np.column_stack([start + np.outer(blend, target - start), np.outer(rate, target - start)])
        trajectory = f.create_group("trajectory")
        trajectory.attrs.update({"cost": 123.0, "iterations": 7, "solve_time_s": 0.2})
        trajectory["t"], trajectory["state"], trajectory["origin"] = t, state, np.zeros(2)
        trajectory["control"] = np.diff(state[:, 2:], axis=0) / dt
        trajectory["start"], trajectory["target"] = [[*start, 0, 0]], [[*target, 0, 0]]
        trajectory["state_bounds"] = [[-18, 5, -0.5, -0.5], [-6, 15, 0.5, 0.5]]
        trajectory["control_bounds"] = [[-0.2, -0.2], [0.2, 0.2]]

        lead = 1.0
        controls = f.create_group("controls")
        controls.attrs["lead_time"] = lead
        controls["t"] = t
        controls["boom_angle"], controls["hoist_change"] = 50 + 10 * blend, blend
        controls["luffing_length"], controls["hoist_length"] = 18 - 2 * blend, 10 - blend
        knots = np.linspace(0.0, t[-1] + 2 * lead, 5)
        knot_blend = np.clip((knots - lead) / t[-1], 0, 1)
        for name, y0, dy in (("luffing_length", 18.0, -2.0), ("hoist_length", 10.0, -1.0)):
            spline = controls.create_group(f"spline/{name}")
            spline["t"], spline["y"], spline["slopes"] = knots, y0 + dy * knot_blend, np.zeros(5)

        inversion = f.create_group("inversion")
        inversion["t"] = t[::5]
        inversion["planned"] = state[::5, :2]
        inversion["reached"] = state[::5, :2] + 1e-3
        inversion["error"] = np.full(3, np.sqrt(2) * 1e-3)

        time = np.linspace(0.0, t[-1] + 2 * lead, 30)
        planned = start + np.outer(np.clip((time - lead) / t[-1], 0, 1), target - start)
        sway = 0.05 * np.sin(2 * time)
        verification = f.create_group("verification")
        verification.attrs.update({"max_error": 0.05, "rms_error": 0.035, "residual_sway": 0.05,
                                   "final_error": 0.01, "status": "complete"})
        verification["t"], verification["planned"] = time, planned
        verification["simulated"] = np.column_stack([planned[:, 0] + sway, 0 * time, planned[:, 1]])
    return path


def write_shaped_plan(path: Path, delay: float) -> Path:
    """The synthetic plan with a /path (method zvd) that arrives `delay` s later than its QR trajectory."""
    write_plan(path)
    with h5py.File(path, "r+") as f:
        t, state = f["trajectory/t"][()], f["trajectory/state"][()]
        extra = np.arange(1, int(round(delay / 0.5)) + 1)
        group = f.create_group("path")
        group["t"] = np.concatenate([t, t[-1] + 0.5 * extra])
        group["state"] = np.vstack([state, np.repeat(state[-1:], len(extra), axis=0)])
        group.attrs.update({"method": "zvd", "motion_time": t[-1] + delay})
    return path


def assert_png(path: Path) -> None:
    assert path.is_file() and path.stat().st_size > 20_000
    assert path.read_bytes().startswith(PNG_SIGNATURE)


def test_full_plan_figure(plot_plan, tmp_path):
    plan = write_plan(tmp_path / "plan.h5")
    output = tmp_path / "figure.png"
    assert plot_plan.main([str(plan), "-o", str(output)]) == 0
    assert_png(output)


def test_default_output_name_and_map_only_file(plot_plan, tmp_path):
    plan = write_plan(tmp_path / "map.h5", contents="map")
    assert plot_plan.main([str(plan)]) == 0
    assert_png(tmp_path / "map_plan.png")


def test_missing_file_is_a_clean_error(plot_plan, tmp_path, capsys):
    assert plot_plan.main([str(tmp_path / "absent.h5")]) == 2
    assert "error" in capsys.readouterr().err


def test_hermite_reproduces_a_cubic_and_is_constant_outside(plot_plan):
    knots = np.array([-1.0, -0.2, 0.5, 1.1, 2.0])
    query = np.linspace(knots[0], knots[-1], 1001)
    values = plot_plan.hermite(query, knots, knots**3, 3 * knots**2)
    np.testing.assert_allclose(values, query**3, rtol=0, atol=1e-12)
    np.testing.assert_allclose(plot_plan.hermite(knots, knots, knots**3, 3 * knots**2), knots**3, atol=1e-12)
    outside = plot_plan.hermite([-5.0, -1.5, 2.5, 10.0], knots, knots**3, 3 * knots**2)
    np.testing.assert_array_equal(outside, [-1.0, -1.0, 8.0, 8.0])
    assert np.ndim(plot_plan.hermite(0.3, knots, knots**3, 3 * knots**2)) == 0


def test_sway_after_arrival_is_the_offset_from_the_target_after_the_planned_arrival(plot_plan, tmp_path):
    """The synthetic verification sways 0.05 sin(2t) about a path that holds the target after
    lead + 5 s; a shaped plan's arrival is its own path's end, 1 s later."""
    for path, arrival in ((write_plan(tmp_path / "plain.h5"), 1.0 + 5.0),
                          (write_shaped_plan(tmp_path / "shaped.h5", 1.0), 1.0 + 6.0)):
        with h5py.File(path, "r") as plan:
            since, offset = plot_plan.sway_after_arrival(plan)
            time = plan["verification/t"][()]
        assert since[0] >= 0 and np.all(np.diff(since) > 0)
        assert len(since) == np.count_nonzero(time >= arrival)
        np.testing.assert_allclose(offset, 0.05 * np.sin(2 * (since + arrival)), atol=1e-12)


def test_comparison_figure_of_several_plans(plot_plan, tmp_path):
    plans = [write_plan(tmp_path / "quasi_static.h5"), write_shaped_plan(tmp_path / "zvd.h5", 1.0)]
    assert plot_plan.main([str(p) for p in plans]) == 0
    assert_png(tmp_path / "quasi_static_compare.png")
    assert plot_plan.main([str(plans[0]), str(tmp_path / "absent.h5")]) == 2


def test_map_panel_draws_the_path_the_controls_follow(plot_plan, tmp_path):
    """A shaped or flatness plan's controls follow /path, not the QR trajectory: panel (a) draws that
    path under the method's name, and the QR trajectory only dotted, as not followed."""
    import matplotlib.pyplot as plt

    for plan_file, expected in ((write_plan(tmp_path / "quasi_static.h5"), ["planned path (quasi_static)"]),
                                (write_shaped_plan(tmp_path / "zvd.h5", 1.0),
                                 ["QR trajectory (not followed)", "planned path (zvd)"])):
        fig, ax = plt.subplots()
        with h5py.File(plan_file, "r") as plan:
            plot_plan.panel_map(ax, plan)
            drawn = {line.get_label(): line for line in ax.get_lines()}
            assert [label for label in drawn if "path" in label or "trajectory" in label] == expected
            t, state = plot_plan.planned_path(plan)
            np.testing.assert_array_equal(drawn[expected[-1]].get_xydata(), plan["trajectory/origin"][()] + state[:, :2])
        plt.close(fig)
