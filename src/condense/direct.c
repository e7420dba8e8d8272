/* The reference receptance at the coordinates by the direct sparse solve: at each
 * frequency K - w^2 M + i w D factored once (KLU, the symbolic analysis shared: as
 * gd_frf's direct method) and solved for the coordinates' vectors as right-hand sides. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/condense.h"
#include "linalg/linalg_impl.h"
#include "system/system_impl.h"

gd_status gd_condense_direct(const gd_system *sys, const gd_condense_coords *c, double speed,
                             int nfreq, const double *w, double *H, gd_error *err)
{
    int nc = c->n;
    for (int e = 0; e < c->nnz; e++)
        if (c->dof[e] < 0 || c->dof[e] >= sys->ndof)
            return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "coordinates",
                                "build the coordinates on this system",
                                "a coordinate names DOF %d, outside the %d DOFs", c->dof[e],
                                sys->ndof);
    gd_dynmat a;
    gd_splu_symbolic sym;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    if ((st = gd_splu_analyze(&a.pat, &sym, err))) {
        gd_dynmat_free(&a);
        return st;
    }
    int n = a.pat.n;
    double *k = malloc((size_t)a.pat.nnz * sizeof *k), *d = malloc((size_t)a.pat.nnz * sizeof *d);
    double *z = malloc((size_t)2 * a.pat.nnz * sizeof *z);
    double *q = malloc((size_t)2 * n * (nc > 0 ? nc : 1) * sizeof *q);
    if (!k || !d || !z || !q) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    gd_dynmat_at(&a, speed, k, d);
    for (int f = 0; f < nfreq; f++) {
        double *h = H + (size_t)2 * nc * nc * f;
        gd_splu lu;
        int rc = gd_dynmat_factor_at(&a, &sym, k, d, w[f], z, &lu);
        if (rc < 0) {
            gd_splu_free(&lu);
            st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
            goto done;
        }
        if (rc) {
            for (int i = 0; i < 2 * nc * nc; i++)
                h[i] = NAN;
            gd_splu_free(&lu);
            continue;
        }
        memset(q, 0, (size_t)2 * n * nc * sizeof *q);
        for (int b = 0; b < nc; b++)
            for (int e = c->start[b]; e < c->start[b + 1]; e++)
                q[2 * ((size_t)b * n + c->dof[e])] += c->a[e];
        gd_splu_solve(&lu, &sym, n, nc, q);
        gd_splu_free(&lu);
        for (int b = 0; b < nc; b++)
            for (int a2 = 0; a2 < nc; a2++) {
                double re = 0, im = 0;
                for (int e = c->start[a2]; e < c->start[a2 + 1]; e++) {
                    re += c->a[e] * q[2 * ((size_t)b * n + c->dof[e])];
                    im += c->a[e] * q[2 * ((size_t)b * n + c->dof[e]) + 1];
                }
                h[2 * (a2 + (size_t)b * nc)] = re;
                h[2 * (a2 + (size_t)b * nc) + 1] = im;
            }
    }
done:
    free(k);
    free(d);
    free(z);
    free(q);
    gd_splu_symbolic_free(&sym);
    gd_dynmat_free(&a);
    return st;
}

gd_status gd_condense_direct_recover(const gd_system *sys, const gd_condense_coords *c,
                                     double speed, double w, const double *u, double *q,
                                     gd_error *err)
{
    int N = sys->ndof;
    for (int e = 0; e < c->nnz; e++)
        if (c->dof[e] < 0 || c->dof[e] >= N)
            return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "coordinates",
                                "build the coordinates on this system",
                                "a coordinate names DOF %d, outside the %d DOFs", c->dof[e], N);
    gd_dynmat a;
    gd_splu_symbolic sym;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    if ((st = gd_splu_analyze(&a.pat, &sym, err))) {
        gd_dynmat_free(&a);
        return st;
    }
    double *k = malloc((size_t)a.pat.nnz * sizeof *k), *d = malloc((size_t)a.pat.nnz * sizeof *d);
    double *z = malloc((size_t)2 * a.pat.nnz * sizeof *z);
    if (!k || !d || !z) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    gd_dynmat_at(&a, speed, k, d);
    gd_splu lu;
    int rc = gd_dynmat_factor_at(&a, &sym, k, d, w, z, &lu);
    if (rc) {
        gd_splu_free(&lu);
        st = rc < 0 ? gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory")
                    : gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "frequency",
                                   "give a frequency above zero for a model free in torsion",
                                   "the dynamic stiffness is singular at %g rad/s", w);
        goto done;
    }
    memset(q, 0, (size_t)2 * N * sizeof *q);
    for (int b = 0; b < c->n; b++)
        for (int e = c->start[b]; e < c->start[b + 1]; e++) {
            q[2 * c->dof[e]] += c->a[e] * u[2 * b];
            q[2 * c->dof[e] + 1] += c->a[e] * u[2 * b + 1];
        }
    gd_splu_solve(&lu, &sym, N, 1, q);
    gd_splu_free(&lu);
done:
    free(k);
    free(d);
    free(z);
    gd_splu_symbolic_free(&sym);
    gd_dynmat_free(&a);
    return st;
}
