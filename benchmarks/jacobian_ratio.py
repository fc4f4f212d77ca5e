"""The crane's DAE Jacobian against its residual, for every lattice fidelity (the goal: ≤ 5 residuals).

Runs `bench_kernels` (Google Benchmark) once per round for the three fidelities of the thesis
crane at its drawn state — super truss (configs/crane.yaml), condensed (crane_condensed.yaml) and
full-member (crane_members.yaml) — and takes each fidelity's ratio of the Jacobian's median time
to the residual's, both timed in the same process (medians of --repetitions), so that the
host's drift between processes cancels. With --baseline a second `bench_kernels` (another
build) runs in the same rounds, the two alternating, for a side-by-side ratio.

Writes benchmarks/results/jacobian_ratio.csv (one row per round, binary and fidelity) and
jacobian_ratio.png (the rounds' ratios per fidelity with their medians and the goal), and prints
the medians and ranges.

With --instructions it counts instead of timing: callgrind (valgrind) over about two seconds of
each benchmark's calls, the instructions per call of the assembler's Jacobian and residual, one
point per binary and fidelity (noise-free; on one core, so that TBB runs every task on the
thread that callgrind counts in). Over many calls, so that what runs once per process (TBB's
first start of a thread, the scratch buffers) does not count: in a profile of a single call it
added a quarter of a million to a million instructions to the residual; over n calls it adds a
1/n share (the CSV gives n).
Writes jacobian_ratio_instructions.csv beside --out.

    python3 benchmarks/jacobian_ratio.py                                   # 6 rounds of build/benchmarks/bench_kernels
    python3 benchmarks/jacobian_ratio.py --baseline /tmp/old/bench_kernels --rounds 8
    python3 benchmarks/jacobian_ratio.py --instructions --baseline /tmp/old/bench_kernels   # ≈ 5 min
"""

import argparse
import csv
import json
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
GOAL = 5.0
# fidelity: (Jacobian benchmark, residual benchmark)
FIDELITIES = {
    "super truss": ("BM_CraneJacobian/condensed:0", "BM_CraneResidual/condensed:0"),
    "condensed": ("BM_CraneJacobian/condensed:1", "BM_CraneResidual/condensed:1"),
    "full-member": ("BM_Scaling/crane_members/jacobian", "BM_Scaling/crane_members/residual"),
}
FILTER = r"^(BM_Crane(Jacobian|Residual)/condensed:[01]|BM_Scaling/crane_members/(jacobian|residual))$"


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", default=str(ROOT / "build" / "benchmarks" / "bench_kernels"), help="bench_kernels binary")
    parser.add_argument("--baseline", help="a second bench_kernels (another build), run alternating with --bin")
    parser.add_argument("--rounds", type=int, default=6, help="processes per binary")
    parser.add_argument("--repetitions", type=int, default=3, help="Google Benchmark repetitions per process (median taken)")
    parser.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "jacobian_ratio.csv"))
    parser.add_argument("--instructions", action="store_true", help="count instructions per call with callgrind instead of timing")
    args = parser.parse_args()
    if args.repetitions < 2 or args.rounds < 1:
        parser.error("--repetitions must be ≥ 2 (Google Benchmark reports medians of repetitions only) and --rounds ≥ 1")
    return args


def medians(binary: str, repetitions: int) -> dict[str, float]:
    """Median real time (ms) of every benchmark of FILTER in one process of `binary`."""
    command = [binary, f"--benchmark_filter={FILTER}", f"--benchmark_repetitions={repetitions}",
               "--benchmark_report_aggregates_only=true", "--benchmark_format=json"]
    try:
        result = subprocess.run(command, capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as error:
        sys.exit(f"jacobian_ratio: {binary} failed: {error}")
    out = {}
    for b in json.loads(result.stdout)["benchmarks"]:
        if b.get("aggregate_name") == "median":
            out[b["run_name"]] = b["real_time"] * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    missing = [name for pair in FIDELITIES.values() for name in pair if name not in out]
    if missing:
        sys.exit(f"jacobian_ratio: {binary} lacks {', '.join(missing)}")
    return out


def instructions_per_call(binary: str, benchmark: str, function: str) -> tuple[float, int]:
    """Instructions per call of cranesim::Assembler::<function> (jacobian or residual), which
    `benchmark` times, counted by callgrind over the calls of a two-second run (valgrind's time),
    and the number of calls."""
    with tempfile.TemporaryDirectory() as tmp:
        profile = Path(tmp) / "callgrind.out"
        # One core: TBB then runs every task on the calling thread, the one the toggle counts in.
        command = ["taskset", "-c", "0", "valgrind", "--tool=callgrind", f"--toggle-collect=cranesim::Assembler::{function}(*",
                   f"--callgrind-out-file={profile}", binary, f"--benchmark_filter=^{re.escape(benchmark)}$",
                   "--benchmark_min_time=2"]
        try:
            subprocess.run(command, capture_output=True, text=True, check=True)
            report = subprocess.run(["callgrind_annotate", "--tree=calling", "--inclusive=yes", str(profile)],
                                    capture_output=True, text=True, check=True).stdout
        except (OSError, subprocess.CalledProcessError) as error:
            sys.exit(f"jacobian_ratio: callgrind of {benchmark} in {binary} failed: {error}")
    total = re.search(r"^\s*([\d,]+)\s+\(100\.0%\)\s+PROGRAM TOTALS", report, re.M)
    calls = re.search(rf">\s+\S*cranesim::Assembler::{function}\(.*\(([\d,]+)x\)", report)
    if not total or not calls:
        sys.exit(f"jacobian_ratio: no calls of Assembler::{function} in the profile of {benchmark}")
    n = int(calls.group(1).replace(",", ""))
    return int(total.group(1).replace(",", "")) / n, n


def count_instructions(binaries: dict[str, str], out: Path) -> None:
    """--instructions: per-call instructions of every fidelity's Jacobian and residual, CSV and print."""
    with out.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["binary", "fidelity", "jacobian_instructions", "jacobian_calls", "residual_instructions",
                         "residual_calls", "ratio"])
        for label, binary in binaries.items():
            for fidelity, (jacobian, residual) in FIDELITIES.items():
                j, j_calls = instructions_per_call(binary, jacobian, "jacobian")
                r, r_calls = instructions_per_call(binary, residual, "residual")
                writer.writerow([label, fidelity, f"{j:.0f}", j_calls, f"{r:.0f}", r_calls, f"{j / r:.4g}"])
                f.flush()
                print(f"{fidelity:12s} {label:8s} Jacobian {j / 1e6:8.3f} M ({j_calls} calls)  "
                      f"residual {r / 1e6:7.3f} M ({r_calls} calls)  ratio {j / r:6.2f}")


def main() -> None:
    args = parse_arguments()
    binaries = {"new": args.bin}
    if args.baseline:
        binaries = {"baseline": args.baseline, "new": args.bin}
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    if args.instructions:
        count_instructions(binaries, out.with_name(out.stem + "_instructions.csv"))
        return
    rows = []
    with out.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["round", "binary", "fidelity", "jacobian_ms", "residual_ms", "ratio"])
        for round_ in range(args.rounds):
            for label, binary in binaries.items():
                times = medians(binary, args.repetitions)
                for fidelity, (jacobian, residual) in FIDELITIES.items():
                    row = (round_, label, fidelity, times[jacobian], times[residual], times[jacobian] / times[residual])
                    writer.writerow([row[0], row[1], row[2], f"{row[3]:.5g}", f"{row[4]:.5g}", f"{row[5]:.4g}"])
                    rows.append(row)
            f.flush()
            print(f"round {round_ + 1}/{args.rounds} done", file=sys.stderr)

    fig, ax = plt.subplots(figsize=(7, 4))
    labels = list(binaries)
    for i, fidelity in enumerate(FIDELITIES):
        for j, label in enumerate(labels):
            ratios = [r[5] for r in rows if r[1] == label and r[2] == fidelity]
            x = i + (j - (len(labels) - 1) / 2) * 0.3
            ax.plot([x] * len(ratios), ratios, "o", color=f"C{j}", alpha=0.5, label=label if i == 0 else None)
            ax.plot([x - 0.12, x + 0.12], [statistics.median(ratios)] * 2, "-", color=f"C{j}", lw=2)
            print(f"{fidelity:12s} {label:8s} median {statistics.median(ratios):6.2f}  range {min(ratios):.2f}–{max(ratios):.2f}  "
                  f"Jacobian {statistics.median(r[3] for r in rows if r[1] == label and r[2] == fidelity):.3f} ms")
    ax.axhline(GOAL, color="k", ls="--", lw=1, label=f"goal ≤ {GOAL:g}")
    ax.set_xticks(range(len(FIDELITIES)), list(FIDELITIES))
    ax.set_ylabel("DAE Jacobian / residual (wall, same process)")
    ax.set_ylim(bottom=0)
    ax.legend()
    ax.set_title("Thesis crane at its drawn state, one point per process (bar: median)")
    fig.tight_layout()
    fig.savefig(out.with_suffix(".png"), dpi=120)


if __name__ == "__main__":
    main()
