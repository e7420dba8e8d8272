/* The Woodbury capacitance S = I - Y L^-1 U of the low-rank solver (lowrank.c) solved
 * without forming it, for a large rank r = ngroup (2H + 1): the dense LU costs
 * (2/3) r^3 flops and r^2 doubles (with the terms' couplings G_t, nterm (2H + 1)^2 more),
 * the TVMS from geometry needs H in the thousands (docs/periodic.md, "Harmonic
 * truncation"). Here S z is applied in O(H log H):
 *   (Y L^-1 U z)_g = sum_{t in g} G_t y_t,   y_t,k = sum_g' T_{t g' k} z_g',k,
 * with the transfer scalars T_{t g k} = w_t^T Z_k^-1 u_g (complex per harmonic block k,
 * read from the columns of L^-1 U once per factorization) and G_t applied as the AFT does:
 * the coefficients y_t sampled at the residual's N phases (with their phase derivative),
 * multiplied by the term's samples s_q + w s_v d/dtau, transformed back. The sampled sums
 * are the ones G_t is made of (hb_blocks.c), so the operator is the dense one's.
 * S z = b is solved by restarted GMRES (right preconditioning, modified Gram-Schmidt,
 * Givens rotations; Saad & Schultz 1986) preconditioned by the same capacitance with only
 * the mean of each term's samples: then G_t keeps the harmonics apart (on block k a
 * multiplication by s_q0 - i k w s_v0), so the preconditioner is one ngroup x ngroup
 * complex matrix per harmonic, exact for a time-invariant law: GMRES iterates only on
 * the variation (the TVMS). */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

/* Restart length and the total iterations allowed per solve. */
#define CAP_RESTART 60
#define CAP_MAXIT 1200

int gd_hb_cap_iterative(int solver, int r)
{
    if (solver == 3) return 1;
    if (solver == 4) return 0;
    return r >= GD_HB_CAP_CROSSOVER;
}

int gd_hb_term_activity(hb *h)
{
    const int N = h->N;
    free(h->tactive);
    h->tactive = malloc((size_t)(h->nterm > 0 ? h->nterm : 1) * sizeof *h->tactive);
    if (!h->tactive) return 1;
    for (int t = 0; t < h->nterm; t++) {
        const double *sq = h->sq + (size_t)t * N, *sv = h->sv + (size_t)t * N;
        int on = 0;
        for (int j = 0; j < N && !on; j++)
            on = sq[j] != 0.0 || sv[j] != 0.0;
        h->tactive[t] = (unsigned char)on;
    }
    return 0;
}

void gd_hb_cap_free(hb *h)
{
    free(h->cT);
    free(h->cpre);
    free(h->cpiv);
    free(h->cq);
    free(h->cwork);
    h->cT = h->cpre = h->cq = h->cwork = NULL;
    h->cpiv = NULL;
}

int gd_hb_cap_alloc(hb *h)
{
    const int nt = h->nterm > 0 ? h->nterm : 1, ng = h->ngroup > 0 ? h->ngroup : 1;
    const size_t H1 = (size_t)h->H + 1, N = (size_t)h->N, r = (size_t)(h->r > 0 ? h->r : 1);
    const size_t m = CAP_RESTART;
    gd_hb_cap_free(h);
    h->cT = malloc(2 * H1 * nt * ng * sizeof *h->cT);
    h->cpre = malloc(2 * H1 * ng * ng * sizeof *h->cpre);
    h->cpiv = malloc(H1 * ng * sizeof *h->cpiv);
    h->cq = malloc(2 * (size_t)nt * N * sizeof *h->cq);
    /* Krylov basis (m + 1) r, Hessenberg (m + 1) m, rotations and rhs 3 (m + 1), three
     * r vectors, the terms' coefficients nt nh, the groups' samples ng N, two rows of N */
    h->cwork = malloc(((m + 1) * r + (m + 1) * m + 3 * (m + 1) + 3 * r + (size_t)nt * h->nh +
                       (size_t)ng * N + 2 * N) *
                      sizeof *h->cwork);
    return h->cT && h->cpre && h->cpiv && h->cq && h->cwork ? 0 : 1;
}

/* Complex LU with partial pivoting of the n x n matrix a (column-major), in place. */
static void zlu(int n, double complex *a, int *piv)
{
    for (int j = 0; j < n; j++) {
        int p = j;
        for (int i = j + 1; i < n; i++)
            if (cabs(a[(size_t)j * n + i]) > cabs(a[(size_t)j * n + p])) p = i;
        piv[j] = p;
        if (p != j)
            for (int c = 0; c < n; c++) {
                double complex x = a[(size_t)c * n + j];
                a[(size_t)c * n + j] = a[(size_t)c * n + p];
                a[(size_t)c * n + p] = x;
            }
        double complex d = a[(size_t)j * n + j];
        if (d == 0.0) {
            a[(size_t)j * n + j] = d = 1.0; /* singular mean block: leave that row alone */
        }
        for (int i = j + 1; i < n; i++) {
            double complex l = a[(size_t)j * n + i] / d;
            a[(size_t)j * n + i] = l;
            for (int c = j + 1; c < n; c++)
                a[(size_t)c * n + i] -= l * a[(size_t)c * n + j];
        }
    }
}

static void zlu_solve(int n, const double complex *a, const int *piv, double complex *b)
{
    for (int j = 0; j < n; j++) {
        if (piv[j] != j) {
            double complex x = b[j];
            b[j] = b[piv[j]];
            b[piv[j]] = x;
        }
        for (int i = j + 1; i < n; i++)
            b[i] -= a[(size_t)j * n + i] * b[j];
    }
    for (int j = n - 1; j >= 0; j--) {
        b[j] /= a[(size_t)j * n + j];
        for (int i = 0; i < j; i++)
            b[i] -= a[(size_t)j * n + i] * b[j];
    }
}

int gd_hb_cap_factor(hb *h, double w, int fresh)
{
    const int nf = h->nf, nh = h->nh, N = h->N, nt = h->nterm, ng = h->ngroup, bw = 2 * nf;
    double complex *T = (double complex *)h->cT, *B = (double complex *)h->cpre;
    /* T_{t g k} = w_t^T (column (g, cos k) of L^-1 U as Re z in the cos half, Im z in the
     * sin half): depends on L only */
    for (int k = 0; fresh && k <= h->H; k++)
        for (int t = 0; t < nt; t++) {
            if (h->tgroup[t] < 0) continue;
            const gd_tr_term *tm = &h->term[t];
            for (int g = 0; g < ng; g++) {
                const double *p = h->P + ((size_t)g * nh + (k ? 2 * k - 1 : 0)) * bw;
                double re = 0.0, im = 0.0;
                for (int j = 0; j < tm->nw; j++) {
                    re += tm->w[j] * p[tm->w_idx[j]];
                    if (k) im += tm->w[j] * p[nf + tm->w_idx[j]];
                }
                T[((size_t)k * nt + t) * ng + g] = re + I * im;
            }
        }
    /* the samples s_q and w s_v of this iterate, and the preconditioner from their means */
    double *cq = h->cq, *cv = h->cq + (size_t)nt * N;
    memcpy(cq, h->sq, (size_t)nt * N * sizeof *cq);
    for (size_t i = 0; i < (size_t)nt * N; i++)
        cv[i] = w * h->sv[i];
    double *mq = h->cwork, *mv = mq + nt; /* scratch, before any solve uses cwork */
    for (int t = 0; t < nt; t++) {
        double a = 0.0, b = 0.0;
        for (int j = 0; j < N; j++) {
            a += cq[(size_t)t * N + j];
            b += cv[(size_t)t * N + j];
        }
        mq[t] = a / N;
        mv[t] = b / N;
    }
    for (int k = 0; k <= h->H; k++) {
        double complex *Bk = B + (size_t)k * ng * ng;
        for (int i = 0; i < ng * ng; i++)
            Bk[i] = 0.0;
        for (int g = 0; g < ng; g++)
            Bk[(size_t)g * ng + g] = 1.0;
        for (int t = 0; t < nt; t++) {
            int g = h->tgroup[t];
            if (g < 0) continue;
            double complex gam = mq[t] - I * (double)k * mv[t];
            for (int g2 = 0; g2 < ng; g2++)
                Bk[(size_t)g2 * ng + g] -= gam * T[((size_t)k * nt + t) * ng + g2];
        }
        zlu(ng, Bk, h->cpiv + (size_t)k * ng);
    }
    return 0;
}

/* out (r) = sum_{t in g} G_t y_t for the terms' coefficients yt (nt x nh), by sampling:
 * the AFT of the residual applied to one rank-one term per group. */
static void apply_G(hb *h, const double *yt, double *out, double *fg, double *row, double *o)
{
    const int nh = h->nh, N = h->N, H = h->H, nt = h->nterm, ng = h->ngroup;
    const double *cq = h->cq, *cv = h->cq + (size_t)nt * N;
    memset(fg, 0, (size_t)ng * N * sizeof *fg);
    for (int t = 0; t < nt; t++) {
        int g = h->tgroup[t];
        if (g < 0) continue;
        const double *y = yt + (size_t)t * nh;
        double *f = fg + (size_t)g * N;
        for (int pass = 0; pass < 2; pass++) { /* y, then its phase derivative */
            memset(row, 0, (size_t)N * sizeof *row);
            if (!pass) row[0] = y[0];
            for (int k = 1; k <= H; k++) {
                double c = y[2 * k - 1], s = y[2 * k];
                row[k] = 0.5 * (pass ? k * s : c);
                row[N - k] = -0.5 * (pass ? -k * c : s);
            }
            fftw_execute_r2r(h->row_inv, row, o);
            const double *m = (pass ? cv : cq) + (size_t)t * N;
            for (int j = 0; j < N; j++)
                f[j] += m[j] * o[j];
        }
    }
    for (int g = 0; g < ng; g++) {
        fftw_execute_r2r(h->row_fwd, fg + (size_t)g * N, o);
        double *z = out + (size_t)g * nh;
        z[0] = o[0] / N;
        for (int k = 1; k <= H; k++) {
            z[2 * k - 1] = 2.0 * o[k] / N;
            z[2 * k] = -2.0 * o[N - k] / N;
        }
    }
}

void gd_hb_cap_Yy(hb *h, const double *x, double *wz)
{
    const int nf = h->nf, nh = h->nh, nt = h->nterm;
    const size_t r = (size_t)(h->r > 0 ? h->r : 1), m = CAP_RESTART;
    double *yt = h->cwork + (m + 1) * r + (m + 1) * m + 3 * (m + 1) + 3 * r;
    double *fg = yt + (size_t)(nt > 0 ? nt : 1) * nh, *row = fg + (size_t)h->ngroup * h->N,
           *o = row + h->N;
    for (int t = 0; t < nt; t++) {
        if (h->tgroup[t] < 0) continue;
        const gd_tr_term *tm = &h->term[t];
        for (int b = 0; b < nh; b++) {
            double z = 0.0;
            for (int j = 0; j < tm->nw; j++)
                z += tm->w[j] * x[(size_t)b * nf + tm->w_idx[j]];
            yt[(size_t)t * nh + b] = z;
        }
    }
    apply_G(h, yt, wz, fg, row, o);
}

/* out = S z = z - sum_{t in g} G_t (sum_g' T_{t g'} z_g') */
static void apply_S(hb *h, const double *z, double *out)
{
    const int nh = h->nh, nt = h->nterm, ng = h->ngroup, H = h->H;
    const size_t r = (size_t)h->r, m = CAP_RESTART;
    const double complex *T = (const double complex *)h->cT;
    double *yt = h->cwork + (m + 1) * r + (m + 1) * m + 3 * (m + 1) + 3 * r;
    double *fg = yt + (size_t)(nt > 0 ? nt : 1) * nh, *row = fg + (size_t)ng * h->N,
           *o = row + h->N;
    for (int t = 0; t < nt; t++) {
        if (h->tgroup[t] < 0) continue;
        double *y = yt + (size_t)t * nh;
        for (int k = 0; k <= H; k++) {
            double complex a = 0.0;
            const double complex *Tk = T + ((size_t)k * nt + t) * ng;
            for (int g = 0; g < ng; g++) {
                const double *zg = z + (size_t)g * nh;
                a += Tk[g] * (k ? zg[2 * k - 1] + I * zg[2 * k] : zg[0]);
            }
            if (k) {
                y[2 * k - 1] = creal(a);
                y[2 * k] = cimag(a);
            } else {
                y[0] = creal(a);
            }
        }
    }
    apply_G(h, yt, out, fg, row, o);
    for (size_t i = 0; i < r; i++)
        out[i] = z[i] - out[i];
}

/* z := M^-1 z, M the capacitance of the terms' means (one small block per harmonic) */
static void apply_pre(hb *h, double *z)
{
    const int nh = h->nh, ng = h->ngroup;
    const double complex *B = (const double complex *)h->cpre;
    double complex v[64], *vb = ng <= 64 ? v : malloc((size_t)ng * sizeof *vb);
    if (!vb) return; /* no memory: unpreconditioned (GMRES still converges) */
    for (int k = 0; k <= h->H; k++) {
        for (int g = 0; g < ng; g++) {
            const double *zg = z + (size_t)g * nh;
            vb[g] = k ? zg[2 * k - 1] + I * zg[2 * k] : zg[0];
        }
        zlu_solve(ng, B + (size_t)k * ng * ng, h->cpiv + (size_t)k * ng, vb);
        for (int g = 0; g < ng; g++) {
            double *zg = z + (size_t)g * nh;
            if (k) {
                zg[2 * k - 1] = creal(vb[g]);
                zg[2 * k] = cimag(vb[g]);
            } else {
                zg[0] = creal(vb[g]);
            }
        }
    }
    if (vb != v) free(vb);
}

static double dot(size_t n, const double *a, const double *b)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

int gd_hb_cap_solve(hb *h, double *b, double tol, int *iters)
{
    const size_t r = (size_t)h->r, m = CAP_RESTART;
    double *V = h->cwork, *Hs = V + (m + 1) * r, *cs = Hs + (m + 1) * m, *sn = cs + m + 1,
           *gv = sn + m + 1, *x = gv + m + 1, *res = x + r, *u = res + r;
    int it = 0;
    if (iters) *iters = 0;
    if (!r) return 0;
    const double bn = sqrt(dot(r, b, b));
    if (bn == 0.0) return 0;
    /* start from the preconditioner's solution */
    memcpy(x, b, r * sizeof *x);
    apply_pre(h, x);
    double rn = 0.0;
    for (;;) {
        apply_S(h, x, res);
        for (size_t i = 0; i < r; i++)
            res[i] = b[i] - res[i];
        rn = sqrt(dot(r, res, res));
        if (!(rn > tol * bn) || it >= CAP_MAXIT || !isfinite(rn)) break;
        for (size_t i = 0; i < r; i++)
            V[i] = res[i] / rn;
        gv[0] = rn;
        size_t j = 0;
        for (; j < m && it < CAP_MAXIT; j++, it++) {
            double *vj = V + j * r, *vn = vj + r, *hj = Hs + j * (m + 1);
            memcpy(u, vj, r * sizeof *u);
            apply_pre(h, u);
            apply_S(h, u, vn);
            for (size_t i = 0; i <= j; i++) { /* modified Gram-Schmidt */
                double c = dot(r, vn, V + i * r);
                hj[i] = c;
                for (size_t q = 0; q < r; q++)
                    vn[q] -= c * V[i * r + q];
            }
            double nn = sqrt(dot(r, vn, vn));
            hj[j + 1] = nn;
            if (nn > 0)
                for (size_t q = 0; q < r; q++)
                    vn[q] /= nn;
            for (size_t i = 0; i < j; i++) { /* the earlier rotations */
                double a = hj[i], c = hj[i + 1];
                hj[i] = cs[i] * a + sn[i] * c;
                hj[i + 1] = -sn[i] * a + cs[i] * c;
            }
            double d = hypot(hj[j], hj[j + 1]);
            cs[j] = d > 0 ? hj[j] / d : 1.0;
            sn[j] = d > 0 ? hj[j + 1] / d : 0.0;
            hj[j] = d;
            hj[j + 1] = 0.0;
            gv[j + 1] = -sn[j] * gv[j];
            gv[j] *= cs[j];
            if (!(fabs(gv[j + 1]) > 0.5 * tol * bn) || nn == 0.0) {
                j++;
                it++;
                break;
            }
        }
        /* y from the triangle, x += M^-1 V y */
        for (size_t i = j; i-- > 0;) {
            double s = gv[i];
            for (size_t q = i + 1; q < j; q++)
                s -= Hs[q * (m + 1) + i] * gv[q];
            gv[i] = Hs[i * (m + 1) + i] != 0.0 ? s / Hs[i * (m + 1) + i] : 0.0;
        }
        memset(u, 0, r * sizeof *u);
        for (size_t i = 0; i < j; i++)
            for (size_t q = 0; q < r; q++)
                u[q] += gv[i] * V[i * r + q];
        apply_pre(h, u);
        for (size_t q = 0; q < r; q++)
            x[q] += u[q];
    }
    if (iters) *iters = it;
    memcpy(b, x, r * sizeof *b);
    h->cap_iters += it;
    h->cap_resid = rn / bn > h->cap_resid ? rn / bn : h->cap_resid;
    return rn <= tol * bn ? 0 : (rn <= 1e-8 * bn ? 2 : 1);
}
