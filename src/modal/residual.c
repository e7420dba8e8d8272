/* The relative residual of each computed eigenpair (gd_mode.residual): the backward
 * error of (lambda, u) for the quadratic eigenproblem P(lambda) u = (lambda^2 M +
 * lambda D + K) u = 0 with the norms of the products in place of the matrices' norms
 * ([Tisseur2000] Thm. 1, with |M u| for ||M|| |u|, which makes it the relative error of
 * omega for an exact shape of an undamped mode), on the sparse matrices at the result's
 * speed; and its rounding floor, eps times the size of the terms that cancel. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

/* y = A x, |A| |x| into ya (if not NULL), for values v on the CSC pattern */
static void spmv(const gd_pattern *p, const double *v, const double *xr, const double *xi,
                 const double *xa, double *yr, double *yi, double *ya)
{
    memset(yr, 0, (size_t)p->n * sizeof *yr);
    memset(yi, 0, (size_t)p->n * sizeof *yi);
    if (ya) memset(ya, 0, (size_t)p->n * sizeof *ya);
    for (int j = 0; j < p->n; j++)
        for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++) {
            int i = p->rowind[q];
            yr[i] += v[q] * xr[j];
            yi[i] += v[q] * xi[j];
            if (ya) ya[i] += fabs(v[q]) * xa[j];
        }
}

static double nrm(const double *a, const double *b, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += a[i] * a[i] + (b ? b[i] * b[i] : 0);
    return sqrt(s);
}

void gd_mode_residual(const gd_dynmat *a, const double *k, const double *d, gd_mode *md,
                      const double *ur, const double *ui, double *w)
{
    int n = a->pat.n;
    double *ua = w, *mr = w + n, *mi = w + 2 * n, *ma = w + 3 * n, *dr = w + 4 * n, *di = w + 5 * n,
           *da = w + 6 * n, *kr = w + 7 * n, *ki = w + 8 * n, *ka = w + 9 * n, *pr = w + 10 * n,
           *pi = w + 11 * n, *pa = w + 12 * n;
    for (int i = 0; i < n; i++)
        ua[i] = hypot(ur[i], ui[i]);
    double lr = md->rigid_body ? 0 : md->lambda_re, li = md->rigid_body ? 0 : md->lambda_im;
    double l2r = lr * lr - li * li, l2i = 2 * lr * li, al = hypot(lr, li);
    spmv(&a->pat, a->m, ur, ui, ua, mr, mi, ma);
    spmv(&a->pat, k, ur, ui, ua, kr, ki, ka);
    if (d)
        spmv(&a->pat, d, ur, ui, ua, dr, di, da);
    else
        memset(dr, 0, (size_t)3 * n * sizeof *dr); /* dr, di, da */
    for (int i = 0; i < n; i++) {
        pr[i] = l2r * mr[i] - l2i * mi[i] + lr * dr[i] - li * di[i] + kr[i];
        pi[i] = l2r * mi[i] + l2i * mr[i] + lr * di[i] + li * dr[i] + ki[i];
        pa[i] = al * al * ma[i] + al * da[i] + ka[i];
    }
    double num = nrm(pr, pi, n), terms = nrm(pa, NULL, n);
    double den =
        md->rigid_body ? terms : al * al * nrm(mr, mi, n) + al * nrm(dr, di, n) + nrm(kr, ki, n);
    md->residual = den > 0 ? num / den : 0;
    md->residual_floor = den > 0 ? DBL_EPSILON * terms / den : DBL_EPSILON;
}

gd_status gd_modal_residuals_on(const gd_dynmat *a, const double *k, const double *d,
                                gd_modal_result *r, double *worst, double *worst_floor)
{
    int n = a->pat.n;
    if (worst) *worst = 0;
    if (worst_floor) *worst_floor = 0;
    if (n != r->ndof) return GD_OK; /* not this system's result */
    double *w = malloc((size_t)13 * n * sizeof *w);
    if (!w) return GD_ENOMEM;
    for (int j = 0; j < r->nmodes; j++) {
        gd_mode *md = &r->modes[j];
        gd_mode_residual(a, k, d, md, r->shape_re + (size_t)j * n, r->shape_im + (size_t)j * n, w);
        if (!md->rigid_body) {
            if (worst && md->residual > *worst) *worst = md->residual;
            if (worst_floor && md->residual_floor > *worst_floor) *worst_floor = md->residual_floor;
        }
    }
    free(w);
    return GD_OK;
}

gd_status gd_modal_residuals(const gd_system *sys, gd_modal_result *r, const double *law_state,
                             gd_error *err)
{
    gd_dynmat a;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    double *k = malloc((size_t)(a.pat.nnz > 0 ? a.pat.nnz : 1) * sizeof *k);
    double *d = malloc((size_t)(a.pat.nnz > 0 ? a.pat.nnz : 1) * sizeof *d);
    if (!k || !d) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    } else {
        gd_dynmat_at_state(&a, r->speed, law_state, k, d);
        if (gd_modal_residuals_on(&a, k, r->damped ? d : NULL, r, NULL, NULL))
            st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    free(k);
    free(d);
    gd_dynmat_free(&a);
    return st;
}
