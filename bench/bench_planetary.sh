#!/bin/sh
# Speed of a planetary set in the linear analyses (docs/planetary.md): `modal` (all modes)
# and `campbell` (11 speeds) of a 5-planet set between two FE shafts against a parallel
# train of the same shafts joined by an idler (the floor, timed in the same run), per DOF.
# CPU time (user + sys, /usr/bin/time), medians of 7 batches of 10 runs; with BENCH_CALLGRIND=1 the
# instruction counts under valgrind's callgrind instead (one run each: deterministic, immune
# to a shared machine's load). Read the ratio, not the absolute figures. Callgrind, 2026-12-02,
# with the per-pattern ordering (src/linalg/ordering.c): modal 0.973, campbell 1.047 (AMD: 1.093).
# usage: [BENCH_CALLGRIND=1] bench/bench_planetary.sh [BUILD_DIR]   (default: build)
set -e
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$SRC/build}
CLI=$BUILD/geardyn
[ -x "$CLI" ] || { echo "no geardyn in $BUILD: build first" >&2; exit 2; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
SHAFTS='materials:
  steel: {density: 7850, E: 210 GPa, poisson: 0.3}
dofs: [x, y, rx, ry, rz]
speed: 1000 rpm
shafts:
  - name: input
    material: steel
    sections: [{length: 0.4, outer_diameter: 40 mm, elements: 20}]
    nodes: [{name: in0, at: 0}, {name: in1, at: 0.1}, {name: sun, at: 0.4}]
  - name: output
    material: steel
    sections: [{length: 0.4, outer_diameter: 60 mm, elements: 20}]
    nodes: [{name: carrier, at: 0}, {name: out1, at: 0.3}, {name: out2, at: 0.4}]
bearings:
  - {node: in0, k: 1e9 N/m}
  - {node: in1, k: 1e9 N/m}
  - {node: out1, k: 1e9 N/m}
  - {node: out2, k: 1e9 N/m}
springs:
  - {node: out2, dof: rz, stiffness: 1e4 N*m/rad}
disks:
  - {node: in0, mass: 5, polar_inertia: 0.02}
  - {node: out2, mass: 8, polar_inertia: 0.05}'
# the set (module 2 mm, Z = 30 / 60 / 15, (30 + 60) / 5 whole), its ring a lumped shaft
cat >"$TMP/planetary.yaml" <<YEOF
$(echo "$SHAFTS" | sed 's/^bearings:/  - {name: housing, nodes: [{name: ring}]}\nbearings:/')
  - {node: sun, mass: 0.5, polar_inertia: 1e-4}
  - {node: carrier, mass: 3, polar_inertia: 0.01}
planetary_sets:
  - name: ps
    held: ring
    sun: {node: sun}
    ring: {node: ring, mass: 2, inertia: 0.01, k_support: 1e8, k_torsion: 1e8}
    carrier: {node: carrier}
    planets: {count: 5, mass: 0.4, inertia: 1.5e-4, bearing_stiffness: 1e8}
    teeth: {sun: 30, ring: 60, planet: 15}
    base_radius: {sun: 28.1908 mm, ring: 56.3816 mm, planet: 14.0954 mm}
    carrier_radius: 45 mm
    pressure_angle: 20 deg
    mesh_stiffness: {sun: 4e8, ring: 5e8}
YEOF
cat >"$TMP/parallel.yaml" <<YEOF
$(echo "$SHAFTS" | sed 's/^bearings:/  - name: idler\n    material: steel\n    sections: [{length: 0.1, outer_diameter: 30 mm, elements: 2}]\n    nodes: [{name: idl, at: 0.05}]\nbearings:\n  - {node: idler@0, k: 1e9 N\/m}\n  - {node: idler@2, k: 1e9 N\/m}/')
  - {node: sun, mass: 0.5, polar_inertia: 1e-4}
  - {node: carrier, mass: 3, polar_inertia: 0.01}
  - {node: idl, mass: 1, polar_inertia: 1e-3}
meshes:
  - {name: m1, driver: sun, driven: idl, base_radius: [20 mm, 20 mm], stiffness: 4e8}
  - {name: m2, driver: idl, driven: carrier, base_radius: [20 mm, 45 mm], stiffness: 4e8, line_of_centres: 180 deg}
YEOF
median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
time_of() { # file, command args...: CPU seconds, or instructions with BENCH_CALLGRIND=1
    f=$1; shift
    if [ "${BENCH_CALLGRIND:-0}" = 1 ]; then
        OPENBLAS_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null \
            "$CLI" "$@" "$f" 2>&1 >/dev/null | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
        return
    fi
    # batches of 10 runs (the CPU clock counts in 10 ms), per run
    for i in 1 2 3 4 5 6 7; do
        OPENBLAS_NUM_THREADS=1 /usr/bin/time -f '%U %S' -o "$TMP/time" sh -c \
            'for j in 1 2 3 4 5 6 7 8 9 10; do "$@" >/dev/null; done' sh "$CLI" "$@" "$f"
        awk '{print ($1 + $2) / 10}' "$TMP/time"
    done | median
}
unit=$([ "${BENCH_CALLGRIND:-0}" = 1 ] && echo "instr" || echo "s CPU")
dofs() { OPENBLAS_NUM_THREADS=1 "$CLI" modal "$1" --json | sed -n 's/.*"dofs":[[:space:]]*\([0-9]*\).*/\1/p' | head -1; }
np=$(dofs "$TMP/planetary.yaml"); nq=$(dofs "$TMP/parallel.yaml")
for what in "modal --modes all" "campbell --speeds 0:3000rpm:11 --threads 1"; do
    tp=$(time_of "$TMP/planetary.yaml" $what); tq=$(time_of "$TMP/parallel.yaml" $what)
    printf '%-44s planetary %.6g %s (%d DOFs)  parallel %.6g %s (%d DOFs)  per-DOF ratio %.3f\n' \
        "$what" "$tp" "$unit" "$np" "$tq" "$unit" "$nq" "$(echo "($tp / $np) / ($tq / $nq)" | bc -l)"
done
