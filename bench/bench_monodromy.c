/* Monodromy benchmark (gd_transient_monodromy): the Chen SFD gear pair (12 states) over
 * one revolution of gear a, against one plain run over the same period (the floor: the
 * augmented system has 13 x 12 unknowns and 1 + 24 RHS evaluations per evaluation), at
 * two tolerances and two speeds, with the largest Floquet multiplier magnitude found by
 * power iteration on Phi.
 * usage: bench_monodromy [MODEL.yaml] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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

/* spectral radius estimate: |Phi^k v|^(1/k) growth over 200 products */
static double radius(int n, const double *P)
{
    double *v = malloc((size_t)n * sizeof *v), *w = malloc((size_t)n * sizeof *w), lg = 0;
    for (int i = 0; i < n; i++)
        v[i] = 1.0 + 0.1 * i;
    for (int it = 0; it < 200; it++) {
        double nn = 0;
        for (int i = 0; i < n; i++) {
            w[i] = 0;
            for (int j = 0; j < n; j++)
                w[i] += P[i + (size_t)j * n] * v[j];
            nn += w[i] * w[i];
        }
        nn = sqrt(nn);
        for (int i = 0; i < n; i++)
            v[i] = w[i] / nn;
        if (it >= 100) lg += log(nn);
    }
    free(v);
    free(w);
    return exp(lg / 100);
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
    const double speeds[2] = {1500, 5500};
    for (int k = 0; k < 2; k++) {
        double W = speeds[k], T = 2 * M_PI / W;
        gd_transient *tr;
        if (gd_transient_new(s, &tm->spec, W, &tr, &err)) return 1;
        int N = gd_transient_nstates(tr), nf = N / 2;
        double *y0 = calloc((size_t)N, sizeof *y0), *phi = malloc((size_t)N * N * sizeof *phi);
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
                   N, W, rtol, 1e3 * mono_s, 1e3 * run_s, mono_s / run_s, radius(N, phi));
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
