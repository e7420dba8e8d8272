#!/usr/bin/env bash
# The Floquet multipliers of `geardyn periodic` (the reduced basis, every default) against
# a long generalized-alpha transient, where they predict a parametric instability: the
# [JMSTHelical] model with spur pairs (helix 0 deg, full coupling) at 4327.42 rpm, a point
# of the Figs. 11-13 grid that the multipliers call unstable (a complex pair, |mu| 1.0104
# per HB period), and its stable neighbour at 4301.00 rpm.
#
# The transient is sampled at T / 96 (T the HB period, 36 mesh-1 periods), so x(t + T) -
# x(t) is a difference of samples: the periodic response cancels and what is left is the
# motion that does not repeat, which grows as |mu|^(t / T) where an orbit is unstable and
# dies out where it is stable. Its envelope (11 windows from 0.5 s to 6 s) is fitted by an
# exponential over the last 7 windows and turned into a modulus per period.
#
# usage: bench/floquet_against_transient.sh      (from the repository root; about 5 min CPU)
# docs/periodic.md, "Stability at scale", has the numbers.
set -euo pipefail
GEARDYN=${GEARDYN:-./build/geardyn}
OUT=${OUT:-build/floquet_against_transient}
MODEL=examples/helical_two_stage.yaml
X=(--set meshes.pair1.geometry.helix_angle=0deg --set meshes.pair2.geometry.helix_angle=0deg
   --coupling full)
REC=(--record mesh:pair1:force --record mesh:pair2:force)
mkdir -p "$OUT"
for rpm in 4327.42 4301.00; do
    "$GEARDYN" periodic "$MODEL" "${X[@]}" --speeds "${rpm}rpm:${rpm}rpm:1" --harmonics 108 \
        --no-estimate "${REC[@]}" --json --quiet >"$OUT/hb_$rpm.json"
    dt=$(/usr/bin/python3 -c "import math; W = $rpm * math.pi / 30
print('%.17g' % (2 * math.pi / (52 * W / 36) / 96))")
    /usr/bin/time -f "%U %S" -o "$OUT/tr_$rpm.time" "$GEARDYN" transient "$MODEL" "${X[@]}" \
        --speed "${rpm}rpm" --duration 6s --from 0.5s --output-interval "${dt}s" \
        --method galpha --step 2e-6s --start static "${REC[@]}" --quiet --out "$OUT/tr_$rpm" \
        >/dev/null
done
/usr/bin/python3 - "$OUT" <<'PY'
import csv, json, math, sys
import numpy as np
out = sys.argv[1]
for rpm in ('4327.42', '4301.00'):
    p = json.load(open('%s/hb_%s.json' % (out, rpm)))['points'][0]
    T = 2 * math.pi / p['omega_rad_s']
    rows = list(csv.reader(open('%s/tr_%s/records.csv' % (out, rpm))))
    a = np.array([[float(x) for x in r] for r in rows[1:]])
    t = a[:-96, 0]
    fits = []
    for col in (1, 2):
        d = np.abs(a[96:, col] - a[:-96, col])
        e = np.linspace(t[0], t[-1], 12)
        env = [d[(t >= e[k]) & (t < e[k + 1])].max() for k in range(11)]
        mid = 0.5 * (e[:-1] + e[1:])
        rate = np.polyfit(mid[4:], np.log(env[4:]), 1)[0]
        fits.append(math.exp(rate * T))
    print('%s rpm: periodic |mu|max %.6f (%s, %d steps, basis %d); transient: the motion '
          'that does not repeat %s, |mu| per period %.6f (mesh 1), %.6f (mesh 2)' % (
              rpm, p['floquet_multiplier_max_abs'], 'stable' if p['stable'] else 'unstable',
              p['floquet_steps'], p['floquet_basis'],
              'grows' if fits[0] > 1 else 'dies out', fits[0], fits[1]))
PY
echo "CPU (user sys) of the transients: $(cat "$OUT"/tr_*.time | tr '\n' ' ')"
