"""Axial forces of a member's beams over a run: the tubes of a lattice section modelled tube by
tube, or the elements of a beam (the scene's `output.section_forces`, docs/results-format.md).

Top: every beam's axial force over time (the mean of its two ends), the most pulled and the
most pressed beams named. Bottom: the range of each beam's axial force over the run, in the
order the results file lists them. Prints the extremes with their beams and times.

A rope listed there records its tension along its elements instead: top, the tension at its two
ends and its least along it over time (0: slack somewhere); bottom, the range of the tension
along the rope over the run. Prints the largest tension, where and when, and the slack time.

Example:

    crane-sim run my_crane.yaml -o lift.h5      # with output: {section_forces: [boom3]}
    python scripts/plot_section_forces.py lift.h5 --member boom3 -o boom3_forces.png
"""

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from cranesim.results import Results, ResultsError, run_command


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="results file")
    parser.add_argument("--member", help="member name (default: the only one with section forces)")
    parser.add_argument("-o", "--output", help="output image (default: <results>_<member>_forces.png)")
    return parser.parse_args()


def member_name(results: Results, requested: str | None) -> str:
    members = sorted(results.file["section_forces"].keys()) if results.has("section_forces") else []
    if not members:
        raise ResultsError(f"{results.path} records no section forces: list the member under the scene's "
                           "output.section_forces")
    if requested is not None:
        if requested not in members:
            raise ResultsError(f"no section forces of '{requested}' in {results.path}; recorded: {', '.join(members)}")
        return requested
    if len(members) != 1:
        raise ResultsError(f"{results.path} records section forces of {', '.join(members)}: choose one with --member")
    return members[0]


def plot_rope(path: Path, member: str, time: np.ndarray, tension: np.ndarray, status: str, output: str | None) -> None:
    """Tension along a rope: (samples, elements, points) from its start to its end."""
    samples, elements, points = tension.shape
    along = (np.arange(elements)[:, None] + np.linspace(0.0, 1.0, points)[None, :]).ravel()  # element units
    flat = tension.reshape(samples, elements * points)
    figure, (history, envelope) = plt.subplots(2, 1, figsize=(10, 7.5))
    history.plot(time, flat[:, 0] / 1e3, label=f"{member}.start")
    history.plot(time, flat[:, -1] / 1e3, label=f"{member}.end")
    history.plot(time, flat.min(axis=1) / 1e3, color="0.5", linewidth=0.8, label="least along the rope")
    history.set_xlabel("time [s]")
    history.set_ylabel(f"{member}: tension [kN]")
    history.legend(fontsize="small")
    envelope.fill_between(along, flat.min(axis=0) / 1e3, flat.max(axis=0) / 1e3, color="tab:red", alpha=0.4)
    envelope.plot(along, flat[-1] / 1e3, color="tab:red", linewidth=1, label=f"at t = {time[-1]:.4g} s")
    envelope.set_xlabel(f"along {member} [elements, from its start]")
    envelope.set_ylabel("tension over the run [kN]")
    envelope.legend(fontsize="small")
    for axes in (history, envelope):
        axes.grid(True, alpha=0.3)
    figure.suptitle(path.name if status == "complete" else f"{path.name} ({status})")
    figure.tight_layout()
    target = Path(output) if output else path.with_name(f"{path.stem}_{member}_forces.png")
    figure.savefig(target, dpi=100)
    sample, point = np.unravel_index(int(np.argmax(flat)), flat.shape)
    slack = (flat.min(axis=1) <= 0.0)[:-1] @ np.diff(time) if samples > 1 else 0.0
    print(f"largest tension: {flat[sample, point]:.6g} N at {along[point]:.3g} elements along {member}, t = {time[sample]:.6g} s")
    print(f"slack somewhere along {member} for {slack:.6g} s")
    print(f"wrote {target}")


def main() -> None:
    args = parse_arguments()
    path = Path(args.results)
    with Results(path) as results:
        member = member_name(results, args.member)
        time = results.sampled_time()
        status = results.status
        if results.has(f"section_forces/{member}/tension"):
            plot_rope(path, member, time, results.get(f"section_forces/{member}/tension"), status, args.output)
            return
        forces = results.get(f"section_forces/{member}/forces")  # (samples, beams, 12)
        nodes = results.names(f"/section_forces/{member}/element_nodes")
    axial = forces[:, :, [0, 6]]  # N at end 1 and end 2
    labels = [f"{a} – {b}" for a, b in nodes]
    tension = axial.max(axis=(0, 2))
    compression = axial.min(axis=(0, 2))
    pulled, pressed = int(np.argmax(tension)), int(np.argmin(compression))

    figure, (history, envelope) = plt.subplots(2, 1, figsize=(10, 7.5))
    for k in range(axial.shape[1]):
        highlighted = k in (pulled, pressed)
        history.plot(time, axial[:, k, :].mean(axis=1) / 1e3, color=None if highlighted else "0.75",
                     linewidth=1.6 if highlighted else 0.6,
                     label=labels[k] if highlighted else None, zorder=2 if highlighted else 1)
    history.set_xlabel("time [s]")
    history.set_ylabel(f"{member}: axial force [kN] (tension > 0)")
    history.legend(fontsize="small")
    beams = np.arange(axial.shape[1])
    colours = np.where(compression > 0, "tab:red", np.where(tension < 0, "tab:blue", "tab:purple"))
    envelope.bar(beams, (tension - compression) / 1e3, bottom=compression / 1e3, color=colours)
    envelope.axhline(0.0, color="k", linewidth=0.6)
    envelope.set_xlabel(f"beam of {member} (as listed in section_forces/{member}/element_nodes)")
    envelope.set_ylabel("axial force over the run [kN]")
    envelope.set_title("red: always pulled, blue: always pressed, purple: both", fontsize="small")
    for axes in (history, envelope):
        axes.grid(True, alpha=0.3)
    figure.suptitle(path.name if status == "complete" else f"{path.name} ({status})")
    figure.tight_layout()
    output = Path(args.output) if args.output else path.with_name(f"{path.stem}_{member}_forces.png")
    figure.savefig(output, dpi=100)

    t_pulled = time[int(np.argmax(axial[:, pulled, :].max(axis=1)))]
    t_pressed = time[int(np.argmin(axial[:, pressed, :].min(axis=1)))]
    print(f"largest tension: {tension[pulled]:.6g} N in {labels[pulled]} at t = {t_pulled:.6g} s")
    print(f"largest compression: {-compression[pressed]:.6g} N in {labels[pressed]} at t = {t_pressed:.6g} s")
    print(f"wrote {output}")


if __name__ == "__main__":
    sys.exit(run_command(main))
