#!/usr/bin/env bash
# Configures and builds cranesim (Release) in build/: the given targets (e.g. crane-sim), or all
# of them (apps, tests, benchmarks) when none is given.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# The Python interpreter `pip install .` builds the package's extension for, so that both
# configure build/ alike and neither rebuilds the other's targets.
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE="$(python3 -c 'import sys; print(sys.executable)')" >/dev/null
if (($#)); then
  cmake --build "$root/build" --parallel "$(nproc)" --target "$@"
else
  cmake --build "$root/build" --parallel "$(nproc)"
fi
