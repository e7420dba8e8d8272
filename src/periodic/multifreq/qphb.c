/* Multi-frequency harmonic balance of one point (qphb_impl.h): residual by AFT on the
 * d-dimensional grid of the torus, Newton-Krylov with SUNDIALS' GMRES (SPGMR) on
 * Jacobian-vector products of the linearised forces, right-preconditioned by the harmonic
 * blocks (K - Omega^2 M + i Omega D) - sum_t u w^T (mean s_q + i Omega mean s_v), the
 * terms' torus means (the time-invariant part of the Jacobian, exact for a linear model;
 * Krack & Gross 2019, ch. 5). Coefficients per harmonic k with Omega = k . W:
 *   cos row: (K - Omega^2 M) C + Omega D S - F_c,  sin row: (K - Omega^2 M) S - Omega D C - F_s,
 * as the single-frequency harmonic balance (hb.c) with k w replaced by Omega; in complex
 * form Z = C - i S, R_c - i R_s = (K - Omega^2 M + i Omega D) Z - (F_c - i F_s). */
#include <lapacke.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include "periodic/multifreq/qphb_impl.h"
#include "signal/fft_planner_impl.h"
#include "transient/transient_impl.h"

#define TWO_PI 6.28318530717958647692

static double omega_of(const gd_qp_torus *T, int j)
{
    double w = 0.0;
    for (int g = 0; g < T->d; g++)
        w += T->k[j * T->d + g] * T->W[g];
    return w;
}

/* the largest preconditioner (complex blocks nk nf^2) taken */
#define MAX_PREC_BYTES 1.5e9

int gd_qp_init(gd_qp *q, gd_transient *tr, const gd_qp_bases *b, int H, char *msg, size_t cap)
{
    gd_fft_planner_init();
    memset(q, 0, sizeof *q);
    q->tr = tr;
    q->b = b;
    q->nf = gd_transient_nstates(tr) / 2;
    q->nt = gd_transient_terms(tr, &q->term);
    if (q->nt < 0) {
        snprintf(msg, cap, "cam torques with include_acceleration are not represented");
        return 2;
    }
    if (gd_qp_torus_init(&q->T, b, H)) return 1;
    const int nf = q->nf;
    const long Nt = q->T.Ntot, nk = q->T.nk;
    q->n = gd_qp_unknowns(&q->T, nf);
    double bytes = (double)nk * nf * nf * 16.0 + (double)Nt * nf * 40.0 +
                   (double)Nt * (q->nt > 0 ? q->nt : 1) * 16.0;
    if (bytes > MAX_PREC_BYTES) {
        snprintf(msg, cap,
                 "the torus of order %d (%ld harmonics, %ld grid points) on %d DOFs needs about "
                 "%.2g GB, over the %.2g GB taken",
                 H, nk, Nt, nf, bytes / 1e9, MAX_PREC_BYTES / 1e9);
        return 2;
    }
    q->buf = fftw_malloc((size_t)Nt * nf * sizeof *q->buf);
    q->qs = malloc((size_t)Nt * nf * sizeof *q->qs);
    q->vs = malloc((size_t)Nt * nf * sizeof *q->vs);
    q->fs = malloc((size_t)Nt * nf * sizeof *q->fs);
    q->sq = malloc((size_t)Nt * (q->nt > 0 ? q->nt : 1) * sizeof *q->sq);
    q->sv = malloc((size_t)Nt * (q->nt > 0 ? q->nt : 1) * sizeof *q->sv);
    q->ltime = malloc((size_t)(tr->nlaw > 0 ? tr->nlaw : 1) * sizeof *q->ltime);
    q->y = malloc(2 * (size_t)nf * sizeof *q->y);
    q->st = malloc(2 * (size_t)(q->nt > 0 ? q->nt : 1) * sizeof *q->st);
    q->P = malloc((size_t)nk * nf * nf * sizeof *q->P);
    q->piv = malloc((size_t)nk * nf * sizeof *q->piv);
    q->w1 = malloc((size_t)q->n * sizeof *q->w1);
    q->w2 = malloc((size_t)q->n * sizeof *q->w2);
    if (!q->buf || !q->qs || !q->vs || !q->fs || !q->sq || !q->sv || !q->ltime || !q->y || !q->st ||
        !q->P || !q->piv || !q->w1 || !q->w2)
        return 1;
    /* one plan each way over every DOF's grid (DOF-major, in place) */
    q->inv = fftw_plan_many_dft(q->T.d, q->T.N, nf, q->buf, NULL, 1, (int)Nt, q->buf, NULL, 1,
                                (int)Nt, FFTW_BACKWARD, FFTW_ESTIMATE);
    q->fwd = fftw_plan_many_dft(q->T.d, q->T.N, nf, q->buf, NULL, 1, (int)Nt, q->buf, NULL, 1,
                                (int)Nt, FFTW_FORWARD, FFTW_ESTIMATE);
    return q->inv && q->fwd ? 0 : 1;
}

void gd_qp_free(gd_qp *q)
{
    if (q->inv) fftw_destroy_plan(q->inv);
    if (q->fwd) fftw_destroy_plan(q->fwd);
    fftw_free(q->buf);
    free(q->qs);
    free(q->vs);
    free(q->fs);
    free(q->sq);
    free(q->sv);
    free(q->ltime);
    free(q->y);
    free(q->st);
    free(q->P);
    free(q->piv);
    free(q->w1);
    free(q->w2);
    if (q->tr) q->tr->law_time = NULL;
    gd_qp_torus_free(&q->T);
    memset(q, 0, sizeof *q);
}

/* Samples (sample-major, out[p * nf + i]) of the coefficients X or of their time
 * derivative (deriv) over the grid. */
static void synth(gd_qp *q, const double *X, int deriv, double *out)
{
    const int nf = q->nf;
    const long Nt = q->T.Ntot;
    memset(q->buf, 0, (size_t)Nt * nf * sizeof *q->buf);
    for (int i = 0; i < nf; i++) {
        fftw_complex *b = q->buf + (size_t)i * Nt;
        if (!deriv) b[0] = X[i];
        for (int j = 1; j < q->T.nk; j++) {
            double c = X[(size_t)(2 * j - 1) * nf + i], s = X[(size_t)2 * j * nf + i];
            double zr = 0.5 * c, zi = -0.5 * s; /* Z = (C - i S) / 2 */
            if (deriv) {                        /* times i Omega */
                double w = omega_of(&q->T, j), t = zr;
                zr = -w * zi;
                zi = w * t;
            }
            long p = q->T.pos[j], m = q->T.neg[j];
            b[p] += zr + I * zi;
            b[m] += zr - I * zi;
        }
    }
    fftw_execute(q->inv);
    for (int i = 0; i < nf; i++) {
        const fftw_complex *b = q->buf + (size_t)i * Nt;
        for (long p = 0; p < Nt; p++)
            out[(size_t)p * nf + i] = creal(b[p]);
    }
}

/* Coefficients (n) of the samples f (sample-major) on the truncation set. */
static void analyse(gd_qp *q, const double *f, double *F)
{
    const int nf = q->nf;
    const long Nt = q->T.Ntot;
    for (int i = 0; i < nf; i++) {
        fftw_complex *b = q->buf + (size_t)i * Nt;
        for (long p = 0; p < Nt; p++)
            b[p] = f[(size_t)p * nf + i];
    }
    fftw_execute(q->fwd);
    const double s = 1.0 / (double)Nt;
    for (int i = 0; i < nf; i++) {
        const fftw_complex *b = q->buf + (size_t)i * Nt;
        F[i] = creal(b[0]) * s;
        for (int j = 1; j < q->T.nk; j++) {
            long p = q->T.pos[j];
            F[(size_t)(2 * j - 1) * nf + i] = 2.0 * creal(b[p]) * s;
            F[(size_t)2 * j * nf + i] = -2.0 * cimag(b[p]) * s;
        }
    }
}

/* out = L X: the linear part per harmonic */
static void linear_apply(const gd_qp *q, const double *X, double *out)
{
    const int nf = q->nf;
    gd_csc M, D, K;
    gd_transient_matrices(q->tr, &M, &D, &K);
    memset(out, 0, (size_t)q->n * sizeof *out);
    for (int j = 0; j < nf; j++)
        for (int p = K.colptr[j]; p < K.colptr[j + 1]; p++)
            out[K.rowind[p]] += K.values[p] * X[j];
    for (int h = 1; h < q->T.nk; h++) {
        const double w = omega_of(&q->T, h), w2 = w * w;
        const double *xc = X + (size_t)(2 * h - 1) * nf, *xs = xc + nf;
        double *rc = out + (size_t)(2 * h - 1) * nf, *rs = rc + nf;
        for (int j = 0; j < nf; j++) {
            for (int p = K.colptr[j]; p < K.colptr[j + 1]; p++) {
                rc[K.rowind[p]] += K.values[p] * xc[j];
                rs[K.rowind[p]] += K.values[p] * xs[j];
            }
            for (int p = M.colptr[j]; p < M.colptr[j + 1]; p++) {
                rc[M.rowind[p]] -= w2 * M.values[p] * xc[j];
                rs[M.rowind[p]] -= w2 * M.values[p] * xs[j];
            }
            for (int p = D.colptr[j]; p < D.colptr[j + 1]; p++) {
                rc[D.rowind[p]] += w * D.values[p] * xs[j];
                rs[D.rowind[p]] -= w * D.values[p] * xc[j];
            }
        }
    }
}

double gd_qp_point_times(gd_qp *q, long p)
{
    const gd_qp_torus *T = &q->T;
    double th[GD_QP_MAXD];
    long r = p;
    for (int g = T->d - 1; g >= 0; g--) {
        th[g] = TWO_PI * (double)(r % T->N[g]) / T->N[g];
        r /= T->N[g];
    }
    const double t0 = th[0] / T->W[0];
    for (int i = 0; i < q->tr->nlaw; i++) {
        int g = q->b->group[i];
        q->ltime[i] = g >= 0 ? th[g] / T->W[g] : t0;
    }
    q->tr->law_time = q->ltime;
    return t0;
}

/* A view's sample buffers (gd_qpc_view): made when first needed. 0 ok. */
static int view_buffers(gd_qp *q)
{
    if (q->buf) return 0;
    const long Nt = q->T.Ntot;
    q->buf = fftw_malloc((size_t)Nt * q->nf * sizeof *q->buf);
    q->qs = malloc((size_t)Nt * q->nf * sizeof *q->qs);
    q->vs = malloc((size_t)Nt * q->nf * sizeof *q->vs);
    if (!q->buf || !q->qs || !q->vs) return 1;
    q->inv = fftw_plan_many_dft(q->T.d, q->T.N, q->nf, q->buf, NULL, 1, (int)Nt, q->buf, NULL, 1,
                                (int)Nt, FFTW_BACKWARD, FFTW_ESTIMATE);
    return q->inv ? 0 : 1;
}

void gd_qp_view_release(gd_qp *q)
{
    if (q->inv) fftw_destroy_plan(q->inv);
    fftw_free(q->buf);
    free(q->qs);
    free(q->vs);
    q->inv = NULL;
    q->buf = NULL;
    q->qs = q->vs = NULL;
}

int gd_qp_samples(gd_qp *q, const double *X)
{
    if (view_buffers(q)) return 1;
    synth(q, X, 0, q->qs);
    synth(q, X, 1, q->vs);
    return 0;
}

int gd_qp_residual(gd_qp *q, const double *X, double *R, double *scale)
{
    const int nf = q->nf, nt = q->nt;
    const long Nt = q->T.Ntot;
    gd_qp_samples(q, X);
    double *st = q->st;
    int bad = 0;
    for (long p = 0; p < Nt; p++) {
        const double t = gd_qp_point_times(q, p);
        memcpy(q->y, q->qs + (size_t)p * nf, (size_t)nf * sizeof *q->y);
        memcpy(q->y + nf, q->vs + (size_t)p * nf, (size_t)nf * sizeof *q->y);
        double *f = q->fs + (size_t)p * nf;
        gd_transient_local(q->tr, t, q->y, f, st, st + nt);
        for (int i = 0; i < nf; i++)
            if (!isfinite(f[i])) bad = 1;
        for (int k = 0; k < nt; k++) {
            q->sq[(size_t)k * Nt + p] = st[k];
            q->sv[(size_t)k * Nt + p] = st[nt + k];
        }
    }
    q->tr->law_time = NULL;
    double *F = q->w1;
    analyse(q, q->fs, F);
    linear_apply(q, X, R);
    double nl = 0.0, nfo = 0.0;
    for (long i = 0; i < q->n; i++) {
        nl += R[i] * R[i];
        nfo += F[i] * F[i];
        R[i] -= F[i];
    }
    if (scale) *scale = sqrt(fmax(nl, nfo));
    return bad;
}

/* z = J v at the last residual's samples */
static void jac_apply(gd_qp *q, const double *v, double *z)
{
    const int nf = q->nf, nt = q->nt;
    const long Nt = q->T.Ntot;
    double *vq = q->qs, *vv = q->vs, *g = q->fs; /* the residual's samples are not needed now */
    synth(q, v, 0, vq);
    synth(q, v, 1, vv);
    memset(g, 0, (size_t)Nt * nf * sizeof *g);
    for (int k = 0; k < nt; k++) {
        const gd_tr_term *tm = &q->term[k];
        if (!tm->nu || !tm->nw) continue;
        const double *sq = q->sq + (size_t)k * Nt, *sv = q->sv + (size_t)k * Nt;
        for (long p = 0; p < Nt; p++) {
            const double *a = vq + (size_t)p * nf, *b = vv + (size_t)p * nf;
            double x = 0.0, xd = 0.0;
            for (int j = 0; j < tm->nw; j++) {
                x += tm->w[j] * a[tm->w_idx[j]];
                xd += tm->w[j] * b[tm->w_idx[j]];
            }
            const double val = sq[p] * x + sv[p] * xd;
            if (val == 0.0) continue;
            double *gp = g + (size_t)p * nf;
            for (int j = 0; j < tm->nu; j++)
                gp[tm->u_idx[j]] += tm->u[j] * val;
        }
    }
    analyse(q, g, q->w1);
    linear_apply(q, v, z);
    for (long i = 0; i < q->n; i++)
        z[i] -= q->w1[i];
    q->matvecs++;
}

/* The harmonic blocks with the terms' torus means, LU-factored. 0 ok, 1 singular. */
static int prec_factor(gd_qp *q)
{
    const int nf = q->nf, nt = q->nt;
    const long Nt = q->T.Ntot;
    gd_csc M, D, K;
    gd_transient_matrices(q->tr, &M, &D, &K);
    double *mq = malloc((size_t)(nt > 0 ? nt : 1) * 2 * sizeof *mq), *mv = mq + (nt > 0 ? nt : 1);
    if (!mq) return 1;
    for (int k = 0; k < nt; k++) {
        double a = 0.0, b = 0.0;
        for (long p = 0; p < Nt; p++) {
            a += q->sq[(size_t)k * Nt + p];
            b += q->sv[(size_t)k * Nt + p];
        }
        mq[k] = a / Nt;
        mv[k] = b / Nt;
    }
    int bad = 0;
    for (int h = 0; h < q->T.nk && !bad; h++) {
        const double w = omega_of(&q->T, h);
        double complex *A = q->P + (size_t)h * nf * nf; /* column-major */
        memset(A, 0, (size_t)nf * nf * sizeof *A);
        for (int j = 0; j < nf; j++) {
            for (int p = K.colptr[j]; p < K.colptr[j + 1]; p++)
                A[K.rowind[p] + (size_t)j * nf] += K.values[p];
            for (int p = M.colptr[j]; p < M.colptr[j + 1]; p++)
                A[M.rowind[p] + (size_t)j * nf] -= w * w * M.values[p];
            for (int p = D.colptr[j]; p < D.colptr[j + 1]; p++)
                A[D.rowind[p] + (size_t)j * nf] += I * w * D.values[p];
        }
        for (int k = 0; k < nt; k++) {
            const gd_tr_term *tm = &q->term[k];
            const double complex s = mq[k] + I * w * mv[k];
            if (s == 0.0) continue;
            for (int a = 0; a < tm->nu; a++)
                for (int c = 0; c < tm->nw; c++)
                    A[tm->u_idx[a] + (size_t)tm->w_idx[c] * nf] -= tm->u[a] * tm->w[c] * s;
        }
        lapack_int info = LAPACKE_zgetrf(LAPACK_COL_MAJOR, nf, nf, (lapack_complex_double *)A, nf,
                                         q->piv + (size_t)h * nf);
        if (info != 0) bad = 1;
    }
    free(mq);
    return bad;
}

/* z = P^-1 r */
static void prec_solve(gd_qp *q, const double *r, double *z)
{
    const int nf = q->nf;
    double complex *b = malloc((size_t)nf * sizeof *b);
    if (!b) {
        memcpy(z, r, (size_t)q->n * sizeof *z);
        return;
    }
    for (int h = 0; h < q->T.nk; h++) {
        const double *rc = r + (size_t)(h ? 2 * h - 1 : 0) * nf, *rs = rc + nf;
        for (int i = 0; i < nf; i++)
            b[i] = h ? rc[i] - I * rs[i] : rc[i];
        LAPACKE_zgetrs(LAPACK_COL_MAJOR, 'N', nf, 1,
                       (const lapack_complex_double *)(q->P + (size_t)h * nf * nf), nf,
                       q->piv + (size_t)h * nf, (lapack_complex_double *)b, nf);
        double *zc = z + (size_t)(h ? 2 * h - 1 : 0) * nf, *zs = zc + nf;
        for (int i = 0; i < nf; i++) {
            zc[i] = creal(b[i]);
            if (h) zs[i] = -cimag(b[i]);
        }
    }
    free(b);
}

static int atimes(void *data, N_Vector v, N_Vector z)
{
    jac_apply(data, N_VGetArrayPointer(v), N_VGetArrayPointer(z));
    return 0;
}

static int psolve(void *data, N_Vector r, N_Vector z, realtype tol, int lr)
{
    prec_solve(data, N_VGetArrayPointer(r), N_VGetArrayPointer(z));
    return 0;
}
int gd_qp_damped_step(long n, const double *X, const double *dx, double nr, gd_qp_residual_fn res,
                      void *ctx, double *w2, double *R, double *scale)
{
    /* a step that raises the residual is halved (up to 4 times) */
    double lam = 1.0;
    for (int ls = 0;; ls++) {
        for (long i = 0; i < n; i++)
            w2[i] = X[i] + lam * dx[i];
        double n2 = 0.0;
        if (!res(ctx, w2, R, scale)) {
            for (long i = 0; i < n; i++)
                n2 += R[i] * R[i];
            if (sqrt(n2) < nr) return 0;
        }
        if (ls >= 4) return 1;
        lam *= 0.5;
    }
}

static int full_residual(void *q, const double *X, double *R, double *scale)
{
    return gd_qp_residual(q, X, R, scale);
}

int gd_qp_newton(gd_qp *q, double *X, double tol, int max_iter, double *resid, int *iters,
                 char *msg, size_t cap)
{
    const long n = q->n;
    SUNContext ctx = NULL;
    N_Vector x = NULL, b = NULL;
    SUNLinearSolver LS = NULL;
    double *R = malloc((size_t)n * sizeof *R);
    int rc = 1;
    *iters = 0;
    *resid = INFINITY;
    if (!R || SUNContext_Create(NULL, &ctx)) goto done;
    x = N_VNew_Serial(n, ctx);
    b = N_VNew_Serial(n, ctx);
    if (!x || !b) goto done;
    LS = SUNLinSol_SPGMR(x, SUN_PREC_RIGHT, 40, ctx);
    if (!LS) goto done;
    SUNLinSol_SPGMRSetMaxRestarts(LS, 4);
    SUNLinSol_SPGMRSetGSType(LS, SUN_MODIFIED_GS);
    SUNLinSolSetATimes(LS, q, atimes);
    SUNLinSolSetPreconditioner(LS, q, NULL, psolve);
    if (SUNLinSolInitialize(LS)) goto done;
    double scale = 0.0;
    if (gd_qp_residual(q, X, R, &scale)) {
        snprintf(msg, cap, "a force is not finite at the start");
        goto done;
    }
    for (int it = 0;; it++) {
        double nr = 0.0;
        for (long i = 0; i < n; i++)
            nr += R[i] * R[i];
        nr = sqrt(nr);
        *resid = scale > 0 ? nr / scale : nr;
        if (*resid <= tol) {
            rc = 0;
            goto done;
        }
        if (it >= max_iter) {
            snprintf(msg, cap,
                     "Newton did not converge in %d steps (relative residual %.2g, multi-frequency "
                     "harmonic balance of order %d)",
                     max_iter, *resid, q->T.H);
            goto done;
        }
        if (prec_factor(q)) {
            snprintf(msg, cap, "a harmonic block of the preconditioner is singular");
            goto done;
        }
        double *bb = N_VGetArrayPointer(b), *xx = N_VGetArrayPointer(x);
        for (long i = 0; i < n; i++) {
            bb[i] = -R[i];
            xx[i] = 0.0;
        }
        /* inexact Newton: the linear residual a small share of the nonlinear one, no
         * smaller than the target needs */
        double ltol = fmax(1e-3 * nr, 0.1 * tol * scale);
        int lrc = SUNLinSolSolve(LS, NULL, x, b, ltol);
        if (lrc < 0) {
            snprintf(msg, cap, "GMRES failed (%d) at Newton step %d", lrc, it);
            goto done;
        }
        if (gd_qp_damped_step(n, X, xx, nr, full_residual, q, q->w2, R, &scale)) {
            snprintf(msg, cap,
                     "Newton stalled at step %d (relative residual %.2g, multi-frequency "
                     "harmonic balance of order %d)",
                     it, *resid, q->T.H);
            goto done;
        }
        memcpy(X, q->w2, (size_t)n * sizeof *X); /* R and scale are its residual's */
        (*iters)++;
    }
done:
    if (LS) SUNLinSolFree(LS);
    if (x) N_VDestroy(x);
    if (b) N_VDestroy(b);
    if (ctx) SUNContext_Free(&ctx);
    free(R);
    return rc;
}

void gd_qp_eval(const gd_qp *q, const double *X, double t, double *qt, double *vt)
{
    const int nf = q->nf;
    for (int i = 0; i < nf; i++) {
        qt[i] = X[i];
        vt[i] = 0.0;
    }
    for (int j = 1; j < q->T.nk; j++) {
        const double w = omega_of(&q->T, j), c = cos(w * t), s = sin(w * t);
        const double *xc = X + (size_t)(2 * j - 1) * nf, *xs = xc + nf;
        for (int i = 0; i < nf; i++) {
            qt[i] += xc[i] * c + xs[i] * s;
            vt[i] += w * (xs[i] * c - xc[i] * s);
        }
    }
}
