/* LSFD, least-squares frequency domain ([Peeters2004] Sec. 2.3): with the poles l_r
 * fixed, every FRF is linear in its residues,
 *   H(w) = sum_r [A_r / (iw - l_r) + conj(A_r) / (iw - conj(l_r))] + U + L / w^2,
 * A_r complex, U and L real residual terms for the modes above and below the band.
 * One real least-squares problem (real and imaginary parts of every line as rows) with
 * every FRF a right-hand side; columns scaled to unit norm for its conditioning. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>

#include "ema/ema_impl.h"

gd_status gd_ema_lsfd(int nfrf, const gd_td_function *const *frfs, int k0, int k1, gd_ema_result *r,
                      gd_error *err)
{
    int m = r->nmodes, ncol = 2 * m + 2, nl = k1 - k0, nrow = 2 * nl;
    r->residue_re = calloc((size_t)nfrf * (m ? m : 1), sizeof(double));
    r->residue_im = calloc((size_t)nfrf * (m ? m : 1), sizeof(double));
    if (!r->residue_re || !r->residue_im)
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    if (m == 0) return GD_OK;
    if (nrow < ncol)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--band", "widen the band",
                            "%d lines cannot fit %d modes", nl, m);
    double *A = malloc((size_t)nrow * ncol * sizeof *A);
    double *B = malloc((size_t)nrow * nfrf * sizeof *B);
    double *scale = malloc((size_t)ncol * sizeof *scale);
    if (!A || !B || !scale) {
        free(A), free(B), free(scale);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    const double *fr = frfs[0]->freq_hz;
    for (int k = 0; k < nl; k++) {
        double w = 2 * M_PI * fr[k0 + k];
        for (int j = 0; j < m; j++) {
            double lr = r->modes[j].lambda_re, li = r->modes[j].lambda_im;
            /* p = 1/(iw - l), q = 1/(iw - conj l) */
            double ar = -lr, ai = w - li, d1 = ar * ar + ai * ai;
            double pr = ar / d1, pi = -ai / d1;
            double br = -lr, bi = w + li, d2 = br * br + bi * bi;
            double qr = br / d2, qi = -bi / d2;
            /* A = a + ib: a (p + q) + b i (p - q) */
            A[k + (2 * j) * nrow] = pr + qr;
            A[nl + k + (2 * j) * nrow] = pi + qi;
            A[k + (2 * j + 1) * nrow] = -(pi - qi);
            A[nl + k + (2 * j + 1) * nrow] = pr - qr;
        }
        A[k + (2 * m) * nrow] = 1;
        A[nl + k + (2 * m) * nrow] = 0;
        A[k + (2 * m + 1) * nrow] = 1 / (w * w);
        A[nl + k + (2 * m + 1) * nrow] = 0;
        for (int o = 0; o < nfrf; o++) {
            B[k + o * nrow] = frfs[o]->re[k0 + k];
            B[nl + k + o * nrow] = frfs[o]->im[k0 + k];
        }
    }
    for (int c = 0; c < ncol; c++) {
        double s = 0;
        for (int k = 0; k < nrow; k++)
            s += A[k + c * nrow] * A[k + c * nrow];
        scale[c] = s > 0 ? 1 / sqrt(s) : 1;
        for (int k = 0; k < nrow; k++)
            A[k + c * nrow] *= scale[c];
    }
    lapack_int info = LAPACKE_dgels(LAPACK_COL_MAJOR, 'N', nrow, ncol, nfrf, A, nrow, B, nrow);
    gd_status st = GD_OK;
    if (info)
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "LSFD", "fewer modes or a wider band",
                          "LSFD least squares failed (LAPACK info %d)", (int)info);
    else
        for (int o = 0; o < nfrf; o++)
            for (int j = 0; j < m; j++) {
                r->residue_re[o + j * nfrf] = B[2 * j + o * nrow] * scale[2 * j];
                r->residue_im[o + j * nfrf] = B[2 * j + 1 + o * nrow] * scale[2 * j + 1];
            }
    free(A), free(B), free(scale);
    return st;
}
