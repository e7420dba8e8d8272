#!/usr/bin/env bash
# Per-period statistics and the Poincare verdict (geardyn transient --periods): CPU
# seconds of the run with --periods against a plain run of the same length beside it
# (the floor: integration only), so the ratio shows what the statistics and the verdict
# add; on the Chen SFD torus (5650 rad/s, e_u/C = 1/2) and, with an argument "ducati",
# on the Ducati train at 10000 rpm (the [Benini2004] worked example: about 2 minutes each).
# usage: bench/bench_periods.sh BUILD_DIR [ducati]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
cpu() { python3 -c 'import json,sys; o=json.load(sys.stdin); print(o["cpu_seconds"], o.get("periods", {}).get("verdict", {}).get("class", "-"))'; }
one() { # name model speed settle_rev periods period_rev extra...
    local name=$1 model=$2 speed=$3 settle=$4 n=$5 prev=$6
    shift 6
    local revs
    revs=$(python3 -c "print($settle + $n * $prev)")
    read -r c1 v < <("$B/geardyn" transient "$model" --speed "$speed" --periods "$n" \
        --settle "${settle}rev" --json --quiet "$@" | cpu)
    read -r c0 _ < <("$B/geardyn" transient "$model" --speed "$speed" --revolutions "$revs" \
        --from "$(python3 -c "import math; print(2 * math.pi * $settle / float('$speed'.replace('rpm','')) / (math.pi / 30 if 'rpm' in '$speed' else 1))")" \
        --json --quiet "$@" | cpu)
    python3 -c "print('%-8s %s periods: %.3g s CPU with --periods (%s), %.3g s plain, ratio %.3f' % ('$name', $n, $c1, '$v', $c0, $c1 / $c0))"
}
one chen examples/chen1998_gear_pair.yaml 5650 200 100 1 --unbalance-scale 3 --record gear_a.y,gear_a.x
if [ "${2:-}" = ducati ]; then
    one ducati examples/ducati_timing_geartrain.yaml 10000rpm 200 100 2
fi
