/* Reading `idlers:`, `synchronisers:`, `gears:` and `gear:` into builder specs
 * (docs/model-format.md, "idlers"). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/model_file_impl.h"

static const char *const IDLER_KEYS[] = {"name",
                                         "on",
                                         "mass",
                                         "polar_inertia",
                                         "diametral_inertia",
                                         "radial_stiffness",
                                         "tilt_stiffness",
                                         "radial_damping",
                                         NULL};
static const char *const SYNC_KEYS[] = {"name",      "node",    "idlers", "engaged",
                                        "stiffness", "damping", "cone",   NULL};
static const char *const SHIFT_KEYS[] = {"from", "to", "at", NULL};
static const char *const CONE_KEYS[] = {"mu", "force", "radius", "cones", "angle", NULL};

static gd_status read_idler(gd_mparser *p, const gd_ynode *im, const char *q, size_t i)
{
    (void)i;
    gd_status st;
    char name[GD_NAME_MAX];
    gd_idler_spec s;
    gd_idler_spec_init(&s);
    if ((st = gd_yexpect(&p->r, im, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, im, q, IDLER_KEYS)) ||
        (st = gd_mp_read_name(p, im, q, name, NULL, 1)) ||
        (st = gd_mp_node_name(p, im, "on", q, 1, &s.on)) ||
        (st = gd_yread_qty(&p->r, im, "mass", q, GD_QTY_MASS, GD_YREQ | GD_YPOS, &s.mass, NULL)) ||
        (st = gd_yread_qty(&p->r, im, "polar_inertia", q, GD_QTY_INERTIA, GD_YREQ | GD_YPOS,
                           &s.polar_inertia, NULL)) ||
        (st = gd_yread_qty(&p->r, im, "diametral_inertia", q, GD_QTY_INERTIA, GD_YNONNEG,
                           &s.diametral_inertia, NULL)) ||
        (st = gd_yread_qty(&p->r, im, "radial_stiffness", q, GD_QTY_STIFFNESS, GD_YREQ | GD_YPOS,
                           &s.radial_stiffness, NULL)) ||
        (st = gd_yread_qty(&p->r, im, "tilt_stiffness", q, GD_QTY_ROT_STIFFNESS, GD_YNONNEG,
                           &s.tilt_stiffness, NULL)) ||
        (st = gd_yread_qty(&p->r, im, "radial_damping", q, GD_QTY_DAMPING, GD_YNONNEG,
                           &s.radial_damping, NULL)))
        return st;
    s.name = name;
    s.loc = gd_mp_loc(im);
    s.path = q;
    return gd_model_add_idler(p->m, &s, NULL, p->r.err);
}

static gd_status read_cone(gd_mparser *p, const gd_ynode *cm, const char *q, gd_synchro_cone *c)
{
    gd_status st;
    long cones = 1;
    if ((st = gd_yexpect(&p->r, cm, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, cm, q, CONE_KEYS)) ||
        (st = gd_yread_qty(&p->r, cm, "mu", q, GD_QTY_DIMLESS, GD_YREQ | GD_YPOS, &c->mu, NULL)) ||
        (st = gd_yread_qty(&p->r, cm, "force", q, GD_QTY_FORCE, GD_YREQ | GD_YPOS, &c->force,
                           NULL)) ||
        (st = gd_yread_qty(&p->r, cm, "radius", q, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &c->radius,
                           NULL)) ||
        (st = gd_yread_qty(&p->r, cm, "angle", q, GD_QTY_ANGLE, GD_YREQ | GD_YPOS, &c->angle,
                           NULL)) ||
        (st = gd_yread_int(&p->r, cm, "cones", q, 1, 10, 0, &cones, NULL)))
        return st;
    c->cones = (int)cones;
    return GD_OK;
}

static gd_status read_sync(gd_mparser *p, const gd_ynode *sm, const char *q, size_t i)
{
    (void)i;
    gd_status st;
    char name[GD_NAME_MAX], ip[160];
    gd_synchroniser_spec s;
    gd_synchroniser_spec_init(&s);
    if ((st = gd_yexpect(&p->r, sm, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, sm, q, SYNC_KEYS)) ||
        (st = gd_mp_read_name(p, sm, q, name, NULL, 1)) ||
        (st = gd_mp_node_name(p, sm, "node", q, 1, &s.node)) ||
        (st = gd_yread_qty(&p->r, sm, "stiffness", q, GD_QTY_ROT_STIFFNESS, GD_YPOS, &s.stiffness,
                           NULL)) ||
        (st = gd_yread_qty(&p->r, sm, "damping", q, GD_QTY_ROT_DAMPING, GD_YNONNEG, &s.damping,
                           NULL)))
        return st;
    const gd_ynode *il = gd_ymap_get(sm, "idlers");
    gd_ypath_key(ip, sizeof ip, q, "idlers");
    if (!il)
        return gd_yfail(&p->r, sm, ip, "list the one or two idlers it engages, e.g. [gear3, gear4]",
                        "missing `idlers:`");
    if ((st = gd_yexpect(&p->r, il, GD_Y_SEQ, ip))) return st;
    if (il->n < 1 || il->n > 2)
        return gd_yfail(&p->r, il, ip, "a synchroniser sits between one or two idlers",
                        "%zu idlers listed", il->n);
    for (size_t j = 0; j < il->n; j++) {
        char jp[180];
        gd_ypath_index(jp, sizeof jp, ip, j);
        if ((st = gd_yexpect(&p->r, il->items[j], GD_Y_SCALAR, jp))) return st;
        s.idlers[j] = il->items[j]->text;
    }
    const gd_ynode *en = gd_ymap_get(sm, "engaged");
    if (en) {
        char ep[160];
        gd_ypath_key(ep, sizeof ep, q, "engaged");
        if (en->kind == GD_Y_SEQ && en->n > 1)
            return gd_yfail(&p->r, en, ep,
                            "a synchroniser engages one gear at a time: name one idler",
                            "two gears engaged on synchroniser '%s'", name);
        if ((st = gd_yexpect(&p->r, en, GD_Y_SCALAR, ep))) return st;
        if (strcmp(en->text, "neutral") && strcmp(en->text, "none")) s.engaged = en->text;
    }
    const gd_ynode *cm = gd_ymap_get(sm, "cone");
    if (cm) {
        char cp[160];
        if ((st = read_cone(p, cm, gd_ypath_key(cp, sizeof cp, q, "cone"), &s.cone))) return st;
    }
    s.name = name;
    s.loc = gd_mp_loc(sm);
    s.path = q;
    return gd_model_add_synchroniser(p->m, &s, NULL, p->r.err);
}

/* gears: {1: idler1, 2: idler2, ...}; gear: 3 (0 or neutral: none) */
static gd_status read_gears(gd_mparser *p)
{
    gd_status st;
    const gd_ynode *gm = gd_ymap_get(p->root, "gears");
    if (gm) {
        if ((st = gd_yexpect(&p->r, gm, GD_Y_MAP, "gears"))) return st;
        for (size_t i = 0; i < gm->n; i++) {
            char gp[120];
            const gd_ynode *k = gm->keys[i], *v = gm->items[i];
            gd_ypath_key(gp, sizeof gp, "gears", k->text);
            char *end;
            long num = strtol(k->text, &end, 10);
            if (*end || end == k->text || num < 1 || num > 99)
                return gd_yfail(&p->r, k, gp, "number the gears 1, 2, ... (reverse e.g. 6)",
                                "'%s' is not a gear number", k->text);
            if ((st = gd_yexpect(&p->r, v, GD_Y_SCALAR, gp)) ||
                (st = gd_model_add_gear(p->m, (int)num, v->text, gd_mp_loc(v), gp, p->r.err)))
                return st;
        }
    }
    const gd_ynode *sh = gd_ymap_get(p->root, "shift");
    if (sh) {
        long from = 0, to = 0;
        double at = 0;
        if ((st = gd_yexpect(&p->r, sh, GD_Y_MAP, "shift")) ||
            (st = gd_ycheck_keys(&p->r, sh, "shift", SHIFT_KEYS)) ||
            (st = gd_yread_int(&p->r, sh, "from", "shift", 1, 99, GD_YREQ, &from, NULL)) ||
            (st = gd_yread_int(&p->r, sh, "to", "shift", 1, 99, GD_YREQ, &to, NULL)) ||
            (st = gd_yread_qty(&p->r, sh, "at", "shift", GD_QTY_TIME, GD_YREQ | GD_YNONNEG, &at,
                               NULL)) ||
            (st = gd_model_set_shift(p->m, (int)from, (int)to, at, gd_mp_loc(sh), p->r.err)))
            return st;
    }
    const gd_ynode *sel = gd_ymap_get(p->root, "gear");
    if (!sel) return GD_OK;
    if ((st = gd_yexpect(&p->r, sel, GD_Y_SCALAR, "gear"))) return st;
    long num = 0;
    if (strcmp(sel->text, "neutral") &&
        (st = gd_yread_int(&p->r, p->root, "gear", "", 0, 99, 0, &num, NULL)))
        return st;
    return gd_model_select_gear(p->m, (int)num, gd_mp_loc(sel), p->r.err);
}

gd_status gd_mp_idlers(gd_mparser *p)
{
    gd_status st;
    if ((st = gd_mp_each(p, "idlers", read_idler)) ||
        (st = gd_mp_each(p, "synchronisers", read_sync)))
        return st;
    return read_gears(p);
}
