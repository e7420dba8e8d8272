#!/usr/bin/env bash
# Bifurcation sweep by time integration (geardyn transient --sweep-speeds): CPU seconds
# per speed on the Chen SFD gear pair (300 revolutions of settling + 64 Poincare
# periods per speed, e_u/C = 1/2), and the monodromy matrix against one plain run.
# usage: bench/bench_poincare.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
"$B/bench_monodromy" examples/chen1998_gear_pair.yaml
"$B/geardyn" transient examples/chen1998_gear_pair.yaml --sweep-speeds 5500:5650:16 \
    --poincare shaft_a --settle 300rev --points 64 --unbalance-scale 3 --record gear_a.y \
    --json --quiet |
    python3 -c 'import json,sys; o=json.load(sys.stdin); s=o["speeds"]; print("sweep: %d speeds, %.3g s CPU per speed (%.3g s total)" % (len(s), o["cpu_seconds"]/len(s), o["cpu_seconds"]))'
