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

echo "rattle map (examples/studies/rattle_map.yaml, 20 cases of 1.5 s)"
c=$(cpu "$G" study examples/studies/rattle_map.yaml --out "$tmp/map" --threads 1 --quiet)
echo "  $c CPU s for 20 cases"
