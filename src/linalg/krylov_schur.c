/* Krylov-Schur (Stewart, SIAM J. Matrix Anal. Appl. 23, 2001) in real arithmetic for
 * the eigenvalues of largest magnitude of a real operator: Arnoldi with full (twice
 * classical Gram-Schmidt) reorthogonalisation, real Schur form of the Rayleigh
 * quotient (dgees), reordering of the wanted Schur vectors to the front (dtrsen) and
 * restart from them. Written here rather than taken from ARPACK because ARPACK keeps
 * its state in Fortran SAVE variables and cannot run in several threads at once; this
 * one keeps everything in its arguments. The vector kernels are plain loops (no
 * threaded BLAS inside a parallel sweep); the m x m problems go to LAPACK.
 *
 * The first pass grows one Arnoldi decomposition and checks for convergence at a few
 * sizes (from twice the wanted count, then extrapolating the residual decay), so a
 * well-separated problem stops without any restart. Before a restart the Rayleigh
 * quotient is still Hessenberg, and a check needs only its eigenvalues (Hessenberg QR)
 * and the wanted eigenvectors (inverse iteration, dhsein); the full Schur form is
 * computed only to restart. A deflated check after convergence finds the further
 * copies of repeated eigenvalues, which one start vector cannot see (see "Repeated
 * eigenvalues" below). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"

/* The vector kernels below are also compiled for AVX2 and AVX-512 and picked at load
 * time (function multiversioning, GCC and Clang on x86-64 Linux); elsewhere they are
 * the portable loops. The clone depends on the machine only, so results do not depend
 * on the number of threads. */
#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__)
#define GD_VECTOR_KERNEL                                                                           \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define GD_VECTOR_KERNEL
#endif

static double dot(const double *a, const double *b, int n)
{
    double s = 0;
#pragma omp simd reduction(+ : s)
    for (int i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

/* sum a[i * lda] b[i]: a row of a column-major matrix times a vector */
static double dot_strided(const double *a, int lda, const double *b, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += a[(size_t)i * lda] * b[i];
    return s;
}

/* h[c] = V[:, c]^T w for c < k, four columns per sweep over w */
GD_VECTOR_KERNEL static void dots(const double *V, int n, int k, const double *w, double *h)
{
    int c = 0;
    for (; c + 4 <= k; c += 4) {
        const double *v0 = V + (size_t)c * n, *v1 = v0 + n, *v2 = v1 + n, *v3 = v2 + n;
        double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
#pragma omp simd reduction(+ : s0, s1, s2, s3)
        for (int i = 0; i < n; i++) {
            s0 += v0[i] * w[i];
            s1 += v1[i] * w[i];
            s2 += v2[i] * w[i];
            s3 += v3[i] * w[i];
        }
        h[c] = s0;
        h[c + 1] = s1;
        h[c + 2] = s2;
        h[c + 3] = s3;
    }
    for (; c < k; c++)
        h[c] = dot(V + (size_t)c * n, w, n);
}

/* w -= V[:, 0:k] h, four columns per sweep */
GD_VECTOR_KERNEL static void subtract(const double *V, int n, int k, const double *h, double *w)
{
    int c = 0;
    for (; c + 4 <= k; c += 4) {
        const double *v0 = V + (size_t)c * n, *v1 = v0 + n, *v2 = v1 + n, *v3 = v2 + n;
        double a0 = h[c], a1 = h[c + 1], a2 = h[c + 2], a3 = h[c + 3];
#pragma omp simd
        for (int i = 0; i < n; i++)
            w[i] -= (a0 * v0[i] + a1 * v1[i]) + (a2 * v2[i] + a3 * v3[i]);
    }
    for (; c < k; c++) {
        const double *v = V + (size_t)c * n;
        double a = h[c];
#pragma omp simd
        for (int i = 0; i < n; i++)
            w[i] -= a * v[i];
    }
}

/* w -= V[:, 0:k] h after h = V^T w; repeated once when the first pass cancelled most
 * of w (Daniel, Gragg, Kaufman and Stewart's criterion), as twice is enough. */
static void orthogonalise(const double *V, int n, int k, double *w, double *h, double *h2)
{
    double before = sqrt(dot(w, w, n));
    dots(V, n, k, w, h);
    subtract(V, n, k, h, w);
    double after = sqrt(dot(w, w, n));
    if (after > 0.7071 * before) return;
    dots(V, n, k, w, h2);
    subtract(V, n, k, h2, w);
    for (int c = 0; c < k; c++)
        h[c] += h2[c];
}

/* Z[:, 0:p] = V[0:n, 0:m] Q[:, 0:p] (V with leading dimension ldv, Q is m x m, Z is
 * n x p) */
GD_VECTOR_KERNEL static void basis_times(const double *V, int ldv, int n, int m, const double *Q,
                                         int p, double *Z)
{
    for (int c = 0; c < p; c++) {
        double *z = Z + (size_t)c * n;
        const double *q = Q + (size_t)c * m;
        for (int i = 0; i < n; i++)
            z[i] = 0;
        int r = 0;
        for (; r + 4 <= m; r += 4) {
            const double *v0 = V + (size_t)r * ldv, *v1 = v0 + ldv, *v2 = v1 + ldv, *v3 = v2 + ldv;
            double a0 = q[r], a1 = q[r + 1], a2 = q[r + 2], a3 = q[r + 3];
#pragma omp simd
            for (int i = 0; i < n; i++)
                z[i] += (a0 * v0[i] + a1 * v1[i]) + (a2 * v2[i] + a3 * v3[i]);
        }
        for (; r < m; r++) {
            const double *v = V + (size_t)r * ldv;
            double a = q[r];
#pragma omp simd
            for (int i = 0; i < n; i++)
                z[i] += a * v[i];
        }
    }
}

/* Deterministic pseudo-random vector (a fixed linear congruential sequence). */
static void start_vector(double *v, int n, unsigned seed)
{
    unsigned long long x = 0x9E3779B97F4A7C15ull ^ seed;
    for (int i = 0; i < n; i++) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        v[i] = (double)(x >> 11) / 9007199254740992.0 - 0.5;
    }
}

static double nrm2(const double *v, int n)
{
    return sqrt(dot(v, v, n));
}

/* Orders eigenvalue indices by decreasing magnitude (ties: index). */
typedef struct mag_index {
    double mag;
    int i;
} mag_index;
static int cmp_mag(const void *a, const void *b)
{
    const mag_index *x = a, *y = b;
    if (x->mag != y->mag) return x->mag < y->mag ? 1 : -1;
    return x->i - y->i;
}

int gd_ks_work_init(gd_ks_work *w, int n, int ncv)
{
    memset(w, 0, sizeof *w);
    if (ncv > n) ncv = n;
    int m = ncv;
    w->n = n;
    w->ncv = m;
    w->V = malloc((size_t)n * (size_t)(m + 1) * sizeof(double));
    w->H = malloc((size_t)(m + 1) * (size_t)m * sizeof(double));
    w->T = malloc((size_t)m * m * sizeof(double));
    w->Q = malloc((size_t)m * m * sizeof(double));
    w->X = malloc((size_t)m * m * sizeof(double));
    w->S = malloc((size_t)m * m * sizeof(double));
    w->work = malloc((size_t)(m + 3) * m * sizeof(double));
    w->wr = malloc((size_t)m * sizeof(double));
    w->wr2 = malloc((size_t)m * sizeof(double));
    w->wi = malloc((size_t)m * sizeof(double));
    w->h = malloc((size_t)(m + 1) * sizeof(double));
    w->h2 = malloc((size_t)(m + 1) * sizeof(double));
    w->b = malloc((size_t)m * sizeof(double));
    w->res = malloc((size_t)m * sizeof(double));
    w->Z = malloc((size_t)n * (size_t)m * sizeof(double));
    w->sel = malloc((size_t)m * sizeof(lapack_logical));
    w->grp = malloc((size_t)m * sizeof(int));
    w->ifail = malloc((size_t)2 * m * sizeof(lapack_int));
    w->order = malloc((size_t)m * sizeof(mag_index));
    if (!w->V || !w->H || !w->T || !w->Q || !w->X || !w->S || !w->work || !w->wr || !w->wr2 ||
        !w->wi || !w->h || !w->h2 || !w->b || !w->res || !w->Z || !w->sel || !w->grp || !w->ifail ||
        !w->order) {
        gd_ks_work_free(w);
        return 1;
    }
    return 0;
}

void gd_ks_work_free(gd_ks_work *w)
{
    free(w->V);
    free(w->H);
    free(w->T);
    free(w->Q);
    free(w->X);
    free(w->S);
    free(w->work);
    free(w->wr);
    free(w->wr2);
    free(w->wi);
    free(w->h);
    free(w->h2);
    free(w->b);
    free(w->res);
    free(w->Z);
    free(w->sel);
    free(w->grp);
    free(w->ifail);
    free(w->order);
    memset(w, 0, sizeof *w);
}

/* Selects the largest eigenvalues, keeping conjugate pairs together, until at least
 * target are selected; returns the count. */
static int select_largest(const double *wr, const double *wi, int m, int target, int *sel,
                          mag_index *order)
{
    for (int i = 0; i < m; i++) {
        order[i] = (mag_index){hypot(wr[i], wi[i]), i};
        sel[i] = 0;
    }
    qsort(order, (size_t)m, sizeof *order, cmp_mag);
    int cnt = 0;
    for (int r = 0; r < m && cnt < target; r++) {
        int i = order[r].i;
        if (sel[i]) continue;
        sel[i] = 1;
        cnt++;
        if (wi[i] != 0) {
            int partner = wi[i] > 0 ? i + 1 : i - 1;
            if (partner >= 0 && partner < m && !sel[partner]) {
                sel[partner] = 1;
                cnt++;
            }
        }
    }
    return cnt;
}

void gd_ks_result_free(gd_ks_result *r)
{
    free(r->mu_re);
    free(r->mu_im);
    free(r->vec_re);
    free(r->vec_im);
    memset(r, 0, sizeof *r);
}

/* Basis size of the first convergence check while the first pass grows: shift-invert
 * Ritz values of the lowest modes typically converge once the basis holds about twice
 * the wanted count (measured on shaft models); each check costs a Hessenberg QR. */
static int first_check(int nev, int ncv)
{
    int m = nev > 8 ? 2 * nev : nev + 8;
    return m < ncv ? m : ncv;
}

/* Basis size of the first check from a warm start vector. */
static int warm_check(int nev, int ncv)
{
    int m = nev + 4;
    return m < ncv ? m : ncv;
}

/* Basis size of the next check: the worst residual falls about geometrically with
 * the basis size, so extrapolate from the last two checks to the size where it reaches
 * tol (at least two more vectors); a fixed step after the first. */
static int next_check(int m, double worst, int prev_m, double prev_worst, int nev, double tol)
{
    int add = nev / 6 > 4 ? nev / 6 : 4;
    if (prev_m > 0 && worst < prev_worst && worst > 0) {
        double rate = log(prev_worst / worst) / (m - prev_m);
        double need = ceil(log(worst / tol) / rate);
        add = need < 2 ? 2 : need > 4 * add ? 4 * add : (int)need;
    }
    return m + add;
}

/* T = the leading m x m block of H (leading dimension m), for LAPACK to overwrite. */
static void copy_rayleigh_quotient(gd_ks_work *ws, int m)
{
    int ldh = ws->ncv + 1;
    for (int j = 0; j < m; j++)
        memcpy(ws->T + (size_t)j * m, ws->H + (size_t)j * ldh, (size_t)m * sizeof *ws->T);
}

/* Real Schur form T = Q^T H Q of the m x m Rayleigh quotient, eigenvalues in wr, wi. */
static gd_status schur_form(gd_ks_work *ws, int m)
{
    copy_rayleigh_quotient(ws, m);
    lapack_int sdim = 0;
    memset(ws->Q, 0, (size_t)m * m * sizeof *ws->Q); /* LAPACKE checks outputs for NaN */
    if (LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'N', NULL, m, ws->T, m, &sdim, ws->wr, ws->wi, ws->Q,
                      m))
        return GD_ENUMERIC;
    return GD_OK;
}

/* The Ritz pairs of the nev largest Ritz values of the m-vector decomposition: their
 * coefficient vectors in the basis as the columns of S (one column per real value,
 * the real and imaginary parts for each conjugate pair), grp[g] = the index of the
 * value of group g (the member with positive imaginary part), and the relative
 * residuals res[g] = |beta e_m^T s| / (|s| |mu|). While H is still Hessenberg (no
 * restart yet), only its eigenvalues are computed (dhseqr) and the wanted vectors come
 * from inverse iteration on H (dhsein). Returns the group count in *ngrp and the
 * count of selected values in *nsel. */
static gd_status ritz_pairs(gd_ks_work *ws, int m, int nev, int hessenberg, double beta, int *ngrp,
                            int *nsel)
{
    int ldh = ws->ncv + 1;
    double *wr = ws->wr, *wi = ws->wi, *S = ws->S;
    gd_status st;
    if (hessenberg) {
        copy_rayleigh_quotient(ws, m);
        lapack_int lw = (lapack_int)((m + 3) * m);
        if (LAPACKE_dhseqr_work(LAPACK_COL_MAJOR, 'E', 'N', m, 1, m, ws->T, m, wr, wi, NULL, 1,
                                ws->work, lw))
            return GD_ENUMERIC;
    } else if ((st = schur_form(ws, m))) {
        return st;
    }
    *nsel = select_largest(wr, wi, m, nev, ws->sel, ws->order);
    int g = 0, ncol = 0;
    for (int j = 0; j < m; j++)
        if (ws->sel[j] && wi[j] >= 0) {
            ws->grp[g++] = j;
            ncol += wi[j] > 0 ? 2 : 1;
        }
    *ngrp = g;
    memset(S, 0, (size_t)m * ncol * sizeof *S);
    lapack_int used = 0;
    if (hessenberg) {
        /* dhsein may perturb close eigenvalues of its wr copy to separate the vectors */
        memcpy(ws->wr2, wr, (size_t)m * sizeof *wr);
        lapack_int info =
            LAPACKE_dhsein_work(LAPACK_COL_MAJOR, 'R', 'Q', 'N', ws->sel, m, ws->H, ldh, ws->wr2,
                                wi, NULL, 1, S, m, ncol, &used, ws->work, ws->ifail, ws->ifail + m);
        if (info < 0) return GD_ENUMERIC;
        if (info > 0) /* a vector did not converge: take the Schur route instead */
            return ritz_pairs(ws, m, nev, 0, beta, ngrp, nsel);
    } else {
        memset(ws->X, 0, (size_t)m * ncol * sizeof *ws->X);
        if (LAPACKE_dtrevc_work(LAPACK_COL_MAJOR, 'R', 'S', ws->sel, m, ws->T, m, NULL, 1, ws->X, m,
                                ncol, &used, ws->work))
            return GD_ENUMERIC;
        /* S = Q X: the vectors of T back in the basis of H */
        for (int c = 0; c < ncol; c++)
            for (int i = 0; i < m; i++)
                S[i + (size_t)c * m] = dot_strided(ws->Q + i, m, ws->X + (size_t)c * m, m);
    }
    for (int k = 0, c = 0; k < g; k++) {
        int j = ws->grp[k], pair = wi[j] > 0;
        const double *sr = S + (size_t)c * m, *si = pair ? sr + m : NULL;
        double ns = sqrt(dot(sr, sr, m) + (pair ? dot(si, si, m) : 0));
        double last = pair ? hypot(sr[m - 1], si[m - 1]) : fabs(sr[m - 1]);
        double mag = hypot(wr[j], wi[j]);
        ws->res[k] = fabs(beta) * last / (ns * (mag > 0 ? mag : 1));
        c += pair ? 2 : 1;
    }
    return GD_OK;
}

/* The selected Ritz pairs: one basis product Y = V S over the first nout rows, then
 * each group's vector (a conjugate pair gives both members, the second the conjugate
 * of the first). */
static gd_status ritz_output(gd_ks_work *ws, int n, int nout, int m, int ngrp, int nsel,
                             gd_ks_result *out)
{
    const double *wr = ws->wr, *wi = ws->wi;
    double *Y = ws->Z;
    out->mu_re = malloc((size_t)nsel * sizeof(double));
    out->mu_im = malloc((size_t)nsel * sizeof(double));
    out->vec_re = malloc((size_t)nout * nsel * sizeof(double));
    out->vec_im = malloc((size_t)nout * nsel * sizeof(double));
    if (!out->mu_re || !out->mu_im || !out->vec_re || !out->vec_im) return GD_ENOMEM;
    int ncol = 0;
    for (int k = 0; k < ngrp; k++)
        ncol += wi[ws->grp[k]] > 0 ? 2 : 1;
    basis_times(ws->V, n, nout, m, ws->S, ncol, Y);
    int c = 0, col = 0;
    for (int k = 0; k < ngrp; k++) {
        int j = ws->grp[k], pair = wi[j] > 0;
        const double *yr = Y + (size_t)col * nout, *yi = pair ? yr + nout : NULL;
        double ny = sqrt(dot(yr, yr, nout) + (pair ? dot(yi, yi, nout) : 0));
        double inv = ny > 0 ? 1.0 / ny : 1.0;
        for (int member = 0; member < (pair ? 2 : 1); member++, c++) {
            double sg = member ? -1.0 : 1.0;
            double *vr = out->vec_re + (size_t)c * nout, *vi = out->vec_im + (size_t)c * nout;
            for (int i = 0; i < nout; i++) {
                vr[i] = yr[i] * inv;
                vi[i] = pair ? sg * inv * yi[i] : 0;
            }
            out->mu_re[c] = wr[j];
            out->mu_im[c] = sg * wi[j];
        }
        col += pair ? 2 : 1;
    }
    out->nconv = c;
    return GD_OK;
}

/* The Krylov-Schur iteration proper, from the start vector of the given seed. On
 * GD_OK the nev largest Ritz values (*nsel_out with conjugates) of the *m-vector
 * decomposition in ws have converged, their vectors in ws->S; GD_ENUMERIC: not within maxit
 * restarts. */
static gd_status ks_iterate(gd_op_fn op, void *ctx, int n, int nev, int ncv, double tol, int maxit,
                            unsigned seed, gd_ks_work *ws, int *m_out, int *nsel_out,
                            int *schur_valid, int *iterations)
{
    int ldh = ws->ncv + 1;
    double *V = ws->V, *H = ws->H, *T = ws->T, *Q = ws->Q, *wr = ws->wr, *wi = ws->wi;
    double *h = ws->h, *h2 = ws->h2, *b = ws->b, *res = ws->res, *Z = ws->Z;
    lapack_logical *sel = ws->sel;
    mag_index *order = ws->order;
    gd_status st;
    memset(H, 0, (size_t)ldh * ncv * sizeof *H);
    int warm = seed == 1u && ws->v0;
    if (warm)
        memcpy(V, ws->v0, (size_t)n * sizeof *V);
    else
        start_vector(V, n, seed);
    double nv = nrm2(V, n);
    if (!(nv > 0) || !isfinite(nv)) { /* an unusable warm vector: the fixed one */
        start_vector(V, n, seed);
        nv = nrm2(V, n);
        warm = 0;
    }
    for (int i = 0; i < n; i++)
        V[i] /= nv;
    /* the first pass grows to the check sizes; after a restart, to ncv at once. A warm
     * start vector lies nearly in the wanted invariant subspace, whose nev vectors the
     * Krylov space holds after about nev steps: check there first */
    int k = 0, m = warm ? warm_check(nev, ncv) : first_check(nev, ncv), restarted = 0, prev_m = 0;
    double prev_worst = 0;
    for (int it = 0; it <= maxit;) {
        for (int j = k; j < m; j++) {
            double *w = V + (size_t)(j + 1) * n;
            op(ctx, V + (size_t)j * n, w);
            orthogonalise(V, n, j + 1, w, h, h2);
            double beta = nrm2(w, n), hn = nrm2(h, j + 1);
            for (int r = 0; r <= j; r++)
                H[r + (size_t)j * ldh] = h[r];
            if (!(beta > 1e-13 * hn)) { /* invariant subspace: continue with a fresh vector */
                start_vector(w, n, 7u + (unsigned)j);
                orthogonalise(V, n, j + 1, w, h, h2);
                beta = 0;
                double inv = 1.0 / nrm2(w, n);
                for (int i = 0; i < n; i++)
                    w[i] *= inv;
            } else {
                double inv = 1.0 / beta;
                for (int i = 0; i < n; i++)
                    w[i] *= inv;
            }
            H[j + 1 + (size_t)j * ldh] = beta;
        }
        k = m;
        double beta = H[m + (size_t)(m - 1) * ldh];
        int ngrp = 0, nsel = 0;
        if ((st = ritz_pairs(ws, m, nev, !restarted, beta, &ngrp, &nsel))) return st;
        /* the nev largest must have converged */
        double worst = 0;
        for (int g = 0; g < ngrp; g++)
            worst = res[g] > worst || isnan(res[g]) ? res[g] : worst;
        *iterations = it;
        if (worst <= tol) {
            *m_out = m;
            *nsel_out = nsel;
            *schur_valid = restarted; /* ritz_pairs left T, Q = the Schur form of H */
            return GD_OK;
        }
        if (it == maxit && m == ncv) return GD_ENUMERIC;
        if (m < ncv) { /* grow the same Arnoldi decomposition */
            int next = next_check(m, worst, prev_m, prev_worst, nev, tol);
            prev_m = m;
            prev_worst = worst;
            m = next < ncv ? next : ncv;
            continue;
        }
        /* restart from the wanted values and half of the rest: reorder them to the
         * front of the Schur form, V[:, 0:p] = V Q[:, 0:p], V[:, p] = v_m,
         * H = [T_pp; b^T] */
        int keep = nev + (m - nev) / 2;
        if (keep > m - 2) keep = m - 2;
        if (!restarted && (st = schur_form(ws, m))) return st;
        select_largest(wr, wi, m, keep, sel, order);
        lapack_int msel = 0;
        double sep, s;
        /* the _work form with our own iwork: dtrsen writes iwork(1) even for job 'N',
         * which LAPACKE_dtrsen passes as NULL */
        lapack_int iwork[1];
        if (LAPACKE_dtrsen_work(LAPACK_COL_MAJOR, 'N', 'V', sel, m, T, m, Q, m, wr, wi, &msel, &s,
                                &sep, h2, m, iwork, 1))
            return GD_ENUMERIC;
        int p = (int)msel;
        for (int i = 0; i < p; i++)
            b[i] = beta * Q[(m - 1) + (size_t)i * m];
        basis_times(V, n, n, m, Q, p, Z);
        memcpy(V + (size_t)p * n, V + (size_t)m * n, (size_t)n * sizeof *V);
        memcpy(V, Z, (size_t)n * p * sizeof *V);
        memset(H, 0, (size_t)ldh * ncv * sizeof *H);
        for (int j = 0; j < p; j++) {
            for (int i = 0; i < p; i++)
                H[i + (size_t)j * ldh] = T[i + (size_t)j * m];
            H[p + (size_t)j * ldh] = b[j];
        }
        k = p;
        m = ncv;
        restarted = 1;
        it++;
    }
    return GD_ENUMERIC;
}

/* ritz_output for the converged state ks_iterate leaves (ritz_pairs' selection; dhsein
 * and dtrevc have cleared the second member of each selected pair). */
static gd_status ritz_output_converged(gd_ks_work *ws, int n, int nout, int m, gd_ks_result *out)
{
    int ngrp = 0, nsel = 0;
    for (int j = 0; j < m; j++)
        if (ws->sel[j] && ws->wi[j] >= 0) {
            ngrp++;
            nsel += ws->wi[j] > 0 ? 2 : 1;
        }
    return ritz_output(ws, n, nout, m, ngrp, nsel, out);
}

/* Repeated eigenvalues. A single start vector v0 meets an eigenspace of dimension > 1
 * only in the direction of v0's own component, so its Krylov space holds one copy of a
 * multiple eigenvalue (exactly so for the double lateral pairs of an isotropic rotor
 * at rest) and the iteration converges with the next distinct value in the other
 * copy's place. Remedy, a deflated restart: lock the converged Schur vectors L
 * (Op L = L T_L), then run a check on the deflated operator (I - L L^T) Op (whose
 * spectrum is that of Op without T_L's eigenvalues, L being its null space) from a new
 * start vector; if its largest eigenvalue is larger than the smallest accepted one, it
 * is a value the first pass missed: lock it too (T_L grows by [G; T_new], G = L^T Op Y)
 * and check again, so a triple value takes two checks. Preferred to a block start of
 * fixed width because it finds any multiplicity and costs one small check (about
 * first_check(1) operator steps) when there is none.
 *
 * The eigenvectors come from the locked Schur form (dtrevc on T_L). A copy's Schur
 * vector y is orthogonal to L and, the eigenvalue being repeated, already an
 * eigenvector of Op (the eigenspace meets L's complement); its coupling G is then
 * rounding noise at the tolerance level, and dividing that by the ~0 gap between the
 * copies would turn y into a duplicate of the locked copy. So a coupling below the
 * convergence tolerance is set to zero: y keeps a residual within the tolerance. */
/* The check: a basis of at most GD_KS_CHECK_NCV vectors (measured on rig366, 6 to 24
 * modes: 20 settles in one pass or one restart, 30 costs the same), converged to
 * GD_KS_CHECK_TOL first; a largest value below the accepted ones by more than
 * GD_KS_CHECK_MARGIN (10 times that residual) is decided there, anything closer is
 * converged to the full tolerance before it is compared. */
#define GD_KS_CHECK_NCV 20
#define GD_KS_CHECK_TOL 1e-4
#define GD_KS_CHECK_MARGIN 1e-3

typedef struct locked {
    int n, cap, nl;  /* basis rows, capacity, locked count */
    double *L, *TL;  /* n x cap basis; cap x cap quasi-triangular T_L */
    double *lr, *li; /* eigenvalues of T_L */
    double *y;       /* n scratch */
} locked;

typedef struct deflated {
    gd_op_fn op;
    void *ctx;
    locked *lk;
    double *h, *h2;
} deflated;

/* y = (I - L L^T) Op x */
static void deflated_apply(void *c, const double *x, double *y)
{
    deflated *d = c;
    d->op(d->ctx, x, y);
    orthogonalise(d->lk->L, d->lk->n, d->lk->nl, y, d->h, d->h2);
}

/* Schur vectors of the p converged Ritz values of the m-vector decomposition in ws,
 * from their coefficient vectors S (ritz_pairs): S = Qs R (QR), B = Qs^T H Qs = W T W^T
 * (real Schur form), so V Qs W spans the same invariant subspace with Rayleigh quotient
 * T. A p x p Schur form instead of the m x m one (dhseqr dominated the cost of a
 * lock: measured 15 % of the whole solve for 12 modes of rig366). Writes Qs W into X
 * (m x p), T into T (p x p) and the eigenvalues into wr, wi. Returns 1 when the vectors
 * are nearly dependent (a defective cluster such as the rigid-body zero), for the full
 * Schur route instead (T and Q untouched), -1 on failure. */
static int small_schur(gd_ks_work *ws, int m, int p)
{
    int ldh = ws->ncv + 1;
    double *A = ws->X, *HQ = ws->Z, *tau = ws->b;
    lapack_int lw = (lapack_int)((m + 3) * m);
    for (int c = 0; c < p; c++) { /* unit columns: R's diagonal measures the angles */
        double *a = A + (size_t)c * m, nr = nrm2(ws->S + (size_t)c * m, m);
        if (!(nr > 0)) return 1;
        for (int i = 0; i < m; i++)
            a[i] = ws->S[i + (size_t)c * m] / nr;
    }
    if (LAPACKE_dgeqrf_work(LAPACK_COL_MAJOR, m, p, A, m, tau, ws->work, lw)) return 1;
    /* the difference of two vectors at an angle a is accurate to ~eps / a^2: a
     * defective value (the rigid-body zero), whose Ritz vectors meet at ~sqrt(tol),
     * takes the full route */
    for (int c = 0; c < p; c++)
        if (!(fabs(A[c + (size_t)c * m]) > 1e-3)) return 1;
    if (LAPACKE_dorgqr_work(LAPACK_COL_MAJOR, m, p, p, A, m, tau, ws->work, lw)) return 1;
    for (int c = 0; c < p; c++) /* HQ = H Qs (not Hessenberg after a restart) */
        for (int i = 0; i < m; i++) {
            double sum = 0;
            for (int q = 0; q < m; q++)
                sum += ws->H[i + (size_t)q * ldh] * A[q + (size_t)c * m];
            HQ[i + (size_t)c * m] = sum;
        }
    for (int c = 0; c < p; c++)
        for (int i = 0; i < p; i++)
            ws->T[i + (size_t)c * p] = dot(A + (size_t)i * m, HQ + (size_t)c * m, m);
    lapack_int sdim = 0;
    memset(ws->Q, 0, (size_t)p * p * sizeof *ws->Q);
    if (LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'N', NULL, p, ws->T, p, &sdim, ws->wr, ws->wi, ws->Q,
                      p))
        return -1;
    for (int c = 0; c < p; c++) /* HQ = Qs W */
        for (int i = 0; i < m; i++)
            HQ[i + (size_t)c * m] = dot_strided(A + i, m, ws->Q + (size_t)c * p, p);
    memcpy(A, HQ, (size_t)m * p * sizeof *A);
    return 0;
}

/* Locks the Schur vectors of the nsel converged Ritz values (the nev largest) of the
 * m-vector decomposition in ws; returns the count locked, < 0 on failure. */
static int lock_converged(gd_op_fn op, void *ctx, gd_ks_work *ws, int m, int nev, int nsel,
                          int schur_valid, double tol, locked *lk)
{
    int n = lk->n, cap = lk->cap, nl = lk->nl, p = nsel, ldt = nsel;
    const double *X = ws->X;
    int rc = small_schur(ws, m, nsel);
    if (rc < 0) return -1;
    if (rc > 0) { /* the full Schur form, wanted values to the front */
        if (!schur_valid && schur_form(ws, m)) return -1;
        select_largest(ws->wr, ws->wi, m, nev, ws->sel, ws->order);
        lapack_int msel = 0, iwork[1];
        double sep, s;
        if (LAPACKE_dtrsen_work(LAPACK_COL_MAJOR, 'N', 'V', ws->sel, m, ws->T, m, ws->Q, m, ws->wr,
                                ws->wi, &msel, &s, &sep, ws->h2, m, iwork, 1))
            return -1;
        p = (int)msel;
        ldt = m;
        X = ws->Q;
    }
    const double *T = ws->T;
    if (nl + p > cap) return 0;
    double *Y = lk->L + (size_t)nl * n;
    basis_times(ws->V, n, n, m, X, p, Y);
    double tn = 0, gn = 0;
    for (int j = 0; j < p; j++) {
        for (int i = 0; i < p; i++) {
            double t = T[i + (size_t)j * ldt];
            lk->TL[nl + i + (size_t)(nl + j) * cap] = t;
            tn += t * t;
        }
        /* G = L^T Op y: the coupling to the earlier locked vectors */
        double *g = lk->TL + (size_t)(nl + j) * cap;
        if (nl > 0) {
            op(ctx, Y + (size_t)j * n, lk->y);
            dots(lk->L, n, nl, lk->y, g);
            gn += dot(g, g, nl);
        }
        lk->lr[nl + j] = ws->wr[j];
        lk->li[nl + j] = ws->wi[j];
    }
    if (gn <= tol * tol * tn) /* noise (see above) */
        for (int j = 0; j < p; j++)
            memset(lk->TL + (size_t)(nl + j) * cap, 0, (size_t)nl * sizeof *lk->TL);
    lk->nl = nl + p;
    return p;
}

/* Appends the values nl0..nl-1 locked by a check and their eigenvectors (first nout
 * rows, unit norm as in ritz_output) to out: x = the vectors of T_L for them (dtrevc;
 * zero on the earlier locked vectors when the coupling was noise), L x. */
static gd_status append_locked(gd_ks_work *ws, const locked *lk, int nl0, int nout,
                               gd_ks_result *out)
{
    int n = lk->n, nl = lk->nl, q = nl - nl0, nc = out->nconv;
    for (int j = 0; j < nl; j++) {
        memcpy(ws->T + (size_t)j * nl, lk->TL + (size_t)j * lk->cap, (size_t)nl * sizeof *ws->T);
        ws->sel[j] = j >= nl0;
    }
    lapack_int used = 0;
    memset(ws->X, 0, (size_t)nl * q * sizeof *ws->X);
    if (LAPACKE_dtrevc_work(LAPACK_COL_MAJOR, 'R', 'S', ws->sel, nl, ws->T, nl, NULL, 1, ws->X, nl,
                            q, &used, ws->work))
        return GD_ENUMERIC;
    basis_times(lk->L, n, nout, nl, ws->X, q, ws->Z);
    double *a = realloc(out->mu_re, (size_t)(nc + q) * sizeof *a);
    if (a) out->mu_re = a;
    double *b = realloc(out->mu_im, (size_t)(nc + q) * sizeof *b);
    if (b) out->mu_im = b;
    double *c = realloc(out->vec_re, (size_t)nout * (nc + q) * sizeof *c);
    if (c) out->vec_re = c;
    double *d = realloc(out->vec_im, (size_t)nout * (nc + q) * sizeof *d);
    if (d) out->vec_im = d;
    if (!a || !b || !c || !d) return GD_ENOMEM;
    for (int k = 0; k < q;) {
        int pair = lk->li[nl0 + k] != 0;
        const double *yr = ws->Z + (size_t)k * nout, *yi = pair ? yr + nout : NULL;
        double ny = sqrt(dot(yr, yr, nout) + (pair ? dot(yi, yi, nout) : 0));
        double inv = ny > 0 ? 1.0 / ny : 1.0;
        for (int member = 0; member < (pair ? 2 : 1); member++, k++, nc++) {
            double sg = member ? -1.0 : 1.0;
            double *vr = out->vec_re + (size_t)nc * nout, *vi = out->vec_im + (size_t)nc * nout;
            for (int i = 0; i < nout; i++) {
                vr[i] = yr[i] * inv;
                vi[i] = pair ? sg * inv * yi[i] : 0;
            }
            out->mu_re[nc] = lk->lr[nl0 + k - member];
            out->mu_im[nc] = sg * fabs(lk->li[nl0 + k - member]);
        }
    }
    out->nconv = nc;
    return GD_OK;
}

/* Keeps the nev largest values of out (conjugate pairs together), in their order. */
static void keep_largest(gd_ks_work *ws, int nout, int nev, gd_ks_result *out)
{
    select_largest(out->mu_re, out->mu_im, out->nconv, nev, ws->sel, ws->order);
    int c = 0;
    for (int j = 0; j < out->nconv; j++) {
        if (!ws->sel[j]) continue;
        out->mu_re[c] = out->mu_re[j];
        out->mu_im[c] = out->mu_im[j];
        memmove(out->vec_re + (size_t)c * nout, out->vec_re + (size_t)j * nout,
                (size_t)nout * sizeof *out->vec_re);
        memmove(out->vec_im + (size_t)c * nout, out->vec_im + (size_t)j * nout,
                (size_t)nout * sizeof *out->vec_im);
        c++;
    }
    out->nconv = c;
}

/* Magnitude of the smallest of the nev largest locked values. */
static double nev_th_magnitude(const locked *lk, int nev, gd_ks_work *ws)
{
    select_largest(lk->lr, lk->li, lk->nl, nev, ws->sel, ws->order);
    double mn = INFINITY;
    for (int j = 0; j < lk->nl; j++)
        if (ws->sel[j] && hypot(lk->lr[j], lk->li[j]) < mn) mn = hypot(lk->lr[j], lk->li[j]);
    return mn;
}

gd_status gd_krylov_schur(gd_op_fn op, void *ctx, int n, int nout, int nev, int ncv, double tol,
                          int maxit, gd_ks_work *ws, gd_ks_result *out)
{
    memset(out, 0, sizeof *out);
    if (ncv > n) ncv = n;
    if (nev > ncv - 2) nev = ncv - 2;
    if (nout > n) nout = n;
    gd_status st = GD_OK;
    gd_ks_work local = {0};
    locked lk = {0};
    if (!ws) {
        if (gd_ks_work_init(&local, n, ncv)) return GD_ENOMEM;
        ws = &local;
    }
    if (ws->n != n || ws->ncv < ncv) {
        gd_ks_work_free(&local);
        return GD_ENOMEM;
    }
    int m = 0, its = 0, nsel = 0, valid = 0, added = 0;
    if ((st = ks_iterate(op, ctx, n, nev, ncv, tol, maxit, 1u, ws, &m, &nsel, &valid, &its)))
        goto done;
    /* the first run's Ritz pairs as they are (dhsein or dtrevc on the full Rayleigh
     * quotient separate the vectors of a cluster better than the locked form) */
    if ((st = ritz_output_converged(ws, n, nout, m, out))) goto done;
    out->iterations = its;
    /* the deflated checks (see above) */
    lk.n = n;
    lk.cap = ncv;
    lk.L = malloc((size_t)n * ncv * sizeof *lk.L);
    lk.TL = calloc((size_t)ncv * ncv, sizeof *lk.TL);
    lk.lr = malloc((size_t)ncv * sizeof *lk.lr);
    lk.li = malloc((size_t)ncv * sizeof *lk.li);
    lk.y = malloc((size_t)n * sizeof *lk.y);
    double *hh = malloc((size_t)2 * (ncv + 1) * sizeof *hh);
    if (!lk.L || !lk.TL || !lk.lr || !lk.li || !lk.y || !hh) {
        free(hh);
        st = GD_ENOMEM;
        goto done;
    }
    if (lock_converged(op, ctx, ws, m, nev, nsel, valid, tol, &lk) <= 0) {
        free(hh);
        st = GD_ENUMERIC;
        goto done;
    }
    deflated dop = {op, ctx, &lk, hh, hh + ncv + 1};
    for (unsigned round = 0;; round++) {
        /* a check basis of 9 (first_check(1)) to GD_KS_CHECK_NCV vectors in the
         * complement of L; none when the first basis spanned the whole space */
        int nc = n - lk.nl - 1 < GD_KS_CHECK_NCV ? n - lk.nl - 1 : GD_KS_CHECK_NCV, mc = 0;
        if (m >= n || nc < 3 || lk.nl + 2 > lk.cap) break;
        double thr = nev_th_magnitude(&lk, nev, ws), top = 0;
        /* first to a loose tolerance, which decides when the largest value is clearly
         * below the accepted ones; to tol when it is not */
        for (double ctol = tol > GD_KS_CHECK_TOL ? tol : GD_KS_CHECK_TOL;; ctol = tol) {
            if (ks_iterate(deflated_apply, &dop, n, 1, nc, ctol, maxit, 2u + round, ws, &mc, &nsel,
                           &valid, &its)) {
                top = 0; /* the check did not settle: keep what converged */
                break;
            }
            top = 0;
            for (int j = 0; j < mc; j++)
                top = hypot(ws->wr[j], ws->wi[j]) > top ? hypot(ws->wr[j], ws->wi[j]) : top;
            if (ctol == tol || top < thr * (1 - GD_KS_CHECK_MARGIN)) break;
        }
        if (!(top > thr)) break;
        int nl0 = lk.nl;
        if (lock_converged(op, ctx, ws, mc, 1, nsel, valid, tol, &lk) <= 0) break;
        if ((st = append_locked(ws, &lk, nl0, nout, out))) break;
        added = 1;
    }
    free(hh);
    if (!st && added) keep_largest(ws, nout, nev, out);
done:
    free(lk.L);
    free(lk.TL);
    free(lk.lr);
    free(lk.li);
    free(lk.y);
    gd_ks_work_free(&local);
    if (st) gd_ks_result_free(out);
    return st;
}

gd_status gd_ks_deflated_top(gd_op_fn op, void *ctx, int n, const double *L, int nl, double tol,
                             gd_ks_work *ws, double *top)
{
    *top = 0;
    int nc = n - nl - 1 < GD_KS_CHECK_NCV ? n - nl - 1 : GD_KS_CHECK_NCV;
    if (nc < 3) return GD_OK; /* L spans (nearly) the whole space: nothing can be missed */
    if (ws->n != n || ws->ncv < nc) return GD_ENOMEM;
    double *hh = malloc((size_t)2 * (nl + 1) * sizeof *hh);
    if (!hh) return GD_ENOMEM;
    locked lk = {n, nl, nl, (double *)L, NULL, NULL, NULL, NULL};
    deflated dop = {op, ctx, &lk, hh, hh + nl + 1};
    int mc = 0, nsel = 0, valid = 0, its = 0;
    gd_status st =
        ks_iterate(deflated_apply, &dop, n, 1, nc, tol, 50, 2u, ws, &mc, &nsel, &valid, &its);
    if (!st)
        for (int j = 0; j < mc; j++)
            *top = hypot(ws->wr[j], ws->wi[j]) > *top ? hypot(ws->wr[j], ws->wi[j]) : *top;
    free(hh);
    return st;
}
