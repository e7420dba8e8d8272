/* The dynamic stiffness s^2 M + s D(W) + K(W) of a system on one sparse pattern: the
 * union of M, C, G, K and the entries of elements whose K and C depend on speed.
 * Built once per system; values at a speed are filled in O(nnz), so a sweep reuses the
 * pattern and its symbolic factorisation at every point. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"
#include "system/system_impl.h"

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
    for (int e = 0; e < sys->ninstances; e++) {
        const gd_element_instance *in = &sys->instances[e];
        if (!(in->terms & GD_TERM_SPEED)) continue;
        a->ntab++;
        for (int i = 0; i < in->nlocal; i++)
            for (int j = 0; j < in->nlocal; j++)
                if (in->dof[i] >= 0 && in->dof[j] >= 0 &&
                    gd_trip_add(&t, in->dof[i], in->dof[j], 1.0))
                    goto nomem;
    }
    for (int l = 0; l < sys->nlaws; l++) {
        const gd_law *L = &sys->laws[l];
        for (int i = 0; i < L->ndofs; i++)
            for (int j = 0; j < L->ndofs; j++)
                if (L->dof[i] >= 0 && L->dof[j] >= 0 && gd_trip_add(&t, L->dof[i], L->dof[j], 1.0))
                    goto nomem;
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
    a->law_pos = malloc((size_t)(sys->law_block > 0 ? sys->law_block : 1) * sizeof *a->law_pos);
    if (!a->m || !a->c || !a->g || !a->k || !a->tab || !a->pat.diag || !a->law_pos) goto nomem;
    for (int j = 0; j < n; j++)
        a->pat.diag[j] = gd_pattern_find(&a->pat, j, j);
    scatter_values(a, &sys->M, a->m);
    scatter_values(a, &sys->C, a->c);
    scatter_values(a, &sys->G, a->g);
    scatter_values(a, &sys->K, a->k);
    int tb = 0;
    for (int e = 0; e < sys->ninstances; e++) {
        const gd_element_instance *in = &sys->instances[e];
        if (!(in->terms & GD_TERM_SPEED)) continue;
        gd_dyn_term *dt = &a->tab[tb++];
        dt->instance = e;
        int nl = in->nlocal;
        for (int i = 0; i < nl; i++)
            for (int j = 0; j < nl; j++)
                dt->pos[i * nl + j] = in->dof[i] >= 0 && in->dof[j] >= 0
                                          ? gd_pattern_find(&a->pat, in->dof[i], in->dof[j])
                                          : -1;
    }
    /* the laws' blocks, column-major as gd_system_law_blocks gives them */
    for (int l = 0, at = 0; l < sys->nlaws; l++) {
        const gd_law *L = &sys->laws[l];
        for (int j = 0; j < L->ndofs; j++)
            for (int i = 0; i < L->ndofs; i++, at++)
                a->law_pos[at] = L->dof[i] >= 0 && L->dof[j] >= 0
                                     ? gd_pattern_find(&a->pat, L->dof[i], L->dof[j])
                                     : -1;
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
    free(a->law_pos);
    memset(a, 0, sizeof *a);
}

void gd_dynmat_add_speed_terms(const gd_dynmat *a, double speed, double *k, double *c)
{
    const gd_system *sys = a->sys;
    for (int t = 0; t < a->ntab; t++) {
        const gd_element_instance *in = &sys->instances[a->tab[t].instance];
        double Kl[GD_ELEMENT_MAX_DOFS * GD_ELEMENT_MAX_DOFS],
            Cl[GD_ELEMENT_MAX_DOFS * GD_ELEMENT_MAX_DOFS];
        in->type->matrices(sys->model, in->index, speed, NULL, Kl, Cl, NULL);
        for (int p = 0; p < in->nlocal * in->nlocal; p++) {
            int q = a->tab[t].pos[p];
            if (q < 0) continue;
            if (k) k[q] += Kl[p];
            if (c) c[q] += Cl[p];
        }
    }
}

void gd_dynmat_at(const gd_dynmat *a, double speed, double *k, double *d)
{
    gd_dynmat_at_state(a, speed, NULL, k, d);
}

void gd_dynmat_at_state(const gd_dynmat *a, double speed, const double *state, double *k, double *d)
{
    size_t z = (size_t)a->pat.nnz;
    if (k) memcpy(k, a->k, z * sizeof *k);
    if (d)
        for (size_t i = 0; i < z; i++)
            d[i] = a->c[i] + speed * a->g[i];
    gd_dynmat_add_speed_terms(a, speed, k, d);
    const gd_system *sys = a->sys;
    if (!sys->nlaws || (!k && !d)) return;
    double *Kb = malloc((size_t)sys->law_block * 2 * sizeof *Kb);
    if (!Kb) return;
    double *Cb = Kb + sys->law_block;
    gd_system_law_blocks_at(sys, speed, state, Kb, Cb);
    for (int p = 0; p < sys->law_block; p++) {
        int at = a->law_pos[p];
        if (at < 0) continue;
        if (k) k[at] += Kb[p];
        if (d) d[at] += Cb[p];
    }
    free(Kb);
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
