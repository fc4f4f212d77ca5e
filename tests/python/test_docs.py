"""The documentation as a product: README.md is a short front door, README and docs/ carry no
dates, issue numbers or commit hashes, the repository cites no document outside itself, every
link resolves, and every command shown in a ```console block runs as written.

Conventions (docs/index.md says them for writers):
- ```console blocks are run from the repository root, each line starting with `$ ` a command (a
  trailing backslash continues it); the lines after it are sample output. A command whose sample
  output has a line starting with `error:` must exit 2 (bad input), every other command 0.
- ```sh blocks show commands that are not run here; each command line says why, with a comment
  containing "not run here". The README's two commands are the exception: `scripts/test.sh` is
  what CI runs, and `scripts/run_main.sh` is run by test_main_command_runs.

Environment: CRANESIM_SOURCE_DIR (default: this checkout).
"""

import os
import re
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("CRANESIM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
README = SOURCE_DIR / "README.md"
DOC_FILES = sorted([README, SOURCE_DIR / "CHANGELOG.md", SOURCE_DIR / "benchmarks" / "README.md"]
                   + list((SOURCE_DIR / "docs").glob("*.md")))
RUN_DOCS = [README] + sorted((SOURCE_DIR / "docs").glob("*.md"))
README_COMMANDS = {"./scripts/run_main.sh", "./scripts/test.sh"}

ISO_DATE = re.compile(r"\b(19|20)\d\d-(0[1-9]|1[0-2])-([0-2]\d|3[01])\b")
MONTH_DATE = re.compile(r"\b(January|February|March|April|May|June|July|August|September|October|"
                        r"November|December) (\d{1,2}, )?(19|20)\d\d\b")
ISSUE_REFERENCE = re.compile(r"\bissues? #?\d+|(^|\s)#\d+\b", re.IGNORECASE)
COMMIT_HASH = re.compile(r"(?<![\w.])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}(?![\w.-])")  # not in 4.707151e-07
OUTSIDE_DOCUMENT = re.compile("DESIGN" + r"\s*(§|section|\.md)", re.IGNORECASE)
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
DOCS_MENTION = re.compile(r"\bdocs/([\w.-]+\.md)(#[\w-]+)?")


def tracked_files():
    listing = subprocess.run(["git", "ls-files", "-z"], cwd=SOURCE_DIR, capture_output=True, check=True)
    for name in listing.stdout.decode().split("\0"):
        path = SOURCE_DIR / name
        if name and path.is_file() and path.suffix not in {".png", ".gif", ".h5"}:
            yield path


def code_blocks(path: Path):
    """(language, first line number, lines) of every fenced block."""
    language, start, lines = None, 0, []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        fence = re.match(r"^\s*```(\w*)", line)
        if fence and language is None:
            language, start, lines = fence.group(1), number + 1, []
        elif fence:
            yield language, start, lines
            language = None
        elif language is not None:
            lines.append(line)


def console_commands(path: Path):
    """(line number, command, expected exit code) of every ```console command."""
    for language, start, lines in code_blocks(path):
        if language != "console":
            continue
        index = 0
        while index < len(lines):
            if not lines[index].startswith("$ "):
                index += 1
                continue
            number, command = start + index, lines[index][2:]
            while command.endswith("\\") and index + 1 < len(lines):
                index += 1
                command = command[:-1] + " " + lines[index].strip()
            index += 1
            output = []
            while index < len(lines) and not lines[index].startswith("$ "):
                output.append(lines[index])
                index += 1
            expected = 2 if any(line.startswith("error:") for line in output) else 0
            yield number, command, expected


def heading_slugs(path: Path) -> set:
    """GitHub's anchors for a markdown file's headings."""
    slugs, counts, in_block = set(), {}, False
    for line in path.read_text().splitlines():
        if line.lstrip().startswith("```"):
            in_block = not in_block
        heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if heading and not in_block:
            text = re.sub(r"[`*]|\[([^\]]*)\]\([^)]*\)", r"\1", heading.group(1)).lower()
            slug = re.sub(r"[^\w\- ]", "", text).replace(" ", "-")
            slugs.add(slug if slug not in counts else f"{slug}-{counts[slug]}")
            counts[slug] = counts.get(slug, 0) + 1
    return slugs


def test_readme_is_a_front_door():
    lines = README.read_text().splitlines()
    assert len(lines) <= 300, f"README.md has {len(lines)} lines; the front door keeps to 300"


@pytest.mark.parametrize("path", DOC_FILES, ids=lambda p: str(p.relative_to(SOURCE_DIR)))
def test_docs_carry_no_dates_issue_numbers_or_commit_hashes(path):
    found = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        for kind, pattern in (("date", ISO_DATE), ("date", MONTH_DATE), ("issue number", ISSUE_REFERENCE),
                              ("commit hash", COMMIT_HASH)):
            match = pattern.search(line)
            if match:
                found.append(f"{path.name}:{number}: {kind} '{match.group(0).strip()}'")
    assert not found, "history belongs in git and benchmarks/results/, not in the docs:\n" + "\n".join(found)


def test_repository_cites_no_document_outside_itself():
    found = []
    for path in tracked_files():
        if path == Path(__file__).resolve():
            continue
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            if OUTSIDE_DOCUMENT.search(line) or re.search(r"\bissues? #?\d+", line, re.IGNORECASE):
                found.append(f"{path.relative_to(SOURCE_DIR)}:{number}: {line.strip()[:100]}")
    assert not found, "cite docs/ or state the requirement instead:\n" + "\n".join(found)


@pytest.mark.parametrize("path", DOC_FILES, ids=lambda p: str(p.relative_to(SOURCE_DIR)))
def test_links_resolve(path):
    broken = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        for target in LINK.findall(line):
            if re.match(r"[a-z]+:", target):
                continue
            file_part, _, anchor = target.partition("#")
            linked = (path.parent / file_part).resolve() if file_part else path
            if not linked.exists():
                broken.append(f"{path.name}:{number}: {target} (no such file)")
            elif anchor and linked.suffix == ".md" and anchor not in heading_slugs(linked):
                broken.append(f"{path.name}:{number}: {target} (no heading '#{anchor}' in {linked.name})")
    assert not broken, "\n".join(broken)


def test_code_mentions_of_docs_resolve():
    broken = []
    for path in tracked_files():
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            for name, anchor in DOCS_MENTION.findall(line):
                target = SOURCE_DIR / "docs" / name
                if not target.exists():
                    broken.append(f"{path.relative_to(SOURCE_DIR)}:{number}: docs/{name} does not exist")
                elif anchor and anchor[1:] not in heading_slugs(target):
                    broken.append(f"{path.relative_to(SOURCE_DIR)}:{number}: no heading '{anchor}' in docs/{name}")
    assert not broken, "\n".join(broken)


@pytest.mark.parametrize("path", RUN_DOCS, ids=lambda p: str(p.relative_to(SOURCE_DIR)))
def test_commands_not_run_say_why(path):
    silent = []
    for language, start, lines in code_blocks(path):
        if language not in {"sh", "bash", "shell"}:
            continue
        for offset, line in enumerate(lines):
            command = line.strip()
            if command and not command.startswith("#") and "not run here" not in command \
                    and not (path == README and command.split("#")[0].strip() in README_COMMANDS):
                silent.append(f"{path.name}:{start + offset}: {command}")
    assert not silent, ("a command in a ```sh block is not run by this test: say why ('# not run here: …') "
                        "or show it in a ```console block:\n" + "\n".join(silent))


@pytest.mark.parametrize("path", RUN_DOCS, ids=lambda p: str(p.relative_to(SOURCE_DIR)))
def test_console_commands_run_as_written(path):
    commands = list(console_commands(path))
    if not commands:
        pytest.skip("no console commands")
    (SOURCE_DIR / "out" / "docs").mkdir(parents=True, exist_ok=True)
    for number, command, expected in commands:
        try:
            run = subprocess.run(["bash", "-c", command], cwd=SOURCE_DIR, capture_output=True, text=True,
                                 timeout=300)
        except subprocess.TimeoutExpired:
            pytest.fail(f"{path.name}:{number}: '{command}' did not finish in 300 s")
        assert run.returncode == expected, (
            f"{path.name}:{number}: '{command}' exited {run.returncode}, the docs imply {expected}\n"
            f"stdout: {run.stdout[-2000:]}\nstderr: {run.stderr[-2000:]}")


CATCH2_COMMAND = re.compile(r'`build/tests/cranesim_tests "((?:[^"\\]|\\.)*)"`')
PYTEST_COMMAND = re.compile(r"`python3 -m pytest (tests/python/[\w/]+\.py)(?: -k (\w+))?`")


def test_reproduce_commands_name_tests_that_exist():
    """The tables' `reproduce` commands are not run here (the suite runs those tests anyway): each must
    select a test that exists, so that a renamed test cannot leave a dead command in the docs."""
    binary = Path(os.environ.get("CRANESIM_TESTS_BIN", SOURCE_DIR / "build" / "tests" / "cranesim_tests"))
    listing = subprocess.run([str(binary), "--list-test-names-only"], capture_output=True, text=True)  # exit: the count
    names = {line.strip() for line in listing.stdout.splitlines() if line.strip()}
    assert len(names) > 100, listing.stderr
    dead = []
    for path in RUN_DOCS:
        text = path.read_text()
        for pattern in CATCH2_COMMAND.findall(text):
            name = pattern.replace("\\,", ",")
            if not any(re.fullmatch(re.escape(name).replace(r"\*", ".*"), candidate) for candidate in names):
                dead.append(f'{path.name}: no Catch2 test "{name}"')
        for file, function in PYTEST_COMMAND.findall(text):
            test_file = SOURCE_DIR / file
            if not test_file.exists():
                dead.append(f"{path.name}: no {file}")
            elif function and not re.search(rf"^def {function}\b", test_file.read_text(), re.MULTILINE):
                dead.append(f"{path.name}: no test {function} in {file}")
    assert not dead, "\n".join(dead)
