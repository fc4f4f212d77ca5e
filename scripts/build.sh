#!/usr/bin/env bash
# Configures and builds cranesim (Release) in build/: the given targets (e.g. crane-sim), or all
# of them (apps, tests, benchmarks) when none is given.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
if (($#)); then
  cmake --build "$root/build" --parallel "$(nproc)" --target "$@"
else
  cmake --build "$root/build" --parallel "$(nproc)"
fi
