#!/usr/bin/env bash
# Linear time response: unbalance switched on from rest, 0.1 s, on the 366-DOF rotor
# (bench/models/rig366_unbalance.yaml, 3000 rpm): CVODE at its default and gen-alpha,
# full and reduced, against CVODE at rtol 1e-10 (about 2 min of CPU for the reference).
# usage: bench_transient_linear.sh BUILD [T_END]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
"$B/bench_transient_linear" bench/models/rig366_unbalance.yaml 314.159265 "${2:-0.1}" gear48 brg_d1
