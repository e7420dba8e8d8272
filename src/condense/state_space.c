/* The reduced model in the time domain on the condensation's basis (docs/condense.md):
 * each kept mode eta' = lambda eta + b^T u in real form (a conjugate pair as the real and
 * imaginary parts of eta, its output 2 Re(c eta)), each rigid mode a'' = r_c^T u, and the
 * discarded modes as the static feedthrough y += G u: the 'modal + residual flexibility'
 * model ([CraigKurdila2006]; [KrackGross2019] Sec. 3.4 for its use under nonlinear forces). */
#include <stdlib.h>
#include <string.h>

#include "condense/condense_impl.h"

int gd_condense_build_lti(gd_condensation *c)
{
    int nc = c->nc, ns = 2 * c->nr;
    for (int k = 0; k < c->nm; k++)
        ns += c->pair[k] ? 2 : 1;
    c->ns = ns;
    size_t n1 = (size_t)(ns > 0 ? ns : 1);
    c->A = calloc(n1 * n1, sizeof *c->A);
    c->B = calloc(n1 * nc, sizeof *c->B);
    c->C = calloc((size_t)nc * n1, sizeof *c->C);
    if (!c->A || !c->B || !c->C) return 1;
#define A_(i, j) c->A[(i) + (size_t)(j)*ns]
#define B_(i, j) c->B[(i) + (size_t)(j)*ns]
#define C_(i, j) c->C[(i) + (size_t)(j)*nc]
    int p = 0;
    for (int k = 0; k < c->nm; k++) {
        double lr = creal(c->lam[k]), li = cimag(c->lam[k]);
        const double complex *cu = c->Cm + (size_t)k * nc, *bv = c->Bm + (size_t)k * nc;
        if (c->pair[k]) {
            A_(p, p) = lr;
            A_(p, p + 1) = -li;
            A_(p + 1, p) = li;
            A_(p + 1, p + 1) = lr;
            for (int a = 0; a < nc; a++) {
                B_(p, a) = creal(bv[a]);
                B_(p + 1, a) = cimag(bv[a]);
                C_(a, p) = 2 * creal(cu[a]);
                C_(a, p + 1) = -2 * cimag(cu[a]);
            }
            p += 2;
        } else { /* a real (overdamped) mode: real vectors */
            A_(p, p) = lr;
            for (int a = 0; a < nc; a++) {
                B_(p, a) = creal(bv[a]);
                C_(a, p) = creal(cu[a]);
            }
            p++;
        }
    }
    for (int r = 0; r < c->nr; r++) {
        A_(p, p + 1) = 1.0;
        for (int a = 0; a < nc; a++) {
            B_(p + 1, a) = c->Rc[a + (size_t)r * nc];
            C_(a, p) = c->Rc[a + (size_t)r * nc];
        }
        p += 2;
    }
#undef A_
#undef B_
#undef C_
    return 0;
}

void gd_condense_state_space(const gd_condensation *c, gd_condense_lti *out)
{
    out->nstates = c->ns;
    out->ncoords = c->nc;
    out->A = c->A;
    out->B = c->B;
    out->C = c->C;
    out->G = c->G;
}

void gd_condense_recover_state(const gd_condensation *c, const double *x, const double *u,
                               double *q)
{
    int N = c->N, nc = c->nc;
    memset(q, 0, (size_t)N * sizeof *q);
    for (int b = 0; b < nc; b++)
        for (int i = 0; i < N; i++)
            q[i] += c->Xres[i + (size_t)b * N] * u[b];
    int p = 0;
    for (int k = 0; k < c->nm; k++) {
        const double complex *uk = c->U + (size_t)k * N;
        if (c->pair[k]) {
            double x1 = x[p], x2 = x[p + 1];
            for (int i = 0; i < N; i++)
                q[i] += 2 * (creal(uk[i]) * x1 - cimag(uk[i]) * x2);
            p += 2;
        } else {
            for (int i = 0; i < N; i++)
                q[i] += creal(uk[i]) * x[p];
            p++;
        }
    }
    for (int r = 0; r < c->nr; r++) {
        const double *rr = c->R + (size_t)r * N;
        for (int i = 0; i < N; i++)
            q[i] += rr[i] * x[p];
        p += 2;
    }
}
