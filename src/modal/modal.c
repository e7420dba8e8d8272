/* Modal analysis on dense matrices (LAPACK). Massless DOFs are condensed statically
 * (Guyan) when they carry no damping; the state-space form follows [MMT2018] Eqs. 5-13 but is
 * solved as the standard problem of the mass-normalised companion matrix, whose left
 * eigenvectors give the physical left eigenvectors directly. */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/modal.h"
#include "modal/modal_impl.h"

#define PI 3.14159265358979323846

void gd_modal_options_init(gd_modal_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->kind = GD_MODAL_AUTO;
    opt->want_left = 1;
}

static int is_symmetric(const double *A, int n)
{
    double mx = 0;
    for (size_t k = 0; k < (size_t)n * n; k++)
        if (fabs(A[k]) > mx) mx = fabs(A[k]);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < j; i++)
            if (fabs(A[i + (size_t)j * n] - A[j + (size_t)i * n]) > 1e-12 * mx) return 0;
    return 1;
}

static int any_nonzero(const double *A, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (A[k] != 0.0) return 1;
    return 0;
}

gd_status gd_modal_undamped_frequencies(const gd_system *sys, const gd_modal_options *opt,
                                        double **omega, int *n, gd_error *err)
{
    *omega = NULL;
    *n = 0;
    int N = sys->ndof;
    size_t nn = (size_t)N * N;
    double *M = malloc(nn * sizeof *M), *D = malloc(nn * sizeof *D), *K = malloc(nn * sizeof *K);
    double *Mr = NULL, *Kr = NULL, *w = NULL;
    gd_condense cond = {0};
    gd_status st = GD_OK;
    if (!M || !D || !K) goto nomem;
    gd_system_dense_at(sys, opt->speed, opt->law_state, M, D, K);
    if (!is_symmetric(K, N)) goto done;
    if ((st = gd_condense_setup(sys, K, NULL, &cond, err))) goto done;
    const int m = cond.nm;
    Mr = gd_condense_matrix(&cond, M, 0);
    Kr = gd_condense_matrix(&cond, K, 1);
    w = malloc((size_t)m * sizeof *w);
    if (!Mr || !Kr || !w) goto nomem;
    const double tol = gd_modal_zero_tol(Kr, Mr, m); /* gd_modal_undamped's rigid rule */
    lapack_int info = LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, 'N', 'U', m, Kr, m, Mr, m, w);
    if (info != 0) {
        /* the full solve words every failure (inf entries, a mass not positive definite) */
        gd_modal_result *r = NULL;
        gd_modal_options o = *opt;
        o.kind = GD_MODAL_UNDAMPED;
        st = gd_modal_solve_dense(sys, &o, &r, err);
        gd_modal_free(r);
        if (!st)
            st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "", "",
                              "the eigensolver did not converge (LAPACK info %d)", (int)info);
        goto done;
    }
    for (int j = 0; j < m; j++)
        w[j] = fabs(w[j]) <= tol ? -1.0 : sqrt(fabs(w[j]));
    *omega = w;
    *n = m;
    w = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce the model size",
                      "out of memory for dense %d x %d matrices", N, N);
done:
    gd_condense_free(&cond);
    free(M);
    free(D);
    free(K);
    free(Mr);
    free(Kr);
    free(w);
    return st;
}

gd_status gd_modal_solve_dense(const gd_system *sys, const gd_modal_options *opt,
                               gd_modal_result **out, gd_error *err)
{
    *out = NULL;
    int N = sys->ndof;
    size_t nn = (size_t)N * N;
    double *M = malloc(nn * sizeof *M), *D = malloc(nn * sizeof *D), *K = malloc(nn * sizeof *K);
    gd_condense cond = {0};
    gd_status st = GD_OK;
    if (!M || !D || !K) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce the model size",
                          "out of memory for dense %d x %d matrices", N, N);
        goto done;
    }
    gd_system_dense_at(sys, opt->speed, opt->law_state, M, D, K);
    int damped = opt->kind == GD_MODAL_DAMPED || (opt->kind == GD_MODAL_AUTO && any_nonzero(D, nn));
    if (opt->kind == GD_MODAL_UNDAMPED) memset(D, 0, nn * sizeof *D);
    if (!is_symmetric(K, N)) damped = 1; /* cross-coupled bearings: general problem */
    if ((st = gd_condense_setup(sys, K, damped ? D : NULL, &cond, err))) goto done;
    if (damped)
        st = gd_modal_state_space(sys, opt, &cond, M, D, K, out, err);
    else
        st = gd_modal_undamped(sys, opt, &cond, M, K, out, err);
done:
    gd_condense_free(&cond);
    free(M);
    free(D);
    free(K);
    return st;
}
