#!/usr/bin/env bash
# [JMSTHelical] (helical two-stage system), Figs. 11-13: gear-1 response and the dynamic
# mesh forces of both pairs versus input speed, by harmonic balance (geardyn periodic),
# for the full and the lateral-torsional mesh coupling at helix angles 0, 5, 10, 15
# and 20 deg on both meshes: 10 curves. docs/periodic.md, "[JMSTHelical]: Figs. 11-13".
#
# usage: examples/seed002/figs11_13.sh [OUTDIR]      (run from the repository root)
# environment: H (harmonics, default 591), SPEEDS (default 100rpm:8000rpm:300),
#              JOBS (curves run at once, default 1), GEARDYN (default ./build/geardyn),
#              ESTIMATE (1, default: every point also solved at 2 H + 1 for its truncation
#              estimate, the peak_to_peak_error column; 0: not, about 3x cheaper),
#              STABILITY (1, default: the Floquet multipliers of every point in a reduced
#              basis, --floquet reduced, about 0.07 s CPU per point at H = 591 (its own
#              Magnus step count): docs/periodic.md, "Stability at scale"; 0:
#              --no-stability)
#
# Why H = 591: the HB period is 36 mesh-1 periods (teeth 52/72, 22/79: w0 = 52 W / 36),
# so harmonic 36 k is k times the mesh-1 frequency. H = 108 (k <= 3, the old default:
# 30 min less CPU, H=108) leaves the peak-to-peak forces off resonance wrong (mesh 2 at
# 2500 rpm: 43 % low against a long transient); 591 is what --harmonics auto takes at
# 1817 and 3000 rpm, within 0.3 % of the transients there. Below 1000 rpm even 591 is
# not enough (the estimate says up to 83 %: auto would need H = 18943 at 100 rpm); each
# point's estimate is the peak_to_peak_error column of periodic.csv. About 20-30 min CPU
# for the set with the estimate and the multipliers of every point (2060 s measured
# before; the full 0-deg curve 186 s on 2026-12-02; docs/periodic.md, "[JMSTHelical]:
# Figs. 11-13" and "Harmonic truncation").
# Why 100-8000 rpm: the OCR text of the paper has lost the figures' speed axes; this
# range holds mesh-1 k = 1 of every mode of this model up to 6.9 kHz, among them the
# modes with 10-37 % of their strain energy in the meshes (4.7-7.2 kHz, 5400-8000 rpm),
# and their k = 2, 3 super-harmonics (1800-4100 rpm), with a 26.4 rpm grid.
# Why --sequential: TVMS is the only law here (teeth never separate at 50 N m), the
# response has no folds, and the arclength winds through the narrow super-harmonic
# peaks at many steps per requested speed (docs/periodic.md).
set -euo pipefail

OUT=${1:-build/seed002}
H=${H:-591}
SPEEDS=${SPEEDS:-100rpm:8000rpm:300}
JOBS=${JOBS:-1}
ESTIMATE=${ESTIMATE:-1}
NOEST=""
STAB="--floquet reduced"
[ "${STABILITY:-1}" = 0 ] && STAB=--no-stability
[ "$ESTIMATE" = 0 ] && NOEST=--no-estimate
GEARDYN=${GEARDYN:-./build/geardyn}
MODEL=examples/helical_two_stage.yaml
[ -x "$GEARDYN" ] || { echo "figs11_13.sh: $GEARDYN not built (make)" >&2; exit 2; }
mkdir -p "$OUT"

run_curve() { # coupling helix_deg
    local c=$1 b=$2 dir="$OUT/${1}_${2}deg"
    rm -rf "$dir"
    /usr/bin/time -f "%e %U %S" -o "$dir.time" \
        "$GEARDYN" periodic "$MODEL" --speeds "$SPEEDS" --harmonics "$H" \
        --sequential $STAB $NOEST --quiet --coupling "$c" \
        --set "meshes.pair1.geometry.helix_angle=${b}deg" \
        --set "meshes.pair2.geometry.helix_angle=${b}deg" \
        --record gear1.x --record gear1.z --record gear1.ry --record gear1.rz \
        --record mesh:pair1:force --record mesh:pair2:force \
        --out "$dir" >"$dir.log"
    read -r wall user sys <"$dir.time"
    printf '%-18s %3s deg  wall %7.1f s  cpu %7.1f s\n' "$c" "$b" "$wall" \
        "$(echo "$user + $sys" | bc)"
}

start=$(date +%s.%N)
for c in full lateral-torsional; do
    for b in 0 5 10 15 20; do
        while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done
        run_curve "$c" "$b" &
    done
done
wait
end=$(date +%s.%N)
cpu=$(cat "$OUT"/*.time | awk '{s += $2 + $3} END {printf "%.1f", s}')
printf 'total: 10 curves, %s speeds, H = %s: wall %.1f s, cpu %s s (%s at once)\n' \
    "${SPEEDS##*:}" "$H" "$(echo "$end - $start" | bc)" "$cpu" "$JOBS"
