/* Reading `planetary_sets:` into builder specs (docs/planetary.md, docs/model-format.md):
 * the members on their nodes, the planets, sizes, angles, meshes and the held member. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/model_file_impl.h"

static const char *const SET_KEYS[] = {
    "name",           "held",           "sun",           "ring",
    "carrier",        "planets",        "teeth",         "base_radius",
    "carrier_radius", "pressure_angle", "helix_angle",   "planet_tip_radius",
    "mesh_stiffness", "mesh_damping",   "carrier_frame", NULL};
static const char *const MEMBER_KEYS[] = {"node",      "mass",      "inertia",
                                          "k_support", "k_torsion", NULL};
static const char *const PLANET_KEYS[] = {
    "count", "angles", "mass", "inertia", "bearing_stiffness", "pin_errors", "pin_errors_radial",
    NULL};
static const char *const SIZE_KEYS[] = {"sun", "ring", "planet", NULL};
static const char *const MESH_KEYS[] = {"sun", "ring", NULL};
static const char *const HELD[] = {"sun", "ring", "carrier", "none", NULL};
static const char *const FRAMES[] = {"planets", "all", NULL};

static gd_status read_member(gd_mparser *p, const gd_ynode *sm, const char *q, int j,
                             gd_planetary_member_spec *b)
{
    gd_yreader *r = &p->r;
    char mp[160];
    const gd_ynode *mm = gd_ymap_get(sm, gd_planetary_member_names[j]);
    gd_ypath_key(mp, sizeof mp, q, gd_planetary_member_names[j]);
    if (!mm)
        return gd_yfail(r, sm, mp, "give {node: NAME, mass, inertia, k_support, k_torsion}",
                        "the set's %s is missing", gd_planetary_member_names[j]);
    gd_status st;
    if ((st = gd_yexpect(r, mm, GD_Y_MAP, mp)) || (st = gd_ycheck_keys(r, mm, mp, MEMBER_KEYS)) ||
        (st = gd_mp_node_name(p, mm, "node", mp, 1, &b->node)) ||
        (st = gd_yread_qty(r, mm, "mass", mp, GD_QTY_MASS, GD_YNONNEG, &b->mass, NULL)) ||
        (st = gd_yread_qty(r, mm, "inertia", mp, GD_QTY_INERTIA, GD_YNONNEG, &b->inertia, NULL)) ||
        (st = gd_yread_qty(r, mm, "k_support", mp, GD_QTY_STIFFNESS, GD_YNONNEG, &b->k_support,
                           NULL)) ||
        (st = gd_yread_qty(r, mm, "k_torsion", mp, GD_QTY_ROT_STIFFNESS, GD_YNONNEG, &b->k_torsion,
                           NULL)))
        return st;
    return GD_OK;
}

/* key: a map {sun:, ring:[, planet:]} of quantities, or (one_value) a single value for all. */
static gd_status read_per_gear(gd_mparser *p, const gd_ynode *sm, const char *q, const char *key,
                               const char *const *keys, int nkeys, gd_qty qty, int flags,
                               int one_value, double *out)
{
    gd_yreader *r = &p->r;
    const gd_ynode *v = gd_ymap_get(sm, key);
    if (!v) {
        if (flags & GD_YREQ)
            return gd_yfail(r, sm, q, "see docs/planetary.md", "'%s' is missing", key);
        return GD_OK;
    }
    char kp[160];
    gd_ypath_key(kp, sizeof kp, q, key);
    if (v->kind == GD_Y_SCALAR && one_value) {
        gd_status st = gd_yread_node_qty(r, v, kp, qty, flags & ~GD_YREQ, &out[0]);
        for (int j = 1; j < nkeys && !st; j++)
            out[j] = out[0];
        return st;
    }
    gd_status st;
    if ((st = gd_yexpect(r, v, GD_Y_MAP, kp)) || (st = gd_ycheck_keys(r, v, kp, keys))) return st;
    for (int j = 0; j < nkeys; j++)
        if ((st = gd_yread_qty(r, v, keys[j], kp, qty, flags, &out[j], NULL))) return st;
    return GD_OK;
}

static gd_status read_planets(gd_mparser *p, const gd_ynode *sm, const char *q,
                              gd_planetary_spec *s, double **angles, double *errors[2])
{
    gd_yreader *r = &p->r;
    char pp[160];
    const gd_ynode *pm = gd_ymap_get(sm, "planets");
    gd_ypath_key(pp, sizeof pp, q, "planets");
    if (!pm)
        return gd_yfail(r, sm, pp, "give {count: N, mass, inertia, bearing_stiffness}",
                        "the set's planets are missing");
    gd_status st;
    long count = 0;
    int has_count, nang = 0;
    if ((st = gd_yexpect(r, pm, GD_Y_MAP, pp)) || (st = gd_ycheck_keys(r, pm, pp, PLANET_KEYS)) ||
        (st = gd_yread_int(r, pm, "count", pp, 1, GD_PLANETARY_MAX_PLANETS, 0, &count,
                           &has_count)) ||
        (st = gd_yread_qty(r, pm, "mass", pp, GD_QTY_MASS, GD_YREQ | GD_YPOS, &s->planet_mass,
                           NULL)) ||
        (st = gd_yread_qty(r, pm, "inertia", pp, GD_QTY_INERTIA, GD_YREQ | GD_YPOS,
                           &s->planet_inertia, NULL)) ||
        (st = gd_yread_qty(r, pm, "bearing_stiffness", pp, GD_QTY_STIFFNESS, GD_YREQ | GD_YPOS,
                           &s->bearing_stiffness, NULL)))
        return st;
    if (gd_ymap_get(pm, "angles")) {
        if ((st = gd_mp_read_qty_list(p, pm, "angles", pp, GD_QTY_ANGLE, angles, &nang))) return st;
        if (has_count && count != nang) {
            char ap[200];
            return gd_yfail(r, gd_ymap_get(pm, "count"), gd_ypath_key(ap, sizeof ap, pp, "count"),
                            "give one angle per planet, or leave out count",
                            "count %ld but %d angles", count, nang);
        }
        if (nang > GD_PLANETARY_MAX_PLANETS)
            return gd_yfail(r, gd_ymap_get(pm, "angles"), pp, "give 64 planets or fewer",
                            "%d planets", nang);
        count = nang;
    } else if (!has_count) {
        return gd_yfail(r, pm, pp, "give `count: N` (equally spaced) or `angles: [...]`",
                        "the number of planets is missing");
    }
    s->nplanets = (int)count;
    s->planet_angles = *angles;
    /* tangential (pin_errors) and radial (pin_errors_radial) pin position errors */
    static const char *const EKEYS[2] = {"pin_errors", "pin_errors_radial"};
    for (int k = 0; k < 2; k++) {
        if (!gd_ymap_get(pm, EKEYS[k])) continue;
        int ne = 0;
        if ((st = gd_mp_read_qty_list(p, pm, EKEYS[k], pp, GD_QTY_LENGTH, &errors[k], &ne)))
            return st;
        if (ne != count) {
            char ep[200];
            return gd_yfail(r, gd_ymap_get(pm, EKEYS[k]), gd_ypath_key(ep, sizeof ep, pp, EKEYS[k]),
                            "give one pin error per planet (0 for an exact pin)",
                            "%d pin errors for %ld planets", ne, count);
        }
    }
    s->pin_errors = errors[0];
    s->pin_errors_radial = errors[1];
    return GD_OK;
}

static gd_status read_set(gd_mparser *p, const gd_ynode *sm, const char *q, size_t index)
{
    (void)index;
    gd_yreader *r = &p->r;
    gd_status st;
    char name[GD_NAME_MAX];
    gd_planetary_spec s;
    gd_planetary_spec_init(&s);
    double *angles = NULL, *errors[2] = {NULL, NULL}, teeth[3] = {0, 0, 0};
    int held = 3, frame = -1, has_frame = 0;
    if ((st = gd_yexpect(r, sm, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, sm, q, SET_KEYS)) ||
        (st = gd_mp_read_name(p, sm, q, name, "", 1)) ||
        (st = gd_yread_str(r, sm, "held", q, HELD, 0, NULL, &held, NULL)) ||
        (st = gd_yread_str(r, sm, "carrier_frame", q, FRAMES, 0, NULL, &frame, &has_frame)))
        return st;
    s.carrier_frame = has_frame ? frame : -1;
    for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++)
        if ((st = read_member(p, sm, q, j, &s.member[j]))) return st;
    if ((st = read_per_gear(p, sm, q, "teeth", SIZE_KEYS, 3, GD_QTY_DIMLESS, GD_YPOS, 0, teeth)) ||
        (st = read_per_gear(p, sm, q, "base_radius", SIZE_KEYS, 3, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                            0, s.base_radius)) ||
        (st = gd_yread_qty(r, sm, "carrier_radius", q, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                           &s.carrier_radius, NULL)) ||
        (st = gd_yread_qty(r, sm, "planet_tip_radius", q, GD_QTY_LENGTH, GD_YPOS,
                           &s.planet_tip_radius, NULL)) ||
        (st = read_per_gear(p, sm, q, "pressure_angle", MESH_KEYS, 2, GD_QTY_ANGLE, GD_YPOS, 1,
                            s.pressure_angle)) ||
        (st = gd_yread_qty(r, sm, "helix_angle", q, GD_QTY_ANGLE, GD_YNONNEG, &s.helix_angle,
                           NULL)) ||
        (st = read_per_gear(p, sm, q, "mesh_stiffness", MESH_KEYS, 2, GD_QTY_STIFFNESS,
                            GD_YREQ | GD_YPOS, 1, s.mesh_stiffness)) ||
        (st = read_per_gear(p, sm, q, "mesh_damping", MESH_KEYS, 2, GD_QTY_DAMPING, GD_YNONNEG, 1,
                            s.mesh_damping)) ||
        (st = read_planets(p, sm, q, &s, &angles, errors))) {
        free(angles);
        free(errors[0]);
        free(errors[1]);
        return st;
    }
    for (int j = 0; j < 3; j++) {
        /* range-checked before the conversion to int */
        if (teeth[j] != 0 && (!(teeth[j] <= 100000) || teeth[j] != floor(teeth[j]))) {
            free(angles);
            free(errors[0]);
            free(errors[1]);
            char tp[160];
            return gd_yfail(r, gd_ymap_get(sm, "teeth"), gd_ypath_key(tp, sizeof tp, q, "teeth"),
                            "teeth numbers are whole numbers from 3 to 100000",
                            "invalid teeth number %g", teeth[j]);
        }
        s.teeth[j] = (int)teeth[j];
    }
    s.held = held == 3 ? -1 : held;
    s.name = name;
    s.loc = gd_mp_loc(sm);
    s.path = q;
    st = gd_model_add_planetary(p->m, &s, NULL, r->err);
    free(angles);
    free(errors[0]);
    free(errors[1]);
    return st;
}

gd_status gd_mp_planetary(gd_mparser *p)
{
    return gd_mp_each(p, "planetary_sets", read_set);
}
