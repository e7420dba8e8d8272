/* The condensed receptance and the full response recovered from it, harmonic by
 * harmonic (docs/condense.md): H_c(w) = sum_kept [c b^T/(iw - lambda) + conj] - Rc Rc^T/w^2
 * + G ([MMT2018] Eqs. 14-15 on the coordinates; [PetrovEwins2003] Sec. 2).  */
#include <math.h>
#include <string.h>

#include "condense/condense_impl.h"

void gd_condense_receptance(const gd_condensation *c, double w, double *H, double *est)
{
    int nc = c->nc;
    double complex s = I * w;
    double complex *h = (double complex *)(void *)H;
    for (int b = 0; b < nc; b++)
        for (int a = 0; a < nc; a++)
            h[a + (size_t)b * nc] = c->G[a + (size_t)b * nc];
    for (int k = 0; k < c->nm; k++) {
        double complex p = 1.0 / (s - c->lam[k]), pc = c->pair[k] ? 1.0 / (s - conj(c->lam[k])) : 0;
        const double complex *cu = c->Cm + (size_t)k * nc, *bv = c->Bm + (size_t)k * nc;
        for (int b = 0; b < nc; b++) {
            double complex x = bv[b] * p, xc = conj(bv[b]) * pc;
            for (int a = 0; a < nc; a++)
                h[a + (size_t)b * nc] += cu[a] * x + conj(cu[a]) * xc;
        }
    }
    if (w > 0)
        for (int r = 0; r < c->nr; r++) {
            const double *rc = c->Rc + (size_t)r * nc;
            for (int b = 0; b < nc; b++)
                for (int a = 0; a < nc; a++)
                    h[a + (size_t)b * nc] -= rc[a] * rc[b] / (w * w);
        }
    if (est) {
        double wd = c->info.first_discarded, z = c->info.zeta_discarded;
        double complex num = w * w - 2 * I * z * wd * w, den = wd * wd - w * w + 2 * I * z * wd * w;
        *est = c->info.ndiscarded == 0 ? 0.0
               : cabs(den) > 0         ? c->info.residual * cabs(num) / cabs(den)
                                       : INFINITY;
    }
}

void gd_condense_recover(const gd_condensation *c, double w, const double *u, double *q)
{
    int N = c->N, nc = c->nc;
    const double complex *uc = (const double complex *)(const void *)u;
    double complex *qc = (double complex *)(void *)q;
    double complex s = I * w;
    for (int i = 0; i < N; i++) {
        double complex x = 0;
        for (int b = 0; b < nc; b++)
            x += c->Xres[i + (size_t)b * N] * uc[b];
        qc[i] = x;
    }
    for (int k = 0; k < c->nm; k++) {
        const double complex *bv = c->Bm + (size_t)k * nc, *u_k = c->U + (size_t)k * N;
        double complex e = 0, ec = 0;
        for (int b = 0; b < nc; b++) {
            e += bv[b] * uc[b];
            ec += conj(bv[b]) * uc[b];
        }
        e /= s - c->lam[k];
        ec = c->pair[k] ? ec / (s - conj(c->lam[k])) : 0;
        for (int i = 0; i < N; i++)
            qc[i] += u_k[i] * e + conj(u_k[i]) * ec;
    }
    if (w > 0)
        for (int r = 0; r < c->nr; r++) {
            const double *rr = c->R + (size_t)r * N, *rc = c->Rc + (size_t)r * nc;
            double complex a = 0;
            for (int b = 0; b < nc; b++)
                a += rc[b] * uc[b];
            a /= -(w * w);
            for (int i = 0; i < N; i++)
                qc[i] += rr[i] * a;
        }
}
