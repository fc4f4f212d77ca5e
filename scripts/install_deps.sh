#!/usr/bin/env bash
# Installs what cranesim needs on Debian (bookworm) when it is missing: the C++ toolchain and
# libraries from Debian's packages, the Python plotting stack and the Python package's build tools from PyPI. Safe to run repeatedly.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

debian_packages=(
  g++ cmake ninja-build pkg-config
  libeigen3-dev libsundials-dev libsuitesparse-dev coinor-libipopt-dev libhdf5-dev
  libyaml-cpp-dev catch2 libcli11-dev libfmt-dev libspdlog-dev libtbb-dev libbenchmark-dev
  python3 python3-pip
  libjs-three            # the replay page's three.js (scripts/view.py)
  openmpi-bin libopenmpi-dev   # studies and static maps across MPI ranks (optional: the build works without)
)
# The tests also render the replay page in a browser: `install_deps.sh --tests` (scripts/test.sh).
if [ "${1:-}" = "--tests" ]; then debian_packages+=(chromium); fi
missing=()
for p in "${debian_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing Debian packages: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}"
fi

if ! python3 -c "import numpy, h5py, matplotlib, pytest, yaml, nanobind, scikit_build_core, gymnasium" 2>/dev/null; then
  echo "installing Python packages from scripts/requirements.txt"
  python3 -m pip install --quiet -r "$here/requirements.txt" ||
    python3 -m pip install --quiet --break-system-packages -r "$here/requirements.txt"
fi
