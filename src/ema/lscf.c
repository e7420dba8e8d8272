/* LSCF, least-squares complex frequency ([Guillaume2003]; [Peeters2004] Sec. 2 for the
 * reduced normal equations), in its poly-reference form: the FRFs arranged as outputs o
 * (responses) by inputs i (references), a right matrix-fraction model
 *   H_o(w) = B_o(z) A(z)^-1,  A(z) = sum_j z^j a_j (Ni x Ni),  z = e^{i w dt},
 *   dt = 1 / (2 f_max),
 * linearised least squares over the lines k: minimise sum_o sum_k |B_o - H_o A|^2. With
 * X_kj = z_k^j and Y_o,k(j,i) = -z_k^j H_oi(w_k) the normal equations are
 * R = Re(X^H X), S_o = Re(X^H Y_o), T_o = Re(Y_o^H Y_o); eliminating the numerators
 * leaves M a = 0, M = sum_o (T_o - S_o^T R^-1 S_o), solved with a_n = I. R, S_o, T_o
 * depend on l - j only (Toeplitz), so the lags up to the highest order are summed once
 * and every order takes its leading blocks. The poles are s = ln(z_r) / dt of the
 * eigenvalues z_r of the block companion matrix of A (det A(z_r) = 0), kept when they
 * are in the band, oscillating and damped below max_damping. With one reference (or
 * FRFs that are not a full response x reference matrix) Ni = 1 and every FRF is an
 * output: one scalar denominator common to all. Several references separate close
 * modes (the x and y modes of a rotor) that one reference sees as one pole. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ema/ema_impl.h"

typedef struct lags {
    int N;      /* highest order */
    int No, Ni; /* outputs, inputs */
    double *r;  /* N + 1: R's lag d */
    double *t;  /* No x Ni x Ni x (2N + 1): T_o's block (i, i') at lag d, index d + N */
    double *sp; /* No x Ni x (2N + 1): S_o's column i at lag d = l - j, index d + N */
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

/* The poles of order n into out (at most n Ni / 2 + 1); returns their count, -1 on
 * failure. work: at least (n+1)^2 + 4 ((n+1) Ni)^2 + 3 (n+1) Ni doubles. */
static int order_poles(const lags *L, int n, double dt, double flo, double fhi, double zmax,
                       double *work, gd_ema_pole *out)
{
    int m = n + 1, Ni = L->Ni, p = m * Ni, q = n * Ni, N = L->N;
    size_t lag = 2 * (size_t)N + 1;
    double *Rn = work, *Mm = Rn + m * m, *W = Mm + p * p, *C = W + m * p;
    double *wr = C + q * q, *wi = wr + q, *rhs = wi + q;
    for (int j = 0; j < m; j++)
        for (int l = 0; l < m; l++)
            Rn[j + l * m] = L->r[abs(l - j)];
    for (int j = 0; j < m; j++)
        for (int i = 0; i < Ni; i++)
            for (int l = 0; l < m; l++)
                for (int i2 = 0; i2 < Ni; i2++) {
                    double tt = 0;
                    for (int o = 0; o < L->No; o++)
                        tt += L->t[(((size_t)o * Ni + i) * Ni + i2) * lag + (size_t)(l - j + N)];
                    Mm[(j * Ni + i) + (size_t)(l * Ni + i2) * p] = tt;
                }
    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', m, Rn, m)) return -1;
    for (int o = 0; o < L->No; o++) {
        for (int j = 0; j < m; j++)
            for (int l = 0; l < m; l++)
                for (int i = 0; i < Ni; i++)
                    W[j + (size_t)(l * Ni + i) * m] =
                        L->sp[((size_t)o * Ni + i) * lag + (size_t)(l - j + N)];
        /* W = L^-1 S_o; M -= W^T W */
        if (LAPACKE_dtrtrs(LAPACK_COL_MAJOR, 'L', 'N', 'N', m, p, Rn, m, W, m)) return -1;
        for (int a = 0; a < p; a++)
            for (int b = 0; b <= a; b++) {
                double sum = 0;
                for (int k = 0; k < m; k++)
                    sum += W[k + (size_t)a * m] * W[k + (size_t)b * m];
                Mm[a + (size_t)b * p] -= sum;
                if (a != b) Mm[b + (size_t)a * p] -= sum;
            }
    }
    /* M[0:q, 0:q] a = -M[0:q, q:p], a_n = I: a_j = rows j Ni.. of the solution */
    double *A = C;
    for (int a = 0; a < q; a++) {
        for (int b = 0; b < q; b++)
            A[a + (size_t)b * q] = Mm[a + (size_t)b * p];
        for (int i = 0; i < Ni; i++)
            rhs[a + (size_t)i * q] = -Mm[a + (size_t)(q + i) * p];
    }
    if (LAPACKE_dposv(LAPACK_COL_MAJOR, 'L', q, Ni, A, q, rhs, q)) {
        for (int a = 0; a < q; a++) {
            for (int b = 0; b < q; b++)
                A[a + (size_t)b * q] = Mm[a + (size_t)b * p];
            for (int i = 0; i < Ni; i++)
                rhs[a + (size_t)i * q] = -Mm[a + (size_t)(q + i) * p];
        }
        lapack_int *piv = (lapack_int *)W;
        if (LAPACKE_dgesv(LAPACK_COL_MAJOR, q, Ni, A, q, piv, rhs, q)) return -1;
    }
    /* block companion of z^n I + a_{n-1} z^{n-1} + ... + a_0: first block row -a_{n-1},
     * ..., -a_0, identities below the diagonal */
    memset(C, 0, (size_t)q * q * sizeof *C);
    for (int j = 0; j < n; j++)
        for (int r = 0; r < Ni; r++)
            for (int c = 0; c < Ni; c++)
                C[r + (size_t)((n - 1 - j) * Ni + c) * q] = -rhs[(j * Ni + r) + (size_t)c * q];
    for (int a = Ni; a < q; a++)
        C[a + (size_t)(a - Ni) * q] = 1;
    if (Ni == 1) {
        if (LAPACKE_dhseqr(LAPACK_COL_MAJOR, 'E', 'N', q, 1, q, C, q, wr, wi, NULL, 1)) return -1;
    } else if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', q, C, q, wr, wi, NULL, 1, NULL, 1)) {
        return -1;
    }
    int np = 0;
    for (int k = 0; k < q; k++) {
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

/* The FRFs as outputs x inputs: Ni > 1 when poly_reference is asked, there are two or
 * more references and every response was measured once for each; else Ni = 1 and each
 * FRF an output. map[o * Ni + i] is the FRF of output o and input i. */
static int arrange(int nfrf, const gd_td_function *const *f, int poly, int *No, int *Ni, int *map)
{
    int refs[16], nref = 0;
    for (int k = 0; k < nfrf && poly; k++) {
        int j = 0;
        while (j < nref && !(f[refs[j]]->reference_node == f[k]->reference_node &&
                             f[refs[j]]->reference_dir == f[k]->reference_dir))
            j++;
        if (j == nref) {
            if (nref == 16) {
                nref = 0;
                break;
            }
            refs[nref++] = k;
        }
    }
    if (nref >= 2 && nfrf % nref == 0) {
        int no = 0, ok = 1;
        for (int k = 0; k < nfrf && ok; k++) {
            if (!(f[k]->reference_node == f[refs[0]]->reference_node &&
                  f[k]->reference_dir == f[refs[0]]->reference_dir))
                continue;
            for (int j = 0; j < nref && ok; j++) {
                int found = -1, count = 0;
                for (int q = 0; q < nfrf; q++)
                    if (f[q]->response_node == f[k]->response_node &&
                        f[q]->response_dir == f[k]->response_dir &&
                        f[q]->reference_node == f[refs[j]]->reference_node &&
                        f[q]->reference_dir == f[refs[j]]->reference_dir)
                        found = q, count++;
                ok = count == 1;
                map[no * nref + j] = found;
            }
            no++;
        }
        if (ok && no * nref == nfrf) {
            *No = no;
            *Ni = nref;
            return 1;
        }
    }
    *No = nfrf;
    *Ni = 1;
    for (int k = 0; k < nfrf; k++)
        map[k] = k;
    return 0;
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
    int No, Ni, *map = malloc((size_t)nfrf * sizeof *map + 1);
    if (!map) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    arrange(nfrf, frfs, opt.poly_reference, &No, &Ni, map);
    size_t lag = 2 * (size_t)N + 1;
    lags L = {N,
              No,
              Ni,
              calloc((size_t)N + 1, sizeof(double)),
              calloc((size_t)No * Ni * Ni * lag, sizeof(double)),
              calloc((size_t)No * Ni * lag, sizeof(double))};
    size_t m = (size_t)N + 1, pp = m * (size_t)Ni;
    double *work = malloc((m * m + 4 * pp * pp + 4 * pp + 8) * sizeof(double));
    gd_ema_result *r = calloc(1, sizeof *r);
    gd_ema_pole *poles = malloc((size_t)(N + 1) * ((size_t)N * Ni + 2) * sizeof *poles);
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
            for (int o = 0; o < No; o++)
                for (int i = 0; i < Ni; i++) {
                    const gd_td_function *fi = frfs[map[o * Ni + i]];
                    double hr = fi->re[k], hi = fi->im[k];
                    /* S_o(d) = -Re(H e^{i th d}); lag -d: -Re(H e^{-i th d}) */
                    double *sp = L.sp + ((size_t)o * Ni + i) * lag + N;
                    sp[d] += -(hr * c - hi * s);
                    if (d) sp[-d] += -(hr * c + hi * s);
                    for (int i2 = 0; i2 < Ni; i2++) {
                        const gd_td_function *f2 = frfs[map[o * Ni + i2]];
                        double gr = f2->re[k], gi = f2->im[k];
                        /* conj(H_i) H_i2 e^{+-i th d} */
                        double cr = hr * gr + hi * gi, ci = hr * gi - hi * gr;
                        double *t = L.t + (((size_t)o * Ni + i) * Ni + i2) * lag + N;
                        t[d] += cr * c - ci * s;
                        if (d) t[-d] += cr * c + ci * s;
                    }
                }
            double cn = c * c1 - s * s1;
            s = s * c1 + c * s1;
            c = cn;
        }
    }
    /* every order: the stabilisation diagram */
    int npoles = 0, prev0 = 0, prevn = 0;
    for (int n = 1; n <= N; n++) {
        int np = order_poles(&L, n, dt, flo, fhi, opt.max_damping, work, poles + npoles);
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
    r->nreferences = Ni;
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
            /* poles per order in the cluster: k at most orders means k modes closer
             * than the stability tolerance (an x and a y mode seen by two references);
             * the i-th pole by frequency of each such order is the i-th mode's */
            memset(seen, 0, (size_t)N + 1);
            int count = 0, hist[8] = {0};
            for (int i = a; i < b; i++)
                if (seen[sel[i].order] < 100) seen[sel[i].order]++;
            for (int o = lo_order; o <= N; o++)
                if (seen[o]) count++, hist[seen[o] < 7 ? seen[o] : 7]++;
            int k = 1;
            for (int c = 2; c < 7; c++)
                if (hist[c] > hist[k]) k = c;
            if (hist[k] < opt.stable_share * norders) k = 1;
            int korders = k == 1 ? count : hist[k];
            for (int sub = 0; sub < k && korders >= opt.stable_share * norders; sub++) {
                int nt = 0;
                for (int i = a; i < b; i++) {
                    if (k > 1 && seen[sel[i].order] != k) continue;
                    if (k > 1) { /* the rank of pole i among its order's poles */
                        int rank = 0;
                        for (int j = a; j < i; j++)
                            rank += sel[j].order == sel[i].order;
                        if (rank != sub) continue;
                    }
                    tmp[nt++] = sel[i].frequency_hz;
                }
                gd_ema_mode *md = &r->modes[r->nmodes++];
                qsort(tmp, (size_t)nt, sizeof *tmp, cmp_double);
                md->frequency_hz = tmp[nt / 2];
                nt = 0;
                for (int i = a; i < b; i++) {
                    if (k > 1 && seen[sel[i].order] != k) continue;
                    if (k > 1) {
                        int rank = 0;
                        for (int j = a; j < i; j++)
                            rank += sel[j].order == sel[i].order;
                        if (rank != sub) continue;
                    }
                    tmp[nt++] = sel[i].damping_ratio;
                }
                qsort(tmp, (size_t)nt, sizeof *tmp, cmp_double);
                md->damping_ratio = tmp[nt / 2];
                md->stable_count = korders;
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
    free(L.r), free(L.t), free(L.sp), free(work), free(poles), free(map);
    if (st)
        gd_ema_free(r);
    else
        *out = r;
    return st;
}
