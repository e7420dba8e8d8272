#!/usr/bin/env bash
# Scaling with model size on one core: the MMT rig (examples/rig2018.yaml) refined from
# 1 000 to 100 000 DOFs (elements_per_section 50 .. 5000, two geared shafts, 5 DOFs per
# node), with an unbalance on the driving gear. CPU time (user + system) and peak memory
# (/usr/bin/time) of check; modal, 10 lowest damped modes at 3000 rpm; campbell, 20
# speeds 0..12000 rpm, 10 modes; frf, direct, 100 frequencies to 2 kHz; transient,
# unbalance from rest for 1 ms by gen-alpha (h 10 us) on the full model and on the model
# reduced to its modes below 5 kHz. Goals (issue 14): 100k modal < 5 s, campbell < 60 s,
# memory linear. usage: bench_scaling.sh BUILD [MAX_DOFS]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
MAX=${2:-100010}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
T=/usr/bin/time
[ -x "$T" ] || { echo "/usr/bin/time missing (apt-get install time)"; exit 0; }
run() { # command...: prints CPU seconds (user + system: the machine may be shared) and MB
    local out="$tmp/time"
    if "$T" -f "%U %S %M" -o "$out" "$@" > /dev/null 2> "$tmp/err"; then
        awk '{printf "%8.2f s %7.0f MB", $1 + $2, $3 / 1024}' "$out"
    else
        printf "%20s" "failed"
        sed 's/^/    # /' "$tmp/err" | head -3 >&2
    fi
}
printf "%8s | %-19s | %-19s | %-19s | %-19s | %-19s | %-19s\n" DOFs check "modal 10" \
    "campbell 20x10" "frf 100" "transient full" "transient reduced"
for e in 50 100 250 500 1000 2500 5000; do
    n=$((20 * e + 10))
    [ "$n" -le "$MAX" ] || break
    f="$tmp/rig$n.yaml"
    sed "s/elements_per_section: 8/elements_per_section: $e/" examples/rig2018.yaml > "$f"
    printf 'unbalances:\n  - {name: u48, node: gear48, amount: 1e-5 kg*m}\n' >> "$f"
    printf "%8d | %s | %s | %s | %s | %s | %s\n" "$n" \
        "$(run "$B/geardyn" check "$f")" \
        "$(run "$B/geardyn" modal "$f" --modes 10 --speed 3000rpm)" \
        "$(run "$B/geardyn" campbell "$f" --speeds 0:12000rpm:20 --modes 10)" \
        "$(run "$B/geardyn" frf "$f" --input gear48.x --output gear32.x --freq 0:2kHz:100 --threads 1)" \
        "$(run "$B/geardyn" transient "$f" --speed 3000rpm --duration 1ms --from 0 --record gear48.x --output-interval 10us --method galpha --step 10us --quiet)" \
        "$(run "$B/geardyn" transient "$f" --speed 3000rpm --duration 1ms --from 0 --record gear48.x --output-interval 10us --method galpha --step 10us --reduce 5kHz --quiet)"
done
