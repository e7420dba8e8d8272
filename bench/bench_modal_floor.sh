#!/usr/bin/env bash
# `geardyn modal --modes N` against its floor on the same matrices: scipy's ARPACK
# (shift-invert, SuperLU) and LAPACK dgeev, from `geardyn matrices --format mtx`
# (Debian python3-scipy; installed here if missing). Model: bench/models/rig366.yaml
# (the MMT rig refined to 366 DOFs), 3000 rpm, 12 modes, one thread on both sides.
# usage: bench_modal_floor.sh BUILD
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
if ! /usr/bin/python3 -c "import scipy" 2>/dev/null; then
    apt-get install -y -qq python3-scipy >/dev/null 2>&1 || { echo "python3-scipy missing: no floor"; exit 0; }
fi
for N in 12 30; do
    "$B/bench_modal_method" bench/models/rig366.yaml 314.159265 $N 5 | tee "$tmp/gd$N"
    "$B/geardyn" matrices bench/models/rig366.yaml --speed 3000rpm --out "$tmp/m$N" > /dev/null
    /usr/bin/python3 bench/floor_modal.py "$tmp/m$N" 314.159265 $N 5 $([ $N = 30 ] && echo --no-dense) | tee "$tmp/fl$N"
    ta=$(awk '/^auto/ {print $2}' "$tmp/gd$N")
    tf=$(awk '/ARPACK/ {for (i = 1; i <= NF; i++) if ($i == "time") print $(i + 1)}' "$tmp/fl$N")
    echo "ratio geardyn auto / ARPACK+SuperLU floor ($N modes): $(echo "$ta / $tf" | bc -l | cut -c1-5) (goal <= 1.2)"
    echo
done
start=$(date +%s.%N)
"$B/geardyn" modal bench/models/rig366.yaml --speed 3000rpm --modes 12 > /dev/null
end=$(date +%s.%N)
echo "geardyn modal --modes 12 CLI end to end (load, build, solve, print): $(echo "$end - $start" | bc -l | cut -c1-6) s"
