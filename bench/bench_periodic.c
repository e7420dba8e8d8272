/* Harmonic balance timings (bench/bench_periodic.sh): CPU per continuation step and per
 * requested point of `geardyn periodic` on a model, with and without the Floquet
 * multipliers, against a floor measured in the same run: the local force evaluation
 * over one period's AFT samples (the least any HB iteration must do).
 * usage: bench_periodic MODEL FROM TO COUNT H [STABILITY 0|1] [SOLVER 0|1|2] [PATH=VALUE]...
 * (SOLVER: 0 automatic, 1 whole sparse LU, 2 low-rank condensation). */
#include <cblas.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/model_file.h"
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"

static double cpu(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr,
                "usage: bench_periodic MODEL FROM TO COUNT H [STAB] [SOLVER] [PATH=VALUE]...\n");
        return 2;
    }
    openblas_set_num_threads(1);
    double from = atof(argv[2]), to = atof(argv[3]);
    int count = atoi(argv[4]), H = atoi(argv[5]), stab = argc > 6 ? atoi(argv[6]) : 1;
    int solver = argc > 7 ? atoi(argv[7]) : 0;
    gd_load_options lo = {argc > 8 ? argc - 8 : 0, (const char *const *)(argv + 8)};
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_error err;
    if (gd_model_load_opts(argv[1], &lo, &m, &err) || gd_system_build(m, &s, &err) ||
        gd_transient_model_build(s, &tm, &err)) {
        fprintf(stderr, "bench_periodic: %s\n", err.message);
        return 1;
    }
    double *v = malloc((size_t)count * sizeof *v);
    for (int i = 0; i < count; i++)
        v[i] = count > 1 ? from + (to - from) * i / (count - 1) : from;
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = H;
    o.stability = stab;
    o.solver = solver;
    /* the truncation estimate (a solution at 2 H + 1 per point) is per point, not per
     * step: off unless GD_BENCH_ESTIMATE=1, so the step cost stays comparable */
    o.estimate = getenv("GD_BENCH_ESTIMATE") ? atoi(getenv("GD_BENCH_ESTIMATE")) : 0;
    gd_periodic_result *r = NULL;
    double t0 = cpu();
    if (gd_periodic_run(s, &tm->spec, NULL, v, count, &o, NULL, 0, &r, &err)) {
        fprintf(stderr, "bench_periodic: %s\n", err.message);
        return 1;
    }
    double t = cpu() - t0;
    int conv = 0;
    for (int i = 0; i < r->npoints; i++)
        conv += r->points[i].converged;
    /* floor: the local forces at the AFT samples of one period (N = 4 (H + 1) -> 2^k) */
    gd_transient *tr = NULL;
    if (gd_transient_new(s, &tm->spec, v[0], &tr, &err)) return 1;
    int ns = gd_transient_nstates(tr), N = 16;
    while (N < 4 * (H + 1))
        N *= 2;
    double *y = calloc((size_t)ns, sizeof *y), *f = calloc((size_t)ns, sizeof *f);
    int reps = 0;
    double f0 = cpu(), tf;
    do {
        for (int j = 0; j < N; j++)
            gd_transient_local(tr, 1e-4 * j, y, f, NULL, NULL);
        reps++;
    } while ((tf = cpu() - f0) < 0.2);
    double floor_s = tf / reps;
    printf("model %s: %d free DOFs, H = %d (%d unknowns), %s, solver %s\n", argv[1], ns / 2, H,
           ns / 2 * (2 * H + 1), stab ? "Floquet on" : "Floquet off",
           solver == 1   ? "sparse LU"
           : solver == 2 ? "low-rank"
                         : "automatic");
    printf("  %d requested values, %d points (%d converged), %d continuation steps, %d "
           "bifurcations\n",
           count, r->npoints, conv, r->steps, r->nbifurcations);
    if (r->npoints && r->points[r->npoints - 1].converged)
        printf("  last point: X[0..2] = %.12g %.12g %.12g, residual %.2e\n",
               r->points[r->npoints - 1].coef[0], r->points[r->npoints - 1].coef[1],
               r->points[r->npoints - 1].coef[2], r->points[r->npoints - 1].residual);
    printf("  total %.3f s CPU; per continuation step %.3f ms; per point %.3f ms\n", t,
           1e3 * t / (r->steps > 0 ? r->steps : 1), 1e3 * t / (r->npoints ? r->npoints : 1));
    printf("  floor (local forces at the %d AFT samples): %.4f ms; step / floor = %.0f\n", N,
           1e3 * floor_s, t / (r->steps > 0 ? r->steps : 1) / floor_s);
    free(y);
    free(f);
    free(v);
    gd_transient_free(tr);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
