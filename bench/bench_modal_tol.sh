#!/usr/bin/env bash
# Frequencies to the precision asked at 100k DOFs (issue 35 item 3): `geardyn modal
# --modes 10 --json` on a large model at the default --tol (1e-9) and at --tol 1e-10,
# CPU time (user + system, best of REPEATS) and the largest reported residual, and each
# frequency against a direct reference (bench/modal_reference.py: shift-invert at each
# mode's own eigenvalue, ARPACK at tolerance 1e-14, on the exported matrices) with that
# reference's own spread. Default model bench/models/gearbox100k.yaml at 0 rpm.
# usage: bench_modal_tol.sh BUILD [MODEL] [SPEED_RPM]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
MODEL=${2:-bench/models/gearbox100k.yaml}
RPM=${3:-0}
R=${REPEATS:-2}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
PY=/usr/bin/python3
"$PY" -c "import scipy" 2>/dev/null || { echo "python3-scipy missing: no reference"; exit 0; }
W=$(echo "$RPM * 3.14159265358979 / 30" | bc -l)
"$B/geardyn" matrices "$MODEL" --speed "${RPM}rpm" --out "$tmp/mat" > /dev/null
echo "model $MODEL at $RPM rpm: $("$B/geardyn" check "$MODEL" | awk '/^DOFs/ {print $2}') DOFs"
for tol in default 1e-10; do
    extra=()
    [ "$tol" = default ] || extra=(--tol "$tol")
    best=
    for _ in $(seq "$R"); do
        /usr/bin/time -f "%U %S" -o "$tmp/t" "$B/geardyn" modal "$MODEL" --speed "${RPM}rpm" \
            --modes 10 --method sparse --json "${extra[@]}" > "$tmp/gd.json" 2>/dev/null
        t=$(awk '{print $1 + $2}' "$tmp/t")
        best=$(echo "$t $best" | awk '{print ($2 == "" || $1 < $2) ? $1 : $2}')
    done
    worst=$("$PY" -c "import json; print('%.1e' % max(m['residual'] for m in json.load(open('$tmp/gd.json'))['modes'] if not m['rigid_body']))")
    echo "--tol $tol: $best s CPU (best of $R, whole command), largest reported residual $worst"
    "$PY" bench/modal_reference.py "$tmp/mat" "$W" "$tmp/gd.json" | sed 's/^/  /'
done
