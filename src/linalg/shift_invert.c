/* The shift-invert operator of the quadratic eigenproblem in first-order form.
 * (lambda^2 M + lambda D + K) u = 0 with z = [u; lambda u / g] is A z = lambda B z,
 * A = [0 gI; -K -gD], B = [I 0; 0 gM]; its eigenvalues mu = 1 / (lambda - sigma) of
 * Op = (A - sigma B)^-1 B are largest for lambda nearest sigma. Solving
 * (A - sigma B) y = B x row by row: -sigma y1 + g y2 = x1 and
 * -K y1 - g (D + sigma M) y2 = g M x2, so
 *     P(sigma) y1 = -(M (g x2 + sigma x1) + D x1),  y2 = (x1 + sigma y1) / g,
 * with P(sigma) = sigma^2 M + sigma D + K: one sparse n x n factorisation serves the
 * whole 2n-state problem. The scale g (a frequency of the wanted range) balances the
 * two halves of the eigenvectors [u; lambda u / g]: unscaled, the velocity half is
 * |lambda| times larger, the displacement half is lost in the norms, and the Ritz
 * values of a converged residual are measured 100 times less accurate. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"

int gd_shift_invert_setup(gd_shift_invert *op, const gd_pattern *a, const double *m,
                          const gd_splu_symbolic *s, double sigma, double scale, const double *k,
                          const double *d)
{
    memset(op, 0, sizeof *op);
    op->a = a;
    op->n = a->n;
    op->sigma = sigma;
    op->scale = scale;
    op->m = m;
    op->d = d;
    op->work = malloc((size_t)(2 * a->n + 1) * sizeof *op->work);
    op->r = malloc((size_t)(a->n + 1) * sizeof *op->r);
    double *p = malloc((size_t)(a->nnz > 0 ? a->nnz : 1) * sizeof *p);
    if (!op->work || !op->r || !p) {
        free(p);
        return -1;
    }
    for (int i = 0; i < a->nnz; i++)
        p[i] = sigma * sigma * m[i] + sigma * d[i] + k[i];
    /* R P R with R = diag(|P_ii|^-1/2) has a unit diagonal whatever the units of the
     * DOFs (N/m beside N m/rad), so KLU needs no row scaling of its own: the solve
     * costs two vector products instead of n divisions, and the pivot-ratio
     * singularity test compares like with like */
    for (int j = 0; j < a->n; j++) {
        int q = a->diag[j];
        double djj = q >= 0 ? fabs(p[q]) : 0;
        op->r[j] = djj > 0 && isfinite(djj) ? 1.0 / sqrt(djj) : 1.0;
    }
    for (int j = 0; j < a->n; j++)
        for (int q = a->colptr[j]; q < a->colptr[j + 1]; q++)
            p[q] *= op->r[a->rowind[q]] * op->r[j];
    int rc = gd_splu_factor(&op->lu, a, s, p, 0, 0);
    free(p);
    return rc;
}

void gd_shift_invert_apply(gd_shift_invert *op, const gd_splu_symbolic *s, const double *x,
                           double *y)
{
    int n = op->n;
    const double *x1 = x, *x2 = x + n;
    double *y1 = y, *y2 = y + n, *t = op->work, *u = op->work + n;
    double g = op->scale, sg = op->sigma, ig = 1.0 / g;
    const double *r = op->r;
    /* y1 = -(M (g x2 + sigma x1) + D x1), then P^-1 = R (R P R)^-1 R in place */
    for (int i = 0; i < n; i++)
        u[i] = -(g * x2[i] + sg * x1[i]);
    for (int i = 0; i < n; i++)
        t[i] = -x1[i];
    gd_pattern_mul2(op->a, op->m, u, op->d, t, y1);
    for (int i = 0; i < n; i++)
        y1[i] *= r[i];
    gd_splu_solve(&op->lu, s, n, 1, y1);
    for (int i = 0; i < n; i++)
        y1[i] *= r[i];
    for (int i = 0; i < n; i++)
        y2[i] = (x1[i] + sg * y1[i]) * ig;
}

void gd_shift_invert_free(gd_shift_invert *op)
{
    gd_splu_free(&op->lu);
    free(op->work);
    free(op->r);
    op->work = op->r = NULL;
}
