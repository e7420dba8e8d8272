/* The shift-invert operator of the quadratic eigenproblem in first-order form.
 * (lambda^2 M + lambda D + K) u = 0 with z = [u; lambda u] is A z = lambda B z,
 * A = [0 I; -K -D], B = [I 0; 0 M]; its eigenvalues mu = 1 / (lambda - sigma) of
 * Op = (A - sigma B)^-1 B are largest for lambda nearest sigma. Solving
 * (A - sigma B) y = B x row by row: -sigma y1 + y2 = x1 and
 * -K y1 - (D + sigma M) y2 = M x2, so
 *     P(sigma) y1 = -(M x2 + (D + sigma M) x1),  y2 = x1 + sigma y1,
 * with P(sigma) = sigma^2 M + sigma D + K: one sparse n x n factorisation serves the
 * whole 2n-state problem. */
#include <stdlib.h>
#include <string.h>

#include "sweep_internal.h"

int gd_shift_invert_setup(gd_shift_invert *op, const gd_dynmat *a, const gd_splu_symbolic *s,
                          double sigma, const double *k, const double *d)
{
    memset(op, 0, sizeof *op);
    op->a = a;
    op->n = a->n;
    op->sigma = sigma;
    op->m = a->m;
    op->d = d;
    op->work = malloc((size_t)(3 * a->n + 1) * sizeof *op->work);
    double *p = malloc((size_t)(a->nnz > 0 ? a->nnz : 1) * sizeof *p);
    if (!op->work || !p) {
        free(p);
        return -1;
    }
    for (int i = 0; i < a->nnz; i++)
        p[i] = sigma * sigma * a->m[i] + sigma * d[i] + k[i];
    int rc = gd_splu_factor(&op->lu, a, s, p, 0);
    free(p);
    return rc;
}

void gd_shift_invert_apply(gd_shift_invert *op, const gd_splu_symbolic *s, const double *x,
                           double *y)
{
    int n = op->n;
    const double *x1 = x, *x2 = x + n;
    double *y1 = y, *y2 = y + n, *t = op->work, *u = op->work + n;
    /* t = M x2 + D x1 + sigma M x1 = M (x2 + sigma x1) + D x1 */
    for (int i = 0; i < n; i++)
        u[i] = x2[i] + op->sigma * x1[i];
    gd_dynmat_mul(op->a, op->m, u, t);
    gd_dynmat_mul(op->a, op->d, x1, u);
    for (int i = 0; i < n; i++)
        y1[i] = -(t[i] + u[i]);
    gd_splu_solve(&op->lu, s, n, 1, y1);
    for (int i = 0; i < n; i++)
        y2[i] = x1[i] + op->sigma * y1[i];
}

void gd_shift_invert_free(gd_shift_invert *op)
{
    gd_splu_free(&op->lu);
    free(op->work);
    op->work = NULL;
}
