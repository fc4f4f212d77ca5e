#!/usr/bin/env bash
# Builds and installs the Python package cranesim (docs/python.md) for python3, in build/ with the
# rest of the project: the first time this compiles the engine's library, later only what changed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
pip_install=(python3 -m pip install --quiet --no-build-isolation --no-deps "$root")
"${pip_install[@]}" 2>/dev/null || "${pip_install[@]}" --break-system-packages
python3 -c 'import cranesim; print(f"cranesim {cranesim.__version__} installed for python3")'
