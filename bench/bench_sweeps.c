/* Times the sweeps on one model: a 100-speed Campbell diagram of the lowest 12 modes
 * (sparse shift-invert), a 1000-point FRF (direct), a 1000-speed unbalance response,
 * and one dense full eigen-solve for comparison, on the thread counts given. Prints
 * figures; asserts nothing. usage: bench_sweeps MODEL [THREADS...] */
#include <cblas.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/campbell.h"
#include "geardyn/frf.h"
#include "geardyn/unbalance.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double *linspace(double a, double b, int n)
{
    double *v = malloc((size_t)n * sizeof *v);
    for (int i = 0; i < n; i++)
        v[i] = a + (b - a) * i / (n - 1);
    return v;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_sweeps MODEL [THREADS...]\n");
        return 2;
    }
    gd_error err;
    gd_model *m;
    gd_system *s;
    if (gd_model_load(argv[1], &m, &err) || gd_system_build(m, &s, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    openblas_set_num_threads(1);
    printf("model %s: %d DOFs (%d states)\n", argv[1], s->ndof, 2 * s->ndof);
    double *sp = linspace(0, 12000 * 3.14159265358979 / 30, 100);
    double *fr = linspace(1, 20000, 1000);
    double *usp = linspace(0, 12000 * 3.14159265358979 / 30, 1000);
    int in = gd_system_dof(s, gd_model_find_node(m, "gear48"), GD_X);
    if (in < 0) in = 0;
    gd_probe outs[3] = {{NULL, in, GD_X, "in"},
                        {&gd_element_mesh, 0, GD_X, "mesh"},
                        {&gd_element_bearing, 0, GD_X, "b"}};
    int nouts = m->nmeshes > 0 ? (m->nbearings > 0 ? 3 : 2) : 1;
    int nthr = argc > 2 ? argc - 2 : 1;
    for (int t = 0; t < nthr; t++) {
        int th = argc > 2 ? atoi(argv[2 + t]) : 1;
        gd_campbell_options co;
        gd_campbell_options_init(&co);
        co.speeds = sp;
        co.nspeeds = 100;
        co.nmodes = 12;
        co.nthreads = th;
        /* best of five: the first run also pays for cold caches and fresh pages */
        double tc = 1e30;
        int sparse = 0;
        for (int rep = 0; rep < 5; rep++) {
            gd_campbell_result *cr;
            double t0 = now();
            if (gd_campbell(s, &co, &cr, &err)) {
                fprintf(stderr, "campbell: %s\n", err.message);
                return 1;
            }
            double dt = now() - t0;
            tc = dt < tc ? dt : tc;
            sparse = cr->sparse;
            gd_campbell_free(cr);
        }
        printf("threads %d: campbell 100 speeds x 12 modes (%s) %.3f s (best of 5)\n", th,
               sparse ? "sparse" : "dense", tc);
        gd_frf_options fo;
        gd_frf_options_init(&fo);
        fo.freqs = fr;
        fo.nfreq = 1000;
        fo.inputs = &in;
        fo.ninputs = 1;
        fo.outputs = outs;
        fo.noutputs = nouts;
        fo.speed = 314.16;
        fo.nthreads = th;
        gd_frf_result *frr;
        double t0 = now();
        if (gd_frf(s, &fo, &frr, &err)) {
            fprintf(stderr, "frf: %s\n", err.message);
            return 1;
        }
        printf("threads %d: frf 1000 frequencies, direct, %d outputs %.3f s\n", th, nouts,
               now() - t0);
        gd_frf_free(frr);
        if (m->nunbalances > 0) {
            gd_unbalance_options uo;
            gd_unbalance_options_init(&uo);
            uo.speeds = usp;
            uo.nspeeds = 1000;
            uo.outputs = outs;
            uo.noutputs = nouts;
            uo.nthreads = th;
            gd_unbalance_result *ur;
            t0 = now();
            if (gd_unbalance_response(s, &uo, &ur, &err)) {
                fprintf(stderr, "unbalance: %s\n", err.message);
                return 1;
            }
            printf("threads %d: unbalance 1000 speeds %.3f s\n", th, now() - t0);
            gd_unbalance_free(ur);
        }
    }
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.speed = 314.16;
    mo.nmodes = 0;
    mo.want_left = 0;
    mo.kind = GD_MODAL_DAMPED;
    gd_modal_result *mr;
    double t0 = now();
    if (gd_modal_solve(s, &mo, &mr, &err)) return 1;
    double td = now() - t0;
    printf("dense full eigen-solve at one speed (all %d modes, 1 BLAS thread) %.3f s; x100 speeds "
           "= %.1f s\n",
           mr->nmodes, td, 100 * td);
    gd_modal_free(mr);
    free(sp);
    free(fr);
    free(usp);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
