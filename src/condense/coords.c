/* Law coordinates: the sparse vectors over the system DOFs on which the structure is
 * condensed (a mesh's deflection d = a . q along its line of action, gd_system_mesh_vector;
 * the DOFs of the model's registry laws as unit vectors). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/condense.h"

void gd_condense_coords_init(gd_condense_coords *c)
{
    memset(c, 0, sizeof *c);
}

void gd_condense_coords_release(gd_condense_coords *c)
{
    if (!c) return;
    free(c->start);
    free(c->dof);
    free(c->a);
    free(c->label);
    memset(c, 0, sizeof *c);
}

static gd_status nomem(gd_error *err)
{
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "coordinates", "", "out of memory");
}

gd_status gd_condense_coords_add(gd_condense_coords *c, const gd_system *sys, const char *label,
                                 int n, const int *dof, const double *a, gd_error *err)
{
    double amax = 0;
    for (int e = 0; e < n; e++) {
        if (dof[e] < 0 || dof[e] >= sys->ndof)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "coordinates",
                                "give active DOF indices (gd_system_dof)",
                                "coordinate %d, entry %d: DOF %d is not one of the %d active DOFs",
                                c->n + 1, e + 1, dof[e], sys->ndof);
        if (!isfinite(a[e]))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "coordinates", "give finite weights",
                                "coordinate %d, entry %d: weight is not finite", c->n + 1, e + 1);
        amax = fmax(amax, fabs(a[e]));
    }
    if (n < 1 || !(amax > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "coordinates",
                            "give at least one nonzero weight",
                            "coordinate %d has no nonzero weight", c->n + 1);
    if (c->n + 1 >= c->cap) {
        int cap = c->cap ? 2 * c->cap : 8;
        int *s = realloc(c->start, (size_t)(cap + 1) * sizeof *s);
        if (!s) return nomem(err);
        c->start = s;
        char(*l)[GD_CONDENSE_LABEL_MAX] = realloc(c->label, (size_t)cap * sizeof *l);
        if (!l) return nomem(err);
        c->label = l;
        if (c->cap == 0) c->start[0] = 0;
        c->cap = cap;
    }
    if (c->nnz + n > c->nnz_cap) {
        int cap = c->nnz_cap ? 2 * c->nnz_cap : 32;
        while (cap < c->nnz + n)
            cap *= 2;
        int *d = realloc(c->dof, (size_t)cap * sizeof *d);
        if (!d) return nomem(err);
        c->dof = d;
        double *w = realloc(c->a, (size_t)cap * sizeof *w);
        if (!w) return nomem(err);
        c->a = w;
        c->nnz_cap = cap;
    }
    memcpy(c->dof + c->nnz, dof, (size_t)n * sizeof *dof);
    memcpy(c->a + c->nnz, a, (size_t)n * sizeof *a);
    c->nnz += n;
    if (label)
        snprintf(c->label[c->n], GD_CONDENSE_LABEL_MAX, "%s", label);
    else
        snprintf(c->label[c->n], GD_CONDENSE_LABEL_MAX, "c%d", c->n + 1);
    c->n++;
    c->start[c->n] = c->nnz;
    return GD_OK;
}

gd_status gd_condense_coords_meshes(gd_condense_coords *c, const gd_system *sys, gd_error *err)
{
    const gd_model *m = sys->model;
    for (int k = 0; k < m->nmeshes; k++) {
        gd_mesh_vector v;
        gd_system_mesh_vector(sys, k, &v);
        if (v.n < 1) continue;
        char label[GD_CONDENSE_LABEL_MAX];
        snprintf(label, sizeof label, "mesh:%.58s", m->meshes[k].name);
        gd_status st = gd_condense_coords_add(c, sys, label, v.n, v.dof, v.a, err);
        if (st) return st;
    }
    return GD_OK;
}

/* 1 when coordinate k of c is the unit vector on DOF i. */
static int is_unit(const gd_condense_coords *c, int k, int i)
{
    return c->start[k + 1] - c->start[k] == 1 && c->dof[c->start[k]] == i &&
           c->a[c->start[k]] == 1.0;
}

gd_status gd_condense_coords_laws(gd_condense_coords *c, const gd_system *sys, gd_error *err)
{
    for (int l = 0; l < sys->nlaws; l++) {
        const gd_law *L = &sys->laws[l];
        for (int j = 0; j < L->ndofs; j++) {
            int i = L->dof[j];
            if (i < 0) continue;
            int seen = 0;
            for (int k = 0; k < c->n && !seen; k++)
                seen = is_unit(c, k, i);
            if (seen) continue;
            char dl[40], label[GD_CONDENSE_LABEL_MAX];
            gd_system_dof_label(sys, i, dl, sizeof dl);
            snprintf(label, sizeof label, "%.20s.%.40s", L->name, dl);
            const double one = 1.0;
            gd_status st = gd_condense_coords_add(c, sys, label, 1, &i, &one, err);
            if (st) return st;
        }
    }
    return GD_OK;
}
