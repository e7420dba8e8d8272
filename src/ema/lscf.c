/* LSCF, least-squares complex frequency ([Guillaume2003]; [Peeters2004] Sec. 2 for the
 * reduced normal equations), with one scalar denominator common to every FRF:
 *   H_o(w) = N_o(z) / d(z),  z = e^{i w dt},  d(z) = sum_j a_j z^j,  dt = 1 / (2 f_max).
 * Linearised least squares over the lines k: minimise sum_o sum_k |N_o - H_o d|^2.
 * With X_kj = z_k^j and Y_o,kj = -z_k^j H_o(w_k) the normal equations are
 * R = Re(X^H X), S_o = Re(X^H Y_o), T_o = Re(Y_o^H Y_o); eliminating the numerators
 * leaves M a = 0, M = sum_o (T_o - S_o^T R^-1 S_o), solved with a_n = 1. R, S_o, T_o
 * depend on l - j only (Toeplitz), so the lags up to the highest order are summed once
 * and every order takes its leading blocks. The poles are s = ln(z_r) / dt of the
 * roots z_r of d, kept when they are in the band, oscillating and damped below
 * max_damping. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ema/ema_impl.h"

typedef struct lags {
    int N;      /* highest order */
    double *r;  /* N + 1: R's lag d */
    double *t;  /* nfrf x (N + 1): T_o's lag d */
    double *sp; /* nfrf x (2N + 1): S_o at lag d = l - j, index d + N */
} lags;

static int cmp_pole(const void *a, const void *b)
{
    const gd_ema_pole *x = a, *y = b;
    return (x->frequency_hz > y->frequency_hz) - (x->frequency_hz < y->frequency_hz);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The poles of order n into out (at most n/2 + 1); returns their count, -1 on failure. */
static int order_poles(const lags *L, int nfrf, int n, double dt, double flo, double fhi,
                       double zmax, double *work, gd_ema_pole *out)
{
    int m = n + 1;
    double *Rn = work, *Mm = Rn + m * m, *W = Mm + m * m, *C = W + m * m;
    double *wr = C + n * n, *wi = wr + n;
    for (int j = 0; j < m; j++)
        for (int l = 0; l < m; l++) {
            Rn[j + l * m] = L->r[abs(l - j)];
            double tt = 0;
            for (int o = 0; o < nfrf; o++)
                tt += L->t[o * (L->N + 1) + abs(l - j)];
            Mm[j + l * m] = tt;
        }
    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', m, Rn, m)) return -1;
    for (int o = 0; o < nfrf; o++) {
        const double *sp = L->sp + (size_t)o * (2 * L->N + 1);
        for (int j = 0; j < m; j++)
            for (int l = 0; l < m; l++)
                W[j + l * m] = sp[l - j + L->N];
        /* W = L^-1 S_o; M -= W^T W */
        if (LAPACKE_dtrtrs(LAPACK_COL_MAJOR, 'L', 'N', 'N', m, m, Rn, m, W, m)) return -1;
        for (int j = 0; j < m; j++)
            for (int l = 0; l <= j; l++) {
                double s = 0;
                for (int k = 0; k < m; k++)
                    s += W[k + j * m] * W[k + l * m];
                Mm[j + l * m] -= s;
                if (l != j) Mm[l + j * m] -= s;
            }
    }
    /* M[0:n,0:n] a = -M[0:n, n], a_n = 1 */
    double *rhs = W; /* reuse */
    for (int j = 0; j < n; j++)
        rhs[j] = -Mm[j + n * m];
    double *A = C;
    for (int j = 0; j < n; j++)
        for (int l = 0; l < n; l++)
            A[j + l * n] = Mm[j + l * m];
    if (LAPACKE_dposv(LAPACK_COL_MAJOR, 'L', n, 1, A, n, rhs, n)) {
        for (int j = 0; j < n; j++)
            for (int l = 0; l < n; l++)
                A[j + l * n] = Mm[j + l * m];
        for (int j = 0; j < n; j++)
            rhs[j] = -Mm[j + n * m];
        lapack_int *piv = (lapack_int *)(wi + n);
        if (LAPACKE_dgesv(LAPACK_COL_MAJOR, n, 1, A, n, piv, rhs, n)) return -1;
    }
    /* companion matrix of z^n + a_{n-1} z^{n-1} + ... + a_0 */
    memset(C, 0, (size_t)n * n * sizeof *C);
    for (int j = 0; j < n; j++)
        C[0 + j * n] = -rhs[n - 1 - j];
    for (int j = 1; j < n; j++)
        C[j + (j - 1) * n] = 1;
    if (LAPACKE_dhseqr(LAPACK_COL_MAJOR, 'E', 'N', n, 1, n, C, n, wr, wi, NULL, 1)) return -1;
    int np = 0;
    for (int k = 0; k < n; k++) {
        double mag = hypot(wr[k], wi[k]), arg = atan2(wi[k], wr[k]);
        if (!(arg > 0) || !(mag > 0)) continue;
        double sr = log(mag) / dt, si = arg / dt;
        double wn = hypot(sr, si), zeta = -sr / wn, f = wn / (2 * M_PI);
        if (!(zeta > 0) || zeta > zmax || f < flo || f > fhi) continue;
        out[np].order = n;
        out[np].frequency_hz = f;
        out[np].damping_ratio = zeta;
        out[np].status = 'o';
        np++;
    }
    qsort(out, (size_t)np, sizeof *out, cmp_pole);
    return np;
}

gd_status gd_ema_lscf(int nfrf, const gd_td_function *const *frfs, const gd_ema_options *opt_in,
                      gd_ema_result **out, gd_error *err)
{
    *out = NULL;
    gd_ema_options opt;
    if (opt_in)
        opt = *opt_in;
    else
        gd_ema_options_init(&opt);
    int N = opt.max_order;
    if (N < 2 || N > 400)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "max_order", "an order from 2 to 400",
                            "model order %d", N);
    int k0, k1;
    gd_status st = gd_ema_band(nfrf, frfs, &opt, 2 * N + 2, &k0, &k1, err);
    if (st) return st;
    const double *fr = frfs[0]->freq_hz;
    double flo = fr[k0], fhi = fr[k1 - 1], dt = 1 / (2 * fhi);
    lags L = {N, calloc((size_t)N + 1, sizeof(double)),
              calloc((size_t)nfrf * (N + 1), sizeof(double)),
              calloc((size_t)nfrf * (2 * N + 1), sizeof(double))};
    size_t m = (size_t)N + 1;
    double *work = malloc((4 * m * m + 4 * m) * sizeof(double));
    gd_ema_result *r = calloc(1, sizeof *r);
    gd_ema_pole *poles = malloc((size_t)(N + 1) * (N / 2 + 2) * sizeof *poles);
    if (!L.r || !L.t || !L.sp || !work || !r || !poles) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    /* the lags: cos and sin of w_k dt d by the recurrence of e^{i w dt} */
    for (int k = k0; k < k1; k++) {
        double th = 2 * M_PI * fr[k] * dt, c1 = cos(th), s1 = sin(th);
        double c = 1, s = 0;
        for (int d = 0; d <= N; d++) {
            if (d % 16 == 0) c = cos(th * d), s = sin(th * d); /* no drift */
            L.r[d] += c;
            for (int o = 0; o < nfrf; o++) {
                double hr = frfs[o]->re[k], hi = frfs[o]->im[k];
                L.t[o * (N + 1) + d] += (hr * hr + hi * hi) * c;
                /* S_o(d) = -Re(H e^{i th d}); lag -d: -Re(H e^{-i th d}) */
                L.sp[(size_t)o * (2 * N + 1) + N + d] += -(hr * c - hi * s);
                if (d) L.sp[(size_t)o * (2 * N + 1) + N - d] += -(hr * c + hi * s);
            }
            double cn = c * c1 - s * s1;
            s = s * c1 + c * s1;
            c = cn;
        }
    }
    /* every order: the stabilisation diagram */
    int npoles = 0, prev0 = 0, prevn = 0;
    for (int n = 1; n <= N; n++) {
        int np = order_poles(&L, nfrf, n, dt, flo, fhi, opt.max_damping, work, poles + npoles);
        if (np < 0) {
            st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "LSCF",
                              "the FRFs may be zero or the band too narrow",
                              "LSCF normal equations singular at order %d", n);
            goto done;
        }
        for (int i = 0; i < np; i++) {
            gd_ema_pole *p = &poles[npoles + i];
            double best = INFINITY;
            int bj = -1;
            for (int j = prev0; j < prev0 + prevn; j++) {
                double df = fabs(poles[j].frequency_hz - p->frequency_hz) / p->frequency_hz;
                if (df < best) best = df, bj = j;
            }
            if (bj >= 0 && best < opt.stab_freq) {
                double dz = fabs(poles[bj].damping_ratio - p->damping_ratio) / p->damping_ratio;
                p->status = dz < opt.stab_damp ? 's' : 'f';
            }
        }
        prev0 = npoles;
        prevn = np;
        npoles += np;
    }
    r->npoles = npoles;
    r->poles = poles;
    poles = NULL;
    r->max_order = N;
    r->nfrf = nfrf;
    r->band_lo_hz = flo;
    r->band_hi_hz = fhi;
    r->nlines = k1 - k0;
    /* the modes: clusters of stable poles over the upper half of the orders */
    {
        int lo_order = N / 2, norders = N - lo_order + 1;
        gd_ema_pole *sel = malloc((size_t)npoles * sizeof *sel + 1);
        double *tmp = malloc((size_t)npoles * sizeof *tmp + 1);
        char *seen = calloc((size_t)N + 1, 1);
        r->modes = malloc((size_t)npoles * sizeof *r->modes + 1);
        if (!sel || !tmp || !seen || !r->modes) {
            free(sel), free(tmp), free(seen);
            st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
            goto done;
        }
        int ns = 0;
        for (int i = 0; i < npoles; i++)
            if (r->poles[i].order >= lo_order && r->poles[i].status == 's') sel[ns++] = r->poles[i];
        qsort(sel, (size_t)ns, sizeof *sel, cmp_pole);
        for (int a = 0; a < ns;) {
            int b = a + 1;
            while (b < ns && (sel[b].frequency_hz - sel[b - 1].frequency_hz) / sel[b].frequency_hz <
                                 opt.stab_freq)
                b++;
            memset(seen, 0, (size_t)N + 1);
            int count = 0;
            for (int i = a; i < b; i++)
                if (!seen[sel[i].order]) seen[sel[i].order] = 1, count++;
            if (count >= opt.stable_share * norders) {
                gd_ema_mode *md = &r->modes[r->nmodes++];
                for (int i = a; i < b; i++)
                    tmp[i - a] = sel[i].frequency_hz;
                qsort(tmp, (size_t)(b - a), sizeof *tmp, cmp_double);
                md->frequency_hz = tmp[(b - a) / 2];
                for (int i = a; i < b; i++)
                    tmp[i - a] = sel[i].damping_ratio;
                qsort(tmp, (size_t)(b - a), sizeof *tmp, cmp_double);
                md->damping_ratio = tmp[(b - a) / 2];
                md->stable_count = count;
                double wn = 2 * M_PI * md->frequency_hz, z = md->damping_ratio;
                md->lambda_re = -z * wn;
                md->lambda_im = wn * sqrt(1 - z * z);
            }
            a = b;
        }
        free(sel), free(tmp), free(seen);
    }
    st = gd_ema_lsfd(nfrf, frfs, k0, k1, r, err);
done:
    free(L.r), free(L.t), free(L.sp), free(work), free(poles);
    if (st)
        gd_ema_free(r);
    else
        *out = r;
    return st;
}
