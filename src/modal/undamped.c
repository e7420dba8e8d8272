/* Undamped modes: K u = w^2 M u, symmetric-definite (LAPACK dsygvd, or dsygvx for the
 * lowest few). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"
#include "linalg/linalg_impl.h"

double gd_modal_zero_tol(const double *Kr, const double *Mr, int n)
{
    double wscale2 = 0; /* the largest diagonal ratio K_ii / M_ii */
    for (int i = 0; i < n; i++) {
        double r = Kr[i + (size_t)i * n] / Mr[i + (size_t)i * n];
        if (r > wscale2) wscale2 = r;
    }
    return 1e-12 * wscale2;
}

gd_status gd_modal_undamped(const gd_system *sys, const gd_modal_options *opt, const gd_condense *c,
                            const double *M, const double *K, gd_modal_result **out, gd_error *err)
{
    int n = c->nm, N = sys->ndof;
    int k = opt->nmodes > 0 && opt->nmodes < n ? opt->nmodes : n;
    double *Mr = gd_condense_matrix(c, M, 0), *Kr = gd_condense_matrix(c, K, 1);
    double *w = malloc((size_t)n * sizeof *w);
    double *Z = NULL;
    double *work = malloc((size_t)(3 * N + 8) * sizeof *work);
    gd_modal_result *res = gd_modal_result_new(sys, k, opt->want_left);
    gd_status st = GD_OK;
    if (!Mr || !Kr || !w || !work || !res) goto nomem;

    const double tol = gd_modal_zero_tol(Kr, Mr, n); /* before dsygvd overwrites them */
    lapack_int info;
    if (k == n) {
        info = LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, 'V', 'U', n, Kr, n, Mr, n, w);
        Z = Kr;
    } else {
        Z = malloc((size_t)n * (size_t)k * sizeof *Z);
        lapack_int *ifail = malloc((size_t)n * sizeof *ifail);
        if (!Z || !ifail) {
            free(ifail);
            goto nomem;
        }
        lapack_int found;
        info = LAPACKE_dsygvx(LAPACK_COL_MAJOR, 1, 'V', 'I', 'U', n, Kr, n, Mr, n, 0, 0, 1, k, 0.0,
                              &found, w, Z, n, ifail);
        free(ifail);
    }
    if (info < 0) { /* an argument refused: inf or NaN entries (issue 38 L3, as state_space.c) */
        st = gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "",
                          "check the bearings' and laws' values for ones so large their "
                          "stiffness or damping overflows",
                          "the matrices at speed %g rad/s hold inf or NaN entries", opt->speed);
        goto done;
    }
    if (info != 0) {
        st = gd_error_set(err, info > n ? GD_EINPUT : GD_ENUMERIC, sys->model->file, 0, 0, "",
                          info > n ? "check for negative or zero masses and inertias" : "",
                          info > n ? "the mass matrix is not positive definite"
                                   : "the eigensolver did not converge (LAPACK info %d)",
                          (int)info);
        goto done;
    }
    double *um = malloc((size_t)n * sizeof *um);
    double *Mu = malloc((size_t)N * sizeof *Mu);
    if (!um || !Mu) {
        free(um);
        free(Mu);
        goto nomem;
    }
    res->damped = 0;
    res->speed = opt->speed;
    /* the rigid-body modes (contiguous: ascending eigenvalues) are any M-orthonormal
       basis of the null space of K: rotated so that each moves one way */
    int r0 = 0, nrigid = 0;
    while (r0 < k && w[r0] < -tol)
        r0++;
    while (r0 + nrigid < k && fabs(w[r0 + nrigid]) <= tol)
        nrigid++;
    for (int j = r0; j < r0 + nrigid; j++) {
        memcpy(um, Z + (size_t)j * n, (size_t)n * sizeof *um);
        gd_condense_expand(c, um, res->shape_re + (size_t)j * N, 0, work);
    }
    gd_rigid_separate(sys, res->shape_re + (size_t)r0 * N, nrigid);
    for (int j = 0; j < k; j++) {
        gd_mode *md = &res->modes[j];
        double lam = w[j];
        md->rigid_body = j >= r0 && j < r0 + nrigid;
        double om = md->rigid_body ? 0.0 : sqrt(fabs(lam));
        md->omega_n = om;
        md->frequency_hz = om / (2.0 * 3.14159265358979323846);
        if (lam < -tol) {
            /* negative stiffness: lambda = +-sqrt(-w^2) is real, a divergence, not an
             * oscillation; reported by its growing root as the state-space solver does */
            md->unstable = md->overdamped = 1;
            md->lambda_re = om;
            md->lambda_im = md->omega_d = 0;
            md->damping_ratio = -1;
            md->log_decrement = NAN;
        } else {
            md->lambda_re = 0;
            md->lambda_im = md->omega_d = om;
        }
        double *re = res->shape_re + (size_t)j * N, *im = res->shape_im + (size_t)j * N;
        if (!md->rigid_body) {
            memcpy(um, Z + (size_t)j * n, (size_t)n * sizeof *um);
            gd_condense_expand(c, um, re, 0, work);
        }
        gd_normalise_max(re, im, N);
        gd_mode_finish(sys, opt->speed, md, re, im,
                       res->energy_by_component + (size_t)j * sys->ncomponents);
        if (opt->want_left && !md->rigid_body && om > 0) {
            /* D = 0: v = u / (2 lambda u^T M u) satisfies v^T (2 lambda M) u = 1; for
             * lambda = i w that is -i u / (2 w u^T M u), for a real lambda real */
            gd_csc_mul(&sys->M, re, Mu);
            double mr = 0;
            for (int i = 0; i < N; i++)
                mr += re[i] * Mu[i];
            for (int i = 0; i < N; i++) {
                double v = re[i] / (2.0 * om * mr);
                res->left_re[i + (size_t)j * N] = md->overdamped ? v : 0;
                res->left_im[i + (size_t)j * N] = md->overdamped ? 0 : -v;
            }
        }
    }
    free(um);
    free(Mu);
    *out = res;
    res = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in modal analysis");
done:
    if (Z != Kr) free(Z);
    free(Mr);
    free(Kr);
    free(w);
    free(work);
    gd_modal_free(res);
    return st;
}
