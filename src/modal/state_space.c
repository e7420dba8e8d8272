/* Damped and gyroscopic modes: (lambda^2 M + lambda D + K) u = 0 with left vectors
 * v^T (lambda^2 M + lambda D + K) = 0, normalised so v^T (2 lambda M + D) u = 1, which
 * is [MMT2018]'s bi-orthonormality phi^T A psi = 1 (Eqs. 9-13) written for u and v.
 *
 * With M = L L^T, p = L^T u and the companion matrix
 *     A = [0, I; -L^-1 K L^-T, -L^-1 D L^-T]
 * the right eigenvector of A is z = [p; lambda p]. A left eigenvector w (w^T A =
 * lambda w^T) has w = [lambda pv + Dt pv; pv] with v = L^-T pv, and w_i^T z_r =
 * v_i^T ((lambda_i + lambda_r) M + D) u_r, so bi-orthonormalising the state vectors
 * (including within clusters of repeated eigenvalues, where LAPACK's vectors are not
 * mutually bi-orthogonal) bi-orthonormalises u and v.
 *
 * All eigenvalues come from the Hessenberg QR algorithm; when only the lowest few modes
 * are wanted, their vectors come from inverse iteration on the Hessenberg matrix
 * (dhsein), which avoids computing the other 2n - k vectors. */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

#define PI 3.14159265358979323846

typedef struct candidate {
    int col;       /* index of the eigenvalue (first of a conjugate pair) */
    double re, im; /* eigenvalue */
    int rigid;
} candidate;

static int cmp_candidate(const void *a, const void *b)
{
    const candidate *x = a, *y = b;
    if (x->rigid != y->rigid) return y->rigid - x->rigid;
    double ax = hypot(x->re, x->im), ay = hypot(y->re, y->im);
    if (ax != ay) return (ax > ay) - (ax < ay);
    return x->col - y->col;
}

/* Eigenvalues and, for the selected ones, right (and left) eigenvectors of the
 * n2 x n2 matrix A (destroyed). vcol[j] gives the first column of eigenvalue j's
 * vector in VR/VL (-1 when not computed). */
typedef struct eig {
    int n2;
    double *wr, *wi;
    double *VR, *VL; /* n2 x ncols */
    int *vcol;
} eig;

static void eig_free(eig *e)
{
    free(e->wr);
    free(e->wi);
    free(e->VR);
    free(e->VL);
    free(e->vcol);
    memset(e, 0, sizeof *e);
}

/* All vectors at once (dgeev): cheapest when many modes are wanted. */
static lapack_int eig_all(double *A, eig *e, int want_left)
{
    int n2 = e->n2;
    e->VR = malloc((size_t)n2 * n2 * sizeof *e->VR);
    e->VL = want_left ? malloc((size_t)n2 * n2 * sizeof *e->VL) : NULL;
    if (!e->VR || (want_left && !e->VL)) return -1000;
    lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, want_left ? 'V' : 'N', 'V', n2, A, n2, e->wr,
                                    e->wi, e->VL, n2, e->VR, n2);
    for (int j = 0; j < n2; j++)
        e->vcol[j] = j;
    return info;
}

typedef struct hess {
    double *A; /* Hessenberg reflectors (lower part) from dgehrd */
    double *H; /* the Hessenberg matrix */
    double *tau, *scale;
    lapack_int ilo, ihi;
} hess;

/* Balanced Hessenberg form and all eigenvalues (no vectors). */
static lapack_int eig_values(double *A, eig *e, hess *h)
{
    int n2 = e->n2;
    h->A = A;
    h->tau = malloc((size_t)n2 * sizeof *h->tau);
    h->scale = malloc((size_t)n2 * sizeof *h->scale);
    h->H = malloc((size_t)n2 * n2 * sizeof *h->H);
    double *T = malloc((size_t)n2 * n2 * sizeof *T);
    if (!h->tau || !h->scale || !h->H || !T) {
        free(T);
        return -1000;
    }
    lapack_int info = LAPACKE_dgebal(LAPACK_COL_MAJOR, 'B', n2, A, n2, &h->ilo, &h->ihi, h->scale);
    if (!info) info = LAPACKE_dgehrd(LAPACK_COL_MAJOR, n2, h->ilo, h->ihi, A, n2, h->tau);
    if (!info) {
        for (int j = 0; j < n2; j++)
            for (int i = 0; i < n2; i++)
                h->H[i + (size_t)j * n2] = i > j + 1 ? 0.0 : A[i + (size_t)j * n2];
        memcpy(T, h->H, (size_t)n2 * n2 * sizeof *T);
        info = LAPACKE_dhseqr(LAPACK_COL_MAJOR, 'E', 'N', n2, h->ilo, h->ihi, T, n2, e->wr, e->wi,
                              NULL, 1);
    }
    free(T);
    return info;
}

/* Vectors of the selected eigenvalues by inverse iteration, back-transformed. */
static lapack_int eig_selected(eig *e, hess *h, const int *want, int want_left)
{
    int n2 = e->n2, ncols = 0;
    lapack_logical *sel = calloc((size_t)n2, sizeof *sel);
    if (!sel) return -1000;
    for (int j = 0; j < n2; j++)
        if (want[j]) {
            sel[j] = 1;
            e->vcol[j] = ncols;
            ncols += e->wi[j] > 0 ? 2 : 1;
        }
    /* zeroed: LAPACKE checks the (unused, initv = 'N') inputs for NaN */
    e->VR = calloc((size_t)n2 * (ncols ? ncols : 1), sizeof *e->VR);
    e->VL = want_left ? calloc((size_t)n2 * (ncols ? ncols : 1), sizeof *e->VL) : NULL;
    lapack_int *fl = malloc((size_t)(ncols ? ncols : 1) * sizeof *fl);
    lapack_int *fr = malloc((size_t)(ncols ? ncols : 1) * sizeof *fr);
    lapack_int info = -1000, m = 0;
    if (e->VR && (!want_left || e->VL) && fl && fr) {
        info = LAPACKE_dhsein(LAPACK_COL_MAJOR, want_left ? 'B' : 'R', 'Q', 'N', sel, n2, h->H, n2,
                              e->wr, e->wi, e->VL, n2, e->VR, n2, ncols, &m, fl, fr);
        /* info > 0: some vectors did not converge; the rest are usable but we refuse */
        if (!info)
            info = LAPACKE_dormhr(LAPACK_COL_MAJOR, 'L', 'N', n2, m, h->ilo, h->ihi, h->A, n2,
                                  h->tau, e->VR, n2);
        if (!info)
            info = LAPACKE_dgebak(LAPACK_COL_MAJOR, 'B', 'R', n2, h->ilo, h->ihi, h->scale, m,
                                  e->VR, n2);
        if (!info && want_left)
            info = LAPACKE_dormhr(LAPACK_COL_MAJOR, 'L', 'N', n2, m, h->ilo, h->ihi, h->A, n2,
                                  h->tau, e->VL, n2);
        if (!info && want_left)
            info = LAPACKE_dgebak(LAPACK_COL_MAJOR, 'B', 'L', n2, h->ilo, h->ihi, h->scale, m,
                                  e->VL, n2);
    }
    free(sel);
    free(fl);
    free(fr);
    return info;
}

/* Complex vector of eigenvalue j from V (re, im). */
static void eigvec(const eig *e, const double *V, int j, double complex *z)
{
    int c = e->vcol[j], n2 = e->n2, pair = e->wi[j] > 0;
    for (int i = 0; i < n2; i++)
        z[i] = V[i + (size_t)c * n2] + (pair ? I * V[i + (size_t)(c + 1) * n2] : 0.0);
}

/* W <- W P^-T with P_ab = w_a^T z_b over each cluster of (nearly) equal eigenvalues,
 * so that w_a^T z_b = delta_ab. Returns 0, or 1 if a cluster is singular. */
static int bi_orthonormalise(double complex *Z, double complex *W, const candidate *cd, int k,
                             int n2, double lmax)
{
    int *done = calloc((size_t)k, sizeof *done), bad = 0;
    int *members = malloc((size_t)k * sizeof *members);
    lapack_complex_double *P = malloc((size_t)k * k * sizeof *P);
    lapack_complex_double *X = malloc((size_t)k * n2 * sizeof *X);
    lapack_int *piv = malloc((size_t)k * sizeof *piv);
    if (!done || !members || !P || !X || !piv) {
        bad = 1;
        goto out;
    }
    for (int a = 0; a < k; a++) {
        if (done[a] || cd[a].rigid) continue;
        int c = 0;
        double complex la = cd[a].re + I * cd[a].im;
        for (int b = a; b < k; b++) {
            double complex lb = cd[b].re + I * cd[b].im;
            if (!done[b] && !cd[b].rigid && cabs(la - lb) <= 1e-8 * lmax) {
                members[c++] = b;
                done[b] = 1;
            }
        }
        /* P (c x c) and X = W^T (c x n2) for the members: solve P^T W'^T... i.e.
         * W' = W P^-T  <=>  P W'^T = W^T */
        for (int x = 0; x < c; x++)
            for (int y = 0; y < c; y++) {
                double complex s = 0;
                const double complex *w = W + (size_t)members[x] * n2,
                                     *z = Z + (size_t)members[y] * n2;
                for (int i = 0; i < n2; i++)
                    s += w[i] * z[i];
                P[x + (size_t)y * c] = s;
            }
        for (int x = 0; x < c; x++)
            for (int i = 0; i < n2; i++)
                X[x + (size_t)i * c] = W[(size_t)members[x] * n2 + i];
        if (LAPACKE_zgesv(LAPACK_COL_MAJOR, c, n2, P, c, piv, X, c) != 0) {
            bad = 1;
            continue;
        }
        for (int x = 0; x < c; x++)
            for (int i = 0; i < n2; i++)
                W[(size_t)members[x] * n2 + i] = X[x + (size_t)i * c];
    }
out:
    free(done);
    free(members);
    free(P);
    free(X);
    free(piv);
    return bad;
}

/* u = L^-T p for a complex vector, into separate real and imaginary parts. */
static void physical(const double *L, int n, const double complex *p, double *re, double *im)
{
    for (int i = 0; i < n; i++) {
        re[i] = creal(p[i]);
        im[i] = cimag(p[i]);
    }
    cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, n, L, n, re, 1);
    cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, n, L, n, im, 1);
}

gd_status gd_modal_state_space(const gd_system *sys, const gd_modal_options *opt,
                               const gd_condense *c, const double *M, const double *D,
                               const double *K, gd_modal_result **out, gd_error *err)
{
    int n = c->nm, N = sys->ndof, n2 = 2 * n;
    gd_status st = GD_OK;
    double *L = gd_condense_matrix(c, M, 0), *Kt = gd_condense_matrix(c, K, 1);
    double *Dt = gd_condense_matrix(c, D, 0);
    double *A = calloc((size_t)n2 * n2, sizeof *A);
    eig e = {n2,   malloc((size_t)n2 * sizeof(double)), malloc((size_t)n2 * sizeof(double)), NULL,
             NULL, malloc((size_t)n2 * sizeof(int))};
    hess h = {0};
    candidate *cand = malloc((size_t)n2 * sizeof *cand);
    int *want = calloc((size_t)n2, sizeof *want);
    double *vr = malloc((size_t)n * sizeof *vr), *vi = malloc((size_t)n * sizeof *vi);
    double *work = malloc((size_t)(N + 8) * sizeof *work);
    double complex *Z = NULL, *W = NULL;
    double *R = NULL, *RU = NULL; /* rigid-body modes: null basis, full shapes */
    gd_modal_result *res = NULL;
    if (!L || !Kt || !Dt || !A || !e.wr || !e.wi || !e.vcol || !cand || !want || !vr || !vi ||
        !work)
        goto nomem;
    for (int j = 0; j < n2; j++)
        e.vcol[j] = -1;

    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', n, L, n) != 0) {
        st = gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "",
                          "check for negative or zero masses and inertias",
                          "the mass matrix is not positive definite");
        goto done;
    }
    /* K~ = L^-1 K L^-T, D~ = L^-1 D L^-T */
    double *mats[2] = {Kt, Dt};
    for (int t = 0; t < 2; t++) {
        cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, n, n, 1.0, L,
                    n, mats[t], n);
        cblas_dtrsm(CblasColMajor, CblasRight, CblasLower, CblasTrans, CblasNonUnit, n, n, 1.0, L,
                    n, mats[t], n);
    }
    for (int j = 0; j < n; j++) {
        A[j + (size_t)(n + j) * n2] = 1.0;
        for (int i = 0; i < n; i++) {
            A[n + i + (size_t)j * n2] = -Kt[i + (size_t)j * n];
            A[n + i + (size_t)(n + j) * n2] = -Dt[i + (size_t)j * n];
        }
    }
    /* inverse iteration pays off when few of the 2n vectors are wanted */
    int few = opt->nmodes > 0 && 4 * opt->nmodes < n2 && n2 > 64;
    lapack_int info = few ? eig_values(A, &e, &h) : eig_all(A, &e, opt->want_left);
    if (info == -1000) goto nomem;
    if (info != 0) goto noconv;

    double lmax = 0;
    for (int j = 0; j < n2; j++)
        if (hypot(e.wr[j], e.wi[j]) > lmax) lmax = hypot(e.wr[j], e.wi[j]);
    double rtol = 1e-6 * lmax;
    int ncand = 0, nrigid_real = 0;
    for (int j = 0; j < n2; j++) {
        if (e.wi[j] < 0) continue; /* conjugate of the previous eigenvalue */
        int rigid = hypot(e.wr[j], e.wi[j]) <= rtol;
        if (rigid && e.wi[j] == 0 && (nrigid_real++ % 2)) continue; /* one per double root */
        cand[ncand++] = (candidate){j, e.wr[j], e.wi[j], rigid};
    }
    qsort(cand, (size_t)ncand, sizeof *cand, cmp_candidate);
    /* rigid-body modes: the null space of K~ (rigid_modes.c), in place of the
       vectors of the defective zero cluster; r = 0 (none found) keeps the
       eigensolver's. |lambda| <= rtol for a rigid root is K~'s |sigma| <= rtol^2. */
    int nrc = 0, r = 0;
    while (nrc < ncand && cand[nrc].rigid)
        nrc++;
    if (nrc > 0 && (r = gd_null_space(Kt, n, rtol * rtol, &R)) < 0) goto nomem;
    const candidate *cs = r > 0 ? cand + nrc : cand;
    int ncs = r > 0 ? ncand - nrc : ncand;
    int k = opt->nmodes > 0 && opt->nmodes < r + ncs ? opt->nmodes : r + ncs;
    int kr = k < r ? k : r, ke = k - kr;
    if (few) {
        for (int m = 0; m < ke; m++)
            want[cs[m].col] = 1;
        info = eig_selected(&e, &h, want, opt->want_left);
        if (info == -1000) goto nomem;
        if (info != 0) goto noconv;
    }
    Z = malloc(((size_t)ke * n2 + 1) * sizeof *Z);
    W = opt->want_left ? malloc(((size_t)ke * n2 + 1) * sizeof *W) : NULL;
    res = gd_modal_result_new(sys, k, opt->want_left);
    if (!Z || (opt->want_left && !W) || !res) goto nomem;
    for (int m = 0; m < ke; m++) {
        eigvec(&e, e.VR, cs[m].col, Z + (size_t)m * n2);
        if (opt->want_left) {
            /* w = conj(y): LAPACK's left vectors satisfy y^H A = lambda y^H */
            double complex *w = W + (size_t)m * n2;
            eigvec(&e, e.VL, cs[m].col, w);
            for (int i = 0; i < n2; i++)
                w[i] = conj(w[i]);
        }
    }
    if (opt->want_left && bi_orthonormalise(Z, W, cs, ke, n2, lmax)) {
        st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "",
                          "the model may have defective (repeated, coupled) modes",
                          "left and right eigenvectors could not be bi-orthonormalised");
        goto done;
    }
    res->damped = 1;
    res->speed = opt->speed;
    if (r > 0) {
        /* u = L^-T p of each null vector, expanded, separated by motion type; the
           first kr of them are reported */
        RU = malloc((size_t)N * r * sizeof *RU);
        if (!RU) goto nomem;
        for (int j = 0; j < r; j++) {
            memcpy(vr, R + (size_t)j * n, (size_t)n * sizeof *vr);
            cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, n, L, n, vr, 1);
            gd_condense_expand(c, vr, RU + (size_t)j * N, 0, work);
        }
        gd_rigid_separate(sys, RU, r);
        gd_rigid_modes_fill(sys, opt->speed, res, RU, kr);
    }
    for (int mi = 0; mi < ke; mi++) {
        const candidate *cd = &cs[mi];
        int m = kr + mi;
        gd_mode *md = &res->modes[m];
        int pair = cd->im > 0;
        md->rigid_body = cd->rigid;
        double mag = hypot(cd->re, cd->im);
        if (!md->rigid_body) {
            md->lambda_re = cd->re;
            md->lambda_im = cd->im;
            md->omega_n = mag;
            md->omega_d = cd->im;
            md->frequency_hz = mag / (2 * PI);
            md->damping_ratio = -cd->re / mag;
            md->overdamped = !pair;
            md->unstable = cd->re > 1e-9 * lmax;
            double z = md->damping_ratio;
            md->log_decrement = pair && fabs(z) < 1 ? 2 * PI * z / sqrt(1 - z * z) : NAN;
        }
        double *re = res->shape_re + (size_t)m * N, *im = res->shape_im + (size_t)m * N;
        physical(L, n, Z + (size_t)mi * n2, vr, vi); /* top half of z is p */
        gd_condense_expand(c, vr, re, 0, work);
        gd_condense_expand(c, vi, im, 0, work);
        double complex alpha = gd_normalise_max(re, im, N);
        gd_mode_finish(sys, opt->speed, md, re, im,
                       res->energy_by_component + (size_t)m * sys->ncomponents);
        if (opt->want_left && !md->rigid_body) {
            /* v = L^-T pv from the bottom half of w, scaled with u */
            physical(L, n, W + (size_t)mi * n2 + n, vr, vi);
            double *lre = res->left_re + (size_t)m * N, *lim = res->left_im + (size_t)m * N;
            gd_condense_expand(c, vr, lre, 1, work);
            gd_condense_expand(c, vi, lim, 1, work);
            for (int i = 0; i < N; i++) {
                double complex v = (lre[i] + I * lim[i]) * alpha;
                lre[i] = creal(v);
                lim[i] = cimag(v);
            }
        }
    }
    *out = res;
    res = NULL;
    goto done;
noconv:
    /* LAPACK's info < 0 names an argument it refused: here a matrix with inf or NaN
     * entries (a viscosity of 1e308 overflows the bearings' coefficients), an input
     * error the user can fix, not a solver failure (issue 38 L3) */
    if (info < 0)
        st = gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "",
                          "check the bearings' and laws' values for ones so large their "
                          "stiffness or damping overflows",
                          "the matrices at speed %g rad/s hold inf or NaN entries", opt->speed);
    else
        st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "", "",
                          "the eigensolver did not converge (LAPACK info %d)", (int)info);
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce the model size",
                      "out of memory in the state-space modal analysis (%d states)", n2);
done:
    gd_modal_free(res);
    eig_free(&e);
    free(h.tau);
    free(h.scale);
    free(h.H);
    free(L);
    free(Kt);
    free(Dt);
    free(A);
    free(cand);
    free(want);
    free(vr);
    free(vi);
    free(work);
    free(Z);
    free(W);
    free(R);
    free(RU);
    return st;
}
