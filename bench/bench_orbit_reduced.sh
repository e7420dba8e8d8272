#!/usr/bin/env bash
# Reduced shooting of seed 002's spur curve (docs/periodic.md, "[JMSTHelical]: Figs. 11-13",
# "Reduced shooting at low speed"): the periodic orbit of the TVMS model linearised at its
# static state, in the reduced basis (modes up to 20 kHz plus the laws' static correction,
# 74 vectors), the monodromy and the forced response in one Magnus sweep of STEPS steps,
# the mesh forces recorded on a grid of OUT steps. Per speed: the mean and peak-to-peak of
# both mesh forces and the CPU, against a long generalized-alpha transient (TRANSIENT=1,
# 6 s from the static state, step 2e-6 s, the last two periods; about 100 s CPU a speed)
# below 1000 rpm and harmonic balance at H = 591 and 1183 above (where it is converged).
# usage: [TRANSIENT=1] bench/bench_orbit_reduced.sh [BUILD]     (from the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
OUT=${OUT:-$B/bench_orbit_reduced}
export OPENBLAS_NUM_THREADS=1
MODEL=examples/helical_two_stage.yaml
SET=(meshes.pair1.geometry.helix_angle=0deg meshes.pair2.geometry.helix_angle=0deg
     meshes.pair1.coupling=full meshes.pair2.coupling=full)
mkdir -p "$OUT"
# speed  monodromy steps  record grid  harmonic balance H (0: none)
while read -r rpm steps out H; do
    STEPS_OUT=$out "$B/bench_orbit_reduced" "$MODEL" "$rpm" "$steps" 20000 "$H" "${SET[@]}"
    if [ "${TRANSIENT:-0}" = 1 ] && [ "$H" = 0 ]; then
        T=$(python3 -c "print(36 * 60 / (52 * $rpm))")
        "$B/geardyn" transient "$MODEL" --set "${SET[0]}" --set "${SET[1]}" --coupling full \
            --speed "${rpm}rpm" --duration 6s --from "$(python3 -c "print(6 - 2 * $T)")s" \
            --output-interval 1e-5s --method galpha --step 2e-6s --start static \
            --record mesh:pair1:force --record mesh:pair2:force --quiet \
            --out "$OUT/tr_$rpm" | awk -v r="$rpm" '/^mesh:pair/ {
                printf "transient rpm %7.1f %s mean %s p2p %s\n", r, $1, $6, $8 }'
    fi
done <<'ROWS'
100 32768 262144 0
300 16384 131072 0
600 8192 65536 0
1000 4096 65536 0
2000 2048 32768 1183
2500 2048 32768 591
3000 2048 32768 1183
ROWS
