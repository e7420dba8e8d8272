#!/bin/sh
# Cost of the operating point in a Campbell sweep (docs/bearings.md; issue 34): the
# 60-speed Campbell of examples/jeffcott_journal.yaml with speed-dependent journal-bearing
# coefficients (the static equilibrium solved and the bearings linearised at every speed)
# against the floor measured in the same run: the same rotor on linear bearings with the
# coefficients fixed at 10000 rpm, same speeds, same solver, one thread. Target: at most 2x.
# Three measures: CPU time of the process (CLOCK_PROCESS_CPUTIME_ID, medians of 21 runs;
# the machine is shared: read the ratio), the instructions inside gd_campbell counted by
# callgrind (one run each: load-independent), and the CPU time of the whole CLI command
# (`geardyn campbell ... --speeds 500:20000rpm:60`, which also reports the speeds without
# an equilibrium: it used to solve each speed once more from rest to find them).
# usage: bench/bench_campbell_bearings.sh [BUILD_DIR]   (default: build)
set -e
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$SRC/build}
[ -f "$BUILD/libgeardyn.so" ] || { echo "no libgeardyn.so in $BUILD: build first" >&2; exit 2; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cat >"$TMP/bench.c" <<'CEOF'
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "geardyn/geardyn.h"
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static int reps = 21;
static double median_campbell(const gd_system *s, const gd_campbell_options *o)
{
    double t[21];
    for (int k = 0; k < reps; k++) {
        gd_campbell_result *r;
        gd_error err;
        double t0 = now();
        if (gd_campbell(s, o, &r, &err)) { fprintf(stderr, "%s\n", err.message); exit(1); }
        t[k] = now() - t0;
        gd_campbell_free(r);
    }
    qsort(t, (size_t)reps, sizeof *t, cmp);
    return t[reps / 2];
}
int main(int argc, char **argv)
{
    /* argv[2]: "fixed" or "dependent": one Campbell of that kind (for callgrind) */
    const char *only = argc > 2 ? argv[2] : NULL;
    if (only) reps = 1;
    char path[1024];
    snprintf(path, sizeof path, "%s/examples/jeffcott_journal.yaml", argv[1]);
    gd_model *m;
    gd_system *s;
    gd_error err;
    if (gd_model_load(path, &m, &err) || gd_system_build(m, &s, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    double sp[60];
    for (int i = 0; i < 60; i++)
        sp[i] = (500 + 19500 * i / 59.0) * M_PI / 30;
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 60;
    o.nmodes = 0;
    o.nthreads = 1;
    /* the floor: the two bearings' K and C at 10000 rpm as linear bearings */
    double W = 10000 * M_PI / 30, K[4] = {0}, C[4] = {0}, *D = calloc(4, sizeof *D),
           *KK = calloc(4, sizeof *KK);
    gd_system_dense(s, W, NULL, D, KK);
    for (int i = 0; i < 4; i++) {
        K[i] = KK[i] / 2; /* two equal bearings on the one node */
        C[i] = D[i] / 2;
    }
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "dofs: [x, y]\nshafts:\n  - {name: rotor, nodes: [{name: disk}]}\n"
             "disks:\n  - {name: disk, node: disk, mass: 20}\nbearings:\n"
             "  - {name: b1, node: disk, kxx: %.17g, kyx: %.17g, kxy: %.17g, kyy: %.17g,\n"
             "     cxx: %.17g, cyx: %.17g, cxy: %.17g, cyy: %.17g}\n"
             "  - {name: b2, node: disk, kxx: %.17g, kyx: %.17g, kxy: %.17g, kyy: %.17g,\n"
             "     cxx: %.17g, cyx: %.17g, cxy: %.17g, cyy: %.17g}\n",
             K[0], K[1], K[2], K[3], C[0], C[1], C[2], C[3], K[0], K[1], K[2], K[3], C[0], C[1],
             C[2], C[3]);
    gd_model *mf;
    gd_system *sf;
    if (gd_model_load_string(yaml, "fixed.yaml", &mf, &err) || gd_system_build(mf, &sf, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    if (only) {
        median_campbell(strcmp(only, "fixed") ? s : sf, &o);
    } else {
        double tf = median_campbell(sf, &o), td = median_campbell(s, &o);
        printf("60-speed Campbell, jeffcott_journal (2 DOFs), 1 thread, CPU time, medians of 21:\n");
        printf("  fixed coefficients (linear bearings): %8.3f ms (floor)\n", 1e3 * tf);
        printf("  speed-dependent (equilibrium + linearisation per speed): %8.3f ms = %.2f x "
               "floor (target <= 2)\n", 1e3 * td, td / tf);
    }
    free(D);
    free(KK);
    gd_system_free(sf);
    gd_model_free(mf);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
CEOF
cc -O2 -std=c11 -D_XOPEN_SOURCE=700 -I"$SRC/include" -I"$BUILD/include" "$TMP/bench.c" -L"$BUILD" -lgeardyn -Wl,-rpath,"$BUILD" -lm -o "$TMP/bench"
OPENBLAS_NUM_THREADS=1 "$TMP/bench" "$SRC"
if command -v valgrind >/dev/null; then
    for kind in fixed dependent; do
        OPENBLAS_NUM_THREADS=1 valgrind --tool=callgrind --toggle-collect=gd_campbell \
            --callgrind-out-file="$TMP/cg.$kind" "$TMP/bench" "$SRC" $kind >/dev/null 2>"$TMP/cg.$kind.log"
        grep -o 'Collected : [0-9]*' "$TMP/cg.$kind.log" | awk '{print $3}' >"$TMP/ir.$kind"
    done
    awk -v f="$(cat "$TMP/ir.fixed")" -v d="$(cat "$TMP/ir.dependent")" 'BEGIN {
        printf "callgrind, instructions in gd_campbell: fixed %.4g, speed-dependent %.4g = %.2f x floor\n",
               f, d, d / f }'
fi
# the CLI command, CPU time (user + system) of N runs over N, median of 3
cli_cpu() {
    for k in 1 2 3; do
        OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 /usr/bin/time -f '%U %S' sh -c \
            'for i in $(seq $2); do "$0" campbell "$1" --speeds 500:20000rpm:60 --threads 1 >/dev/null || exit 1; done' \
            "$BUILD/geardyn" "$1" "$2" 2>&1 | tail -1 | awk -v n="$2" '{printf "%.4f\n", ($1 + $2) / n}'
    done | sort -g | sed -n 2p
}
if [ -x "$BUILD/geardyn" ] && [ -x /usr/bin/time ]; then
    # the same rotor on the finite-length film (model: 1, each film solution about 3 ms)
    sed 's/clearance: 50 um}/clearance: 50 um, model: 1}/' "$SRC/examples/jeffcott_journal.yaml" \
        >"$TMP/finite.yaml"
    echo "CLI: geardyn campbell MODEL --speeds 500:20000rpm:60 --threads 1, CPU s per run (user + system), median of 3:"
    echo "  examples/jeffcott_journal.yaml (short bearing, 20 runs):  $(cli_cpu "$SRC/examples/jeffcott_journal.yaml" 20) s"
    echo "  the same on the finite-length film (model: 1, 1 run):     $(cli_cpu "$TMP/finite.yaml" 1) s"
fi
