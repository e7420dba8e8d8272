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
    "mesh_stiffness", "mesh_damping",   "carrier_frame", "centrifugal_stiffness",
    "geometry",       "mesh_laws",      "mesh_phases",   NULL};
static const char *const GEOMETRY_KEYS[] = {
    "module", "pressure_angle", "face_width", "profile_shift", "method", "points", NULL};
static const char *const LAW_KEYS[] = {"tvms", "backlash", "damping", NULL};
static const char *const PHASE_KEYS[] = {"sun", "ring", "sun_ring", NULL};
static const char *const METHODS[] = {"energy", "iso6336", "single-pair-law", "square", NULL};
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

/* `geometry:` (docs/planetary.md, "Meshes from geometry") into g. */
static gd_status read_geometry(gd_mparser *p, const gd_ynode *sm, const char *q,
                               gd_planetary_geometry *g, int *given)
{
    gd_yreader *r = &p->r;
    const gd_ynode *gm = gd_ymap_get(sm, "geometry");
    *given = gm != NULL;
    if (!gm) return GD_OK;
    char gp[160];
    gd_ypath_key(gp, sizeof gp, q, "geometry");
    gd_status st;
    int idx = 0, present = 0;
    long points = 0;
    if ((st = gd_yexpect(r, gm, GD_Y_MAP, gp)) || (st = gd_ycheck_keys(r, gm, gp, GEOMETRY_KEYS)) ||
        (st = gd_yread_qty(r, gm, "module", gp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &g->module,
                           NULL)) ||
        (st = gd_yread_qty(r, gm, "pressure_angle", gp, GD_QTY_ANGLE, GD_YPOS, &g->pressure_angle,
                           NULL)) ||
        (st = gd_yread_qty(r, gm, "face_width", gp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                           &g->face_width, NULL)) ||
        (st = read_per_gear(p, gm, gp, "profile_shift", SIZE_KEYS, 3, GD_QTY_DIMLESS, 0, 0,
                            g->profile_shift)) ||
        (st = gd_yread_str(r, gm, "method", gp, METHODS, 0, NULL, &idx, &present)))
        return st;
    if (present) g->tvms.method = (gd_tvms_method)idx;
    if ((st = gd_yread_int(r, gm, "points", gp, 8, 100000, 0, &points, &present))) return st;
    if (present) g->tvms.points = (int)points;
    return GD_OK;
}

/* `mesh_laws: {sun: {...}, ring: {...}}`: the mesh keys of time integration
 * (gd_mp_mesh_dynamics), the tables into tv[] (to free after the add). */
static gd_status read_mesh_laws(gd_mparser *p, const gd_ynode *sm, const char *q,
                                gd_planetary_spec *s, int sun_teeth, gd_table *tv[2])
{
    gd_yreader *r = &p->r;
    const gd_ynode *lm = gd_ymap_get(sm, "mesh_laws");
    if (!lm) return GD_OK;
    char lp[160], kp[200];
    gd_ypath_key(lp, sizeof lp, q, "mesh_laws");
    gd_status st;
    if ((st = gd_yexpect(r, lm, GD_Y_MAP, lp)) || (st = gd_ycheck_keys(r, lm, lp, MESH_KEYS)))
        return st;
    for (int k = 0; k < 2; k++) {
        const gd_ynode *km = gd_ymap_get(lm, MESH_KEYS[k]);
        if (!km) continue;
        gd_ypath_key(kp, sizeof kp, lp, MESH_KEYS[k]);
        if ((st = gd_yexpect(r, km, GD_Y_MAP, kp)) || (st = gd_ycheck_keys(r, km, kp, LAW_KEYS)))
            return st;
        gd_mesh_spec ms;
        gd_mesh_spec_init(&ms);
        gd_table *ste = NULL;
        if ((st = gd_mp_mesh_dynamics(p, km, kp, sun_teeth, &ms, &tv[k], &ste))) return st;
        gd_table_free(ste); /* not a key here */
        gd_planetary_mesh_law_spec *l = &s->mesh_law[k];
        l->tvms = gd_mp_table_spec(tv[k]);
        l->damping_per_stiffness = ms.damping_per_stiffness;
        l->damping_separated = ms.damping_separated;
        l->backlash = ms.backlash;
        l->backlash_gap = ms.backlash_gap;
        l->coast_stiffness_ratio = ms.coast_stiffness_ratio;
        if (ms.damping > 0) s->mesh_damping[k] = ms.damping;
    }
    return GD_OK;
}

/* `mesh_phases: {sun: [...], ring: [...], sun_ring: x}` (mesh periods) */
static gd_status read_phases(gd_mparser *p, const gd_ynode *sm, const char *q, gd_planetary_spec *s,
                             double *ph[2])
{
    gd_yreader *r = &p->r;
    const gd_ynode *pm = gd_ymap_get(sm, "mesh_phases");
    if (!pm) return GD_OK;
    char pp[160];
    gd_ypath_key(pp, sizeof pp, q, "mesh_phases");
    gd_status st;
    if ((st = gd_yexpect(r, pm, GD_Y_MAP, pp)) || (st = gd_ycheck_keys(r, pm, pp, PHASE_KEYS)) ||
        (st = gd_yread_qty(r, pm, "sun_ring", pp, GD_QTY_DIMLESS, GD_YNONNEG, &s->sun_ring_phase,
                           &s->has_sun_ring_phase)))
        return st;
    for (int k = 0; k < 2; k++) {
        if (!gd_ymap_get(pm, MESH_KEYS[k])) continue;
        int n = 0;
        if ((st = gd_mp_read_qty_list(p, pm, MESH_KEYS[k], pp, GD_QTY_DIMLESS, &ph[k], &n)))
            return st;
        if (n != s->nplanets) {
            char kp[200];
            return gd_yfail(r, gd_ymap_get(pm, MESH_KEYS[k]),
                            gd_ypath_key(kp, sizeof kp, pp, MESH_KEYS[k]),
                            "give one phase per planet (mesh periods)", "%d phases for %d planets",
                            n, s->nplanets);
        }
        s->mesh_phases[k] = ph[k];
    }
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
    double *phases[2] = {NULL, NULL};
    int held = 3, frame = -1, has_frame = 0, has_geometry = 0;
    gd_planetary_geometry geometry;
    gd_planetary_geometry_init(&geometry);
    gd_table *tv[2] = {NULL, NULL};
    if ((st = gd_yexpect(r, sm, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, sm, q, SET_KEYS)) ||
        (st = gd_mp_read_name(p, sm, q, name, "", 1)) ||
        (st = gd_yread_str(r, sm, "held", q, HELD, 0, NULL, &held, NULL)) ||
        (st = gd_yread_str(r, sm, "carrier_frame", q, FRAMES, 0, NULL, &frame, &has_frame)) ||
        (st = gd_yread_bool(r, sm, "centrifugal_stiffness", q, 0, &s.centrifugal_stiffness, NULL)))
        return st;
    s.carrier_frame = has_frame ? frame : -1;
    for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++)
        if ((st = read_member(p, sm, q, j, &s.member[j]))) return st;
    if ((st = read_geometry(p, sm, q, &geometry, &has_geometry))) return st;
    /* with the tooth geometry, the sizes and the mean stiffness come from it */
    const int req = has_geometry ? 0 : GD_YREQ;
    if (has_geometry && gd_ymap_get(sm, "pressure_angle"))
        return gd_yfail(r, gd_ymap_get(sm, "pressure_angle"), q,
                        "give the normal pressure angle in `geometry:` (the operating ones follow)",
                        "pressure_angle given with the tooth geometry");
    if ((st = read_per_gear(p, sm, q, "teeth", SIZE_KEYS, 3, GD_QTY_DIMLESS, GD_YPOS, 0, teeth)) ||
        (st = read_per_gear(p, sm, q, "base_radius", SIZE_KEYS, 3, GD_QTY_LENGTH, req | GD_YPOS, 0,
                            s.base_radius)) ||
        (st = gd_yread_qty(r, sm, "carrier_radius", q, GD_QTY_LENGTH, req | GD_YPOS,
                           &s.carrier_radius, NULL)) ||
        (st = gd_yread_qty(r, sm, "planet_tip_radius", q, GD_QTY_LENGTH, GD_YPOS,
                           &s.planet_tip_radius, NULL)) ||
        (st = read_per_gear(p, sm, q, "pressure_angle", MESH_KEYS, 2, GD_QTY_ANGLE, GD_YPOS, 1,
                            s.pressure_angle)) ||
        (st = gd_yread_qty(r, sm, "helix_angle", q, GD_QTY_ANGLE, GD_YNONNEG, &s.helix_angle,
                           NULL)) ||
        (st = read_per_gear(p, sm, q, "mesh_stiffness", MESH_KEYS, 2, GD_QTY_STIFFNESS,
                            req | GD_YPOS, 1, s.mesh_stiffness)) ||
        (st = read_per_gear(p, sm, q, "mesh_damping", MESH_KEYS, 2, GD_QTY_DAMPING, GD_YNONNEG, 1,
                            s.mesh_damping)) ||
        (st = read_planets(p, sm, q, &s, &angles, errors)) ||
        (st = read_mesh_laws(p, sm, q, &s, (int)teeth[0], tv)) ||
        (st = read_phases(p, sm, q, &s, phases)))
        goto done;
    for (int j = 0; j < 3; j++) {
        /* range-checked before the conversion to int */
        if (teeth[j] != 0 && (!(teeth[j] <= 100000) || teeth[j] != floor(teeth[j]))) {
            char tp[160];
            st = gd_yfail(r, gd_ymap_get(sm, "teeth"), gd_ypath_key(tp, sizeof tp, q, "teeth"),
                          "teeth numbers are whole numbers from 3 to 100000",
                          "invalid teeth number %g", teeth[j]);
            goto done;
        }
        s.teeth[j] = (int)teeth[j];
    }
    s.held = held == 3 ? -1 : held;
    s.name = name;
    s.loc = gd_mp_loc(sm);
    s.path = q;
    if (has_geometry) s.geometry = &geometry;
    st = gd_model_add_planetary(p->m, &s, NULL, r->err);
done:
    free(angles);
    free(errors[0]);
    free(errors[1]);
    for (int k = 0; k < 2; k++) {
        free(phases[k]);
        gd_table_free(tv[k]);
    }
    return st;
}

gd_status gd_mp_planetary(gd_mparser *p)
{
    return gd_mp_each(p, "planetary_sets", read_set);
}
