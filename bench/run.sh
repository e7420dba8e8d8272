#!/usr/bin/env bash
# Prints timings and ratios of geardyn's main computations. Asserts nothing.
# usage: bench/run.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "== modal: rig2018 refined to ~1000 DOFs (50 elements per half shaft), 3000 rpm"
sed 's/elements_per_section: 8/elements_per_section: 50/' examples/rig2018.yaml > "$tmp/rig1000.yaml"
"$B/bench_modal" "$tmp/rig1000.yaml" 314.159 3
start=$(date +%s.%N)
"$B/geardyn" modal "$tmp/rig1000.yaml" --speed 3000rpm --json > /dev/null
end=$(date +%s.%N)
echo "geardyn modal CLI end to end: $(echo "$end - $start" | bc -l | cut -c1-6) s"
echo
echo "== modal: the paper examples"
for f in kumar2011_coupled chen1998_gear_pair rig2018; do
    "$B/bench_modal" "examples/$f.yaml" 0 5 | grep -E "model|modal \(|ratio"
done
for extra in bench/bench_*.sh; do
    [ -e "$extra" ] || continue
    echo
    echo "== $extra"
    bash "$extra" "$B"
done
