/* Reader of the `geometry:` and `stiffness: {from: geometry}` keys of a mesh entry. */
#include "model_file/mesh_geometry_read_impl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"
#include "model_file/material_read_impl.h"

static const char *const GEOMETRY_KEYS[] = {"normal_module", "normal_pressure_angle",
                                            "helix_angle",   "hand",
                                            "face_width",    "center_distance",
                                            "internal",      "driver",
                                            "driven",        NULL};
static const char *const GEAR_KEYS[] = {"teeth",
                                        "profile_shift",
                                        "addendum_coef",
                                        "dedendum_coef",
                                        "fillet_radius_coef",
                                        "tip_radius",
                                        "root_radius",
                                        "bore_radius",
                                        "material",
                                        "body_torsional_stiffness",
                                        "web_thickness",
                                        "web_inner_radius",
                                        "web_outer_radius",
                                        "modifications",
                                        NULL};
static const char *const MOD_KEYS[] = {"tip_relief", "root_relief",           "crowning",
                                       "end_relief", "helix_slope_deviation", NULL};
static const char *const RELIEF_KEYS[] = {"amount", "start_diameter", "start_roll_angle", "shape",
                                          NULL};
static const char *const END_KEYS[] = {"amount", "length", "shape", NULL};
static const char *const SHAPES[] = {"linear", "parabolic", NULL};
static const char *const STIFFNESS_KEYS[] = {
    "from",      "method", "points",       "cycles", "slices", "body_compliance",
    "harmonics", "load",   "misalignment", NULL};
static const char *const HANDS[] = {"right", "left", NULL};
static const char *const FROM[] = {"geometry", "contact_analysis", NULL};
static const char *const METHODS[] = {"energy", "iso6336", "single-pair-law", "square", NULL};

/* A tip or root relief map. Amounts are read signed and checked (with the geometry) by
 * gd_gear_pair_derive, which names the limits. */
static gd_status read_relief(gd_yreader *r, const gd_ynode *m, const char *path, const char *key,
                             gd_profile_relief *p)
{
    const gd_ynode *n = gd_ymap_get(m, key);
    if (!n) return GD_OK;
    char q[220];
    gd_ypath_key(q, sizeof q, path, key);
    gd_status st;
    int has_d = 0, has_a = 0, shape = 0;
    if ((st = gd_yexpect(r, n, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, n, q, RELIEF_KEYS)) ||
        (st = gd_yread_qty(r, n, "amount", q, GD_QTY_LENGTH, GD_YREQ, &p->amount, NULL)) ||
        (st = gd_yread_qty(r, n, "start_diameter", q, GD_QTY_LENGTH, GD_YPOS, &p->start_diameter,
                           &has_d)) ||
        (st = gd_yread_qty(r, n, "start_roll_angle", q, GD_QTY_ANGLE, GD_YPOS, &p->start_roll_angle,
                           &has_a)) ||
        (st = gd_yread_str(r, n, "shape", q, SHAPES, 0, NULL, &shape, NULL)))
        return st;
    if (has_d && has_a)
        return gd_yfail(r, gd_ymap_get(n, "start_roll_angle"), q, "keep one of the two",
                        "both start_diameter and start_roll_angle given");
    p->shape = (gd_relief_shape)shape;
    return GD_OK;
}

static gd_status read_modifications(gd_yreader *r, const gd_ynode *m, const char *path,
                                    gd_tooth_modifications *t)
{
    const gd_ynode *n = gd_ymap_get(m, "modifications");
    if (!n) return GD_OK;
    char q[220], e[240];
    gd_ypath_key(q, sizeof q, path, "modifications");
    gd_status st;
    if ((st = gd_yexpect(r, n, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, n, q, MOD_KEYS)) ||
        (st = read_relief(r, n, q, "tip_relief", &t->tip_relief)) ||
        (st = read_relief(r, n, q, "root_relief", &t->root_relief)) ||
        (st = gd_yread_qty(r, n, "crowning", q, GD_QTY_LENGTH, 0, &t->crowning, NULL)) ||
        (st = gd_yread_qty(r, n, "helix_slope_deviation", q, GD_QTY_LENGTH, 0,
                           &t->helix_slope_deviation, NULL)))
        return st;
    const gd_ynode *er = gd_ymap_get(n, "end_relief");
    if (!er) return GD_OK;
    gd_ypath_key(e, sizeof e, q, "end_relief");
    int shape = 0;
    if ((st = gd_yexpect(r, er, GD_Y_MAP, e)) || (st = gd_ycheck_keys(r, er, e, END_KEYS)) ||
        (st = gd_yread_qty(r, er, "amount", e, GD_QTY_LENGTH, GD_YREQ, &t->end_relief, NULL)) ||
        (st = gd_yread_qty(r, er, "length", e, GD_QTY_LENGTH, GD_YREQ, &t->end_relief_length,
                           NULL)) ||
        (st = gd_yread_str(r, er, "shape", e, SHAPES, 0, NULL, &shape, NULL)))
        return st;
    t->end_relief_shape = (gd_relief_shape)shape;
    return GD_OK;
}

static gd_status read_gear(gd_yreader *r, const gd_ynode *root, const gd_ynode *m, const char *path,
                           gd_gear_geometry *w)
{
    gd_status st;
    if ((st = gd_yexpect(r, m, GD_Y_MAP, path)) || (st = gd_ycheck_keys(r, m, path, GEAR_KEYS)))
        return st;
    long teeth = 0;
    if ((st = gd_yread_int(r, m, "teeth", path, 5, 100000, GD_YREQ, &teeth, NULL))) return st;
    w->teeth = (int)teeth;
    if ((st = gd_yread_qty(r, m, "profile_shift", path, GD_QTY_DIMLESS, 0, &w->profile_shift,
                           NULL)) ||
        (st = gd_yread_qty(r, m, "addendum_coef", path, GD_QTY_DIMLESS, GD_YPOS, &w->addendum_coef,
                           NULL)) ||
        (st = gd_yread_qty(r, m, "dedendum_coef", path, GD_QTY_DIMLESS, GD_YPOS, &w->dedendum_coef,
                           NULL)) ||
        (st = gd_yread_qty(r, m, "fillet_radius_coef", path, GD_QTY_DIMLESS, GD_YNONNEG,
                           &w->fillet_radius_coef, NULL)) ||
        (st = gd_yread_qty(r, m, "tip_radius", path, GD_QTY_LENGTH, GD_YPOS, &w->tip_radius,
                           NULL)) ||
        (st = gd_yread_qty(r, m, "root_radius", path, GD_QTY_LENGTH, GD_YPOS, &w->root_radius,
                           NULL)) ||
        (st = gd_yread_qty(r, m, "bore_radius", path, GD_QTY_LENGTH, GD_YPOS, &w->bore_radius,
                           NULL)) ||
        (st = gd_yread_qty(r, m, "body_torsional_stiffness", path, GD_QTY_ROT_STIFFNESS, GD_YPOS,
                           &w->body_torsional_stiffness, NULL)) ||
        (st = gd_yread_qty(r, m, "web_thickness", path, GD_QTY_LENGTH, GD_YPOS, &w->web_thickness,
                           NULL)) ||
        (st = gd_yread_qty(r, m, "web_inner_radius", path, GD_QTY_LENGTH, GD_YPOS,
                           &w->web_inner_radius, NULL)) ||
        (st = gd_yread_qty(r, m, "web_outer_radius", path, GD_QTY_LENGTH, GD_YPOS,
                           &w->web_outer_radius, NULL)))
        return st;
    char p[200];
    const gd_ynode *mat = gd_ymap_get(m, "material");
    if (!mat)
        return gd_yfail(r, m, gd_ypath_key(p, sizeof p, path, "material"),
                        "name a material from `materials:` or give {E: ..., poisson: ...}",
                        "required key 'material' is missing");
    gd_material mt;
    if ((st = gd_material_resolve(r, root, mat, gd_ypath_key(p, sizeof p, path, "material"), 0,
                                  &mt)))
        return st;
    w->E = mt.E;
    w->poisson = mt.poisson;
    return read_modifications(r, m, path, &w->mod);
}

/* The node for a field path like "driver.profile_shift" under map, or the deepest map
 * on the way when the key is absent. */
static const gd_ynode *locate(const gd_ynode *map, const char *field)
{
    const gd_ynode *n = map;
    const char *p = field;
    while (*p && n && n->kind == GD_Y_MAP) {
        char key[80];
        size_t len = strcspn(p, ".");
        if (len >= sizeof key) break;
        memcpy(key, p, len);
        key[len] = '\0';
        const gd_ynode *next = gd_ymap_get(n, key);
        if (!next) break;
        n = next;
        p += len;
        if (*p == '.') p++;
    }
    return n;
}

void gd_gear_pair_error_locate(const char *file, const gd_ynode *mesh_map, const char *path,
                               gd_error *err)
{
    if (!err || err->line > 0) return;
    char relative[sizeof err->field];
    snprintf(relative, sizeof relative, "%s", err->field);
    const char *section = gd_gear_pair_error_prefix(err, path);
    const gd_ynode *sec = gd_ymap_get(mesh_map, section);
    const gd_ynode *n = sec ? locate(sec, relative) : mesh_map;
    if (n)
        gd_ylocate(err, file, n);
    else if (file)
        snprintf(err->file, sizeof err->file, "%s", file);
}

static gd_status read_options(gd_yreader *r, const gd_ynode *s, const char *path,
                              gd_tvms_options *opt)
{
    gd_status st;
    if ((st = gd_ycheck_keys(r, s, path, STIFFNESS_KEYS))) return st;
    int idx = 0, present = 0, from = 0;
    if ((st = gd_yread_str(r, s, "from", path, FROM, GD_YREQ, NULL, &from, NULL))) return st;
    /* the load and misalignment of a contact analysis */
    double load = 0, mis = 0;
    int has_load = 0, has_mis = 0;
    if ((st = gd_yread_qty(r, s, "load", path, GD_QTY_TORQUE, GD_YPOS, &load, &has_load)) ||
        (st = gd_yread_qty(r, s, "misalignment", path, GD_QTY_LENGTH, 0, &mis, &has_mis)))
        return st;
    if (from == 1 && !has_load)
        return gd_yfail(r, s, path, "add `load: <driver torque>`, e.g. `load: 200 N m`",
                        "a contact analysis needs the load (driver torque)");
    if (from == 0 && (has_load || has_mis))
        return gd_yfail(r, gd_ymap_get(s, has_load ? "load" : "misalignment"), path,
                        "write `from: contact_analysis` to use the loaded stiffness, or remove it",
                        "'%s' goes with `from: contact_analysis`",
                        has_load ? "load" : "misalignment");
    if (!opt) return GD_OK;
    opt->contact_analysis = from == 1;
    opt->load_torque = load;
    opt->misalignment = mis;
    if ((st = gd_yread_str(r, s, "method", path, METHODS, 0, NULL, &idx, &present))) return st;
    if (present) opt->method = (gd_tvms_method)idx;
    if (present && from == 1 && opt->method == GD_TVMS_ISO6336)
        return gd_yfail(r, gd_ymap_get(s, "method"), path,
                        "use energy (default), single-pair-law or square",
                        "the contact analysis needs a stiffness law along the contact (iso6336 "
                        "gives one constant)");
    long v;
    if ((st = gd_yread_int(r, s, "points", path, 8, 1000000, 0, &v, &present))) return st;
    if (present) opt->points = (int)v;
    if ((st = gd_yread_int(r, s, "cycles", path, 1, 10000, 0, &v, &present))) return st;
    if (present) opt->cycles = (int)v;
    if ((st = gd_yread_int(r, s, "slices", path, 1, 100000, 0, &v, &present))) return st;
    if (present) opt->slices = (int)v;
    if ((st = gd_yread_int(r, s, "harmonics", path, 0, 100, 0, &v, &present))) return st;
    if (present) opt->harmonics = (int)v;
    if ((st = gd_yread_bool(r, s, "body_compliance", path, 0, &opt->body_compliance, NULL)))
        return st;
    /* the table's work bounds (gd_tvms_compute's), located here */
    double samples = (double)opt->points * opt->cycles, evals = (double)opt->points * opt->slices;
    if (samples > GD_TVMS_MAX_SAMPLES)
        return gd_yfail(r, s, path, "lower points or cycles",
                        "points x cycles = %.3g samples, more than the limit of %.0e per table",
                        samples, GD_TVMS_MAX_SAMPLES);
    if (evals > GD_TVMS_MAX_SLICE_EVALS)
        return gd_yfail(r, s, path, "lower points or slices",
                        "points x slices = %.3g contact evaluations, more than the limit of %.0e",
                        evals, GD_TVMS_MAX_SLICE_EVALS);
    return GD_OK;
}

/* Values the stiffness models cannot mean, refused at their keys (issue 38 M7: a
 * contact-analysis load of 1e308 N m said "table values must be finite"; the bore radius
 * bound is gd_gear_pair_derive's, located by the caller):
 * - a contact-analysis normal load T / (r_b1 cos beta_b) above E b m_n (a tooth section
 *   b x m_n strained by 1), and a misalignment above the normal module. */
static gd_status check_extremes(gd_yreader *r, const gd_ynode *s, const char *path,
                                const gd_gear_pair_geometry *geom, const gd_gear_pair_derived *d,
                                const gd_tvms_options *opt)
{
    char p[200], q[200];
    if (!opt || !opt->contact_analysis || !s) return GD_OK;
    const double E = fmin(geom->gear[0].E, geom->gear[1].E), mn = geom->normal_module;
    const double fmax_n = E * geom->face_width * mn;
    const double per_torque = 1.0 / (d->base_radius[0] * cos(d->base_helix_angle));
    gd_ypath_key(p, sizeof p, path, "stiffness");
    if (!(opt->load_torque * per_torque <= fmax_n))
        return gd_yfail(r, gd_ymap_get(s, "load"), gd_ypath_key(q, sizeof q, p, "load"),
                        "give a driver torque within the bound",
                        "a driver torque of %g N m is a normal load of %g N, over E b m_n = "
                        "%.4g N (a tooth section strained by 1): at most %.4g N m",
                        opt->load_torque, opt->load_torque * per_torque, fmax_n,
                        fmax_n / per_torque);
    if (!(fabs(opt->misalignment) <= mn))
        return gd_yfail(r, gd_ymap_get(s, "misalignment"),
                        gd_ypath_key(q, sizeof q, p, "misalignment"),
                        "give a misalignment below the normal module",
                        "misalignment %g m is over the normal module %g m: flanks parting by "
                        "more across the face do not mesh",
                        opt->misalignment, mn);
    return GD_OK;
}

static gd_status read_pair(gd_yreader *r, const gd_ynode *root, const gd_ynode *mesh_map,
                           const char *path, gd_gear_pair_geometry *geom, gd_tvms_options *opt,
                           int allow_internal)
{
    gd_status st;
    char gp[200], p[200];
    gd_ypath_key(gp, sizeof gp, path, "geometry");
    const gd_ynode *g = gd_ymap_get(mesh_map, "geometry");
    if (!g)
        return gd_yfail(r, mesh_map, gp,
                        "add a `geometry:` map (teeth, normal_module, face_width, ...) or give the "
                        "stiffness as a number",
                        "this mesh has no geometry to compute its stiffness from");
    if ((st = gd_yexpect(r, g, GD_Y_MAP, gp)) || (st = gd_ycheck_keys(r, g, gp, GEOMETRY_KEYS)))
        return st;
    gd_gear_pair_geometry_init(geom);
    if ((st = gd_yread_qty(r, g, "normal_module", gp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                           &geom->normal_module, NULL)) ||
        (st = gd_yread_qty(r, g, "normal_pressure_angle", gp, GD_QTY_ANGLE, GD_YPOS,
                           &geom->normal_pressure_angle, NULL)) ||
        (st = gd_yread_qty(r, g, "helix_angle", gp, GD_QTY_ANGLE, GD_YNONNEG, &geom->helix_angle,
                           NULL)) ||
        (st = gd_yread_qty(r, g, "face_width", gp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                           &geom->face_width, NULL)) ||
        (st = gd_yread_qty(r, g, "center_distance", gp, GD_QTY_LENGTH, GD_YPOS,
                           &geom->center_distance, NULL)))
        return st;
    /* the hand does not change k; absent here, the mesh's own `hand` is used if it
     * says right or left, else right */
    int hand = 0, present = 0;
    if ((st = gd_yread_str(r, g, "hand", gp, HANDS, 0, NULL, &hand, &present))) return st;
    if (!present) {
        const gd_ynode *mh = gd_ymap_get(mesh_map, "hand");
        if (mh && mh->kind == GD_Y_SCALAR && !strcmp(mh->text, "left")) hand = 1;
    }
    geom->hand = hand == 1 ? -1 : 1;
    /* an internal pair: the driven gear is a ring (docs/mesh-stiffness.md) */
    if ((st = gd_yread_bool(r, g, "internal", gp, 0, &geom->internal, &present))) return st;
    if (geom->internal && !allow_internal)
        return gd_yfail(r, gd_ymap_get(g, "internal"), gp,
                        "a ring-planet mesh belongs to a planetary set; `geardyn mesh-stiffness` "
                        "computes an internal pair's stiffness from a stand-alone file",
                        "a model mesh couples two external gears: internal pairs are not "
                        "supported here");
    static const char *const NAMES[2] = {"driver", "driven"};
    for (int i = 0; i < 2; i++) {
        const gd_ynode *m = gd_ymap_get(g, NAMES[i]);
        gd_ypath_key(p, sizeof p, gp, NAMES[i]);
        if (!m) {
            char hint[200];
            snprintf(hint, sizeof hint, "add `%s: {teeth: ..., material: ...}`", NAMES[i]);
            return gd_yfail(r, g, p, hint, "required key '%s' is missing", NAMES[i]);
        }
        if ((st = read_gear(r, root, m, p, &geom->gear[i]))) return st;
    }
    const gd_ynode *s = gd_ymap_get(mesh_map, "stiffness");
    if (s && s->kind == GD_Y_MAP) {
        if ((st = read_options(r, s, gd_ypath_key(p, sizeof p, path, "stiffness"), opt))) return st;
    }
    gd_gear_pair_derived d;
    gd_error local;
    gd_error *e = r->err ? r->err : &local;
    if ((st = gd_gear_pair_derive(geom, &d, e))) {
        gd_gear_pair_error_locate(r->file, mesh_map, path, e);
        return st;
    }
    return check_extremes(r, s, path, geom, &d, opt);
}

gd_status gd_gear_pair_read(gd_yreader *r, const gd_ynode *root, const gd_ynode *mesh_map,
                            const char *path, gd_gear_pair_geometry *geom, gd_tvms_options *opt)
{
    return read_pair(r, root, mesh_map, path, geom, opt, 0);
}

gd_status gd_gear_pair_read_any(gd_yreader *r, const gd_ynode *root, const gd_ynode *mesh_map,
                                const char *path, gd_gear_pair_geometry *geom, gd_tvms_options *opt)
{
    return read_pair(r, root, mesh_map, path, geom, opt, 1);
}
