/* Shooting's natural continuation in the value (docs/periodic.md, "Shooting"), and the
 * entry gd_per_shoot_run, which takes the pseudo-arclength (shooting_arclength.c, dense
 * or matrix-free) unless --sequential: each point starts from the previous points' states
 * extrapolated linearly, the first (or one whose Newton fails from there) from a short
 * transient from rest or from the static state under the loads, which a stable orbit
 * attracts. Bifurcations are found between points where the multipliers cross the unit
 * circle and located by secant iterations on the critical multiplier's modulus, each a
 * shooting solve. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/method.h"
#include "periodic/shooting/shooting_impl.h"

/* The critical multiplier of kind k at value key from state y (a shooting solve):
 * |mu| - 1 in *g, the multiplier in (*re, *im). 0 ok. */
static int critical(shoot *sh, double key, double *y, int k, double *g, double *re, double *im)
{
    int it;
    double res;
    int nm;
    if (gd_per_sh_problem(sh, key) || gd_per_sh_newton(sh, y, &it, &res) ||
        (nm = gd_per_sh_multipliers(sh, y, sh->mre, sh->mim)) < 0)
        return 1;
    double gg[3];
    int at[3];
    gd_per_sh_kinds(sh->mre, sh->mim, nm, gg, at);
    /* none of that kind (a complex pair not yet split on the axis): modulus 0 */
    *g = gg[k] - 1.0;
    *re = at[k] >= 0 ? sh->mre[at[k]] : NAN;
    *im = at[k] >= 0 ? sh->mim[at[k]] : NAN;
    return 0;
}

/* A crossing of the unit circle by the multipliers of kind k between (la, ya, ga) and
 * (lb, yb, gb), located by secant iterations (regula falsi with the Illinois rule, a
 * bisection where the secant leaves the bracket) on |mu| - 1 to 1e-8 relative in the
 * value. The located value with |mu| - 1 there in *off, or NAN when a shooting solve failed
 * before the bracket closed. */
static double locate(shoot *sh, int k, double la, const double *ya, double ga, double lb,
                     const double *yb, double gb, double *mre, double *mim, double *off)
{
    const int N = sh->N;
    double *y = malloc((size_t)N * sizeof *y), lx = NAN;
    if (!y) return NAN;
    double a = la, b = lb, fa = ga, fb = gb;
    int side = 0, located = 0;
    *off = INFINITY;
    for (int it = 0; it < 30; it++) {
        double x = b - fb * (b - a) / (fb - fa), g, re, im;
        if (!(x > fmin(a, b) && x < fmax(a, b))) x = 0.5 * (a + b);
        /* start from the nearer end's state, interpolated */
        double s = (x - la) / (lb - la);
        for (int i = 0; i < N; i++)
            y[i] = (1 - s) * ya[i] + s * yb[i];
        if (critical(sh, x, y, k, &g, &re, &im)) break;
        lx = x;
        *off = fabs(g);
        if (isfinite(re)) {
            *mre = re;
            *mim = im;
        }
        if (fabs(g) < 1e-12 || fabs(b - a) <= 1e-8 * fabs(x)) {
            located = 1;
            break;
        }
        if ((g > 0) == (fb > 0)) {
            b = x;
            fb = g;
            if (side == -1) fa *= 0.5;
            side = -1;
        } else {
            a = x;
            fa = g;
            if (side == 1) fb *= 0.5;
            side = 1;
        }
        if (fabs(b - a) <= 1e-8 * fabs(x)) {
            located = 1;
            break;
        }
    }
    free(y);
    return located ? lx : NAN;
}

/* Bifurcations between the previous converged point (la, ya, its multipliers) and this
 * one: every kind whose largest modulus crossed 1. */
static int detect(shoot *sh, double la, const double *ya, const double *ma_re, const double *ma_im,
                  int na, double lb, const double *yb, const gd_periodic_point *pb)
{
    double ga[3], gb[3];
    int aa[3], ab[3];
    gd_per_sh_kinds(ma_re, ma_im, na, ga, aa);
    gd_per_sh_kinds(pb->mu_re, pb->mu_im, pb->nmult, gb, ab);
    static const gd_bifurcation_type type[3] = {GD_BIF_FOLD, GD_BIF_PERIOD_DOUBLING,
                                                GD_BIF_NEIMARK_SACKER};
    for (int k = 0; k < 3; k++) {
        /* a kind absent on one side counts as modulus 0 (a complex pair meets the real
         * axis before one of it leaves through -1 or +1) */
        if ((ga[k] > 1.0) == (gb[k] > 1.0)) continue;
        double re = NAN, im = NAN, off;
        double x = locate(sh, k, la, ya, ga[k] - 1.0, lb, yb, gb[k] - 1.0, &re, &im, &off);
        /* a period doubling or Neimark-Sacker point only where located, its multiplier on
         * the circle to 1e-4 (as on the arclength and in harmonic balance) */
        if (k > 0 && (isnan(x) || !(off < 1e-4))) continue;
        if (isnan(x)) { /* a fold not located (the branch ends there): linearly */
            x = la + (lb - la) * (1.0 - ga[k]) / (gb[k] - ga[k]);
            re = im = NAN;
        }
        /* a real multiplier through +1 on a branch followed in the value is a fold or a
         * branch point: natural continuation cannot tell (it jumps at a fold), so it is
         * reported as the fold it usually is */
        if (gd_per_sh_add_bif(sh, type[k], x, k == 0 ? NAN : re, k == 0 ? NAN : im)) return 1;
    }
    return 0;
}

/* ---------------------------------------------------------------- the branch */

static int run_direction(shoot *sh, const double *vals, int nv)
{
    /* pseudo-arclength (shooting_arclength.c, dense or matrix-free) unless --sequential */
    if (sh->opt->method == GD_PER_ARCLENGTH && nv >= 2 && !gd_per_sh_problem(sh, vals[0]))
        return gd_per_sh_arclength(sh, vals, nv);
    sh->steps += nv;
    const int stab = sh->opt->stability;
    double *ys = NULL; /* the last two converged states, their values */
    double lv[2] = {NAN, NAN};
    int nprev = 0, rc = 1;
    double *mre = NULL, *mim = NULL, *y = NULL;
    int have_mu = 0;
    for (int v = 0; v < nv; v++) {
        double key = vals[v];
        if (gd_per_sh_problem(sh, key)) {
            if (gd_per_sh_fail(sh, key)) goto done;
            nprev = 0;
            continue;
        }
        const int N = sh->N;
        if (!ys) {
            ys = malloc((size_t)5 * N * sizeof *ys);
            if (!ys) goto done;
            y = ys + 2 * (size_t)N;
            mre = y + N;
            mim = mre + N;
        }
        int it = 0, ok = 0;
        double res = NAN;
        sh->work = 0.0;
        sh->t_mono = 0.0;
        sh->warm_change = NAN;
        sh->budget_hit = 0;
        if (nprev) {
            /* predictor: the last state, or the secant through the last two */
            if (nprev == 2) {
                double s = (key - lv[1]) / (lv[1] - lv[0]);
                for (int i = 0; i < N; i++)
                    y[i] = ys[N + i] + s * (ys[N + i] - ys[i]);
            } else { /* one state only: ys[0..N) is not set yet (0 * garbage can be NaN) */
                memcpy(y, ys + N, (size_t)N * sizeof *y);
            }
            ok = !gd_per_sh_newton(sh, y, &it, &res);
        }
        if (!ok && !sh->budget_hit) {
            char first[256];
            snprintf(first, sizeof first, "%s", nprev ? sh->why : "");
            ok = !gd_per_sh_warm(sh, y) && !gd_per_sh_newton(sh, y, &it, &res);
            if (!ok && first[0] && strcmp(first, sh->why)) {
                char both[256];
                snprintf(both, sizeof both, "%.110s; from a transient: %.110s", first, sh->why);
                snprintf(sh->why, sizeof sh->why, "%s", both);
            }
        }
        if (!ok) {
            if (gd_per_sh_fail(sh, key)) goto done;
            nprev = 0;
            have_mu = 0;
            continue;
        }
        if (gd_per_sh_emit(sh, key, y, it, res)) goto done;
        gd_periodic_point *p = &sh->res->points[sh->res->npoints - 1];
        if (stab && p->nmult && have_mu && nprev) {
            /* the previous point's state and multipliers are ys[N..] and mre/mim */
            double *ya = malloc((size_t)2 * N * sizeof *ya);
            if (!ya) goto done;
            memcpy(ya, ys + N, (size_t)N * sizeof *ya);
            memcpy(ya + N, y, (size_t)N * sizeof *ya);
            double la = lv[1];
            int e = detect(sh, la, ya, mre, mim, have_mu, key, ya + N, p);
            free(ya);
            if (e) goto done;
            if (gd_per_sh_problem(sh, key)) goto done; /* locate moved the problem: back */
        }
        p = &sh->res->points[sh->res->npoints - 1];
        have_mu = p->nmult; /* the count of the previous point's multipliers */
        if (have_mu) {
            memcpy(mre, p->mu_re, (size_t)have_mu * sizeof *mre);
            memcpy(mim, p->mu_im, (size_t)have_mu * sizeof *mim);
        }
        if (nprev) memcpy(ys, ys + N, (size_t)N * sizeof *ys);
        lv[0] = lv[1];
        memcpy(ys + N, y, (size_t)N * sizeof *ys);
        lv[1] = key;
        nprev = nprev < 2 ? nprev + 1 : 2;
    }
    rc = 0;
done:
    free(ys);
    return rc;
}

int gd_per_shoot_run(const gd_system *sys, const gd_transient_spec *spec,
                     const gd_periodic_param *param, const double *values, int nvalues,
                     const gd_periodic_options *opt, const gd_tr_record *records, int nrecords,
                     gd_periodic_result *res)
{
    shoot sh;
    memset(&sh, 0, sizeof sh);
    sh.sys0 = sys;
    sh.spec0 = spec;
    sh.param = param;
    sh.opt = opt;
    sh.rec = records;
    sh.nrec = nrecords;
    sh.res = res;
    sh.ndir = opt->both_directions ? 2 : 1;
    double *rev = malloc((size_t)nvalues * sizeof *rev);
    int rc = !rev;
    for (int d = 0; d < sh.ndir && !rc; d++) {
        sh.dir = d ? -1 : 1;
        for (int i = 0; i < nvalues; i++)
            rev[i] = d ? values[nvalues - 1 - i] : values[i];
        sh.v0 = rev[0];
        sh.v1 = rev[nvalues - 1];
        rc = run_direction(&sh, rev, nvalues);
    }
    free(rev);
    res->steps += sh.steps;
    gd_per_sh_free(&sh);
    return rc;
}

/* The method table's row for shooting (method.h). */
gd_status gd_per_shoot_method(const gd_system *sys, const gd_transient_spec *spec,
                              const gd_periodic_param *param, const double *values, int nvalues,
                              const gd_periodic_options *opt, const gd_tr_record *records,
                              int nrecords, gd_periodic_result *res, gd_error *err)
{
    if (gd_per_shoot_run(sys, spec, param, values, nvalues, opt, records, nrecords, res))
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    return GD_OK;
}
