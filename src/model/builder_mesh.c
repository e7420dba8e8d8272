/* The builder's gear meshes: the spec's checks and gear size (gd_model_add_mesh), and
 * the names resolved by gd_model_finish. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

#define PI 3.14159265358979323846

void gd_mesh_spec_init(gd_mesh_spec *s)
{
    memset(s, 0, sizeof *s);
    s->pressure_angle = 20.0 * PI / 180.0;
    s->hand = 1;
    s->coupling = GD_COUPLING_FULL;
    gd_tvms_options_init(&s->tvms_options);
    s->tvms.interp = GD_INTERP_LINEAR;
    s->transmission_error.interp = GD_INTERP_LINEAR;
    s->coast_stiffness_ratio = 1.0;
}

static gd_status check_angle(const gd_model *m, gd_error *err, const gd_mesh_spec *s,
                             const char *path, const char *key, const char *what, double v)
{
    gd_status st = gd_build_positive(m, err, s->loc, path, key, v, 1);
    if (st || v < 60.0 * PI / 180.0) return st;
    char hint[80], fp[200];
    snprintf(hint, sizeof hint, "did you mean '%g deg'?", v);
    gd_build_path(fp, sizeof fp, path, key);
    return gd_build_fail(m, err, s->loc, fp, fp, hint,
                         "%s angle %g rad is not below 60 deg (plain numbers are radians)", what,
                         v);
}

static gd_status check_pair(const gd_model *m, gd_error *err, const gd_mesh_spec *s,
                            const char *path, const char *key, const double v[2], int *given)
{
    *given = v[0] != 0 || v[1] != 0;
    if (!*given) return GD_OK;
    for (int i = 0; i < 2; i++) {
        char q[200], ip[220];
        snprintf(q, sizeof q, "%s.%s", path, key);
        snprintf(ip, sizeof ip, "%s[%d]", q, i);
        if (!(v[i] > 0))
            return gd_build_fail(m, err, s->loc, ip, ip, "give a value greater than zero",
                                 "must be positive (got %g)", v[i]);
    }
    return GD_OK;
}

/* The gear size and angles of a mesh without geometry; the checks of its keys. */
static gd_status mesh_size(const gd_model *m, gd_error *err, const gd_mesh_spec *s,
                           const char *path, gd_mesh *g)
{
    gd_status st;
    char fp[200];
    int has_teeth = s->teeth[0] != 0 || s->teeth[1] != 0, has_rb, has_rp;
    int has_geom = s->geometry != NULL, has_mod = s->module != 0;
    if (has_teeth)
        for (int i = 0; i < 2; i++)
            if (s->teeth[i] < 3)
                return gd_build_fail(m, err, s->loc, gd_build_path(fp, sizeof fp, path, "teeth"),
                                     fp, "teeth numbers are whole numbers of 3 or more",
                                     "invalid teeth number %g", (double)s->teeth[i]);
    if ((st = check_pair(m, err, s, path, "base_radius", s->base_radius, &has_rb)) ||
        (st = check_pair(m, err, s, path, "pitch_radius", s->pitch_radius, &has_rp)) ||
        (st = gd_build_positive(m, err, s->loc, path, "module", s->module, 1)) ||
        (st = check_angle(m, err, s, path, "pressure_angle", "pressure", s->pressure_angle)) ||
        (st = check_angle(m, err, s, path, "helix_angle", "helix", s->helix_angle)))
        return st;
    if (has_geom && has_teeth)
        return gd_build_fail(m, err, s->loc, gd_build_path(fp, sizeof fp, path, "teeth"), fp,
                             "with `geometry:` the teeth and angles come from it; remove this key",
                             "'teeth' given together with `geometry:`");
    if ((st = gd_build_positive(m, err, s->loc, path, "face_width", s->face_width, 1))) return st;
    if (has_geom && s->face_width > 0)
        return gd_build_fail(m, err, s->loc, gd_build_path(fp, sizeof fp, path, "face_width"), fp,
                             "with `geometry:` the face width comes from it; remove this key",
                             "'face_width' given together with `geometry:`");
    g->face_width = s->face_width;
    int ngiven = has_rb + has_rp + has_mod + has_geom;
    if (ngiven != 1)
        return gd_build_fail(m, err, s->loc, NULL, path,
                             "give exactly one of base_radius: [rb1, rb2], pitch_radius: [r1, r2], "
                             "module with teeth, or geometry:",
                             ngiven ? "gear size given more than once" : "gear size missing");
    if (has_mod && !has_teeth)
        return gd_build_fail(m, err, s->loc, gd_build_path(fp, sizeof fp, path, "module"), path,
                             "add `teeth: [z1, z2]`", "module needs the teeth numbers");
    g->pressure_angle = s->pressure_angle;
    g->helix_angle = s->helix_angle;
    double ca = cos(g->pressure_angle);
    for (int i = 0; i < 2; i++) {
        g->teeth[i] = s->teeth[i];
        if (has_rb) g->base_radius[i] = s->base_radius[i];
        if (has_rp) g->base_radius[i] = s->pitch_radius[i] * ca;
        if (has_mod) g->base_radius[i] = 0.5 * s->module * s->teeth[i] * ca;
    }
    if (has_teeth && (has_rb || has_rp)) {
        double rr = g->base_radius[1] / g->base_radius[0];
        double tr = (double)s->teeth[1] / s->teeth[0];
        if (fabs(rr - tr) > 1e-3 * tr)
            return gd_build_fail(m, err, s->loc, gd_build_path(fp, sizeof fp, path, "teeth"), fp,
                                 "radii and teeth numbers must give the same gear ratio",
                                 "radius ratio %.6g differs from teeth ratio %.6g", rr, tr);
    }
    g->hand = s->hand < 0 ? -1 : 1;
    g->base_helix_angle = atan(tan(g->helix_angle) * cos(g->pressure_angle));
    return GD_OK;
}

/* The time-integration values of a mesh. */
static gd_status mesh_dynamics(const gd_model *m, gd_error *err, const gd_mesh_spec *s,
                               const char *path, gd_mesh *g)
{
    gd_status st;
    char q[200], fp[220];
    int teeth = s->geometry ? s->geometry->gear[0].teeth : s->teeth[0];
    const char *need = "add `teeth: [z1, z2]` (or `geometry:`) to the mesh";
    const char *need_msg = "a table over the mesh period needs the driver's teeth number";
    if ((st = gd_build_positive(m, err, s->loc, path, "damping", s->damping, 1)) ||
        (st = gd_build_positive(m, err, s->loc, path, "damping_per_stiffness",
                                s->damping_per_stiffness, 1)) ||
        (st =
             gd_build_positive(m, err, s->loc, path, "damping_separated", s->damping_separated, 1)))
        return st;
    if (s->tvms.n) {
        gd_build_path(q, sizeof q, path, "tvms");
        if (s->stiffness_from_geometry)
            return gd_build_fail(m, err, s->loc, q, q,
                                 "keep one: the table, or `stiffness: {from: geometry}`",
                                 "tvms table given together with stiffness from geometry");
        if (!(teeth > 0)) return gd_build_fail(m, err, s->loc, q, q, need, "%s", need_msg);
        if (s->tvms.n < 2 || !s->tvms.x || !s->tvms.y)
            return gd_build_fail(m, err, s->loc, q, q, "give two points or more", "only %d point%s",
                                 s->tvms.n, s->tvms.n == 1 ? "" : "s");
        for (int i = 0; i < s->tvms.n; i++)
            if (!(s->tvms.y[i] > 0))
                return gd_build_fail(m, err, s->loc, gd_build_path(fp, sizeof fp, q, "stiffness"),
                                     q, "mesh stiffness values must be positive",
                                     "stiffness %g at entry %d", s->tvms.y[i], i);
    }
    if (s->transmission_error.n) {
        gd_build_path(q, sizeof q, path, "transmission_error");
        if (s->stiffness_from_geometry && s->tvms_options.contact_analysis)
            return gd_build_fail(m, err, s->loc, q, q,
                                 "keep one: the table, or `stiffness: {from: contact_analysis}`",
                                 "transmission_error table given together with the contact "
                                 "analysis, which gives the loaded transmission error");
        if (!(teeth > 0)) return gd_build_fail(m, err, s->loc, q, q, need, "%s", need_msg);
        if (s->transmission_error.n < 2 || !s->transmission_error.x || !s->transmission_error.y)
            return gd_build_fail(m, err, s->loc, q, q, "give two points or more", "only %d point%s",
                                 s->transmission_error.n, s->transmission_error.n == 1 ? "" : "s");
    }
    if (s->backlash) {
        gd_build_path(q, sizeof q, path, "backlash");
        if ((st = gd_build_positive(m, err, s->loc, q, "gap", s->backlash_gap, 1)) ||
            (st = gd_build_positive(m, err, s->loc, q, "coast_stiffness_ratio",
                                    s->coast_stiffness_ratio, 1))) /* 0: one-sided */
            return st;
    }
    if ((st = gd_build_positive(m, err, s->loc, path, "stiffness", s->stiffness, 1))) return st;
    if (!(s->stiffness > 0) && !s->tvms.n && !s->stiffness_from_geometry)
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "stiffness"),
                             "give the stiffness (N/m), a tvms table, or stiffness from geometry",
                             "mesh has no stiffness");
    gd_mesh_dynamics *d = &g->dyn;
    g->stiffness = s->stiffness;
    g->damping = s->damping;
    d->tvms_phase = s->tvms_phase;
    d->damping_per_stiffness = s->damping_per_stiffness;
    d->damping_separated = s->damping_separated;
    d->backlash = s->backlash != 0;
    d->gap = s->backlash ? s->backlash_gap : 0;
    d->coast_stiffness_ratio = s->backlash ? s->coast_stiffness_ratio : 1.0;
    return GD_OK;
}

gd_status gd_model_add_mesh(gd_model *m, const gd_mesh_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nmeshes;
    char path[160], fp[200];
    if (s->path)
        snprintf(path, sizeof path, "%s", s->path);
    else
        snprintf(path, sizeof path, "meshes[%d]", idx);
    gd_mesh g;
    memset(&g, 0, sizeof g);
    g.driver = g.driven = -1;
    g.loc = s->loc;
    if ((st = gd_build_name(m, err, s->loc, path, s->name, NULL, g.name)) ||
        (st = mesh_size(m, err, s, path, &g)))
        return st;
    if ((int)s->coupling < GD_COUPLING_TORSIONAL || (int)s->coupling > GD_COUPLING_FULL)
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(fp, sizeof fp, path, "coupling"),
                             "use a gd_coupling", "unknown coupling %d", (int)s->coupling);
    g.coupling = s->coupling;
    g.line_of_centres = s->line_of_centres;
    if (s->stiffness_from_geometry && !s->geometry)
        return gd_build_fail(m, err, s->loc, gd_build_path(fp, sizeof fp, path, "stiffness"), fp,
                             "add a `geometry:` map to the mesh (docs/mesh-stiffness.md)",
                             "stiffness from geometry needs the mesh's geometry");
    if ((st = mesh_dynamics(m, err, s, path, &g))) return st;

    gd_bmesh bm;
    memset(&bm, 0, sizeof bm);
    bm.path = gd_build_strdup(path);
    bm.driver = gd_build_strdup(s->driver);
    bm.driven = gd_build_strdup(s->driven);
    bm.has_geometry = s->geometry != NULL;
    if (s->geometry) bm.geometry = *s->geometry;
    bm.from_geometry = s->stiffness_from_geometry != 0;
    bm.options = s->tvms_options;
    bm.driver_rotation = s->driver_rotation;
    int ok = bm.path && (!s->driver || bm.driver) && (!s->driven || bm.driven) &&
             gd_build_copy_table(&bm.tvms, &s->tvms) &&
             gd_build_copy_table(&bm.ste, &s->transmission_error) &&
             gd_build_grow(&m->meshes, m->nmeshes, sizeof *m->meshes) &&
             gd_build_grow(&m->build->meshes, m->nmeshes, sizeof *m->build->meshes);
    if (!ok) {
        free(bm.path);
        free(bm.driver);
        free(bm.driven);
        free(bm.tvms.x);
        free(bm.tvms.y);
        free(bm.ste.x);
        free(bm.ste.y);
        return gd_build_oom(m, err);
    }
    m->meshes[idx] = g;
    m->build->meshes[idx] = bm;
    m->nmeshes++;
    if (index) *index = idx;
    return GD_OK;
}

gd_status gd_build_resolve_meshes(gd_model *m, gd_error *err)
{
    gd_status st;
    for (int k = 0; k < m->nmeshes; k++) {
        gd_mesh *g = &m->meshes[k];
        const gd_bmesh *bm = &m->build->meshes[k];
        if ((st = gd_build_node_ref(m, err, g->loc, bm->path, "driver", bm->driver, &g->driver)) ||
            (st = gd_build_node_ref(m, err, g->loc, bm->path, "driven", bm->driven, &g->driven)))
            return st;
        int sa = m->nodes[g->driver].shaft, sb = m->nodes[g->driven].shaft;
        if (sa == sb) {
            char fp[200];
            gd_build_path(fp, sizeof fp, bm->path, "driven");
            return gd_build_fail(
                m, err, g->loc, fp, fp, "a gear mesh joins gears on two different shafts",
                "driver '%s' and driven '%s' are on the same shaft '%s'", m->nodes[g->driver].name,
                m->nodes[g->driven].name, m->shafts[sa].name);
        }
        if ((st = gd_build_mesh_from_geometry(m, k, err)) ||
            (st = gd_build_component_name(m, err, "mesh", k, g->loc, bm->path)))
            return st;
    }
    return GD_OK;
}
