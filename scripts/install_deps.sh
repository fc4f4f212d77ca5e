#!/usr/bin/env bash
# Installs what cranesim needs on Debian (bookworm) when it is missing: the C++ toolchain and
# libraries from Debian's packages, the Python plotting stack and the Python package's build tools from PyPI. Safe to run repeatedly.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

debian_packages=(
  g++ cmake ninja-build pkg-config
  libeigen3-dev libsundials-dev libsuitesparse-dev coinor-libipopt-dev libhdf5-dev
  libyaml-cpp-dev catch2 libcli11-dev libfmt-dev libtbb-dev libbenchmark-dev
  python3 python3-pip python3-dev   # python3-dev: the headers the Python package's extension builds on
  libjs-three            # the replay page's three.js (scripts/view.py)
  openmpi-bin libopenmpi-dev   # studies and static maps across MPI ranks (optional: the build works without)
)
# The tests also render the replay page in a browser: `install_deps.sh --tests` (scripts/test.sh).
# Chromium keeps its recommended packages (fonts, GL) for the rendering.
browser_packages=()
if [ "${1:-}" = "--tests" ]; then browser_packages+=(chromium); fi
sudo_cmd=""
[ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
updated=0
# apt-get install of those of the given packages that are missing; the further arguments
# before `--` go to apt-get.
install_missing() {
  local options=() missing=() p
  while [ "$1" != "--" ]; do options+=("$1"); shift; done
  shift
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "installing Debian packages: ${missing[*]}"
  ((updated)) || { $sudo_cmd apt-get update -qq; updated=1; }
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${options[@]}" "${missing[@]}"
}
# Without the recommended packages (debuggers, documentation, graphics libraries, PETSc's
# examples): what the list needs and nothing else.
install_missing --no-install-recommends -- "${debian_packages[@]}"
if ((${#browser_packages[@]})); then install_missing -- "${browser_packages[@]}"; fi

if ! python3 -c "import numpy, h5py, matplotlib, pytest, yaml, nanobind, scikit_build_core, gymnasium" 2>/dev/null; then
  echo "installing Python packages from scripts/requirements.txt"
  python3 -m pip install --quiet -r "$here/requirements.txt" ||
    python3 -m pip install --quiet --break-system-packages -r "$here/requirements.txt"
fi
