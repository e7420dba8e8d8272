/* Assembly of the global sparse matrices over the active DOFs: every element of every
 * kind in the registry contributes its local M, K, C, G (geardyn/elements.h); DOFs
 * that no inertia, stiffness or damping acts on are dropped. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "elements/elements_impl.h"
#include "geardyn/system.h"
#include "linalg/linalg_impl.h"
#include "system/system_impl.h"

typedef struct assembler {
    const gd_model *m;
    gd_trip M, K, C, G;
    int *used; /* raw DOF touched by some matrix term */
    int fail;
} assembler;

/* Adds local (n x n, row-major) at raw DOFs idx[] into t, skipping DOFs outside the
 * model's active mask. */
static void scatter(assembler *as, gd_trip *t, const double *local, int n, const int *idx)
{
    unsigned mask = as->m->dof_mask;
    for (int a = 0; a < n; a++) {
        if (idx[a] < 0 || !(mask & GD_DOF_BIT(idx[a] % 6))) continue;
        for (int b = 0; b < n; b++) {
            if (idx[b] < 0 || !(mask & GD_DOF_BIT(idx[b] % 6))) continue;
            double v = local[a * n + b];
            if (v == 0.0) continue;
            if (gd_trip_add(t, idx[a], idx[b], v)) as->fail = 1;
            /* a gyroscopic term alone does not make a DOF: with no inertia, stiffness or
             * damping it has nothing to act on and is dropped with its G entries */
            if (t != &as->G) as->used[idx[a]] = as->used[idx[b]] = 1;
        }
    }
}

/* Rayleigh damping ([JMSTHelical]): C += alpha M + beta K on the assembled terms. 0 ok, 1 out
 * of memory. */
static int rayleigh(assembler *as)
{
    double a = as->m->rayleigh_alpha, b = as->m->rayleigh_beta;
    int nm = as->M.n, nk = as->K.n;
    for (int k = 0; k < nm && a != 0; k++)
        if (gd_trip_add(&as->C, as->M.i[k], as->M.j[k], a * as->M.x[k])) return 1;
    for (int k = 0; k < nk && b != 0; k++)
        if (gd_trip_add(&as->C, as->K.i[k], as->K.j[k], b * as->K.x[k])) return 1;
    return 0;
}

/* Raw DOF indices (6 x node + dof) of an element's local DOFs; -1 for ground. */
static int raw_dofs(const gd_element_type *t, const gd_model *m, int i, int *idx)
{
    int node[2];
    int nn = t->nodes(m, i, node);
    for (int k = 0; k < nn; k++)
        for (int d = 0; d < 6; d++)
            idx[6 * k + d] = node[k] < 0 ? -1 : 6 * node[k] + d;
    return 6 * nn;
}

/* Marks the DOFs a speed-dependent element acts on at any speed, so they stay active. */
static void mark_speed_dofs(assembler *as, const gd_element_type *t, int i, const int *idx, int n)
{
    int acts[GD_ELEMENT_MAX_DOFS];
    t->speed_pattern(as->m, i, acts);
    for (int a = 0; a < n; a++)
        if (acts[a] && idx[a] >= 0 && (as->m->dof_mask & GD_DOF_BIT(a % 6))) as->used[idx[a]] = 1;
}

static void assemble(assembler *as, int *has_speed)
{
    const gd_model *m = as->m;
    double Ml[144], Kl[144], Cl[144], Gl[144];
    for (int k = 0; k < gd_nelement_types; k++) {
        const gd_element_type *t = gd_element_types[k];
        int count = t->count(m);
        for (int i = 0; i < count; i++) {
            int idx[GD_ELEMENT_MAX_DOFS];
            int n = raw_dofs(t, m, i, idx);
            unsigned terms = t->terms(m, i);
            int speed = (terms & GD_TERM_SPEED) != 0;
            t->matrices(m, i, 0.0, Ml, speed ? NULL : Kl, speed ? NULL : Cl, Gl);
            scatter(as, &as->M, Ml, n, idx);
            if (speed) {
                *has_speed = 1;
                mark_speed_dofs(as, t, i, idx, n);
            } else {
                scatter(as, &as->K, Kl, n, idx);
                scatter(as, &as->C, Cl, n, idx);
            }
            scatter(as, &as->G, Gl, n, idx);
        }
    }
}

/* The instances with their active DOFs, components and constant local stiffness. */
static int build_instances(gd_system *s)
{
    const gd_model *m = s->model;
    int total = 0;
    size_t kspace = 0;
    for (int k = 0; k < gd_nelement_types; k++) {
        const gd_element_type *t = gd_element_types[k];
        int count = t->count(m);
        total += count;
        for (int i = 0; i < count; i++) {
            int node[2];
            int n = 6 * t->nodes(m, i, node);
            if (t->ncomponents && !(t->terms(m, i) & GD_TERM_SPEED)) kspace += (size_t)(n * n);
        }
    }
    s->ninstances = total;
    s->instances = calloc((size_t)(total > 0 ? total : 1), sizeof *s->instances);
    s->instance_K = malloc((kspace > 0 ? kspace : 1) * sizeof *s->instance_K);
    if (!s->instances || !s->instance_K) return 1;
    int e = 0, comp0 = 0;
    double *kp = s->instance_K;
    for (int k = 0; k < gd_nelement_types; k++) {
        const gd_element_type *t = gd_element_types[k];
        int count = t->count(m);
        for (int i = 0; i < count; i++, e++) {
            gd_element_instance *in = &s->instances[e];
            int node[2];
            int nn = t->nodes(m, i, node);
            in->type = t;
            in->index = i;
            in->nlocal = 6 * nn;
            in->terms = t->terms(m, i);
            for (int a = 0; a < in->nlocal; a++)
                in->dof[a] = node[a / 6] < 0 ? -1 : gd_system_dof(s, node[a / 6], (gd_dof)(a % 6));
            in->component = t->ncomponents ? comp0 + t->component(m, i) : -1;
            if (t->ncomponents && !(in->terms & GD_TERM_SPEED)) {
                in->K = kp;
                t->matrices(m, i, 0.0, NULL, kp, NULL, NULL);
                kp += in->nlocal * in->nlocal;
            }
        }
        if (t->ncomponents) comp0 += t->ncomponents(m);
    }
    s->ncomponents = comp0;
    return 0;
}

static int has_speed_damping(const gd_system *s)
{
    for (int e = 0; e < s->ninstances; e++)
        if ((s->instances[e].terms & GD_TERM_SPEED) && (s->instances[e].terms & GD_TERM_C))
            return 1;
    return 0;
}

gd_status gd_system_build(const gd_model *m, gd_system **out, gd_error *err)
{
    *out = NULL;
    if (m->build) /* under construction (geardyn/builder.h): no nodes or names resolved */
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "",
                            "call gd_model_finish before building the system",
                            "the model is not finished");
    int raw = 6 * m->nnodes;
    assembler as = {.m = m, .used = calloc((size_t)(raw > 0 ? raw : 1), sizeof(int))};
    gd_system *s = calloc(1, sizeof *s);
    int *map = malloc((size_t)(raw > 0 ? raw : 1) * sizeof *map);
    if (!as.used || !s || !map) goto nomem;
    s->model = m;
    assemble(&as, &s->has_speed_dependent);
    if (as.fail || rayleigh(&as)) goto nomem;

    int n = 0;
    for (int r = 0; r < raw; r++)
        map[r] = as.used[r] ? n++ : -1;
    if (n == 0) {
        gd_error_set(err, GD_EINPUT, m->file, 0, 0, "dofs",
                     "add shafts with sections, disks or springs on the active DOFs",
                     "the model has no active degree of freedom");
        goto fail;
    }
    s->ndof = n;
    s->node_dof = map;
    map = NULL;
    s->dof_node = malloc((size_t)n * sizeof *s->dof_node);
    s->dof_type = malloc((size_t)n * sizeof *s->dof_type);
    s->massless = calloc((size_t)n, sizeof *s->massless);
    if (!s->dof_node || !s->dof_type || !s->massless) goto nomem;
    for (int r = 0; r < raw; r++)
        if (s->node_dof[r] >= 0) {
            s->dof_node[s->node_dof[r]] = r / 6;
            s->dof_type[s->node_dof[r]] = (gd_dof)(r % 6);
        }
    if (gd_trip_compress(&as.M, s->node_dof, n, &s->M) ||
        gd_trip_compress(&as.K, s->node_dof, n, &s->K) ||
        gd_trip_compress(&as.C, s->node_dof, n, &s->C) ||
        gd_trip_compress(&as.G, s->node_dof, n, &s->G) || build_instances(s))
        goto nomem;
    if (gd_system_make_laws(s, err)) goto fail;
    s->ncomponents += s->nlaws; /* each linearised law its own component, after the elements' */
    for (int j = 0; j < n; j++) {
        int has = 0;
        for (int k = s->M.colptr[j]; k < s->M.colptr[j + 1]; k++)
            if (s->M.rowind[k] == j && s->M.values[k] > 0) has = 1;
        if (!has) {
            s->massless[j] = 1;
            s->nmassless++;
        }
    }
    s->has_gyroscopic = s->G.colptr[n] > 0;
    s->has_damping = s->C.colptr[n] > 0 || has_speed_damping(s) || s->nlaws > 0;
    gd_trip_free(&as.M);
    gd_trip_free(&as.K);
    gd_trip_free(&as.C);
    gd_trip_free(&as.G);
    free(as.used);
    *out = s;
    return GD_OK;
nomem:
    gd_error_set(err, GD_ENOMEM, m->file, 0, 0, "", "", "out of memory assembling the system");
fail:
    gd_trip_free(&as.M);
    gd_trip_free(&as.K);
    gd_trip_free(&as.C);
    gd_trip_free(&as.G);
    free(as.used);
    free(map);
    gd_system_free(s);
    return err ? err->status : GD_ENOMEM;
}

void gd_system_free(gd_system *s)
{
    if (!s) return;
    free(s->dof_node);
    free(s->dof_type);
    free(s->node_dof);
    free(s->massless);
    free(s->instances);
    free(s->instance_K);
    free(s->laws);
    free(s->op_f0);
    free(s->op_held);
    gd_csc_free(&s->M);
    gd_csc_free(&s->K);
    gd_csc_free(&s->C);
    gd_csc_free(&s->G);
    free(s);
}

int gd_system_dof(const gd_system *s, int node, gd_dof dof)
{
    if (node < 0 || node >= s->model->nnodes || dof < 0 || dof >= GD_NODE_DOFS) return -1;
    return s->node_dof[6 * node + dof];
}

void gd_system_dof_label(const gd_system *s, int i, char *buf, int size)
{
    snprintf(buf, (size_t)size, "%s.%s", s->model->nodes[s->dof_node[i]].name,
             gd_dof_names[s->dof_type[i]]);
}

const gd_element_type *gd_system_component(const gd_system *s, int c, int *index, const char **name)
{
    const gd_model *m = s->model;
    for (int k = 0; k < gd_nelement_types; k++) {
        const gd_element_type *t = gd_element_types[k];
        if (!t->ncomponents) continue;
        int nc = t->ncomponents(m);
        if (c < nc) {
            *index = c;
            *name = t->component_name(m, c);
            return t;
        }
        c -= nc;
    }
    if (c >= 0 && c < s->nlaws) { /* a linearised law: no element kind */
        *index = c;
        *name = s->laws[c].name;
        return NULL;
    }
    *index = -1;
    *name = "";
    return NULL;
}

void gd_system_mesh_vector(const gd_system *s, int mesh, gd_mesh_vector *out)
{
    const gd_mesh *g = &s->model->meshes[mesh];
    double a[12];
    gd_mesh_vector_local(g, a);
    out->n = 0;
    for (int k = 0; k < 12; k++) {
        int node = k < 6 ? g->driver : g->driven;
        int i = gd_system_dof(s, node, (gd_dof)(k % 6));
        if (i < 0 || a[k] == 0.0) continue;
        out->dof[out->n] = i;
        out->a[out->n] = a[k];
        out->n++;
    }
}
