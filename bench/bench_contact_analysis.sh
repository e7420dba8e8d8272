#!/bin/sh
# Timing of the loaded tooth contact analysis (docs/mesh-stiffness.md, "Loaded contact
# analysis"): helical pair 1 of [JMSTHelical] at 20 deg with tip relief and crowning on both
# gears and 10 um misalignment, 40 slices x 64 positions (energy method): one contact
# analysis (target < 50 ms) and a 20-load Harris map (target < 1 s), against the TVMS
# of the same pair and options timed in the same run (the floor: the contact analysis
# builds the same stiffness law, then solves). Medians of 21 runs. The machine is
# shared: read the ratios, not the absolute times.
# usage: bench/bench_contact_analysis.sh [BUILD_DIR]   (default: build)
set -e
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$SRC/build}
[ -f "$BUILD/libgeardyn.a" ] || { echo "no libgeardyn.a in $BUILD: build first" >&2; exit 2; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cat >"$TMP/bench.c" <<'CEOF'
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "geardyn/mesh_stiffness.h"
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
enum { REP = 21, NL = 20 };
int main(void)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_geometry_init(&g);
    g.gear[0].teeth = 52, g.gear[1].teeth = 72;
    g.normal_module = 1.75e-3, g.face_width = 0.02, g.helix_angle = 20 * 3.14159265358979 / 180;
    for (int i = 0; i < 2; i++) {
        g.gear[i].bore_radius = 12.7e-3;
        g.gear[i].mod.tip_relief.amount = 8e-6;
        g.gear[i].mod.tip_relief.start_roll_angle = 0; /* set below from the diameter */
        g.gear[i].mod.crowning = 3e-6;
    }
    g.gear[0].mod.tip_relief.start_diameter = 0.0985; /* d = 96.85 mm, d_a = 100.35 mm */
    g.gear[1].mod.tip_relief.start_diameter = 0.1355; /* d = 134.1 mm, d_a = 137.6 mm */
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 64, o.slices = 40, o.load_torque = 100, o.misalignment = 10e-6;
    double loads[NL];
    for (int l = 0; l < NL; l++)
        loads[l] = 20 + 20 * l;
    double tt[REP], tc[REP], tm[REP], pp = 0, khb = 0;
    gd_error err;
    for (int i = 0; i < REP; i++) {
        gd_tvms_result *r;
        gd_ltca_result *c;
        gd_ltca_map *m;
        double t0 = now();
        if (gd_tvms_compute(&g, &o, &r, &err)) return 1;
        double t1 = now();
        if (gd_ltca_compute(&g, &o, &c, &err)) return 1;
        double t2 = now();
        if (gd_ltca_map_compute(&g, &o, loads, NL, &m, &err)) return 1;
        double t3 = now();
        tt[i] = t1 - t0, tc[i] = t2 - t1, tm[i] = t3 - t2;
        pp = c->ste_peak_to_peak, khb = c->face_load_factor_cycle;
        gd_tvms_free(r);
        gd_ltca_free(c);
        gd_ltca_map_free(m);
    }
    qsort(tt, REP, sizeof tt[0], cmp);
    qsort(tc, REP, sizeof tc[0], cmp);
    qsort(tm, REP, sizeof tm[0], cmp);
    double T = tt[REP / 2], C = tc[REP / 2], M = tm[REP / 2];
    printf("TVMS (floor)          64 points x 40 slices: median %8.3f ms\n", 1e3 * T);
    printf("contact analysis      64 points x 40 slices: median %8.3f ms  = %.2f x TVMS "
           "(target < 50 ms)  [p-p TE %.3f um, K_Hbeta %.3f at 100 N m]\n",
           1e3 * C, C / T, pp * 1e6, khb);
    printf("Harris map, %d loads  64 points x 40 slices: median %8.3f ms  = %.2f x TVMS "
           "(target < 1 s)\n",
           NL, 1e3 * M, M / T);
    return 0;
}
CEOF
cc -O2 -std=c11 -D_XOPEN_SOURCE=700 -I"$SRC/include" "$TMP/bench.c" "$BUILD/libgeardyn.a" -lm -o "$TMP/bench"
echo "library ($BUILD/libgeardyn.a), helical 52/72 pair, tip relief + crowning, 10 um misalignment:"
"$TMP/bench"
