#!/usr/bin/env bash
# Regenerates docs/figures: the HTML plots of the rig, the Kumar pair and the two-stage
# gearbox (tests/plot/gearbox_two_stage.yaml), each figure shot in headless Chromium
# (figures.mjs). Not a test: run by hand after changing a figure, then look at them.
#   usage: tests/plot/figures.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
G=${1:-build}/geardyn
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
F=docs/figures
mkdir -p "$F"
g() { "$G" "$@" >/dev/null; }
RIG=examples/rig2018.yaml KUM=examples/kumar2011_coupled.yaml GB=tests/plot/gearbox_two_stage.yaml
g modal $RIG --speed 3000rpm --modes 8 --plot "$tmp/rig_modal.html"
g campbell $RIG --speeds 0:12000rpm:41 --modes 8 --max-frequency 600 \
  --operating-range 2500:3500rpm --plot "$tmp/rig_campbell.html"
g frf $RIG --input torque:gear48 --output mesh:mesh --output brg_d1.y --freq 10:3000Hz:300 \
  --speed 3000rpm --plot "$tmp/rig_frf.html"
g mesh-stiffness examples/rig2018_pair.yaml --cycles 2 --plot "$tmp/rig_tvms.html"
g report $RIG --speed 3000rpm --out "$tmp/rig_report.html"
g modal $KUM --plot "$tmp/kumar_modal.html"
g campbell $KUM --speeds 0:3000rpm:31 --max-frequency 120 --plot "$tmp/kumar_campbell.html"
g frf $KUM --input torque:motor --output mesh:mesh --output pinion.y --freq 1:200Hz:400 \
  --plot "$tmp/kumar_frf.html"
g unbalance $KUM --speeds 100:3000rpm:60 --plot "$tmp/kumar_unbalance.html"
g report $KUM --out "$tmp/kumar_report.html"
g modal $GB --modes 12 --plot "$tmp/gearbox_modal.html"
g campbell $GB --speeds 0:6000rpm:31 --modes 16 --max-frequency 800 \
  --operating-range 2700:3300rpm --plot "$tmp/gearbox_campbell.html"
g mesh-stiffness examples/helical_pair1.yaml --cycles 2 --plot "$tmp/gearbox_tvms.html"
g report $GB --speeds 0:6000rpm:21 --modes 12 --out "$tmp/gearbox_report.html"
g transient examples/ducati_timing_geartrain.yaml --revolutions 0.2 --quiet \
  --plot "$tmp/transient.html"
g periodic tests/plot/mathieu_pair.yaml --speeds 680:730:11 --harmonics 4 --both-directions \
  --record mesh:m:force --plot "$tmp/periodic.html"
g periodic examples/helical_two_stage.yaml --speeds 2000rpm:4000rpm:21 --harmonics 36 --no-estimate \
  --no-stability --record mesh:pair1:force --plot "$tmp/gearbox_periodic.html"
g transient tests/plot/runup_pair_te.yaml --sweep-speeds 6000:9000rpm:16 --poincare shaft_a \
  --points 32 --settle 30rev --waterfall gear_a.x --quiet --plot "$tmp/waterfall.html"
g transient tests/plot/runup_pair_te.yaml --speed-ramp 6000:9000rpm --duration 2s --revs-per-block 8 \
  --waterfall gear_a.x --method galpha --step 5e-5 --quiet --plot "$tmp/ramp.html"
node tests/plot/figures.mjs \
  "$tmp/rig_modal.html:$F/rig_modal.png:0" \
  "$tmp/rig_modal.html:$F/rig_modal_3d_orbits.png:~whirl of the mode:3" \
  "$tmp/rig_campbell.html:$F/rig_campbell.png:0" \
  "$tmp/rig_frf.html:$F/rig_frf_bode.png:0" "$tmp/rig_frf.html:$F/rig_frf_nyquist.png:2" \
  "$tmp/rig_tvms.html:$F/rig_mesh_stiffness.png:0" \
  "$tmp/rig_report.html:$F/rig_report.png:top" "$tmp/rig_report.html:$F/rig_report_model.png:0" \
  "$tmp/kumar_modal.html:$F/kumar_modal.png:0" \
  "$tmp/kumar_campbell.html:$F/kumar_campbell.png:0" \
  "$tmp/kumar_frf.html:$F/kumar_frf_bode.png:0" "$tmp/kumar_frf.html:$F/kumar_frf_nyquist.png:2" \
  "$tmp/kumar_unbalance.html:$F/kumar_unbalance.png:0" \
  "$tmp/kumar_report.html:$F/kumar_report.png:top" \
  "$tmp/gearbox_modal.html:$F/gearbox_modal_torsional.png:0" \
  "$tmp/gearbox_modal.html:$F/gearbox_modal_motor_tilt.png:~mode 6:" \
  "$tmp/gearbox_campbell.html:$F/gearbox_campbell.png:0" \
  "$tmp/gearbox_tvms.html:$F/gearbox_mesh_stiffness.png:0" \
  "$tmp/gearbox_report.html:$F/gearbox_report.png:top" \
  "$tmp/gearbox_report.html:$F/gearbox_report_model.png:0" \
  "$tmp/transient.html:$F/transient.png:0" \
  "$tmp/periodic.html:$F/periodic.png:0" \
  "$tmp/gearbox_periodic.html:$F/gearbox_periodic_orders.png:1" \
  "$tmp/waterfall.html:$F/runup_waterfall_cascade.png:0" \
  "$tmp/waterfall.html:$F/runup_waterfall_map.png:1" \
  "$tmp/waterfall.html:$F/runup_order_cuts.png:2" \
  "$tmp/ramp.html:$F/runup_ramp_cascade.png:0" "$tmp/ramp.html:$F/runup_ramp_order_map.png:2" \
  "$tmp/ramp.html:$F/runup_ramp_order_cuts.png:3"
ls -l "$F"/*.png | awk '{print $5, $9}'
