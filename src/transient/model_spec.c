/* The transient spec of a model: its meshes' nonlinear laws, dampers, loads, prescribed
 * motions and cams turned into the C description gd_transient_new takes. */
#include "geardyn/transient_model.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static gd_status oom(gd_error *err)
{
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
}

static void *xcalloc(int n, size_t size)
{
    return calloc((size_t)(n > 0 ? n : 1), size);
}

/* "node.dof" for messages */
static void dof_text(const gd_model *m, int node, gd_dof d, char *buf, size_t size)
{
    snprintf(buf, size, "%s.%s", node >= 0 && node < m->nnodes ? m->nodes[node].name : "?",
             (int)d >= 0 && d < GD_NODE_DOFS ? gd_dof_names[d] : "?");
}

static gd_status inactive_dof(const gd_model *m, gd_loc loc, const char *field, const char *what,
                              int node, gd_dof d, gd_error *err)
{
    char buf[GD_NODE_NAME_MAX + 8];
    dof_text(m, node, d, buf, sizeof buf);
    return gd_error_set(err, GD_EINPUT, m->file, loc.line, loc.column, field,
                        "keep the DOF type in 'dofs:' and give the node something that acts on "
                        "it (an inertia, a spring, a mesh or a bearing)",
                        "%s acts on %s, which is not an active DOF of the model", what, buf);
}

static int mesh_is_nonlinear(const gd_mesh *g)
{
    const gd_mesh_dynamics *d = &g->dyn;
    return d->tvms || g->tvms || d->ste || d->backlash || d->damping_per_stiffness != 0.0 ||
           d->damping_separated != 0.0;
}

gd_status gd_transient_model_build(const gd_system *sys, gd_transient_model **out, gd_error *err)
{
    *out = NULL;
    const gd_model *m = sys->model;
    gd_transient_model *tm = calloc(1, sizeof *tm);
    if (!tm) return oom(err);
    gd_status st = GD_OK;
    int nvalves = 0, nsfd = 0;
    for (int i = 0; i < m->ncams; i++)
        nvalves += m->cams[i].nvalves;
    for (int i = 0; i < m->nbearings; i++)
        nsfd += m->bearings[i].has_sfd != 0;
    tm->meshes = xcalloc(gd_model_mesh_count(m), sizeof *tm->meshes);
    tm->owned = xcalloc(m->nmeshes, sizeof *tm->owned);
    tm->sfds = xcalloc(nsfd, sizeof *tm->sfds);
    tm->sfd_bearing = xcalloc(nsfd, sizeof *tm->sfd_bearing);
    tm->loads = xcalloc(m->nexcitations, sizeof *tm->loads);
    tm->prescribed = xcalloc(m->nprescribed, sizeof *tm->prescribed);
    tm->cams = xcalloc(nvalves, sizeof *tm->cams);
    tm->cam_of = xcalloc(nvalves, sizeof *tm->cam_of);
    if (!tm->meshes || !tm->owned || !tm->sfds || !tm->sfd_bearing || !tm->loads ||
        !tm->prescribed || !tm->cams || !tm->cam_of) {
        st = oom(err);
        goto fail;
    }
    gd_transient_spec *sp = &tm->spec;

    /* meshes */
    for (int i = 0; i < m->nmeshes; i++) {
        const gd_mesh *g = &m->meshes[i];
        if (!mesh_is_nonlinear(g)) continue;
        const gd_mesh_dynamics *d = &g->dyn;
        gd_tr_mesh *tmsh = &tm->meshes[sp->nmeshes++];
        gd_tr_mesh_init(sys, i, tmsh);
        tmsh->tvms = d->tvms;
        if (!tmsh->tvms && g->tvms) {
            gd_table *t = NULL;
            if ((st = gd_table_from_tvms(g->tvms, GD_INTERP_LINEAR, &t, err))) {
                if (err) {
                    snprintf(err->file, sizeof err->file, "%s", m->file);
                    err->line = g->loc.line;
                    err->column = g->loc.column;
                }
                goto fail;
            }
            tm->owned[tm->nowned++] = t;
            tmsh->tvms = t;
        }
        tmsh->angle_offset = d->tvms_phase;
        tmsh->damping_per_k = d->damping_per_stiffness;
        tmsh->damping_free = d->damping_separated;
        tmsh->ste = d->ste;
        tmsh->backlash = d->backlash;
        tmsh->gap = d->gap;
        /* 0 with backlash: one-sided contact (no coast flank); without, 0 means 1 */
        tmsh->coast_scale =
            d->coast_stiffness_ratio > 0 || (d->backlash && d->coast_stiffness_ratio == 0)
                ? d->coast_stiffness_ratio
                : 1.0;
    }
    /* the planetary sets' meshes with a law (docs/planetary.md, "Meshes as laws"); their
       TVMS tables are the model's */
    for (int i = m->nmeshes; i < gd_model_mesh_count(m); i++) {
        int set, ring, n;
        gd_model_planetary_mesh(m, i, &set, &ring, &n);
        const gd_planetary_mesh_law *l = &m->planetary[set].mesh_law[ring];
        if (!l->active) continue;
        gd_tr_mesh *tmsh = &tm->meshes[sp->nmeshes++];
        gd_tr_mesh_init(sys, i, tmsh);
        tmsh->tvms = l->tvms;
        tmsh->damping_per_k = l->damping_per_stiffness;
        tmsh->damping_free = l->damping_separated;
        tmsh->backlash = l->backlash;
        tmsh->gap = l->gap;
        tmsh->coast_scale =
            l->coast_stiffness_ratio > 0 || l->backlash ? l->coast_stiffness_ratio : 1.0;
    }
    sp->meshes = tm->meshes;

    /* squeeze film dampers */
    for (int i = 0; i < m->nbearings; i++) {
        const gd_bearing *b = &m->bearings[i];
        if (!b->has_sfd) continue;
        if (gd_system_dof(sys, b->node, GD_X) < 0 || gd_system_dof(sys, b->node, GD_Y) < 0 ||
            (b->node2 >= 0 &&
             (gd_system_dof(sys, b->node2, GD_X) < 0 || gd_system_dof(sys, b->node2, GD_Y) < 0))) {
            char field[96];
            snprintf(field, sizeof field, "bearings[%d].sfd", i);
            st = gd_error_set(err, GD_EINPUT, m->file, b->loc.line, b->loc.column, field,
                              "keep x and y in 'dofs:' (the damper acts on them)",
                              "squeeze film damper '%s': node '%s' has no active x and y DOFs",
                              b->name, m->nodes[b->node].name);
            goto fail;
        }
        tm->sfd_bearing[sp->nsfds] = i;
        gd_tr_sfd *s = &tm->sfds[sp->nsfds++];
        s->node = b->node;
        s->node2 = b->node2;
        s->params = b->sfd;
    }
    sp->sfds = tm->sfds;

    /* loads */
    for (int i = 0; i < m->nexcitations; i++) {
        const gd_excitation *e = &m->excitations[i];
        char field[96], what[GD_NAME_MAX + 32];
        snprintf(field, sizeof field, "excitations.loads[%d]", i);
        snprintf(what, sizeof what, "load '%s'", e->name[0] ? e->name : "(unnamed)");
        int dof = gd_system_dof(sys, e->node, e->dof);
        if (dof < 0) {
            st = inactive_dof(m, e->loc, field, what, e->node, e->dof, err);
            goto fail;
        }
        if (e->law.kind == GD_LOAD_TABLE_ANGLE && !e->law.table) {
            st = gd_error_set(err, GD_EINPUT, m->file, e->loc.line, e->loc.column, field,
                              "give table: {angle: [...], value: [...]}",
                              "%s: table law without a table", what);
            goto fail;
        }
        gd_tr_load *l = &tm->loads[sp->nloads++];
        l->dof = dof;
        l->law = e->law;
    }
    sp->loads = tm->loads;

    /* laws of the registry: the type's directions at node, then at node2 (or ground) */
    tm->laws = xcalloc(m->nlaws, sizeof *tm->laws);
    if (!tm->laws) {
        st = oom(err);
        goto fail;
    }
    for (int i = 0; i < m->nlaws; i++) /* the one maker, the one rule (law_instance.c) */
        if ((st = gd_system_law_instance(sys, i, &tm->laws[i], err))) goto fail;
    sp->laws = tm->laws;
    sp->nlaws = m->nlaws;

    /* prescribed motions */
    for (int i = 0; i < m->nprescribed; i++) {
        const gd_prescription *p = &m->prescribed[i];
        char field[96];
        snprintf(field, sizeof field, "prescribed[%d]", i);
        int dof = gd_system_dof(sys, p->node, p->dof);
        if (dof < 0) {
            st = inactive_dof(m, p->loc, field, "prescribed motion", p->node, p->dof, err);
            goto fail;
        }
        if (p->law.kind == GD_PRESCRIBED_TABLE && !p->law.table) {
            st = gd_error_set(err, GD_EINPUT, m->file, p->loc.line, p->loc.column, field,
                              "give table: {time: [...], angle: [...]}",
                              "prescribed motion: table law without a table");
            goto fail;
        }
        for (int j = 0; j < sp->nprescribed; j++)
            if (tm->prescribed[j].dof == dof) {
                char buf[GD_NODE_NAME_MAX + 8];
                dof_text(m, p->node, p->dof, buf, sizeof buf);
                st = gd_error_set(err, GD_EINPUT, m->file, p->loc.line, p->loc.column, field,
                                  "keep one prescription per DOF", "%s is prescribed twice", buf);
                goto fail;
            }
        gd_tr_prescribed *q = &tm->prescribed[sp->nprescribed++];
        q->dof = dof;
        q->law = p->law;
    }
    sp->prescribed = tm->prescribed;

    /* cams: one valve train per valve */
    for (int i = 0; i < m->ncams; i++) {
        const gd_cam *c = &m->cams[i];
        char field[96], what[GD_NAME_MAX + 32];
        snprintf(field, sizeof field, "cam_torques[%d]", i);
        snprintf(what, sizeof what, "cam '%s'", c->name[0] ? c->name : "(unnamed)");
        int dof = gd_system_dof(sys, c->node, GD_RZ);
        if (dof < 0) {
            st = inactive_dof(m, c->loc, field, what, c->node, GD_RZ, err);
            goto fail;
        }
        if (c->lift.kind == GD_LIFT_TABLE && !c->lift.table) {
            st = gd_error_set(err, GD_EINPUT, m->file, c->loc.line, c->loc.column, field,
                              "give lift: {angle: [...], lift: [...]} or lift: {harmonics: ...}",
                              "%s has no lift table", what);
            goto fail;
        }
        if (c->nvalves <= 0) {
            st = gd_error_set(err, GD_EINPUT, m->file, c->loc.line, c->loc.column, field,
                              "list the valves: valves: [{mass: 0.12 kg, phase: 0 deg}, ...]",
                              "%s drives no valve", what);
            goto fail;
        }
        for (int v = 0; v < c->nvalves; v++) {
            tm->cam_of[sp->ncams] = i;
            gd_tr_cam *t = &tm->cams[sp->ncams++];
            t->dof = dof;
            t->law = &c->lift;
            t->mass = c->valve_mass[v];
            t->phase = c->valve_phase[v];
        }
        if (c->include_acceleration) sp->cam_acceleration = 1;
    }
    sp->cams = tm->cams;
    sp->unbalances = m->excite_unbalances;
    *out = tm;
    return GD_OK;
fail:
    gd_transient_model_free(tm);
    return st;
}

void gd_transient_model_free(gd_transient_model *tm)
{
    if (!tm) return;
    for (int i = 0; i < tm->nowned; i++)
        gd_table_free(tm->owned[i]);
    free(tm->owned);
    free(tm->meshes);
    free(tm->sfds);
    free(tm->sfd_bearing);
    free(tm->loads);
    free(tm->laws);
    free(tm->prescribed);
    free(tm->cams);
    free(tm->cam_of);
    free(tm);
}

int gd_transient_model_mesh_index(const gd_transient_model *tm, int mesh)
{
    for (int i = 0; i < tm->spec.nmeshes; i++)
        if (tm->meshes[i].mesh == mesh) return i;
    return -1;
}

int gd_transient_model_sfd_index(const gd_transient_model *tm, int bearing)
{
    for (int i = 0; i < tm->spec.nsfds; i++)
        if (tm->sfd_bearing[i] == bearing) return i;
    return -1;
}
