#!/usr/bin/env python3
"""Tip of a flexible beam over time for several runs, like the thesis' Figures 8-2..8-4.

Top panel: the global z coordinate of the member's end joint (<member>.end). Bottom panel: its
z displacement relative to the rigid rotation, i.e. the tip position expressed in the frame of
the member's root section (<member>.start) minus the undeformed length along x. One line per
results file, labelled with the file's stem (or --labels).

Example:
    python3 scripts/plot_beam_tip.py t1.h5 t3.h5 t10.h5 --labels "T-beam 1,T-beam 3,T-beam 10" \\
        -o tip.png
"""

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cranesim.results import Results, ResultsError, run_command  # noqa: E402


def tip_series(path: Path, member: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Time, global tip z and the tip's z displacement in the root-section frame."""
    with Results(path) as results:
        t = results.time()
        root = results.get(f"joints/{member}.start/position")
        root_rotation = results.get(f"joints/{member}.start/rotation")
        tip = results.get(f"joints/{member}.end/position")
    local = np.einsum("nji,nj->ni", root_rotation, tip - root)  # Rᵀ (r_tip − r_root)
    return t, tip[:, 2], local[:, 2]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="+", type=Path, help="results files (HDF5)")
    parser.add_argument("--member", default="beam", help="name of the flexible member (default: beam)")
    parser.add_argument("--labels", help="comma-separated legend labels, one per file")
    parser.add_argument("--title", default="", help="figure title")
    parser.add_argument("-o", "--output", type=Path, default=Path("beam_tip.png"), help="image to write")
    args = parser.parse_args()
    labels = args.labels.split(",") if args.labels else [p.stem for p in args.results]
    if len(labels) != len(args.results):
        raise ResultsError(f"--labels has {len(labels)} entries for {len(args.results)} results files")
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9.0, 7.0), sharex=True)
    for path, label in zip(args.results, labels):
        t, z, w = tip_series(path, args.member)
        top.plot(t, z, lw=0.9, label=label)
        bottom.plot(t, w, lw=0.9, label=label)
    top.set_ylabel("tip z (m)")
    bottom.set_ylabel("tip z relative to the root section (m)")
    bottom.set_xlabel("time (s)")
    for ax in (top, bottom):
        ax.grid(True, alpha=0.3)
    top.legend(fontsize=8)
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(run_command(main))
