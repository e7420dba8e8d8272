/* Monodromy benchmark (gd_transient_monodromy): the Chen SFD gear pair (12 states) over
 * one revolution of gear a, against one plain run over the same period (the floor: the
 * augmented system has 13 x 12 unknowns and 1 + 24 RHS evaluations per evaluation), at
 * two tolerances and two speeds, with the largest Floquet multiplier magnitude.
 * usage: bench_monodromy [MODEL.yaml]
 *        bench_monodromy MODEL.yaml UNBALANCE_SCALE REVS W...   (study: every multiplier
 *        above 0.5 of the orbit reached after REVS revolutions from rest at each W) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lapacke.h>

#include "geardyn/transient_model.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Floquet multipliers: eigenvalues of Phi (LAPACK dgeev); returns the largest modulus. */
static double multipliers(int n, const double *P, double *wr, double *wi)
{
    double *A = malloc((size_t)n * n * sizeof *A), mx = 0;
    memcpy(A, P, (size_t)n * n * sizeof *A);
    LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n, A, n, wr, wi, NULL, 1, NULL, 1);
    for (int i = 0; i < n; i++)
        mx = fmax(mx, hypot(wr[i], wi[i]));
    free(A);
    return mx;
}

/* Study mode: the orbit at W after `revs` revolutions from rest with the unbalances
 * scaled, and all its multipliers. */
static int study(const gd_system *s, const gd_transient_model *tm, double W, double revs)
{
    gd_error err;
    gd_transient *tr;
    if (gd_transient_new(s, &tm->spec, W, &tr, &err)) return 1;
    int N = gd_transient_nstates(tr), nf = N / 2;
    double T = 2 * M_PI / W, *y0 = calloc((size_t)N, sizeof *y0),
           *phi = malloc((size_t)N * N * sizeof *phi), *y1 = malloc((size_t)N * sizeof *y1);
    double *wr = malloc((size_t)N * sizeof *wr), *wi = malloc((size_t)N * sizeof *wi);
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = revs * T;
    o.record_from = o.t_end;
    o.rtol = 1e-9;
    o.atol_q = 1e-15;
    o.atol_v = 1e-12;
    gd_transient_result *r = NULL;
    if (gd_transient_run(tr, &o, NULL, 0, &r, &err)) return 1;
    for (int i = 0; i < nf; i++) {
        y0[i] = r->q_end[r->ndof - nf + i];
        y0[nf + i] = r->v_end[r->ndof - nf + i];
    }
    gd_transient_result_free(r);
    if (gd_transient_monodromy(tr, o.t_end, T, y0, &o, phi, y1, &err)) return 1;
    double dy = 0, ny = 0;
    for (int i = 0; i < N; i++) {
        dy = fmax(dy, fabs(y1[i] - y0[i]));
        ny = fmax(ny, fabs(y0[i]));
    }
    printf("W = %g rad/s: orbit closes to %.2e of max|y| after %g revolutions; multipliers:", W,
           dy / ny, revs);
    multipliers(N, phi, wr, wi);
    for (int i = 0; i < N; i++)
        if (hypot(wr[i], wi[i]) > 0.5)
            printf(" %.5f%+.5fi (|%.5f|)", wr[i], wi[i], hypot(wr[i], wi[i]));
    printf("\n");
    free(y0);
    free(phi);
    free(y1);
    free(wr);
    free(wi);
    gd_transient_free(tr);
    return 0;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "examples/chen1998_gear_pair.yaml";
    gd_error err;
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    if (gd_model_load(path, &m, &err) || gd_system_build(m, &s, &err) ||
        gd_transient_model_build(s, &tm, &err)) {
        fprintf(stderr, "bench_monodromy: %s\n", err.message);
        return 1;
    }
    if (argc > 4) {
        gd_transient_model_free(tm);
        gd_system_free(s);
        for (int i = 0; i < m->nunbalances; i++)
            m->unbalances[i].amount *= atof(argv[2]);
        if (gd_system_build(m, &s, &err) || gd_transient_model_build(s, &tm, &err)) return 1;
        for (int k = 4; k < argc; k++)
            if (study(s, tm, atof(argv[k]), atof(argv[3]))) return 1;
        gd_transient_model_free(tm);
        gd_system_free(s);
        gd_model_free(m);
        return 0;
    }
    const double speeds[2] = {1500, 5500};
    for (int k = 0; k < 2; k++) {
        double W = speeds[k], T = 2 * M_PI / W;
        gd_transient *tr;
        if (gd_transient_new(s, &tm->spec, W, &tr, &err)) return 1;
        int N = gd_transient_nstates(tr), nf = N / 2;
        double *y0 = calloc((size_t)N, sizeof *y0), *phi = malloc((size_t)N * N * sizeof *phi);
        double wr[64], wi[64];
        gd_transient_options o;
        gd_transient_options_init(&o);
        o.t_end = 200 * T;
        o.record_from = o.t_end;
        gd_transient_result *r = NULL;
        if (gd_transient_run(tr, &o, NULL, 0, &r, &err)) return 1;
        for (int i = 0; i < nf; i++) {
            y0[i] = r->q_end[r->ndof - nf + i];
            y0[nf + i] = r->v_end[r->ndof - nf + i];
        }
        gd_transient_result_free(r);
        for (int t = 0; t < 2; t++) {
            double rtol = t ? 1e-10 : 1e-8;
            o.rtol = rtol;
            o.atol_q = 1e-6 * rtol;
            o.atol_v = 1e-3 * rtol;
            /* floor: one plain run over the period from the same state */
            double *q0 = calloc((size_t)s->ndof, sizeof *q0),
                   *v0 = calloc((size_t)s->ndof, sizeof *v0);
            for (int i = 0; i < nf; i++) {
                q0[s->ndof - nf + i] = y0[i];
                v0[s->ndof - nf + i] = y0[nf + i];
            }
            gd_transient_options p = o;
            p.t_start = 200 * T;
            p.t_end = 201 * T;
            p.record_from = p.t_end;
            p.init = GD_TR_INIT_GIVEN;
            p.q0 = q0;
            p.v0 = v0;
            int reps = 20;
            double t0 = now();
            for (int i = 0; i < reps; i++) {
                if (gd_transient_run(tr, &p, NULL, 0, &r, &err)) return 1;
                gd_transient_result_free(r);
            }
            double run_s = (now() - t0) / reps;
            t0 = now();
            for (int i = 0; i < reps; i++)
                if (gd_transient_monodromy(tr, 200 * T, T, y0, &o, phi, NULL, &err)) return 1;
            double mono_s = (now() - t0) / reps;
            printf("Chen SFD pair, %d states, W = %g rad/s, rtol %g: monodromy %.3g ms, one run "
                   "over the period %.3g ms, ratio %.1f; max |Floquet multiplier| %.6f\n",
                   N, W, rtol, 1e3 * mono_s, 1e3 * run_s, mono_s / run_s,
                   multipliers(N, phi, wr, wi));
            free(q0);
            free(v0);
        }
        free(y0);
        free(phi);
        gd_transient_free(tr);
    }
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
