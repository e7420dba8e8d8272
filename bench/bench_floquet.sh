#!/usr/bin/env bash
# Floquet multipliers of harmonic balance points: the dense Magnus monodromy (every
# multiplier, 30 (2 nf)^3 flops per step) against Krylov-Schur on monodromy-vector
# products (the 8 largest; each product sums a Taylor series per step, about 8 |Omega|
# Omega actions, so its cost grows with the period times the largest natural frequency,
# not with nf^3), and the reduced basis (--floquet reduced: the modes below 4x the highest
# excitation frequency plus the laws' residual flexibility, every multiplier of that
# monodromy and the discarded modes' estimates; its cost grows with the steps times the
# basis squared). CPU per point of `geardyn periodic` at one speed, each printed with its
# floor (the same point with --no-stability, measured in the same run) and the ratios
# Krylov / dense, reduced / dense, and reduced / floor. docs/periodic.md, "Stability at
# scale". With CALLGRIND=1 also the instructions of gd_hb_floquet_reduced per point on
# seed 002 at H = 591 (2500 and 3000 rpm; the second point reuses the first's modes of
# (K, M)), the count that does not depend on the machine's load: 1.26 G for both points
# before the blocked steps, 0.99 G after (2026-12-02; issue 33 item 5 asks about 0.13 G).
# usage: [CALLGRIND=1] bench_floquet.sh BUILD
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
G="$B/geardyn"
export OPENBLAS_NUM_THREADS=1
NOEST=--no-estimate # auto H always compares H with 2 H

cpu_of() { # args...: the CPU time (stderr's "N points, T s CPU": the JSON has no timing)
    local err
    err=$(mktemp)
    "$G" periodic "$@" $NOEST --json --quiet --floquet-budget 0 2>"$err" |
        python3 -c "import json,re,sys; d=json.load(sys.stdin); p=d['points'][0]; \
t=float(re.search(r'([0-9.eE+-]+) s CPU', open(sys.argv[1]).read()).group(1)); \
print('%.4f %s %s %s' % (t, p.get('floquet_method', '-'), \
p.get('floquet_multiplier_max_abs'), p['harmonics']))" "$err"
    rm -f "$err"
}

# label model speeds H [args...]: the floor and the reduced multipliers only (the dense and
# Krylov ones take minutes to hours on these models: docs/periodic.md)
row_reduced() {
    local label=$1 model=$2 speeds=$3 H=$4
    shift 4
    [ "$H" = auto ] && NOEST= || NOEST=--no-estimate
    read -r t0 _ _ h0 < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --no-stability "$@")
    read -r tr mr mur hr < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --floquet reduced "$@")
    awk -v l="$label" -v t0="$t0" -v tr="$tr" -v mur="$mur" -v h="$hr" 'BEGIN {
        r = tr - t0
        printf "%-28s H %5d  floor %7.3f s  reduced %7.3f s (|mu|max %.10f)  reduced/floor %.3g\n", l, h, t0, r, mur, r / t0 }'
    [ "$mr" = reduced ] || echo "  (method not as asked: $mr)"
}

row3() { # label model speeds H: dense, Krylov and reduced
    local label=$1 model=$2 speeds=$3 H=$4
    row "$label" "$model" "$speeds" "$H"
    read -r t0 _ _ _ < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --no-stability)
    read -r td _ mud _ < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --floquet dense)
    read -r tr mr mur _ < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --floquet reduced)
    awk -v l="$label" -v t0="$t0" -v td="$td" -v tr="$tr" -v mud="$mud" -v mur="$mur" -v m="$mr" 'BEGIN {
        d = td - t0; r = tr - t0
        printf "%-28s reduced (%s) %8.4f s (|mu|max %.10f, dense %.10f)  reduced/dense %.3g\n", l, m, r, mur, mud, r / (d > 1e-9 ? d : 1e-9) }'
}

row() { # label model speeds H
    local label=$1 model=$2 speeds=$3 H=$4
    read -r t0 _ _ _ < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --no-stability)
    read -r td md mud _ < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --floquet dense)
    read -r tk mk muk _ < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --floquet krylov)
    awk -v l="$label" -v t0="$t0" -v td="$td" -v tk="$tk" -v mud="$mud" -v muk="$muk" 'BEGIN {
        d = td - t0; k = tk - t0
        printf "%-28s floor %7.4f s  dense %8.4f s (|mu|max %.10f)  krylov %8.4f s (|mu|max %.10f)  krylov/dense %.3g\n", l, t0, d, mud, k, muk, k / (d > 1e-9 ? d : 1e-9) }'
    [ "$md" = dense ] && [ "$mk" = krylov ] || echo "  (method not as asked: $md $mk)"
}

echo "-- stability cost per point (CPU s, without the floor), dense vs Krylov (8 largest) vs reduced"
row3 "Chen SFD pair, 12 states" examples/chen1998_gear_pair.yaml 5600:5600:1 12
row3 "Kumar 2011 coupled, 16 st." examples/kumar2011_coupled.yaml 300:300:1 94
echo "   (Kumar's free rotation has no eigenvector basis: reduced hands over to dense)"
echo "-- large models: the reduced multipliers against the harmonic balance solve of the point"
echo "   (dense about 1.2 s per Magnus step x 2048 steps, Krylov about 10 s per product and"
echo "    no convergence in 30 min on the first: docs/periodic.md)"
row_reduced "[JMSTHelical] 2500 rpm, 754 st." examples/helical_two_stage.yaml 2500rpm:2500rpm:1 108
# the figures set's order (H = 591), two speeds: the second reuses the first's modes of
# (K, M) (floquet_reduced.c, modes_of); the time is of both points
row_reduced "[JMSTHelical] 2 speeds, H 591" examples/helical_two_stage.yaml 2500rpm:3000rpm:2 591 \
    --sequential --method hb
echo "   (per point: half the reduced time above; issue 33 item 5 asks for 20 ms)"
if [ "${CALLGRIND:-0}" = 1 ] && command -v valgrind >/dev/null; then
    cg=$(mktemp)
    valgrind --tool=callgrind --toggle-collect=gd_hb_floquet_reduced --callgrind-out-file="$cg" \
        "$G" periodic examples/helical_two_stage.yaml --speeds 2500rpm:3000rpm:2 --harmonics 591 \
        --sequential --method hb --floquet reduced --no-estimate --quiet --floquet-budget 0 \
        >/dev/null 2>&1
    callgrind_annotate "$cg" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1);
        printf "   callgrind: gd_hb_floquet_reduced %.3g G instructions for both points (%.3g G per point)\n",
        $1 / 1e9, $1 / 2e9 }'
    rm -f "$cg"
fi
GB=(--set meshes.pair1.geometry.driver.teeth=23 --set meshes.pair1.geometry.driven.teeth=67
    --set meshes.pair2.geometry.driver.teeth=19 --set meshes.pair2.geometry.driven.teeth=71)
row_reduced "gearbox 23/67-19/71, 1500 rpm" examples/helical_two_stage.yaml 1500rpm:1500rpm:1 auto "${GB[@]}"
