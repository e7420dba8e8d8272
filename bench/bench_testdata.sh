#!/usr/bin/env bash
# Test data (issue 36): a 1000-FRF, 4096-line UFF 58b file read, and a 60-order LSCF
# stabilisation diagram of 12 FRFs, each with a floor measured in the same run (the
# file's bytes read alone; one pass over the FRF values). usage: bench/bench_testdata.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
"$B/bench_testdata"
