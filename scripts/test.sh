#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, and runs every test
# (Catch2 unit and scene tests, the Python package, script and CLI tests, the benchmark smoke
# test).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh" --tests
"$root/scripts/build.sh"
"$root/scripts/install_python.sh"   # the tests import the package as a user does
cd "$root/build"
ctest --output-on-failure --parallel "$(nproc)" --timeout 900
