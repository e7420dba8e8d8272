#!/usr/bin/env bash
# Python overhead (issue 13): a modal solve from Python against the C call, on the
# Kumar model (8 DOFs, where the overhead weighs most) and the rig (170 DOFs).
# Needs `make python`. usage: bench/bench_python.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
if ! ls python/geardyn/_native*.so >/dev/null 2>&1; then
    echo "bench_python: no python/geardyn/_native*.so: run make python"; exit 0
fi
export OPENBLAS_NUM_THREADS=1
/usr/bin/python3 bench/bench_python.py "$B" examples/kumar2011_coupled.yaml 2000
/usr/bin/python3 bench/bench_python.py "$B" examples/rig2018.yaml 50
