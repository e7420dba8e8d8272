#include "linalg/linalg_impl.h"

#include <cs.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int gd_trip_add(gd_trip *t, int i, int j, double x)
{
    if (x == 0.0) return 0;
    if (t->n == t->cap) {
        int cap = t->cap ? 2 * t->cap : 256;
        int *ni = realloc(t->i, (size_t)cap * sizeof *ni);
        if (!ni) return 1;
        t->i = ni;
        int *nj = realloc(t->j, (size_t)cap * sizeof *nj);
        if (!nj) return 1;
        t->j = nj;
        double *nx = realloc(t->x, (size_t)cap * sizeof *nx);
        if (!nx) return 1;
        t->x = nx;
        t->cap = cap;
    }
    t->i[t->n] = i;
    t->j[t->n] = j;
    t->x[t->n] = x;
    t->n++;
    return 0;
}

void gd_trip_free(gd_trip *t)
{
    free(t->i);
    free(t->j);
    free(t->x);
    memset(t, 0, sizeof *t);
}

int gd_trip_compress(const gd_trip *t, const int *map, int n, gd_csc *out)
{
    memset(out, 0, sizeof *out);
    cs *T = cs_spalloc(n, n, t->n > 0 ? t->n : 1, 1, 1);
    if (!T) return 1;
    for (int k = 0; k < t->n; k++) {
        int a = map[t->i[k]], b = map[t->j[k]];
        if (a >= 0 && b >= 0 && !cs_entry(T, a, b, t->x[k])) {
            cs_spfree(T);
            return 1;
        }
    }
    cs *C = cs_compress(T);
    cs_spfree(T);
    if (!C || !cs_dupl(C) || cs_dropzeros(C) < 0) {
        cs_spfree(C);
        return 1;
    }
    /* transposing twice sorts the row indices within each column */
    cs *Ct = cs_transpose(C, 1);
    cs_spfree(C);
    cs *A = Ct ? cs_transpose(Ct, 1) : NULL;
    cs_spfree(Ct);
    if (!A) return 1;
    out->n = n;
    out->colptr = malloc((size_t)(n + 1) * sizeof *out->colptr);
    int nnz = A->p[n];
    out->rowind = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *out->rowind);
    out->values = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *out->values);
    if (!out->colptr || !out->rowind || !out->values) {
        cs_spfree(A);
        gd_csc_free(out);
        return 1;
    }
    memcpy(out->colptr, A->p, (size_t)(n + 1) * sizeof *out->colptr);
    memcpy(out->rowind, A->i, (size_t)nnz * sizeof *out->rowind);
    memcpy(out->values, A->x, (size_t)nnz * sizeof *out->values);
    cs_spfree(A);
    return 0;
}

void gd_csc_free(gd_csc *a)
{
    free(a->colptr);
    free(a->rowind);
    free(a->values);
    memset(a, 0, sizeof *a);
}

void gd_csc_add_dense(const gd_csc *s, double scale, double *A)
{
    if (!s->colptr || scale == 0.0) return;
    for (int j = 0; j < s->n; j++)
        for (int k = s->colptr[j]; k < s->colptr[j + 1]; k++)
            A[(size_t)s->rowind[k] + (size_t)j * (size_t)s->n] += scale * s->values[k];
}

void gd_csc_mul(const gd_csc *s, const double *x, double *y)
{
    memset(y, 0, (size_t)s->n * sizeof *y);
    if (!s->colptr) return;
    for (int j = 0; j < s->n; j++)
        for (int k = s->colptr[j]; k < s->colptr[j + 1]; k++)
            y[s->rowind[k]] += s->values[k] * x[j];
}

int gd_pattern_find(const gd_pattern *a, int row, int col)
{
    int lo = a->colptr[col], hi = a->colptr[col + 1] - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (a->rowind[mid] == row) return mid;
        if (a->rowind[mid] < row)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

int gd_pattern_symmetric(const gd_pattern *p, const double *k)
{
    double mx = 0;
    for (int q = 0; q < p->nnz; q++)
        mx = fmax(mx, fabs(k[q]));
    for (int j = 0; j < p->n; j++)
        for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++) {
            int i = p->rowind[q];
            if (i >= j) continue;
            int t = gd_pattern_find(p, j, i);
            double kt = t >= 0 ? k[t] : 0.0;
            if (fabs(k[q] - kt) > 1e-12 * mx) return 0;
        }
    return 1;
}

void gd_pattern_mul2(const gd_pattern *a, const double *s, const double *x, const double *t,
                     const double *z, double *y)
{
    memset(y, 0, (size_t)a->n * sizeof *y);
    for (int j = 0; j < a->n; j++) {
        double xj = x[j], zj = z[j];
        for (int p = a->colptr[j]; p < a->colptr[j + 1]; p++)
            y[a->rowind[p]] += s[p] * xj + t[p] * zj;
    }
}
