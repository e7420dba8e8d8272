#!/usr/bin/env bash
# Gear rattle (issue 37, docs/rattle.md): CPU seconds per simulated second of the rattle
# examples by `geardyn transient --rattle` (BDF, rtol 1e-6, contact changes located),
# against the floor measured in the same run: the same model and run without backlash
# (the teeth always in contact: a smooth problem of the same size). The accuracy: the
# rattle metrics at rtol 1e-6 against a tight reference at rtol 1e-9 over the same
# window (the motion is chaotic, so the metrics, not the trajectories, are compared,
# each with its 95 % half-width). Then the 20-point rattle map (study). Prints figures
# only. usage: bench/bench_rattle.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=$(cd "${1:-build}" && pwd)
G="$B/geardyn"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OPENBLAS_NUM_THREADS=1
cpu() { /usr/bin/time -f "%U %S" -o "$tmp/cpu" "$@" > "$tmp/out.json"; awk '{ printf "%.3f", $1 + $2 }' "$tmp/cpu"; }
field() { python3 -c "
import json, sys
o = json.load(open('$tmp/out.json')); r = o['rattle']['meshes'][0]
k = sys.argv[1]
print('%.4g +- %.2g' % (r[k]['mean'], r[k]['half_width']) if isinstance(r[k], dict) else r[k])" "$1"; }

D=4
FROM=1
echo "CPU s per simulated s ($D s runs, metrics over the last $((D - FROM)) s)"
for case in "rattle_pair.yaml 3 mrad|--set prescribed.0.amplitude=3mrad" \
            "rattle_pair.yaml 1.3 mrad (grazing)|--set prescribed.0.amplitude=1.3mrad" \
            "rattle_idle.yaml 800 rpm 1 N m|" \
            "gearbox_neutral_rattle.yaml 2 N m|" \
            "gearbox_neutral_rattle.yaml 1.1 N m|--set excitations.loads.firing.amplitude=1.1"; do
    name=${case%%|*}
    sets=${case#*|}
    model=examples/${name%% *}
    c=$(cpu "$G" transient "$model" --duration $D --from $FROM --rattle --json $sets)
    ev=$(python3 -c "import json; print(json.load(open('$tmp/out.json'))['events'])")
    sep=$(field separated_fraction)
    sed '/backlash:/d' "$model" > "$tmp/floor.yaml"
    f=$(cpu "$G" transient "$tmp/floor.yaml" --duration $D --from $FROM --json $sets)
    printf "  %-36s %7.3f s/s  (%s contact events; floor without backlash %.3f s/s, ratio %.1f)\n" \
        "$name" "$(echo "$c / $D" | bc -l)" "$ev" "$(echo "$f / $D" | bc -l)" \
        "$(echo "$c / ($f + 0.001)" | bc -l)"
    echo "      separated fraction $sep"
done

echo "accuracy: rattle_pair.yaml at 3 mrad, rtol 1e-6 .. 1e-10"
for rtol in 1e-6 1e-7 1e-8 1e-9 1e-10; do
    c=$(cpu "$G" transient examples/rattle_pair.yaml --duration $D --from $FROM --rattle --json --rtol $rtol)
    echo "  rtol $rtol: $c CPU s; separated $(field separated_fraction), drive /s $(field drive_impacts_per_s), coast /s $(field coast_impacts_per_s), intensity W $(field intensity_w)"
done

# The 236-DOF 5-speed box (bench/models/manual5_rattle.yaml: FE shafts, backlash on six
# meshes, drag, 3rd gear engaged, 800 rpm idle). Before: the full model (--condense off,
# CVODE BDF, GMRES with the sparse preconditioner) over a short run (about 3000 CPU s per
# simulated s); with GEARDYN_BEFORE=path/to/an/older/geardyn also that build's
# `--condense auto` (BDF, GMRES with a dense preconditioner, per-state error weights).
# After: the default (the condensed transient chosen for this model: --condense auto,
# Adams with the dense direct solver, error weights from the coordinates), and the same
# with --method bdf. The floor: the default at the same cut-off without backlash (a
# smooth problem of the same size). The accuracy: each mesh's rattle metrics against a
# tight reference, the condensed model at 60 kHz (static-correction estimate 1e-11) and
# rtol 1e-8, over the same window (the motion is chaotic: metrics with their 95 %
# half-widths, not trajectories). CPU seconds of the whole process (set-up included).
M=bench/models/manual5_rattle.yaml
MD=${MANUAL5_DURATION:-0.6}
MF=${MANUAL5_FROM:-0.1}
FD=${MANUAL5_FULL_DURATION:-0.02}
echo "5-speed box, 236 DOFs ($M): CPU s per simulated s, process total with set-up"
run5() { # label, json copy, duration, from, binary, extra options
    local lab=$1 js=$2 d=$3 f=$4 bin=$5; shift 5
    c=$(cpu "$bin" transient "$M" --duration $d --from $f --rattle --json "$@")
    cp "$tmp/out.json" "$tmp/$js"
    echo "$c" > "$tmp/$js.cpu"
    python3 -c "
import json; o = json.load(open('$tmp/$js')); c = o.get('condensed')
print('  %-40s %8.2f s/s  (%g s run, %d steps, %d contact events%s)' % ('$lab', $c / $d, $d,
      o['steps'], o['events'], ', %d states, %d of %d modes, cut-off %.4g Hz, estimate %.2g' % (
      c['states'], c['modes_kept'], c['modes_kept'] + c['modes_discarded'], c['cutoff_hz'],
      c['truncation_estimate']) if c else ''))"
}
run5 "before: full, bdf rtol 1e-6" full.json $FD $(echo "$FD / 2" | bc -l) "$G" --condense off --method bdf
if [ -n "${GEARDYN_BEFORE:-}" ]; then
    run5 "before: older build, --condense auto" old.json $MD $MF "$GEARDYN_BEFORE" --condense auto
fi
run5 "after: default (condensed, adams)" auto.json $MD $MF "$G"
run5 "after: --method bdf" bdf.json $MD $MF "$G" --method bdf
sed 's/, backlash: {gap: [0-9]* um}//; /^ *backlash:/d' "$M" > "$tmp/m5floor.yaml"
FC=$(python3 -c "import json; print('%.6gHz' % json.load(open('$tmp/auto.json'))['condensed']['cutoff_hz'])")
c=$(cpu "$G" transient "$tmp/m5floor.yaml" --duration $MD --from $MF --rattle --json --condense $FC)
printf "  %-40s %8.2f s/s\n" "floor: same cut-off, no backlash" "$(echo "$c / $MD" | bc -l)"
python3 -c "
f = float(open('$tmp/full.json.cpu').read()) / $FD; a = float(open('$tmp/auto.json.cpu').read()) / $MD
print('  speed-up full / after %.0f; after / floor %.1f' % (f / a, a / max($c / $MD, 1e-3)))"
run5 "reference: --condense 60kHz, rtol 1e-8" ref.json $MD $MF "$G" --condense 60kHz --rtol 1e-8
python3 - "$tmp" <<'PY'
import json, sys
t = sys.argv[1]
ref = json.load(open(t + '/ref.json'))['rattle']['meshes']
o = json.load(open(t + '/auto.json'))['rattle']['meshes']
print('  metrics, after (default, rtol 1e-6) | reference, mean +- 95 % half-width:')
outside = 0
for k in ('separated_fraction', 'drive_impacts_per_s', 'coast_impacts_per_s', 'intensity_w'):
    print('    ' + k + ': ' + '; '.join('%s %.4g+-%.2g | %.4g+-%.2g' % (
        r['name'], x[k]['mean'], x[k]['half_width'], r[k]['mean'], r[k]['half_width'])
        for r, x in zip(ref, o)))
    outside += sum(abs(x[k]['mean'] - r[k]['mean']) > r[k]['half_width'] + x[k]['half_width']
                   for r, x in zip(ref, o))
print('  %d of %d metrics with disjoint 95 %% intervals' % (outside, 4 * len(ref)))
PY

echo "rattle map of the 5-speed box (bench/models/manual5_rattle_map.yaml, 20 cases of 0.5 s, condensed)"
c=$(cpu "$G" study bench/models/manual5_rattle_map.yaml --out "$tmp/map5" --threads 1 --quiet)
echo "  $c CPU s for 20 cases"
echo "rattle map (examples/studies/rattle_map.yaml, 20 cases of 1.5 s)"
c=$(cpu "$G" study examples/studies/rattle_map.yaml --out "$tmp/map" --threads 1 --quiet)
echo "  $c CPU s for 20 cases"
