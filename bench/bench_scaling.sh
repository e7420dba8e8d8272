#!/usr/bin/env bash
# Scaling with model size on one core: the MMT rig (examples/rig2018.yaml) refined from
# 1 000 to 100 000 DOFs (elements_per_section 50 .. 5000, two geared shafts, 5 DOFs per
# node), with an unbalance on the driving gear. CPU time (user + system) and peak memory
# (/usr/bin/time) of check; modal, 10 lowest damped modes at 3000 rpm; campbell, 20
# speeds 0..12000 rpm, 10 modes; frf, direct, 100 frequencies to 2 kHz; transient,
# unbalance from rest for 1 ms by gen-alpha (h 10 us) on the full model and on the model
# reduced to its modes below 5 kHz. Goals (issue 14): 100k modal < 5 s, campbell < 60 s,
# memory linear.
#
# Then (issue 23) models from outside our examples, each against its floor measured in
# the same run: bench/models/shaft{1k,10k,100k}.yaml (a 10 m shaft of 0.2 m diameter,
# 60 mm to 0.6 mm elements) and gearbox{10k,100k}.yaml (three finely meshed shafts, two
# meshes). modal: `geardyn modal --modes 10 --json` end to end (process start, parse,
# assembly, solve, output) against scipy's ARPACK shift-invert with SuperLU on the
# exported matrices (bench/floor_modal.py: the solve alone, same shift, tol 1e-9),
# REPEATS (default 3) runs of each interleaved, minima of CPU time (below 5000 DOFs a run
# is 20 runs in a row, divided by 20: /usr/bin/time counts 10 ms ticks); agreement:
# largest relative difference of the elastic frequencies, and the floor's own stability
# (its tol-1e-12 frequencies at 3 times the shift against those at the shift: the fine
# shafts' low modes carry rounding of order eps (element frequency / mode's)^2, which
# no solver removes). campbell: 20 speeds 0..3000 rpm, 10 modes, CPU per speed (whole command / 20)
# against the floor's mean of 4 speeds over the same range. Peak memory of each side
# (the floor's includes the Python interpreter with scipy, about 60 MB).
# usage: bench_scaling.sh BUILD [MAX_DOFS] [--models-only]
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
    [ "${3:-}" != --models-only ] || break
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

# ---- issue 23: models from outside our examples, against the ARPACK floor ----
PY=/usr/bin/python3
if ! "$PY" -c "import scipy" 2>/dev/null; then
    echo "python3-scipy missing (apt-get install python3-scipy): no floor"
    exit 0
fi
R=${REPEATS:-3}
cpu_mem() { # OUT command...: CPU seconds and peak MB of one run, stdout to OUT
    local out=$1
    shift
    if "$T" -f "%U %S %M" -o "$tmp/t1" "$@" > "$out" 2> "$tmp/err"; then
        awk '{printf "%.4f %.0f\n", $1 + $2, $3 / 1024}' "$tmp/t1"
    else
        echo "nan nan"
        sed 's/^/    # /' "$tmp/err" | head -3 >&2
    fi
}
fl_time() { awk '/time/ {for (i = 1; i <= NF; i++) if ($i == "time") print $(i + 1)}' "$1"; }
minf() { awk -v a="$1" -v b="$2" 'BEGIN {print (b == "" || a + 0 < b + 0) ? a : b}'; }
echo
printf "%-22s %7s | %-40s | %-16s | %-36s\n" model DOFs \
    "modal 10: geardyn / floor = ratio" "freq. agreement" "campbell 20x10, per speed: ratio"
printf "%-22s %7s | %-40s | %-16s | %-36s\n" "" "" "(CPU s, peak MB)" "gd-fl  fl-self" ""
for f in bench/models/shaft1k.yaml bench/models/shaft10k.yaml bench/models/gearbox10k.yaml \
    bench/models/shaft100k.yaml bench/models/gearbox100k.yaml; do
    n=$("$B/geardyn" check "$f" | awk '/^DOFs/ {print $2}')
    [ "$n" -le "$MAX" ] || continue
    rm -rf "$tmp/mat"
    "$B/geardyn" matrices "$f" --out "$tmp/mat" > /dev/null
    gbest="" fbest="" gmem="" fmem=""
    k=1
    [ "$n" -ge 5000 ] || k=20
    for r in $(seq "$R"); do # interleaved: the machine may be shared
        read -r t m < <(cpu_mem /dev/null sh -c 'for i in $(seq "$1"); do
            "$2" modal "$3" --modes 10 --json > "$4"; done' - "$k" "$B/geardyn" "$f" "$tmp/gd.json")
        t=$(echo "$t / $k" | bc -l)
        gbest=$(minf "$t" "$gbest") gmem=$m
        read -r _ m < <(cpu_mem "$tmp/fl.txt" "$PY" bench/floor_modal.py "$tmp/mat" 0 10 1 \
            --no-dense --freqs)
        fbest=$(minf "$(fl_time "$tmp/fl.txt")" "$fbest") fmem=$m
    done
    "$PY" bench/floor_modal.py "$tmp/mat" 0 10 1 --no-dense --freqs --tol 1e-12 > "$tmp/fl12.txt"
    "$PY" bench/floor_modal.py "$tmp/mat" 0 10 1 --no-dense --freqs --tol 1e-12 \
        --sigma-scale 3 > "$tmp/fl12s.txt"
    agree=$("$PY" bench/compare_freqs.py "$tmp/gd.json" "$tmp/fl.txt")
    self=$("$PY" bench/compare_freqs.py "$tmp/fl12s.txt" "$tmp/fl12.txt")
    read -r ct cm < <(cpu_mem /dev/null "$B/geardyn" campbell "$f" --speeds 0:3000rpm:20 --modes 10)
    read -r _ cfm < <(cpu_mem "$tmp/flc.txt" "$PY" bench/floor_modal.py "$tmp/mat" 0 10 1 \
        --no-dense --speeds 0:314.159265:4)
    cf=$(fl_time "$tmp/flc.txt")
    printf "%-22s %7d | %7.3f s %5s MB / %7.3f s %4s MB = %5.2f | %7s %7s | %6.3f s %5s MB / %6.3f s %4s MB = %5.2f\n" \
        "$(basename "$f" .yaml)" "$n" "$gbest" "$gmem" "$fbest" "$fmem" \
        "$(echo "$gbest / $fbest" | bc -l)" "$agree" "$self" \
        "$(echo "$ct / 20" | bc -l)" "$cm" "$cf" "$cfm" "$(echo "$ct / 20 / $cf" | bc -l)"
done
