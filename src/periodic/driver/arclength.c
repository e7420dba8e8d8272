/* The one pseudo-arclength driver (method.h) for every method of the table: Keller's
 * (1977) predictor along the unit tangent in the variables scaled by the method's D and by
 * the requested range, step control by the corrector's iteration count and the turn of the
 * tangent, every requested value hit exactly, the method's bifurcations between steps. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/method.h"

/* Step control by the turn of the tangent and the chord's direction for the step y, lam
 * -> y1, l1 of length ds (tangents t and t1, n unknowns and the parameter, scales D and
 * sl): a step that turned more than ~25 deg, or whose corrector fell back behind the start
 * (retracing a branch past a fold), is retried shorter. 1: retry with half the step; 0:
 * taken (t1 the chord at a corner). *tt_rej: the turn of the last step refused from y (2:
 * none). */
static int refuse_step(const gd_per_arc *a, int n, const double *D, double sl, const double *t,
                       double *t1, const double *y, double lam, const double *y1, double l1,
                       double ds, double *tt_rej)
{
    const double dsmin = a->dsmin;
    double tt = 0.0, tc = 0.0;
    for (int i = 0; i < n; i++) {
        tt += t[i] * t1[i];
        tc += t[i] * (y1[i] - y[i]) / D[i];
    }
    tt += t[n] * t1[n];
    tc += t[n] * (l1 - lam) / sl;
    /* a corrector that went far beyond the step (the chord more than 3 ds, in the scaled
     * variables) jumped to another part of the branch: NLvib's example 03 at H = 3 went
     * from 0.6537 to 0.9146 in 26 iterations on a step of 0.053; the backlash pair at H = 3
     * over 300..2500 rad/s from 354.04 to 428.14 rad/s in 20 iterations, onto the part of
     * its branch already traced (the chord turned there: a false fold at 354.04 and the
     * loop traced twice, seven folds instead of four); by shooting at rtol 1e-11 its step
     * of 0.1 from 362 rad/s landed at 326.5 rad/s with the tangent turned by less than the
     * limit */
    double cc = (l1 - lam) * (l1 - lam) / (sl * sl);
    for (int i = 0; i < n; i++)
        cc += (y1[i] - y[i]) * (y1[i] - y[i]) / (D[i] * D[i]);
    if (sqrt(cc) > 3.0 * ds && ds > 16 * dsmin) return 1;
    /* a corner, not a curve: the turn did not shrink with the halved step (a contact
     * switching at one sample makes the sampled branch piecewise smooth: NLvib's example 03
     * at 1024 samples turns by 27 deg at every step size near its resonance peak). It is
     * taken with the chord as the next direction: the tangent at y1 may still be the other
     * side's. */
    const int corner = a->corners && tt < 0.9 && tc > 0.0 && *tt_rej <= 1.0 && tt <= *tt_rej + 0.02;
    if ((tt < 0.9 || tc <= 0.0) && ds > 16 * dsmin && !corner) {
        *tt_rej = tc > 0.0 ? tt : 2.0;
        return 1;
    }
    *tt_rej = 2.0;
    if (corner) {
        double nc = 0.0;
        for (int i = 0; i < n; i++) {
            t1[i] = (y1[i] - y[i]) / D[i];
            nc += t1[i] * t1[i];
        }
        t1[n] = (l1 - lam) / sl;
        nc = sqrt(nc + t1[n] * t1[n]);
        for (int i = 0; i <= n; i++)
            t1[i] /= nc;
    }
    return 0;
}

/* The requested values the step lam -> l1 crossed, in the step's order (nearest to lam
 * first), each solved at its value from the interpolate, else (near a fold) from either
 * end of the step (yg: work), and emitted or failed. 0 ok, 1 an error. */
static int emit_crossed(const gd_per_arc *a, const double *vals, int nv, int i0, int step, int n,
                        const double *y, double lam, const double *y1, double l1, double *yg)
{
    const gd_per_arc_ops *o = a->ops;
    const int up = vals[nv - 1] >= vals[0]; /* the requested values increase */
    for (int q = 0; q < nv; q++) {
        const int i = (l1 >= lam) == up ? q : nv - 1 - q;
        const double v = vals[i];
        if (i == i0 && step == 0) continue;
        if (!(l1 >= lam ? (v > lam && v <= l1) : (v < lam && v >= l1))) continue;
        const double sig = (v - lam) / (l1 - lam);
        int itg = 0, bad = 1;
        double resg = NAN;
        for (int start = 0; bad && start < 3; start++) {
            for (int k = 0; k < n; k++)
                yg[k] = start == 0 ? (1 - sig) * y[k] + sig * y1[k] : start == 1 ? y[k] : y1[k];
            if (o->begin) o->begin(a->m);
            bad = o->solve_at(a->m, yg, v, &itg, &resg);
        }
        if (bad ? o->fail(a->m, v) : o->emit(a->m, yg, v, itg, resg)) return 1;
    }
    return 0;
}

/* The work arrays of n unknowns (n + 1 each, the parameter last): 0 ok. */
static int work(int n, double **arr[], int na)
{
    for (int i = 0; i < na; i++) {
        free(*arr[i]);
        *arr[i] = calloc((size_t)n + 1, sizeof **arr[i]);
        if (!*arr[i]) return 1;
    }
    return 0;
}

int gd_per_arclength(const gd_per_arc *a, const double *vals, int nv, int i0, double **yio,
                     double lam)
{
    const gd_per_arc_ops *o = a->ops;
    void *m = a->m;
    double *y = *yio, *t = NULL, *t1 = NULL, *y1 = NULL, *yg = NULL, *yp = NULL, *yb = NULL,
           *D = NULL;
    double **arr[5] = {&t1, &y1, &yg, &yp, &yb};
    int n = o->size(m), it = 0, rc = 1;
    double res = NAN;
    const double lend = vals[nv - 1], lstart = vals[i0], sign = lend > lstart ? 1.0 : -1.0;
    const double sl = fabs(lend - lstart);
    double reached = lam;
    if (work(n, arr, 5) || work(n, (double **[]){&t, &D}, 2)) goto done;
    if (o->start(m, y, lam, sign, sl, D, t)) goto stop;
    double lb = lam, tt_rej = 2.0; /* the turn of the last step refused from y (2: none) */
    int have_b = 0, fold_prev = 0;
    double ds = fmin(1.0 / (nv - 1), 0.05), dsmax = fmin(2.0 / (nv - 1), 0.1);
    const int maxsteps = a->max_steps > 0 ? a->max_steps : 50 * nv + 200;
    for (int step = 0;; step++) {
        if (step >= maxsteps) {
            snprintf(a->why, a->why_cap, "continuation stopped after %d steps (raise max_steps)",
                     maxsteps);
            goto stop;
        }
        o->step(m);
        for (int i = 0; i < n; i++)
            yp[i] = y1[i] = y[i] + ds * t[i] * D[i];
        double l1 = yp[n] = lam + ds * t[n] * sl;
        if (o->correct(m, y1, &l1, t, yp, &it, &res) || o->tangent(m, y1, l1, t, sign, t1)) {
            if (o->give_up && o->give_up(m)) goto stop;
            ds *= 0.5;
            if (ds < a->dsmin) goto stop;
            continue;
        }
        if (refuse_step(a, n, D, sl, t, t1, y, lam, y1, l1, ds, &tt_rej)) {
            ds *= 0.5;
            continue;
        }
        o->measure(m, y1, l1);
        if (emit_crossed(a, vals, nv, i0, step, n, y, lam, y1, l1, yg)) goto done;
        const gd_per_arc_step s = {.n = n,
                                   .ds = ds,
                                   .sl = sl,
                                   .D = D,
                                   .yb = yb,
                                   .lb = lb,
                                   .have_b = have_b,
                                   .y = y,
                                   .t = t,
                                   .lam = lam,
                                   .y1 = y1,
                                   .t1 = t1,
                                   .l1 = l1,
                                   .fold_prev = fold_prev};
        const int fold = o->detect(m, &s);
        if (fold < 0) goto done;
        fold_prev = fold;
        lb = lam;
        have_b = 1;
        memcpy(yb, y, (size_t)n * sizeof *y);
        memcpy(y, y1, (size_t)n * sizeof *y);
        memcpy(t, t1, (size_t)(n + 1) * sizeof *t);
        /* the scales follow the orbit's size (a growing resonance does not eat the
         * arclength): the method re-expresses the tangent in them */
        o->rescale(m, y, D, t);
        lam = l1;
        if (sign * (lam - reached) > 0) reached = lam;
        if (a->on_step) a->on_step(lam, a->user);
        if (o->grow) {
            /* a requested point needed more unknowns (harmonics): the branch goes on with
             * them from the last point solved again */
            const int g = o->grow(m, &y, &t, &D, lam, &it);
            if (g < 0) goto done;
            if (g > 0) {
                n = o->size(m);
                if (work(n, arr, 5)) goto done;
                have_b = 0; /* the point before has the old size */
            }
            if (g == 2) goto stop;
        }
        if (it <= 3) ds = fmin(ds * 1.6, dsmax);
        if (it > 6) ds *= 0.6;
        if (sign * (lam - lend) >= 0) break;
        if (sign * (lam - lstart) < -0.5 * sl || (a->speed && lam <= 0)) {
            snprintf(a->why, a->why_cap, "the branch turned back out of the range");
            goto stop;
        }
    }
    rc = 0;
    goto done;
stop:
    /* values beyond the furthest point reached get the reason */
    for (int i = i0 + 1; i < nv; i++)
        if (sign * (vals[i] - reached) > 0 && o->fail(m, vals[i])) goto done;
    rc = 0;
done:
    *yio = y;
    free(t);
    free(t1);
    free(y1);
    free(yg);
    free(yp);
    free(yb);
    free(D);
    return rc;
}
