"""What the benchmark plotters (plot_*.py beside this file) share: reading a benchmark's CSV with
its columns checked, matplotlib without a display, and the error convention of the command line
(one line on standard error, exit status 2)."""

import csv
import sys
from pathlib import Path


class BadFile(Exception):
    """A CSV that cannot be plotted; the message names the file and says why."""


def read_rows(path, columns, producer, integers=(), texts=()):
    """The rows of `path` as dicts of `columns`: ints for `integers`, non-empty strings for
    `texts`, floats for the rest ('nan' accepted). Raises BadFile on anything else."""
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            if reader.fieldnames is None:
                raise BadFile(f"{path}: empty file, expected a header row")
            missing = [c for c in columns if c not in reader.fieldnames]
            if missing:
                raise BadFile(f"{path}: missing column(s) {', '.join(missing)}; "
                              f"expected the header of {producer}: {','.join(columns)}")
            rows = []
            for line, raw in enumerate(reader, start=2):
                row = {}
                for c in columns:
                    text = (raw.get(c) or "").strip()
                    try:
                        if c in texts:
                            if not text:
                                raise ValueError("empty")
                            row[c] = text
                        elif c in integers:
                            row[c] = int(text)
                        else:
                            row[c] = float(text)
                    except ValueError:
                        raise BadFile(f"{path}:{line}: column '{c}' has an invalid value {text!r}") from None
                rows.append(row)
    except OSError as e:
        raise BadFile(f"{path}: cannot read ({e.strerror})") from None
    except (UnicodeDecodeError, csv.Error) as e:
        raise BadFile(f"{path}: not a readable CSV file ({e})") from None
    if not rows:
        raise BadFile(f"{path}: no data rows")
    return rows


def pyplot():
    """matplotlib.pyplot on the Agg backend; imported on demand, so that --help and bad input
    answer without paying matplotlib's start-up."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def fail(script, message):
    """Reports a bad input the way every plotter does; returns the exit status."""
    print(f"{script}: error: {message}", file=sys.stderr)
    return 2


def machine():
    """This machine as the benchmarks' tables name it: cores and CPU model (from /proc/cpuinfo)."""
    import os

    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            model = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), model)
    except OSError:
        pass
    return f"{os.cpu_count()} cores, {model}"


def write_rows(path, rows):
    """Writes dict rows (the first row's keys as the header) to `path`, making its directory."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
