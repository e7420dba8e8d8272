#!/usr/bin/env bash
# Time integration: steps/s, RHS evaluations per simulated second, one RHS vs one K x,
# on a torsional gear pair with backlash and on the rig refined to ~1000 DOFs with one
# backlash mesh; and the Ducati timing geartrain example (12 gears, 9 backlash meshes
# with TVMS, 16 cam valve trains) over two crank revolutions at 10000 rpm, and the
# `geardyn transient` command end to end on it. usage: bench/bench_transient.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed 's/elements_per_section: 8/elements_per_section: 50/' examples/rig2018.yaml > "$tmp/rig1000.yaml"
"$B/bench_transient" "$tmp/rig1000.yaml"
"$B/bench_transient_model" examples/ducati_timing_geartrain.yaml 2
start=$(date +%s.%N)
"$B/geardyn" transient examples/ducati_timing_geartrain.yaml --revolutions 2 --from 0 \
    --record ratio:gear_wheel/crank_pinion,ratio:cam_ve/crank_pinion --json --quiet > /dev/null
end=$(date +%s.%N)
echo "geardyn transient (Ducati, 2 crank revolutions) end to end: $(echo "$end - $start" | bc -l | cut -c1-6) s"
