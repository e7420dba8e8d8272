/* The dynamic stiffness s^2 M + s D(W) + K(W) of a system on one sparse pattern: the
 * union of M, C, G, K and the entries of bearings whose coefficients depend on speed.
 * Built once per system; values at a speed are filled in O(nnz), so a sweep reuses the
 * pattern and its symbolic factorisation at every point. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "elements/elements_impl.h"
#include "linalg/linalg_impl.h"
#include "system/system_impl.h"

static void bearing_dofs(const gd_system *sys, const gd_bearing *b, int idx[12])
{
    for (int d = 0; d < 6; d++) {
        idx[d] = gd_system_dof(sys, b->node, (gd_dof)d);
        idx[d + 6] = b->node2 >= 0 ? gd_system_dof(sys, b->node2, (gd_dof)d) : -1;
    }
}

static int add_pattern(gd_trip *t, const gd_csc *s)
{
    if (!s->colptr) return 0;
    for (int j = 0; j < s->n; j++)
        for (int k = s->colptr[j]; k < s->colptr[j + 1]; k++)
            if (gd_trip_add(t, s->rowind[k], j, 1.0)) return 1;
    return 0;
}

static void sort_ints(int *a, int n)
{
    for (int i = 1; i < n; i++) {
        int v = a[i], j = i - 1;
        while (j >= 0 && a[j] > v) {
            a[j + 1] = a[j];
            j--;
        }
        a[j + 1] = v;
    }
}

static void scatter_values(const gd_dynmat *a, const gd_csc *s, double *v)
{
    memset(v, 0, (size_t)a->pat.nnz * sizeof *v);
    if (!s->colptr) return;
    for (int j = 0; j < s->n; j++)
        for (int k = s->colptr[j]; k < s->colptr[j + 1]; k++)
            v[gd_pattern_find(&a->pat, s->rowind[k], j)] += s->values[k];
}

gd_status gd_dynmat_build(const gd_system *sys, gd_dynmat *a, gd_error *err)
{
    memset(a, 0, sizeof *a);
    int n = sys->ndof;
    const gd_model *m = sys->model;
    gd_trip t = {0};
    gd_csc u = {0};
    int *map = malloc((size_t)n * sizeof *map);
    if (!map) goto nomem;
    for (int i = 0; i < n; i++) {
        map[i] = i;
        if (gd_trip_add(&t, i, i, 1.0)) goto nomem; /* the diagonal always: pivots */
    }
    if (add_pattern(&t, &sys->M) || add_pattern(&t, &sys->C) || add_pattern(&t, &sys->G) ||
        add_pattern(&t, &sys->K))
        goto nomem;
    for (int b = 0; b < m->nbearings; b++) {
        if (!m->bearings[b].ntable) continue;
        a->ntab++;
        int idx[12];
        bearing_dofs(sys, &m->bearings[b], idx);
        for (int i = 0; i < 12; i++)
            for (int j = 0; j < 12; j++)
                if (idx[i] >= 0 && idx[j] >= 0 && gd_trip_add(&t, idx[i], idx[j], 1.0)) goto nomem;
    }
    if (gd_trip_compress(&t, map, n, &u)) goto nomem;
    gd_trip_free(&t);
    free(map);
    map = NULL;
    a->pat.n = n;
    a->pat.nnz = u.colptr[n];
    a->pat.colptr = u.colptr;
    a->pat.rowind = u.rowind;
    free(u.values);
    for (int j = 0; j < n; j++)
        sort_ints(a->pat.rowind + a->pat.colptr[j], a->pat.colptr[j + 1] - a->pat.colptr[j]);
    size_t z = (size_t)a->pat.nnz;
    a->m = malloc(z * sizeof(double));
    a->c = malloc(z * sizeof(double));
    a->g = malloc(z * sizeof(double));
    a->k = malloc(z * sizeof(double));
    a->tab = calloc((size_t)(a->ntab > 0 ? a->ntab : 1), sizeof *a->tab);
    a->pat.diag = malloc((size_t)(n > 0 ? n : 1) * sizeof *a->pat.diag);
    if (!a->m || !a->c || !a->g || !a->k || !a->tab || !a->pat.diag) goto nomem;
    for (int j = 0; j < n; j++)
        a->pat.diag[j] = gd_pattern_find(&a->pat, j, j);
    scatter_values(a, &sys->M, a->m);
    scatter_values(a, &sys->C, a->c);
    scatter_values(a, &sys->G, a->g);
    scatter_values(a, &sys->K, a->k);
    int tb = 0;
    for (int b = 0; b < m->nbearings; b++) {
        if (!m->bearings[b].ntable) continue;
        gd_dyn_bearing *db = &a->tab[tb++];
        db->bearing = b;
        int idx[12];
        bearing_dofs(sys, &m->bearings[b], idx);
        for (int i = 0; i < 12; i++)
            for (int j = 0; j < 12; j++)
                db->pos[i * 12 + j] =
                    idx[i] >= 0 && idx[j] >= 0 ? gd_pattern_find(&a->pat, idx[i], idx[j]) : -1;
    }
    a->sys = sys;
    return GD_OK;
nomem:
    gd_trip_free(&t);
    free(map);
    gd_dynmat_free(a);
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                        "out of memory building the sparse pattern");
}

void gd_dynmat_free(gd_dynmat *a)
{
    free(a->pat.colptr);
    free(a->pat.rowind);
    free(a->m);
    free(a->c);
    free(a->g);
    free(a->k);
    free(a->tab);
    free(a->pat.diag);
    memset(a, 0, sizeof *a);
}

void gd_dynmat_at(const gd_dynmat *a, double speed, double *k, double *d)
{
    size_t z = (size_t)a->pat.nnz;
    if (k) memcpy(k, a->k, z * sizeof *k);
    if (d)
        for (size_t i = 0; i < z; i++)
            d[i] = a->c[i] + speed * a->g[i];
    const gd_model *m = a->sys->model;
    for (int t = 0; t < a->ntab; t++) {
        const gd_bearing *b = &m->bearings[a->tab[t].bearing];
        double ws = fabs(m->shafts[m->nodes[b->node].shaft].speed_ratio * speed);
        gd_bearing_coeffs c;
        gd_bearing_coeffs_at(b, ws, &c);
        double Kb[36], Cb[36];
        gd_bearing_matrices(&c, Kb, Cb);
        for (int i = 0; i < 12; i++)
            for (int j = 0; j < 12; j++) {
                int p = a->tab[t].pos[i * 12 + j];
                if (p < 0) continue;
                double sg = (i < 6) != (j < 6) ? -1.0 : 1.0;
                if (k) k[p] += sg * Kb[(i % 6) * 6 + j % 6];
                if (d) d[p] += sg * Cb[(i % 6) * 6 + j % 6];
            }
    }
}

int gd_dynmat_factor_at(const gd_dynmat *a, const gd_splu_symbolic *s, const double *k,
                        const double *d, double w, double *z, gd_splu *lu)
{
    for (int p = 0; p < a->pat.nnz; p++) {
        z[2 * p] = k[p] - w * w * a->m[p];
        z[2 * p + 1] = w * d[p];
    }
    return gd_splu_factor(lu, &a->pat, s, z, 1, 1);
}
