#!/usr/bin/env bash
# Sweeps on the MMT 2018 rig refined to 60 elements per shaft (610 DOFs) with an
# unbalance on each gear: Campbell (100 speeds, 12 modes), FRF (1000 points),
# unbalance (1000 speeds), on one thread and on all cores. Then issue 23's Campbell case:
# the 366-DOF rotor (bench/models/rig366.yaml), 100 speeds 0..12000 rpm, 12 modes, one
# thread, with the mode continuation (the default) against Krylov-Schur at every speed
# (the floor of the old path, measured in the same run), the fallback count and the
# ratio to ROSS's 16.8 s (a constant from the issue, measured on its machine).
# usage: bench_sweeps.sh BUILD
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed 's/elements_per_section: 8/elements_per_section: 30/' examples/rig2018.yaml > "$tmp/rig60.yaml"
cat >> "$tmp/rig60.yaml" <<'YAML'
unbalances:
  - {name: u48, node: gear48, amount: 1e-5 kg*m}
  - {name: u32, node: gear32, amount: 5e-6 kg*m, phase: 90 deg}
YAML
"$B/bench_sweeps" "$tmp/rig60.yaml" 1 "$(nproc)"
start=$(date +%s.%N)
"$B/geardyn" campbell "$tmp/rig60.yaml" --speeds 0:12000rpm:100 --modes 12 --json > /dev/null
end=$(date +%s.%N)
echo "geardyn campbell CLI end to end (all cores): $(echo "$end - $start" | bc -l | cut -c1-6) s"
# best of 15: on a loaded machine best of 5 of the 0.17 s continuation ranged 2.1-2.9x
"$B/bench_campbell" bench/models/rig366.yaml 100 12000 12 15
