/* The builder's idling gears, synchronisers and gear selection (docs/model-format.md,
 * "idlers"). An idler is made of what exists: a one-node shaft, a disk and a bearing to
 * its carrying node; an engaged synchroniser adds a torsional spring (its lock). The
 * selection is settled by name before the model is resolved (the locks are springs the
 * resolution then treats like any other); the nodes are resolved after the supports. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

#define PI 3.14159265358979323846
#define DEFAULT_LOCK_STIFFNESS 1e7 /* N m/rad: builder.h */

void gd_idler_spec_init(gd_idler_spec *s)
{
    memset(s, 0, sizeof *s);
    s->diametral_inertia = -1;
}

void gd_synchroniser_spec_init(gd_synchroniser_spec *s)
{
    memset(s, 0, sizeof *s);
    s->stiffness = DEFAULT_LOCK_STIFFNESS;
}

gd_status gd_model_add_idler(gd_model *m, const gd_idler_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nidlers;
    char path[160], q[200];
    gd_build_item_path(path, sizeof path, s->path, "idlers", idx);
    gd_idler id;
    memset(&id, 0, sizeof id);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, NULL, id.name))) return st;
    if (strlen(s->name) + 8 >= GD_NAME_MAX)
        return gd_build_fail(m, err, s->loc, gd_build_path(q, sizeof q, path, "name"), q,
                             "use a shorter name", "name too long for the idler's bearing name");
    if (!s->on)
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "on"),
                             "name the node of the shaft the idler turns on", "no `on:` node");
    if ((st = gd_build_positive(m, err, s->loc, path, "mass", s->mass, 0)) ||
        (st = gd_build_positive(m, err, s->loc, path, "polar_inertia", s->polar_inertia, 0)) ||
        (st =
             gd_build_positive(m, err, s->loc, path, "radial_stiffness", s->radial_stiffness, 0)) ||
        (st = gd_build_positive(m, err, s->loc, path, "tilt_stiffness", s->tilt_stiffness, 1)) ||
        (st = gd_build_positive(m, err, s->loc, path, "radial_damping", s->radial_damping, 1)))
        return st;
    id.node = id.carrier = id.synchroniser = -1;
    id.loc = s->loc;
    gd_bidler bi = {gd_build_strdup(path), gd_build_strdup(s->on)};
    if (!bi.path || !bi.on || !gd_build_grow(&m->idlers, m->nidlers, sizeof *m->idlers) ||
        !gd_build_grow(&m->build->idlers, m->nidlers, sizeof *m->build->idlers)) {
        free(bi.path);
        free(bi.on);
        return gd_build_oom(m, err);
    }
    m->idlers[idx] = id;
    m->build->idlers[idx] = bi;
    m->nidlers++;

    /* its own node on a one-node shaft, its body, its needle bearing */
    gd_station_spec sta;
    gd_station_spec_init(&sta);
    sta.name = s->name;
    sta.loc = s->loc;
    gd_shaft_spec sh;
    gd_shaft_spec_init(&sh);
    sh.name = s->name;
    sh.nstations = 1;
    sh.stations = &sta;
    sh.loc = s->loc;
    sh.path = path;
    gd_disk_spec d;
    gd_disk_spec_init(&d);
    d.name = s->name;
    d.node = s->name;
    d.mass = s->mass;
    d.polar_inertia = s->polar_inertia;
    d.diametral_inertia = s->diametral_inertia;
    d.loc = s->loc;
    d.path = path;
    char bname[GD_NAME_MAX];
    snprintf(bname, sizeof bname, "%.54s.needle", s->name);
    gd_bearing_spec b;
    gd_bearing_spec_init(&b);
    b.name = bname;
    b.node = s->name;
    b.to = s->on;
    b.coeffs.kxx = b.coeffs.kyy = b.coeffs.kzz = s->radial_stiffness;
    b.coeffs.ktilt = s->tilt_stiffness;
    b.coeffs.cxx = b.coeffs.cyy = b.coeffs.czz = s->radial_damping;
    b.loc = s->loc;
    b.path = path;
    if ((st = gd_model_add_shaft(m, &sh, NULL, err)) ||
        (st = gd_model_add_disk(m, &d, NULL, err)) || (st = gd_model_add_bearing(m, &b, NULL, err)))
        return st;
    if (index) *index = idx;
    return GD_OK;
}

static gd_status check_cone(const gd_model *m, gd_error *err, const gd_synchroniser_spec *s,
                            const char *path)
{
    const gd_synchro_cone *c = &s->cone;
    if (c->mu == 0 && c->force == 0 && c->radius == 0 && c->angle == 0 && c->cones == 0)
        return GD_OK;
    char q[200];
    gd_build_path(q, sizeof q, path, "cone");
    gd_status st;
    if ((st = gd_build_positive(m, err, s->loc, q, "mu", c->mu, 0)) ||
        (st = gd_build_positive(m, err, s->loc, q, "force", c->force, 0)) ||
        (st = gd_build_positive(m, err, s->loc, q, "radius", c->radius, 0)) ||
        (st = gd_build_positive(m, err, s->loc, q, "angle", c->angle, 0)))
        return st;
    char f[240];
    if (c->cones < 1)
        return gd_build_fail(m, err, s->loc, gd_build_path(f, sizeof f, q, "cones"), f,
                             "give 1 or more friction surfaces (e.g. 1, 2 or 3)",
                             "%d friction cones", c->cones);
    if (c->angle >= PI / 4)
        return gd_build_fail(m, err, s->loc, gd_build_path(f, sizeof f, q, "angle"), f,
                             "a synchroniser cone's half angle is about 6-8 deg",
                             "cone angle %g rad above 45 deg", c->angle);
    return GD_OK;
}

gd_status gd_model_add_synchroniser(gd_model *m, const gd_synchroniser_spec *s, int *index,
                                    gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nsynchronisers;
    char path[160], q[200];
    gd_build_item_path(path, sizeof path, s->path, "synchronisers", idx);
    gd_synchroniser g;
    memset(&g, 0, sizeof g);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, NULL, g.name))) return st;
    if (strlen(s->name) + 6 >= GD_NAME_MAX)
        return gd_build_fail(m, err, s->loc, gd_build_path(q, sizeof q, path, "name"), q,
                             "use a shorter name", "name too long for the lock's spring name");
    if (!s->node)
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "node"),
                             "name the shaft node the synchroniser's hub sits on", "no node");
    if (!s->idlers[0])
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "idlers"),
                             "list the one or two idlers it engages, e.g. [idler3, idler4]",
                             "no idlers");
    if (s->idlers[1] && !strcmp(s->idlers[0], s->idlers[1]))
        return gd_build_fail(m, err, s->loc, gd_build_path(q, sizeof q, path, "idlers"), q,
                             "list two different idlers, or one", "idler '%s' listed twice",
                             s->idlers[0]);
    if ((st = gd_build_positive(m, err, s->loc, path, "stiffness", s->stiffness, 0)) ||
        (st = gd_build_positive(m, err, s->loc, path, "damping", s->damping, 1)) ||
        (st = check_cone(m, err, s, path)))
        return st;
    g.node = g.engaged = g.spring = -1;
    g.idler[0] = g.idler[1] = -1;
    g.stiffness = s->stiffness;
    g.damping = s->damping;
    g.cone = s->cone;
    g.loc = s->loc;
    gd_bsync bs = {gd_build_strdup(path),
                   gd_build_strdup(s->node),
                   {gd_build_strdup(s->idlers[0]), gd_build_strdup(s->idlers[1])},
                   gd_build_strdup(s->engaged)};
    int ok = bs.path && bs.node && bs.idlers[0] && (!s->idlers[1] || bs.idlers[1]) &&
             (!s->engaged || bs.engaged);
    if (!ok || !gd_build_grow(&m->synchronisers, m->nsynchronisers, sizeof *m->synchronisers) ||
        !gd_build_grow(&m->build->syncs, m->nsynchronisers, sizeof *m->build->syncs)) {
        free(bs.path);
        free(bs.node);
        free(bs.idlers[0]);
        free(bs.idlers[1]);
        free(bs.engaged);
        return gd_build_oom(m, err);
    }
    m->synchronisers[idx] = g;
    m->build->syncs[idx] = bs;
    m->nsynchronisers++;
    if (index) *index = idx;
    return GD_OK;
}

gd_status gd_model_add_gear(gd_model *m, int number, const char *idler, gd_loc loc,
                            const char *path, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    char p[64];
    if (!path) snprintf(p, sizeof p, "gears.%d", number);
    const char *gp = path ? path : p;
    if (number < 1 || number > 99)
        return gd_build_fail(m, err, loc, gp, gp, "number the gears 1, 2, ... (reverse e.g. 6)",
                             "gear number %d", number);
    if (!idler)
        return gd_build_fail(m, err, loc, gp, gp, "name the idler the gear engages",
                             "no idler for gear %d", number);
    for (int i = 0; i < m->ngears; i++)
        if (m->gears[i].number == number)
            return gd_build_fail(m, err, loc, gp, gp, "give each gear number once",
                                 "gear %d given twice", number);
    gd_bgear bg = {gd_build_strdup(gp), gd_build_strdup(idler), loc};
    if (!bg.path || !bg.idler || !gd_build_grow(&m->gears, m->ngears, sizeof *m->gears) ||
        !gd_build_grow(&m->build->gears, m->ngears, sizeof *m->build->gears)) {
        free(bg.path);
        free(bg.idler);
        return gd_build_oom(m, err);
    }
    m->gears[m->ngears] = (gd_gear_choice){number, -1};
    m->build->gears[m->ngears] = bg;
    m->ngears++;
    return GD_OK;
}

gd_status gd_model_select_gear(gd_model *m, int number, gd_loc loc, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    if (number < 0)
        return gd_build_fail(m, err, loc, "gear", "gear", "select a gear number (0: neutral)",
                             "gear %d", number);
    m->gear = number;
    m->build->gear_loc = loc;
    return GD_OK;
}

gd_status gd_model_set_shift(gd_model *m, int from, int to, double time, gd_loc loc, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    if (from < 1 || to < 1 || from == to)
        return gd_build_fail(m, err, loc, "shift", "shift",
                             "shift between two gear numbers of `gears:`, e.g. 3:4@0.5",
                             "shift from gear %d to gear %d", from, to);
    if (!(time >= 0) || !isfinite(time))
        return gd_build_fail(m, err, loc, "shift.at", "shift.at", "give the shift time in s, >= 0",
                             "shift time %g", time);
    m->build->shift_from = from;
    m->build->shift_to = to;
    m->build->shift_time = time;
    m->build->shift_loc = loc;
    return GD_OK;
}

/* The idler named name, or -1. */
static int find_idler(const gd_model *m, const char *name)
{
    for (int i = 0; name && i < m->nidlers; i++)
        if (!strcmp(m->idlers[i].name, name)) return i;
    return -1;
}

/* "idlers: a b c" for a hint */
static void idler_list(const gd_model *m, char *buf, size_t cap)
{
    size_t n = (size_t)snprintf(buf, cap, "%s", m->nidlers ? "idlers:" : "no idlers in `idlers:`");
    for (int i = 0; i < m->nidlers && n < cap; i++)
        n += (size_t)snprintf(buf + n, cap - n, " %s", m->idlers[i].name);
}

static gd_status not_an_idler(const gd_model *m, gd_error *err, gd_loc loc, const char *field,
                              const char *name)
{
    char hint[400], list[240];
    idler_list(m, list, sizeof list);
    snprintf(hint, sizeof hint,
             "only an idler can be engaged: a gear fixed on its shaft (a disk or node) turns "
             "with it already; list the gear under `idlers:` with `on:` its shaft node (%s)",
             list);
    return gd_build_fail(m, err, loc, field, field, hint, "'%s' is not an idler", name);
}

/* The idlers of the synchronisers, checked by name; each idler's synchroniser. */
static gd_status link_idlers(gd_model *m, gd_error *err)
{
    gd_model_build *b = m->build;
    char q[220];
    for (int k = 0; k < m->nsynchronisers; k++) {
        gd_synchroniser *g = &m->synchronisers[k];
        for (int j = 0; j < 2 && b->syncs[k].idlers[j]; j++) {
            const char *nm = b->syncs[k].idlers[j];
            snprintf(q, sizeof q, "%s.idlers[%d]", b->syncs[k].path, j);
            int i = find_idler(m, nm);
            if (i < 0) return not_an_idler(m, err, g->loc, q, nm);
            if (m->idlers[i].synchroniser >= 0)
                return gd_build_fail(m, err, g->loc, q, q,
                                     "an idler is engaged by one synchroniser: remove it here or "
                                     "there",
                                     "idler '%s' is on synchronisers '%s' and '%s'", nm,
                                     m->synchronisers[m->idlers[i].synchroniser].name, g->name);
            m->idlers[i].synchroniser = k;
            g->idler[j] = i;
        }
    }
    return GD_OK;
}

static gd_status add_shift(gd_model *m, gd_error *err);

gd_status gd_build_engage_synchronisers(gd_model *m, gd_error *err)
{
    gd_model_build *b = m->build;
    gd_status st;
    char q[220], hint[300];
    if ((st = link_idlers(m, err))) return st;
    /* the gears: each names an idler on a synchroniser */
    int selected = -1; /* idler of the selected gear */
    for (int i = 0; i < m->ngears; i++) {
        int id = find_idler(m, b->gears[i].idler);
        if (id < 0)
            return not_an_idler(m, err, b->gears[i].loc, b->gears[i].path, b->gears[i].idler);
        if (m->idlers[id].synchroniser < 0)
            return gd_build_fail(m, err, b->gears[i].loc, b->gears[i].path, b->gears[i].path,
                                 "list the idler under a synchroniser's `idlers:`",
                                 "gear %d: idler '%s' is on no synchroniser", m->gears[i].number,
                                 b->gears[i].idler);
        m->gears[i].idler = id;
        if (m->gears[i].number == m->gear) selected = id;
    }
    if (m->gear > 0 && selected < 0) {
        int n = snprintf(hint, sizeof hint, "%s",
                         m->ngears ? "select one of the gears in `gears:`:"
                                   : "add a `gears:` map (number: idler), e.g. {3: idler3}");
        for (int i = 0; i < m->ngears && n < (int)sizeof hint; i++)
            n += snprintf(hint + n, sizeof hint - (size_t)n, " %d", m->gears[i].number);
        if (n < (int)sizeof hint) snprintf(hint + n, sizeof hint - (size_t)n, ", or 0 (neutral)");
        return gd_build_fail(m, err, b->gear_loc, "gear", "gear", hint,
                             "gear %d does not exist in this model", m->gear);
    }
    /* each synchroniser: its own `engaged`, the selected gear's; one at most */
    for (int k = 0; k < m->nsynchronisers; k++) {
        gd_synchroniser *g = &m->synchronisers[k];
        const gd_bsync *bs = &b->syncs[k];
        int own = -1;
        if (bs->engaged) {
            snprintf(q, sizeof q, "%s.engaged", bs->path);
            own = find_idler(m, bs->engaged);
            if (own < 0 || (g->idler[0] != own && g->idler[1] != own))
                return gd_build_fail(m, err, g->loc, q, q,
                                     "engage one of the synchroniser's own idlers (or remove "
                                     "`engaged:` for neutral)",
                                     "'%s' is not an idler of synchroniser '%s'", bs->engaged,
                                     g->name);
        }
        int sel =
            selected >= 0 && (g->idler[0] == selected || g->idler[1] == selected) ? selected : -1;
        if (own >= 0 && sel >= 0 && own != sel) {
            snprintf(q, sizeof q, "%s.engaged", bs->path);
            return gd_build_fail(m, err, g->loc, q, q,
                                 "a synchroniser engages one gear: remove `engaged:` here or "
                                 "select another gear",
                                 "two gears engaged on synchroniser '%s': '%s' (engaged:) and "
                                 "'%s' (gear %d)",
                                 g->name, m->idlers[own].name, m->idlers[sel].name, m->gear);
        }
        g->engaged = own >= 0 ? own : sel;
        if (g->engaged < 0) continue;
        m->idlers[g->engaged].engaged = 1;
        char name[GD_NAME_MAX];
        snprintf(name, sizeof name, "%.56s.lock", g->name);
        gd_spring_spec sp;
        gd_spring_spec_init(&sp);
        sp.name = name;
        sp.node = m->idlers[g->engaged].name;
        sp.to = bs->node;
        sp.dof = GD_RZ;
        sp.stiffness = g->stiffness;
        sp.damping = g->damping;
        sp.loc = g->loc;
        sp.path = bs->path;
        g->spring = m->nsprings;
        if ((st = gd_model_add_spring(m, &sp, NULL, err))) return st;
    }
    return b->shift_from ? add_shift(m, err) : GD_OK;
}

static int gear_idler(const gd_model *m, int number)
{
    for (int i = 0; i < m->ngears; i++)
        if (m->gears[i].number == number) return m->gears[i].idler;
    return -1;
}

/* The shift's two laws: the old gear's lock cancelled, the new gear's cone (builder.h). */
static gd_status add_shift(gd_model *m, gd_error *err)
{
    gd_model_build *b = m->build;
    gd_loc loc = b->shift_loc;
    int from = gear_idler(m, b->shift_from), to = gear_idler(m, b->shift_to);
    if (from < 0 || to < 0)
        return gd_build_fail(
            m, err, loc, from < 0 ? "shift.from" : "shift.to", from < 0 ? "shift.from" : "shift.to",
            "shift between gears of `gears:`", "gear %d does not exist in this model",
            from < 0 ? b->shift_from : b->shift_to);
    if (!m->idlers[from].engaged)
        return gd_build_fail(m, err, loc, "shift.from", "shift.from",
                             "select the gear the shift starts from (`gear:` or --set gear=N)",
                             "the shift starts from gear %d, which is not engaged", b->shift_from);
    if (m->idlers[to].engaged)
        return gd_build_fail(m, err, loc, "shift.to", "shift.to",
                             "shift to a gear of another synchroniser position",
                             "gear %d is engaged already", b->shift_to);
    const gd_synchroniser *gf = &m->synchronisers[m->idlers[from].synchroniser];
    const gd_synchroniser *gt = &m->synchronisers[m->idlers[to].synchroniser];
    const gd_synchro_cone *c = &gt->cone;
    if (!(c->mu > 0))
        return gd_build_fail(m, err, loc, "shift.to", "shift.to",
                             "give the synchroniser a `cone: {mu, force, radius, angle}`",
                             "synchroniser '%s' of gear %d has no cone to synchronise with",
                             gt->name, b->shift_to);
    /* T_c = mu F R_c n / sin(alpha) (src/laws/synchro_cone.c) */
    double torque = c->mu * c->force * c->radius * c->cones / sin(c->angle);
    const gd_bsync *bf = &b->syncs[m->idlers[from].synchroniser];
    const gd_bsync *bt = &b->syncs[m->idlers[to].synchroniser];
    double rel[3] = {b->shift_time, gf->stiffness, gf->damping};
    double cone[3] = {b->shift_time, torque, 1000.0};
    gd_law_spec ls;
    gd_law_spec_init(&ls);
    ls.name = "shift.release";
    ls.type = &gd_law_gear_release;
    ls.node = m->idlers[from].name;
    ls.node2 = bf->node;
    ls.values = rel;
    ls.loc = loc;
    ls.path = "shift";
    gd_status st = gd_model_add_law(m, &ls, NULL, err);
    if (st) return st;
    ls.name = "shift.cone";
    ls.type = &gd_law_synchro_cone;
    ls.node = m->idlers[to].name;
    ls.node2 = bt->node;
    ls.values = cone;
    return gd_model_add_law(m, &ls, NULL, err);
}

gd_status gd_build_resolve_idlers(gd_model *m, gd_error *err)
{
    gd_model_build *b = m->build;
    gd_status st;
    for (int i = 0; i < m->nidlers; i++) {
        gd_idler *id = &m->idlers[i];
        id->node = gd_model_find_node(m, id->name);
        if ((st = gd_build_node_ref(m, err, id->loc, b->idlers[i].path, "on", b->idlers[i].on,
                                    &id->carrier)))
            return st;
        if (m->nodes[id->node].shaft == m->nodes[id->carrier].shaft) {
            char q[200];
            gd_build_path(q, sizeof q, b->idlers[i].path, "on");
            return gd_build_fail(m, err, id->loc, q, q, "name a node of the carrying shaft",
                                 "idler '%s' cannot turn on itself", id->name);
        }
    }
    for (int k = 0; k < m->nsynchronisers; k++) {
        gd_synchroniser *g = &m->synchronisers[k];
        if ((st = gd_build_node_ref(m, err, g->loc, b->syncs[k].path, "node", b->syncs[k].node,
                                    &g->node)))
            return st;
        for (int j = 0; j < 2 && g->idler[j] >= 0; j++) {
            const gd_idler *id = &m->idlers[g->idler[j]];
            int sync_shaft = m->nodes[g->node].shaft, idler_shaft = m->nodes[id->carrier].shaft;
            if (sync_shaft != idler_shaft) {
                char q[200];
                gd_build_path(q, sizeof q, b->syncs[k].path, "node");
                return gd_build_fail(m, err, g->loc, q, q,
                                     "put the synchroniser on a node of the shaft its idlers turn "
                                     "on",
                                     "synchroniser '%s' is on shaft '%s', its idler '%s' turns on "
                                     "shaft '%s'",
                                     g->name, m->shafts[sync_shaft].name, id->name,
                                     m->shafts[idler_shaft].name);
            }
        }
    }
    return GD_OK;
}
