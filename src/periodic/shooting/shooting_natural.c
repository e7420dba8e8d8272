/* Shooting's bifurcation rule between two points of the natural continuation (--sequential,
 * driver/sequential.c; method.h, between; docs/periodic.md, "Shooting"): where the
 * multipliers cross the unit circle, located by secant iterations on the critical
 * multiplier's modulus, each a shooting solve at fixed value. */
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

/* Bifurcations between two consecutive points of the natural continuation, ya at la and
 * yb at lb, both emitted (the last two points of res): every kind whose largest modulus
 * crossed 1 (method.h, between). 0 ok, 1 an error. */
int gd_per_sh_between(shoot *sh, const double *ya, double la, const double *yb, double lb)
{
    const gd_periodic_result *r = sh->res;
    const gd_periodic_point *pa = &r->points[r->npoints - 2], *pb = &r->points[r->npoints - 1];
    if (!sh->opt->stability || !pb->nmult || !pa->nmult) return 0;
    /* locate works on copies: its solves use sh's work arrays */
    const int N = sh->N;
    double *w = malloc((size_t)(2 * N + 2 * pa->nmult) * sizeof *w);
    if (!w) return 1;
    memcpy(w, ya, (size_t)N * sizeof *w);
    memcpy(w + N, yb, (size_t)N * sizeof *w);
    memcpy(w + 2 * N, pa->mu_re, (size_t)pa->nmult * sizeof *w);
    memcpy(w + 2 * N + pa->nmult, pa->mu_im, (size_t)pa->nmult * sizeof *w);
    int e = detect(sh, la, w, w + 2 * N, w + 2 * N + pa->nmult, pa->nmult, lb, w + N, pb);
    free(w);
    /* locate moved the problem: back to lb's */
    return e || gd_per_sh_problem(sh, lb);
}
