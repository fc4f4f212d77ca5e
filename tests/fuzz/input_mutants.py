"""Mutated scenes and targets against the tools' input contract: no crash, no hang, a clear error.

Every mutant is one of the shipped scenes (configs/*.yaml, their `base:` scenes beside them) with
one defect: a value replaced by a hostile one (NaN, ±inf, 0, negative, 1e308, 1e-308, a huge
integer, an empty or very long string, a list, a mapping, null), a key deleted, renamed or
duplicated, a list item duplicated or dropped, or the text itself cut, spliced or garbled.
Each mutant goes through `crane-sim check` (and, with --run-fraction, a short `crane-sim run`
of a small scene); with --targets the mutants are crane-opt's target files (those whose map is
quick: TARGETS) and go through `crane-opt map`. The contract is checked:

  * the process ends by itself within the time limit (no hang) and not by a signal (no crash);
  * its exit code is 0 (a valid scene), 2 (bad input) or, for `run` and `map`, 1 (solver failure);
  * exit 2 prints one line "error: <file>: <where> (line L, column C): <what>";
  * no results file is left behind by exit 2.

    python3 tests/fuzz/input_mutants.py --mutants 10000 --seed 1 --out benchmarks/results/input_fuzz.csv
    python3 tests/fuzz/input_mutants.py --mutants 200                # a quick look
    python3 tests/fuzz/input_mutants.py --targets --mutants 2000 --out benchmarks/results/target_fuzz.csv

Writes a CSV (one row per mutant: its seed, mutation, command, exit code, seconds, verdict)
and prints a summary with every contract violation and the command that reproduces it.
The same functions serve tests/python/test_input_fuzz.py, which runs a fixed sample in CI.
"""

from __future__ import annotations

import argparse
import copy
import csv
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
# Scenes small enough for a short `run` of every mutant (a few ms of simulated time).
RUNNABLE = ["pendulum.yaml", "rope_pendulum.yaml", "slider_crank.yaml", "double_jib_pendulum.yaml",
            "cantilever_timoshenko.yaml", "spinning_body.yaml"]
# Targets whose static map takes milliseconds (Table 8-2's crane takes seconds a map).
TARGETS = ["target_luffing_jib.yaml"]
HOSTILE_VALUES = [float("nan"), float("inf"), -float("inf"), 0, -1, -1e-9, 1e308, 1e-308, 2**63, -(2**63), 10**30,
                  "", "x" * 5000, "ground", [], [1, 2], {}, {"a": 1}, None, True, 0.5, 3]


@dataclass
class Mutant:
    seed: int
    scene: str          # the shipped scene it comes from
    mutation: str       # what was done, e.g. "value bodies[0].mass -> nan"
    text: str           # the mutant's YAML text


@dataclass
class Verdict:
    command: str
    exit_code: int | None   # None: killed after the time limit
    seconds: float
    violation: str          # empty when the contract holds
    message: str            # the first stderr line


def scenes() -> list[Path]:
    """The shipped scenes (targets of crane-opt excluded)."""
    return sorted(p for p in CONFIGS.glob("*.yaml") if not p.name.startswith(("target", "tmp")))


def targets() -> list[Path]:
    return [CONFIGS / name for name in TARGETS]


def _paths(node, prefix=""):
    """Every (path, container, key) of a parsed YAML tree, scalars and containers alike."""
    if isinstance(node, dict):
        for k, v in node.items():
            path = f"{prefix}.{k}" if prefix else str(k)
            yield path, node, k
            yield from _paths(v, path)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            path = f"{prefix}[{i}]"
            yield path, node, i
            yield from _paths(v, path)


def _tree_mutation(tree, rng: random.Random) -> str:
    """Applies one structural mutation to the parsed tree in place; returns its description."""
    places = list(_paths(tree))
    if not places:
        return "nothing to mutate"
    path, container, key = rng.choice(places)
    kind = rng.choice(["value", "value", "value", "delete", "rename", "duplicate_item", "drop_item", "nest"])
    if kind == "value":
        value = rng.choice(HOSTILE_VALUES)
        container[key] = copy.deepcopy(value)
        return f"value {path} -> {value!r}"[:200]
    if kind == "delete":
        del container[key]
        return f"delete {path}"
    if kind == "rename" and isinstance(container, dict):
        container[str(key) + rng.choice(["_", "s", "X"])] = container.pop(key)
        return f"rename {path}"
    if kind == "duplicate_item" and isinstance(container, list):
        container.insert(key, copy.deepcopy(container[key]))
        return f"duplicate item {path}"
    if kind == "drop_item" and isinstance(container, list) and len(container) > 1:
        container.pop(key)
        return f"drop item {path}"
    container[key] = [container[key]] if rng.random() < 0.5 else {"value": container[key]}
    return f"nest {path}"


def _text_mutation(text: str, rng: random.Random) -> tuple[str, str]:
    """One defect in the text itself."""
    kind = rng.choice(["truncate", "splice", "garble", "duplicate_line", "indent", "tab", "alias"])
    lines = text.splitlines(keepends=True)
    if kind == "truncate":
        cut = rng.randrange(len(text) + 1)
        return text[:cut], f"truncate at {cut}"
    if kind == "splice":
        at = rng.randrange(len(text) + 1)
        junk = "".join(rng.choice("{}[]:,-&*!|>'\"#%@`\\\n \t\x00é∞") for _ in range(rng.randint(1, 12)))
        return text[:at] + junk + text[at:], f"splice {junk!r} at {at}"
    if kind == "garble":
        at = rng.randrange(max(len(text), 1))
        return text[:at] + chr(rng.randrange(1, 0x3000)) + text[at + 1:], f"garble at {at}"
    if kind == "duplicate_line" and lines:
        i = rng.randrange(len(lines))
        return "".join(lines[:i + 1] + lines[i:]), f"duplicate line {i + 1}"
    if kind == "indent" and lines:
        i = rng.randrange(len(lines))
        lines[i] = rng.choice(["", " ", "   ", "      "]) + lines[i].lstrip(" ")
        return "".join(lines), f"re-indent line {i + 1}"
    if kind == "tab" and lines:
        i = rng.randrange(len(lines))
        lines[i] = "\t" + lines[i]
        return "".join(lines), f"tab before line {i + 1}"
    return "x: &a [*a]\n" + text, "self-referential alias"


def make_mutant(seed: int, of_targets: bool = False) -> Mutant:
    rng = random.Random(seed)
    source = rng.choice(targets() if of_targets else scenes())
    text = source.read_text(encoding="utf-8")
    if rng.random() < 0.35:
        mutated, what = _text_mutation(text, rng)
        return Mutant(seed, source.name, what, mutated)
    tree = yaml.safe_load(text)
    what = _tree_mutation(tree, rng)
    mutated = yaml.safe_dump(tree, sort_keys=False, allow_unicode=True, width=4096)
    return Mutant(seed, source.name, what, mutated)


def _short_run(text: str) -> str:
    """The mutant with a few milliseconds of simulated time, if it still parses as a mapping."""
    try:
        tree = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    if isinstance(tree, dict) and isinstance(tree.get("solver"), dict):
        start = tree["solver"].get("t_start", 0)
        if isinstance(start, (int, float)) and not isinstance(start, bool) and math.isfinite(start):
            tree["solver"]["t_end"] = start + 0.005
        return yaml.safe_dump(tree, sort_keys=False, allow_unicode=True, width=4096)
    return text


def check_contract(binary: Path, mutant: Mutant, workdir: Path, run: bool, time_limit: float) -> Verdict:
    """Runs one mutant (in a copy of configs/, so `base:` resolves) and judges the contract: a
    scene by `crane-sim check` or, with `run`, a short `crane-sim run`; a target (binary is
    crane-opt) by `crane-opt map`."""
    scene = workdir / f"mutant_{mutant.seed}.yaml"
    is_target = mutant.scene in TARGETS
    scene.write_text(_short_run(mutant.text) if run else mutant.text, encoding="utf-8", errors="surrogatepass")
    out = workdir / f"mutant_{mutant.seed}.h5"
    if is_target:
        command = [str(binary), "map", scene.name, "-o", out.name, "--quiet"]
    elif run:
        command = [str(binary), "run", scene.name, "-o", out.name, "--quiet"]
    else:
        command = [str(binary), "check", scene.name]
    start = time.perf_counter()
    try:
        done = subprocess.run(command, cwd=workdir, capture_output=True, timeout=time_limit)
        code, stderr = done.returncode, done.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as expired:
        code, stderr = None, (expired.stderr or b"").decode("utf-8", "replace")
    seconds = time.perf_counter() - start
    lines = [line for line in stderr.splitlines() if line.strip()]
    first_error = next((line for line in lines if line.startswith("error:")), lines[0] if lines else "")
    violation = ""
    if code is None:
        violation = f"hang: no exit within {time_limit:g} s"
    elif code < 0:
        violation = f"crash: killed by signal {-code}"
    elif code not in ((0, 1, 2) if run or is_target else (0, 2)):
        violation = f"exit code {code}"
    elif code == 2:
        if not first_error.startswith("error: "):
            violation = "exit 2 without an 'error:' line"
        elif scene.name not in first_error:
            violation = "exit 2 without the scene file's name"
        elif "(line " not in first_error:
            violation = "exit 2 without the line of the defect"
        elif out.exists():
            violation = "exit 2 left a results file"
    if code == 1 and run and not is_target and not out.exists():
        violation = violation or "exit 1 without the results up to the failure"
    scene.unlink(missing_ok=True)
    out.unlink(missing_ok=True)
    return Verdict(" ".join(command[1:]), code, seconds, violation, first_error[:300])


def workspace() -> tempfile.TemporaryDirectory:
    """A temporary copy of configs/ in which the mutants run."""
    tmp = tempfile.TemporaryDirectory(prefix="cranesim_fuzz_")
    for p in CONFIGS.glob("*.yaml"):
        shutil.copy(p, tmp.name)
    return tmp


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", help="crane-sim (default: $CRANESIM_BIN or build/crane-sim), with --targets crane-opt "
                        "(default: $CRANEOPT_BIN or build/crane-opt)")
    parser.add_argument("--targets", action="store_true", help="mutate crane-opt's target files instead of scenes")
    parser.add_argument("--mutants", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=1, help="first mutant's seed; mutant k has seed + k")
    parser.add_argument("--run-fraction", type=float, default=0.2,
                        help="share of the mutants of small scenes that are also run for 5 ms")
    parser.add_argument("--time-limit", type=float, default=20.0, help="seconds before a mutant counts as hanging")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "input_fuzz.csv"))
    args = parser.parse_args()
    default = (os.environ.get("CRANEOPT_BIN", str(ROOT / "build" / "crane-opt")) if args.targets
               else os.environ.get("CRANESIM_BIN", str(ROOT / "build" / "crane-sim")))
    binary = Path(args.bin or default).resolve()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    counts: dict[str, int] = {}
    violations = []
    start = time.perf_counter()
    with workspace() as tmp, out.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["seed", "scene", "mutation", "command", "exit_code", "seconds", "violation", "message"])
        for k in range(args.mutants):
            mutant = make_mutant(args.seed + k, args.targets)
            runs = [False]
            if not args.targets and mutant.scene in RUNNABLE and random.Random(mutant.seed).random() < args.run_fraction:
                runs.append(True)
            for run in runs:
                v = check_contract(binary, mutant, Path(tmp), run, args.time_limit)
                key = "violation" if v.violation else f"exit {v.exit_code}"
                counts[key] = counts.get(key, 0) + 1
                writer.writerow([mutant.seed, mutant.scene, mutant.mutation, v.command, v.exit_code, f"{v.seconds:.3f}",
                                 v.violation, v.message])
                if v.violation:
                    violations.append((mutant, v))
            if (k + 1) % 500 == 0:
                print(f"{k + 1} mutants, {time.perf_counter() - start:.0f} s: {counts}", file=sys.stderr)
    print(f"{args.mutants} mutants in {time.perf_counter() - start:.0f} s: {counts}")
    for mutant, v in violations:
        print(f"VIOLATION {v.violation}: seed {mutant.seed} ({mutant.scene}: {mutant.mutation}) — {v.command}: {v.message}")
    sys.exit(1 if violations else 0)


if __name__ == "__main__":
    main()
