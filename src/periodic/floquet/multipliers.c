/* Floquet multipliers ordered as every method reports them: largest modulus first (the
 * bifurcation search ranks by it). Insertion sort, stable: ties keep the order LAPACK or
 * Krylov-Schur gave them, so the reports stay bit for bit the same. */
#include <math.h>

#include "periodic/periodic_impl.h"

void gd_hb_sort_multipliers(double *mu_re, double *mu_im, int n)
{
    for (int i = 1; i < n; i++) {
        double re = mu_re[i], im = mu_im[i], a = hypot(re, im);
        int j = i;
        for (; j > 0 && hypot(mu_re[j - 1], mu_im[j - 1]) < a; j--) {
            mu_re[j] = mu_re[j - 1];
            mu_im[j] = mu_im[j - 1];
        }
        mu_re[j] = re;
        mu_im[j] = im;
    }
}
