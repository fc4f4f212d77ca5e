#!/usr/bin/env bash
# Builds crane-sim and the Catch2 tests with AddressSanitizer and UndefinedBehaviorSanitizer in
# build-sanitize/ (RelWithDebInfo, -fno-omit-frame-pointer) and runs the unit and scene tests and
# a sample of the input fuzz campaign (tests/fuzz/input_mutants.py) under them. Any report of
# the sanitizers fails the run. Takes ~15 min on 2 cores; not part of the test command.
#   scripts/sanitize.sh [number of fuzz mutants, default 300]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$root/build-sanitize"
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$build" --parallel "$(nproc)" --target crane-sim cranesim_tests
# TBB's and HDF5's own allocations are freed at exit by their runtimes, not by us.
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
"$build/tests/cranesim_tests" "~[benchmark]"
python3 "$root/tests/fuzz/input_mutants.py" --bin "$build/crane-sim" --mutants "${1:-300}" --time-limit 120 \
  --out "$build/input_fuzz.csv"
echo "sanitizers: no reports"
