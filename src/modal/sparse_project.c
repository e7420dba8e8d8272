/* The lowest damped modes of one speed without Krylov-Schur on the first-order form (issue 35):
 * 1. the undamped problem K u = omega^2 M u (K symmetric) by block shift-invert Lanczos,
 *    Op = (K + s^2 M)^-1 M in the M inner product with full reorthogonalisation (real,
 *    n long vectors: half the length of the first-order form's, a symmetric projected
 *    matrix instead of a Hessenberg one);
 * 2. the damped and gyroscopic problem projected on the lowest undamped Ritz vectors Phi
 *    (M-orthonormal): lambda^2 y + lambda Phi^T D Phi y + Phi^T K Phi y = 0, a dense
 *    companion problem of twice their count;
 * 3. these approximations refined on the full quadratic problem and vouched for by the
 *    Campbell continuation (gd_sparse_track, sparse_track.c): a complex factorisation per
 *    cluster, residual inverse iteration with Rayleigh-Ritz, and the deflated shift-invert
 *    completeness check at -s, which finds any mode the projection missed.
 * The rule for the fallback (Krylov-Schur, sparse_modes.c; *out NULL here): K not symmetric
 * (cross-coupled bearings), an undamped solve (GD_MODAL_UNDAMPED), a user's shift, fewer
 * than 20 Krylov vectors of workspace, a wanted mode that is overdamped (real) in the
 * projection, an undamped Ritz vector not converged, or any refusal of the continuation
 * (a cluster of more than 6 modes, no convergence, a missed mode). */
#include <cblas.h>
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

/* block size: the x-y pairs of an axisymmetric rotor are double eigenvalues, which a
 * single start vector finds only once */
#define PJ_BLOCK 2
/* undamped Ritz vectors kept beyond the wanted modes (the damped ones mix neighbours) */
#define PJ_GUARD 4
/* an undamped Ritz pair is converged when its residual in the M norm is below this
 * fraction of its operator eigenvalue */
#define PJ_RTOL 1e-8
/* the wanted Ritz values have settled when none moved by more than this (relative) in the
 * last two Lanczos steps: their vectors are then computed and their residuals checked */
#define PJ_SETTLE 1e-10
/* the projected modes handed to the continuation beyond the wanted ones: those within the
 * continuation's loose check margin of the last wanted |lambda|, and one more */
#define PJ_EDGE 2e-2

typedef struct pj_ctx {
    gd_shift_invert op;
    const gd_splu_symbolic *sym;
    double *x2, *y2; /* 2 n */
} pj_ctx;

/* y = (K + s^2 M)^-1 M x: the top half of the first-order operator at D = 0 applied to
 * [0; -x / g] (shift_invert.c) */
static void pj_apply(pj_ctx *c, const double *x, double *y)
{
    int n = c->op.n;
    double ig = -1.0 / c->op.scale;
    memset(c->x2, 0, (size_t)n * sizeof *c->x2);
    for (int i = 0; i < n; i++)
        c->x2[n + i] = ig * x[i];
    gd_shift_invert_apply(&c->op, c->sym, c->x2, c->y2);
    memcpy(y, c->y2, (size_t)n * sizeof *y);
}

/* y = A x for values v on the pattern */
static void pat_mul(const gd_pattern *p, const double *v, const double *x, double *y)
{
    memset(y, 0, (size_t)p->n * sizeof *y);
    for (int j = 0; j < p->n; j++) {
        double xj = x[j];
        for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++)
            y[p->rowind[q]] += v[q] * xj;
    }
}

/* x M-orthogonalised against the m columns of V (MV = M V) twice (classical Gram-Schmidt
 * with reorthogonalisation), the coefficients added to h (m, may be NULL); then
 * M-normalised into V's column m, MV's too. Returns its M norm before normalising. */
static double m_orth(const gd_pattern *p, const double *mv, double *V, double *MV, int n, int m,
                     double *x, double *h, double *c)
{
    for (int pass = 0; pass < 2 && m > 0; pass++) {
        cblas_dgemv(CblasColMajor, CblasTrans, n, m, 1.0, MV, n, x, 1, 0.0, c, 1);
        cblas_dgemv(CblasColMajor, CblasNoTrans, n, m, -1.0, V, n, c, 1, 1.0, x, 1);
        if (h)
            for (int i = 0; i < m; i++)
                h[i] += c[i];
    }
    double *vm = V + (size_t)n * m, *mm = MV + (size_t)n * m;
    pat_mul(p, mv, x, mm);
    double nr = sqrt(fabs(cblas_ddot(n, x, 1, mm, 1)));
    double inv = nr > 0 ? 1.0 / nr : 0;
    for (int i = 0; i < n; i++) {
        vm[i] = x[i] * inv;
        mm[i] *= inv;
    }
    return nr;
}

/* T (P x P, leading dimension P) = the symmetric part of H's leading P x P section */
static void sym_section(const double *H, int ld, int P, double *T)
{
    for (int j = 0; j < P; j++)
        for (int i = 0; i < P; i++)
            T[i + (size_t)P * j] = 0.5 * (H[i + (size_t)ld * j] + H[j + (size_t)ld * i]);
}

typedef struct pj_cand {
    double re, im, mag;
    int col; /* eigenvector column of the companion problem (its real part) */
} pj_cand;

static int cmp_pj(const void *a, const void *b)
{
    const pj_cand *x = a, *y = b;
    if (x->mag != y->mag) return (x->mag > y->mag) - (x->mag < y->mag);
    return x->col - y->col;
}

gd_status gd_sparse_modes_projected(const gd_dynmat *a, const gd_splu_symbolic *sym,
                                    const gd_modal_options *opt, gd_sparse_ws *ws,
                                    gd_modal_result **out, gd_error *err)
{
    *out = NULL;
    const gd_system *sys = a->sys;
    const gd_pattern *p = &a->pat;
    int n = p->n, nnz = p->nnz, want = opt->nmodes;
    if (want <= 0 || opt->kind == GD_MODAL_UNDAMPED || sys->nmassless > 0 || ws->ks.ncv < 20 ||
        ws->ks.n != 2 * n)
        return GD_OK;
    double *k = ws->k, *d = ws->d;
    gd_dynmat_at_state(a, opt->speed, opt->law_state, k, d);
    if (!gd_pattern_symmetric(p, k)) return GD_OK;
    double s, g, rtol;
    gd_sparse_shift_auto(a, k, &s, &g, &rtol);
    int nu = want + PJ_GUARD;         /* undamped Ritz vectors wanted */
    int mmax = 3 * nu + 4 * PJ_BLOCK; /* basis columns at most */
    if (mmax > n) mmax = n;
    if (nu + 2 * PJ_BLOCK > mmax) return GD_OK;
    gd_status st = GD_OK;
    pj_ctx ctx = {0};
    ctx.sym = sym;
    double *zero = calloc((size_t)(nnz > 0 ? nnz : 1), sizeof *zero);
    double *V = malloc((size_t)n * mmax * sizeof *V), *MV = malloc((size_t)n * mmax * sizeof *MV);
    double *H = calloc((size_t)mmax * mmax, sizeof *H),
           *T = malloc((size_t)mmax * mmax * sizeof *T);
    double *x = malloc((size_t)5 * n * sizeof *x), *c = malloc((size_t)mmax * sizeof *c);
    double *w = malloc((size_t)2 * mmax * sizeof *w), *wold = NULL,
           *S = malloc((size_t)mmax * nu * sizeof *S);
    int *isup = malloc((size_t)2 * mmax * sizeof *isup);
    double *Phi = NULL, *KP = NULL, *DP = NULL, *A = NULL, *VR = NULL, *wr = NULL, *wi = NULL;
    double *RU = NULL;
    pj_cand *cd = NULL;
    gd_modal_result *prev = NULL, *res = NULL;
    if (w) wold = w + mmax;
    if (!zero || !V || !MV || !H || !T || !x || !c || !w || !S || !isup) goto nomem;
    ctx.x2 = x + n;
    ctx.y2 = x + 3 * n;
    int rc = gd_shift_invert_setup(&ctx.op, p, a->m, sym, -s, g, k, zero);
    if (rc < 0) goto nomem;
    if (rc > 0) goto done; /* K + s^2 M singular: Krylov-Schur words it */
    /* 1. block Lanczos from fixed pseudo-random vectors (deterministic) */
    unsigned int seed = 12345u;
    int m = 0;
    for (int b = 0; b < PJ_BLOCK; b++) {
        for (int i = 0; i < n; i++) {
            seed = seed * 1103515245u + 12345u;
            x[i] = (double)((seed >> 8) & 0xffff) / 65536.0 - 0.5;
        }
        pj_apply(&ctx, x, x + n); /* into the range of Op: no stiff start components */
        memcpy(x, x + n, (size_t)n * sizeof *x);
        if (!(m_orth(p, a->m, V, MV, n, m, x, NULL, c) > 0)) goto done;
        m++;
    }
    int P = 0, nev = 0, nold = 0;
    while (m < mmax) {
        /* column P of H: Op v_P = V h */
        pj_apply(&ctx, V + (size_t)n * P, x);
        double nr = m_orth(p, a->m, V, MV, n, m, x, H + (size_t)mmax * P, c);
        H[m + (size_t)mmax * P] = nr;
        m++;
        P++;
        if (P < want + PJ_BLOCK || (P - want) % 2) continue;
        /* the Ritz values (mu = 1 / (omega^2 + s^2)) of the symmetric P x P section: the
         * vectors (a far costlier eigensolve) only once the wanted values have settled */
        sym_section(H, mmax, P, T);
        if (LAPACKE_dsyev(LAPACK_COL_MAJOR, 'N', 'U', P, T, P, w)) goto done;
        int settled = nold == want;
        for (int j = 0; j < want; j++) {
            double v = w[P - want + j];
            settled &= fabs(v - wold[j]) <= PJ_SETTLE * fabs(v);
            wold[j] = v;
        }
        nold = want;
        if (!settled || P < nu) continue;
        sym_section(H, mmax, P, T);
        int nf = 0;
        if (LAPACKE_dsyevr(LAPACK_COL_MAJOR, 'V', 'I', 'U', P, T, P, 0, 0, P - nu + 1, P, 0.0, &nf,
                           w, S, P, isup) != 0 ||
            nf != nu)
            goto done;
        /* residual of Ritz pair j: || H[P..m, 0..P) s_j || (V M-orthonormal), for the
         * wanted ones (the guard vectors only enrich the projection) */
        int nconv = 0;
        for (int j = nu - want; j < nu; j++) {
            double r2 = 0;
            for (int i = P; i < m; i++) {
                double t = 0;
                for (int q = 0; q < P; q++)
                    t += H[i + (size_t)mmax * q] * S[q + (size_t)P * j];
                r2 += t * t;
            }
            nconv += sqrt(r2) <= PJ_RTOL * fabs(w[j]);
        }
        if (nconv == want) {
            nev = P;
            break;
        }
    }
    if (nev == 0) goto done; /* not converged within the basis: Krylov-Schur */
    /* Ritz vectors, largest mu first (dsyevr: ascending) */
    Phi = malloc((size_t)n * nu * sizeof *Phi);
    if (!Phi) goto nomem;
    for (int j = 0; j < nu; j++)
        cblas_dgemv(CblasColMajor, CblasNoTrans, n, nev, 1.0, V, n, S + (size_t)nev * (nu - 1 - j),
                    1, 0.0, Phi + (size_t)n * j, 1);
    /* rigid-body modes: omega below the automatic zero, refined into K's null space and
     * separated by motion type as gd_sparse_modes does */
    int r0 = 0;
    while (r0 < nu && sqrt(fabs(1.0 / w[nu - 1 - r0] - s * s)) <= rtol)
        r0++;
    int kr = 0;
    if (r0 > 0) {
        if (!(RU = malloc((size_t)n * r0 * sizeof *RU))) goto nomem;
        memcpy(RU, Phi, (size_t)n * r0 * sizeof *RU);
        kr = gd_rigid_null_sparse(a, sym, k, s * s, rtol * rtol, RU, r0);
        if (kr != r0) goto done;
        gd_rigid_separate(sys, RU, kr);
    }
    if (kr >= want) goto done; /* nothing elastic wanted: Krylov-Schur's simple case */
    /* 2. the damped problem on the elastic Ritz vectors: z = [y; lambda y / g2],
     * [0 g2 I; -Kp / g2 -Dp] z = lambda z */
    int ne = nu - kr, n2 = 2 * ne;
    double *Pe = Phi + (size_t)n * kr;
    KP = malloc(((size_t)n * ne + (size_t)2 * ne * ne) * sizeof *KP);
    DP = malloc((size_t)n * ne * sizeof *DP);
    A = calloc((size_t)n2 * n2, sizeof *A);
    VR = malloc((size_t)n2 * n2 * sizeof *VR);
    wr = malloc((size_t)2 * n2 * sizeof *wr);
    cd = malloc((size_t)n2 * sizeof *cd);
    if (!KP || !DP || !A || !VR || !wr || !cd) goto nomem;
    wi = wr + n2;
    for (int j = 0; j < ne; j++) {
        pat_mul(p, k, Pe + (size_t)n * j, KP + (size_t)n * j);
        pat_mul(p, d, Pe + (size_t)n * j, DP + (size_t)n * j);
    }
    double *Kp = KP + (size_t)n * ne, *Dp = Kp + (size_t)ne * ne;
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, ne, ne, n, 1.0, Pe, n, KP, n, 0.0, Kp, ne);
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, ne, ne, n, 1.0, Pe, n, DP, n, 0.0, Dp, ne);
    double g2 = sqrt(fabs(Kp[(size_t)(ne - 1) * (ne + 1)])) + 1.0;
    for (int j = 0; j < ne; j++) {
        A[j + (size_t)n2 * (ne + j)] = g2;
        for (int i = 0; i < ne; i++) {
            A[ne + i + (size_t)n2 * j] = -Kp[i + (size_t)ne * j] / g2;
            A[ne + i + (size_t)n2 * (ne + j)] = -Dp[i + (size_t)ne * j];
        }
    }
    if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', n2, A, n2, wr, wi, NULL, n2, VR, n2) != 0)
        goto done;
    int nc = 0;
    for (int j = 0; j < n2; j++) {
        if (wi[j] < 0) continue;
        cd[nc++] = (pj_cand){wr[j], wi[j], hypot(wr[j], wi[j]), j};
    }
    qsort(cd, (size_t)nc, sizeof *cd, cmp_pj);
    int we = want - kr; /* elastic modes wanted */
    if (nc < we) goto done;
    int ke = we;
    while (ke < nc && cd[ke].mag <= (1 + PJ_EDGE) * cd[we - 1].mag)
        ke++;
    if (ke < nc) ke++;
    for (int j = 0; j < ke; j++)
        if (!(cd[j].im > 0) || cd[j].mag <= 10 * rtol) goto done; /* overdamped, near-rigid */
    /* the projected modes as a result for the continuation: rigid-body modes first */
    prev = gd_modal_result_new(sys, kr + ke, 0);
    if (!prev) goto nomem;
    prev->damped = 1;
    prev->sparse = 1;
    prev->speed = opt->speed;
    gd_rigid_modes_fill(sys, opt->speed, prev, RU, kr);
    for (int j = 0; j < ke; j++) {
        gd_mode *md = &prev->modes[kr + j];
        gd_mode_set_lambda(md, cd[j].re, cd[j].im);
        double *re = prev->shape_re + (size_t)(kr + j) * n,
               *im = prev->shape_im + (size_t)(kr + j) * n;
        const double *yr = VR + (size_t)n2 * cd[j].col, *yi = yr + n2;
        cblas_dgemv(CblasColMajor, CblasNoTrans, n, ne, 1.0, Pe, n, yr, 1, 0.0, re, 1);
        if (cd[j].im > 0)
            cblas_dgemv(CblasColMajor, CblasNoTrans, n, ne, 1.0, Pe, n, yi, 1, 0.0, im, 1);
        gd_normalise_max(re, im, n);
    }
    /* 3. refined and vouched for on the full problem */
    int hard = 0;
    st = gd_sparse_track(a, sym, opt, prev, NULL, ws, &res, &hard, err);
    if (st) goto done;
    if (res && res->nmodes < want) { /* the continuation dropped a wanted mode */
        gd_modal_free(res);
        res = NULL;
    }
    if (res) res->nmodes = want; /* the guard band above the wanted modes left out */
    *out = res;
    res = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the sparse eigensolver");
done:
    gd_shift_invert_free(&ctx.op);
    gd_modal_free(prev);
    gd_modal_free(res);
    free(zero);
    free(V);
    free(MV);
    free(H);
    free(T);
    free(x);
    free(c);
    free(w);
    free(S);
    free(isup);
    free(Phi);
    free(KP);
    free(DP);
    free(A);
    free(VR);
    free(wr);
    free(cd);
    free(RU);
    return st;
}
