"""The compile CPU time of what the README's main command builds, with and without the unity build.

For each configuration (CRANESIM_UNITY_BUILD ON and OFF) the project is configured in a scratch
build directory without a compiler cache and the targets are built with one job; this script is
the compiler launcher and records each compilation's user and system CPU time from the
compiler's own resource usage, so that other load on the machine changes it little. Writes one
row per translation unit and configuration, and prints the totals by part of the build.

    python3 benchmarks/build_cpu.py                       # crane-sim and the Python extension
    python3 benchmarks/build_cpu.py --targets crane-sim   # one target
    python3 benchmarks/build_cpu.py --configurations on   # the unity build only
"""

import argparse
import csv
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "build_cpu.csv"
COLUMNS = ["configuration", "part", "unit", "sources", "user_s", "sys_s", "machine"]


def launch(log: Path, command: list[str]) -> int:
    """Runs one compiler command and appends its CPU time to `log` (launcher mode)."""
    process = subprocess.Popen(command)
    _, status, usage = os.wait4(process.pid, 0)
    output = command[command.index("-o") + 1] if "-o" in command else ""
    with log.open("a", encoding="utf-8") as f:
        f.write(json.dumps({"object": output, "user": usage.ru_utime, "sys": usage.ru_stime}) + "\n")
    return os.waitstatus_to_exitcode(status)


def unity_sources(build: Path, obj: str) -> list[str]:
    """The source files a unity translation unit includes, or [] for an ordinary one."""
    if "/Unity/" not in obj:
        return []
    unit = build / obj.removesuffix(".o")
    return [line.split('"')[1] for line in unit.read_text().splitlines() if line.startswith("#include")]


def part_of(obj: str) -> str:
    """Which part of the build a translation unit belongs to, as the docs' table groups them."""
    target = obj.split("CMakeFiles/")[1].split(".dir/")[0] if "CMakeFiles/" in obj else "other"
    if target == "cranesim":
        return "element kernels (src/elements/)" if "/src/elements/" in obj else "engine library, other folders"
    if target in ("cranesim_study", "cranesim_farm"):
        return "studies and the task farm"
    if target in ("_core", "nanobind-static", "crane-sim"):
        return "Python extension, nanobind and the crane-sim app"
    return target


def measure(configuration: str, targets: list[str], jobs: int) -> list[dict]:
    """Configures and builds `targets` from scratch; one row per translation unit."""
    with tempfile.TemporaryDirectory(prefix="cranesim-build-cpu-") as scratch:
        build, log = Path(scratch) / "build", Path(scratch) / "cpu.jsonl"
        launcher = f"{sys.executable};{Path(__file__).resolve()};--record;{log};--"
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                        f"-DCRANESIM_UNITY_BUILD={configuration.upper()}", f"-DCMAKE_CXX_COMPILER_LAUNCHER={launcher}",
                        f"-DPython_EXECUTABLE={sys.executable}"], check=True, stdout=subprocess.DEVNULL)
        subprocess.run(["cmake", "--build", str(build), "--parallel", str(jobs), "--target", *targets], check=True,
                       stdout=subprocess.DEVNULL)
        rows = []
        for line in log.read_text().splitlines():
            record = json.loads(line)
            obj = record["object"]
            sources = unity_sources(build, obj)
            unit = obj.split(".dir/")[-1].removesuffix(".o")
            rows.append({"configuration": f"unity {configuration}", "part": part_of(obj), "unit": unit,
                         "sources": len(sources) or 1, "user_s": f"{record['user']:.2f}", "sys_s": f"{record['sys']:.2f}",
                         "machine": f"{os.cpu_count()} cores, {platform.processor() or platform.machine()}"})
        return rows


def main() -> int:
    if len(sys.argv) > 3 and sys.argv[1] == "--record":
        return launch(Path(sys.argv[2]), sys.argv[4:])
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--targets", nargs="+", default=["crane-sim", "_core"], help="what to build (the main command's)")
    parser.add_argument("--configurations", nargs="+", choices=["on", "off"], default=["on", "off"])
    parser.add_argument("--jobs", type=int, default=1, help="parallel compilations (CPU times do not depend on it)")
    parser.add_argument("--out", type=Path, default=RESULTS)
    args = parser.parse_args()
    if not shutil.which("ninja"):
        print("build_cpu: needs ninja (scripts/install_deps.sh installs it)", file=sys.stderr)
        return 2
    rows = [row for configuration in args.configurations for row in measure(configuration, args.targets, args.jobs)]
    partial = args.out.with_suffix(".csv.partial")
    with partial.open("w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    partial.replace(args.out)
    totals = defaultdict(float)
    for row in rows:
        totals[(row["configuration"], row["part"])] += float(row["user_s"]) + float(row["sys_s"])
    for (configuration, part), cpu in sorted(totals.items()):
        print(f"{configuration:9s} {part:50s} {cpu:7.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
