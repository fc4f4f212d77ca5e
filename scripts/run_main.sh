#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, runs the thesis crane's combined
# motion (configs/crane_combined.yaml, thesis 8.3.2) from its equilibrium and leaves the results,
# the load's position and velocity plot, a snapshot, an animation and a 3-D replay page of the
# whole crane in out/main/, and installs the Python package cranesim.
# Another scene: scripts/run_main.sh configs/<scene>.yaml
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scene="${1:-$root/configs/crane_combined.yaml}"
out="$root/out/main"
mkdir -p "$out"
times="$out/main_command_times.csv"   # each phase's wall time, as docs/performance.md quotes them
echo "phase,wall_s" > "$times.partial"
phase_start=$SECONDS
end_phase() { echo "$1,$((SECONDS - phase_start))" >> "$times.partial"; phase_start=$SECONDS; }
"$root/scripts/install_deps.sh"
end_phase install
"$root/scripts/build.sh" crane-sim   # only what the main job runs; the tests build everything
"$root/scripts/install_python.sh"    # the Python package cranesim, on the same build
end_phase build
name="$(basename "$scene" .yaml)"
results="$out/$name.h5"
"$root/build/crane-sim" run "$scene" -o "$results"
end_phase run
python3 "$root/scripts/report.py" "$results"
if python3 -c 'import sys, h5py; sys.exit("bodies/load" not in h5py.File(sys.argv[1], "r"))' "$results"; then
  python3 "$root/scripts/plot_load.py" "$results" -o "$out/${name}_load.png"
fi
if python3 -c 'import sys, h5py; sys.exit("constraint_loads/slewing" not in h5py.File(sys.argv[1], "r"))' "$results"; then
  python3 "$root/scripts/plot_timeseries.py" "$results" constraint_loads/slewing/force[2] constraint_loads/hook/force[norm] \
    --title "$name: slewing ring's axial force, hook load (N)" -o "$out/${name}_loads.png"
fi
python3 "$root/scripts/plot_timeseries.py" "$results" energy/kinetic energy/potential energy/drive_work energy/winch_work \
  --title "$name: energies" -o "$out/${name}_energy.png"
python3 "$root/scripts/plot_snapshot.py" "$results" -o "$out/${name}_snapshot.png"
python3 "$root/scripts/animate.py" "$results" --every 10 -o "$out/${name}_animation.gif"
python3 "$root/scripts/view.py" "$results" -o "$out/$name.html"
end_phase "plots and replay page"
mv "$times.partial" "$times"
echo "wall time by phase (s): $(tail -n +2 "$times" | paste -sd ' ' | sed 's/,/ /g')"
echo "results, plots, animation and 3-D replay page ($name.html: open it in a browser) in $out"
