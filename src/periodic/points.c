/* The points of a branch (continuation_impl.h): Floquet multipliers, record
 * statistics over one period, the truncation estimate (the point again at 2H + 1),
 * progress, and the points emitted to the result and the caller's callback. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/continuation_impl.h"
#include "periodic/periodic_impl.h"

static void announce(ctx *c, double lam);

void gd_per_floquet(ctx *c, const double *X, double lam, double *mre, double *mim, int *stable,
                    double *mu_max)
{
    *stable = -1;
    *mu_max = NAN;
    c->floquet_msg[0] = '\0';
    if (!c->opt->stability) return;
    stage *s = gd_per_get_stage(c, lam);
    if (!s) return;
    c->floquet_shooting = 0;
    c->floquet_change = NAN;
    c->floquet_note[0] = '\0';
    if (c->shoot_stab) {
        /* a non-smooth law: the multipliers of the time-domain orbit (issue 33 item 1) */
        const int n2s = 2 * c->nf;
        int nm = 0;
        double chg;
        memset(mre, 0, (size_t)n2s * sizeof *mre);
        memset(mim, 0, (size_t)n2s * sizeof *mim);
        if (!gd_per_floquet_shooting(c->sys, c->spec, c->param, c->opt, lam, &c->h, s->w, X, mre,
                                     mim, &nm, &chg, c->floquet_note, sizeof c->floquet_note)) {
            double m = 0.0;
            for (int i = 0; i < nm; i++)
                m = fmax(m, hypot(mre[i], mim[i]));
            *mu_max = m;
            *stable = m <= 1.0 + 1e-6;
            c->floquet_n = nm;
            c->floquet_krylov = nm < n2s;
            c->floquet_basis = 0;
            c->floquet_steps = 0;
            c->floquet_shooting = 1;
            c->floquet_change = chg;
            return;
        }
    }
    int steps = c->opt->monodromy_steps > 0 ? c->opt->monodromy_steps : 4 * c->h.N;
    if (steps < 256 && c->opt->monodromy_steps <= 0) steps = 256;
    gd_tr_record bl[64]; /* the laws' modes: Floquet's steps are split where they change */
    int nbl = gd_transient_mode_records(s->tr, bl, 64);
    const int n2 = 2 * c->nf;
    const int dmax = c->opt->floquet_dmax > 0 ? c->opt->floquet_dmax : 300;
    int krylov = c->opt->floquet == GD_FLOQUET_KRYLOV;
    int rc, nmu = n2, nbasis = 0, used = steps;
    c->floquet_n = 0;
    c->floquet_basis = 0;
    /* rc 5: not by the reduced basis (not asked for, or no usable basis there) */
    rc = 5;
    /* auto: the reduced basis also where the dense monodromy would be over the budget
     * (floquet.c counts 30 n2^3 flops a Magnus step, at least `steps` of them) instead of
     * no multipliers at all: examples/wind_turbine_gearbox.yaml, 232 states, 767 s counted
     * at H = 255, by 59 vectors in 0.07 s CPU, |mu|max 1.000000 as shooting's in 118 s */
    const double fb = c->opt->floquet_budget;
    const int over = fb > 0 && gd_per_work_seconds(30.0 * pow(n2, 3) * steps) > fb;
    if (c->opt->floquet == GD_FLOQUET_REDUCED ||
        (c->opt->floquet == GD_FLOQUET_AUTO && (n2 > dmax || over))) {
        /* 2 r multipliers and the discarded modes' estimates, at most n2: the rest zero
         * (the bifurcation search ranks them all) */
        memset(mre, 0, (size_t)n2 * sizeof *mre);
        memset(mim, 0, (size_t)n2 * sizeof *mim);
        rc = gd_per_floquet_reduced(c, s, X, lam, c->opt->monodromy_steps > 0 ? steps : 0, steps,
                                    &used, bl, nbl, mre, mim, &nmu, &nbasis);
        if (rc == 1 && !c->floquet_msg[0])
            snprintf(c->floquet_msg, sizeof c->floquet_msg,
                     "stability not computed: the reduced-basis multipliers failed");
        /* no usable basis (a free rotation): the full model's dense or Krylov multipliers */
        if (rc == 5) {
            krylov = n2 > dmax;
            nmu = n2;
            nbasis = 0;
            c->floquet_msg[0] = '\0';
        }
    }
    if (rc == 5 && !krylov) {
        rc = gd_hb_floquet_budget(&c->h, s->tr, s->w, X, steps, bl, nbl, c->opt->floquet_budget,
                                  mre, mim, c->floquet_msg);
    } else if (rc == 5) {
        /* the largest few; more while all but one of them lie outside the unit circle
         * (the count outside and the next one in locate the bifurcations) */
        int want = c->opt->floquet_count > 0 ? c->opt->floquet_count : 8, retry = 0;
        for (;;) {
            int products;
            memset(mre, 0, (size_t)n2 * sizeof *mre);
            memset(mim, 0, (size_t)n2 * sizeof *mim);
            rc = gd_hb_floquet_krylov(&c->h, s->tr, s->w, X, steps, bl, nbl, want, 1e-10,
                                      c->opt->floquet_budget, mre, mim, &nmu, &products,
                                      c->floquet_msg);
            if (rc == 3 && retry++ < 3) { /* moduli tied across the cut: take them all */
                want += 2;
                continue;
            }
            if (rc) break;
            int out = 0;
            for (int i = 0; i < nmu; i++)
                out += hypot(mre[i], mim[i]) > 1.0 + 1e-6;
            if (out < nmu - 1 || nmu + 4 > n2 || want >= 256) break;
            want *= 2;
        }
        if (rc == 3) rc = 1;
        if (rc == 1 && !c->floquet_msg[0])
            snprintf(c->floquet_msg, sizeof c->floquet_msg,
                     "stability not computed: the Krylov multipliers failed");
    }
    if (rc == 2)
        snprintf(c->floquet_msg, sizeof c->floquet_msg,
                 "stability not computed: the monodromy matrix over the period %.3g s overflowed "
                 "with %d Magnus steps (a long period needs more: monodromy_steps)",
                 TWO_PI / s->w, steps);
    if (rc) return;
    double m = 0.0;
    for (int i = 0; i < nmu; i++) {
        double a = hypot(mre[i], mim[i]);
        m = a > m ? a : m;
    }
    *mu_max = m;
    *stable = m <= 1.0 + 1e-6;
    c->floquet_n = nmu;
    c->floquet_krylov = krylov && !nbasis;
    c->floquet_basis = nbasis;
    c->floquet_steps = nbasis ? used : steps;
}

static gd_periodic_point *new_point(ctx *c)
{
    return gd_per_point_new(c->res, &c->cap_points, c->dir, GD_PER_HB);
}

static void set_value(const ctx *c, gd_periodic_point *p, double lam)
{
    p->speed = c->param ? c->param->speed : lam;
    p->parameter = c->param ? lam : NAN;
}

int gd_per_fail_point(ctx *c, double lam, const char *why)
{
    gd_periodic_point *p = new_point(c);
    if (!p) return 1;
    set_value(c, p, lam);
    p->converged = 0;
    p->harmonics = c->H;
    snprintf(p->reason, sizeof p->reason, "%.250s", why);
    announce(c, lam);
    return 0;
}

/* Record statistics over one period sampled at Nr points. */
static int record_stats(ctx *c, stage *s, const double *X, gd_periodic_point *p)
{
    const int nf = c->nf, H = c->H, nr = c->nrec;
    int Nr = 256;
    while (Nr < 8 * (H + 1))
        Nr *= 2;
    p->records = calloc((size_t)(nr > 0 ? nr : 1), sizeof *p->records);
    double *vals = malloc((size_t)(nr > 0 ? nr : 1) * Nr * sizeof *vals);
    double *buf = fftw_malloc((size_t)Nr * sizeof *buf),
           *out = fftw_malloc((size_t)Nr * sizeof *out);
    double *y = calloc(2 * (size_t)nf, sizeof *y), *qs = NULL, *vs = NULL;
    /* only the DOFs the records read are sampled (the others stay zero in y) */
    int *dofs = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *dofs), nd = 0;
    double *rv = malloc((size_t)(nr > 0 ? nr : 1) * sizeof *rv);
    unsigned char *seen = calloc((size_t)(nf > 0 ? nf : 1), 1);
    int *tmp = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *tmp);
    for (int r = 0; r < nr && dofs && seen && tmp && nd >= 0; r++) {
        int k = gd_transient_record_dofs(s->tr, &c->rec[r], tmp, nf);
        for (int q = 0; q < k; q++)
            if (!seen[tmp[q]]) {
                seen[tmp[q]] = 1;
                dofs[nd++] = tmp[q];
            }
        if (k < 0) nd = -1;
    }
    const int listed = dofs && seen && tmp;
    free(seen);
    free(tmp);
    int ok = p->records && vals && buf && out && y && listed && rv &&
             (!nr || !gd_hb_samples(&c->h, s->w, X, Nr, nd >= 0 ? dofs : NULL, nd, &qs, &vs));
    const int all = nd < 0; /* a record that reads every DOF: all sampled, in order */
    if (all) nd = nf;
    if (!ok) {
        free(vals);
        fftw_free(buf);
        fftw_free(out);
        free(y);
        free(dofs);
        free(rv);
        return 1;
    }
    /* the state once per sample, every record from it */
    for (int j = 0; j < Nr && nr; j++) {
        double tau = TWO_PI * j / Nr;
        for (int m = 0; m < nd; m++) {
            int i = all ? m : dofs[m];
            y[i] = qs[(size_t)j * nd + m];
            y[nf + i] = vs[(size_t)j * nd + m];
        }
        gd_transient_record_values(s->tr, c->rec, nr, tau / s->w, y, rv);
        for (int r = 0; r < nr; r++)
            vals[(size_t)r * Nr + j] = rv[r];
    }
    free(dofs);
    free(rv);
    fftw_plan plan = fftw_plan_r2r_1d(Nr, buf, out, FFTW_R2HC, FFTW_ESTIMATE);
    for (int r = 0; r < nr; r++)
        gd_per_sample_stats(&vals[(size_t)r * Nr], Nr, H, plan, buf, out, &p->records[r]);
    fftw_destroy_plan(plan);
    free(vals);
    fftw_free(buf);
    fftw_free(out);
    free(y);
    return 0;
}

/* The main and the refined workspaces trade places (the Newton, the records and the
 * multipliers work on c->h at c->H). */
static void swap_ws(ctx *c)
{
    hb t = c->h;
    c->h = c->hr;
    c->hr = t;
    int k = c->H;
    c->H = c->Hr;
    c->Hr = k;
}

static void free_point_data(gd_periodic_point *p, int nrec)
{
    free(p->coef);
    free(p->mu_re);
    free(p->mu_im);
    if (p->records)
        for (int k = 0; k < nrec; k++) {
            free(p->records[k].amplitude);
            free(p->records[k].phase_deg);
        }
    free(p->records);
    p->coef = p->mu_re = p->mu_im = NULL;
    p->records = NULL;
}

/* The point at lam solved at Hf from the coarse solution Xc (Hc harmonics) padded with
 * zeros, in the refined workspace: coefficients and records into f. 0 ok. */
static int solve_refined(ctx *c, const double *Xc, int Hc, int Hf, double lam, gd_periodic_point *f)
{
    const int nf = c->nf;
    swap_ws(c);
    int rc = 1;
    if (c->H != Hf && gd_per_hb_setup(c, Hf)) {
        snprintf(c->reason, sizeof c->reason, "out of memory at H = %d", Hf);
        c->H = 0;
        goto done;
    }
    size_t nfine = (size_t)nf * (2 * Hf + 1);
    double *X = calloc(nfine + 1, sizeof *X);
    if (!X) goto done;
    memcpy(X, Xc, (size_t)nf * (2 * Hc + 1) * sizeof *X);
    int it;
    double res;
    stage *s;
    if (gd_per_newton(c, X, &lam, NULL, NULL, &it, &res) || !(s = gd_per_get_stage(c, lam))) {
        free(X);
        goto done;
    }
    f->converged = 1;
    f->harmonics = Hf;
    f->omega = s->w;
    f->residual = res;
    f->iterations = it;
    f->nfree = nf;
    f->coef = X;
    rc = record_stats(c, s, X, f);
done:
    swap_ws(c);
    return rc;
}

/* Truncation estimate of point p (converged at p->harmonics): the records against a
 * solution at 2 H. Fixed H: p keeps its solution and gets the change as its estimate.
 * Adaptive H: H doubles until the change is within harmonic_tol, and p becomes the finer
 * solution of the last comparison. A refinement that fails (Newton, or memory) leaves p
 * as it is with the reason. Returns 0. */
/* Adaptive H stops where a doubling did not shrink the truncation estimate to this
 * fraction of the doubling before, both from H = STALL_MIN_H on: a series that falls
 * slower than 1 / sqrt(H) there will not reach the tolerance at any H that fits
 * (planetary_mesh_laws.yaml, geometry TVMS with backlash: 7.3 % between H = 1 and 3 and
 * between 3 and 7, 40 % between 31 and 63; the walk on to H = 1023 took minutes a point;
 * a TVMS step alone falls as 1 / H, 0.5 a doubling, and walks on). Below STALL_MIN_H
 * the first harmonics may change alike before the series falls. Counts, no clock. */
#define STALL_RATIO 0.7
#define STALL_MIN_H 15

static int estimate_point(ctx *c, gd_periodic_point *p, double lam)
{
    const int adaptive = c->opt->adaptive, nrec = c->nrec;
    const double tol = c->opt->harmonic_tol;
    double prev = NAN; /* the estimate of the doubling before (adaptive) */
    int prevH = 0;
    for (;;) {
        const int Hc = p->harmonics,
                  Hf = 2 * Hc + 1; /* odd: a response with only odd harmonics (a symmetric law)
                                      changes from H = 1 to 3, not 2 */
        if (Hf > c->Hcap) {
            if (adaptive || p->harmonic_ok < 0)
                snprintf(p->reason, sizeof p->reason,
                         "harmonic truncation %s: H = %d is the largest that fits in memory "
                         "(or max_harmonics)",
                         p->harmonic_ok == 0 ? "not within the tolerance" : "not estimated", Hc);
            return 0;
        }
        gd_periodic_point f;
        memset(&f, 0, sizeof f);
        if (solve_refined(c, p->coef, Hc, Hf, lam, &f)) {
            free_point_data(&f, nrec);
            snprintf(p->reason, sizeof p->reason,
                     "harmonic truncation not estimated: the solution at H = %d failed: %.180s", Hf,
                     c->reason);
            return 0; /* the point stands, without its estimate */
        }
        double ep, ea;
        if (nrec) {
            double *zero = malloc((size_t)nrec * sizeof *zero);
            if (zero)
                gd_hb_record_zero(c->rec, nrec, f.coef, c->nf * (2 * Hf + 1), Hf, f.omega, zero);
            gd_hb_truncation(p->records, Hc, f.records, Hf, nrec, zero, &ep, &ea);
            free(zero);
        } else {
            ep = ea =
                gd_hb_coef_change(p->coef, c->nf * (2 * Hc + 1), f.coef, c->nf * (2 * Hf + 1));
        }
        const int ok = ep <= tol && ea <= tol;
        if (!adaptive) {
            for (int r = 0; r < nrec; r++) {
                p->records[r].p2p_error = f.records[r].p2p_error;
                p->records[r].amp_error = f.records[r].amp_error;
            }
            p->harmonics_ref = Hf;
            p->harmonic_error_p2p = ep;
            p->harmonic_error_amp = ea;
            p->harmonic_ok = ok;
            if (!ok)
                snprintf(p->reason, sizeof p->reason,
                         "harmonic truncation: at H = %d the peak-to-peak changes by %.2g and "
                         "the harmonic amplitudes by %.2g (tolerance %.2g): raise --harmonics",
                         Hf, ep, ea, tol);
            free_point_data(&f, nrec);
            return 0;
        }
        /* adaptive: the finer solution replaces the point; the branch follows Hc */
        f.speed = p->speed;
        f.parameter = p->parameter;
        f.direction = p->direction;
        f.stable = -1;
        f.mu_max = NAN;
        f.harmonics_ref = Hc;
        f.harmonic_error_p2p = ep;
        f.harmonic_error_amp = ea;
        f.harmonic_ok = ok;
        free_point_data(p, nrec);
        *p = f;
        if (Hc > c->want_H) c->want_H = Hc;
        if (ok) return 0;
        snprintf(p->reason, sizeof p->reason,
                 "harmonic truncation: between H = %d and %d the peak-to-peak changes by %.2g "
                 "and the harmonic amplitudes by %.2g (tolerance %.2g)",
                 Hc, Hf, ep, ea, tol);
        const double e = fmax(ep, ea);
        if (isfinite(prev) && prevH >= STALL_MIN_H && e > STALL_RATIO * prev) {
            char msg[320];
            snprintf(msg, sizeof msg,
                     "harmonic truncation not within the tolerance: %.2g between H = %d and %d "
                     "after %.2g between %d and %d, it does not converge at any H that fits "
                     "(--method shooting, or --harmonics N to accept one)",
                     e, Hc, Hf, prev, prevH, Hc);
            snprintf(p->reason, sizeof p->reason, "%.255s", msg);
            return 0;
        }
        prev = e;
        prevH = p->harmonics_ref;
    }
}

static double progress(const ctx *c, double lam)
{
    double f = c->v1 != c->v0 ? (lam - c->v0) / (c->v1 - c->v0) : 1.0;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    return ((c->dir < 0 ? 1 : 0) + f) / c->ndir;
}

static void announce(ctx *c, double lam)
{
    if (c->opt->on_point)
        c->opt->on_point(&c->res->points[c->res->npoints - 1], c->res->npoints - 1,
                         progress(c, lam), c->opt->user);
}

int gd_per_emit_point(ctx *c, const double *X, double lam, int iters, double resid)
{
    stage *s = gd_per_get_stage(c, lam);
    gd_periodic_point *p = new_point(c);
    if (!p) return 1;
    set_value(c, p, lam);
    if (!s) {
        snprintf(p->reason, sizeof p->reason, "%.250s", c->reason);
        announce(c, lam);
        return 0;
    }
    p->converged = 1;
    p->harmonics = c->H;
    p->omega = s->w;
    p->residual = resid;
    p->iterations = iters;
    p->nfree = c->nf;
    size_t n = (size_t)c->h.n;
    p->coef = malloc(n * sizeof *p->coef);
    if (!p->coef) return 1;
    memcpy(p->coef, X, n * sizeof *X);
    if (record_stats(c, s, X, p)) return 1;
    if ((c->opt->estimate || c->opt->adaptive) && estimate_point(c, p, lam)) return 1;
    p->mu_re = malloc(2 * (size_t)c->nf * sizeof *p->mu_re);
    p->mu_im = malloc(2 * (size_t)c->nf * sizeof *p->mu_im);
    if (!p->mu_re || !p->mu_im) return 1;
    /* the multipliers of the reported solution, in its workspace */
    const int fine = p->harmonics != c->H;
    if (fine) swap_ws(c);
    /* a truncation not within the tolerance: the Fourier orbit is not the time-domain one
     * to that accuracy, so its multipliers come from the orbit corrected by shooting too
     * (issue 33 item 1), where the dense monodromy is cheap (shoot_dense_max states) */
    const int was = c->shoot_stab,
              dmax = c->opt->shoot_dense_max > 0 ? c->opt->shoot_dense_max : 64;
    if (c->opt->shoot_stability == 1 && p->harmonic_ok == 0 && 2 * c->nf <= dmax) c->shoot_stab = 1;
    gd_per_floquet(c, p->coef, lam, p->mu_re, p->mu_im, &p->stable, &p->mu_max);
    c->shoot_stab = was;
    if (fine) swap_ws(c);
    p->nmult = p->stable >= 0 ? c->floquet_n : 0;
    p->floquet_krylov = p->stable >= 0 && c->floquet_krylov;
    p->floquet_basis = p->stable >= 0 ? c->floquet_basis : 0;
    p->floquet_steps = p->stable >= 0 ? c->floquet_steps : 0;
    p->stability_method = p->stable < 0 ? -1 : c->floquet_shooting ? GD_PER_SHOOTING : GD_PER_HB;
    if (p->stable >= 0 && c->floquet_shooting && !p->reason[0])
        snprintf(p->reason, sizeof p->reason,
                 "stability from the orbit corrected by shooting (its state moved by %.2g, "
                 "scaled)",
                 c->floquet_change);
    else if (p->stable >= 0 && c->shoot_stab && !c->floquet_shooting && !p->reason[0])
        snprintf(p->reason, sizeof p->reason,
                 "stability from the harmonic balance orbit: the shooting correction failed: "
                 "%.180s",
                 c->floquet_note);
    if (p->stable < 0 && c->floquet_msg[0])
        snprintf(p->reason, sizeof p->reason, "%s", c->floquet_msg);
    announce(c, lam);
    return 0;
}

/* ---------------------------------------------------------------- bifurcations */
