/* Harmonic balance residual and Jacobian by the alternating frequency-time scheme
 * (Cameron & Griffin 1989): the coefficients give q(t), q'(t) at N samples of one period
 * (FFTW half-complex inverse), the local forces and their term derivatives are evaluated
 * there by gd_transient_local, and a forward transform gives their coefficients. The
 * linear part acts per harmonic in the frequency domain,
 *   cos k:  (K - k^2 w^2 M) Q_ck + k w D Q_sk,   sin k:  (K - k^2 w^2 M) Q_sk - k w D Q_ck,
 * and each rank-one term s(t) u w^T of df/dq (df/dq') couples harmonics a, b through
 *   G_ab = c_a / N sum_j phi_a(t_j) [s_q(t_j) phi_b(t_j) + w s_v(t_j) phi_b'(t_j)],
 * c_0 = 1, c_a = 2, phi the basis (1, cos k tau, sin k tau). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/condensed/chb.h"
#include "periodic/periodic_impl.h"
#include "signal/fft_planner_impl.h"

#define TWO_PI 6.28318530717958647692

int gd_hb_init(hb *h, int nf, int H, int N)
{
    gd_fft_planner_init(); /* every plan of a run is made after its first hb_init */
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
    if (!h->tq || !h->tv || !h->tf || !h->y) return 1;
    int kind_f = FFTW_R2HC, kind_i = FFTW_HC2R;
    /* samples are sample-major (x[j * nf + i]: one state per row, what the force
     * evaluation reads and writes), spectra DOF-major (c[i * N + k]) */
    h->fwd_f = fftw_plan_many_r2r(1, &N, nf, h->tv, NULL, nf, 1, h->tf, NULL, 1, N,
                                  (const fftw_r2r_kind *)&kind_f, FFTW_ESTIMATE);
    h->inv_q = fftw_plan_many_r2r(1, &N, nf, h->tv, NULL, 1, N, h->tq, NULL, nf, 1,
                                  (const fftw_r2r_kind *)&kind_i, FFTW_ESTIMATE);
    h->rowbuf = fftw_malloc(2 * (size_t)N * sizeof *h->rowbuf);
    if (!h->fwd_f || !h->inv_q || !h->rowbuf) return 1;
    /* single rows (the support path): unaligned, rows of tf start anywhere */
    h->row_fwd =
        fftw_plan_r2r_1d(N, h->rowbuf, h->rowbuf + N, FFTW_R2HC, FFTW_ESTIMATE | FFTW_UNALIGNED);
    h->row_inv =
        fftw_plan_r2r_1d(N, h->rowbuf, h->rowbuf + N, FFTW_HC2R, FFTW_ESTIMATE | FFTW_UNALIGNED);
    if (!h->row_fwd || !h->row_inv) return 1;
    klu_defaults(&h->com);
    return 0;
}

void gd_hb_free(hb *h)
{
    gd_chb_free(h->chb);
    h->chb = NULL;
    gd_floquet_modes_free(h->fmodes);
    h->fmodes = NULL;
    if (h->fwd_f) fftw_destroy_plan(h->fwd_f);
    if (h->inv_q) fftw_destroy_plan(h->inv_q);
    if (h->row_fwd) fftw_destroy_plan(h->row_fwd);
    if (h->row_inv) fftw_destroy_plan(h->row_inv);
    fftw_free(h->rowbuf);
    free(h->win);
    free(h->win2);
    free(h->rowmark);
    fftw_free(h->tq);
    fftw_free(h->tv);
    fftw_free(h->tf);
    fftw_free(h->smp);
    free(h->umark);
    free(h->Up);
    free(h->Uq);
    free(h->Ui);
    free(h->Ui2);
    free(h->UK);
    free(h->sq);
    free(h->sv);
    free(h->y);
    free(h->Gall);
    free(h->tactive);
    free(h->Fh);
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

/* Half-complex spectrum (length N > 2 H) of DOF i of sum_h X_h phi_h (deriv: of its
 * phase derivative), for a half-complex inverse transform to sample. */
static void fill_row(int nf, int H, int N, const double *X, int i, int deriv, double *b)
{
    memset(b, 0, (size_t)N * sizeof *b);
    if (!deriv) b[0] = X[i];
    for (int k = 1; k <= H; k++) {
        double c = X[(size_t)(2 * k - 1) * nf + i], sn = X[(size_t)2 * k * nf + i];
        /* d/dtau: cos coefficient k sn, sin coefficient -k c */
        b[k] = 0.5 * (deriv ? k * sn : c);
        b[N - k] = -0.5 * (deriv ? -k * c : sn);
    }
}

/* The spectra of every DOF, DOF-major (hc[i * N + j]). */
static void fill_spectra(int nf, int H, int N, const double *X, int deriv, double *hc)
{
    for (int i = 0; i < nf; i++)
        fill_row(nf, H, N, X, i, deriv, hc + (size_t)i * N);
}

/* Samples (sample-major, out[j * nf + i]) at the solver's N points. */
static void synth(hb *h, const double *X, int deriv, double *out)
{
    double *hc = h->tv; /* the inverse plan's input buffer */
    fill_spectra(h->nf, h->H, h->N, X, deriv, hc);
    fftw_execute_r2r(h->inv_q, hc, out);
}

int gd_hb_samples(hb *h, double w, const double *X, int N, const int *dofs, int nd, double **q,
                  double **v)
{
    const int nf = h->nf, H = h->H;
    if (N < 2 * H + 2) return 1;
    if (!dofs) nd = nf;
    /* spectra (every DOF) or one row and its samples (a few), then q and v */
    size_t sz = (size_t)nd * N, hsz = dofs ? 2 * (size_t)N : sz, need = hsz + 2 * sz;
    if (h->nsmp < need) { /* kept: a fresh buffer per point costs its page faults */
        fftw_free(h->smp);
        h->smp = fftw_malloc(need * sizeof *h->smp);
        h->nsmp = h->smp ? need : 0;
        if (!h->smp) return 1;
    }
    double *hc = h->smp, *qs = hc + hsz, *vs = qs + sz;
    if (!dofs) { /* every DOF: two batched transforms */
        int kind = FFTW_HC2R;
        fftw_plan p = fftw_plan_many_r2r(1, &N, nf, hc, NULL, 1, N, qs, NULL, nf, 1,
                                         (const fftw_r2r_kind *)&kind, FFTW_ESTIMATE);
        if (!p) return 1;
        fill_spectra(nf, H, N, X, 0, hc);
        fftw_execute_r2r(p, hc, qs);
        fill_spectra(nf, H, N, X, 1, hc);
        fftw_execute_r2r(p, hc, vs);
        fftw_destroy_plan(p);
    } else { /* a few DOFs: one row transform each, hc holds the row and its samples */
        fftw_plan p = fftw_plan_r2r_1d(N, hc, hc + N, FFTW_HC2R, FFTW_ESTIMATE);
        if (!p) return 1;
        for (int m = 0; m < nd; m++)
            for (int deriv = 0; deriv < 2; deriv++) {
                double *out = deriv ? vs : qs;
                fill_row(nf, H, N, X, dofs[m], deriv, hc);
                fftw_execute(p);
                for (int j = 0; j < N; j++)
                    out[(size_t)j * nd + m] = hc[N + j];
            }
        fftw_destroy_plan(p);
    }
    for (size_t i = 0; i < sz; i++)
        vs[i] *= w;
    *q = qs;
    *v = vs;
    return 0;
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

/* The free DOFs the local forces read (the union of the terms' w vectors: every law
 * states its dependence there, which is what Newton's Jacobian rests on), sorted, into
 * h->win; nin = -1 when unknown or not worth it (every DOF is sampled). Made anew each
 * call (a few dozen entries); a change clears the samples, whose other DOFs then stay
 * zero (the forces do not read them). 0 ok, 1 out of memory. */
static int input_support(hb *h, gd_transient *tr)
{
    const int nf = h->nf;
    const gd_tr_term *term;
    int nt = gd_transient_terms(tr, &term);
    if (!h->win) {
        h->win = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *h->win);
        h->win2 = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *h->win2);
        h->rowmark = calloc((size_t)(nf > 0 ? nf : 1), sizeof *h->rowmark);
        if (!h->win || !h->win2 || !h->rowmark) return 1;
        h->nin = -2; /* none yet */
    }
    int n = -1;
    if (nt >= 0) {
        for (int t = 0; t < nt; t++)
            for (int j = 0; j < term[t].nw; j++)
                h->rowmark[term[t].w_idx[j]] = 1;
        n = 0;
        for (int i = 0; i < nf; i++)
            if (h->rowmark[i]) h->win2[n++] = i;
        for (int q = 0; q < n; q++)
            h->rowmark[h->win2[q]] = 0;
        if (4 * n >= nf) n = -1; /* a quarter of the DOFs or more: batched transforms */
    }
    if (n == h->nin && (n < 0 || !memcmp(h->win, h->win2, (size_t)n * sizeof *h->win))) return 0;
    int *t = h->win;
    h->win = h->win2;
    h->win2 = t;
    h->nin = n;
    memset(h->tq, 0, (size_t)nf * h->N * sizeof *h->tq);
    memset(h->tf, 0, (size_t)nf * h->N * sizeof *h->tf);
    memset(h->y, 0, 2 * (size_t)nf * sizeof *h->y);
    return 0;
}

/* Samples (sample-major) of the DOFs in win only, one row transform each. */
static void synth_support(hb *h, const double *X, int deriv, double *out)
{
    const int nf = h->nf, N = h->N, H = h->H;
    double *b = h->rowbuf, *o = h->rowbuf + N;
    for (int q = 0; q < h->nin; q++) {
        int i = h->win[q];
        fill_row(nf, H, N, X, i, deriv, b);
        fftw_execute_r2r(h->row_inv, b, o);
        for (int j = 0; j < N; j++)
            out[(size_t)j * nf + i] = o[j];
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
    /* time samples: q' into tf first (synth overwrites its input buffer tv), the
     * forces then into tv, sample-major, and their spectra into tf. With a small input
     * support only its DOFs are sampled, and only the rows where a force is non-zero
     * are transformed back (the 378-DOF helical pair: 26 and 38 of 377) */
    if (input_support(h, tr)) return 1;
    const int sup = h->nin >= 0;
    double *qs = h->tq, *vs = h->tf;
    if (sup) {
        synth_support(h, X, 1, vs);
        synth_support(h, X, 0, qs);
    } else {
        synth(h, X, 1, vs);
        synth(h, X, 0, qs);
    }
    double *st = jac ? malloc((size_t)(h->nterm > 0 ? h->nterm : 1) * 2 * sizeof *st) : NULL;
    if (jac && !st) return 1;
    int bad = 0;
    unsigned char *nz = h->rowmark;
    for (int j = 0; j < N; j++) {
        double t = TWO_PI * j / N / w;
        const double *qj = qs + (size_t)j * nf, *vj = vs + (size_t)j * nf;
        double *fj = h->tv + (size_t)j * nf;
        if (sup) { /* the other entries of y stay zero (set when the support changed) */
            for (int q = 0; q < h->nin; q++) {
                int i = h->win[q];
                h->y[i] = qj[i];
                h->y[nf + i] = w * vj[i];
            }
        } else {
            memcpy(h->y, qj, (size_t)nf * sizeof *h->y);
            for (int i = 0; i < nf; i++)
                h->y[nf + i] = w * vj[i];
        }
        gd_transient_local(tr, t, h->y, fj, jac ? st : NULL, jac ? st + h->nterm : NULL);
        for (int i = 0; i < nf; i++) {
            if (!isfinite(fj[i])) bad = 1;
            nz[i] |= fj[i] != 0.0;
        }
        if (jac)
            for (int k = 0; k < h->nterm; k++) {
                h->sq[(size_t)k * N + j] = st[k];
                h->sv[(size_t)k * N + j] = st[h->nterm + k];
            }
    }
    free(st);
    if (sup) {
        for (int i = 0; i < nf; i++) {
            if (!nz[i]) continue;
            for (int j = 0; j < N; j++)
                h->rowbuf[j] = h->tv[(size_t)j * nf + i];
            fftw_execute_r2r(h->row_fwd, h->rowbuf, h->tf + (size_t)i * N);
        }
    } else {
        fftw_execute(h->fwd_f);
        memset(nz, 1, (size_t)nf);
    }
    double nl = 0.0, nf2 = 0.0;
    if (gd_hb_linear_union(h, tr)) return 1;
    memset(R, 0, (size_t)h->n * sizeof *R);
    /* the linear part per harmonic block: mean K X_0; cos/sin pair k, with
     * A = K - (k w)^2 M: A Q_c + k w D Q_s and A Q_s - k w D Q_c */
    for (int j = 0; j < nf; j++)
        for (int p = h->Up[j]; p < h->Up[j + 1]; p++)
            R[h->Ui[p]] += h->UK[p] * X[j];
    for (int k = 1; k <= H; k++) {
        const double kw = k * w, kw2 = kw * kw;
        const double *xc = X + (size_t)(2 * k - 1) * nf, *xs = xc + nf;
        double *rc = R + (size_t)(2 * k - 1) * nf, *rs = rc + nf;
        for (int j = 0; j < nf; j++) {
            double c = xc[j], sn = xs[j];
            for (int p = h->Up[j]; p < h->Up[j + 1]; p++) {
                double a = h->UK[p] - kw2 * h->UM[p], d = kw * h->UD[p];
                int i = h->Ui[p];
                rc[i] += a * c + d * sn;
                rs[i] += a * sn - d * c;
            }
        }
    }
    for (int i = 0; i < h->n; i++)
        nl += R[i] * R[i];
    /* the force coefficients are kept (Fh) for gd_hb_solve_newton */
    if (!h->Fh) h->Fh = malloc((size_t)h->n * sizeof *h->Fh);
    double *Fh = h->Fh, tail = 0.0;
    const int kt = H + 1 > 3 * N / 8 ? H + 1 : 3 * N / 8;
    if (Fh) memset(Fh, 0, (size_t)h->n * sizeof *Fh);
    h->Fh_ok = Fh != NULL;
    for (int i = 0; i < nf; i++) {
        if (!nz[i]) continue; /* a zero force in every sample */
        nz[i] = 0;
        const double *c = h->tf + (size_t)i * N;
        double F = c[0] / N;
        R[i] -= F;
        nf2 += F * F;
        if (Fh) Fh[i] = F;
        /* the force's content in the top quarter below the Nyquist harmonic: what lies
         * beyond it folds back onto the harmonics kept (the aliasing floor, below) */
        for (int k = kt; 2 * k < N; k++) {
            double fc = 2.0 * c[k] / N, fs = 2.0 * c[N - k] / N;
            tail += fc * fc + fs * fs;
        }
        for (int k = 1; k <= H; k++) {
            double fc = 2.0 * c[k] / N, fs = -2.0 * c[N - k] / N;
            R[(size_t)(2 * k - 1) * nf + i] -= fc;
            R[(size_t)2 * k * nf + i] -= fs;
            nf2 += fc * fc + fs * fs;
            if (Fh) {
                Fh[(size_t)(2 * k - 1) * nf + i] = fc;
                Fh[(size_t)2 * k * nf + i] = fs;
            }
        }
    }
    if (scale) *scale = sqrt(nl > nf2 ? nl : nf2);
    {
        double sc = sqrt(nl > nf2 ? nl : nf2);
        h->alias = sc > 0 ? sqrt(tail) / sc : 0.0;
    }
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
    if (h->solver >= 2) return 1; /* 2 low-rank, 3 / 4 with the iterative / dense capacitance */
    return h->n >= 2000 && 4 * gd_hb_term_groups(h, NULL, NULL) * h->nh <= h->n;
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

void gd_hb_solve_newton(hb *h, const double *X, double *b)
{
    if (gd_hb_use_lowrank(h))
        gd_hb_lowrank_solve_newton(h, X, b);
    else
        gd_hb_solve(h, b);
}

void gd_hb_solve(hb *h, double *b)
{
    if (gd_hb_use_lowrank(h)) {
        gd_hb_lowrank_solve(h, b);
        return;
    }
    klu_solve(h->sym, h->num, h->n + 1, 1, b, &h->com);
}
