"""Every C++ test case runs under ctest. catch_discover_tests registers each Catch test case by its
name, and CMake splits a name at ';' into two tests that each select no test case: both report
"No tests ran" and pass, so a test case with ';' in its name would never run in CI."""

import re
from pathlib import Path

SOURCE_DIR = Path(__file__).resolve().parents[2]
TEST_CASE = re.compile(r'TEST_CASE\(\s*"((?:[^"\\]|\\.)*)"')


def test_no_test_case_name_holds_a_semicolon():
    names = [(path.relative_to(SOURCE_DIR), name) for path in sorted((SOURCE_DIR / "tests").rglob("*.cpp"))
             for name in TEST_CASE.findall(path.read_text(encoding="utf-8"))]
    assert len(names) > 200  # the suite's test cases were found
    split = [f"{path}: {name}" for path, name in names if ";" in name]
    assert not split, "ctest would split these names at ';' and run nothing:\n" + "\n".join(split)
