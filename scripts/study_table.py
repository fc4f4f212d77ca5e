#!/usr/bin/env python3
"""Prints the case table of a `crane-sim study` file (docs/study-format.md): one row per case with
its parameter values, its figures, its status, with criteria whether it is admissible and with a
capacity search the capacity found and what limits it, with a least stable angle search the angle
found and the grid angle that was worst.

    python3 scripts/study_table.py TABLE.h5                    # every case, aligned columns
    python3 scripts/study_table.py TABLE.h5 --status complete  # only the complete cases
    python3 scripts/study_table.py TABLE.h5 --csv cases.csv    # the same rows as CSV

A file that is not a study table is refused in one line, exit status 2.
"""

import argparse
import csv
import math
import sys

import h5py
import numpy as np


class NotAStudy(Exception):
    pass


def read_table(path: str) -> tuple[list, list]:
    """(header, rows): case number, parameters, figures, admissible (with criteria), the capacity
    and what limits it (with capacity), the least stable angle found and the grid's worst (with
    least_stable_angle), status, message."""
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise NotAStudy(f"{path}: cannot open as HDF5 ({e})") from None
    with f:
        if f.attrs.get("contents") != "study":
            raise NotAStudy(f"{path}: not a study table (crane-sim study writes one)")
        columns = [(name, f["parameters"][name][()]) for name in f["parameters"]]
        columns += [(name, f["figures"][name][()]) for name in f.get("figures", {})]
        if "admissible" in f["cases"]:
            columns.append(("admissible", f["cases/admissible"][()]))
        texts = []
        if "capacity" in f:
            columns.append(("capacity", f["capacity/load"][()]))
            columns.append(("inadmissible_load", f["capacity/inadmissible_load"][()]))
            texts.append(("limited_by", f["capacity/limited_by"].asstr()[()]))
        if "least_stable" in f:
            columns.append(("least_stable_angle", f["least_stable/angle"][()]))
            columns.append(("worst_grid_angle", f["least_stable/grid_angle"][()]))
        status = f["cases/status"].asstr()[()]
        message = f["cases/message"].asstr()[()]
    header = ["case"] + [name for name, _ in columns] + [name for name, _ in texts] + ["status", "message"]
    rows = [[case] + [float(values[case]) for _, values in columns] + [values[case] for _, values in texts]
            + [status[case], message[case]] for case in range(len(status))]
    return header, rows


def formatted(value) -> str:
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.6g}"
    return str(value)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("table", help="a case table written by crane-sim study")
    parser.add_argument("--status", help="only the cases of this status (complete, failed, bad_input, not_run)")
    parser.add_argument("--csv", metavar="FILE", help="write the rows as CSV to FILE instead of printing them")
    args = parser.parse_args(argv)
    try:
        header, rows = read_table(args.table)
    except NotAStudy as e:
        print(f"study_table.py: error: {e}", file=sys.stderr)
        return 2
    if args.status:
        rows = [row for row in rows if row[-2] == args.status]
    if args.csv:
        with open(args.csv, "w", newline="") as out:
            writer = csv.writer(out)
            writer.writerow(header)
            writer.writerows([[formatted(v) for v in row] for row in rows])
        return 0
    text = [header] + [[formatted(v) for v in row] for row in rows]
    widths = np.max([[len(cell) for cell in line[:-1]] for line in text], axis=0)
    for line in text:
        print("  ".join(cell.rjust(width) for cell, width in zip(line[:-1], widths)) + ("  " + line[-1]).rstrip())
    return 0


if __name__ == "__main__":
    sys.exit(main())
