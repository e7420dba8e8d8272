/* Refinement of the kept modes on the sparse quadratic problem P(s) = s^2 M + s D + K:
 * the dense eigensolution of the first-order (companion) form is accurate to about
 * eps |lambda_max| in each eigenvalue, which near a lightly damped resonance leaves
 * 1e-7 of the receptance (w - Im lambda is then of the size of Re lambda). Two steps of
 * two-sided inverse iteration at the current eigenvalue with the Newton (two-sided
 * Rayleigh functional) update lambda -= v^T P u / v^T P' u ([Ruhe1973] Sec. 3;
 * [TisseurMeerbergen2001] Sec. 5) bring eigenvalue and both vectors to round-off; each step is one
 * complex KLU factorisation and a solve with it and one with its transpose. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "condense/condense_impl.h"
#include "linalg/linalg_impl.h"
#include "system/system_impl.h"

/* y = Z x (tr: Z^T x) for complex values z on the pattern. */
static void zmul(const gd_pattern *p, const double complex *z, const double complex *x,
                 double complex *y, int tr)
{
    memset(y, 0, (size_t)p->n * sizeof *y);
    for (int j = 0; j < p->n; j++)
        for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++) {
            int i = p->rowind[q];
            if (tr)
                y[j] += z[q] * x[i];
            else
                y[i] += z[q] * x[j];
        }
}

static double complex dotu(const double complex *a, const double complex *b, int n)
{
    double complex s = 0;
    for (int i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

gd_status gd_condense_refine(const gd_system *sys, double speed, int nm, double complex *lam,
                             double complex *U, double complex *V, int iters, double *worst_step,
                             gd_error *err)
{
    gd_dynmat a;
    gd_splu_symbolic sym;
    *worst_step = 0;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    if ((st = gd_splu_analyze(&a.pat, &sym, err))) {
        gd_dynmat_free(&a);
        return st;
    }
    int n = a.pat.n, nnz = a.pat.nnz;
    double *k = malloc((size_t)nnz * sizeof *k), *d = malloc((size_t)nnz * sizeof *d);
    double complex *z = malloc((size_t)nnz * sizeof *z), *zp = malloc((size_t)nnz * sizeof *zp);
    double complex *t = malloc((size_t)n * sizeof *t), *t2 = malloc((size_t)n * sizeof *t2);
    if (!k || !d || !z || !zp || !t || !t2) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    gd_dynmat_at(&a, speed, k, d);
    for (int j = 0; j < nm; j++) {
        double complex *u = U + (size_t)j * n, *v = V + (size_t)j * n, s = lam[j];
        for (int it = 0; it < iters; it++) {
            for (int q = 0; q < nnz; q++) {
                z[q] = k[q] + s * d[q] + s * s * a.m[q];
                zp[q] = 2 * s * a.m[q] + d[q];
            }
            gd_splu lu;
            int rc = gd_splu_factor(&lu, &a.pat, &sym, (const double *)z, 1, 1);
            if (rc < 0 || !lu.num) { /* out of memory, or an exactly zero pivot */
                gd_splu_free(&lu);
                if (rc < 0) st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
                break; /* keep the pair as it is */
            }
            /* near-singular factors are what inverse iteration needs (rc 1 is fine) */
            zmul(&a.pat, zp, u, t, 0);
            klu_z_solve(sym.sym, lu.num, n, 1, (double *)t, &lu.common);
            zmul(&a.pat, zp, v, t2, 1);
            klu_z_tsolve(sym.sym, lu.num, n, 1, (double *)t2, 0, &lu.common);
            gd_splu_free(&lu);
            double mx = 0;
            int im = 0;
            for (int i = 0; i < n; i++)
                if (cabs(t[i]) > mx) {
                    mx = cabs(t[i]);
                    im = i;
                }
            if (!(mx > 0) || !isfinite(mx)) break;
            double complex sc = 1.0 / t[im];
            for (int i = 0; i < n; i++)
                t[i] *= sc;
            /* Newton step on v^T P(s) u = 0 */
            zmul(&a.pat, z, t, u, 0); /* u as scratch: P(s) u_new */
            double complex num = dotu(t2, u, n);
            zmul(&a.pat, zp, t, u, 0);
            double complex den = dotu(t2, u, n);
            if (!(cabs(den) > 0)) break;
            double complex ds = num / den;
            s -= ds;
            memcpy(u, t, (size_t)n * sizeof *u);
            memcpy(v, t2, (size_t)n * sizeof *v);
            *worst_step = fmax(*worst_step, cabs(ds) / cabs(s));
            if (it > 0 && cabs(ds) <= 1e-15 * cabs(s)) break;
        }
        if (st) break;
        if (cimag(lam[j]) == 0) s = creal(s); /* a real mode stays real */
        lam[j] = s;
        /* v^T P'(lambda) u = 1 */
        for (int q = 0; q < nnz; q++)
            zp[q] = 2 * s * a.m[q] + d[q];
        zmul(&a.pat, zp, u, t, 0);
        double complex nv = dotu(v, t, n);
        for (int i = 0; i < n; i++)
            v[i] /= nv;
    }
done:
    free(k);
    free(d);
    free(z);
    free(zp);
    free(t);
    free(t2);
    gd_splu_symbolic_free(&sym);
    gd_dynmat_free(&a);
    return st;
}
