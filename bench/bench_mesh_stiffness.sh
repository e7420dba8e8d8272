#!/bin/sh
# Timing of the mesh-stiffness computation: one mesh cycle at 360 points with 50 slices
# (energy method, helical pair 1 of [JMSTHelical] at 20 deg), by a small C driver compiled
# against the built library, and end to end through the CLI. Prints figures only.
# usage: bench/bench_mesh_stiffness.sh [BUILD_DIR]   (default: build-ms, else build)
set -e
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-}
if [ -z "$BUILD" ]; then
    if [ -f "$SRC/build-ms/libgeardyn.a" ]; then BUILD="$SRC/build-ms"; else BUILD="$SRC/build"; fi
fi
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
int main(void)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_geometry_init(&g);
    g.gear[0].teeth = 52, g.gear[1].teeth = 72;
    g.normal_module = 1.75e-3, g.face_width = 0.02, g.helix_angle = 20 * 3.14159265358979 / 180;
    g.gear[0].bore_radius = g.gear[1].bore_radius = 12.7e-3;
    static const char *const names[4] = {"energy", "iso6336", "single-pair-law", "square"};
    for (int m = 0; m < 4; m++) {
        gd_tvms_options o;
        gd_tvms_options_init(&o);
        o.method = (gd_tvms_method)m, o.points = 360, o.slices = 50, o.cycles = 1;
        enum { REP = 21 };
        double t[REP], mean = 0;
        for (int i = 0; i < REP; i++) {
            gd_tvms_result *r;
            gd_error err;
            double t0 = now();
            if (gd_tvms_compute(&g, &o, &r, &err)) return 1;
            t[i] = now() - t0;
            mean = r->mean;
            gd_tvms_free(r);
        }
        qsort(t, REP, sizeof t[0], cmp);
        printf("%-16s 1 cycle, 360 points, 50 slices: min %8.3f ms  median %8.3f ms  (mean k %.4g N/m)\n",
               names[m], 1e3 * t[0], 1e3 * t[REP / 2], mean);
    }
    return 0;
}
CEOF
cc -O2 -std=c11 -D_XOPEN_SOURCE=700 -I"$SRC/include" "$TMP/bench.c" "$BUILD/libgeardyn.a" -lm -o "$TMP/bench"
echo "library ($BUILD/libgeardyn.a):"
"$TMP/bench"
echo "CLI end to end (load YAML, compute, print JSON), 10 runs:"
t0=$(date +%s.%N)
for i in 1 2 3 4 5 6 7 8 9 10; do
    "$BUILD/geardyn" mesh-stiffness "$SRC/examples/helical_pair1.yaml" --points 360 --slices 50 --json >/dev/null
done
t1=$(date +%s.%N)
echo "$t0 $t1" | awk '{printf "  %.1f ms per run\n", ($2 - $1) * 100}'
