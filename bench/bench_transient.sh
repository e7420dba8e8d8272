#!/usr/bin/env bash
# Time integration: steps/s, RHS evaluations per simulated second, one RHS vs one K x,
# on a torsional gear pair with backlash and on the rig refined to ~1000 DOFs with one
# backlash mesh. usage: bench/bench_transient.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed 's/elements_per_section: 8/elements_per_section: 50/' examples/rig2018.yaml > "$tmp/rig1000.yaml"
"$B/bench_transient" "$tmp/rig1000.yaml"
