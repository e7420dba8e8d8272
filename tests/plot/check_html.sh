#!/usr/bin/env bash
# The HTML plots in a real browser: writes the --plot FILE.html of every analysis and a
# report into BUILD/plot-artefacts, then opens them all in one headless Chromium session
# (check_html.mjs, playwright-core from package.json driving Debian's /usr/bin/chromium):
# no console errors, every plot drawn with its traces, a screenshot FILE.png beside each
# page (the CI artefacts).   usage: check_html.sh BUILD_DIR GEARDYN
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$1 geardyn=$2
out=$build/plot-artefacts
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "chromium is missing: run 'make deps'"; exit 1; }
[ -d node_modules/playwright-core ] || { echo "node_modules is missing: run 'make deps' (npm ci)"; exit 1; }
rm -rf "$out" && mkdir -p "$out"
out=$(cd "$out" && pwd)
g() { "$geardyn" "$@" >/dev/null; }
g modal examples/chen1998_gear_pair.yaml --plot "$out/modal.html"
g campbell examples/kumar2011_coupled.yaml --speeds 0:3000rpm:4 --modes 6 --plot "$out/campbell.html"
g frf examples/chen1998_gear_pair.yaml --input gear_a.xy --output gear_b.xy --freq 100:6000:60 \
  --plot "$out/frf_directional.html"
g unbalance examples/chen1998_gear_pair.yaml --speeds 100:6000:30 --plot "$out/unbalance.html"
g transient examples/ducati_timing_geartrain.yaml --revolutions 0.2 --quiet --plot "$out/transient.html"
g mesh-stiffness examples/rig2018_pair.yaml --cycles 2 --compare-helix 10deg,20deg --plot "$out/mesh_stiffness.html"
g periodic tests/plot/mathieu_pair.yaml --speeds 680:730:11 --harmonics 4 --both-directions \
  --record mesh:m:force --plot "$out/periodic.html"
g transient tests/plot/runup_pair.yaml --sweep-speeds 6800:8400rpm:5 --poincare shaft_a --points 16 \
  --settle 20rev --waterfall gear_a.x --quiet --plot "$out/waterfall.html"
g report tests/plot/study.yaml --speeds 0:6000rpm:9 --freq-points 100 --out "$out/report.html"
# a run-up through a speed ramp, order-tracked (cascade, frequency and order maps, cuts),
# and a report with its run-up waterfall
g transient tests/transient/runup_rotor.yaml --speed-ramp 4000:9000rpm --duration 1s \
  --waterfall gear48.x --revs-per-block 8 --method galpha --step 1e-4 --plot "$out/runup.html"
g report tests/transient/runup_rotor.yaml --speeds 0:9000rpm:7 --freq-points 50 \
  --run-up 4000:9000rpm --run-up-revolutions 100 --out "$out/report_runup.html"
# a planetary set's report (Lin & Parker's set: its drawing, mode classes, a Campbell
# diagram without critical speeds)
g report examples/planetary_lin_parker.yaml --out "$out/report_planetary.html"
# FILE:PLOTS, the plot elements each page must draw (the 3-D view counts as one)
exec node tests/plot/check_html.mjs "$out/modal.html:11" "$out/campbell.html:2" \
  "$out/frf_directional.html:3" "$out/unbalance.html:10" "$out/transient.html:3" \
  "$out/mesh_stiffness.html:4" "$out/periodic.html:3" "$out/waterfall.html:3" "$out/report.html:32" \
  "$out/runup.html:4" "$out/report_runup.html:30" "$out/report_planetary.html:86"
