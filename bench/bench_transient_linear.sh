#!/usr/bin/env bash
# Linear time response: unbalance switched on from rest, 0.1 s, on the 366-DOF rotor
# (bench/models/rig366_unbalance.yaml, 3000 rpm), every method against CVODE at rtol
# 1e-10 (about 2 min of CPU for the reference): the default (auto: the linear
# time-invariant method) at rtol 1e-4 and 1e-2, CVODE at its default, gen-alpha, full and
# reduced. Ends with the default at rtol 1e-4 against ROSS's Newmark (1.7 s at error
# 1.6e-2 on record A: issue 23's figure, ROSS is not installed here) and against a floor
# measured in the same run (gen-alpha at one step per output sample), then the CLI end
# to end (process CPU time, set-up and file reading included).
# usage: bench_transient_linear.sh BUILD [T_END]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
"$B/bench_transient_linear" bench/models/rig366_unbalance.yaml 314.159265 "${2:-0.1}" gear48 brg_d1
for rec in gear48.x gear48.x,brg_d1.y; do
    best=
    for _ in 1 2 3; do
        t=$( { /usr/bin/time -f "%U %S" "$B/geardyn" transient bench/models/rig366_unbalance.yaml \
            --speed 3000rpm --duration "${2:-0.1}" --from 0 --output-interval 0.1ms --rtol 1e-4 \
            --record "$rec" --quiet > /dev/null; } 2>&1 | awk '{print $1 + $2}')
        best=$(echo "$t $best" | awk '{print ($2 == "" || $1 < $2) ? $1 : $2}')
    done
    echo "geardyn transient (default method) --rtol 1e-4 --record $rec, CLI end to end: $best s CPU (min of 3)"
done
