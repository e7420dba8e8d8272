/* Assembly of the global sparse matrices over the active DOFs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "elements/elements_impl.h"
#include "geardyn/system.h"
#include "linalg/linalg_impl.h"

const char *const gd_motion_names[GD_NMOTIONS] = {"lateral", "torsional", "axial", "tilt"};

typedef struct assembler {
    const gd_model *m;
    gd_trip M, K, C, G;
    int *used; /* raw DOF touched by some matrix term */
    int fail;
} assembler;

/* Adds scale * local (n x n, row-major) at raw DOFs idx[] into t, skipping DOFs
 * outside the model's active mask. */
static void scatter(assembler *as, gd_trip *t, const double *local, int n, const int *idx,
                    double scale)
{
    unsigned mask = as->m->dof_mask;
    for (int a = 0; a < n; a++) {
        if (idx[a] < 0 || !(mask & GD_DOF_BIT(idx[a] % 6))) continue;
        for (int b = 0; b < n; b++) {
            if (idx[b] < 0 || !(mask & GD_DOF_BIT(idx[b] % 6))) continue;
            double v = scale * local[a * n + b];
            if (v == 0.0) continue;
            if (gd_trip_add(t, idx[a], idx[b], v)) as->fail = 1;
            /* a gyroscopic term alone does not make a DOF: with no inertia, stiffness or
             * damping it has nothing to act on and is dropped with its G entries */
            if (t != &as->G) as->used[idx[a]] = as->used[idx[b]] = 1;
        }
    }
}

static void node_idx(int node, int *idx)
{
    for (int d = 0; d < 6; d++)
        idx[d] = node < 0 ? -1 : 6 * node + d;
}

/* Two-node 12 x 12 from a one-node 6 x 6 connecting node1 to node2 (or ground):
 * [A -A; -A A]. */
static void two_node(const double *a6, double *a12)
{
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            double v = a6[i * 6 + j];
            a12[i * 12 + j] = v;
            a12[(i + 6) * 12 + j + 6] = v;
            a12[i * 12 + j + 6] = -v;
            a12[(i + 6) * 12 + j] = -v;
        }
}

static void add_connector(assembler *as, gd_trip *t, const double *a6, int node1, int node2)
{
    int idx[12];
    node_idx(node1, idx);
    node_idx(node2, idx + 6);
    if (node2 < 0) {
        scatter(as, t, a6, 6, idx, 1.0);
    } else {
        double a12[144];
        two_node(a6, a12);
        scatter(as, t, a12, 12, idx, 1.0);
    }
}

/* Marks the DOFs a speed-table bearing acts on, so they stay active. */
static void mark_table_bearing(assembler *as, const gd_bearing *b)
{
    for (int r = 0; r < b->ntable; r++) {
        double K[36], C[36];
        gd_bearing_matrices(&b->table[r], K, C);
        for (int d = 0; d < 6; d++) {
            if (!(as->m->dof_mask & GD_DOF_BIT(d))) continue;
            int nz = 0;
            for (int e = 0; e < 6; e++)
                nz |= K[d * 6 + e] != 0 || C[d * 6 + e] != 0;
            if (nz) {
                as->used[6 * b->node + d] = 1;
                if (b->node2 >= 0) as->used[6 * b->node2 + d] = 1;
            }
        }
    }
}

static void assemble(assembler *as, int *has_table, double *element_K)
{
    const gd_model *m = as->m;
    int idx[12];
    for (int e = 0; e < m->nelements; e++) {
        const gd_element *el = &m->elements[e];
        double Me[144], Ge[144], *Ke = element_K + (size_t)e * 144;
        gd_shaft_element_matrices(el, &m->materials[el->material], Me, Ke, Ge);
        node_idx(el->node1, idx);
        node_idx(el->node2, idx + 6);
        scatter(as, &as->M, Me, 12, idx, 1.0);
        scatter(as, &as->K, Ke, 12, idx, 1.0);
        scatter(as, &as->G, Ge, 12, idx, m->shafts[el->shaft].speed_ratio);
    }
    for (int d = 0; d < m->ndisks; d++) {
        const gd_disk *dk = &m->disks[d];
        double Md[36], Gd[36];
        gd_disk_matrices(dk, Md, Gd);
        node_idx(dk->node, idx);
        scatter(as, &as->M, Md, 6, idx, 1.0);
        scatter(as, &as->G, Gd, 6, idx, m->shafts[m->nodes[dk->node].shaft].speed_ratio);
    }
    for (int b = 0; b < m->nbearings; b++) {
        const gd_bearing *br = &m->bearings[b];
        if (br->ntable) {
            *has_table = 1;
            mark_table_bearing(as, br);
            continue;
        }
        double Kb[36], Cb[36];
        gd_bearing_matrices(&br->coeffs, Kb, Cb);
        add_connector(as, &as->K, Kb, br->node, br->node2);
        add_connector(as, &as->C, Cb, br->node, br->node2);
    }
    for (int s = 0; s < m->nsprings; s++) {
        const gd_spring *sp = &m->springs[s];
        double Ks[36] = {0}, Cs[36] = {0};
        Ks[sp->dof * 7] = sp->stiffness;
        Cs[sp->dof * 7] = sp->damping;
        add_connector(as, &as->K, Ks, sp->node1, sp->node2);
        add_connector(as, &as->C, Cs, sp->node1, sp->node2);
    }
    for (int g = 0; g < m->nmeshes; g++) {
        const gd_mesh *mesh = &m->meshes[g];
        double a[12], kk[144], cc[144];
        gd_mesh_vector_local(mesh, a);
        for (int i = 0; i < 12; i++)
            for (int j = 0; j < 12; j++) {
                kk[i * 12 + j] = mesh->stiffness * a[i] * a[j];
                cc[i * 12 + j] = gd_mesh_linear_damping(mesh) * a[i] * a[j];
            }
        node_idx(mesh->driver, idx);
        node_idx(mesh->driven, idx + 6);
        scatter(as, &as->K, kk, 12, idx, 1.0);
        scatter(as, &as->C, cc, 12, idx, 1.0);
    }
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
    s->element_K = malloc((size_t)(m->nelements > 0 ? m->nelements : 1) * 144 * sizeof(double));
    if (!s->element_K) goto nomem;
    assemble(&as, &s->has_speed_dependent, s->element_K);
    if (as.fail) goto nomem;

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
        gd_trip_compress(&as.G, s->node_dof, n, &s->G))
        goto nomem;
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
    s->has_damping = s->C.colptr[n] > 0;
    for (int b = 0; b < m->nbearings; b++)
        for (int r = 0; r < m->bearings[b].ntable; r++) {
            const gd_bearing_coeffs *c = &m->bearings[b].table[r];
            if (c->cxx || c->cxy || c->cyx || c->cyy || c->czz || c->ctilt || c->ctorsion)
                s->has_damping = 1;
        }
    s->ncomponents = m->nshafts + m->nbearings + m->nsprings + m->nmeshes;
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
    free(s->element_K);
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

/* Speed of the shaft carrying node (magnitude), for bearing tables. */
static double node_speed(const gd_model *m, int node, double ref_speed)
{
    return fabs(m->shafts[m->nodes[node].shaft].speed_ratio * ref_speed);
}

static void add_dense_local(const gd_system *s, const double *a6, int node1, int node2, double *A)
{
    int n = s->ndof;
    int idx[12];
    for (int d = 0; d < 6; d++) {
        idx[d] = gd_system_dof(s, node1, (gd_dof)d);
        idx[d + 6] = node2 >= 0 ? gd_system_dof(s, node2, (gd_dof)d) : -1;
    }
    for (int i = 0; i < 12; i++)
        for (int j = 0; j < 12; j++) {
            if (idx[i] < 0 || idx[j] < 0) continue;
            double v = a6[(i % 6) * 6 + j % 6];
            if ((i < 6) != (j < 6)) v = -v;
            A[(size_t)idx[i] + (size_t)idx[j] * (size_t)n] += v;
        }
}

void gd_system_dense(const gd_system *s, double speed, double *M, double *D, double *K)
{
    size_t nn = (size_t)s->ndof * (size_t)s->ndof;
    if (M) {
        memset(M, 0, nn * sizeof *M);
        gd_csc_add_dense(&s->M, 1.0, M);
    }
    if (D) {
        memset(D, 0, nn * sizeof *D);
        gd_csc_add_dense(&s->C, 1.0, D);
        gd_csc_add_dense(&s->G, speed, D);
    }
    if (K) {
        memset(K, 0, nn * sizeof *K);
        gd_csc_add_dense(&s->K, 1.0, K);
    }
    if (!s->has_speed_dependent) return;
    const gd_model *m = s->model;
    for (int b = 0; b < m->nbearings; b++) {
        const gd_bearing *br = &m->bearings[b];
        if (!br->ntable) continue;
        gd_bearing_coeffs c;
        gd_bearing_coeffs_at(br, node_speed(m, br->node, speed), &c);
        double Kb[36], Cb[36];
        gd_bearing_matrices(&c, Kb, Cb);
        if (K) add_dense_local(s, Kb, br->node, br->node2, K);
        if (D) add_dense_local(s, Cb, br->node, br->node2, D);
    }
}

gd_component_kind gd_system_component(const gd_system *s, int c, int *index, const char **name)
{
    const gd_model *m = s->model;
    if (c < m->nshafts) {
        *index = c;
        *name = m->shafts[c].name;
        return GD_COMP_SHAFT;
    }
    c -= m->nshafts;
    if (c < m->nbearings) {
        *index = c;
        *name = m->bearings[c].name;
        return GD_COMP_BEARING;
    }
    c -= m->nbearings;
    if (c < m->nsprings) {
        *index = c;
        *name = m->springs[c].name;
        return GD_COMP_SPRING;
    }
    c -= m->nsprings;
    *index = c;
    *name = m->meshes[c].name;
    return GD_COMP_MESH;
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

/* ---- modal strain energy ---- */

typedef struct cplx {
    double re, im;
} cplx;

static cplx dof_value(const gd_system *s, int node, int d, const double *re, const double *im)
{
    int i = node < 0 ? -1 : gd_system_dof(s, node, (gd_dof)d);
    cplx z = {0, 0};
    if (i >= 0) {
        z.re = re[i];
        z.im = im ? im[i] : 0.0;
    }
    return z;
}

/* 1/2 Re(u^H K u) of an n x n local matrix over node DOFs, split by the DOF type
 * partition into motions (motion_of[d] for d = 0..5). */
static double local_energy(const double *Kl, int n, const cplx *u, const gd_motion *motion_of,
                           double *by_motion)
{
    double total = 0;
    int act[12], na = 0; /* DOFs that move (absent DOF types are zero) */
    for (int b = 0; b < n && b < 12; b++)
        if (u[b].re != 0 || u[b].im != 0) act[na++] = b;
    for (int ia = 0; ia < na; ia++) {
        int a = act[ia];
        double fr = 0, fi = 0;
        for (int ib = 0; ib < na; ib++) {
            int b = act[ib];
            fr += Kl[a * n + b] * u[b].re;
            fi += Kl[a * n + b] * u[b].im;
        }
        double e = 0.5 * (u[a].re * fr + u[a].im * fi);
        by_motion[motion_of[a % 6]] += e;
        total += e;
    }
    return total;
}

static const gd_motion SHAFT_MOTION[6] = {GD_MOTION_LATERAL, GD_MOTION_LATERAL,
                                          GD_MOTION_AXIAL,   GD_MOTION_LATERAL,
                                          GD_MOTION_LATERAL, GD_MOTION_TORSIONAL};
static const gd_motion SUPPORT_MOTION[6] = {GD_MOTION_LATERAL, GD_MOTION_LATERAL,
                                            GD_MOTION_AXIAL,   GD_MOTION_TILT,
                                            GD_MOTION_TILT,    GD_MOTION_TORSIONAL};

static double connector_energy(const gd_system *s, const double *a6, int node1, int node2,
                               const double *re, const double *im, double *by_motion)
{
    cplx u[6];
    for (int d = 0; d < 6; d++) {
        cplx a = dof_value(s, node1, d, re, im), b = dof_value(s, node2, d, re, im);
        u[d].re = a.re - b.re; /* relative motion: the 12 x 12 [A -A; -A A] form */
        u[d].im = a.im - b.im;
    }
    return local_energy(a6, 6, u, SUPPORT_MOTION, by_motion);
}

double gd_system_strain_energy(const gd_system *s, double speed, const double *re, const double *im,
                               double *by_motion, double *by_component)
{
    const gd_model *m = s->model;
    double total = 0;
    for (int k = 0; k < GD_NMOTIONS; k++)
        by_motion[k] = 0;
    if (by_component)
        for (int c = 0; c < s->ncomponents; c++)
            by_component[c] = 0;
    unsigned mask = m->dof_mask;
    for (int e = 0; e < m->nelements; e++) {
        const gd_element *el = &m->elements[e];
        const double *Ke = s->element_K + (size_t)e * 144;
        cplx u[12];
        for (int k = 0; k < 12; k++) {
            int d = k % 6;
            u[k] = (mask & GD_DOF_BIT(d)) ? dof_value(s, k < 6 ? el->node1 : el->node2, d, re, im)
                                          : (cplx){0, 0};
        }
        double en = local_energy(Ke, 12, u, SHAFT_MOTION, by_motion);
        total += en;
        if (by_component) by_component[el->shaft] += en;
    }
    int c0 = m->nshafts;
    for (int b = 0; b < m->nbearings; b++) {
        const gd_bearing *br = &m->bearings[b];
        gd_bearing_coeffs c;
        gd_bearing_coeffs_at(br, node_speed(m, br->node, speed), &c);
        double Kb[36], Cb[36];
        gd_bearing_matrices(&c, Kb, Cb);
        for (int d = 0; d < 6; d++)
            if (!(mask & GD_DOF_BIT(d)))
                for (int e = 0; e < 6; e++)
                    Kb[d * 6 + e] = Kb[e * 6 + d] = 0;
        double en = connector_energy(s, Kb, br->node, br->node2, re, im, by_motion);
        total += en;
        if (by_component) by_component[c0 + b] += en;
    }
    c0 += m->nbearings;
    for (int k = 0; k < m->nsprings; k++) {
        const gd_spring *sp = &m->springs[k];
        double Ks[36] = {0};
        if (mask & GD_DOF_BIT(sp->dof)) Ks[sp->dof * 7] = sp->stiffness;
        double en = connector_energy(s, Ks, sp->node1, sp->node2, re, im, by_motion);
        total += en;
        if (by_component) by_component[c0 + k] += en;
    }
    c0 += m->nsprings;
    for (int g = 0; g < m->nmeshes; g++) {
        gd_mesh_vector v;
        gd_system_mesh_vector(s, g, &v);
        /* d split by motion of the contributing DOFs; the energy k|d|^2/2 is shared in
         * proportion to |d_motion|^2 so the shares are non-negative and sum up. */
        cplx dm[GD_NMOTIONS] = {{0, 0}};
        cplx d = {0, 0};
        for (int j = 0; j < v.n; j++) {
            gd_motion mo = SUPPORT_MOTION[s->dof_type[v.dof[j]]];
            double ur = re[v.dof[j]], ui = im ? im[v.dof[j]] : 0;
            dm[mo].re += v.a[j] * ur;
            dm[mo].im += v.a[j] * ui;
            d.re += v.a[j] * ur;
            d.im += v.a[j] * ui;
        }
        double en = 0.5 * m->meshes[g].stiffness * (d.re * d.re + d.im * d.im);
        double wsum = 0;
        for (int k = 0; k < GD_NMOTIONS; k++)
            wsum += dm[k].re * dm[k].re + dm[k].im * dm[k].im;
        if (wsum > 0)
            for (int k = 0; k < GD_NMOTIONS; k++)
                by_motion[k] += en * (dm[k].re * dm[k].re + dm[k].im * dm[k].im) / wsum;
        total += en;
        if (by_component) by_component[c0 + g] += en;
    }
    return total;
}
