#!/usr/bin/env bash
# Floquet multipliers of harmonic balance points: the dense Magnus monodromy (every
# multiplier, 30 (2 nf)^3 flops per step) against Krylov-Schur on monodromy-vector
# products (the 8 largest; each product sums a Taylor series per step, about 8 |Omega|
# Omega actions, so its cost grows with the period times the largest natural frequency,
# not with nf^3). CPU per point of `geardyn periodic` at one speed, each printed with its
# floor (the same point with --no-stability, measured in the same run) and the ratio
# Krylov / dense. docs/periodic.md, "Stability at scale".
# usage: bench_floquet.sh BUILD
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
G="$B/geardyn"
export OPENBLAS_NUM_THREADS=1

cpu_of() { # args...: the JSON's cpu_seconds
    "$G" periodic "$@" --no-estimate --json --quiet |
        python3 -c "import json,sys; d=json.load(sys.stdin); p=d['points'][0]; \
print('%.4f %s %s' % (d['cpu_seconds'], p.get('floquet_method', '-'), \
p.get('floquet_multiplier_max_abs')))"
}

row() { # label model speeds H
    local label=$1 model=$2 speeds=$3 H=$4
    read -r t0 _ _ < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --no-stability)
    read -r td md mud < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --floquet dense)
    read -r tk mk muk < <(cpu_of "$model" --speeds "$speeds" --harmonics "$H" --floquet krylov)
    awk -v l="$label" -v t0="$t0" -v td="$td" -v tk="$tk" -v mud="$mud" -v muk="$muk" 'BEGIN {
        d = td - t0; k = tk - t0
        printf "%-28s floor %7.4f s  dense %8.4f s (|mu|max %.10f)  krylov %8.4f s (|mu|max %.10f)  krylov/dense %.3g\n", l, t0, d, mud, k, muk, k / (d > 1e-9 ? d : 1e-9) }'
    [ "$md" = dense ] && [ "$mk" = krylov ] || echo "  (method not as asked: $md $mk)"
}

echo "-- stability cost per point (CPU s, without the floor), dense vs Krylov (8 largest)"
row "Chen SFD pair, 12 states" examples/chen1998_gear_pair.yaml 5600:5600:1 12
row "Kumar 2011 coupled, 16 st." examples/kumar2011_coupled.yaml 300:300:1 94
echo "   (the 378-DOF [JMSTHelical] model, 756 states, H = 108: dense about 1.5 s per Magnus"
echo "    step x 2048 steps, Krylov about 10 s per product: docs/periodic.md)"
