/* Harmonic balance residual and Jacobian by the alternating frequency-time scheme
 * (Cameron & Griffin 1989): the coefficients give q(t), q'(t) at N samples of one period
 * (FFTW half-complex inverse), the local forces and their term derivatives are evaluated
 * there by gd_transient_local, and a forward transform gives their coefficients. The
 * linear part acts per harmonic in the frequency domain,
 *   cos k:  (K - k^2 w^2 M) Q_ck + k w D Q_sk,   sin k:  (K - k^2 w^2 M) Q_sk - k w D Q_ck,
 * and each rank-one term s(t) u w^T of df/dq (df/dq') couples harmonics a, b through
 *   G_ab = c_a / N sum_j phi_a(t_j) [s_q(t_j) phi_b(t_j) + w s_v(t_j) phi_b'(t_j)],
 * c_0 = 1, c_a = 2, phi the basis (1, cos k tau, sin k tau). */
#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

#define TWO_PI 6.28318530717958647692

int gd_hb_init(hb *h, int nf, int H, int N)
{
    memset(h, 0, sizeof *h);
    h->nf = nf;
    h->H = H;
    h->nh = 2 * H + 1;
    h->N = N;
    h->n = nf * h->nh;
    size_t sz = (size_t)nf * N;
    h->tq = fftw_malloc(sz * sizeof(double));
    h->tv = fftw_malloc(sz * sizeof(double));
    h->tf = fftw_malloc(sz * sizeof(double));
    h->y = malloc(2 * (size_t)nf * sizeof *h->y);
    h->f = malloc((size_t)nf * sizeof *h->f);
    h->E = malloc((size_t)N * h->nh * sizeof *h->E);
    h->Ed = malloc((size_t)N * h->nh * sizeof *h->Ed);
    if (!h->tq || !h->tv || !h->tf || !h->y || !h->f || !h->E || !h->Ed) return 1;
    int kind_f = FFTW_R2HC, kind_i = FFTW_HC2R;
    h->fwd_f = fftw_plan_many_r2r(1, &N, nf, h->tf, NULL, 1, N, h->tf, NULL, 1, N,
                                  (const fftw_r2r_kind *)&kind_f, FFTW_ESTIMATE);
    h->inv_q = fftw_plan_many_r2r(1, &N, nf, h->tv, NULL, 1, N, h->tq, NULL, 1, N,
                                  (const fftw_r2r_kind *)&kind_i, FFTW_ESTIMATE);
    if (!h->fwd_f || !h->inv_q) return 1;
    for (int j = 0; j < N; j++) {
        double tau = TWO_PI * j / N;
        h->E[j] = 1.0;
        h->Ed[j] = 0.0;
        for (int k = 1; k <= H; k++) {
            double c = cos(k * tau), s = sin(k * tau);
            h->E[(size_t)(2 * k - 1) * N + j] = c;
            h->E[(size_t)(2 * k) * N + j] = s;
            h->Ed[(size_t)(2 * k - 1) * N + j] = -k * s;
            h->Ed[(size_t)(2 * k) * N + j] = k * c;
        }
    }
    klu_defaults(&h->com);
    return 0;
}

void gd_hb_free(hb *h)
{
    if (h->fwd_f) fftw_destroy_plan(h->fwd_f);
    if (h->inv_q) fftw_destroy_plan(h->inv_q);
    fftw_free(h->tq);
    fftw_free(h->tv);
    fftw_free(h->tf);
    free(h->sq);
    free(h->sv);
    free(h->y);
    free(h->f);
    free(h->E);
    free(h->Ed);
    free(h->Gall);
    gd_hb_lowrank_free(h);
    free(h->Ap);
    free(h->Ai);
    free(h->Ax);
    free(h->ti);
    free(h->tj);
    if (h->num) klu_free_numeric(&h->num, &h->com);
    if (h->sym) klu_free_symbolic(&h->sym, &h->com);
    memset(h, 0, sizeof *h);
}

/* Samples (DOF-major, out[i * N + j]) of sum_h X_h phi_h (deriv: of its phase
 * derivative) through a half-complex inverse transform. */
static void synth(hb *h, const double *X, int deriv, double *out)
{
    const int nf = h->nf, N = h->N;
    double *hc = h->tv; /* the inverse plan's input buffer */
    memset(hc, 0, (size_t)nf * N * sizeof *hc);
    for (int i = 0; i < nf; i++) {
        double *b = hc + (size_t)i * N;
        if (!deriv) b[0] = X[i];
        for (int k = 1; k <= h->H; k++) {
            double c = X[(2 * k - 1) * nf + i], s = X[2 * k * nf + i];
            if (deriv) { /* d/dtau: cos coefficient k s, sin coefficient -k c */
                double c2 = k * s, s2 = -k * c;
                c = c2;
                s = s2;
            }
            b[k] = 0.5 * c;
            b[N - k] = -0.5 * s;
        }
    }
    fftw_execute_r2r(h->inv_q, hc, out);
}

void gd_hb_eval(const hb *h, double w, const double *X, double tau, double *q, double *v)
{
    const int nf = h->nf;
    for (int i = 0; i < nf; i++) {
        q[i] = X[i];
        v[i] = 0.0;
    }
    for (int k = 1; k <= h->H; k++) {
        double c = cos(k * tau), s = sin(k * tau);
        const double *xc = X + (size_t)(2 * k - 1) * nf, *xs = X + (size_t)2 * k * nf;
        for (int i = 0; i < nf; i++) {
            q[i] += xc[i] * c + xs[i] * s;
            v[i] += w * k * (xs[i] * c - xc[i] * s);
        }
    }
}

/* y += alpha A x */
static void spmv(const gd_csc *A, double alpha, const double *x, double *y)
{
    for (int j = 0; j < A->n; j++) {
        double xj = alpha * x[j];
        if (xj == 0.0) continue;
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            y[A->rowind[p]] += A->values[p] * xj;
    }
}

int gd_hb_residual(hb *h, gd_transient *tr, double w, const double *X, double *R, int jac,
                   double *scale)
{
    const int nf = h->nf, N = h->N, H = h->H;
    if (jac) {
        int nt = gd_transient_terms(tr, &h->term);
        if (nt < 0) return 1;
        if (nt != h->nterm || !h->sq) {
            free(h->sq);
            free(h->sv);
            h->nterm = nt;
            h->sq = malloc((size_t)(nt > 0 ? nt : 1) * N * sizeof *h->sq);
            h->sv = malloc((size_t)(nt > 0 ? nt : 1) * N * sizeof *h->sv);
            if (!h->sq || !h->sv) return 1;
        }
    }
    /* time samples: tv holds q' first (synth overwrites its input buffer) */
    double *qs = h->tq, *vs = h->tf;
    synth(h, X, 1, vs);
    synth(h, X, 0, qs);
    double *st = jac ? malloc((size_t)(h->nterm > 0 ? h->nterm : 1) * 2 * sizeof *st) : NULL;
    if (jac && !st) return 1;
    int bad = 0;
    for (int j = 0; j < N; j++) {
        double t = TWO_PI * j / N / w;
        for (int i = 0; i < nf; i++) {
            h->y[i] = qs[(size_t)i * N + j];
            h->y[nf + i] = w * vs[(size_t)i * N + j];
        }
        gd_transient_local(tr, t, h->y, h->f, jac ? st : NULL, jac ? st + h->nterm : NULL);
        for (int i = 0; i < nf; i++) {
            if (!isfinite(h->f[i])) bad = 1;
            h->tv[(size_t)i * N + j] = h->f[i];
        }
        if (jac)
            for (int k = 0; k < h->nterm; k++) {
                h->sq[(size_t)k * N + j] = st[k];
                h->sv[(size_t)k * N + j] = st[h->nterm + k];
            }
    }
    free(st);
    /* forward transform of the forces (tv -> tf, through the in-place plan on tf) */
    memcpy(h->tf, h->tv, (size_t)nf * N * sizeof *h->tf);
    fftw_execute(h->fwd_f);
    gd_csc M, D, K;
    gd_transient_matrices(tr, &M, &D, &K);
    double nl = 0.0, nf2 = 0.0;
    for (int i = 0; i < h->n; i++)
        R[i] = 0.0;
    for (int hh = 0; hh < h->nh; hh++) {
        int k = (hh + 1) / 2;
        double *r = R + (size_t)hh * nf;
        const double *x = X + (size_t)hh * nf;
        spmv(&K, 1.0, x, r);
        if (k) {
            spmv(&M, -(k * w) * (k * w), x, r);
            if (hh & 1)
                spmv(&D, k * w, X + (size_t)(hh + 1) * nf, r);
            else
                spmv(&D, -k * w, X + (size_t)(hh - 1) * nf, r);
        }
    }
    for (int i = 0; i < h->n; i++)
        nl += R[i] * R[i];
    for (int i = 0; i < nf; i++) {
        const double *c = h->tf + (size_t)i * N;
        double F = c[0] / N;
        R[i] -= F;
        nf2 += F * F;
        for (int k = 1; k <= H; k++) {
            double fc = 2.0 * c[k] / N, fs = -2.0 * c[N - k] / N;
            R[(size_t)(2 * k - 1) * nf + i] -= fc;
            R[(size_t)2 * k * nf + i] -= fs;
            nf2 += fc * fc + fs * fs;
        }
    }
    if (scale) *scale = sqrt(nl > nf2 ? nl : nf2);
    return bad;
}

/* ---------------------------------------------------------------- Jacobian */

static int trip_add(hb *h, int i, int j)
{
    if (h->ntrip == h->captrip) {
        int cap = h->captrip ? 2 * h->captrip : 4096;
        int *a = realloc(h->ti, (size_t)cap * sizeof *a);
        if (!a) return 1;
        h->ti = a;
        int *b = realloc(h->tj, (size_t)cap * sizeof *b);
        if (!b) return 1;
        h->tj = b;
        h->captrip = cap;
    }
    h->ti[h->ntrip] = i;
    h->tj[h->ntrip] = j;
    h->ntrip++;
    return 0;
}

int gd_hb_couplings(hb *h, double w)
{
    const int nh = h->nh, N = h->N;
    size_t need = (size_t)(h->nterm > 0 ? h->nterm : 1) * nh * nh;
    if (h->nGall < need) {
        free(h->Gall);
        h->Gall = malloc(need * sizeof *h->Gall);
        h->nGall = h->Gall ? need : 0;
        if (!h->Gall) return 1;
    }
    double *B = malloc((size_t)N * nh * sizeof *B), *Ew = malloc((size_t)N * nh * sizeof *Ew);
    if (!B || !Ew) {
        free(B);
        free(Ew);
        return 1;
    }
    for (int a = 0; a < nh; a++)
        for (int j = 0; j < N; j++)
            Ew[(size_t)a * N + j] = h->E[(size_t)a * N + j] * (a ? 2.0 : 1.0) / N;
    for (int t = 0; t < h->nterm; t++) {
        const double *sq = h->sq + (size_t)t * N, *sv = h->sv + (size_t)t * N;
        for (int b = 0; b < nh; b++)
            for (int j = 0; j < N; j++)
                B[(size_t)b * N + j] =
                    sq[j] * h->E[(size_t)b * N + j] + w * sv[j] * h->Ed[(size_t)b * N + j];
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, nh, nh, N, 1.0, Ew, N, B, N, 0.0,
                    h->Gall + (size_t)t * nh * nh, nh);
    }
    free(B);
    free(Ew);
    return 0;
}

/* mode 0: collect the pattern; 1: add val at (i, j) */
static void emit(hb *h, int mode, int i, int j, double val)
{
    if (mode == 0) {
        if (trip_add(h, i, j)) h->miss = 2;
        return;
    }
    int lo = h->Ap[j], hi = h->Ap[j + 1] - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (h->Ai[mid] == i) {
            h->Ax[mid] += val;
            return;
        }
        if (h->Ai[mid] < i)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    if (val != 0.0) h->miss = 1;
}

/* Every entry of the bordered matrix, through emit. */
static void assemble(hb *h, int mode, gd_transient *tr, double w, const double *dRdp,
                     const double *row)
{
    const int nf = h->nf, nh = h->nh, n = h->n;
    gd_csc M, D, K;
    gd_transient_matrices(tr, &M, &D, &K);
    for (int hh = 0; hh < nh; hh++) {
        int k = (hh + 1) / 2, o = hh * nf;
        double kw2 = (k * w) * (k * w);
        for (int j = 0; j < nf; j++) {
            for (int p = K.colptr[j]; p < K.colptr[j + 1]; p++)
                emit(h, mode, o + K.rowind[p], o + j, K.values[p]);
            for (int p = M.colptr[j]; p < M.colptr[j + 1]; p++)
                emit(h, mode, o + M.rowind[p], o + j, -kw2 * M.values[p]);
            if (!k) continue;
            int oc = (hh & 1) ? o + nf : o - nf;
            double s = (hh & 1) ? k * w : -k * w;
            for (int p = D.colptr[j]; p < D.colptr[j + 1]; p++)
                emit(h, mode, o + D.rowind[p], oc + j, s * D.values[p]);
        }
    }
    /* nonlinear terms: - u w^T (x) G */
    if (mode && gd_hb_couplings(h, w)) {
        h->miss = 2;
        return;
    }
    for (int t = 0; t < h->nterm; t++) {
        const gd_tr_term *tm = &h->term[t];
        if (!tm->nu || !tm->nw) continue;
        const double *G = mode ? h->Gall + (size_t)t * nh * nh : NULL;
        for (int b = 0; b < nh; b++)
            for (int a = 0; a < nh; a++) {
                double g = mode ? G[(size_t)b * nh + a] : 0.0;
                for (int jw = 0; jw < tm->nw; jw++)
                    for (int iu = 0; iu < tm->nu; iu++)
                        emit(h, mode, a * nf + tm->u_idx[iu], b * nf + tm->w_idx[jw],
                             -tm->u[iu] * tm->w[jw] * g);
            }
    }
    for (int i = 0; i < n; i++) {
        emit(h, mode, i, n, dRdp ? dRdp[i] : 0.0);
        emit(h, mode, n, i, row[i]);
    }
    emit(h, mode, n, n, row[n]);
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* CSC pattern from the collected triplets: counts per column, sort, drop duplicates. */
static int build_pattern(hb *h)
{
    const int n1 = h->n + 1;
    free(h->Ap);
    free(h->Ai);
    free(h->Ax);
    h->Ap = calloc((size_t)n1 + 1, sizeof *h->Ap);
    h->Ai = malloc((size_t)(h->ntrip > 0 ? h->ntrip : 1) * sizeof *h->Ai);
    int *next = malloc((size_t)n1 * sizeof *next);
    if (!h->Ap || !h->Ai || !next) {
        free(next);
        return 1;
    }
    for (int k = 0; k < h->ntrip; k++)
        h->Ap[h->tj[k] + 1]++;
    for (int j = 0; j < n1; j++)
        h->Ap[j + 1] += h->Ap[j];
    memcpy(next, h->Ap, (size_t)n1 * sizeof *next);
    for (int k = 0; k < h->ntrip; k++)
        h->Ai[next[h->tj[k]]++] = h->ti[k];
    free(next);
    int nz = 0;
    for (int j = 0; j < n1; j++) {
        int p0 = h->Ap[j], p1 = h->Ap[j + 1];
        qsort(h->Ai + p0, (size_t)(p1 - p0), sizeof *h->Ai, cmp_int);
        h->Ap[j] = nz;
        for (int p = p0; p < p1; p++)
            if (p == p0 || h->Ai[p] != h->Ai[p - 1]) h->Ai[nz++] = h->Ai[p];
    }
    h->Ap[n1] = nz;
    h->nnz = nz;
    h->Ax = malloc((size_t)(nz > 0 ? nz : 1) * sizeof *h->Ax);
    return h->Ax ? 0 : 1;
}

int gd_hb_use_lowrank(const hb *h)
{
    if (h->solver == 1) return 0;
    if (h->solver == 2) return 1;
    return h->n >= 2000 && 4 * h->nterm * h->nh <= h->n;
}

int gd_hb_factor(hb *h, gd_transient *tr, double w, const double *dRdp, const double *row)
{
    if (gd_hb_use_lowrank(h)) return gd_hb_lowrank_factor(h, tr, w, dRdp, row);
    for (int attempt = 0; attempt < 2; attempt++) {
        if (!h->sym) {
            h->ntrip = 0;
            h->miss = 0;
            assemble(h, 0, tr, w, dRdp, row);
            if (h->miss == 2 || build_pattern(h)) return 1;
            h->sym = klu_analyze(h->n + 1, h->Ap, h->Ai, &h->com);
            if (!h->sym) return 1;
        }
        memset(h->Ax, 0, (size_t)h->nnz * sizeof *h->Ax);
        h->miss = 0;
        assemble(h, 1, tr, w, dRdp, row);
        if (h->miss == 2) return 1;
        if (h->miss) { /* the matrices gained entries (e.g. gyroscopic terms off zero speed) */
            if (h->num) klu_free_numeric(&h->num, &h->com);
            klu_free_symbolic(&h->sym, &h->com);
            continue;
        }
        if (h->num) klu_free_numeric(&h->num, &h->com);
        h->num = klu_factor(h->Ap, h->Ai, h->Ax, h->sym, &h->com);
        return h->num ? 0 : 1;
    }
    return 1;
}

void gd_hb_solve(hb *h, double *b)
{
    if (gd_hb_use_lowrank(h)) {
        gd_hb_lowrank_solve(h, b);
        return;
    }
    klu_solve(h->sym, h->num, h->n + 1, 1, b, &h->com);
}
