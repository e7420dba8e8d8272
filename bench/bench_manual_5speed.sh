#!/usr/bin/env bash
# The 800 rpm idle transient of examples/manual_5speed.yaml (issue 37: idlers as elements,
# 3rd gear engaged, 6 backlash meshes; docs/rattle.md): CPU seconds per simulated second
# by `geardyn transient --rattle --start static` (BDF, contact changes located) at the
# firing amplitudes 1 N m (four idlers rattling) and 0.4 N m (below the onset), against
# the floor measured in the same run: the same model and run without backlash. Accuracy:
# the rattle metrics of 5th gear's mesh at rtol 1e-6 against a tight reference at rtol
# 1e-9 over the same window. Prints figures only. usage: bench/bench_manual_5speed.sh [BUILD]
set -euo pipefail
cd "$(dirname "$0")/.."
B=$(cd "${1:-build}" && pwd)
G="$B/geardyn"
M=examples/manual_5speed.yaml
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OPENBLAS_NUM_THREADS=1
cpu() { /usr/bin/time -f "%U %S" -o "$tmp/cpu" "$@" > "$tmp/out.json"; awk '{ printf "%.3f", $1 + $2 }' "$tmp/cpu"; }
metric() { python3 -c "
import json, sys
o = json.load(open('$tmp/out.json'))
r = [m for m in o['rattle']['meshes'] if m['name'] == 'gear5'][0]
k = sys.argv[1]
print('%.4g +- %.2g' % (r[k]['mean'], r[k]['half_width']))" "$1"; }

D=3
FROM=1
RUN="--duration $D --from $FROM --start static --rattle --json"
sed '/backlash:/d' "$M" > "$tmp/floor.yaml"
echo "CPU s per simulated s ($D s runs, metrics over the last $((D - FROM)) s)"
for amp in 1 0.4; do
    c=$(cpu "$G" transient "$M" $RUN --set excitations.loads.firing.amplitude=$amp)
    ev=$(python3 -c "import json; print(json.load(open('$tmp/out.json'))['events'])")
    f=$(cpu "$G" transient "$tmp/floor.yaml" --duration $D --from $FROM --start static --json \
        --set excitations.loads.firing.amplitude=$amp)
    printf "  firing %-4s N m: %7.3f s/s  (%s contact events; floor without backlash %.3f s/s, ratio %.1f)\n" \
        "$amp" "$(echo "$c / $D" | bc -l)" "$ev" "$(echo "$f / $D" | bc -l)" \
        "$(echo "$c / ($f + 0.001)" | bc -l)"
done
echo "accuracy: gear5 mesh at 1 N m, rtol 1e-6 against 1e-9"
for rtol in 1e-6 1e-9; do
    c=$(cpu "$G" transient "$M" $RUN --rtol $rtol)
    echo "  rtol $rtol: $c CPU s; separated $(metric separated_fraction), drive /s $(metric drive_impacts_per_s), intensity W $(metric intensity_w)"
done
