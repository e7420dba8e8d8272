#!/usr/bin/env bash
# The issue-20 check of harmonic balance on a real gear train: the two-stage gearbox
# (examples/helical_two_stage.yaml with 23/67 and 19/71 teeth, 378 DOFs) at 1500 rpm by
# `geardyn periodic --method auto` (every other option default) against a long
# generalized-alpha transient from the static state, run until its successive periods agree.
# Prints per record the peak-to-peak of the last periods (from the raw samples) and of HB,
# and the mesh-order amplitudes (1x-3x of each mesh) of both; CPU of both runs.
# usage: bench/periodic_against_transient.sh [PERIODS (default 70)] [STEP (default 1e-6s)]
# About 6 min CPU at the defaults (the transient: 327 s). docs/periodic.md has the numbers.
set -euo pipefail
PERIODS=${1:-70}
STEP=${2:-1e-6s}
GEARDYN=${GEARDYN:-./build/geardyn}
MODEL=examples/helical_two_stage.yaml
OUT=${OUT:-build/periodic_against_transient}
GB=(--set meshes.pair1.geometry.driver.teeth=23 --set meshes.pair1.geometry.driven.teeth=67
    --set meshes.pair2.geometry.driver.teeth=19 --set meshes.pair2.geometry.driven.teeth=71)
REC=(--record mesh:pair1:force --record mesh:pair2:force --record gear1.x)
mkdir -p "$OUT"
/usr/bin/time -f "%U %S" -o "$OUT/hb.time" "$GEARDYN" periodic "$MODEL" "${GB[@]}" \
    --speeds 1500rpm:1500rpm:1 --method auto "${REC[@]}" --json --quiet >"$OUT/hb.json" || true
# the HB period, and the transient's record grid on it: T / 8192 from period PERIODS - 4 on
read -r T FROM DT END < <(/usr/bin/python3 -c "
import json, math
w = json.load(open('$OUT/hb.json'))['points'][0]['omega_rad_s']
T = 2 * math.pi / w
print('%.17g %.17g %.17g %.17g' % (T, ($PERIODS - 4) * T, T / 8192, $PERIODS * T))")
/usr/bin/time -f "%U %S" -o "$OUT/tr.time" "$GEARDYN" transient "$MODEL" "${GB[@]}" \
    --speed 1500rpm --duration "${END}s" --from "${FROM}s" --output-interval "${DT}s" \
    --method galpha --step "$STEP" --start static "${REC[@]}" --quiet --out "$OUT/tr" >/dev/null
/usr/bin/python3 - "$OUT" "$T" "$PERIODS" <<'PY'
import csv, json, sys
import numpy as np
out, T, P = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
rows = list(csv.reader(open(out + '/tr/records.csv')))
a = np.array([[float(x) for x in r] for r in rows[1:]])
t = a[:, 0]
hb = json.load(open(out + '/hb.json'))['points'][0]
print('HB: H = %d, estimate p2p %.2g, amplitudes %.2g' % (
    hb['harmonics'], hb['truncation']['peak_to_peak'], hb['truncation']['amplitudes']))
for j, name in enumerate(hb['records'], start=1):
    r = hb['records'][name]
    pp = []
    for k in range(P - 4, P):
        m = (t >= k * T - 1e-9 * T) & (t < (k + 1) * T - 1e-9 * T)
        pp.append(np.ptp(a[m, j]))
    print('%-18s transient p2p per period %s   HB %.6g (%+.2f %%)' % (
        name, ' '.join('%.6g' % p for p in pp), r['peak_to_peak'],
        100 * (r['peak_to_peak'] / pp[-1] - 1)))
    m = (t >= (P - 1) * T - 1e-9 * T) & (t < P * T - 1e-9 * T)
    v = a[m, j][:8192]
    F = np.abs(np.fft.rfft(v)) / len(v) * 2
    A = r['amplitudes']
    print('    orders ' + '  '.join('%d: %+.2f %%' % (o, 100 * (A[o] / F[o] - 1))
                                   for o in (67, 134, 201, 19, 38, 57)))
PY
echo "CPU (user sys): periodic $(cat "$OUT/hb.time"), transient $(cat "$OUT/tr.time")"
