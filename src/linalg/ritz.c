/* Ritz values of an Arnoldi factorisation A V_m = V_m H_m + h_{m+1,m} v_{m+1} e_m^T and how
 * far each is converged: the pair (theta_j, V_m s_j), H_m s_j = theta_j s_j with |s_j| = 1,
 * leaves the residual |A V_m s_j - theta_j V_m s_j| = |h_{m+1,m}| |e_m^T s_j| (Saad, Numerical
 * Methods for Large Eigenvalue Problems, 2nd ed. 2011, Prop. 6.8), known without a product. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>

#include "linalg/linalg_impl.h"

int gd_ritz(const double *H, int ld, int m, double *re, double *im, double *res)
{
    if (m <= 0) return 0;
    double *Hs = malloc(2 * (size_t)m * m * sizeof *Hs);
    if (!Hs) return 2;
    double *S = Hs + (size_t)m * m, dummy[1];
    for (int c = 0; c < m; c++)
        for (int r = 0; r < m; r++)
            Hs[(size_t)c * m + r] = H[(size_t)c * ld + r];
    const double beta = fabs(H[(size_t)(m - 1) * ld + m]);
    /* dgeev normalises every right vector to unit length; a complex pair's vectors are the
     * columns (j, j + 1) as s = S_j +- i S_{j+1} */
    int rc = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', m, Hs, m, re, im, dummy, 1, S, m) ? 1 : 0;
    for (int j = 0; !rc && j < m; j++) {
        const double last = S[(size_t)j * m + m - 1];
        if (im[j] != 0.0 && j + 1 < m) {
            res[j] = res[j + 1] = beta * hypot(last, S[(size_t)(j + 1) * m + m - 1]);
            j++;
        } else {
            res[j] = beta * fabs(last);
        }
    }
    free(Hs);
    return rc;
}

int gd_ritz_verdict(const double *re, const double *im, const double *res, int n, double bound)
{
    int undecided = 0;
    for (int j = 0; j < n; j++) {
        const double a = hypot(re[j], im[j]);
        if (a - res[j] > bound) return 0; /* converged and outside: unstable */
        if (a + res[j] > bound) undecided = 1;
    }
    return undecided ? -1 : 1;
}
