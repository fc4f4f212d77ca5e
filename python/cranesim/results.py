"""Reader for cranesim HDF5 results files (format: docs/results-format.md).

Quantities are addressed by their dataset path, optionally followed by a
component selector in brackets:

    time                              whole dataset
    energy/balance                    whole dataset
    lambda[0]                         column 0
    joints/link3.tip/position[2]      z component
    bodies/link1/velocity[norm]       Euclidean norm over the last axis

Example, as a command listing what a results file holds:

    python3 -m cranesim.results run.h5

Example, as a library (cranesim.run and cranesim.static return one):

    from cranesim.results import Results
    with Results("run.h5") as results:
        t = results.time()
        z = results.get("joints/link3.tip/position[2]")
"""

import argparse
import difflib
import re
import sys
from pathlib import Path
from typing import Callable

import h5py
import numpy as np

QUANTITY_SYNTAX = re.compile(r"^/?(?P<path>[^\[\]]+?)(?:\[(?P<selector>-?\d+|norm)\])?$")

# Checked in order: the first fragment contained in the path decides the unit.
UNIT_BY_PATH_FRAGMENT = (
    ("residual", "-"),
    ("supports/margin", "N·m"),
    ("pressure", "Pa"),
    ("peak_at", "m"),
    ("contact_length", "m"),
    ("supports/resultant", "m"),
    ("supports/tipping_line", "m"),
    ("supports/", "N"),
    ("energy/", "J"),
    ("lambda", "N, N·m"),
    ("angular_velocity", "rad/s"),
    ("velocity", "m/s"),
    ("position", "m"),
    ("rotation", "-"),
    ("time", "s"),
)
UNIT_BY_EXACT_PATH = {"q": "m, rad", "v": "m/s, rad/s"}


class ResultsError(Exception):
    """Bad input: missing or unreadable file, unknown quantity, malformed data."""


def run_command(main: Callable[[], None]) -> int:
    """Run a command-line entry point; report ResultsError/OSError in one line, exit code 2."""
    try:
        main()
    except (ResultsError, OSError) as error:
        print(f"{Path(sys.argv[0]).name}: error: {error}", file=sys.stderr)
        return 2
    return 0


def parse_quantity(quantity: str) -> tuple[str, int | str | None]:
    """Split 'path[selector]' into the dataset path and None, a column index or 'norm'."""
    match = QUANTITY_SYNTAX.match(quantity.strip())
    if match is None:
        raise ResultsError(
            f"malformed quantity '{quantity}'; expected PATH, PATH[INDEX] or PATH[norm]"
        )
    selector = match["selector"]
    if selector is not None and selector != "norm":
        selector = int(selector)
    return match["path"], selector


def guess_unit(quantity: str) -> str:
    """SI unit of a quantity, guessed from its path ('?' when unknown)."""
    path, _ = parse_quantity(quantity)
    if path in UNIT_BY_EXACT_PATH:
        return UNIT_BY_EXACT_PATH[path]
    for fragment, unit in UNIT_BY_PATH_FRAGMENT:
        if fragment in path:
            return unit
    return "?"


def as_text(value) -> str:
    """HDF5 strings arrive as str or bytes depending on how they were written."""
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


class Results:
    """An open results file. Warns on stderr when the run is incomplete."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        if not self.path.is_file():
            raise ResultsError(f"no such results file: {self.path}")
        if not h5py.is_hdf5(self.path):
            raise ResultsError(f"not an HDF5 file: {self.path}")
        self.file = h5py.File(self.path, "r")
        if self.status == "incomplete":
            print(
                f"warning: {self.path}: run is INCOMPLETE: {self.message or '(no message)'}",
                file=sys.stderr,
            )

    def __enter__(self) -> "Results":
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()

    def close(self) -> None:
        self.file.close()

    def attribute(self, name: str, group: str = "/") -> str | float | int | None:
        value = self.file[group].attrs.get(name)
        if isinstance(value, (bytes, str)):
            return as_text(value)
        return value.item() if isinstance(value, np.generic) else value

    @property
    def status(self) -> str:
        return self.attribute("status") or "unknown"

    @property
    def message(self) -> str:
        return self.attribute("message") or ""

    def dataset_paths(self) -> list[str]:
        paths = []
        self.file.visititems(
            lambda name, item: paths.append(name) if isinstance(item, h5py.Dataset) else None
        )
        return paths

    def solver_statistics(self) -> dict[str, float | int]:
        if "solver" not in self.file:
            return {}
        return {name: self.attribute(name, "solver") for name in self.file["solver"].attrs}

    def time(self) -> np.ndarray:
        return self.dataset("time")[()]

    def tipping_moments(self) -> dict[str, np.ndarray]:
        """The moments about the scene's tipping lines (output.tipping_lines), N·m: > 0 holds the
        structure on its footprint."""
        if "tipping_moments" not in self.file or self.time().size == 0:
            return {}
        return {name: dataset[()] for name, dataset in self.file["tipping_moments"].items()}

    def sampled_time(self) -> np.ndarray:
        """The output times of a file that has samples; one without is an error."""
        time = self.time()
        if time.size == 0:
            raise ResultsError(f"{self.path} holds no samples")
        return time

    def has(self, path: str) -> bool:
        return path.strip("/") in self.file

    def names(self, path: str) -> np.ndarray:
        """A string dataset of /model as an array of str (keeps its shape)."""
        dataset = self.dataset(path)
        if h5py.check_string_dtype(dataset.dtype) is None:
            raise ResultsError(f"'{path}' in {self.path} should hold strings, not {dataset.dtype}")
        return np.asarray(dataset.asstr()[()], dtype=object).astype(str)

    def get(self, quantity: str) -> np.ndarray:
        """Values of a quantity (see module docstring), first axis is time."""
        path, selector = parse_quantity(quantity)
        data = self.dataset(path)[()]
        if data.dtype.kind not in "iuf":
            raise ResultsError(f"'{path}' in {self.path} is not numeric")
        if selector is None:
            return data
        if data.ndim < 2:
            raise ResultsError(f"'{path}' has shape {data.shape}; it has no components to select")
        if selector == "norm":
            return np.linalg.norm(data, axis=-1)
        count = data.shape[1]
        if not -count <= selector < count:
            raise ResultsError(
                f"component {selector} of '{path}' is out of range; it has {count} (0..{count - 1})"
            )
        return data[:, selector]

    def dataset(self, path: str) -> h5py.Dataset:
        path = path.strip("/")
        item = self.file.get(path)
        if isinstance(item, h5py.Dataset):
            return item
        if isinstance(item, h5py.Group):
            raise ResultsError(
                f"'{path}' in {self.path} is a group, not a dataset; it holds: {', '.join(item)}"
            )
        close = difflib.get_close_matches(path, self.dataset_paths(), n=5, cutoff=0.5)
        hint = f"did you mean: {', '.join(close)}?" if close else "no similar paths"
        raise ResultsError(
            f"no quantity '{path}' in {self.path}; {hint} "
            f"(list all with: python3 -m cranesim.results {self.path})"
        )


def describe(results: Results) -> str:
    lines = [f"{results.path}"]
    lines += [f"  @{name} = {results.attribute(name)!r}" for name in results.file.attrs
              if name != "scene_text"]
    for path in results.dataset_paths():
        dataset = results.file[path]
        lines.append(f"  /{path}  {dataset.shape}  {dataset.dtype}")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("results", help="results file (.h5)")
    args = parser.parse_args()
    with Results(args.results) as results:
        print(describe(results))


if __name__ == "__main__":
    sys.exit(run_command(main))
