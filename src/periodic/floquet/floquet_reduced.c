/* Floquet multipliers of a harmonic balance solution in a reduced basis (docs/periodic.md,
 * "Stability at scale"): the variational equations M x'' + D x' + K x = sum_t u_t (sq_t(t)
 * w_t.x + sv_t(t) w_t.x') (gd_transient_local's rank-one terms) projected on
 *   V = [the modes of (sym K, M) below a cut-off frequency,
 *        the residual flexibility of the discarded modes along every term's u_t and w_t]
 * (a Craig-Bampton-like Ritz basis: the static correction sum_j phi_j phi_j^T v / lambda_j
 * over the discarded modes, as the constraint modes of Craig & Bampton 1968 carry the
 * statics of the DOFs they keep), M-orthonormal. The reduced
 * constant state matrix A0 = [0, I; -Kr, -Dr] (2r x 2r) is diagonalised once (LAPACK
 * dgeev; D is not proportional, so its modes are complex: real 2 x 2 blocks), so its
 * exponential over any step is exact and costs O((2r)^2) on the propagated matrix however
 * stiff the kept modes. The time-varying part B(t) = P C R(t) has rank nterm (P the ng
 * distinct force directions, R the nterm input rows with the laws' derivatives), and each
 * step is a fourth-order Magnus step in the interaction picture about its midpoint (see the
 * propagation below), whose exponential is a closed-form rank-2 ng update, so a step costs
 * about 4 (nterm + ng) (2r)^2 flops. The steps are the Magnus steps of floquet.c (split at
 * contact changes), and the orbit at their two Gauss points comes from inverse FFTs of the
 * input DOFs' coefficients shifted by the Gauss-point phase (direct sums only on the steps
 * a contact change split). The multipliers are the eigenvalues of Psi (similar to the
 * reduced monodromy), LAPACK dgeev, then the discarded modes' estimates. */
#include <cblas.h>
#include <fftw3.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"
#include "periodic/continuation_impl.h"
#include "periodic/periodic_impl.h"

#ifndef TWO_PI
#define TWO_PI 6.28318530717958647692
#endif
/* the default cut-off, in multiples of the highest excitation frequency (measured: docs) */
#define GD_FLOQUET_CUTOFF 4.0
/* residual vectors per direction: (K^-1 M)^(o-1) K^-1 v over the discarded modes for the
 * orders o up to this one. Measured on the [JMSTHelical] model (docs/periodic.md): the
 * second and third orders moved the largest multiplier by 2e-5 but added spurious ones
 * (0.99 and 0.85 where the whole model has none), so only the static correction */
#define GD_FLOQUET_RESID_ORDER 1
/* the least reciprocal condition of the equilibrated eigenvector basis (a defective pair's
 * computed eigenvectors are parallel to about sqrt(eps)) */
#define GD_FLOQUET_RCOND 1e-8
/* the most Magnus steps per period the reduced method takes of its own choice */
#define GD_FLOQUET_STEPS_MAX 131072

/* out = A (dense n x n; A is n x n) */
static void dense_of(const gd_csc *A, int n, double *out)
{
    memset(out, 0, (size_t)n * n * sizeof *out);
    gd_csc_add_dense(A, 1.0, out);
}

/* C = alpha A B with A m x k and B k x n, column-major, for the small matrices of the
 * Magnus steps (4 ng = 12 on the [JMSTHelical] model): inline, as a BLAS call per product
 * cost more than its 1728 multiply-adds (callgrind: 25 calls per step, half the
 * stability's instructions). */
static void small_mul_rect(int m, int k, int n, double alpha, const double *A, const double *B,
                           double *C)
{
    for (int j = 0; j < n; j++) {
        double *c = C + (size_t)j * m;
        for (int i = 0; i < m; i++)
            c[i] = 0.0;
        for (int l = 0; l < k; l++) {
            const double b = alpha * B[(size_t)j * k + l];
            if (b == 0.0) continue;
            const double *a = A + (size_t)l * m;
            for (int i = 0; i < m; i++)
                c[i] += a[i] * b;
        }
    }
}

/* C = alpha A B, n x n */
static void small_mul(int n, double alpha, const double *A, const double *B, double *C)
{
    small_mul_rect(n, n, n, alpha, A, B, C);
}

/* P = phi1(A) = sum_m A^m / (m + 1)! for a small n x n matrix (the rank-2 ng update's
 * kernel, 2 ng = 6 on the [JMSTHelical] model): Taylor of exp and phi1 together after
 * scaling A to a 1-norm of 1/2, until a term's 1-norm bound falls below 1e-18 of the sum's
 * (at most 18 terms: 1/2^18/18! < 1e-21), then s doublings phi1(2 A) = phi1(A) (exp(A) +
 * I) / 2, exp(2 A) = exp(A)^2. Before: the exponential of the 2n x 2n block [A, I; 0, 0],
 * 8 times the multiply-adds. W: 4 n^2. */
static void small_phi1(int n, const double *A, double *P, double *W)
{
    const size_t nn = (size_t)n * n;
    const double norm = LAPACKE_dlange_work(LAPACK_COL_MAJOR, '1', n, n, A, n, NULL);
    int s = norm > 0.5 ? (int)ceil(log2(norm / 0.5)) : 0;
    if (s > 1000) s = 1000;
    const double sc = ldexp(1.0, -s);
    double *S = W, *T = W + nn, *U = W + 2 * nn, *E = W + 3 * nn;
    for (size_t k = 0; k < nn; k++)
        S[k] = A[k] * sc;
    memset(E, 0, nn * sizeof *E);
    memset(T, 0, nn * sizeof *T);
    memset(P, 0, nn * sizeof *P);
    for (int i = 0; i < n; i++)
        E[(size_t)i * n + i] = T[(size_t)i * n + i] = P[(size_t)i * n + i] = 1.0;
    /* T = S^m / m!: |T| <= (norm sc)^m / m!; E += T, P += T / (m + 1) */
    double bound = 1.0;
    const double ns = norm * sc;
    for (int m = 1; m <= 18; m++) {
        bound *= ns / m;
        if (bound < 0.5e-18) break;
        small_mul(n, 1.0 / m, S, T, U);
        memcpy(T, U, nn * sizeof *T);
        for (size_t k = 0; k < nn; k++) {
            E[k] += T[k];
            P[k] += T[k] / (m + 1);
        }
    }
    for (int k = 0; k < s; k++) {
        for (int i = 0; i < n; i++) /* E + I, then P (E + I) / 2 and E^2 */
            E[(size_t)i * n + i] += 1.0;
        small_mul(n, 0.5, P, E, U);
        memcpy(P, U, nn * sizeof *P);
        for (int i = 0; i < n; i++)
            E[(size_t)i * n + i] -= 1.0;
        small_mul(n, 1.0, E, E, U);
        memcpy(E, U, nn * sizeof *E);
    }
}

/* Same vector (indices and values) for the terms' u or w. */
static int same_vec(int na, const int *ia, const double *va, int nb, const int *ib,
                    const double *vb)
{
    return na == nb && !memcmp(ia, ib, (size_t)na * sizeof *ia) &&
           !memcmp(va, vb, (size_t)na * sizeof *va);
}

/* The blocks of E(s) = exp(s Lambda) (ec, es: a pair's e^(s re) (cos, sin)(s im) at its
 * first row, a real eigenvalue's e^(s re) in ec) and of E(-s), its inverse (ic, is). */
static void exp_blocks(int n, const double *lre, const double *lim, double s, double *ec,
                       double *es, double *ic, double *is)
{
    for (int i = 0; i < n; i++) {
        const double e = exp(lre[i] * s);
        if (lim[i] > 0.0 && i + 1 < n) {
            const double c = cos(lim[i] * s), sn = sin(lim[i] * s);
            ec[i] = e * c;
            es[i] = e * sn;
            ic[i] = c / e;
            is[i] = -sn / e;
            i++;
        } else {
            ec[i] = e;
            ic[i] = 1.0 / e;
        }
    }
}

/* M's rows <- E M (n x ncol, column-major) with E's blocks [c, s; -s, c] from exp_blocks;
 * sgn -1 applies E^T instead (a row times E, for rows stored as columns) */
static void rotate(int n, int ncol, const double *lim, const double *ec, const double *es,
                   double sgn, double *M)
{
    for (int j = 0; j < ncol; j++) {
        double *p = M + (size_t)j * n;
        for (int i = 0; i < n; i++) {
            if (lim[i] > 0.0 && i + 1 < n) {
                const double a = p[i], b = p[i + 1], s = sgn * es[i];
                p[i] = ec[i] * a + s * b;
                p[i + 1] = -s * a + ec[i] * b;
                i++;
            } else {
                p[i] *= ec[i];
            }
        }
    }
}

/* E(s + h)'s blocks from E(s)'s and E(h)'s (hc, hs): a pair's e^(lambda s) times
 * e^(lambda h), a real eigenvalue's product; so do the inverse blocks with E(-h)'s. For a
 * run of equal steps, in place of exp_blocks' exponentials, sines and cosines (a third of
 * a vector pass's instructions, callgrind). */
static void exp_advance(int n, const double *lim, double *ec, double *es, const double *hc,
                        const double *hs)
{
    for (int i = 0; i < n; i++) {
        if (lim[i] > 0.0 && i + 1 < n) {
            const double a = ec[i], b = es[i];
            ec[i] = a * hc[i] - b * hs[i];
            es[i] = a * hs[i] + b * hc[i];
            i++;
        } else {
            ec[i] *= hc[i];
        }
    }
}

/* The blocks of E(s) (8 n: ec, es, ic, is, then E(h)'s and E(-h)'s) for a sequence of
 * arguments s: advanced from the last one when s is the last plus h (then exact to the
 * rounding of a few hundred products: refreshed every 256), else from exp_blocks. */
typedef struct exp_run {
    double *b; /* 8 n */
    double last, h;
    int have, cnt;
} exp_run;

static const double *exp_at(exp_run *e, int n, const double *lre, const double *lim, double s,
                            double h)
{
    double *ec = e->b, *es = ec + n, *ic = es + n, *is = ic + n, *hc = is + n, *hs = hc + n,
           *hic = hs + n, *his = hic + n;
    /* equal steps differ by the rounding of their ends (1e-16 relative) */
    const int same = e->have && fabs(h - e->h) <= 1e-12 * fabs(h);
    if (same && e->cnt < 256 && fabs(s - (e->last + e->h)) <= 1e-9 * fabs(h)) {
        exp_advance(n, lim, ec, es, hc, hs);
        exp_advance(n, lim, ic, is, hic, his);
        e->cnt++;
    } else {
        exp_blocks(n, lre, lim, s, ec, es, ic, is);
        if (!same) {
            exp_blocks(n, lre, lim, h, hc, hs, hic, his);
            e->h = h;
        }
        e->have = 1;
        e->cnt = 0;
    }
    e->last = s;
    return e->b;
}

/* qsort: complex pairs (re, im) by decreasing modulus, then decreasing imaginary part */
static int by_modulus(const void *pa, const void *pb)
{
    const double *a = pa, *b = pb, ma = hypot(a[0], a[1]), mb = hypot(b[0], b[1]);
    if (ma != mb) return ma < mb ? 1 : -1;
    return a[1] < b[1] ? 1 : a[1] > b[1] ? -1 : 0;
}

/* Descending order (the moduli of two step counts' multipliers, compared by rank). */
static int by_value_desc(const void *pa, const void *pb)
{
    const double a = *(const double *)pa, b = *(const double *)pb;
    return (a < b) - (a > b);
}

/* Two step counts' multipliers agree where stability is decided: each modulus (sorted, by
 * rank) within 1 % of its distance from the unit circle and at least within 1e-7 (a tenth
 * of the stability margin 1e-6), and the same count outside the circle. A fast mode's
 * multiplier far inside converges at fourth order from further away (on the [JMSTHelical]
 * model at 2500 rpm, 0.5515: 1.7e-4 between 512 and 1024 steps) but decides nothing; a
 * step too long for the laws' variation gives spurious ones (0 deg, 400 rpm, 256 steps:
 * 1.8e5), which differ. */
static int steps_agree(const double *a, const double *b, int n)
{
    int out_a = 0, out_b = 0;
    for (int i = 0; i < n; i++) {
        const double tol = fmax(1e-7, 0.01 * fabs(1.0 - a[i]));
        if (!(fabs(a[i] - b[i]) <= tol)) return 0;
        out_a += a[i] > 1.0 + 1e-6;
        out_b += b[i] > 1.0 + 1e-6;
    }
    return out_a == out_b;
}

/* The modes of (sym K, M) kept between points (hb's fmodes): every point of a curve
 * whose structure does not change with speed has the same K and M, and their dense
 * eigensolution (about 10 nf^3 flops: 0.16 G instructions of the 0.9 G a point's
 * multipliers took on seed 002, callgrind) is the same. */
struct gd_floquet_modes {
    int nf;
    double *K, *M; /* the matrices they are the modes of (sym K, M), dense */
    double *Phi, *lam;
};

void gd_floquet_modes_free(struct gd_floquet_modes *m)
{
    if (!m) return;
    free(m->K);
    free(m->M);
    free(m->Phi);
    free(m->lam);
    free(m);
}

/* Phi (in: sym K, dense; out: the M-orthonormal modes) and lam, from h's kept modes when
 * K and M are those they were made of, else by LAPACK dsygvd (then kept). 0 ok, > 0
 * dsygvd's info, -1 out of memory. */
static int modes_of(hb *h, int nf, double *Phi, const double *Mm, double *lam)
{
    const size_t ff = (size_t)nf * nf;
    struct gd_floquet_modes *m = h->fmodes;
    if (m && m->nf == nf && !memcmp(m->K, Phi, ff * sizeof *Phi) &&
        !memcmp(m->M, Mm, ff * sizeof *Mm)) {
        memcpy(Phi, m->Phi, ff * sizeof *Phi);
        memcpy(lam, m->lam, (size_t)nf * sizeof *lam);
        return 0;
    }
    gd_floquet_modes_free(m);
    h->fmodes = m = calloc(1, sizeof *m);
    h->fmodes_free = gd_floquet_modes_free;
    double *Mc = malloc(ff * sizeof *Mc);
    if (m) {
        m->nf = nf;
        m->K = malloc(ff * sizeof *m->K);
        m->M = malloc(ff * sizeof *m->M);
        m->Phi = malloc(ff * sizeof *m->Phi);
        m->lam = malloc((size_t)nf * sizeof *m->lam);
    }
    if (!Mc || !m || !m->K || !m->M || !m->Phi || !m->lam) {
        free(Mc);
        gd_floquet_modes_free(m);
        h->fmodes = NULL;
        return -1;
    }
    memcpy(m->K, Phi, ff * sizeof *Phi);
    memcpy(m->M, Mm, ff * sizeof *Mm);
    memcpy(Mc, Mm, ff * sizeof *Mc);
    int info = LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, 'V', 'U', nf, Phi, nf, Mc, nf, lam);
    free(Mc);
    if (info) {
        gd_floquet_modes_free(m);
        h->fmodes = NULL;
        return info;
    }
    memcpy(m->Phi, Phi, ff * sizeof *Phi);
    memcpy(m->lam, lam, (size_t)nf * sizeof *lam);
    return 0;
}

/* The reduced problem of one point, built in the stages the method's description names
 * (the modes, the residual flexibility, the balanced A0 and its eigenvectors, the inputs
 * in that basis), then the step-count loop. Every array is owned (red_free). */
typedef struct red {
    hb *h;
    gd_transient *tr;
    double om;
    const double *X;
    const gd_tr_term *term;
    int nf, nt;
    /* red_modes: dense K, M, D (freed once reduced), the modes Phi and eigenvalues lam of
     * (sym K, M), nk kept below the cut-off; the term groups by equal u (tg: each term's,
     * grep: each group's first term, ng groups) */
    double *Km, *Mm, *Dm, *Phi, *lam;
    int *tg, *grep;
    int nk, ng;
    /* the terms with the same u and the same w act as one (their scalars add: mrep[c] the
     * first of class c, mcls[t] each term's, nm classes); red_scalars folds them */
    int *mrep, *mcls, *mtg;
    int nm;
    /* red_residual: nres residual vectors (columns of C, nd = nf - nk entries each) */
    double *C;
    int nd, nres;
    /* red_reduce: the basis V (nf x r), the balanced A0 (n2 x n2, n2 = 2 r), the reduced
     * force directions ur and input rows wr, the balancing cs, the discarded modes'
     * damping dd; XR, XL and tmp are work (red_eigenbasis: XR the eigenvectors, XL their
     * inverse) */
    int r, n2;
    size_t rr;
    double *V, *A0, *XR, *XL, *lre, *lim, *ur, *wr, *cs, *dd, *tmp;
    int *ipiv;
    /* red_inputs: P, the input rows At, Bt in the eigenvector basis and their products;
     * the propagation's work */
    double *Pt, *At, *Bt, *AP, *BP, *Psi, *mod, *prev, *Rk, *Y, *Z, *sqv, *yv;
    int *sup;
    /* one step count: its steps tb (nsub), the terms' scalars at their Gauss points, the
     * transform; the discarded modes' estimates est (nest) */
    double *tb, *scal, *hc, *smp, *est, *small;
    fftw_plan plan;
    int nsub, nest;
    /* the forced orbit (gd_hb_orbit_reduced): Psi has ncol columns (0: n2, the
     * monodromy); aug 1: its last column carries the constant coordinate 1 of the
     * augmented state, whose forcing is the laws' force about the static state, f(t, x_s)
     * - f0 = sum_g u_g c_g(t): red_scalars fills fc (c at every Gauss point, ng each) from
     * f0 and the groups' least-squares rows upi (ng x nf) when they are set; orb, when
     * set, is called at every step's end with Psi (one column) in the frame of the
     * anchor ta */
    int ncol, aug;
    double *fc, *f0, *upi, *fw;
    int *gfirst; /* ng: the first class row of each group */
    void (*orb)(struct red *R, int j, double ta);
    void *orb_user;
} red;

static void red_free(red *R)
{
    if (R->plan) fftw_destroy_plan(R->plan);
    fftw_free(R->hc);
    free(R->smp);
    free(R->Km);
    free(R->Mm);
    free(R->Dm);
    free(R->Phi);
    free(R->lam);
    free(R->tg);
    free(R->grep);
    free(R->mrep);
    free(R->mcls);
    free(R->mtg);
    free(R->V);
    free(R->C);
    free(R->A0);
    free(R->XR);
    free(R->XL);
    free(R->lre);
    free(R->lim);
    free(R->Pt);
    free(R->At);
    free(R->Bt);
    free(R->AP);
    free(R->BP);
    free(R->Psi);
    free(R->Rk);
    free(R->Y);
    free(R->Z);
    free(R->sqv);
    free(R->yv);
    free(R->ur);
    free(R->wr);
    free(R->tmp);
    free(R->tb);
    free(R->ipiv);
    free(R->sup);
    free(R->dd);
    free(R->est);
    free(R->small);
    free(R->cs);
    free(R->scal);
    free(R->mod);
    free(R->prev);
    free(R->fc);
    free(R->f0);
    free(R->upi);
    free(R->fw);
    free(R->gfirst);
}

/* The modes of (sym K, M) below the cut-off wcut (rad/s) and the term groups. 0 ok. */
static int red_modes(red *R, double wcut, char *msg)
{
    const int nf = R->nf, nt = R->nt;
    const gd_tr_term *term = R->term;
    const size_t ff = (size_t)nf * nf;
    double *Km = R->Km = malloc(ff * sizeof *Km), *Mm = R->Mm = malloc(ff * sizeof *Mm),
           *Dm = R->Dm = malloc(ff * sizeof *Dm), *Phi = R->Phi = malloc(ff * sizeof *Phi),
           *lam = R->lam = malloc((size_t)nf * sizeof *lam);
    int *tg = R->tg = malloc((size_t)(nt + 1) * sizeof *tg),
        *grep = R->grep = malloc((size_t)(nt + 1) * sizeof *grep);
    if (!Km || !Mm || !Dm || !Phi || !lam || !tg || !grep) return 1;
    gd_csc M, D, K;
    gd_transient_matrices(R->tr, &M, &D, &K);
    dense_of(&K, nf, Km);
    dense_of(&M, nf, Mm);
    dense_of(&D, nf, Dm);
    /* the modes of the symmetric part of K (a bearing's cross-coupling or a follower
     * stiffness only enters through the projection below) */
    for (int j = 0; j < nf; j++)
        for (int i = 0; i < nf; i++)
            Phi[(size_t)j * nf + i] = 0.5 * (Km[(size_t)j * nf + i] + Km[(size_t)i * nf + j]);
    {
        int info = modes_of(R->h, nf, Phi, Mm, lam);
        if (info < 0) return 1;
        if (info) {
            snprintf(msg, 160, "stability not computed: the modes of (K, M) failed (dsygvd %d)",
                     info);
            return 1;
        }
    }
    int nk = 0;
    while (nk < nf && lam[nk] < wcut * wcut)
        nk++;
    R->nk = nk;
    /* the term groups by equal u (the columns of P) */
    int ng = 0;
    for (int t = 0; t < nt; t++) {
        int g = 0;
        for (; g < ng; g++)
            if (same_vec(term[t].nu, term[t].u_idx, term[t].u, term[grep[g]].nu,
                         term[grep[g]].u_idx, term[grep[g]].u))
                break;
        if (g == ng) grep[ng++] = t;
        tg[t] = g;
    }
    R->ng = ng;
    /* the classes of equal (u, w) */
    int *mrep = R->mrep = malloc((size_t)(nt + 1) * sizeof *mrep),
        *mcls = R->mcls = malloc((size_t)(nt + 1) * sizeof *mcls),
        *mtg = R->mtg = malloc((size_t)(nt + 1) * sizeof *mtg);
    if (!mrep || !mcls || !mtg) return 1;
    int nm = 0;
    for (int t = 0; t < nt; t++) {
        int c = 0;
        for (; c < nm; c++)
            if (tg[mrep[c]] == tg[t] &&
                same_vec(term[t].nw, term[t].w_idx, term[t].w, term[mrep[c]].nw,
                         term[mrep[c]].w_idx, term[mrep[c]].w))
                break;
        if (c == nm) {
            mtg[nm] = tg[t];
            mrep[nm++] = t;
        }
        mcls[t] = c;
    }
    R->nm = nm;
    return 0;
}

/* The residual flexibility of the discarded modes along each distinct u and w, in the
 * discarded modes' coordinates (M-orthonormal there: Gram-Schmidt in plain dot
 * products), dependent ones dropped. 0 ok. */
static int red_residual(red *R)
{
    const int nf = R->nf, nt = R->nt, nk = R->nk;
    const gd_tr_term *term = R->term;
    const int *tg = R->tg;
    const double *Phi = R->Phi, *lam = R->lam;
    const int nord = GD_FLOQUET_RESID_ORDER;
    const int nd = R->nd = nf - nk, ncand = 2 * nt * nord;
    int nres = 0;
    if (nd > 0 && ncand > 0) {
        double *C = R->C = malloc((size_t)nd * ncand * sizeof *C);
        R->tmp = malloc((size_t)nf * sizeof *R->tmp);
        if (!C || !R->tmp) return 1;
        for (int c = 0; c < ncand; c++) {
            const int ord = c / (2 * nt), cc = c % (2 * nt);
            const gd_tr_term *tm = &term[cc % nt];
            const int isw = cc >= nt;
            int dup = 0;
            for (int p = 0; p < cc % nt && !dup; p++)
                dup = isw ? same_vec(tm->nw, tm->w_idx, tm->w, term[p].nw, term[p].w_idx, term[p].w)
                          : tg[p] == tg[cc % nt];
            if (dup) continue;
            double *cv = C + (size_t)nres * nd, n0 = 0.0;
            for (int j = 0; j < nd; j++) {
                const double *ph = Phi + (size_t)(nk + j) * nf;
                double s = 0.0;
                if (isw)
                    for (int b = 0; b < tm->nw; b++)
                        s += ph[tm->w_idx[b]] * tm->w[b];
                else
                    for (int a = 0; a < tm->nu; a++)
                        s += ph[tm->u_idx[a]] * tm->u[a];
                cv[j] = lam[nk + j] > 0 ? s / pow(lam[nk + j], ord + 1) : 0.0;
                n0 += cv[j] * cv[j];
            }
            n0 = sqrt(n0);
            for (int pass = 0; pass < 2; pass++)
                for (int p = 0; p < nres; p++) {
                    const double *cp = C + (size_t)p * nd;
                    double d = cblas_ddot(nd, cp, 1, cv, 1);
                    cblas_daxpy(nd, -d, cp, 1, cv, 1);
                }
            double n1 = cblas_dnrm2(nd, cv, 1);
            if (!(n1 > 1e-8 * n0) || n0 == 0.0) continue;
            cblas_dscal(nd, 1.0 / n1, cv, 1);
            nres++;
        }
    }
    R->nres = nres;
    return 0;
}

/* The basis V = [kept modes, residual vectors] (every mode where those would not be
 * fewer), the reduced Kr, Dr, Mr, the balanced A0, the reduced force directions and input
 * rows, and the discarded modes' damping; K, M and D are freed. 0 ok. */
static int red_reduce(red *R, char *msg)
{
    const int nf = R->nf, nt = R->nt, nk = R->nk, nd = R->nd, nres = R->nres, ng = R->ng;
    const gd_tr_term *term = R->term;
    const int *grep = R->grep;
    const double *Phi = R->Phi, *C = R->C, *Km = R->Km, *Mm = R->Mm, *Dm = R->Dm;
    const size_t ff = (size_t)nf * nf;
    int r = nk + nres;
    if (r >= nf || nres >= nd) r = nf; /* every mode */
    if (r == 0) {
        snprintf(msg, 160, "stability not computed: the reduced basis is empty");
        return 1;
    }
    const int n2 = 2 * r;
    const size_t rr = (size_t)n2 * n2;
    R->r = r;
    R->n2 = n2;
    R->rr = rr;
    double *V = R->V = malloc((size_t)nf * r * sizeof *V);
    double *A0 = R->A0 = calloc(rr, sizeof *A0);
    double *XR = R->XR = malloc(rr * sizeof *XR);
    double *XL = R->XL = malloc(rr * sizeof *XL);
    R->lre = malloc((size_t)n2 * sizeof *R->lre);
    R->lim = malloc((size_t)n2 * sizeof *R->lim);
    int *ipiv = R->ipiv = malloc((size_t)n2 * sizeof *ipiv);
    double *ur = R->ur = malloc(((size_t)ng * r + 1) * sizeof *ur);
    double *cs = R->cs = malloc((size_t)r * sizeof *cs);
    double *wr = R->wr = malloc(((size_t)nt * r + 1) * sizeof *wr);
    free(R->tmp);
    double *tmp = R->tmp = malloc(((size_t)nf * r + rr) * sizeof *tmp);
    if (!V || !A0 || !XR || !XL || !R->lre || !R->lim || !ipiv || !ur || !wr || !tmp || !cs)
        return 1;
    if (r == nf) {
        memcpy(V, Phi, ff * sizeof *V);
    } else {
        memcpy(V, Phi, (size_t)nf * nk * sizeof *V);
        if (nres)
            cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, nres, nd, 1.0,
                        Phi + (size_t)nk * nf, nf, C, nd, 0.0, V + (size_t)nk * nf, nf);
    }
    /* Kr, Dr, Mr (r x r) into A0's blocks: A0 = [0, I; -Mr^-1 Kr, -Mr^-1 Dr] */
    {
        double *KV = tmp, *Mr = tmp + (size_t)nf * r, *Kr = XR, *Dr = XL;
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, r, nf, 1.0, Mm, nf, V, nf, 0.0,
                    KV, nf);
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, r, r, nf, 1.0, V, nf, KV, nf, 0.0, Mr,
                    r);
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, r, nf, 1.0, Km, nf, V, nf, 0.0,
                    KV, nf);
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, r, r, nf, 1.0, V, nf, KV, nf, 0.0, Kr,
                    r);
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, r, nf, 1.0, Dm, nf, V, nf, 0.0,
                    KV, nf);
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, r, r, nf, 1.0, V, nf, KV, nf, 0.0,
                    Kr + (size_t)r * r, r);
        memcpy(Dr, Kr + (size_t)r * r, (size_t)r * r * sizeof *Dr);
        /* the reduced force directions V^T u_g and input rows V^T w_t */
        memset(ur, 0, (size_t)ng * r * sizeof *ur);
        for (int g = 0; g < ng; g++) {
            const gd_tr_term *tm = &term[grep[g]];
            for (int j = 0; j < r; j++) {
                double s = 0.0;
                for (int a = 0; a < tm->nu; a++)
                    s += V[(size_t)j * nf + tm->u_idx[a]] * tm->u[a];
                ur[(size_t)g * r + j] = s;
            }
        }
        for (int t = 0; t < nt; t++)
            for (int j = 0; j < r; j++) {
                double s = 0.0;
                for (int b = 0; b < term[t].nw; b++)
                    s += V[(size_t)j * nf + term[t].w_idx[b]] * term[t].w[b];
                wr[(size_t)t * r + j] = s;
            }
        /* Mr^-1 [Kr, Dr, U] (Mr is I to rounding: M-orthonormal basis) */
        double *rhs = malloc(((size_t)r * (2 * r + ng) + 1) * sizeof *rhs);
        if (!rhs) return 1;
        memcpy(rhs, Kr, (size_t)r * r * sizeof *rhs);
        memcpy(rhs + (size_t)r * r, Dr, (size_t)r * r * sizeof *rhs);
        memcpy(rhs + 2 * (size_t)r * r, ur, (size_t)ng * r * sizeof *rhs);
        int info = LAPACKE_dgesv(LAPACK_COL_MAJOR, r, 2 * r + ng, Mr, r, ipiv, rhs, r);
        if (info) {
            free(rhs);
            return 1;
        }
        memcpy(ur, rhs + 2 * (size_t)r * r, (size_t)ng * r * sizeof *ur);
        /* balanced state [c_j x_j; x_j'], c_j = sqrt(Kr_jj) (the kept mode's frequency):
         * A0 = [0, C; -Kr C^-1, -Dr]. Unbalanced, |A0| is w_max^2 and dgeev's eigenvalues
         * carry absolute errors of eps w_max^2 (4e-4 1/s on the [JMSTHelical] model, a
         * uniform 6e-6 on every |mu|: measured); balanced, eps w_max */
        double kmax = 0.0;
        for (int j = 0; j < r; j++)
            kmax = fmax(kmax, fabs(rhs[(size_t)j * r + j]));
        for (int j = 0; j < r; j++)
            cs[j] = fmax(sqrt(fabs(rhs[(size_t)j * r + j])), 1e-6 * sqrt(kmax));
        for (int j = 0; j < r; j++) {
            A0[(size_t)(r + j) * n2 + j] = cs[j];
            for (int i = 0; i < r; i++) {
                A0[(size_t)j * n2 + r + i] = -rhs[(size_t)j * r + i] / cs[j];
                A0[(size_t)(r + j) * n2 + r + i] = -rhs[(size_t)r * r + (size_t)j * r + i];
            }
        }
        free(rhs);
    }
    /* the discarded modes' damping phi_j^T D phi_j (their multipliers' estimate below) */
    if (r < nf) {
        double *dd = R->dd = malloc((size_t)nd * sizeof *dd);
        double *DP = malloc((size_t)nf * nd * sizeof *DP);
        if (!dd || !DP) {
            free(DP);
            return 1;
        }
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, nd, nf, 1.0, Dm, nf,
                    Phi + (size_t)nk * nf, nf, 0.0, DP, nf);
        for (int j = 0; j < nd; j++)
            dd[j] = cblas_ddot(nf, Phi + (size_t)(nk + j) * nf, 1, DP + (size_t)j * nf, 1);
        free(DP);
    }
    free(R->Km);
    free(R->Dm);
    free(R->Mm);
    R->Km = R->Dm = R->Mm = NULL;
    return 0;
}

/* A0 = XR Lambda XR^-1 (real blocks for the complex pairs), XL = XR^-1; 5 (with msg)
 * where A0 has no well-conditioned eigenvector basis, 1 another failure, 0 ok. */
static int red_eigenbasis(red *R, char *msg)
{
    const int nf = R->nf, r = R->r, n2 = R->n2;
    const size_t rr = R->rr;
    double *XR = R->XR, *XL = R->XL, *tmp = R->tmp;
    int *ipiv = R->ipiv;
    const double *lam = R->lam;
    double dummy[1];
    memcpy(XL, R->A0, rr * sizeof *XL);
    int info =
        LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', n2, XL, n2, R->lre, R->lim, dummy, 1, XR, n2);
    if (info) return 1;
    /* a defective eigenvalue (a free rotation: the Jordan block at 0) or a near one
     * leaves no usable eigenvector basis: judged on XR in the balanced state
     * [c x; x'] (c the largest kept frequency, so a mode's eigenvector is [c x; s x]
     * with |s| <= c), each column of unit length: a free rotation's pair s ~ 0 has two
     * parallel columns */
    double rcond = 0.0;
    const double cb = 1.0; /* the state is balanced already */
    double *E = tmp;       /* nf r + rr >= rr */
    for (int j = 0; j < n2; j++) {
        double *e = E + (size_t)j * n2, nrm = 0.0;
        for (int i = 0; i < n2; i++) {
            e[i] = XR[(size_t)j * n2 + i] * (i < r ? cb : 1.0);
            nrm += e[i] * e[i];
        }
        nrm = nrm > 0 ? 1.0 / sqrt(nrm) : 1.0;
        for (int i = 0; i < n2; i++)
            e[i] *= nrm;
    }
    double anorm = LAPACKE_dlange(LAPACK_COL_MAJOR, '1', n2, n2, E, n2);
    info = LAPACKE_dgetrf(LAPACK_COL_MAJOR, n2, n2, E, n2, ipiv);
    if (!info) info = LAPACKE_dgecon(LAPACK_COL_MAJOR, '1', n2, E, n2, anorm, &rcond);
    memcpy(XL, XR, rr * sizeof *XL);
    if (!info) info = LAPACKE_dgetrf(LAPACK_COL_MAJOR, n2, n2, XL, n2, ipiv);
    /* a free rotation shows plainly in the modes of (K, M): a zero eigenvalue */
    const int free_body = lam[0] <= 1e-12 * fabs(lam[nf - 1]);
    if (info || free_body || !(rcond > GD_FLOQUET_RCOND)) {
        snprintf(msg, 160,
                 "the reduced constant part has no well-conditioned eigenvector basis "
                 "(%s, reciprocal condition %.1e)",
                 free_body ? "a free rotation" : "near-defective modes", rcond);
        return 5;
    }
    if (LAPACKE_dgetri(LAPACK_COL_MAJOR, n2, XL, n2, ipiv)) return 1;
    return 0;
}

/* P (n2 x ng) = XR^-1 [0; ur_g]; At, Bt (nt x n2) rows [wr_t, 0] XR and [0, wr_t] XR;
 * AP, BP (nt x ng) = At P, Bt P; and the propagation's work. 0 ok. */
static int red_inputs(red *R)
{
    const int nf = R->nf, nt = R->nt, ng = R->ng, r = R->r, n2 = R->n2;
    const size_t rr = R->rr;
    double *Pt = R->Pt = malloc(((size_t)n2 * ng + 1) * sizeof *Pt);
    double *At = R->At = malloc(((size_t)nt * n2 + 1) * sizeof *At);
    double *Bt = R->Bt = malloc(((size_t)nt * n2 + 1) * sizeof *Bt);
    double *AP = R->AP = malloc(((size_t)nt * ng + 1) * sizeof *AP);
    double *BP = R->BP = malloc(((size_t)nt * ng + 1) * sizeof *BP);
    R->Psi = calloc(rr, sizeof *R->Psi);
    R->mod = malloc((size_t)n2 * sizeof *R->mod);
    R->prev = malloc((size_t)n2 * sizeof *R->prev);
    double *Rk = R->Rk = malloc((2 * (size_t)nt * n2 + 1) * sizeof *Rk);
    R->Y = malloc((2 * (size_t)nt * (n2 + 1) + 1) * sizeof *R->Y);
    R->Z = malloc((6 * (size_t)(ng + 1) * (n2 + 1) + 1) * sizeof *R->Z);
    R->sqv = malloc((2 * (size_t)nt + 2) * sizeof *R->sqv);
    R->yv = calloc(2 * (size_t)nf, sizeof *R->yv);
    R->sup = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *R->sup);
    if (!Pt || !At || !Bt || !AP || !BP || !R->Psi || !Rk || !R->Y || !R->Z || !R->sqv || !R->yv ||
        !R->sup || !R->mod || !R->prev)
        return 1;
    const double *XR = R->XR, *XL = R->XL, *ur = R->ur, *wr = R->wr, *cs = R->cs;
    if (ng)
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n2, ng, r, 1.0, XL + (size_t)r * n2,
                    n2, ur, r, 0.0, Pt, n2);
    /* At, Bt row-major (nt rows of n2): At[t][j] = sum_i wr_t[i] XR[i, j] */
    if (nt) {
        /* the laws read x = C^-1 x~ (the balanced displacements); Bt the velocities as they
         * are */
        for (int t = 0; t < nt; t++)
            for (int j = 0; j < r; j++)
                Rk[(size_t)t * r + j] = wr[(size_t)t * r + j] / cs[j];
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, n2, nt, r, 1.0, XR, n2, Rk, r, 0.0, At,
                    n2);
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, n2, nt, r, 1.0, XR + r, n2, wr, r, 0.0,
                    Bt, n2);
        /* AP[t + g nt] = At_t . P_g */
        if (ng) {
            cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, nt, ng, n2, 1.0, At, n2, Pt, n2,
                        0.0, AP, nt);
            cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, nt, ng, n2, 1.0, Bt, n2, Pt, n2,
                        0.0, BP, nt);
        }
    }
    return 0;
}

/* The Magnus steps of S per period (split at contact changes) and the term scalars at
 * their two Gauss points (sq1, sv1, sq2, sv2), the orbit there from inverse FFTs of the
 * input DOFs' coefficients. 0 ok. */
static int red_scalars(red *R, int S, const gd_tr_record *bl, int nbl)
{
    const int nf = R->nf, nt = R->nt;
    const gd_tr_term *term = R->term;
    const hb *h = R->h;
    const double om = R->om, *X = R->X;
    int *sup = R->sup;
    double *yv = R->yv, *sqv = R->sqv;
    free(R->tb);
    R->tb = NULL;
    free(R->scal);
    R->scal = NULL;
    if (R->plan) fftw_destroy_plan(R->plan);
    R->plan = NULL;
    fftw_free(R->hc);
    R->hc = NULL;
    free(R->smp);
    R->smp = NULL;
    /* the steps and the term scalars at their two Gauss points (sq1, sv1, sq2, sv2) */
    if (gd_hb_magnus_steps(h, R->tr, om, X, S, bl, nbl, &R->tb, &R->nsub)) return 1;
    const double *tb = R->tb;
    const int nsub = R->nsub;
    const double gp[2] = {0.5 - sqrt(3.0) / 6.0, 0.5 + sqrt(3.0) / 6.0};
    double *scal = R->scal = malloc(((size_t)nsub * 4 * nt + 1) * sizeof *scal);
    if (!scal) return 1;
    double *fw = NULL;
    if (R->upi) {
        free(R->fc);
        R->fc = malloc(((size_t)nsub * 2 * R->ng + 1) * sizeof *R->fc);
        fw = R->fw;
        if (!R->fc) return 1;
    }
    /* the input support: the DOFs the terms read (their w) */
    unsigned char *mark = calloc((size_t)nf + 1, 1);
    int ns = 0;
    if (!mark) return 1;
    for (int t = 0; t < nt; t++)
        for (int b = 0; b < term[t].nw; b++)
            mark[term[t].w_idx[b]] = 1;
    for (int i = 0; i < nf; i++)
        if (mark[i]) sup[ns++] = i;
    free(mark);
    /* the transform is long enough for every harmonic of the orbit (Nt >= 2 H + 2,
     * a multiple of the steps): the steps' own count may be below 2 H (their
     * Gauss points then read every stride-th sample), and the law's coefficients
     * must still see every harmonic the orbit has */
    const int Ns = S, H = h->H;
    int Nt = Ns;
    while (Nt < 2 * H + 2)
        Nt *= 2;
    const int stride = Nt / Ns;
    double *hc = R->hc = fftw_malloc(2 * (size_t)Nt * sizeof *hc);
    double *smp = R->smp = malloc(((size_t)Ns * 4 * ns + 1) * sizeof *smp);
    if (!hc || !smp) return 1;
    R->plan = fftw_plan_r2r_1d(Nt, hc, hc + Nt, FFTW_HC2R, FFTW_ESTIMATE);
    if (!R->plan) return 1;
    /* q and q' of each support DOF at tau_j = (j + g) 2 pi / Ns for either Gauss point
     * g: the coefficients shifted by g steps, one half-complex inverse transform each
     * (FFTW's HC2R: x_j = hc_0 + 2 sum_k (Re_k cos - Im_k sin)) */
    const int Hm = H < (Nt - 1) / 2 ? H : (Nt - 1) / 2;
    /* cos and sin of k dl for the two Gauss points (the same for every DOF) */
    double *cs2 = malloc((4 * (size_t)Hm + 4) * sizeof *cs2);
    if (!cs2) return 1;
    for (int g = 0; g < 2; g++)
        for (int k = 1; k <= Hm; k++) {
            const double dl = gp[g] * TWO_PI / Ns;
            cs2[(size_t)g * 2 * (Hm + 1) + 2 * k] = cos(k * dl);
            cs2[(size_t)g * 2 * (Hm + 1) + 2 * k + 1] = sin(k * dl);
        }
    for (int m = 0; m < ns; m++)
        for (int pd = 0; pd < 4; pd++) {
            const int deriv = pd & 1;
            const double *csg = cs2 + (size_t)(pd >> 1) * 2 * (Hm + 1);
            const int i = sup[m];
            memset(hc, 0, (size_t)Nt * sizeof *hc);
            if (!deriv) hc[0] = X[i];
            for (int k = 1; k <= Hm; k++) {
                const double xc = X[(size_t)(2 * k - 1) * nf + i], xs = X[(size_t)2 * k * nf + i],
                             c = csg[2 * k], s = csg[2 * k + 1];
                /* x(tau + dl) = a cos(k tau) + b sin(k tau) */
                double a = xc * c + xs * s, b = xs * c - xc * s;
                if (deriv) { /* q' = k w (b cos - a sin) */
                    double a2 = k * om * b, b2 = -k * om * a;
                    a = a2;
                    b = b2;
                }
                hc[k] = 0.5 * a;
                hc[Nt - k] = -0.5 * b;
            }
            fftw_execute(R->plan);
            for (int j = 0; j < Ns; j++)
                smp[((size_t)j * 4 + pd) * ns + m] = hc[Nt + (size_t)j * stride];
        }
    free(cs2);
    double *yfull = NULL;
    for (int j = 0; j < nsub; j++) {
        const double a = tb[j], b = tb[j + 1];
        const long k = lround(a / TWO_PI * Ns);
        const int uniform =
            fabs(a - TWO_PI * k / Ns) < 1e-12 && fabs(b - TWO_PI * (k + 1) / Ns) < 1e-12 && k < Ns;
        for (int g = 0; g < 2; g++) {
            const double tau = a + gp[g] * (b - a);
            double *sj = scal + (size_t)j * 4 * nt + (size_t)g * 2 * nt;
            if (uniform) {
                const double *qs = smp + ((size_t)k * 4 + 2 * g) * ns, *vs = qs + ns;
                for (int m = 0; m < ns; m++) {
                    yv[sup[m]] = qs[m];
                    yv[nf + sup[m]] = vs[m];
                }
                gd_transient_local(R->tr, tau / om, yv, fw, sqv, sqv + nt + 1);
            } else { /* a step split at a contact change: a direct sum */
                if (!yfull) yfull = malloc(2 * (size_t)nf * sizeof *yfull);
                if (!yfull) return 1;
                gd_hb_eval(h, om, X, tau, yfull, yfull + nf);
                gd_transient_local(R->tr, tau / om, yfull, fw, sqv, sqv + nt + 1);
            }
            if (fw) { /* the groups' coefficients of f - f0 (least squares on the u_g) */
                double *cg = R->fc + ((size_t)j * 2 + g) * R->ng;
                for (int gr = 0; gr < R->ng; gr++) {
                    double acc = 0.0;
                    for (int i = 0; i < nf; i++)
                        acc += R->upi[(size_t)i * R->ng + gr] * (fw[i] - R->f0[i]);
                    cg[gr] = acc;
                }
            }
            memcpy(sj, sqv, (size_t)nt * sizeof *sj);
            memcpy(sj + nt, sqv + nt + 1, (size_t)nt * sizeof *sj);
            /* a term of an earlier one's class adds to that one's scalars */
            for (int t = 0; t < nt; t++) {
                const int rt = R->mrep[R->mcls[t]];
                if (rt == t) continue;
                sj[rt] += sj[t];
                sj[nt + rt] += sj[nt + t];
                sj[t] = sj[nt + t] = 0.0;
            }
        }
    }
    free(yfull);
    return 0;
}

/* The discarded modes (r < nf) are not in the propagated basis: their multipliers are
 * estimated as the constant-coefficient ones of each mode alone, exp(s T) with
 * s^2 + d s + k = 0, k and d the mode's stiffness and damping with the laws' period
 * means added (first order in the coupling; those modes lie far above every
 * excitation, so the laws drive them quasi-statically, which the residual vectors
 * carry). The largest ones fill the multipliers after the reduced ones. 0 ok. */
static int red_estimates(red *R)
{
    const int nf = R->nf, nt = R->nt, nk = R->nk, nd = R->nd, nsub = R->nsub;
    const gd_tr_term *term = R->term;
    const double *Phi = R->Phi, *lam = R->lam, *dd = R->dd, *tb = R->tb, *scal = R->scal;
    R->nest = 0;
    if (R->r < nf) {
        free(R->est);
        double *est = R->est = malloc(4 * (size_t)nd * sizeof *est);
        double *mq = calloc(2 * (size_t)nt + 1, sizeof *mq), T = TWO_PI / R->om;
        if (!est || !mq) {
            free(mq);
            return 1;
        }
        for (int j = 0; j < nsub; j++) {
            const double wgt = 0.5 * (tb[j + 1] - tb[j]) / TWO_PI;
            for (int t = 0; t < 2 * nt; t++)
                mq[t] +=
                    wgt * (scal[(size_t)j * 4 * nt + t] + scal[(size_t)j * 4 * nt + 2 * nt + t]);
        }
        int nest = 0;
        for (int j = 0; j < nd; j++) {
            const double *ph = Phi + (size_t)(nk + j) * nf;
            double kk = lam[nk + j], d = dd[j];
            for (int t = 0; t < nt; t++) {
                double pu = 0.0, pw = 0.0;
                for (int a = 0; a < term[t].nu; a++)
                    pu += ph[term[t].u_idx[a]] * term[t].u[a];
                for (int b = 0; b < term[t].nw; b++)
                    pw += ph[term[t].w_idx[b]] * term[t].w[b];
                kk -= mq[t] * pu * pw;
                d -= mq[nt + t] * pu * pw;
            }
            const double disc = d * d - 4.0 * kk;
            double *e = est + 2 * (size_t)nest;
            if (disc < 0) { /* a pair exp(-d T / 2) e^(+-i beta T) */
                const double a = exp(-0.5 * d * T), bt = 0.5 * sqrt(-disc) * T;
                e[0] = a * cos(bt);
                e[1] = a * sin(bt);
                e[2] = e[0];
                e[3] = -e[1];
            } else {
                const double sq = sqrt(disc);
                e[0] = exp(0.5 * (-d + sq) * T);
                e[2] = exp(0.5 * (-d - sq) * T);
                e[1] = e[3] = 0.0;
            }
            if (isfinite(e[0]) && isfinite(e[1]) && isfinite(e[2])) nest += 2;
        }
        R->nest = nest;
        free(mq);
    }
    return 0;
}

/* The monodromy pass's steps in blocks: a step's update is I + U_j W_j (W_j = phi1 Cm V^T,
 * g2 rows), and nb steps' product is I + Ub Wt, Ub = [U_1 .. U_nb] (n2 x g2 nb) and
 * Wt's row blocks W~_i = W_i (I + sum_{l<i} U_l W~_l) = W_i + (W_i Ub_<i) Wt_<i. Psi
 * then takes Psi + Ub (Wt Psi) once per block: the same product, but two products of
 * n2 x n2 by g2 nb instead of four thin ones per step (dgemm's kernel on a 10-row or
 * 6-deep product is a third as efficient: callgrind). Forming Wt costs about g2^2 nb n2
 * per step against 2 g2 n2^2 for the application; nb = n2 / (4 g2) (4 on seed 002):
 * measured there (two points, callgrind) 1.154 G at nb 1, 1.049 G at 2, 1.042 G at 4,
 * 1.072 G at 8, 1.164 G at 16, against 1.258 G before. */
typedef struct red_block {
    int nb, cnt, g2, t2;
    double *Ub, *Wt, *T, *G, *FC;
} red_block;

static void red_block_free(red_block *B)
{
    free(B->Ub);
    free(B->Wt);
    free(B->T);
    free(B->G);
    free(B->FC);
}

static int red_block_init(red_block *B, int n2, int g2, int t2)
{
    B->nb = n2 / (4 * g2) > 1 ? n2 / (4 * g2) : 1;
    B->g2 = g2;
    B->t2 = t2;
    const size_t w = (size_t)g2 * B->nb;
    B->Ub = malloc((w * n2 + 1) * sizeof *B->Ub);
    B->Wt = malloc((w * n2 + 1) * sizeof *B->Wt);
    B->T = malloc((w * n2 + 1) * sizeof *B->T);
    B->G = malloc(((size_t)g2 * w + 1) * sizeof *B->G);
    B->FC = malloc(((size_t)g2 * t2 + 1) * sizeof *B->FC);
    if (B->Ub && B->Wt && B->T && B->G && B->FC) return 0;
    red_block_free(B);
    return 1;
}

/* The next step's U (n2 x g2), to be filled before red_block_add. */
static double *red_block_u(red_block *B, int n2)
{
    return B->Ub + (size_t)B->cnt * B->g2 * n2;
}

/* Psi <- Psi + Ub (Wt Psi) for the steps gathered; none left. */
static void red_block_flush(red_block *B, double *Psi, int n2)
{
    if (!B->cnt) return;
    const int w = B->g2 * B->cnt, ld = B->g2 * B->nb;
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, w, n2, n2, 1.0, B->Wt, ld, Psi, n2, 0.0,
                B->T, w);
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n2, n2, w, 1.0, B->Ub, n2, B->T, w, 1.0,
                Psi, n2);
    B->cnt = 0;
}

/* Appends the step with kernel F (g2 x g2), Cm (g2 x t2) and V^T's rows Rk (n2 x t2,
 * column-major: a row per column), its U already in red_block_u; a full block is
 * applied to Psi. */
static void red_block_add(red_block *B, const double *F, const double *Cm, const double *Rk,
                          double *Psi, int n2)
{
    const int g2 = B->g2, t2 = B->t2, ld = g2 * B->nb, k = g2 * B->cnt;
    double *W = B->Wt + k; /* its rows in Wt */
    small_mul_rect(g2, g2, t2, 1.0, F, Cm, B->FC);
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, g2, n2, t2, 1.0, B->FC, g2, Rk, n2, 0.0, W,
                ld);
    if (k) {
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, g2, k, n2, 1.0, W, ld, B->Ub, n2,
                    0.0, B->G, g2);
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, g2, n2, k, 1.0, B->G, g2, B->Wt, ld,
                    1.0, W, ld);
    }
    if (++B->cnt == B->nb) red_block_flush(B, Psi, n2);
}

/* The propagation over the steps of one count into R->Psi: per step [0, h] about its
 * midpoint m, the interaction picture zeta = E(m - t) z, d zeta/dt = E(m - t) B(t)
 * E(t - m) zeta, whose fourth-order Magnus step with the two Gauss points (t_g - m = -+d,
 * d = sqrt(3)/6 h) is
 *   Omega = h/2 (B1^ + B2^) + sqrt(3)/12 h^2 [B2^, B1^],
 *   B1^ = E(d) B1 E(-d),  B2^ = E(-d) B2 E(d),
 * so z(h) = E(h/2) exp(Omega) E(h/2) z(0) (the order-4 Magnus step of Blanes, Casas,
 * Oteo & Ros 2009, Eq. 4.3, applied to the interaction-picture equation). With B_g = P C
 * R_g, Omega = U Cm V^T with U = [E(d) P, E(-d) P] (2 ng columns), V^T = [R1 E(-d); R2
 * E(d)] (2 nt rows) and Cm = [h/2 C, -c2 C (R1^ P2^) C; c2 C (R2^ P1^) C, h/2 C],  c2 =
 * sqrt(3)/12 h^2, and exp(U Cm V^T) = I + U phi1(Cm V^T U) Cm V^T: a rank-2 ng update.
 * *rc: 1 on entry (else nothing is propagated), 2 when Psi overflowed. 0 ok, 1 out of
 * memory. */
static int red_propagate(red *R, int *rc)
{
    /* nt: the classes of equal (u, w) (their rows); ntt: the terms (the scalars' stride) */
    const int ntt = R->nt, nt = R->nm, ng = R->ng, n2 = R->n2, nsub = R->nsub;
    const size_t rr = R->rr;
    const double om = R->om, *tb = R->tb, *scal = R->scal, *lre = R->lre, *lim = R->lim,
                 *At = R->At, *Bt = R->Bt, *Pt = R->Pt;
    const int *tg = R->mtg, *mrep = R->mrep;
    double *Psi = R->Psi, *Rk = R->Rk, *Y = R->Y, *Z = R->Z;
    /* the monodromy: Psi = I (n2 columns); the forced orbit: the caller's columns */
    const int nc = R->ncol > 0 ? R->ncol : n2, aug = R->aug;
    const size_t rc_n = (size_t)n2 * nc;
    if (R->ncol <= 0) {
        memset(Psi, 0, rr * sizeof *Psi);
        for (int i = 0; i < n2; i++)
            Psi[(size_t)i * n2 + i] = 1.0;
    }
    const int g2 = 2 * ng, t2 = 2 * nt, ga = 2 * g2;
    const size_t gg = (size_t)ga * ga;
    free(R->small);
    double *small = R->small = malloc(
        (5 * gg + 2 * (size_t)g2 * t2 + (size_t)g2 * g2 + 4 * (size_t)n2 + 1) * sizeof *small);
    if (!small) return 1;
    double *G = small, *F = G + gg, *W3 = F + gg, *Cm = W3 + 3 * gg, *VU = Cm + (size_t)g2 * t2,
           *CV = VU + (size_t)g2 * t2, *ec = CV + (size_t)g2 * g2, *es = ec + n2, *ic = es + n2,
           *is = ic + n2;
    double *U = Z + (size_t)2 * g2 * (n2 + 1); /* n2 x g2 (Z and CY: up to n2 + 1 columns) */
    /* the monodromy pass (no forcing, no records) gathers its steps' updates into blocks
     * of nb steps (red_block) */
    const int blocked = R->ncol <= 0 && !aug && !R->orb;
    red_block B = {0};
    if (blocked && red_block_init(&B, n2, g2, t2)) return 1;
    exp_run run[2] = {{0}, {0}};
    if (R->ncol == 1 || blocked) {
        run[0].b = malloc(16 * (size_t)n2 * sizeof *run[0].b);
        if (!run[0].b) {
            red_block_free(&B);
            return 1;
        }
        run[1].b = run[0].b + 8 * (size_t)n2;
    }
    /* the anchor ta (s) of Psi's frame and how far from it the frame may drift: e^20 */
    double lmax = 0.0, ta = 0.0;
    for (int i = 0; i < n2; i++)
        lmax = fmax(lmax, fabs(lre[i]));
    const double drift = 20.0;
    for (int j = 0; j < nsub && *rc == 1; j++) {
        const double dt = (tb[j + 1] - tb[j]) / om, d = sqrt(3.0) / 6.0 * dt,
                     c2 = sqrt(3.0) / 12.0 * dt * dt, m = 0.5 * (tb[j] + tb[j + 1]) / om;
        const double *sc = scal + (size_t)j * 4 * ntt;
        int any = 0;
        for (int t = 0; t < 4 * ntt; t++)
            any |= sc[t] != 0.0;
        if (!any || !ng) { /* B = 0: Psi's frame carries E exactly */
            if (R->orb) R->orb(R, j + 1, ta);
            continue;
        }
        if (lmax * (m + d - ta) > drift) { /* a new anchor at the step's start */
            const double t0 = tb[j] / om;
            if (blocked) red_block_flush(&B, Psi, n2);
            exp_blocks(n2, lre, lim, t0 - ta, ec, es, ic, is);
            rotate(n2, nc, lim, ec, es, 1.0, Psi);
            ta = t0;
        }
        /* V^T rows (Rk: t2 rows of n2, row-major): R_g's rows times E(t_g - ta), and
         * U = [E(ta - t_1) P, E(ta - t_2) P] */
        for (int g = 0; g < 2; g++) {
            const double *sq = sc + (size_t)g * 2 * ntt, *sv = sq + ntt;
            double *rg = Rk + (size_t)g * nt * n2,
                   *ug = (blocked ? red_block_u(&B, n2) : U) + (size_t)g * ng * n2;
            for (int t = 0; t < nt; t++) {
                double *rk = rg + (size_t)t * n2;
                const int rt = mrep[t];
                const double *at = At + (size_t)rt * n2, *bt = Bt + (size_t)rt * n2;
                for (int i = 0; i < n2; i++)
                    rk[i] = sq[rt] * at[i] + sv[rt] * bt[i];
            }
            const double *eb = ec;
            if (run[0].b) /* the vector and monodromy passes: equal steps advance the blocks */
                eb = exp_at(&run[g], n2, lre, lim, m + (g ? d : -d) - ta, dt);
            else
                exp_blocks(n2, lre, lim, m + (g ? d : -d) - ta, ec, es, ic, is);
            /* a row times E(s) is E(s)^T applied to the column: the transposed blocks */
            rotate(n2, nt, lim, eb, eb + n2, -1.0, rg);
            memcpy(ug, Pt, (size_t)n2 * ng * sizeof *ug);
            rotate(n2, ng, lim, eb + 2 * (size_t)n2, eb + 3 * (size_t)n2, 1.0, ug);
        }
        /* VU = V^T U (t2 x g2) */
        const double *Uj = blocked ? red_block_u(&B, n2) : U;
        cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, t2, g2, n2, 1.0, Rk, n2, Uj, n2, 0.0,
                    VU, t2);
        /* Cm (g2 x t2): C h/2 on the diagonal blocks; the commutator's blocks
         * (2,1) = c2 C (R2^ P1^) C (rows ng.., columns 0..nt), (1,2) = -c2 C (R1^ P2^) C */
        memset(Cm, 0, (size_t)g2 * t2 * sizeof *Cm);
        for (int t = 0; t < nt; t++) {
            Cm[(size_t)t * g2 + tg[t]] = 0.5 * dt;
            Cm[(size_t)(nt + t) * g2 + ng + tg[t]] = 0.5 * dt;
        }
        for (int t = 0; t < nt; t++) {           /* column t of block (2,1): from R1 row t */
            for (int t2r = 0; t2r < nt; t2r++) { /* C (R2^ P1^): row group of term t2r */
                /* (R2^ P1^)[t2r, g] = VU[nt + t2r, g]; times C[g, t] = (g == tg[t]) */
                Cm[(size_t)t * g2 + ng + tg[t2r]] += c2 * VU[(size_t)tg[t] * t2 + nt + t2r];
                /* block (1,2): -c2 C (R1^ P2^) C: (R1^ P2^)[t2r, g] = VU[t2r, ng + g] */
                Cm[(size_t)(nt + t) * g2 + tg[t2r]] -= c2 * VU[(size_t)(ng + tg[t]) * t2 + t2r];
            }
        }
        /* phi1(Cm VU) (small_phi1) */
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, g2, g2, t2, 1.0, Cm, g2, VU, t2, 0.0,
                    CV, g2);
        small_phi1(g2, CV, F, W3);
        if (blocked) {
            red_block_add(&B, F, Cm, Rk, Psi, n2);
        } else {
            /* Y = V^T Psi (t2 x n2); Z = phi1 Cm Y (g2 x n2); Psi += U Z */
            cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, t2, nc, n2, 1.0, Rk, n2, Psi, n2,
                        0.0, Y, t2);
            if (aug) { /* the constant coordinate's entry of the first row of each group: the
                        * forcing's coefficient c_g at the Gauss point (E is 1 on it) */
                double *ya = Y + (size_t)(nc - 1) * t2;
                for (int g = 0; g < 2; g++)
                    for (int a = 0; a < ng; a++)
                        ya[(size_t)g * nt + R->gfirst[a]] += R->fc[((size_t)j * 2 + g) * ng + a];
            }
            double *CY = Z + (size_t)g2 * (n2 + 1);
            cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, g2, nc, t2, 1.0, Cm, g2, Y, t2,
                        0.0, CY, g2);
            cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, g2, nc, g2, 1.0, F, g2, CY, g2,
                        0.0, Z, g2);
            cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n2, nc, g2, 1.0, U, n2, Z, g2,
                        1.0, Psi, n2);
        }
        if ((j & 255) == 255 && (!isfinite(Psi[0]) || !isfinite(Psi[rc_n - 1]))) {
            *rc = 2;
            break;
        }
        if (R->orb) R->orb(R, j + 1, ta);
    }
    if (blocked) {
        red_block_flush(&B, Psi, n2);
        red_block_free(&B);
    }
    if (*rc == 1) {
        exp_blocks(n2, lre, lim, tb[nsub] / om - ta, ec, es, ic, is);
        rotate(n2, nc, lim, ec, es, 1.0, Psi);
        for (size_t m = 0; m < rc_n; m++)
            if (!isfinite(Psi[m])) {
                *rc = 2;
                break;
            }
    }
    free(run[0].b);
    return 0;
}

/* The step count: fixed when the caller gives one (steps > 0); otherwise doubled from s0
 * until the moduli of the multipliers that decide stability agree with the previous
 * count's (steps_agree), at most steps_cap. In the interaction picture the constant part
 * is exact, so the steps only have to follow the laws' variation: measured on the
 * [JMSTHelical] model (docs/periodic.md, "Stability at scale"), 512 to 1024 steps per
 * period agree with 16384 (the 4 x samples of H = 591) to 3e-8. A Richardson step on the
 * symmetric steps' h^4 error (Psi_S + (Psi_S - Psi_S/2) / 15, accepted when it agrees with
 * Psi_S: half the steps) was tried and left out: on seed 002's 0-deg curve it accepted 512
 * steps where the plain rule takes 2048 and 28 of 300 points missed the 1 % rule (3.1 % at
 * 2689 rpm against 8192 steps: the 256 steps are not yet in the h^4 regime there;
 * docs/periodic.md, "Toward 20 ms per point"). The reduced multipliers
 * (n2) into mu_re, mu_im: 0, else the return codes of gd_hb_floquet_reduced. */
static int red_step_counts(red *R, int steps, int s0, int steps_cap, int *steps_used,
                           const gd_tr_record *bl, int nbl, double setup, double budget,
                           double *mu_re, double *mu_im, char *msg)
{
    const int ng = R->ng, n2 = R->n2, r = R->r;
    double *mod = R->mod, *prev = R->prev;
    int rc = 1;
    int S = steps > 0 ? steps : s0;
    for (int pass = 0;; pass++) {
        if (red_scalars(R, S, bl, nbl)) return rc;
        if (red_estimates(R)) return rc;
        const int nsub = R->nsub;
        {
            /* counted (work.c): per step the four products of red_propagate and the small
             * exponential (about 30 ga^3), after the modes' set-up; decided before the
             * first step */
            const int g2 = 2 * ng, t2 = 2 * R->nm, ga = 2 * g2;
            const double step = 2.0 * ((double)t2 * n2 * n2 + (double)g2 * n2 * t2 +
                                       (double)g2 * n2 * g2 + (double)n2 * n2 * g2) +
                                30.0 * pow(ga, 3),
                         need = gd_per_work_seconds(step * nsub) + setup;
            if (budget > 0 && need > budget) {
                int len = snprintf(msg, 160,
                                   "stability not computed: the reduced monodromy (%d modes, %d "
                                   "steps) would take about %.3g s (counted work), over the %g s "
                                   "budget per point",
                                   r, nsub, need, budget);
                if (len < 0) msg[0] = '\0';
                rc = 4;
            }
        }
        if (red_propagate(R, &rc)) return rc;
        /* overflow: the steps are too long for the laws' variation (a long period: the
         * residual vectors carry the stiff mesh modes, whose coupling the steps must
         * follow); a count of its own doubles and tries again */
        const int can_double = steps <= 0 && 2 * (long)S <= steps_cap;
        if (rc == 2 && can_double) {
            rc = 1;
            pass = -1; /* the next count is compared with its double, not with this one */
            S *= 2;
            continue;
        }
        if (rc == 2 && steps <= 0) {
            snprintf(msg, 160,
                     "stability not computed: the reduced monodromy over the period %.3g s "
                     "overflowed up to %d Magnus steps",
                     TWO_PI / R->om, S);
            rc = 6;
        }
        if (rc != 1) return rc;
        {
            double dummy[1];
            if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n2, R->Psi, n2, mu_re, mu_im, dummy, 1,
                              dummy, 1))
                return rc;
        }
        if (steps > 0) break;
        for (int i = 0; i < n2; i++)
            mod[i] = hypot(mu_re[i], mu_im[i]);
        qsort(mod, (size_t)n2, sizeof *mod, by_value_desc);
        if (pass > 0 && steps_agree(mod, prev, n2)) {
            if (steps_used) *steps_used = S;
            break;
        }
        if (!can_double) {
            /* no two counts agreed: nothing to trust (an unsettled count once gave
             * |mu|max 2.8e73 at 100 rpm on the [JMSTHelical] model) */
            double worst = 0.0;
            for (int i = 0; pass > 0 && i < n2; i++)
                worst = fmax(worst, fabs(mod[i] - prev[i]));
            snprintf(msg, 160,
                     "stability not computed: the reduced multipliers did not settle by %d Magnus "
                     "steps (moduli moved by %.2g from %d)",
                     S, worst, S / 2);
            return 6;
        }
        memcpy(prev, mod, (size_t)n2 * sizeof *prev);
        S *= 2;
    }
    if (steps_used && steps > 0) *steps_used = S;
    return 0;
}

int gd_hb_floquet_reduced(hb *h, gd_transient *tr, double om, const double *X, int steps, int s0,
                          int steps_cap, int *steps_used, const gd_tr_record *bl, int nbl,
                          double wcut, double budget, double *mu_re, double *mu_im, int *nmu,
                          int *nbasis, char *msg)
{
    const int nf = h->nf;
    *nmu = 0;
    *nbasis = 0;
    msg[0] = '\0';
    const gd_tr_term *term;
    const int nt = gd_transient_terms(tr, &term);
    if (nt < 0) return 1;
    if (nf > 6000) {
        snprintf(msg, 160,
                 "the reduced basis needs every mode of the %d free DOFs (dense, at most 6000)",
                 nf);
        return 5;
    }
    /* every mode of (K, M), dense: about 10 nf^3 flops before any step (work.c) */
    const double setup = gd_per_work_seconds(10.0 * pow(nf, 3));
    if (budget > 0 && setup > budget) {
        snprintf(msg, 160,
                 "stability not computed: the reduced basis's modes of %d DOFs would take "
                 "about %.3g s (counted work), over the %g s budget per point",
                 nf, setup, budget);
        return 4;
    }
    red R = {.h = h, .tr = tr, .om = om, .X = X, .term = term, .nf = nf, .nt = nt};
    int rc = red_modes(&R, wcut, msg);
    if (!rc) rc = red_residual(&R);
    if (!rc) rc = red_reduce(&R, msg);
    if (!rc) rc = red_eigenbasis(&R, msg);
    if (!rc) rc = red_inputs(&R);
    if (!rc)
        rc = red_step_counts(&R, steps, s0, steps_cap, steps_used, bl, nbl, setup, budget, mu_re,
                             mu_im, msg);
    if (!rc) {
        /* then the discarded modes' estimates, largest first, while there is room (2 nf) */
        int nall = R.n2;
        if (R.nest) {
            qsort(R.est, (size_t)R.nest, 2 * sizeof *R.est, by_modulus);
            for (int i = 0; i < R.nest && nall < 2 * nf; i++, nall++) {
                mu_re[nall] = R.est[2 * i];
                mu_im[nall] = R.est[2 * i + 1];
            }
        }
        gd_hb_sort_multipliers(mu_re, mu_im, nall);
        *nmu = nall;
        *nbasis = R.r;
    }
    red_free(&R);
    return rc;
}

/* The records along the forced orbit (gd_hb_orbit_reduced's second pass): at a step's
 * end t, the state z = E(t - ta) zeta of the anchored frame, the record DOFs' q and q'
 * from z by G (their rows of V C^-1 XR, V XR) plus the static state, the records'
 * values, their least, largest and mean over the steps' ends. */
typedef struct orbit_rec {
    const gd_tr_record *rec;
    int nrec, ns;
    int *sup;
    double *G, *xs, *y, *z, *vals, *lo, *hi, *sum;
    exp_run run;
    long cnt;
    double *smp; /* NULL, or nrec x nsmp: the records on the grid (gd_orbit_samples) */
    long nsmp;
} orbit_rec;

static void orbit_at(red *R, int j, double ta)
{
    orbit_rec *o = R->orb_user;
    const int n2 = R->n2, ns = o->ns, nf = R->nf;
    const double t = R->tb[j] / R->om;
    const double *eb =
        exp_at(&o->run, n2, R->lre, R->lim, t - ta, (R->tb[j] - R->tb[j - 1]) / R->om);
    memcpy(o->z, R->Psi, (size_t)n2 * sizeof *o->z);
    rotate(n2, 1, R->lim, eb, eb + n2, 1.0, o->z);
    for (int m = 0; m < 2 * ns; m++) {
        double a = 0.0;
        for (int i = 0; i < n2; i++)
            a += o->G[(size_t)i * 2 * ns + m] * o->z[i];
        const int d = o->sup[m % ns];
        o->y[m < ns ? d : nf + d] = m < ns ? o->xs[d] + a : a;
    }
    gd_transient_record_values(R->tr, o->rec, o->nrec, t, o->y, o->vals);
    for (int k = 0; k < o->nrec; k++) {
        const double v = o->vals[k];
        if (!o->cnt || v < o->lo[k]) o->lo[k] = v;
        if (!o->cnt || v > o->hi[k]) o->hi[k] = v;
        o->sum[k] += v;
        /* step end cnt + 1 is at (cnt + 1) T / nsmp: t = T is the grid's t = 0 */
        if (o->smp && o->cnt < o->nsmp) o->smp[(size_t)k * o->nsmp + (o->cnt + 1) % o->nsmp] = v;
    }
    o->cnt++;
}

static void orbit_rec_free(orbit_rec *o)
{
    free(o->sup);
    free(o->G);
    free(o->xs);
    free(o->y);
    free(o->z);
    free(o->run.b);
    free(o->vals);
}

/* x_s = K^-1 f0, f0 = f(t, 0) (R->f0: the forces at rest), when those forces do not change
 * over the period (loads and prescribed couplings constant: the laws at rest give none).
 * 0 ok, 1 out of memory, 2 they change (msg), 3 K singular. */
static int orbit_static(red *R, double *xs, char *msg)
{
    const int nf = R->nf;
    double *y = calloc(2 * (size_t)nf, sizeof *y), *f = malloc((size_t)nf * sizeof *f),
           *Kd = malloc((size_t)nf * nf * sizeof *Kd);
    int *piv = malloc((size_t)nf * sizeof *piv), rc = 0;
    if (!y || !f || !Kd || !piv) rc = 1;
    if (!rc) {
        const double T = TWO_PI / R->om;
        gd_transient_local(R->tr, 0.0, y, xs, NULL, NULL);
        double big = 0.0, dif = 0.0;
        for (int i = 0; i < nf; i++)
            big = fmax(big, fabs(xs[i]));
        for (int k = 1; k < 8; k++) {
            gd_transient_local(R->tr, T * k / 8.0 * 0.987, y, f, NULL, NULL);
            for (int i = 0; i < nf; i++)
                dif = fmax(dif, fabs(f[i] - xs[i]));
        }
        if (dif > 1e-9 * big) {
            snprintf(msg, 160,
                     "the forces at rest change over the period (%.3g of %.3g): not a constant "
                     "load",
                     dif, big);
            rc = 2;
        }
    }
    if (!rc) {
        gd_csc M, D, K;
        gd_transient_matrices(R->tr, &M, &D, &K);
        dense_of(&K, nf, Kd);
        memcpy(R->f0, xs, (size_t)nf * sizeof *xs);
        if (LAPACKE_dgesv(LAPACK_COL_MAJOR, nf, 1, Kd, nf, piv, xs, nf)) rc = 3;
    }
    free(y);
    free(f);
    free(Kd);
    free(piv);
    return rc;
}

int gd_hb_orbit_reduced(hb *h, gd_transient *tr, double om, int steps, int steps_out, double wcut,
                        const gd_tr_record *rec, int nrec, double *mean, double *p2p, int *nbasis,
                        double *mumax, char *msg)
{
    return gd_hb_orbit_reduced_out(h, tr, om, steps, steps_out, wcut, rec, nrec, mean, p2p, nbasis,
                                   mumax, NULL, msg);
}

int gd_hb_orbit_reduced_out(hb *h, gd_transient *tr, double om, int steps, int steps_out,
                            double wcut, const gd_tr_record *rec, int nrec, double *mean,
                            double *p2p, int *nbasis, double *mumax, gd_orbit_samples *x, char *msg)
{
    const int nf = h->nf;
    msg[0] = '\0';
    *nbasis = 0;
    const gd_tr_term *term;
    const int nt = gd_transient_terms(tr, &term);
    if (nt < 0) return 1;
    double *X = calloc((size_t)nf * h->nh, sizeof *X);
    if (!X) return 1;
    red R = {.h = h, .tr = tr, .om = om, .X = X, .term = term, .nf = nf, .nt = nt};
    orbit_rec o = {.rec = rec, .nrec = nrec};
    /* the static state x_s, the linearisation's point (the orbit X = x_s constant) */
    o.xs = malloc((size_t)nf * sizeof *o.xs);
    R.f0 = malloc((size_t)nf * sizeof *R.f0);
    R.fw = malloc((size_t)nf * sizeof *R.fw);
    int rc = !o.xs || !R.f0 || !R.fw;
    if (!rc) rc = orbit_static(&R, o.xs, msg);
    if (!rc) memcpy(X, o.xs, (size_t)nf * sizeof *X);
    if (!rc) rc = red_modes(&R, wcut, msg);
    if (!rc) rc = red_residual(&R);
    if (!rc) rc = red_reduce(&R, msg);
    if (!rc) rc = red_eigenbasis(&R, msg);
    if (!rc) rc = red_inputs(&R);
    const int n2 = R.n2, r = R.r, ng = R.ng;
    /* the groups' least-squares rows (U^T U)^-1 U^T and each group's first class */
    if (!rc) {
        R.upi = calloc((size_t)nf * ng + 1, sizeof *R.upi);
        R.gfirst = malloc(((size_t)ng + 1) * sizeof *R.gfirst);
        double *gram = calloc((size_t)ng * ng + 1, sizeof *gram);
        int *gp = malloc(((size_t)ng + 1) * sizeof *gp);
        if (!R.upi || !R.gfirst || !gram || !gp) rc = 1;
        for (int a = 0; !rc && a < ng; a++) {
            const gd_tr_term *u = &term[R.grep[a]];
            for (int b = 0; b < u->nu; b++)
                R.upi[(size_t)u->u_idx[b] * ng + a] = u->u[b];
            R.gfirst[a] = -1;
        }
        for (int t = R.nm - 1; !rc && t >= 0; t--)
            R.gfirst[R.mtg[t]] = t;
        for (int a = 0; !rc && a < ng; a++)
            for (int b = 0; b < ng; b++)
                for (int i = 0; i < nf; i++)
                    gram[(size_t)b * ng + a] +=
                        R.upi[(size_t)i * ng + a] * R.upi[(size_t)i * ng + b];
        /* upi^T (nf x ng, row-major ng per DOF) <- U gram^-1: solve gram Y = U^T */
        if (!rc && LAPACKE_dgesv(LAPACK_COL_MAJOR, ng, nf, gram, ng, gp, R.upi, ng)) rc = 3;
        free(gram);
        free(gp);
    }
    if (!rc) rc = red_scalars(&R, steps, NULL, 0);
    /* pass 1: the monodromy and the response p over one period from x_s at rest, in the
     * eigenvector coordinates: Psi = [I | 0] with the constant coordinate */
    double *A = NULL;
    int *piv = NULL;
    if (!rc) {
        free(R.Psi);
        R.Psi = calloc((size_t)n2 * (n2 + 1), sizeof *R.Psi);
        A = malloc((size_t)n2 * n2 * sizeof *A);
        piv = malloc((size_t)n2 * sizeof *piv);
        if (!R.Psi || !A || !piv) rc = 1;
    }
    if (!rc) {
        for (int i = 0; i < n2; i++)
            R.Psi[(size_t)i * n2 + i] = 1.0;
        R.ncol = n2 + 1;
        R.aug = 1;
        int prc = 1;
        if (red_propagate(&R, &prc))
            rc = 1;
        else if (prc != 1) {
            snprintf(msg, 160, "the reduced monodromy overflowed at %d steps", steps);
            rc = 2;
        }
    }
    /* the periodic orbit's start xi0 = (I - Phi)^-1 p */
    if (!rc) {
        for (size_t m = 0; m < (size_t)n2 * n2; m++)
            A[m] = -R.Psi[m];
        for (int i = 0; i < n2; i++)
            A[(size_t)i * n2 + i] += 1.0;
        if (LAPACKE_dgesv(LAPACK_COL_MAJOR, n2, 1, A, n2, piv, R.Psi + (size_t)n2 * n2, n2)) {
            snprintf(msg, 160, "a multiplier at 1: no isolated periodic orbit");
            rc = 2;
        }
    }
    if (!rc && (mumax || x)) {
        double *wr = malloc(2 * (size_t)n2 * sizeof *wr), dummy[1];
        for (size_t m = 0; m < (size_t)n2 * n2; m++)
            A[m] = R.Psi[m];
        double mx = 0.0;
        if (wr &&
            !LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n2, A, n2, wr, wr + n2, dummy, 1, dummy, 1))
            for (int i = 0; i < n2; i++)
                mx = fmax(mx, hypot(wr[i], wr[n2 + i]));
        else if (x) { /* the multipliers are an output: no eigenvalues is a failure */
            snprintf(msg, 160, "the eigenvalues of the reduced monodromy failed");
            rc = wr ? 2 : 1;
        }
        if (mumax) *mumax = mx;
        if (!rc && x) { /* handed over: wr holds n2 real parts then n2 imaginary parts */
            x->mu = wr;
            x->nmu = n2;
            wr = NULL;
        }
        free(wr);
    }
    /* pass 2: the orbit from xi0, the records at every step's end */
    if (!rc) {
        int *idx = malloc(64 * (size_t)(nrec + 1) * sizeof *idx);
        unsigned char *mark = calloc((size_t)nf + 1, 1);
        int ns = 0;
        if (!idx || !mark) rc = 1;
        for (int k = 0; !rc && k < nrec; k++) {
            const int c = gd_transient_record_dofs(tr, &rec[k], idx, 64);
            if (c < 0) {
                snprintf(msg, 160, "a record reads every DOF");
                rc = 2;
            }
            for (int i = 0; !rc && i < c; i++)
                mark[idx[i]] = 1;
        }
        o.sup = malloc((size_t)(nf + 1) * sizeof *o.sup);
        if (!o.sup) rc = 1;
        for (int i = 0; !rc && i < nf; i++)
            if (mark[i]) o.sup[ns++] = i;
        o.ns = ns;
        free(idx);
        free(mark);
        if (!rc) {
            o.G = calloc(2 * (size_t)ns * n2 + 1, sizeof *o.G);
            o.y = calloc(2 * (size_t)nf, sizeof *o.y);
            o.z = malloc((size_t)n2 * sizeof *o.z);
            o.run.b = malloc(8 * (size_t)n2 * sizeof *o.run.b);
            o.vals = calloc(4 * (size_t)nrec + 1, sizeof *o.vals);
            if (!o.G || !o.y || !o.z || !o.run.b || !o.vals) rc = 1;
            if (!rc && x) {
                o.nsmp = steps_out > steps ? steps_out : steps;
                o.smp = x->values = calloc((size_t)nrec * o.nsmp + 1, sizeof *o.smp);
                x->n = (int)o.nsmp;
                if (!o.smp) rc = 1;
            }
        }
        if (!rc) {
            o.lo = o.vals + nrec;
            o.hi = o.lo + nrec;
            o.sum = o.hi + nrec;
            /* G rows: q = V C^-1 x~, q' = V x~' of the support DOFs, x~ = XR xi */
            for (int m = 0; m < ns; m++)
                for (int k = 0; k < r; k++) {
                    const double v = R.V[(size_t)k * nf + o.sup[m]];
                    if (v == 0.0) continue;
                    for (int i = 0; i < n2; i++) {
                        o.G[(size_t)i * 2 * ns + m] += v * R.XR[(size_t)i * n2 + k] / R.cs[k];
                        o.G[(size_t)i * 2 * ns + ns + m] += v * R.XR[(size_t)i * n2 + r + k];
                    }
                }
            memmove(R.Psi, R.Psi + (size_t)n2 * n2, (size_t)n2 * sizeof *R.Psi);
            /* the records at a finer grid than the monodromy's steps: the orbit's pass
             * propagates one vector (2 (nt + ng) n2 a step against the monodromy's
             * 2 (nt + ng) n2^2), so its steps are cheap */
            if (steps_out > steps) rc = red_scalars(&R, steps_out, NULL, 0);
        }
        if (!rc) {
            R.ncol = 1;
            R.orb = orbit_at;
            R.orb_user = &o;
            int prc = 1;
            if (red_propagate(&R, &prc))
                rc = 1;
            else if (prc != 1)
                rc = 2;
        }
        if (!rc && x && o.cnt != o.nsmp) { /* steps split at breakpoints: no equal grid */
            snprintf(msg, 160, "the records' grid is not equally spaced (%ld steps for %ld)", o.cnt,
                     o.nsmp);
            rc = 2;
        }
        for (int k = 0; !rc && k < nrec; k++) {
            mean[k] = o.sum[k] / (double)o.cnt;
            p2p[k] = o.hi[k] - o.lo[k];
        }
    }
    if (!rc) *nbasis = r;
    free(A);
    free(piv);
    free(X);
    orbit_rec_free(&o);
    red_free(&R);
    return rc;
}

int gd_floquet_reduced_first_steps(long top)
{
    int s0 = 256;
    while (s0 < 8 * top && s0 < GD_PERIODIC_MAX_SAMPLES / 2)
        s0 *= 2;
    return s0;
}

int gd_per_floquet_reduced(ctx *c, stage *s, const double *X, double lam, int steps, int steps_cap,
                           int *steps_used, const gd_tr_record *bl, int nbl, double *mre,
                           double *mim, int *nmu, int *nbasis)
{
    /* the cut-off: a multiple of the highest excitation frequency (the top order of the
     * fundamental: the highest tooth-mesh frequency), or of H w where that is unknown */
    const double speed = c->param ? c->param->speed : lam;
    double w0 = 0.0, wexc = c->H * s->w;
    int order = 0;
    gd_error err;
    if (!gd_periodic_fundamental(s->sys, s->spec, speed, &w0, &order, &err) && w0 > 0 && order > 0)
        wexc = w0 * order;
    const double fc = c->opt->floquet_cutoff > 0 ? c->opt->floquet_cutoff : GD_FLOQUET_CUTOFF;
    /* the first step count: 8 per period of the highest excitation (the top order of the
     * fundamental, or H), a power of 2, at least 256 */
    /* (a subharmonic period holds subharmonic times as many) */
    const int sub = c->opt->subharmonic > 1 ? c->opt->subharmonic : 1;
    const long top = order > 0 ? (long)order * sub : c->H;
    /* a count of its own may go past the caller's (4 x samples): a long period at a low
     * speed needs more steps for the stiff directions the residual vectors carry (the
     * [JMSTHelical] model at 100-180 rpm overflowed at 16384), and there the basis is
     * small (6 vectors), so the steps are cheap; the CPU budget still bounds it */
    if (steps <= 0 && steps_cap < GD_FLOQUET_STEPS_MAX) steps_cap = GD_FLOQUET_STEPS_MAX;
    const int s0 = gd_floquet_reduced_first_steps(top);
    return gd_hb_floquet_reduced(&c->h, s->tr, s->w, X, steps, s0 < steps_cap ? s0 : steps_cap,
                                 steps_cap, steps_used, bl, nbl, fc * wexc, c->opt->floquet_budget,
                                 mre, mim, nmu, nbasis, c->floquet_msg);
}
