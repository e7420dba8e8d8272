#!/usr/bin/env bash
# Harmonic balance (geardyn periodic): CPU per continuation step on the Chen SFD gear pair
# with H = 15 (issue 10 goal: < 5 ms), and on the 378-DOF two-stage helical system of
# seed 002 with both meshes' TVMS (H = 36: mesh 1 is harmonic 36 of the common period),
# whose Figs. 11-13 set is 10 curves x 300 speeds. usage: bench_periodic.sh BUILD
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
echo "-- Chen SFD pair, 400..1500 rad/s, 111 speeds, H = 15"
"$B/bench_periodic" examples/chen1998_gear_pair.yaml 400 1500 111 15 0
"$B/bench_periodic" examples/chen1998_gear_pair.yaml 400 1500 111 15 1
echo "-- seed 002 helical system (378 DOFs), 2990..3010 rpm, 3 speeds, H = 36, no Floquet"
"$B/bench_periodic" examples/helical_two_stage.yaml 313.11 315.21 3 36 0
