/* The builder's unbalances and time-integration items: applied loads, prescribed
 * motions and cam torques, and the tables they carry. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

#define PI 3.14159265358979323846

int gd_build_copy_table(gd_btable *dst, const gd_table_spec *src)
{
    memset(dst, 0, sizeof *dst);
    if (src->n <= 0) return 1;
    dst->x = malloc((size_t)src->n * sizeof *dst->x);
    dst->y = malloc((size_t)src->n * sizeof *dst->y);
    if (!dst->x || !dst->y) {
        free(dst->x);
        free(dst->y);
        dst->x = dst->y = NULL;
        return 0;
    }
    memcpy(dst->x, src->x, (size_t)src->n * sizeof *dst->x);
    memcpy(dst->y, src->y, (size_t)src->n * sizeof *dst->y);
    dst->n = src->n;
    dst->interp = src->interp;
    return 1;
}

gd_status gd_build_make_table(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                              const gd_btable *t, double period, gd_table **out)
{
    gd_status st = gd_table_new(t->n, t->x, t->y, period, t->interp, out, err);
    if (st && err && st == GD_EINPUT) {
        /* locate the library's complaint at the table */
        char msg[sizeof err->message], hint[sizeof err->hint];
        snprintf(msg, sizeof msg, "%s", err->message);
        snprintf(hint, sizeof hint, "%s", err->hint);
        return gd_build_fail(m, err, loc, path, path, hint, "%s", msg);
    }
    return st;
}

/* Grows a model array and its builder array by one; 0 on failure. */
static int grow2(void *a, void *b, int n, size_t sa, size_t sb)
{
    return gd_build_grow(a, n, sa) && gd_build_grow(b, n, sb);
}

static void item_drop(gd_bitem *it, gd_btable *t)
{
    free(it->path);
    free(it->node);
    free(it->node2);
    free(it->material);
    if (t) {
        free(t->x);
        free(t->y);
    }
}

static gd_status check_dof(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                           gd_dof dof)
{
    if ((int)dof >= 0 && (int)dof < GD_NODE_DOFS) return GD_OK;
    char q[200];
    return gd_build_fail(m, err, loc, NULL, gd_build_path(q, sizeof q, path, "dof"),
                         "use one of GD_X ... GD_RZ", "unknown DOF %d", (int)dof);
}

static gd_status check_table_given(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                                   const gd_table_spec *t)
{
    char q[200];
    gd_build_path(q, sizeof q, path, "table");
    if (t->n < 2 || !t->x || !t->y)
        return gd_build_fail(m, err, loc, q, q, "give two points or more", "only %d point%s",
                             t->n > 0 ? t->n : 0, t->n == 1 ? "" : "s");
    return GD_OK;
}

/* ---- unbalances ---- */

void gd_unbalance_spec_init(gd_unbalance_spec *s)
{
    memset(s, 0, sizeof *s);
}

gd_status gd_model_add_unbalance(gd_model *m, const gd_unbalance_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nunbalances;
    char path[160], fb[32];
    gd_build_item_path(path, sizeof path, s->path, "unbalances", idx);
    gd_unbalance u;
    memset(&u, 0, sizeof u);
    snprintf(fb, sizeof fb, "unbalance%d", idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, u.name)) ||
        (st = gd_build_positive(m, err, s->loc, path, "amount", s->amount, 0)))
        return st;
    u.node = -1;
    u.amount = s->amount;
    u.phase = s->phase;
    u.loc = s->loc;
    gd_bitem it;
    if (!gd_build_item_init(&it, path, s->node, NULL, NULL)) return gd_build_oom(m, err);
    if (!grow2(&m->unbalances, &m->build->unbalances, idx, sizeof *m->unbalances,
               sizeof *m->build->unbalances)) {
        item_drop(&it, NULL);
        return gd_build_oom(m, err);
    }
    m->unbalances[idx] = u;
    m->build->unbalances[idx] = it;
    m->nunbalances++;
    if (index) *index = idx;
    return GD_OK;
}

/* ---- applied loads ---- */

void gd_excitation_spec_init(gd_excitation_spec *s)
{
    memset(s, 0, sizeof *s);
    s->dof = GD_RZ;
    s->law.kind = GD_LOAD_CONSTANT;
    s->table.interp = GD_INTERP_LINEAR;
}

gd_status gd_model_add_excitation(gd_model *m, const gd_excitation_spec *s, int *index,
                                  gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nexcitations;
    char path[160], fb[32];
    gd_build_item_path(path, sizeof path, s->path, "excitations.loads", idx);
    gd_excitation e;
    memset(&e, 0, sizeof e);
    snprintf(fb, sizeof fb, "load%d", idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, e.name)) ||
        (st = check_dof(m, err, s->loc, path, s->dof)))
        return st;
    e.node = -1;
    e.dof = s->dof;
    e.loc = s->loc;
    e.law = s->law;
    e.law.table = NULL;
    switch (s->law.kind) {
    case GD_LOAD_CONSTANT:
        break;
    case GD_LOAD_HARMONIC_TIME:
        st = gd_build_positive(m, err, s->loc, path, "frequency", s->law.frequency, 0);
        break;
    case GD_LOAD_HARMONIC_ANGLE:
        st = gd_build_positive(m, err, s->loc, path, "order", s->law.frequency, 0);
        break;
    case GD_LOAD_TABLE_ANGLE:
        st = check_table_given(m, err, s->loc, path, &s->table);
        break;
    default: {
        char q[200];
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "law"),
                             "use a gd_load_kind", "unknown load law %d", (int)s->law.kind);
    }
    }
    if (st) return st;
    gd_bitem it;
    gd_btable t;
    memset(&t, 0, sizeof t);
    if (!gd_build_item_init(&it, path, s->node, NULL, NULL)) return gd_build_oom(m, err);
    if ((s->law.kind == GD_LOAD_TABLE_ANGLE && !gd_build_copy_table(&t, &s->table)) ||
        !grow2(&m->excitations, &m->build->excitations, idx, sizeof *m->excitations,
               sizeof *m->build->excitations) ||
        !gd_build_grow(&m->build->excitation_tables, idx, sizeof *m->build->excitation_tables)) {
        item_drop(&it, &t);
        return gd_build_oom(m, err);
    }
    m->excitations[idx] = e;
    m->build->excitations[idx] = it;
    m->build->excitation_tables[idx] = t;
    m->nexcitations++;
    if (index) *index = idx;
    return GD_OK;
}

/* ---- prescribed motion ---- */

void gd_prescribed_spec_init(gd_prescribed_spec *s)
{
    memset(s, 0, sizeof *s);
    s->dof = GD_RZ;
    s->law.kind = GD_PRESCRIBED_NOMINAL;
    s->table.interp = GD_INTERP_SPLINE;
}

gd_status gd_model_add_prescribed(gd_model *m, const gd_prescribed_spec *s, int *index,
                                  gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nprescribed;
    char path[160];
    gd_build_item_path(path, sizeof path, s->path, "prescribed", idx);
    if ((st = check_dof(m, err, s->loc, path, s->dof))) return st;
    gd_prescription p;
    memset(&p, 0, sizeof p);
    p.node = -1;
    p.dof = s->dof;
    p.loc = s->loc;
    p.law = s->law;
    p.law.table = NULL;
    switch (s->law.kind) {
    case GD_PRESCRIBED_NOMINAL:
    case GD_PRESCRIBED_SPEED:
        break;
    case GD_PRESCRIBED_HARMONIC:
        st = gd_build_positive(m, err, s->loc, path, "frequency", s->law.frequency, 0);
        break;
    case GD_PRESCRIBED_TABLE:
        st = check_table_given(m, err, s->loc, path, &s->table);
        break;
    default: {
        char q[200];
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "law"),
                             "use a gd_prescribed_kind", "unknown prescribed motion %d",
                             (int)s->law.kind);
    }
    }
    if (st) return st;
    gd_bitem it;
    gd_btable t;
    memset(&t, 0, sizeof t);
    if (!gd_build_item_init(&it, path, s->node, NULL, NULL)) return gd_build_oom(m, err);
    if ((s->law.kind == GD_PRESCRIBED_TABLE && !gd_build_copy_table(&t, &s->table)) ||
        !grow2(&m->prescribed, &m->build->prescribed, idx, sizeof *m->prescribed,
               sizeof *m->build->prescribed) ||
        !gd_build_grow(&m->build->prescribed_tables, idx, sizeof *m->build->prescribed_tables)) {
        item_drop(&it, &t);
        return gd_build_oom(m, err);
    }
    m->prescribed[idx] = p;
    m->build->prescribed[idx] = it;
    m->build->prescribed_tables[idx] = t;
    m->nprescribed++;
    if (index) *index = idx;
    return GD_OK;
}

/* ---- cam torques ---- */

void gd_cam_spec_init(gd_cam_spec *s)
{
    memset(s, 0, sizeof *s);
    s->lift.kind = GD_LIFT_TABLE;
    s->lift_table.interp = GD_INTERP_SPLINE;
    s->include_acceleration = 1;
}

gd_status gd_model_add_cam(gd_model *m, const gd_cam_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->ncams;
    char path[160], fb[32], q[200];
    gd_build_item_path(path, sizeof path, s->path, "cam_torques", idx);
    gd_cam c;
    memset(&c, 0, sizeof c);
    snprintf(fb, sizeof fb, "cam%d", idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, c.name))) return st;
    c.node = -1;
    c.loc = s->loc;
    c.include_acceleration = s->include_acceleration != 0;
    c.lift = s->lift;
    c.lift.table = NULL;
    gd_build_path(q, sizeof q, path, "lift");
    if (s->lift.kind == GD_LIFT_TABLE) {
        if (s->lift_table.n < 2 || !s->lift_table.x || !s->lift_table.y)
            return gd_build_fail(m, err, s->loc, q, q,
                                 "give the valve lift over one cam revolution, two points or more",
                                 "cam torque without a lift law");
    } else if (s->lift.kind != GD_LIFT_HARMONIC || s->lift.harmonic.n < 0 ||
               s->lift.harmonic.n > GD_HARMONICS_MAX) {
        return gd_build_fail(m, err, s->loc, q, q, "a table or up to 32 harmonics",
                             "invalid lift law");
    }
    gd_build_path(q, sizeof q, path, "valves");
    if (s->nvalves <= 0 || !s->valve_mass)
        return gd_build_fail(m, err, s->loc, q, q,
                             "list the valves: [{mass: 0.1 kg, phase: 0 deg}]", "no valves");
    for (int j = 0; j < s->nvalves; j++) {
        char vp[220];
        snprintf(vp, sizeof vp, "%s[%d]", q, j);
        if ((st = gd_build_positive(m, err, s->loc, vp, "mass", s->valve_mass[j], 0))) return st;
    }
    gd_bitem it;
    gd_btable t;
    memset(&t, 0, sizeof t);
    if (!gd_build_item_init(&it, path, s->camshaft, NULL, NULL)) return gd_build_oom(m, err);
    c.valve_mass = malloc((size_t)s->nvalves * sizeof *c.valve_mass);
    c.valve_phase = calloc((size_t)s->nvalves, sizeof *c.valve_phase);
    if (!c.valve_mass || !c.valve_phase ||
        (s->lift.kind == GD_LIFT_TABLE && !gd_build_copy_table(&t, &s->lift_table)) ||
        !grow2(&m->cams, &m->build->cams, idx, sizeof *m->cams, sizeof *m->build->cams) ||
        !gd_build_grow(&m->build->cam_tables, idx, sizeof *m->build->cam_tables)) {
        free(c.valve_mass);
        free(c.valve_phase);
        item_drop(&it, &t);
        return gd_build_oom(m, err);
    }
    memcpy(c.valve_mass, s->valve_mass, (size_t)s->nvalves * sizeof *c.valve_mass);
    if (s->valve_phase)
        memcpy(c.valve_phase, s->valve_phase, (size_t)s->nvalves * sizeof *c.valve_phase);
    c.nvalves = s->nvalves;
    m->cams[idx] = c;
    m->build->cams[idx] = it;
    m->build->cam_tables[idx] = t;
    m->ncams++;
    if (index) *index = idx;
    return GD_OK;
}

/* ---- finish ---- */

gd_status gd_build_resolve_dynamics(gd_model *m, gd_error *err)
{
    gd_status st;
    gd_model_build *b = m->build;
    char tq[220];
    for (int i = 0; i < m->nunbalances; i++)
        if ((st = gd_build_node_ref(m, err, m->unbalances[i].loc, b->unbalances[i].path, "node",
                                    b->unbalances[i].node, &m->unbalances[i].node)))
            return st;
    for (int i = 0; i < m->nexcitations; i++) {
        gd_excitation *e = &m->excitations[i];
        if ((st = gd_build_node_ref(m, err, e->loc, b->excitations[i].path, "node",
                                    b->excitations[i].node, &e->node)))
            return st;
        if (e->law.kind == GD_LOAD_TABLE_ANGLE) {
            gd_table *t;
            gd_build_path(tq, sizeof tq, b->excitations[i].path, "table");
            if ((st =
                     gd_build_make_table(m, err, e->loc, tq, &b->excitation_tables[i], 2 * PI, &t)))
                return st;
            e->law.table = t;
        }
    }
    for (int i = 0; i < m->nprescribed; i++) {
        gd_prescription *p = &m->prescribed[i];
        const char *path = b->prescribed[i].path;
        if ((st = gd_build_node_ref(m, err, p->loc, path, "node", b->prescribed[i].node, &p->node)))
            return st;
        for (int j = 0; j < i; j++)
            if (m->prescribed[j].node == p->node && m->prescribed[j].dof == p->dof)
                return gd_build_fail(m, err, p->loc, NULL, path, "prescribe each DOF once",
                                     "this DOF is already prescribed (entry %d)", j);
        if (p->law.kind == GD_PRESCRIBED_TABLE) {
            gd_table *t;
            gd_build_path(tq, sizeof tq, path, "table");
            if ((st = gd_build_make_table(m, err, p->loc, tq, &b->prescribed_tables[i], 0, &t)))
                return st;
            p->law.table = t;
        }
    }
    for (int i = 0; i < m->ncams; i++) {
        gd_cam *c = &m->cams[i];
        if ((st = gd_build_node_ref(m, err, c->loc, b->cams[i].path, "camshaft", b->cams[i].node,
                                    &c->node)))
            return st;
        if (c->lift.kind == GD_LIFT_TABLE) {
            gd_table *t;
            gd_build_path(tq, sizeof tq, b->cams[i].path, "lift");
            if ((st = gd_build_make_table(m, err, c->loc, tq, &b->cam_tables[i], 2 * PI, &t)))
                return st;
            c->lift.table = t;
        }
    }
    return GD_OK;
}
