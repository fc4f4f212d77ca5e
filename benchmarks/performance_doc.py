"""Writes docs/performance.md from the benchmark results in benchmarks/results/.

Each section reads one benchmark's CSV, picks its columns and prints them as a table with the
command that produced it, the machine and the links to the CSV and the plot. What a CSV does not
record about its run (a loaded machine, a second command that added rows) is said beside the
command in its section: update it with the CSV. The page is never edited by hand: re-run a
benchmark, then this script, and commit both.

    python3 benchmarks/performance_doc.py            # writes docs/performance.md
    python3 benchmarks/performance_doc.py --check    # exit 1 if the page is stale or a result is missing
    python3 benchmarks/performance_doc.py --results DIR --output FILE [--check]
"""

import argparse
import csv
import difflib
import math
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LINK = "../benchmarks/results/"  # from docs/ to the results, whatever --results says
MACHINE = "2 cores, Debian bookworm (the CSV does not record the CPU model)"
FIDELITY = {"members": "full-member", "super_truss": "super truss", "condensed": "condensed",
            "beam": "equivalent beam", "mixed": "mixed (boom3 tube by tube)"}
ELEMENT = {"timoshenko": "Timoshenko", "spline_beam": "spline beam"}


class Results:
    """The results directory; remembers every file a section asked for and which were missing."""

    def __init__(self, directory: Path):
        self.directory, self.missing = directory, []

    def csv(self, name: str) -> list[dict]:
        path = self.directory / name
        if not path.is_file():
            self.missing.append(name)
            return []
        with path.open(newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def source(self, command: str | None, name: str, rows: list[dict], plot: str | None = None) -> str:
        """The line under a table: command, machine, links to the CSV and the plot."""
        machines = sorted({r["machine"] for r in rows if r.get("machine")}) or [MACHINE]
        links = f"[{name}]({LINK}{name})"
        if plot:
            if not (self.directory / plot).is_file():
                self.missing.append(plot)
            links += f", plot [{plot}]({LINK}{plot})"
        return (f"Command: `{command}`. " if command else "") + f"Machine: {'; '.join(machines)}. Result: {links}."


def table(header: list[str], rows: list[list]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(str(c) for c in row) + " |" for row in rows])


def num(x) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def sig(x: float, digits: int = 2) -> str:
    """x to `digits` significant digits, plain between 1e-3 and 1e5, else 1.2e-5."""
    if math.isnan(x):
        return "–"
    if x == 0:
        return "0"
    if not 1e-3 <= abs(x) < 1e5:
        mantissa, exponent = f"{x:.{digits - 1}e}".split("e")
        return f"{mantissa}e{int(exponent)}"
    x = round(x, digits - 1 - math.floor(math.log10(abs(x))))
    return f"{x:.{max(digits - 1 - math.floor(math.log10(abs(x))), 0)}f}"


def tol(x) -> str:
    mantissa, exponent = f"{num(x):.0e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def seconds(x) -> str:
    x = num(x)
    return "–" if math.isnan(x) else f"{sig(x * 1e3, 2)} ms" if x < 0.1 else f"{sig(x, 3)} s"


def metres(x) -> str:
    x = num(x)
    if math.isnan(x):
        return "–"
    return f"{sig(x * 1e3)} mm" if abs(x) >= 0.995e-3 else f"{sig(x * 1e6)} µm" if abs(x) >= 0.995e-6 else f"{sig(x)} m"


def percent(x) -> str:
    x = num(x)
    if abs(x) < 1e-12:
        return "0 %"
    return "–" if math.isnan(x) else ("+" if x >= 0 else "") + sig(100 * x) + " %"


def combined_motion(r: Results) -> str:
    rows = r.csv("crane_work_precision.csv")
    label = lambda i: f"BDF order ≤ {i[3:]}" if i.startswith("bdf") else f"generalized-α ρ∞ = {i[2:]}"
    body = table(["sections", "integrator", "rtol", "wall", "real-time factor", "steps / Jacobians",
                  "load position error (max)", "sway kept", "runs"],
                 [[FIDELITY[x["fidelity"]], label(x["integrator"]), tol(x["rtol"]), seconds(x["wall_median_s"]),
                   f"{sig(num(x['realtime_factor']), 3)}×", f"{x['steps']} / {x['jacobians']}",
                   metres(x["hook_error_max_m"]), f"{num(x['sway_amplitude_ratio']):.4f}", x["reps"]] for x in rows])
    return f"""## The thesis crane's combined motion

60 s of the combined lifting, luffing and slewing motion of 8.3.2 (`configs/crane_combined.yaml`,
the main scene) with the eight lattice sections as super truss elements (the thesis' model,
`configs/crane.yaml`) and as condensed truss elements. Wall: the integration's wall time (the
results' `solver/wall_time_s`: the equilibrium excluded), median of the runs; atol = rtol/10.
Load position error: the largest distance over the whole motion between the load and the same
model at BDF order 5, rtol 1e-8. Sway kept: the load's sway amplitude after the drives stop
(45–60 s) over the reference's; below 1 is numerical damping.

{body}

{r.source("python3 benchmarks/crane_work_precision.py --integrators bdf2,bdf5,ga0.8 --rtols 1e-4,1e-5", "crane_work_precision.csv", rows, "crane_work_precision.png")}
"""


def fidelities(r: Results) -> str:
    rows = r.csv("crane_fidelities.csv")
    ref = next((x for x in rows if x["fidelity"] == "members"), None)

    def offset(x, point):
        if ref is None or x is ref:
            return "reference"
        return metres(math.dist([num(x[f"{point}_{a}_m"]) for a in "xyz"], [num(ref[f"{point}_{a}_m"]) for a in "xyz"]))

    body = table(["fidelity", "coordinates", "equilibrium: iterations, time", "head / hook from full-member",
                  "sway periods", "modes 5, 6", "motion: wall (real-time factor)", "steps / Jacobians",
                  "hook path: max distance from full-member"],
                 [[FIDELITY[x["fidelity"]], x["coordinates"], f"{x['newton_iterations']}, {seconds(x['statics_s'])}",
                   f"{offset(x, 'head')} / {offset(x, 'hook')}",
                   f"{num(x['sway_period_1_s']):.3f}, {num(x['sway_period_2_s']):.3f} s",
                   f"{num(x['mode_5_hz']):.4f}, {num(x['mode_6_hz']):.4f} Hz",
                   f"{seconds(x['wall_median_s'])} ({sig(num(x['realtime_factor']), 2)}×)",
                   f"{x['steps']} / {x['jacobians']}", metres(x["hook_distance_max_m"])] for x in rows])
    return f"""## The lattice fidelities on the whole crane

The thesis crane with every lattice section modelled one way ([lattice sections](truss.md)), at
the thesis' initial controls: the equilibrium (`crane-sim static`), the modes about it
(`crane-sim modes`) and the 60 s combined motion at the main scene's setting (BDF order ≤ 2,
rtol 1e-4, atol 1e-5; wall: median of 3 runs). The hook path is compared with the full-member
crane's at rtol 1e-5; the full-member row is its own rtol 1e-4 run against that reference, the
integrator's share of every row. Walls vary by 10–30 % between runs on this shared machine;
steps and distances do not.

{body}

{r.source("python3 benchmarks/crane_fidelities.py", "crane_fidelities.csv", rows, "crane_fidelities.png")}
"""


def equilibrium_grid(r: Results) -> str:
    rows = r.csv("equilibrium_grid.csv")
    out = []
    for fidelity, kind in dict.fromkeys((x["fidelity"], x["kind"]) for x in rows):
        cases = [x for x in rows if x["fidelity"] == fidelity and x["kind"] == kind]
        found = [x for x in cases if x["converged"] == "1"]
        span = lambda key, scale=1: f"{sig(min(num(x[key]) for x in cases) * scale, 3)}–{sig(max(num(x[key]) for x in cases) * scale, 3)}"
        what = {"controls": f"control pairs: luffing rope {span('luffing_m')} m × hoist rope {span('hoist_m')} m, "
                            f"{sig(num(cases[0]['load_kg']) / 1e3, 3)} t",
                "load": f"loads {span('load_kg', 1e-3)} t at the thesis' controls",
                "mixed": "mixed: random controls, load and slewing angle"}.get(kind, kind)
        iterations = [num(x["newton_iterations"]) for x in found]
        times = [num(x["statics_s"]) for x in found]
        out.append([FIDELITY.get(fidelity, fidelity), f"{len(cases)} {what}", len(found),
                    f"{statistics.median(iterations):g} / {max(iterations):g}" if found else "–",
                    f"{seconds(statistics.median(times))} / {seconds(max(times))}" if found else "–"])
    body = table(["sections", "cases", "found", "Newton iterations median / max", "statics time median / max"], out)
    return f"""## Statics over the working range

`crane-sim static` on the thesis crane from its drawn geometry, with one set of solver settings,
over a grid of rope lengths, a row of loads and random mixed cases (seed 25). Statics time: the
solve's own, as `crane-sim static` prints it (model compilation excluded).

{body}

{r.source("python3 benchmarks/equilibrium_grid.py", "equilibrium_grid.csv", rows, "equilibrium_grid.png")}
"""


def map_parallel(r: Results) -> str:
    rows = r.csv("map_parallel.csv")
    medians = [x for x in rows if x["rows_s"].startswith("median")]
    runs = {x["workers"]: x for x in rows if not x["rows_s"].startswith("median")}
    label = lambda w: f"{w[3:]} MPI ranks" if w.startswith("mpi") else f"{w} thread" + ("s" if w != "1" else "")
    value = lambda s: num(s.split()[-1])
    body = table(["workers", "points", "rows (median)", "whole map (median)", "Jacobians", "speed-up of the rows"],
                 [[label(x["workers"]), x["points"], seconds(value(x["rows_s"])), seconds(value(x["map_s"])),
                   runs.get(x["workers"], {}).get("jacobians", "–"), f"{value(x['jacobians']):.2f}×"] for x in medians])
    return f"""## The static map on threads and MPI ranks

`crane-opt map configs/target.yaml` (thesis 6.2: one equilibrium per point of the boom angle ×
hoist change grid) on 1 and 2 threads and on 2 MPI ranks, 3 runs each, alternating. Rows: the
map's rows (`map/sweep_time_s`), which run in parallel; whole map: with the serial part (the
scene's equilibrium and the spine). The script checks that every map is bitwise the same and
exits 1 otherwise.

{body}

{r.source("python3 benchmarks/map_parallel.py --workers 1,2,mpi2", "map_parallel.csv", rows)}
"""


def jacobian_ratio(r: Results) -> str:
    timed = [x for x in r.csv("jacobian_ratio.csv") if x["binary"] == "new"]
    counted = [x for x in r.csv("jacobian_ratio_instructions.csv") if x["binary"] == "new"]
    out = []
    for fidelity in dict.fromkeys(x["fidelity"] for x in timed):
        sel = [x for x in timed if x["fidelity"] == fidelity]
        med = lambda key: statistics.median(num(x[key]) for x in sel)
        ratios = [num(x["ratio"]) for x in sel]
        count = next((x for x in counted if x["fidelity"] == fidelity), None)
        out.append([fidelity, seconds(med("residual_ms") / 1e3), seconds(med("jacobian_ms") / 1e3),
                    f"{med('ratio'):.1f} ({min(ratios):.1f}–{max(ratios):.1f})", len(sel)]
                   + ([f"{num(count['residual_instructions']) / 1e6:.2f} M", f"{num(count['jacobian_instructions']) / 1e6:.2f} M",
                       f"{num(count['ratio']):.1f}"] if count else ["–"] * 3))
    body = table(["sections", "residual", "DAE Jacobian", "ratio, median (range)", "rounds",
                  "residual instructions", "Jacobian instructions", "ratio of instructions"], out)
    return f"""## The crane's Jacobian against its residual

`bench_kernels` on the thesis crane at its drawn state in three lattice fidelities (super truss
and condensed: 162 coordinates; full-member: 1230): one DAE residual and one DAE Jacobian, both
timed in the same process (medians of 3 repetitions per round), and their ratio per round; the
goal is a Jacobian of at most 5 residuals. The instruction counts are callgrind's per call over about two seconds of calls, on
one core. The rows are the build under test (`new` in the CSV; with `--baseline` a second build
runs in the same rounds for comparison).

{body}

{r.source("python3 benchmarks/jacobian_ratio.py --baseline OTHER_BUILD/benchmarks/bench_kernels --rounds 4", "jacobian_ratio.csv", timed, "jacobian_ratio.png")}
Instructions: `python3 benchmarks/jacobian_ratio.py --instructions --baseline OTHER_BUILD/benchmarks/bench_kernels`,
[jacobian_ratio_instructions.csv]({LINK}jacobian_ratio_instructions.csv) (needs valgrind).
"""


def truss_reduction(r: Results) -> str:
    rows = r.csv("truss_reduction.csv")
    get = {(x["fidelity"], x["quantity"], x["rtol"]): x for x in rows}
    order = ["members", "super_truss", "condensed", "beam"]
    quantities = [("coordinates", "coordinates", lambda v: f"{v:g}"), ("mass_kg", "mass", lambda v: f"{sig(v, 5)} kg"),
                  ("gravity_tip_z_m", "tip under gravity", metres),
                  ("axial_stiffness_N_per_m", "axial stiffness", lambda v: f"{sig(v, 4)} N/m"),
                  ("lateral_stiffness_y_N_per_m", "lateral stiffness y", lambda v: f"{sig(v, 4)} N/m"),
                  ("lateral_stiffness_z_N_per_m", "lateral stiffness z", lambda v: f"{sig(v, 4)} N/m"),
                  ("torsion_stiffness_Nm_per_rad", "torsion stiffness", lambda v: f"{sig(v, 4)} N·m/rad"),
                  ("frequency_1_Hz", "frequency 1", lambda v: f"{sig(v, 4)} Hz"),
                  ("frequency_2_Hz", "frequency 2", lambda v: f"{sig(v, 4)} Hz"),
                  ("frequency_3_Hz", "frequency 3", lambda v: f"{sig(v, 4)} Hz")]
    statics = []
    for key, name, show in quantities:
        cells = [show(num(get[(f, key, "nan")]["value"])) if f == "members" or key == "coordinates"
                 else percent(get[(f, key, "nan")]["relative_error"]) for f in order if (f, key, "nan") in get]
        statics.append([name] + cells)
    released = [[FIDELITY[f], tol(x["rtol"]), seconds(x["wall_time_s_median"]), f"{sig(num(x['speedup']), 2)}×",
                 f"{x['steps']} / {x['jacobians']}", metres(x["value"]),
                 f"{sig(100 * num(get[(f, 'released_tip_z_error_rel_peak', x['rtol'])]['value']))} %"]
                for f in order for x in rows if x["fidelity"] == f and x["quantity"] == "released_tip_z_max_error_m"]
    return f"""## Lattice section: full-member, super truss, condensed, equivalent beam

Thesis 8.2: the type 2 section (Table D-3, 15 m) clamped at one end, as the full-member model
(every tube a Timoshenko beam, `configs/truss_type2_cantilever.yaml`), one super truss element
(`configs/truss_type2_super.yaml`), one condensed truss element
(`configs/truss_type2_condensed.yaml`) and an equivalent Timoshenko beam of 6 elements. The
full-member column gives the values, the others their relative error.

{table(["quantity"] + [FIDELITY[f] for f in order], statics)}

Released under gravity for 1 s: wall time (median of 3), speed-up over the full-member model at
the same rtol (ratios within one run), and the largest tip error against the full-member model
at rtol 1e-8, also as a share of the tip's peak motion. The reduced models' errors are model
error, not the integrator's.

{table(["model", "rtol", "wall", "speed-up", "steps / Jacobians", "tip error (max)", "of the peak"], released)}

{r.source("build/benchmarks/bench_truss_reduction", "truss_reduction.csv", rows)}
"""


def element_bending(r: Results) -> str:
    rows = [x for x in r.csv("element_bending.csv") if x["strategy"] == "direct"]
    ks = list(dict.fromkeys(x["K"] for x in rows))
    out = []
    for kind, segments in dict.fromkeys((x["type"], x["segments"]) for x in rows):
        cells = {x["K"]: x for x in rows if x["type"] == kind and x["segments"] == segments}
        show = lambda x: (f"{sig(num(x['tip_error_rel']))} · {x['newton_iterations']} · {seconds(x['cpu_time_s_median'])}"
                          if x["converged"] == "1" else "not converged")
        out.append([ELEMENT[kind], segments] + [show(cells[k]) if k in cells else "–" for k in ks])
    return f"""## Beam elements: static bending by an end moment

Thesis 8.1.1: the 15 m cantilever of Table 8-1 bent by an end moment M = K·2πEI/L
(`configs/end_moment_<type>.yaml`); K = 1 rolls it into a full circle. The exact solution is a
circular arc. Each cell: tip error / L · Newton iterations · CPU time of the solve (median of 3),
solved from the straight beam as `crane-sim static` does. A Timoshenko element bent by 180° or
more, or a spline beam segment by 90° or more, is beyond the element's range. The CSV also
has the solves by continuation from the previous K.

{table(["element", "segments"] + [f"K = {k}" for k in ks], out)}

{r.source("build/benchmarks/bench_element_bending", "element_bending.csv", rows, "element_bending.png")}
"""


def slender_statics(r: Results) -> str:
    rows = r.csv("slender_statics.csv")
    parts = []
    for case, title, load in (("end_moment", "End moment", "K"), ("tip_force", "Tip force", "PL²/EI")):
        sel = [x for x in rows if x["case"] == case]
        loads = list(dict.fromkeys(x["load"] for x in sel))
        out = []
        for kind, segments in dict.fromkeys((x["type"], x["segments"]) for x in sel):
            cells = {x["load"]: x for x in sel if x["type"] == kind and x["segments"] == segments}
            show = lambda x: (f"{sig(num(x['tip_error_rel']))} · {x['newton_iterations']} · {seconds(x['statics_s'])}"
                              + (" †" if x["stable"] != "1" else "") if x["converged"] == "1" else "not found")
            out.append([ELEMENT[kind], segments] + [show(cells[v]) if v in cells else "–" for v in loads])
        parts.append(f"{title}:\n\n" + table(["element", "segments"] + [f"{load} = {sig(num(v), 2)}" for v in loads], out))
    body = "\n\n".join(parts)
    return f"""## Slender beams bent far

`crane-sim static` from the straight beam: the end moment of 8.1.1 (M = K·2πEI/L, against the
circular arc) and a 10 m cantilever (solid round, r = 0.05 m) with a tip force across it
(against the inextensible elastica). Each cell: tip error / L · Newton iterations · statics
time. † the equilibrium found is unstable.

{body}

{r.source("python3 benchmarks/slender_statics.py", "slender_statics.csv", rows)}
"""


def element_vibration(r: Results) -> str:
    rows = r.csv("element_vibration.csv")
    rtols = sorted(dict.fromkeys(x["rtol"] for x in rows), key=num)
    out = []
    for case, kind, segments in dict.fromkeys((x["case"], x["element"], x["segments"]) for x in rows):
        cells = {x["rtol"]: x for x in rows if (x["case"], x["element"], x["segments"]) == (case, kind, segments)}
        row = [case, ELEMENT[kind], segments]
        for rtol in rtols:
            x = cells.get(rtol)
            row += [metres(x["tip_error_m"]), seconds(x["cpu_time_s"]), x["steps"]] if x and x["completed"] == "1" else ["–"] * 3
        tight = cells.get(rtols[0])
        out.append(row + [metres(tight["tip_error_cross_m"]) if tight else "–"])
    header = ["case", "element", "segments"]
    for rtol in rtols:
        header += [f"rtol {tol(rtol)}: tip error", "CPU", "steps"]
    return f"""## Beam elements: vibration and rotation

Thesis 8.1.2 (`vibration`: the cantilever `configs/cantilever_<element>.yaml` released under
gravity, 3 s) and 8.1.3 (`rotation`: `configs/rotation_drive_<element>.yaml`, the beam turned up
by its drive, the first 4 s), Kelvin–Voigt damping η = 1e-4 s, atol = rtol/100. Tip error: the
largest distance over the samples from the 10-segment model of the same element at rtol 1e-8;
last column: from the other element type's reference (how far the two converged models are
apart). One run per case on a loaded machine: the CPU time is steadier than the wall time, which
the CSV also has. The rotation case has Timoshenko rows only (see
[known limits](known-limits.md)).

{table(header + ["from the other element"], out)}

{r.source("build/benchmarks/bench_element_vibration --cases vibration --dampings 1e-4 --rtols 1e-4,1e-6 --ref-rtol 1e-8 --reps 1", "element_vibration.csv", rows, "element_vibration.png")}
The rotation rows: `build/benchmarks/bench_element_vibration --cases rotation --elements timoshenko --dampings 1e-4 --rtols 1e-4,1e-6 --ref-rtol 1e-8 --rotation-t-end 4 --reps 1`.
"""


def pendulum_chain(r: Results) -> str:
    rows = r.csv("pendulum_chain.csv")
    rtol = 1e-6
    pick = {(x["n_links"], x["formulation"]): x for x in rows if num(x["rtol"]) == rtol and x["completed"] == "1"}
    out = []
    for n in dict.fromkeys(x["n_links"] for x in rows):
        g, b = pick.get((n, "ggl")), pick.get((n, "baumgarte"))
        if g and b:
            out.append([n, seconds(g["wall_time_s_median"]), seconds(b["wall_time_s_median"]),
                        f"{num(b['wall_time_s_median']) / num(g['wall_time_s_median']):.1f}",
                        metres(g["tip_error_m"]), metres(b["tip_error_m"]),
                        sig(num(g["max_constraint_residual"])), sig(num(b["max_constraint_residual"])),
                        f"{g['steps']} / {b['steps']}"])
    return f"""## Pendulum chains: GGL against Baumgarte

Planar chains of N links (1 m in all), released from a bent arc, 5 s, in the two constraint
formulations: GGL (index 2) and Baumgarte (index 1, α = 20, β = 1). Tip error: the largest
distance of the last link's tip from a GGL run at rtol 1e-10; max ‖Φ‖: the largest position
constraint residual over the samples. At rtol {tol(rtol)}, atol = rtol/100; wall: median of 3 runs,
measured while other builds ran (load average 5–8, so ±30 %). The CSV and the plot have rtol
1e-3 … 1e-7.

{table(["N", "wall GGL", "wall Baumgarte", "Baumgarte / GGL", "tip error GGL", "tip error Baumgarte",
        "max ‖Φ‖ GGL", "max ‖Φ‖ Baumgarte", "steps GGL / Baumgarte"], out)}

{r.source("build/benchmarks/bench_pendulum_chain", "pendulum_chain.csv", rows, "pendulum_chain.png")}
"""


def reeving_cost(r: Results) -> str:
    rows = r.csv("reeving_cost.csv")
    build = {"before": "one dense element", "after": "a block per cable"}
    body = table(["scene", "coordinates", "Jacobian of the massive rope", "steps", "residual evaluations", "wall",
                  "CPU", "real-time factor (CPU)"],
                 [[x["case"], x["coordinates"], build[x["binary"]] if x["elements_per_part"] != "0" else "massless",
                   x["steps"], x["residual_evaluations"], seconds(x["wall_median_s"]), seconds(x["cpu_median_s"]),
                   f"{sig(num(x['simulated_s']) / num(x['cpu_median_s']), 3)}×"] for x in rows])
    apart = next((x["load_distance_max_m"] for x in rows if x.get("load_distance_max_m")), "nan")
    return f"""## Reeved ropes: massless and massive

What a massive reeved rope costs against the massless one on the same path, and how it grows with
its cables per part ([massless or massive](elements.md#massless-or-massive-what-each-costs)):
the hook block on 4 falls (12 s) and the reeved thesis crane (60 s), rows of one session with the
massive rope assembled as one dense element (before) and as a block per cable (after),
alternating run by run. Wall: the integration's; CPU: the whole process's; medians of the runs.
On the combined motion the massive hoist rope moves the load at most {metres(apart)} from the
massless one's path.

{body}

{r.source("python3 benchmarks/reeving_cost.py --before-bin OTHER_BUILD/crane-sim --reps 3", "reeving_cost.csv", rows)}
"""


def sheave_grip(r: Results) -> str:
    rows = r.csv("sheave_grip.csv")
    law = {"band": "friction band, 1 cm/s", "grip": "grip (pre-sliding)"}
    body = table(["sections", "sheave law", "steps", "nonlinear failures", "wall", "CPU", "real-time factor (CPU)",
                  "load off its rtol 1e-7 run", "load average"],
                 [[x["sections"], law[x["binary"]], x["steps"], x["nonlinear_failures"], seconds(x["wall_median_s"]),
                   seconds(x["cpu_median_s"]), f"{sig(60.0 / num(x['cpu_median_s']), 3)}×", metres(x["load_error_m"]),
                   x["load_average"]] for x in rows])
    apart = {x["sections"]: x["load_apart_m"] for x in rows}
    return f"""## Reeved ropes: the sheaves' grip

The reeved thesis crane's 60 s combined motion (`crane_reeved_combined.yaml`, rtol 1e-4) with
the massless ropes' sheaves gripping the rope ([scene-format.md](scene-format.md#reeved-ropes)),
against a build whose sheaves pass their ratio through a friction band of 1 cm/s, with
condensed and with super truss sections, alternating run by run. Wall: the integration's; CPU:
the whole process's; medians of the runs. The load's path with the grip ends
{metres(apart.get("condensed", "nan"))} (condensed) and {metres(apart.get("super truss", "nan"))}
(super truss) from the band's (rtol 1e-7 runs of both): the band's creep after the hoist stops.

{body}

{r.source("python3 benchmarks/sheave_grip.py --before-bin OTHER_BUILD/crane-sim --before-configs OTHER_BUILD_SOURCE/configs --reps 3", "sheave_grip.csv", rows)}
"""


def session_stepping(r: Results) -> str:
    rows = r.csv("session_stepping.csv")
    method = {"profiles": "the scene's profiles (`crane-sim run`)", "inputs": "inputs, commanded every sample",
              "tables": "the same commands as linear tables"}
    body = table(["drives", "lags", "wall", "real-time factor", "steps / Jacobians", "restarts",
                  "hook error against rtol 1e-8"],
                 [[method[x["method"]], x["order"] if x["method"] == "inputs" else "–", seconds(x["wall_s"]),
                   f"{sig(num(x['real_time_factor']), 3)}×", f"{x['steps']} / {x['jacobians']}", x["restarts"],
                   metres(x["hook_error_m"])] for x in rows])
    python = r.csv("python_stepping.csv")
    python_body = table(["driven from", "wall", "real-time factor", "steps"],
                        [[x["driver"], seconds(x["wall_s"]), f"{sig(num(x['real_time_factor']), 3)}×", x["steps"]]
                         for x in python])
    overhead = percent(num(python[0]["python_overhead"])) if python else "–"
    gym = r.csv("gym_throughput.csv")
    gym_body = table(["setup", "environment steps per second", "simulated seconds per second, all environments",
                      "rtol", "load from its path at rtol 1e-8"],
                     [[x["setup"], x["steps_per_s"], f"{x['real_time_factor']}×", x["rtol"],
                       metres(x["load_error_m"])] for x in gym])
    scaling = gym[0]["scaling_1_to_2"] if gym else "–"
    error_time = f"{0.02 * int(gym[0]['error_steps']):g} s" if gym else "–"
    return f"""## Driving the crane step by step

The condensed thesis crane's 60 s combined motion (8.3.2) commanded at 50 Hz
([step by step](session.md)): each drive's speed is its trapezoid's speed at the sample, and the
slewing rate adds a sway-damping feedback on the load, so every command differs from the last.
rtol 1e-4, atol 1e-5; wall: the stepping only (the equilibrium excluded), median of the runs.
Hook error: the largest distance over the motion from the same commands at rtol 1e-8.

{body}

{r.source("build/benchmarks/bench_session_stepping", "session_stepping.csv", rows)}

The same feedback law in a Python loop over `cranesim.Simulation` against the C++ loop above
(inputs, second-order lags); the Python loop's overhead: {overhead}.

{python_body}

{r.source("python3 benchmarks/python_stepping.py", "python_stepping.csv", python)}

The Gymnasium environment `cranesim/CraneLift-v0` stepped with random actions (every drive's
command jumps at every 20 ms step); from 1 to 2 worker processes of `AsyncVectorEnv` the
throughput grows {scaling}-fold, and `cranesim.gym.ThreadedVectorEnv` steps its environments on
the threads of one process, without the workers' messages. The environment integrates at rtol
1e-3 (`rtol`); the last column is the largest distance of the load from its path at rtol 1e-8
under the same random actions over {error_time}.

{gym_body}

{r.source("python3 benchmarks/gym_throughput.py", "gym_throughput.csv", gym)}
"""


def anti_sway(r: Results) -> str:
    rows = r.csv("anti_sway.csv")
    body = table(["case", "5–10 s after: open / closed loop", "last 10 s: open / closed loop", "less swing",
                  "real-time factor open / closed"],
                 [[x["case"], f"{metres(x['open_5_10_s_m'])} / {metres(x['closed_5_10_s_m'])}",
                   f"{metres(x['open_last_10_s_m'])} / {metres(x['closed_last_10_s_m'])}",
                   f"{100 * num(x['reduction_last_10_s']):.0f} %",
                   f"{x['open_real_time_factor']}× / {x['closed_real_time_factor']}×"] for x in rows])
    study = r.csv("anti_sway_study.csv")
    study_body = table(["load", "hoist rope", "from 5 s after the release: open / closed", "last 10 s: open / closed",
                        "less swing", "largest hoist tension: open / closed"],
                       [[f"{x['load_t']} t", f"{num(x['hoist_rope_m']):.2f} m",
                         f"{metres(x['open_from_25_s_m'])} / {metres(x['closed_from_25_s_m'])}",
                         f"{metres(x['open_last_10_s_m'])} / {metres(x['closed_last_10_s_m'])}",
                         f"{100 * num(x['reduction_last_10_s']):.0f} %",
                         f"{num(x['open_tension_max_n']) / 1e6:.2f} / {num(x['closed_tension_max_n']) / 1e6:.2f} MN"]
                        for x in study])
    wind = r.csv("anti_sway_wind_study.csv")
    speeds = list(dict.fromkeys(x["wind_m_s"] for x in wind))
    wind_body = table(["mean wind at 10 m", "last 10 s, open loop", "last 10 s, closed loop", "less swing",
                       "largest hoist tension: open / closed"],
                      [[f"{v} m/s",
                        f"{metres(min(num(x['open_last_10_s_m']) for x in wind if x['wind_m_s'] == v))}–"
                        f"{metres(max(num(x['open_last_10_s_m']) for x in wind if x['wind_m_s'] == v))}",
                        f"{metres(min(num(x['closed_last_10_s_m']) for x in wind if x['wind_m_s'] == v))}–"
                        f"{metres(max(num(x['closed_last_10_s_m']) for x in wind if x['wind_m_s'] == v))}",
                        f"{100 * min(num(x['reduction_last_10_s']) for x in wind if x['wind_m_s'] == v):.0f}–"
                        f"{100 * max(num(x['reduction_last_10_s']) for x in wind if x['wind_m_s'] == v):.0f} %",
                        f"{max(num(x['open_tension_max_n']) for x in wind if x['wind_m_s'] == v) / 1e6:.2f} / "
                        f"{max(num(x['closed_tension_max_n']) for x in wind if x['wind_m_s'] == v) / 1e6:.2f} MN"]
                       for v in speeds])
    return f"""## Feedback against sway

The condensed thesis crane at 50 Hz from Python, each case open loop and with
`cranesim.control.AntiSway` ([feedback against sway](control.md)): the largest swing of the hook
about the boom head from 5 to 10 s after the last stop of the lever (or the end of the gust), and
over the last 10 s of the run. The cases are in the benchmark's docstring.

{body}

{r.source("python3 benchmarks/anti_sway.py", "anti_sway.csv", rows, "anti_sway.png")}

**Robustness** (`configs/study_anti_sway.yaml`, run by `crane-sim study`): the same lever and
release from the command line (`configs/crane_anti_sway.yaml`, the controller in the scene's
`feedback:`) on the load's mass × the hoist rope's length, the feedback holding the head from the
release against open loop; the controller knows the rope it measures, not the load's mass.

{study_body}

{r.source("python3 benchmarks/anti_sway_study.py", "anti_sway_study.csv", study, "anti_sway_study.png")}

**In wind** (`configs/study_anti_sway_wind.yaml`): the same cases in a mean wind across the boom
(`configs/crane_anti_sway_wind.yaml`: power-law profile, on the load, the ropes and every lattice
tube) with a gust of 1.4 times its speed from 30 to 38 s, ten seconds after the release; the swing
about the load's mean offset under the boom head. The nine load × rope cases of each wind speed,
as ranges:

{wind_body}

{r.source("python3 benchmarks/anti_sway_study.py", "anti_sway_wind_study.csv", wind, "anti_sway_wind_study.png")}
"""


def operator_assistance(r: Results) -> str:
    rows = r.csv("operator_assistance.csv")
    body = table(["lever driven by", "crane stops at", "largest swing from 5 s after each stop", "largest swing",
                  "real-time factor", "controller per sample"],
                 [[x["case"], f"{num(x['stop1_s']):.1f} s, {num(x['stop2_s']):.1f} s",
                   f"{metres(x['stop1_from_5_s_m'])}, {metres(x['stop2_from_5_s_m'])}", metres(x["largest_m"]),
                   f"{x['real_time_factor']}×",
                   "–" if x["case"] == "lever" else f"{num(x['controller_us_per_sample']):.0f} µs"] for x in rows])
    return f"""## Operator assistance

The condensed thesis crane at 50 Hz from Python under an operator's lever: a slew with a hoist, a
stop, a reversal with a lowering, a stop ([operator assistance](control.md#operator-assistance)).
The lever's speeds drive the crane directly, through `AntiSway` following them, or through
`AntiSway(shaping=17.1, boom_period=1.4)`; the largest swing of the hook about the boom head from
5 s after each stop of the crane until it moves again.

{body}

{r.source("python3 benchmarks/operator_assistance.py", "operator_assistance.csv", rows, "operator_assistance.png")}
"""


def plan_tracking(r: Results) -> str:
    rows = r.csv("plan_tracking.csv")
    cases = list(dict.fromkeys(x["case"] for x in rows))
    groups = list(dict.fromkeys((x["target"], x["crane"]) for x in rows))

    def run(target, crane, case, loop):
        return next(x for x in rows if (x["target"], x["crane"], x["case"], x["loop"]) == (target, crane, case, loop))

    body = table(["case"] + [f"{t}, {c}: open / tracked" for t, c in groups],
                 [[case] + [f"{metres(run(t, c, case, 'open')['sway_from_5_s_m'])} / "
                            f"{metres(run(t, c, case, 'closed')['sway_from_5_s_m'])}" for t, c in groups]
                  for case in cases])
    speed = table(["target, crane", "real-time factor open / tracked", "controller per sample", "largest dynamic factor tracked"],
                  [[f"{t}, {c}",
                    f"{min(num(x['real_time_factor']) for x in rows if (x['target'], x['crane'], x['loop']) == (t, c, 'open')):.0f}–"
                    f"{max(num(x['real_time_factor']) for x in rows if (x['target'], x['crane'], x['loop']) == (t, c, 'open')):.0f}× / "
                    f"{min(num(x['real_time_factor']) for x in rows if (x['target'], x['crane'], x['loop']) == (t, c, 'closed')):.0f}–"
                    f"{max(num(x['real_time_factor']) for x in rows if (x['target'], x['crane'], x['loop']) == (t, c, 'closed')):.0f}×",
                    f"{max(num(x['controller_us_per_sample']) for x in rows if (x['target'], x['crane']) == (t, c)):.0f} µs at most",
                    f"{max(num(x['dynamic_factor']) for x in rows if (x['target'], x['crane'], x['loop']) == (t, c, 'closed')):.3f}"]
                   for t, c in groups])
    return f"""## Tracking a plan

The shipped targets' feedback cases ([tracking a plan](control.md#tracking-a-plan)): each
crane-opt plan run on a crane that differs from the planned one, the plan alone (open) and
tracked by the anti-sway feedback, at rtol 1e-4. The largest sway of the load from its rope's
suspension from 5 s after the planned arrival to the run's end (20 s after the last knot):

{body}

Cost of the 81 s runs (the real-time factor includes building each run's model and, tracked,
the controller's table of 14 equilibria):

{speed}

{r.source("python3 benchmarks/plan_tracking.py", "plan_tracking.csv", rows, "plan_tracking.png")}
"""


def sway_sensor(r: Results) -> str:
    rows = r.csv("sway_sensor.csv")
    closed = [x for x in rows if x["loop"] == "closed"]
    delays = list(dict.fromkeys(x["delay_s"] for x in closed))
    noises = list(dict.fromkeys(x["noise"] for x in closed))
    open_loop = next((x for x in rows if x["loop"] == "open"), {"sway_from_5_s_m": "nan"})

    def cell(delay, noise):
        x = next(x for x in closed if (x["delay_s"], x["noise"]) == (delay, noise))
        return metres(x["sway_from_5_s_m"])

    body = table(["sensor delay"] + [f"noise {1e3 * num(n):g} mrad, mrad/s" for n in noises],
                 [[f"{num(d):g} s"] + [cell(d, n) for n in noises] for d in delays])
    return f"""## The sway sensor

Table 8-2 on the condensed crane with the load let go 0.5 m out of plumb, tracked by the
feedback while the rope's angles reach it late and noisy ([the sensor](control.md#the-sensor));
the largest sway of the load from 5 s after the planned arrival (the plan alone:
{metres(open_loop["sway_from_5_s_m"])}):

{body}

{r.source("python3 benchmarks/sway_sensor.py", "sway_sensor.csv", rows, "sway_sensor.png")}
"""


def setup_times(r: Results) -> str:
    rows = r.csv("setup_times.csv")
    body = table(["step", "command", "wall", "detail"],
                 [[x["step"], f"`{x['command']}`", seconds(x["wall_s"]) if num(x["wall_s"]) < 120
                   else f"{int(num(x['wall_s']) // 60)} min {int(num(x['wall_s']) % 60)} s", x["detail"]] for x in rows])
    return f"""## Setting up and building

The README's main command times its own phases into `out/main/main_command_times.csv`; copy them
into `benchmarks/results/setup_times.csv` after a run on a fresh machine. The fresh machine is a
minimal Debian bookworm (debootstrap minbase, with git) in a chroot on the 2-core machine, the
packages from this machine's mirror; nothing else ran on the machine meanwhile. The CI time is
the clean-clone run's log.

{body}

{r.source(None, "setup_times.csv", rows)}

{build_cpu(r)}

{compile_times(r)}
"""


def build_cpu(r: Results) -> str:
    rows = r.csv("build_cpu.csv")
    cpu: dict[tuple[str, str], float] = {}
    units: dict[tuple[str, str], int] = {}
    for x in rows:
        key = (x["part"], x["configuration"])
        cpu[key] = cpu.get(key, 0.0) + num(x["user_s"]) + num(x["sys_s"])
        units[key] = units.get(key, 0) + 1
    parts = list(dict.fromkeys(x["part"] for x in rows))
    total = {c: sum(v for (_, k), v in cpu.items() if k == c) for c in ("unity off", "unity on")}

    def line(name, off, on, units_off, units_on):
        return [name, f"{units_off} / {units_on}", seconds(off), seconds(on), f"{on / off - 1:+.0%}" if off else "–"]

    body = table(["part of the build", "translation units (off / on)", "CPU, unity off", "CPU, unity on", "change"],
                 [line(p, cpu.get((p, "unity off"), 0.0), cpu.get((p, "unity on"), 0.0),
                       units.get((p, "unity off"), 0), units.get((p, "unity on"), 0)) for p in parts]
                 + [line("**in all**", total["unity off"], total["unity on"],
                         sum(v for (_, k), v in units.items() if k == "unity off"),
                         sum(v for (_, k), v in units.items() if k == "unity on"))])
    return f"""What the main command compiles (`crane-sim`, the Python extension and the libraries they
link), from scratch, with and without the unity build (`CRANESIM_UNITY_BUILD`): user and system
CPU time summed over the compilations, g++ 12 at `-O3`. The element kernels and the Python
extension are not batched: their rows differ by the measurement's spread. On two cores the
build's wall time is about half the total.

{body}

{r.source("python3 benchmarks/build_cpu.py", "build_cpu.csv", rows)}"""


def compile_times(r: Results) -> str:
    rows = r.csv("compile_times.csv")
    body = table(["file compiled", "front-end CPU", "of it template instantiation", "detail"],
                 [[f"`{x['file']}`" if x["file"].endswith(".cpp") else x["file"], seconds(x["cpu_s"]), f"{num(x['instantiation_share']):.0%}", x["detail"]]
                  for x in rows])
    return f"""Where a build's CPU time goes, file by file: the front end alone (`g++ -fsyntax-only
-ftime-report`, user CPU time, g++ 12 at `-O3`; the code generation comes on top; measured on the
shared 2-core machine while other builds ran). A file that only includes a kernel header pays
for parsing it, no longer for its tangents.

{body}

{r.source("g++ -fsyntax-only -ftime-report <the file's flags from build/compile_commands.json>", "compile_times.csv", rows)}"""


SECTIONS = [combined_motion, fidelities, equilibrium_grid, map_parallel, jacobian_ratio, truss_reduction,
            element_bending, slender_statics, element_vibration, pendulum_chain, reeving_cost, sheave_grip, session_stepping, anti_sway,
            operator_assistance, plan_tracking, sway_sensor, setup_times]


def render(results: Results) -> str:
    head = """<!-- generated by benchmarks/performance_doc.py from benchmarks/results/; do not edit by hand -->
# Performance

Generated by `benchmarks/performance_doc.py` from the results in `benchmarks/results/`; do not
edit by hand. Every table is the latest run of one benchmark, with the command that produced
it (run from the repository root after building; [benchmarks/README.md](../benchmarks/README.md)
says how long each takes) and the machine. Timings come from a shared 2-core machine and vary by
10–30 % between runs; the benchmarks are not re-run together, so compare rows within one table,
not across tables. Verified accuracy against references is in [verification](verification.md).
"""
    return "\n".join([head] + [section(results) for section in SECTIONS])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", type=Path, default=ROOT / "benchmarks" / "results", help="the CSV directory")
    parser.add_argument("--output", type=Path, default=ROOT / "docs" / "performance.md", help="the page to write")
    parser.add_argument("--check", action="store_true", help="write nothing; exit 1 if the page differs or a result is missing")
    args = parser.parse_args()
    results = Results(args.results)
    text = render(results)
    if results.missing:
        print(f"performance_doc: missing in {args.results}: {', '.join(results.missing)} "
              f"(quoted by {args.output.name}); re-run the benchmark or restore the file", file=sys.stderr)
        return 1
    if args.check:
        current = args.output.read_text(encoding="utf-8") if args.output.is_file() else ""
        if current != text:
            diff = list(difflib.unified_diff(current.splitlines(), text.splitlines(), str(args.output), "generated", lineterm=""))
            print(f"performance_doc: {args.output} is not what benchmarks/results/ gives; "
                  f"run python3 benchmarks/performance_doc.py\n" + "\n".join(diff[:40]), file=sys.stderr)
            return 1
        return 0
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
