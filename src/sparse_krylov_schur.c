/* Krylov-Schur (Stewart, SIAM J. Matrix Anal. Appl. 23, 2001) in real arithmetic for
 * the eigenvalues of largest magnitude of a real operator: Arnoldi with full (twice
 * classical Gram-Schmidt) reorthogonalisation, real Schur form of the Rayleigh
 * quotient (dgees), reordering of the wanted Schur vectors to the front (dtrsen) and
 * restart from them. Written here rather than taken from ARPACK because ARPACK keeps
 * its state in Fortran SAVE variables and cannot run in several threads at once; this
 * one keeps everything in its arguments. The vector kernels are plain loops (no
 * threaded BLAS inside a parallel sweep); the m x m problems go to LAPACK. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sweep_internal.h"

static double dot(const double *a, const double *b, int n)
{
    double s = 0;
#pragma omp simd reduction(+ : s)
    for (int i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

/* h[c] = V[:, c]^T w for c < k, four columns per sweep over w */
static void dots(const double *V, int n, int k, const double *w, double *h)
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
static void subtract(const double *V, int n, int k, const double *h, double *w)
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

/* Z[:, 0:p] = V[:, 0:m] Q[:, 0:p] (Q is m x m) */
static void basis_times(const double *V, int n, int m, const double *Q, int p, double *Z)
{
    for (int c = 0; c < p; c++) {
        double *z = Z + (size_t)c * n;
        const double *q = Q + (size_t)c * m;
        for (int i = 0; i < n; i++)
            z[i] = 0;
        int r = 0;
        for (; r + 4 <= m; r += 4) {
            const double *v0 = V + (size_t)r * n, *v1 = v0 + n, *v2 = v1 + n, *v3 = v2 + n;
            double a0 = q[r], a1 = q[r + 1], a2 = q[r + 2], a3 = q[r + 3];
#pragma omp simd
            for (int i = 0; i < n; i++)
                z[i] += (a0 * v0[i] + a1 * v1[i]) + (a2 * v2[i] + a3 * v3[i]);
        }
        for (; r < m; r++) {
            const double *v = V + (size_t)r * n;
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
    w->wr = malloc((size_t)m * sizeof(double));
    w->wi = malloc((size_t)m * sizeof(double));
    w->h = malloc((size_t)(m + 1) * sizeof(double));
    w->h2 = malloc((size_t)(m + 1) * sizeof(double));
    w->b = malloc((size_t)m * sizeof(double));
    w->res = malloc((size_t)m * sizeof(double));
    w->Z = malloc((size_t)n * (size_t)m * sizeof(double));
    w->sel = malloc((size_t)m * sizeof(lapack_logical));
    w->order = malloc((size_t)m * sizeof(mag_index));
    if (!w->V || !w->H || !w->T || !w->Q || !w->X || !w->wr || !w->wi || !w->h || !w->h2 || !w->b ||
        !w->res || !w->Z || !w->sel || !w->order) {
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
    free(w->wr);
    free(w->wi);
    free(w->h);
    free(w->h2);
    free(w->b);
    free(w->res);
    free(w->Z);
    free(w->sel);
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

gd_status gd_krylov_schur(gd_op_fn op, void *ctx, int n, int nev, int ncv, double tol, int maxit,
                          gd_ks_work *ws, gd_ks_result *out)
{
    memset(out, 0, sizeof *out);
    if (ncv > n) ncv = n;
    if (nev > ncv - 2) nev = ncv - 2;
    int m = ncv, ldh = m + 1;
    gd_status st = GD_OK;
    gd_ks_work local = {0};
    if (!ws) {
        if (gd_ks_work_init(&local, n, ncv)) return GD_ENOMEM;
        ws = &local;
    }
    if (ws->n != n || ws->ncv < m) {
        gd_ks_work_free(&local);
        return GD_ENOMEM;
    }
    double *V = ws->V, *H = ws->H, *T = ws->T, *Q = ws->Q, *X = ws->X, *wr = ws->wr, *wi = ws->wi;
    double *h = ws->h, *h2 = ws->h2, *b = ws->b, *res = ws->res, *Z = ws->Z;
    lapack_logical *sel = ws->sel;
    mag_index *order = ws->order;
    memset(H, 0, (size_t)ldh * m * sizeof *H);
    start_vector(V, n, 1u);
    double nv = nrm2(V, n);
    for (int i = 0; i < n; i++)
        V[i] /= nv;
    int k = 0, p = 0, converged = 0;
    for (int it = 0; it <= maxit; it++) {
        /* extend the Krylov-Schur decomposition from k to m vectors */
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
                double nw = nrm2(w, n);
                for (int i = 0; i < n; i++)
                    w[i] /= nw;
            } else {
                for (int i = 0; i < n; i++)
                    w[i] /= beta;
            }
            H[j + 1 + (size_t)j * ldh] = beta;
        }
        double beta = H[m + (size_t)(m - 1) * ldh];
        for (int j = 0; j < m; j++)
            for (int i = 0; i < m; i++)
                T[i + (size_t)j * m] = H[i + (size_t)j * ldh];
        lapack_int sdim = 0, msel = 0;
        if (LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'N', NULL, m, T, m, &sdim, wr, wi, Q, m)) {
            st = GD_ENUMERIC;
            goto done;
        }
        /* keep the wanted ones and half of the rest */
        int keep = nev + (m - nev) / 2;
        if (keep > m - 2) keep = m - 2;
        p = select_largest(wr, wi, m, keep, sel, order);
        double sep, s;
        /* the _work form with our own iwork: dtrsen writes iwork(1) even for job 'N',
         * which LAPACKE_dtrsen passes as NULL */
        lapack_int iwork[1];
        if (LAPACKE_dtrsen_work(LAPACK_COL_MAJOR, 'N', 'V', sel, m, T, m, Q, m, wr, wi, &msel, &s,
                                &sep, h2, m, iwork, 1)) {
            st = GD_ENUMERIC;
            goto done;
        }
        p = (int)msel;
        for (int i = 0; i < p; i++)
            b[i] = beta * Q[(m - 1) + (size_t)i * m];
        /* Ritz vectors of the leading p x p block and their residuals |b^T x| / |x| */
        lapack_int got = 0;
        memset(X, 0, (size_t)m * m * sizeof *X);
        if (LAPACKE_dtrevc(LAPACK_COL_MAJOR, 'R', 'A', NULL, p, T, m, NULL, 1, X, m, p, &got)) {
            st = GD_ENUMERIC;
            goto done;
        }
        for (int j = 0; j < p; j++) {
            double mag = hypot(wr[j], wi[j]);
            if (wi[j] > 0 && j + 1 < p) {
                const double *xr = X + (size_t)j * m, *xi = X + (size_t)(j + 1) * m;
                double rr = dot(b, xr, p), ri = dot(b, xi, p);
                double nx = sqrt(dot(xr, xr, p) + dot(xi, xi, p));
                res[j] = res[j + 1] = hypot(rr, ri) / (nx * mag);
                j++;
            } else {
                const double *x = X + (size_t)j * m;
                res[j] = fabs(dot(b, x, p)) / (nrm2(x, p) * (mag > 0 ? mag : 1));
            }
        }
        /* the nev largest within the block must have converged */
        int wanted = select_largest(wr, wi, p, nev, sel, order);
        converged = 1;
        for (int j = 0; j < p; j++)
            if (sel[j] && !(res[j] <= tol)) converged = 0;
        out->iterations = it;
        if (converged || it == maxit) {
            /* Z = V Q[:, 0:p], then the wanted Ritz vectors Z x */
            basis_times(V, n, m, Q, p, Z);
            out->mu_re = malloc((size_t)wanted * sizeof(double));
            out->mu_im = malloc((size_t)wanted * sizeof(double));
            out->vec_re = malloc((size_t)n * wanted * sizeof(double));
            out->vec_im = malloc((size_t)n * wanted * sizeof(double));
            if (!out->mu_re || !out->mu_im || !out->vec_re || !out->vec_im) {
                st = GD_ENOMEM;
                goto done;
            }
            int c = 0;
            for (int j = 0; j < p; j++) {
                if (!sel[j]) continue;
                int pair = wi[j] != 0;
                int j0 = pair && wi[j] < 0 ? j - 1 : j; /* columns j0 (re), j0+1 (im) */
                double sg = pair && wi[j] < 0 ? -1.0 : 1.0;
                double *yr = out->vec_re + (size_t)c * n, *yi = out->vec_im + (size_t)c * n;
                memset(yr, 0, (size_t)n * sizeof *yr);
                memset(yi, 0, (size_t)n * sizeof *yi);
                for (int r = 0; r < p; r++) {
                    double xr = X[r + (size_t)j0 * m],
                           xi = pair ? sg * X[r + (size_t)(j0 + 1) * m] : 0;
                    const double *z = Z + (size_t)r * n;
                    for (int i = 0; i < n; i++) {
                        yr[i] += xr * z[i];
                        yi[i] += xi * z[i];
                    }
                }
                double ny = sqrt(dot(yr, yr, n) + dot(yi, yi, n));
                for (int i = 0; i < n; i++) {
                    yr[i] /= ny;
                    yi[i] /= ny;
                }
                out->mu_re[c] = wr[j];
                out->mu_im[c] = wi[j];
                c++;
            }
            out->nconv = c;
            if (!converged) st = GD_ENUMERIC;
            goto done;
        }
        /* restart: V[:, 0:p] = V Q[:, 0:p], V[:, p] = v_{m}, H = [T_pp; b^T] */
        basis_times(V, n, m, Q, p, Z);
        memcpy(V + (size_t)p * n, V + (size_t)m * n, (size_t)n * sizeof *V);
        memcpy(V, Z, (size_t)n * p * sizeof *V);
        memset(H, 0, (size_t)ldh * m * sizeof *H);
        for (int j = 0; j < p; j++) {
            for (int i = 0; i < p; i++)
                H[i + (size_t)j * ldh] = T[i + (size_t)j * m];
            H[p + (size_t)j * ldh] = b[j];
        }
        k = p;
    }
done:
    gd_ks_work_free(&local);
    if (st == GD_ENOMEM) gd_ks_result_free(out);
    return st;
}
