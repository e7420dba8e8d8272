/* Times the Campbell diagram on one thread with the mode continuation along the sweep
 * (gd_sparse_track, the default) and without it (every speed by shift-invert
 * Krylov-Schur, the reference), counts the speeds continued and the fallbacks, and
 * gives the largest relative difference of the frequencies and damping ratios between
 * the two (each speed's elastic modes compared in order). CPU time, best of REPEATS.
 * Asserts nothing. usage: bench_campbell MODEL NSPEEDS MAX_RPM NMODES [REPEATS] */
#include <cblas.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "campbell/campbell_impl.h"
#include "geardyn/model_file.h"

static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t); /* CPU: the machine is shared */
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

typedef struct eig {
    double mag, re, im;
} eig;

static int cmp_eig(const void *a, const void *b)
{
    const eig *x = a, *y = b;
    return (x->mag > y->mag) - (x->mag < y->mag);
}

/* the elastic modes' eigenvalues at speed s, by |lambda| */
static int speed_modes(const gd_campbell_result *r, int s, eig *e)
{
    int c = 0;
    for (int t = 0; t < r->ntracks; t++) {
        const gd_mode *m = &r->modes[(size_t)t * r->nspeeds + s];
        if (isnan(m->omega_n)) continue;
        e[c++] = (eig){m->omega_n, m->lambda_re, m->lambda_im};
    }
    qsort(e, (size_t)c, sizeof *e, cmp_eig);
    return c;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: bench_campbell MODEL NSPEEDS MAX_RPM NMODES [REPEATS]\n");
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
    int ns = atoi(argv[2]), reps = argc > 5 ? atoi(argv[5]) : 3;
    double *sp = malloc((size_t)ns * sizeof *sp);
    for (int i = 0; i < ns; i++)
        sp[i] = atof(argv[3]) * 3.14159265358979323846 / 30 * i / (ns > 1 ? ns - 1 : 1);
    gd_campbell_options co;
    gd_campbell_options_init(&co);
    co.speeds = sp;
    co.nspeeds = ns;
    co.nmodes = atoi(argv[4]);
    co.nthreads = 1;
    gd_campbell_result *r[2] = {NULL, NULL};
    double best[2] = {1e30, 1e30};
    gd_campbell_stats st[2];
    for (int rep = 0; rep < reps; rep++)
        for (int c = 1; c >= 0; c--) {
            gd_campbell_result *cr;
            double t0 = cpu();
            if (gd_campbell_run(s, &co, c, &st[c], &cr, &err)) {
                fprintf(stderr, "campbell: %s\n", err.message);
                return 1;
            }
            double dt = cpu() - t0;
            if (dt < best[c]) best[c] = dt;
            gd_campbell_free(r[c]);
            r[c] = cr;
        }
    double df = 0, dl = 0;
    int cnt = 0, cap = r[0]->ntracks > r[1]->ntracks ? r[0]->ntracks : r[1]->ntracks;
    eig *e0 = malloc((size_t)(cap > 0 ? cap : 1) * sizeof *e0),
        *e1 = malloc((size_t)(cap > 0 ? cap : 1) * sizeof *e1);
    if (!e0 || !e1) return 1;
    for (int i = 0; i < ns; i++) {
        int n0 = speed_modes(r[0], i, e0), n1 = speed_modes(r[1], i, e1);
        if (n0 != n1) cnt++;
        for (int j = 0; j < n0 && j < n1; j++) {
            df = fmax(df, fabs(e1[j].mag - e0[j].mag) / e0[j].mag);
            dl = fmax(dl, hypot(e1[j].re - e0[j].re, e1[j].im - e0[j].im) / e0[j].mag);
        }
    }
    /* both against the dense (LAPACK) solver at every tenth speed (up to 2000 DOFs) */
    double dd[2] = {0, 0};
    int dense = r[1]->sparse && s->ndof <= 2000;
    for (int i = 0; i < ns && dense; i += 10) {
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.speed = sp[i];
        mo.nmodes = 0;
        mo.want_left = 0;
        mo.kind = GD_MODAL_DAMPED;
        mo.method = GD_EIG_DENSE;
        gd_modal_result *dr;
        if (gd_modal_solve(s, &mo, &dr, &err)) break;
        for (int c = 0; c < 2; c++)
            for (int t = 0; t < r[c]->ntracks; t++) { /* the nearest dense eigenvalue */
                const gd_mode *md = &r[c]->modes[(size_t)t * ns + i];
                if (isnan(md->omega_n)) continue;
                double near = INFINITY;
                for (int q = 0; q < dr->nmodes; q++)
                    if (!dr->modes[q].rigid_body)
                        near = fmin(near, hypot(dr->modes[q].lambda_re - md->lambda_re,
                                                dr->modes[q].lambda_im - md->lambda_im));
                dd[c] = fmax(dd[c], near / md->omega_n);
            }
        gd_modal_free(dr);
    }
    printf("%s: %d DOFs, %d speeds 0-%s rpm, %d modes, one thread (%s)\n", argv[1], s->ndof, ns,
           argv[3], co.nmodes, r[1]->sparse ? "sparse" : "dense");
    printf("  Krylov-Schur at every speed (reference): %.4f s CPU (best of %d)\n", best[0], reps);
    printf("  continuation (default):                  %.4f s CPU: %.2fx faster; %d speeds "
           "continued, %d fallbacks\n",
           best[1], best[0] / best[1], st[1].continued, st[1].fallbacks);
    printf("  agreement: max |df|/f = %.2e, max |d lambda|/|lambda| = %.2e, %d speeds with "
           "another mode count\n",
           df, dl, cnt);
    /* issue 23: ROSS 2.3 took 16.8 s for rig366, 100 speeds, 12 modes, and this
     * Campbell's Krylov-Schur path 0.18 s (93x) on its machine, unloaded */
    printf("  against ROSS's 16.8 s (issue 23, its machine): %.0fx on this run's CPU time; "
           "%.0fx projected from the same-run ratio to Krylov-Schur (93x in the issue)\n",
           16.8 / best[1], 93.0 * best[0] / best[1]);
    if (dense)
        printf("  against the dense solver (every tenth speed): max |d lambda|/|lambda| = %.2e "
               "(Krylov-Schur), %.2e (continuation)\n",
               dd[0], dd[1]);
    free(e0);
    free(e1);
    gd_campbell_free(r[0]);
    gd_campbell_free(r[1]);
    free(sp);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
