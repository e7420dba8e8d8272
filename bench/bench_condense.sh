#!/usr/bin/env bash
# The condensation onto the meshes' coordinates (docs/condense.md) against the direct
# sparse solve: build cost, cost per frequency, ratios, accuracy. Asserts nothing.
# usage: bench/bench_condense.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
export OPENBLAS_NUM_THREADS=1
"$B/bench_condense" examples/helical_two_stage.yaml 200 0
"$B/bench_condense" examples/helical_two_stage.yaml 200 30 dense
"$B/bench_condense" examples/helical_two_stage.yaml 200 30 sparse
"$B/bench_condense" bench/models/gearbox10k.yaml 50 30 sparse
"$B/bench_condense" bench/models/gearbox10k.yaml 50 100 sparse
