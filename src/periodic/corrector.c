/* Newton corrector of the continuation (continuation_impl.h): the bordered Newton in
 * scaled variables, the tangent from the bordered Jacobian, the harmonic-balance
 * workspace for H, and the fixed-value solves (from rest through the contact
 * homotopy, or warm from a short transient). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/condensed/chb.h"
#include "periodic/continuation_impl.h"
#include "periodic/periodic_impl.h"

double gd_per_norm2(const double *x, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += x[i] * x[i];
    return sqrt(s);
}

/* The fixed-value solve by the condensed harmonic balance (condensed/chb.h) where it
 * applies, its solution accepted when the full residual (R: n workspace) is within tol.
 * 0 solved (X, *iters, *resid set), 1 not (X as given: the full Newton goes on), 2 not
 * and forced (opt->condensed 1: c->reason says why). */
static int condensed_newton(ctx *c, double *X, double lam, double *R, int *iters, double *resid)
{
    hb *h = &c->h;
    const int force = c->opt->condensed > 0;
    stage *s = gd_per_get_stage(c, lam);
    if (!s) return force ? 2 : 1;
    if (!h->chb) h->chb = gd_chb_new(h->nf, h->H, h->N);
    const int ap = gd_chb_applies(h->chb, s->tr);
    /* a law the harmonic-diagonal preconditioner cannot follow (contact: the condensed
     * Newton fails and hands over) stops being tried after three failures in a row: the
     * receptances it builds first cost as much as a full Newton step (counts, not clocks) */
    if (!force && c->chb_streak >= 3) return 1;
    if (ap < 0 || (ap == 0 && !force)) {
        if (force)
            snprintf(c->reason, sizeof c->reason,
                     "condensed harmonic balance does not apply (no law terms)");
        return force ? 2 : 1;
    }
    double *X0 = malloc((size_t)h->n * sizeof *X0);
    if (!X0) return force ? 2 : 1;
    memcpy(X0, X, (size_t)h->n * sizeof *X0);
    c->chb_tried++;
    int it = 0;
    /* the condensed residual a hundredth of the full tolerance: its scale is the
     * coordinates', the full one's the largest of |L X| and |F| */
    const double tolc = fmax(1e-2 * c->opt->tol, 1e-14);
    int cr = GD_CHB_NOMEM;
    if (!gd_hb_linear_union(h, s->tr)) {
        const gd_chb_linear lin = {h->Up, h->Ui, h->UK, h->UM, h->UD, h->Upat_id};
        gd_chb_lend(h->chb, c->hr.chb); /* the other H's receptances of this problem */
        cr = gd_chb_solve(h->chb, &lin, s->tr, s->id, s->w, X, tolc, &it);
    }
    double scale = 0.0, rel = NAN;
    /* the full residual from the coordinates, the full check on a count (chb.h) */
    if (cr == GD_CHB_OK && gd_chb_check(h->chb, s->tr, s->w, X, &rel) &&
        !gd_hb_residual(h, s->tr, s->w, X, R, 0, &scale)) {
        double rn = gd_per_norm2(R, h->n);
        rel = scale > 0 ? rn / scale : rn;
    }
    c->chb_nc = gd_chb_ncoords(h->chb);
    if (cr == GD_CHB_OK && rel <= c->opt->tol) {
        free(X0);
        *iters = it;
        *resid = rel;
        c->chb_solves++;
        c->chb_streak = 0;
        return 0;
    }
    c->chb_streak++;
    memcpy(X, X0, (size_t)h->n * sizeof *X0);
    free(X0);
    if (force)
        snprintf(c->reason, sizeof c->reason, "condensed harmonic balance on %d coordinates: %s",
                 c->chb_nc,
                 cr == GD_CHB_NA      ? "does not apply (dependent coordinates or a singular Z_k)"
                 : cr == GD_CHB_NOMEM ? "out of memory"
                 : cr == GD_CHB_OK    ? "the full residual is not within tol"
                                      : "Newton did not converge");
    return force ? 2 : 1;
}

/* Newton on R(X, lam) = 0 and, with tan (scaled tangent, n + 1), the hyperplane
 * tan . ((X, lam) - yp) = 0 in scaled variables; without, lam fixed. 0 converged. */
int gd_per_newton(ctx *c, double *X, double *lam, const double *tan, const double *yp, int *iters,
                  double *resid)
{
    hb *h = &c->h;
    const int n = h->n;
    double *R = malloc((size_t)(n + 1) * sizeof *R), *R2 = malloc((size_t)n * sizeof *R2);
    double *row = calloc((size_t)n + 1, sizeof *row);
    int rc = 1;
    *resid = NAN;
    if (!R || !R2 || !row) {
        snprintf(c->reason, sizeof c->reason, "out of memory");
        goto done;
    }
    if (!tan && c->opt->condensed >= 0) {
        int cr = condensed_newton(c, X, *lam, R, iters, resid);
        if (cr == 0) {
            rc = 0;
            goto done;
        }
        if (cr == 2) goto done; /* forced and failed: the reason is set */
    }
    double prev = INFINITY, have_scale = 0.0, hist[3] = {INFINITY, INFINITY, INFINITY};
    int have = 0;  /* the line search left R2 = R(X) with its term derivatives */
    int chord = 0; /* reuse the factorization for this step */
    for (int it = 0; it <= c->opt->max_iter; it++) {
        *iters = it;
        double dl = 0.0;
        if (tan) {
            dl = 1e-7 * (fabs(*lam) > c->sl * 1e-3 ? fabs(*lam) : c->sl * 1e-3);
            stage *s2 = gd_per_get_stage(c, *lam + dl);
            if (!s2) goto done;
            if (gd_hb_residual(h, s2->tr, s2->w, X, R2, 0, NULL)) goto nonfinite;
        }
        stage *s = gd_per_get_stage(c, *lam);
        if (!s) goto done;
        double scale;
        if (have) {
            memcpy(R, R2, (size_t)n * sizeof *R);
            scale = have_scale;
            have = 0;
        } else if (gd_hb_residual(h, s->tr, s->w, X, R, 1, &scale)) {
            goto nonfinite;
        }
        double rn = gd_per_norm2(R, n), rel = scale > 0 ? rn / scale : rn;
        double g = 0.0;
        if (tan) {
            for (int i = 0; i < n; i++)
                g += tan[i] * (X[i] - yp[i]) / c->sx;
            g += tan[n] * (*lam - yp[n]) / c->sl;
        }
        *resid = rel;
        /* the aliasing floor: with contact laws the sampled residual is only piecewise
         * smooth, and near grazing Newton can cycle (a sample's contact state flips with
         * each step: the backlash test at 560 rad/s and H = 7 alternates 1.49e-8 and
         * 2.66e-8). A residual that stagnates (not halved over three iterations) below
         * the force content the samples cannot resolve (hb.alias) and within 1000 tol is
         * accepted; the point reports it. */
        const int floor_ok = it >= 4 && rel <= h->alias && rel <= 1e3 * c->opt->tol &&
                             rel > 0.5 * fmin(hist[0], fmin(hist[1], hist[2]));
        hist[it % 3] = rel;
        if ((rel <= c->opt->tol || rn == 0.0 || floor_ok) && fabs(g) <= 1e-9) {
            rc = 0;
            goto done;
        }
        if (it == c->opt->max_iter) break;
        if (!(rel < 1e6 * (prev < 1 ? 1 : prev)) && it > 3) break; /* diverging */
        prev = rel;
        if (tan) {
            for (int i = 0; i < n; i++) {
                R2[i] = (R2[i] - R[i]) / dl;
                row[i] = tan[i] / c->sx;
            }
            row[n] = tan[n] / c->sl;
        } else {
            memset(row, 0, (size_t)n * sizeof *row);
            row[n] = 1.0;
        }
        h->stage_id = s->id;
        /* chord step (fixed value only): after a step that cut |R| 100-fold the iterate
         * is close and the Jacobian barely changes, so its factorization is kept (the TVMS
         * pairs of [JMSTHelical]: 3e-3 -> 2e-6 -> 3e-10 -> 3e-14 on one factorization, where a
         * fresh one costs the dense LU again); a step that contracts less is followed by
         * a fresh Jacobian */
        if (!(chord && !tan) &&
            (gd_hb_factor(h, s->tr, s->w, tan ? R2 : NULL, row) || h->com.status != KLU_OK)) {
            snprintf(c->reason, sizeof c->reason, "singular harmonic balance Jacobian");
            goto done;
        }
        for (int i = 0; i < n; i++)
            R[i] = -R[i];
        R[n] = -g;
        if (tan)
            gd_hb_solve(h, R);
        else /* R is the residual at X, the last one evaluated */
            gd_hb_solve_newton(h, X, R);
        if (tan) {
            for (int i = 0; i < n; i++)
                X[i] += R[i];
            *lam += R[n];
            continue;
        }
        /* fixed value: backtracking on |R| (contact laws make the residual only piecewise
         * smooth, and a full step from a poor start can overshoot) */
        double alpha = 1.0;
        for (int i = 0; i < n; i++)
            X[i] += R[i];
        chord = 0;
        for (int ls = 0; ls < 12; ls++) {
            double sc, rn2;
            if (!gd_hb_residual(h, s->tr, s->w, X, R2, 1, &sc) &&
                (rn2 = gd_per_norm2(R2, n)) < (1.0 - 1e-4 * alpha) * rn) {
                have = 1; /* the next iteration starts from this residual */
                have_scale = sc;
                chord = ls == 0 && rn2 < 1e-2 * rn;
                break;
            }
            alpha *= 0.5; /* X = start + alpha step */
            for (int i = 0; i < n; i++)
                X[i] -= alpha * R[i];
        }
    }
    snprintf(c->reason, sizeof c->reason,
             "Newton did not converge in %d iterations (relative residual %.3g > tol %.3g)",
             c->opt->max_iter, *resid, c->opt->tol);
    goto done;
nonfinite:
    snprintf(c->reason, sizeof c->reason, "a force is not finite along the trial solution");
done:
    free(R);
    free(R2);
    free(row);
    return rc;
}

/* Unit tangent (scaled, n + 1) at a converged (X, lam): the bordered system with last row
 * prev (scaled; NULL: e_lam) and right-hand side e_{n+1}; oriented along prev or sign. */
int gd_per_tangent(ctx *c, const double *X, double lam, const double *prev, double sign, double *t)
{
    hb *h = &c->h;
    const int n = h->n;
    double *R = malloc((size_t)n * sizeof *R), *R2 = malloc((size_t)n * sizeof *R2);
    double *row = calloc((size_t)n + 1, sizeof *row);
    int rc = 1;
    if (!R || !R2 || !row) goto done;
    double dl = 1e-7 * (fabs(lam) > c->sl * 1e-3 ? fabs(lam) : c->sl * 1e-3);
    stage *s2 = gd_per_get_stage(c, lam + dl);
    if (!s2 || gd_hb_residual(h, s2->tr, s2->w, X, R2, 0, NULL)) goto done;
    stage *s = gd_per_get_stage(c, lam);
    if (!s || gd_hb_residual(h, s->tr, s->w, X, R, 1, NULL)) goto done;
    for (int i = 0; i < n; i++) {
        R2[i] = (R2[i] - R[i]) / dl;
        row[i] = prev ? prev[i] / c->sx : 0.0;
    }
    row[n] = prev ? prev[n] / c->sl : 1.0;
    h->stage_id = s->id;
    if (gd_hb_factor(h, s->tr, s->w, R2, row) || h->com.status != KLU_OK) goto done;
    memset(t, 0, (size_t)(n + 1) * sizeof *t);
    t[n] = 1.0;
    gd_hb_solve(h, t);
    for (int i = 0; i < n; i++)
        t[i] /= c->sx;
    t[n] /= c->sl;
    double nt = gd_per_norm2(t, n + 1), dot = 0.0;
    if (!(nt > 0) || !isfinite(nt)) goto done;
    for (int i = 0; i <= n; i++) {
        t[i] /= nt;
        if (prev) dot += t[i] * prev[i];
    }
    if ((prev && dot < 0) || (!prev && t[n] * sign < 0))
        for (int i = 0; i <= n; i++)
            t[i] = -t[i];
    rc = 0;
done:
    free(R);
    free(R2);
    free(row);
    return rc;
}

/* ---------------------------------------------------------------- harmonic count */

static int samples_for(const gd_periodic_options *o, int H, int min)
{
    if (o->samples > 0) return o->samples;
    int N = 16;
    while (N < 4 * (H + 1) || N < min)
        N *= 2;
    return N;
}

int gd_per_hb_setup(ctx *c, int H)
{
    gd_hb_free(&c->h);
    c->H = H;
    int N = samples_for(c->opt, H, c->min_samples);
    if (N < 2 * H + 2) N = 2 * H + 2;
    int rc = gd_hb_init(&c->h, c->nf, H, N);
    c->h.solver = c->opt->solver;
    return rc;
}

/* Grows X (and t, with its parameter entry last) to H2 harmonics. */
static int grow(ctx *c, double **X, double **t, int H2)
{
    const int nf = c->nf, n1 = nf * (2 * c->H + 1), n2 = nf * (2 * H2 + 1);
    double *x = realloc(*X, (size_t)(n2 + 1) * sizeof *x);
    if (!x) return 1;
    *X = x;
    memset(x + n1, 0, (size_t)(n2 + 1 - n1) * sizeof *x);
    if (t && *t) {
        double *y = realloc(*t, (size_t)(n2 + 1) * sizeof *y);
        if (!y) return 1;
        *t = y;
        double tl = y[n1];
        memset(y + n1, 0, (size_t)(n2 + 1 - n1) * sizeof *y);
        y[n2] = tl;
    }
    return gd_per_hb_setup(c, H2);
}

/* ---------------------------------------------------------------- points */

double gd_per_inf_norm(const double *x, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m = fabs(x[i]) > m ? fabs(x[i]) : m;
    return m;
}

/* The contact homotopy's counted limits (issue 33): a release step to a smaller h that
 * fails halves the step; two failures in a row, or more release solves than
 * GD_PER_RELEASE_MAX, end it. Each failed solve is a whole Newton (up to max_iter
 * iterations with their line searches): on examples/manual_5speed.yaml, whose rattling
 * idlers have no orbit near the drive flank, the old rule (halve down to a step of 1e-3)
 * spent 7 solves, 141 factorisations and 1543 residuals on a release it never finished. */
#define GD_PER_RELEASE_MAX 12
#define GD_PER_RELEASE_FAILS 2

/* Newton from rest (from the static state of load-carrying laws: gd_hb_static_start)
 * through a contact homotopy: every backlash mesh first held on its
 * drive flank (h = 1: smooth), then released step by step to the backlash law (h = 0),
 * each Newton starting from the last solution; a failed release halves the step, within
 * the counted limits above. Without backlash meshes h changes nothing and the first
 * solve is the answer. */
static int solve_from_rest(ctx *c, double *X, double lam, int *it, double *res)
{
    stage *s = gd_per_get_stage(c, lam);
    if (!s) return 1;
    const int n = c->h.n;
    double *Xok = malloc((size_t)n * sizeof *Xok);
    if (!Xok) return 1;
    double h = 1.0, step = 0.5;
    const gd_transient_spec *spec = s->spec;
    gd_hb_static_start(s->sys, spec, s->tr, c->param ? c->param->speed : lam, c->nf, X);
    int rc = 1, nbl = gd_transient_nswitches(s->tr); /* contact laws (backlash meshes) */
    int solves = 0, fails = 0;                       /* release solves, failures in a row */
    const char *stop = "";
    if (!nbl) {
        free(Xok);
        return gd_per_newton(c, X, &lam, NULL, NULL, it, res);
    }
    gd_transient_hold_drive(s->tr, h);
    if (gd_per_newton(c, X, &lam, NULL, NULL, it, res)) goto done;
    memcpy(Xok, X, (size_t)n * sizeof *X);
    while (h > 0) {
        if (solves >= GD_PER_RELEASE_MAX) {
            stop = "the solve limit";
            goto done;
        }
        double h2 = h - step < 1e-3 ? 0.0 : h - step;
        gd_transient_hold_drive(s->tr, h2);
        solves++;
        if (gd_per_newton(c, X, &lam, NULL, NULL, it, res)) {
            memcpy(X, Xok, (size_t)n * sizeof *X);
            step *= 0.5;
            if (++fails >= GD_PER_RELEASE_FAILS) {
                stop = "failed twice in a row";
                goto done;
            }
            if (step < 1e-3) goto done;
            continue;
        }
        fails = 0;
        memcpy(Xok, X, (size_t)n * sizeof *X);
        h = h2;
        step = step * 2 < 0.5 ? step * 2 : 0.5;
    }
    rc = 0;
done:
    gd_transient_hold_drive(s->tr, 0.0);
    /* named, counted: the point's reason says where the homotopy stopped and why */
    if (rc && solves)
        snprintf(c->reason + strlen(c->reason), sizeof c->reason - strlen(c->reason),
                 " (contact homotopy stopped at h = %.3g after %d release solves: %s; limits "
                 "%d solves, %d failures in a row)",
                 h, solves, stop[0] ? stop : "a step below 1e-3", GD_PER_RELEASE_MAX,
                 GD_PER_RELEASE_FAILS);
    free(Xok);
    return rc;
}

/* Newton from a short transient's last period (warmstart.c), after Newton from rest
 * failed: 0 converged. The reason of the first failure is kept, extended, otherwise. */
int gd_per_solve_warm(ctx *c, double *X, double lam, int *it, double *res)
{
    enum { PERIODS = 60 };
    stage *s = gd_per_get_stage(c, lam);
    if (!s) return 1;
    char why[320];
    snprintf(why, sizeof why, "%s", c->reason);
    const gd_system *sys = s->sys;
    const gd_transient_spec *spec = s->spec;
    double speed = c->param ? c->param->speed : lam;
    if (!gd_hb_warm_start(sys, spec, speed, s->w, c->H, PERIODS, X) &&
        !gd_per_newton(c, X, &lam, NULL, NULL, it, res))
        return 0;
    snprintf(c->reason, sizeof c->reason, "%.230s (and from a transient of %d periods)", why,
             PERIODS);
    return 1;
}

/* Fixed-value Newton at the branch's H. rest: X is zero. */
int gd_per_solve_fixed(ctx *c, double **X, double **t, double lam, int *it, double *res, int rest)
{
    (void)t;
    return rest ? solve_from_rest(c, *X, lam, it, res)
                : gd_per_newton(c, *X, &lam, NULL, NULL, it, res);
}

/* Adaptive H: the branch follows the coarse H its last point needed (X, and t if given,
 * padded with zeros). 0 ok. */
int gd_per_follow_H(ctx *c, double **X, double **t)
{
    if (!c->opt->adaptive || c->want_H <= c->H) return 0;
    return grow(c, X, t, c->want_H);
}
