#!/usr/bin/env bash
# Condensed harmonic balance (docs/periodic.md, "Condensed harmonic balance"): CPU of the
# same periodic runs solved on the laws' coordinates (the default, --method hb) and by the
# full harmonic balance (--method full-hb: the whole sparse LU or the low-rank
# condensation), measured one after the other in this run, and their ratio; the largest
# difference of the recorded peak-to-peaks between the two (the solutions are equal to
# 1e-9, tests/periodic/test_condensed_hb.c). Seed 002 ([JMSTHelical],
# examples/helical_two_stage.yaml, 377 free DOFs, 4 law coordinates), one curve.
# usage: bench_condensed_hb.sh BUILD [H [SPEEDS]]   (defaults 108 and 1000rpm:8000rpm:30)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
H=${2:-108}
SPEEDS=${3:-1000rpm:8000rpm:30}
M=examples/helical_two_stage.yaml
declare -A cpu
for m in full-hb hb; do
    d=$(mktemp -d)
    OPENBLAS_NUM_THREADS=1 "$B/geardyn" periodic "$M" --speeds "$SPEEDS" --harmonics "$H" \
        --sequential --no-stability --no-estimate --method "$m" --record mesh:pair1:force \
        --record mesh:pair2:force --out "$d" 2>"$d/err" >"$d/log"
    cpu[$m]=$(sed -n 's/.* \([0-9.]*\) s CPU.*/\1/p' "$d/err" | tail -1)
    cp "$d/periodic.csv" "/tmp/bench_chb_$m.csv"
    printf '   %-8s %8.3f s CPU  (%s)\n' "$m" "${cpu[$m]}" "$(grep -m1 '^method' "$d/log" || true)"
    rm -rf "$d"
done
python3 - "${cpu[full-hb]}" "${cpu[hb]}" <<'PY'
import csv, sys
full, cond = float(sys.argv[1]), float(sys.argv[2])
a = list(csv.DictReader(open('/tmp/bench_chb_full-hb.csv')))
b = list(csv.DictReader(open('/tmp/bench_chb_hb.csv')))
cols = [k for k in a[0] if k.endswith('peak_to_peak')]
d = max(abs(float(x[k]) - float(y[k])) / max(abs(float(x[k])), 1e-300)
        for x, y in zip(a, b) for k in cols)
print('   full / condensed: %.2fx; largest relative peak-to-peak difference %.2g' % (full / cond, d))
PY
rm -f /tmp/bench_chb_full-hb.csv /tmp/bench_chb_hb.csv
