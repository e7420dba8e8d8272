#!/usr/bin/env bash
# Harmonic balance (geardyn periodic): CPU per continuation step on the Chen SFD gear pair
# with H = 15 (issue 10 goal: < 5 ms); on the 378-DOF two-stage helical system of [JMSTHelical]
# with both meshes' TVMS, the whole sparse LU against the low-rank condensation (H = 36,
# the ratio), one curve of 30 speeds and 4 speeds by arclength; and the Figs. 11-13 set
# itself, 10 curves x 300 speeds at H = 108 (goal: < 60 s CPU on one core), one curve at
# a time. Each bench_periodic line prints its floor (the local forces at the AFT samples)
# and the step / floor ratio. Shooting against harmonic balance per point on the Chen
# pair (the ratio of the two, measured in the same run) and auto's choice.
# usage: bench_periodic.sh BUILD [--no-set]   (--no-set: skip the 1-minute set)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
SET=${2:-}
H2=examples/helical_two_stage.yaml
echo "-- Chen SFD pair, 400..1500 rad/s, 111 speeds, H = 15, without and with Floquet"
"$B/bench_periodic" examples/chen1998_gear_pair.yaml 400 1500 111 15 0
"$B/bench_periodic" examples/chen1998_gear_pair.yaml 400 1500 111 15 1
echo "-- shooting against harmonic balance, CPU per point (both measured here, one after the"
echo "   other): Chen SFD pair 400..1500 rad/s, 12 speeds, 12 states (HB H = 15); a shooting"
echo "   Newton step integrates n (n + 1) unknowns: its cost grows about as n^2 (n states)"
for m in hb shooting; do
    err=$(mktemp) # the CPU time is on stderr ("N points, T s CPU"), not in the JSON
    OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic examples/chen1998_gear_pair.yaml \
        --speeds 400:1500:12 --harmonics 15 --sequential --method "$m" --record gear_a.x \
        --json --quiet 2>"$err" | python3 -c "import json,re,sys; d=json.load(sys.stdin); \
t=float(re.search(r'([0-9.eE+-]+) s CPU', open(sys.argv[1]).read()).group(1)); \
print('   %-16s %.4f s per point (%d points)' % (d['method'], t / len(d['points']), \
len(d['points'])))" "$err"
    rm -f "$err"
done
echo "   auto: $(OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic examples/chen1998_gear_pair.yaml \
    --speeds 1000:1000:1 --method auto --quiet | head -1)"
echo "-- [JMSTHelical] helical system (378 DOFs), 2990..3010 rpm, 3 speeds, H = 36, no Floquet:"
echo "   whole sparse LU (1) against the low-rank condensation (2)"
"$B/bench_periodic" "$H2" 313.11 315.21 3 36 0 1
"$B/bench_periodic" "$H2" 313.11 315.21 3 36 0 2
echo "-- [JMSTHelical], one curve: 1000..10000 rpm, 30 speeds, gear 1 y and both mesh forces, sequential"
OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic "$H2" --speeds 1000rpm:10000rpm:30 --harmonics 36 \
    --no-stability --no-estimate --sequential --record gear1.y --record mesh:pair1:force \
    --record mesh:pair2:force | tail -1
echo "   (H = 36 holds only the fundamental of mesh 1: the set below needs H = 108)"
echo "-- the same curve at H = 591: condensed harmonic balance (the default) against the full"
echo "   solve (--method full-hb), 40 speeds, CPU and ratio (bench_condensed_hb.sh)"
bench/bench_condensed_hb.sh "$B" 591 1000rpm:8000rpm:40
echo "-- the same model by arclength, 1000..2000 rpm, 4 speeds"
OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic "$H2" --speeds 1000rpm:2000rpm:4 --harmonics 36 \
    --no-stability --no-estimate --record gear1.y | tail -1
echo "-- [JMSTHelical] at 2500 rpm, the default --harmonics auto (H doubled from 36 until the"
echo "   records agree with 2 H + 1 to 1 %) and the fixed H = 108 with its estimate"
OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic "$H2" --speeds 2500rpm:2500rpm:1 --no-stability \
    --record mesh:pair2:force --quiet | sed -n '2p;$p'
OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic "$H2" --speeds 2500rpm:2500rpm:1 --no-stability \
    --harmonics 108 --record mesh:pair2:force --quiet 2>/dev/null | sed -n '2p;$p'
if [ "$SET" != "--no-set" ]; then
    echo "-- [JMSTHelical], the Figs. 11-13 set: 10 curves x 300 speeds, H = 108, one curve at a time"
    OPENBLAS_NUM_THREADS=1 JOBS=1 ESTIMATE=0 GEARDYN="$B/geardyn" examples/seed002/figs11_13.sh \
        "$B/bench-seed002" | tail -1
    echo "   (goal: < 60 s CPU on one core; 557 s before the condensation's rework)"
fi
