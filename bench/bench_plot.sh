#!/usr/bin/env bash
# Timing of plots and reports (docs/plots.md): the cost of --plot over the analysis it
# draws (floor: the same command without --plot, in the same run), and the report of
# the rig with its size. Best of 3 wall-clock runs. Prints figures only.
# usage: bench/bench_plot.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
best() { # best wall time in s of 3 runs of "geardyn ARGS"
    local b=999 s e t
    for _ in 1 2 3; do
        s=$(date +%s.%N); "$B/geardyn" "$@" >/dev/null; e=$(date +%s.%N)
        t=$(echo "$e - $s" | bc -l); (($(echo "$t < $b" | bc -l))) && b=$t
    done
    printf '%.3f' "$b"
}
m="modal examples/rig2018.yaml --speed 3000rpm --modes 12"
floor=$(best $m)
svg=$(best $m --plot "$tmp/m.svg")
html=$(best $m --plot "$tmp/m.html")
echo "modal of the rig (170 DOFs, 12 modes): $floor s; with --plot .svg $svg s ($(echo "$svg / $floor" | bc -l | cut -c1-4)x), .html $html s ($(echo "$html / $floor" | bc -l | cut -c1-4)x)"
echo "  sizes: svg $(stat -c %s "$tmp/m.svg") B, html $(stat -c %s "$tmp/m.html") B"
r=$(best report examples/rig2018.yaml --out "$tmp/r.html")
echo "report of the rig (modes, Campbell 41 speeds, FRF 400 points): $r s, $(stat -c %s "$tmp/r.html") B (plotly.js $(stat -c %s node_modules/plotly.js-gl3d-dist-min/plotly-gl3d.min.js) B of it)"
# PNG and PDF (librsvg + cairo rendering the SVG): their cost over the SVG report
if "$B/geardyn" report examples/rig2018.yaml --out "$tmp/probe.png" >/dev/null 2>&1; then
    rs=$(best report examples/rig2018.yaml --out "$tmp/r.svg")
    rp=$(best report examples/rig2018.yaml --out "$tmp/r.png")
    rd=$(best report examples/rig2018.yaml --out "$tmp/r.pdf")
    echo "report of the rig as .svg $rs s, .png $rp s ($(echo "$rp / $rs" | bc -l | cut -c1-4)x, $(stat -c %s "$tmp/r.png") B), .pdf $rd s ($(echo "$rd / $rs" | bc -l | cut -c1-4)x, $(stat -c %s "$tmp/r.pdf") B)"
fi
# the run-up waterfall: the sweep with --waterfall (finer samples, spectra) and with its
# --plot, over the plain sweep (the floor, same run)
w="transient tests/plot/runup_pair.yaml --sweep-speeds 6000:9000rpm:16 --poincare shaft_a --points 32 --settle 30rev --quiet"
wf=$(best $w)
ww=$(best $w --waterfall gear_a.x)
wh=$(best $w --waterfall gear_a.x --plot "$tmp/w.html")
echo "run-up of the test pair (16 speeds): sweep $wf s; with --waterfall $ww s ($(echo "$ww / $wf" | bc -l | cut -c1-4)x), and its --plot .html $wh s ($(echo "$wh / $wf" | bc -l | cut -c1-4)x), $(stat -c %s "$tmp/w.html") B"
# the report with a run-up waterfall (report --run-up): the rig (no unbalance: a note, no
# run) and the rig with an unbalance (tests/transient/rig_unbalance.yaml: a transient of
# 200 turns, order-tracked), against each one's report without it (the floor, same run)
r0=$(best report examples/rig2018.yaml --out "$tmp/r0.html")
r1=$(best report examples/rig2018.yaml --run-up 0:6000rpm --out "$tmp/r1.html")
u0=$(best report tests/transient/rig_unbalance.yaml --out "$tmp/u0.html")
u1=$(best report tests/transient/rig_unbalance.yaml --run-up 0:6000rpm --out "$tmp/u1.html")
echo "report of the rig: $r0 s, with --run-up 0:6000rpm $r1 s (nothing excites it: a note); with an unbalance $u0 s, with --run-up $u1 s ($(echo "$u1 / $u0" | bc -l | cut -c1-4)x)"
