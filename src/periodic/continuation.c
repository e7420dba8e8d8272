/* The continuation driver (continuation_impl.h): pseudo-arclength (Keller 1977) or
 * sequential steps from the first requested value to the last, step control by the
 * corrector's iteration count, every requested value hit exactly, adaptive H. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/continuation_impl.h"
#include "periodic/periodic_impl.h"

/* The first requested value that converges, from rest or from a warm start (the ones
 * before it fail with the reason): its index (nv: none), its solution in *X, or -1 when
 * a failure could not be recorded. */
static int first_point(ctx *c, const double *vals, int nv, double **X, double *lam, int *it,
                       double *res)
{
    int i0;
    for (i0 = 0; i0 < nv; i0++) {
        *lam = vals[i0];
        memset(*X, 0, (size_t)(c->h.n + 1) * sizeof **X);
        if (!gd_per_get_stage(c, *lam) || (gd_per_solve_fixed(c, X, NULL, *lam, it, res, 1) &&
                                           gd_per_solve_warm(c, *X, *lam, it, res))) {
            if (gd_per_fail_point(c, *lam, c->reason)) return -1;
            continue;
        }
        break;
    }
    return i0;
}

/* --sequential: each requested value after vals[i0] (X solved at lam, n unknowns) from
 * the secant through the last two solutions (the plain last solution if the secant
 * start fails): on a smooth curve its error is second order in the step (the
 * [JMSTHelical] curve: starting residual 4.5e-3 -> 1e-3, Newton iterations 601 -> 584
 * over 300 speeds). 0 done, 1 an error. */
static int sequential(ctx *c, const double *vals, int nv, int i0, double **Xio, double lam, int n)
{
    double *X = *Xio;
    int it = 0;
    double res = NAN;
    int rc = 1;
    double *Xp = NULL, lamx = lam, lamp = lam;
    for (int i = i0 + 1; i < nv; i++) {
        double *Xs = malloc((size_t)(c->h.n + 1) * sizeof *Xs);
        if (!Xs) {
            free(Xp);
            goto done;
        }
        memcpy(Xs, X, (size_t)(c->h.n + 1) * sizeof *Xs);
        c->steps++;
        int staged = gd_per_get_stage(c, vals[i]) != NULL, ok = 0;
        if (staged && Xp && lamx != lamp) {
            double f = (vals[i] - lamx) / (lamx - lamp);
            for (int j = 0; j < n; j++)
                Xs[j] += f * (X[j] - Xp[j]);
            ok = !gd_per_solve_fixed(c, &Xs, NULL, vals[i], &it, &res, 0);
            if (!ok && c->h.n == n) {
                memcpy(Xs, X, (size_t)(n + 1) * sizeof *Xs);
                staged = gd_per_get_stage(c, vals[i]) != NULL;
            } else if (!ok) {
                staged = 0; /* H grew on the way: no second start */
            }
        }
        if (staged && !ok) ok = !gd_per_solve_fixed(c, &Xs, NULL, vals[i], &it, &res, 0);
        if (!ok) {
            free(Xs);
            if (gd_per_fail_point(c, vals[i], c->reason)) {
                free(Xp);
                goto done;
            }
            continue;
        }
        free(Xp);
        Xp = X;
        lamp = lamx;
        lamx = vals[i];
        if (c->h.n != n) { /* H grew: the last solution no longer matches */
            free(Xp);
            Xp = NULL;
        }
        X = Xs;
        n = c->h.n;
        if (gd_per_emit_point(c, X, vals[i], it, res)) {
            free(Xp);
            goto done;
        }
        if (c->opt->adaptive && c->want_H > c->H) { /* the secant spans two H */
            if (gd_per_follow_H(c, &X, NULL)) {
                free(Xp);
                goto done;
            }
            free(Xp);
            Xp = NULL;
            n = c->h.n;
        }
    }
    free(Xp);
    rc = 0;
done:
    *Xio = X;
    return rc;
}

/* Step control by the turn of the tangent and the chord's direction for the step X, lam
 * -> X1, l1 of length ds (tangents t and t1, n unknowns and the parameter): a step that
 * turned more than ~25 deg, or whose corrector fell back behind the start (retracing a
 * branch past a fold), is retried shorter. 1: retry with half the step; 0: taken (t1 the
 * chord at a corner). *tt_rej: the turn of the last step refused from X (2: none). */
static int refuse_step(ctx *c, int n, const double *t, double *t1, const double *X, double lam,
                       const double *X1, double l1, double ds, double dsmin, double *tt_rej)
{
    double tt = 0.0, tc = 0.0;
    for (int i = 0; i < n; i++) {
        tt += t[i] * t1[i];
        tc += t[i] * (X1[i] - X[i]) / c->sx;
    }
    tt += t[n] * t1[n];
    tc += t[n] * (l1 - lam) / c->sl;
    /* a corrector that went far beyond the step (the chord more than 3 ds, in
     * the scaled variables) jumped to another part of the branch: NLvib's
     * example 03 at H = 3 went from 0.6537 to 0.9146 in 26 iterations on a step
     * of 0.053; the backlash pair at H = 3 over 300..2500 rad/s from 354.04 to
     * 428.14 rad/s in 20 iterations, onto the part of its branch already
     * traced (the chord turned there: a false fold at 354.04 and the loop
     * traced twice, seven folds instead of four) */
    double cc = 0.0;
    for (int i = 0; i < n; i++)
        cc += (X1[i] - X[i]) * (X1[i] - X[i]);
    cc = sqrt(cc / (c->sx * c->sx) + (l1 - lam) * (l1 - lam) / (c->sl * c->sl));
    if (cc > 3.0 * ds && ds > 16 * dsmin) return 1;
    /* a corner, not a curve: the turn did not shrink with the halved step (a
     * contact switching at one sample makes the sampled branch piecewise smooth:
     * NLvib's example 03 at 1024 samples turns by 27 deg at every step size near
     * its resonance peak). It is taken with the chord as the next direction:
     * the tangent at X1 may still be the other side's. */
    const int corner = c->corners && tt < 0.9 && tc > 0.0 && *tt_rej <= 1.0 && tt <= *tt_rej + 0.02;
    if ((tt < 0.9 || tc <= 0.0) && ds > 16 * dsmin && !corner) {
        *tt_rej = tc > 0.0 ? tt : 2.0;
        return 1;
    }
    *tt_rej = 2.0;
    if (corner) {
        double nc = 0.0;
        for (int i = 0; i < n; i++) {
            t1[i] = (X1[i] - X[i]) / c->sx;
            nc += t1[i] * t1[i];
        }
        t1[n] = (l1 - lam) / c->sl;
        nc = sqrt(nc + t1[n] * t1[n]);
        for (int i = 0; i <= n; i++)
            t1[i] /= nc;
    }
    return 0;
}

/* The requested values the step lam -> l1 crossed, in the step's order, each solved
 * from the interpolate (Xg: work) and emitted. 0 ok, 1 an error. */
static int emit_crossed(ctx *c, const double *vals, int nv, int i0, int step, int n,
                        const double *X, double lam, const double *X1, double l1, double *Xg)
{
    const int up = vals[nv - 1] >= vals[0]; /* the requested values increase */
    for (int q = 0; q < nv; q++) {
        /* nearest to lam first: the values in the step's direction */
        int i = (l1 >= lam) == up ? q : nv - 1 - q;
        double v = vals[i];
        if (i == i0 && step == 0) continue;
        int crossed = l1 >= lam ? (v > lam && v <= l1) : (v < lam && v >= l1);
        if (!crossed) continue;
        double sig = (v - lam) / (l1 - lam);
        for (int k = 0; k < n; k++)
            Xg[k] = (1 - sig) * X[k] + sig * X1[k];
        int itg;
        double resg;
        int bad = gd_per_newton(c, Xg, &v, NULL, NULL, &itg, &resg);
        for (int end = 0; bad && end < 2; end++) { /* near a fold: from either step */
            memcpy(Xg, end ? X1 : X, (size_t)n * sizeof *Xg);
            v = vals[i];
            bad = gd_per_newton(c, Xg, &v, NULL, NULL, &itg, &resg);
        }
        if (bad) {
            if (gd_per_fail_point(c, v, c->reason)) return 1;
        } else if (gd_per_emit_point(c, Xg, v, itg, resg)) {
            return 1;
        }
    }
    return 0;
}

/* A fold where the parameter itself turns: the chords before and after X (Xb, lamp: the
 * point before, have_p: it exists at this H; X1, l1: the step's end) move it in opposite
 * directions, so the branch from the point before X through X to X1 holds its extremum,
 * located there by gd_per_locate_turn (Yt, ut: work) and added. Not the sign of the
 * tangent's parameter component: with a contact law the sampled residual is only
 * piecewise smooth and the tangent is not trusted near a turn (NLvib's example 03 at
 * 2048 samples: 12 flips and one turn; at auto H a turn at 0.75560 with the component at
 * +0.007 on both sides; the backlash pair at H = 20, 1024 samples and 81 speeds: a flip
 * between 479.630 and 479.768 rad/s with the branch's maximum beyond both, a fold the
 * tangent rule dropped). A step that turns within itself and back is refused by the step
 * control (the tangent turned more than 25 deg). 1 a fold, 0 none, -1 an error. */
static int fold_at_turn(ctx *c, const double *Xb, double lamp, int have_p, const double *X,
                        double lam, const double *X1, double l1, double ds, double *Yt, double *ut)
{
    const double cl = l1 - lam, cp = have_p ? lam - lamp : 0.0;
    const double tiny = 1e-13 * c->sl;
    if (!(fabs(cl) > tiny && fabs(cp) > tiny && cp * cl < 0)) return 0;
    double lf;
    if (gd_per_locate_turn(c, Xb, lamp, X, lam, X1, l1, &lf, Yt, ut) < 0) return -1;
    const double sg = lam >= lamp ? 1.0 : -1.0;
    if (c->min_samples > 0) {
        /* a contact law: the turn is the highest tooth of the saw there, once
         * per zigzag (a turn within its reach and no higher takes it) */
        const int reach =
            c->climb_dir != 0 && c->climb_H == c->H && fabs(lf - c->climbed) < 1e-2 * c->sl;
        const int same = reach && c->climb_dir == sg * c->dir;
        if (same && sg * lf > sg * c->climbed) c->climbed = lf;
        if (!reach) {
            double best = lf;
            if (gd_per_climb_teeth(c, Yt, ut, ds / 16, sg, &best) < 0) return -1;
            c->climbed = best;
            c->climb_dir = (int)sg * c->dir;
            c->climb_H = c->H;
        }
        /* a turn the other way within the zigzag's reach is one of its
         * teeth: left as located, gd_per_merge_zigzags takes the run */
        if (!reach || same) lf = c->climbed;
    }
    if (gd_per_add_bif(c, GD_BIF_FOLD, lf, NAN, NAN)) return -1;
    return 1;
}

/* Pseudo-arclength from X (*Xio, solved at vals[i0] = lam) to the last requested value:
 * the steps, their control, the requested values on the way, folds and the crossings
 * of the multipliers. 0 done (values beyond the furthest point reached failed with the
 * reason), 1 an error. */
static int arclength(ctx *c, const double *vals, int nv, int i0, double **Xio, double lam)
{
    double *X = *Xio;
    int n = c->h.n, it = 0, rc = 1;
    double res = NAN, reached = 0.0, sign = 1.0;
    double *t = NULL, *t1 = NULL, *X1 = NULL, *Xg = NULL, *yp = NULL, *Xb = NULL, *Yt = NULL,
           *ut = NULL;
    double *mre = NULL, *mim = NULL, *mre1 = NULL, *mim1 = NULL;
    sign = vals[nv - 1] > vals[i0] ? 1.0 : -1.0;
    reached = lam;
    const double lend = vals[nv - 1], lstart = vals[i0];
    c->sl = fabs(lend - lstart);
    c->sx = gd_per_inf_norm(X, c->h.n);
    if (!(c->sx > 0)) c->sx = 1.0;
    int cap = 0;
#define ALLOC_ALL()                                                                                \
    do {                                                                                           \
        n = c->h.n;                                                                                \
        cap = n + 1;                                                                               \
        double **arr[7] = {&t1, &X1, &Xg, &yp, &Xb, &Yt, &ut};                                     \
        for (int a = 0; a < 7; a++) {                                                              \
            free(*arr[a]);                                                                         \
            *arr[a] = calloc((size_t)cap, sizeof **arr[a]);                                        \
            if (!*arr[a]) goto done;                                                               \
        }                                                                                          \
    } while (0)
    ALLOC_ALL();
    t = calloc((size_t)cap, sizeof *t);
    mre = malloc(2 * (size_t)c->nf * sizeof *mre);
    mim = malloc(2 * (size_t)c->nf * sizeof *mim);
    mre1 = malloc(2 * (size_t)c->nf * sizeof *mre1);
    mim1 = malloc(2 * (size_t)c->nf * sizeof *mim1);
    if (!t || !mre || !mim || !mre1 || !mim1) goto done;
    if (gd_per_tangent(c, X, lam, NULL, sign, t)) {
        snprintf(c->reason, sizeof c->reason, "no tangent at the start of the branch");
        goto stop;
    }
    int stable, out[3], out1[3];
    double mu_max, rho[3], rho1[3];
    (void)rho;
    (void)rho1;
    gd_per_floquet(c, X, lam, mre, mim, &stable, &mu_max);
    int have_mu = stable >= 0, fold_prev = 0;
    /* the point before X (Xb, lamp; have_p: it exists at this H) */
    double lamp = lam;
    int have_p = 0;
    double tt_rej = 2.0; /* the turn of the last step refused from X (2: none) */
    if (have_mu) gd_per_categorise(c, mre, mim, out, rho);
    double ds = 1.0 / (nv - 1), dsmax = 2.0 / (nv - 1), dsmin = 1e-7;
    if (ds > 0.05) ds = 0.05;
    if (dsmax > 0.1) dsmax = 0.1;
    int maxsteps = c->opt->max_steps > 0 ? c->opt->max_steps : 50 * nv + 200;
    for (int step = 0;; step++) {
        if (step >= maxsteps) {
            snprintf(c->reason, sizeof c->reason,
                     "continuation stopped after %d steps (raise max_steps)", maxsteps);
            goto stop;
        }
        c->steps++;
        for (int i = 0; i < n; i++)
            yp[i] = X1[i] = X[i] + ds * t[i] * c->sx;
        double l1 = yp[n] = lam + ds * t[n] * c->sl;
        if (gd_per_newton(c, X1, &l1, t, yp, &it, &res)) {
            ds *= 0.5;
            if (ds < dsmin) goto stop;
            continue;
        }
        if (gd_per_tangent(c, X1, l1, t, sign, t1)) {
            ds *= 0.5;
            if (ds < dsmin) goto stop;
            continue;
        }
        if (refuse_step(c, n, t, t1, X, lam, X1, l1, ds, dsmin, &tt_rej)) {
            ds *= 0.5;
            continue;
        }
        int stable1 = -1;
        if (have_mu) {
            gd_per_floquet(c, X1, l1, mre1, mim1, &stable1, &mu_max);
            if (stable1 >= 0) gd_per_categorise(c, mre1, mim1, out1, rho1);
        }
        if (emit_crossed(c, vals, nv, i0, step, n, X, lam, X1, l1, Xg)) goto done;
        /* bifurcations between the two steps */
        const int fold = fold_at_turn(c, Xb, lamp, have_p, X, lam, X1, l1, ds, Yt, ut);
        if (fold < 0) goto done;
        if (have_mu && stable1 >= 0) {
            int tot = out[0] + out[1] + out[2], tot1 = out1[0] + out1[1] + out1[2];
            if (tot != tot1) {
                /* a multiplier crossed the circle (two meeting on the real axis only move
                 * between categories); a real one through +1 at a fold is the fold */
                int m = tot < tot1 ? tot1 : tot, ia, ib;
                double ga = gd_per_ranked(c, mre, mim, m, &ia) - 1.0;
                double gb = gd_per_ranked(c, mre1, mim1, m, &ib) - 1.0;
                /* a tangent that flipped on this step: the turn is seen on the next */
                c->near_fold = fold || fold_prev || t[n] * t1[n] < 0;
                if (gd_per_locate(c, m, X, lam, ga, X1, l1, gb, t, mre1, mim1)) goto done;
            }
            memcpy(out, out1, sizeof out);
            memcpy(mre, mre1, 2 * (size_t)c->nf * sizeof *mre);
            memcpy(mim, mim1, 2 * (size_t)c->nf * sizeof *mim);
        }
        have_mu = have_mu && stable1 >= 0;
        fold_prev = fold;
        lamp = lam;
        have_p = 1;
        memcpy(Xb, X, (size_t)n * sizeof *X);
        memcpy(X, X1, (size_t)n * sizeof *X);
        memcpy(t, t1, (size_t)(n + 1) * sizeof *t);
        {
            /* rescale X to its present size, so that a growing resonance does not eat the
             * arclength: re-express the tangent in the new scale */
            double sx2 = gd_per_inf_norm(X, n);
            if (sx2 > 0) {
                double nt = 0.0;
                for (int i = 0; i < n; i++) {
                    t[i] *= c->sx / sx2;
                    nt += t[i] * t[i];
                }
                nt = sqrt(nt + t[n] * t[n]);
                for (int i = 0; i <= n; i++)
                    t[i] /= nt;
                c->sx = sx2;
            }
        }
        lam = l1;
        if (sign * (lam - reached) > 0) reached = lam;
        if (c->opt->adaptive && c->want_H > c->H) {
            /* a requested point needed more harmonics: the branch goes on with them */
            if (gd_per_follow_H(c, &X, &t)) goto done;
            ALLOC_ALL();
            have_p = 0; /* the point before has the old H */
            if (gd_per_solve_fixed(c, &X, &t, lam, &it, &res, 0)) goto stop;
        }
        if (it <= 3) ds = ds * 1.6 < dsmax ? ds * 1.6 : dsmax;
        if (it > 6) ds *= 0.6;
        if (sign * (lam - lend) >= 0) break;
        if (sign * (lam - lstart) < -0.5 * c->sl || (!c->param && lam <= 0)) {
            snprintf(c->reason, sizeof c->reason, "the branch turned back out of the range");
            goto stop;
        }
    }
    rc = 0;
    goto done;
stop:
    /* values beyond the furthest point reached get the reason */
    for (int i = i0 + 1; i < nv; i++)
        if (sign * (vals[i] - reached) > 0 && gd_per_fail_point(c, vals[i], c->reason)) goto done;
    rc = 0;
done:
#undef ALLOC_ALL
    *Xio = X;
    free(t);
    free(t1);
    free(X1);
    free(Xg);
    free(yp);
    free(Xb);
    free(Yt);
    free(ut);
    free(mre);
    free(mim);
    free(mre1);
    free(mim1);
    return rc;
}

int gd_per_run_branch(ctx *c, const double *vals, int nv)
{
    int it = 0, rc = 1;
    const int nb0 = c->res->nbifurcations;
    double res = NAN, lam = 0.0;
    double *X = calloc((size_t)c->h.n + 1, sizeof *X);
    if (!X) return 1;
    const int i0 = first_point(c, vals, nv, &X, &lam, &it, &res);
    if (i0 < 0) goto done;
    if (i0 == nv) {
        rc = 0;
        goto done;
    }
    if (gd_per_emit_point(c, X, lam, it, res)) goto done;
    if (c->opt->adaptive && c->want_H > c->H) {
        /* the first point needed more harmonics: the branch starts from it solved again
         * at them (padded with zeros it is no solution there: the backlash pair over
         * 300..2500 rad/s went from 300 to 292 rad/s on a step of 1e-6, a false fold at
         * 241.85 and 300 rad/s reported twice) */
        if (gd_per_follow_H(c, &X, NULL)) goto done;
        if (gd_per_solve_fixed(c, &X, NULL, lam, &it, &res, 0)) {
            snprintf(c->reason, sizeof c->reason,
                     "the first point did not converge again at H = %d", c->H);
            rc = 0;
            for (int i = i0 + 1; i < nv; i++)
                if (gd_per_fail_point(c, vals[i], c->reason)) rc = 1;
            goto done;
        }
    }
    if (c->opt->method == GD_PER_SEQUENTIAL)
        rc = sequential(c, vals, nv, i0, &X, lam, c->h.n);
    else if (i0 == nv - 1)
        rc = 0;
    else
        rc = arclength(c, vals, nv, i0, &X, lam);
done:
    if (!rc) gd_per_merge_zigzags(c, nb0);
    free(X);
    return rc;
}
