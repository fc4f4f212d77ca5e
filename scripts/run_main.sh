#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, runs the main scene and
# leaves results, plots and an animation in out/main/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scene="${1:-$root/configs/jib_pendulum.yaml}"
out="$root/out/main"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
mkdir -p "$out"
name="$(basename "$scene" .yaml)"
results="$out/$name.h5"
"$root/build/crane-sim" run "$scene" -o "$results"
python3 "$root/scripts/report.py" "$results"
python3 "$root/scripts/plot_timeseries.py" "$results" \
  joints/link1.bottom/position[0] joints/link1.bottom/position[1] joints/link1.bottom/position[2] \
  --subplots --title "$name: load position" -o "$out/${name}_load_position.png"
python3 "$root/scripts/plot_timeseries.py" "$results" energy/kinetic energy/potential energy/drive_work energy/balance \
  --title "$name: energies" -o "$out/${name}_energy.png"
python3 "$root/scripts/plot_snapshot.py" "$results" -o "$out/${name}_snapshot.png"
python3 "$root/scripts/animate.py" "$results" --every 5 -o "$out/${name}_animation.gif"
echo "results, plots and animation in $out"
