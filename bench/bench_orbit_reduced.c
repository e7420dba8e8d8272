/* The periodic orbit of a linear time-periodic model by shooting in the reduced basis
 * (gd_hb_orbit_reduced, floquet_reduced.c; docs/periodic.md, "[JMSTHelical]: Figs. 11-13",
 * "Reduced shooting"): the mean and peak-to-peak of both mesh forces at one speed, the
 * basis size, the largest multiplier and the CPU, for a given step count and cut-off; with
 * H > 0 also harmonic balance at H (public API, no estimate) for comparison.
 * usage: [STEPS_OUT=N] bench_orbit_reduced MODEL RPM STEPS CUTOFF_HZ H [PATH=VALUE]...
 * (STEPS_OUT: the records' grid, finer than the monodromy's STEPS) */
#include <cblas.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/model_file.h"
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "periodic/periodic_impl.h"

static double cpu(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr, "usage: bench_orbit_reduced MODEL RPM STEPS CUTOFF_HZ H [PATH=VALUE]...\n");
        return 2;
    }
    openblas_set_num_threads(1);
    const double W = atof(argv[2]) * 6.28318530717958647692 / 60.0;
    const int steps = atoi(argv[3]), H = atoi(argv[5]);
    const int steps_out = getenv("STEPS_OUT") ? atoi(getenv("STEPS_OUT")) : 0;
    const double wcut = atof(argv[4]) * 6.28318530717958647692;
    gd_load_options lo = {argc - 6, (const char *const *)(argv + 6)};
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_error err;
    if (gd_model_load_opts(argv[1], &lo, &m, &err) || gd_system_build(m, &s, &err) ||
        gd_transient_model_build(s, &tm, &err) || gd_transient_new(s, &tm->spec, W, &tr, &err)) {
        fprintf(stderr, "bench_orbit_reduced: %s\n", err.message);
        return 1;
    }
    double w0 = 0.0;
    int order = 0;
    if (gd_periodic_fundamental(s, &tm->spec, W, &w0, &order, &err)) {
        fprintf(stderr, "bench_orbit_reduced: %s\n", err.message);
        return 1;
    }
    const gd_tr_record rec[4] = {{GD_REC_MESH_FORCE, 0, 0},
                                 {GD_REC_MESH_FORCE, 1, 0},
                                 {GD_REC_MESH_DEFLECTION, 0, 0},
                                 {GD_REC_MESH_DEFLECTION, 1, 0}};
    const int nf = gd_transient_nstates(tr) / 2;
    hb h;
    if (gd_hb_init(&h, nf, 1, 4)) return 1;
    double mean[4], p2p[4], mumax = 0.0;
    int nb = 0;
    char msg[160];
    double t0 = cpu();
    int rc = gd_hb_orbit_reduced(&h, tr, w0, steps, steps_out, wcut, rec, 4, mean, p2p, &nb, &mumax,
                                 msg);
    double t1 = cpu();
    if (rc) {
        fprintf(stderr, "bench_orbit_reduced: failed (%d): %s\n", rc, msg);
        return 1;
    }
    printf("reduced  rpm %7.1f steps %6d cutoff %6.0f Hz basis %3d  mesh1 mean %.6g p2p %.6g  "
           "mesh2 mean %.6g p2p %.6g  |mu|max %.10f  cpu %.3f s\n",
           atof(argv[2]), steps, wcut / 6.28318530717958647692, nb, mean[0], p2p[0], mean[1],
           p2p[1], mumax, t1 - t0);
    if (H > 0) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = H;
        o.estimate = 0;
        o.stability = 0;
        gd_periodic_result *r = NULL;
        t0 = cpu();
        if (gd_periodic_run(s, &tm->spec, NULL, &W, 1, &o, rec, 2, &r, &err)) {
            fprintf(stderr, "bench_orbit_reduced: %s\n", err.message);
            return 1;
        }
        t1 = cpu();
        const gd_periodic_point *p = &r->points[0];
        printf("hb       rpm %7.1f H %5d converged %d  mesh1 mean %.6g p2p %.6g  mesh2 mean %.6g "
               "p2p %.6g  cpu %.3f s\n",
               atof(argv[2]), H, p->converged, p->records[0].mean, p->records[0].peak_to_peak,
               p->records[1].mean, p->records[1].peak_to_peak, t1 - t0);
        gd_periodic_result_free(r);
    }
    gd_hb_free(&h);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
