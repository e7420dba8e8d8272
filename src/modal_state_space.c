/* Damped and gyroscopic modes: (lambda^2 M + lambda D + K) u = 0 with left vectors
 * v^T (lambda^2 M + lambda D + K) = 0, normalised so v^T (2 lambda M + D) u = 1, which
 * is 004's bi-orthonormality phi^T A psi = 1 (Eqs. 9-13) written for u and v.
 *
 * With M = L L^T, p = L^T u and the companion matrix
 *     A = [0, I; -L^-1 K L^-T, -L^-1 D L^-T]
 * the right eigenvector of A is z = [p; lambda p]. A left eigenvector w (w^T A =
 * lambda w^T) has w = [lambda pv + Dt pv; pv] with v = L^-T pv, and w^T z =
 * v^T (2 lambda M + D) u, so the normalisation costs one dot product per mode. */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal_internal.h"

#define PI 3.14159265358979323846

typedef struct candidate {
    int col;       /* LAPACK column of the eigenvalue (first of a pair) */
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

/* Column j of a dgeev eigenvector matrix as a complex vector (re, im). */
static void eigvec(const double *V, int ld, int n2, int col, int is_pair, double *re, double *im)
{
    for (int i = 0; i < n2; i++) {
        re[i] = V[i + (size_t)col * ld];
        im[i] = is_pair ? V[i + (size_t)(col + 1) * ld] : 0.0;
    }
}

/* x <- L^-T x for a complex vector stored as two real vectors. */
static void solve_lt(const double *L, int n, double *re, double *im)
{
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
    double *wr = malloc((size_t)n2 * sizeof *wr), *wi = malloc((size_t)n2 * sizeof *wi);
    double *VR = malloc((size_t)n2 * n2 * sizeof *VR);
    double *VL = opt->want_left ? malloc((size_t)n2 * n2 * sizeof *VL) : NULL;
    candidate *cand = malloc((size_t)n2 * sizeof *cand);
    double *zr = malloc((size_t)n2 * sizeof *zr), *zi = malloc((size_t)n2 * sizeof *zi);
    double *yr = malloc((size_t)n2 * sizeof *yr), *yi = malloc((size_t)n2 * sizeof *yi);
    double *work = malloc((size_t)(N + 8) * sizeof *work);
    gd_modal_result *res = NULL;
    if (!L || !Kt || !Dt || !A || !wr || !wi || !VR || (opt->want_left && !VL) || !cand || !zr ||
        !zi || !yr || !yi || !work)
        goto nomem;

    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', n, L, n) != 0) {
        st = gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "",
                          "check for negative or zero masses and inertias",
                          "the mass matrix is not positive definite");
        goto done;
    }
    /* K~ = L^-1 K L^-T, D~ = L^-1 D L^-T */
    double *mats[2] = {Kt, Dt};
    for (int t = 0; t < 2; t++) {
        cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, n, n, 1.0,
                    L, n, mats[t], n);
        cblas_dtrsm(CblasColMajor, CblasRight, CblasLower, CblasTrans, CblasNonUnit, n, n, 1.0,
                    L, n, mats[t], n);
    }
    for (int j = 0; j < n; j++) {
        A[j + (size_t)(n + j) * n2] = 1.0;
        for (int i = 0; i < n; i++) {
            A[n + i + (size_t)j * n2] = -Kt[i + (size_t)j * n];
            A[n + i + (size_t)(n + j) * n2] = -Dt[i + (size_t)j * n];
        }
    }
    lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, opt->want_left ? 'V' : 'N', 'V', n2, A, n2,
                                    wr, wi, VL, n2, VR, n2);
    if (info != 0) {
        st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "", "",
                          "the eigensolver did not converge (LAPACK info %d)", (int)info);
        goto done;
    }
    double lmax = 0;
    for (int j = 0; j < n2; j++)
        if (hypot(wr[j], wi[j]) > lmax) lmax = hypot(wr[j], wi[j]);
    double rtol = 1e-6 * lmax;
    int ncand = 0, nrigid_real = 0;
    for (int j = 0; j < n2; j++) {
        if (wi[j] < 0) continue; /* conjugate of the previous column */
        int rigid = hypot(wr[j], wi[j]) <= rtol;
        if (rigid && wi[j] == 0 && (nrigid_real++ % 2)) continue; /* one per double root */
        cand[ncand++] = (candidate){j, wr[j], wi[j], rigid};
    }
    qsort(cand, (size_t)ncand, sizeof *cand, cmp_candidate);
    int k = opt->nmodes > 0 && opt->nmodes < ncand ? opt->nmodes : ncand;
    res = gd_modal_result_new(sys, k, opt->want_left);
    if (!res) goto nomem;
    res->damped = 1;
    res->speed = opt->speed;
    for (int m = 0; m < k; m++) {
        const candidate *cd = &cand[m];
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
        eigvec(VR, n2, n2, cd->col, pair, zr, zi);
        double *re = res->shape_re + (size_t)m * N, *im = res->shape_im + (size_t)m * N;
        /* u = L^-T p from the top half of z */
        double *pr = yr, *pi = yi;
        memcpy(pr, zr, (size_t)n * sizeof *pr);
        memcpy(pi, zi, (size_t)n * sizeof *pi);
        solve_lt(L, n, pr, pi);
        gd_condense_expand(c, pr, re, 0, work);
        gd_condense_expand(c, pi, im, 0, work);
        double complex alpha = gd_normalise_max(re, im, N);
        gd_mode_finish(sys, opt->speed, md, re, im,
                       res->energy_by_component + (size_t)m * sys->ncomponents);
        if (opt->want_left && !md->rigid_body) {
            /* w = conj(y): LAPACK's left vectors satisfy y^H A = lambda y^H */
            eigvec(VL, n2, n2, cd->col, pair, yr, yi);
            for (int i = 0; i < n2; i++) yi[i] = -yi[i];
            double complex s = 0;
            for (int i = 0; i < n2; i++) s += (yr[i] + I * yi[i]) * (zr[i] + I * zi[i]);
            double *vr = yr + n, *vi = yi + n; /* pv, bottom half */
            solve_lt(L, n, vr, vi);
            double *lre = res->left_re + (size_t)m * N, *lim = res->left_im + (size_t)m * N;
            gd_condense_expand(c, vr, lre, 1, work);
            gd_condense_expand(c, vi, lim, 1, work);
            double complex f = alpha / s;
            for (int i = 0; i < N; i++) {
                double complex v = (lre[i] + I * lim[i]) * f;
                lre[i] = creal(v);
                lim[i] = cimag(v);
            }
        }
    }
    *out = res;
    res = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce the model size",
                      "out of memory in the state-space modal analysis (%d states)", n2);
done:
    gd_modal_free(res);
    free(L);
    free(Kt);
    free(Dt);
    free(A);
    free(wr);
    free(wi);
    free(VR);
    free(VL);
    free(cand);
    free(zr);
    free(zi);
    free(yr);
    free(yi);
    free(work);
    return st;
}
