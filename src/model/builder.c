/* The model builder (include/geardyn/builder.h): a model under construction, materials,
 * globals, and gd_model_finish. Its error and name helpers: builder_support.c; the
 * teardown of its state: builder_state.c. Shafts and their stations: builder_shafts.c;
 * disks, bearings, springs: builder_items.c; meshes: builder_mesh.c; unbalances and
 * time-integration items: builder_dynamics.c. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

void gd_model_set_locator(gd_model *m, const gd_field_locator *locator)
{
    if (m->build) m->build->locator = *locator;
}

/* ---- the model ---- */

gd_status gd_model_new(const char *name, gd_model **out, gd_error *err)
{
    *out = NULL;
    gd_model *m = calloc(1, sizeof *m);
    if (!m) return gd_error_set(err, GD_ENOMEM, name ? name : "", 0, 0, "", "", "out of memory");
    m->build = calloc(1, sizeof *m->build);
    if (!m->build) {
        free(m);
        return gd_error_set(err, GD_ENOMEM, name ? name : "", 0, 0, "", "", "out of memory");
    }
    snprintf(m->file, sizeof m->file, "%s", name ? name : "");
    m->dof_mask = GD_DOFS_ALL;
    m->excite_unbalances = 1;
    m->build->rotation = 1;
    *out = m;
    return GD_OK;
}

int gd_model_is_finished(const gd_model *m)
{
    return m->build == NULL;
}

/* ---- materials ---- */

void gd_material_spec_init(gd_material_spec *s)
{
    memset(s, 0, sizeof *s);
}

gd_status gd_model_add_material(gd_model *m, const gd_material_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    char path[200], q[220];
    if (s->path)
        snprintf(path, sizeof path, "%s", s->path);
    else
        snprintf(path, sizeof path, "materials.%s", s->name ? s->name : "");
    gd_material mat;
    memset(&mat, 0, sizeof mat);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, NULL, mat.name))) return st;
    for (int i = 0; i < m->nmaterials; i++)
        if (!strcmp(m->materials[i].name, mat.name))
            return gd_build_fail(m, err, s->loc, NULL, path, "give every material its own name",
                                 "duplicate material name '%s'", mat.name);
    if ((st = gd_build_positive(m, err, s->loc, path, "density", s->density, 0)) ||
        (st = gd_build_positive(m, err, s->loc, path, "E", s->E, 0)) ||
        (st = gd_build_positive(m, err, s->loc, path, "G", s->G, 1)))
        return st;
    mat.density = s->density;
    mat.E = s->E;
    mat.G = s->G;
    mat.poisson = s->poisson;
    if (!(s->G > 0))
        mat.G = s->E / (2.0 * (1.0 + s->poisson));
    else if (s->poisson == 0)
        mat.poisson = s->E / (2.0 * s->G) - 1.0;
    if (!(mat.poisson > -1.0 && mat.poisson < 0.5)) {
        const char *key = s->G > 0 && s->poisson == 0 ? "G" : "poisson";
        gd_build_path(q, sizeof q, path, key);
        return gd_build_fail(m, err, s->loc, q, q,
                             "Poisson's ratio lies between -1 and 0.5 (steel: 0.3)",
                             "poisson %g is not physical", mat.poisson);
    }
    char *pcopy = gd_build_strdup(path);
    if (!pcopy || !gd_build_grow(&m->materials, m->nmaterials, sizeof *m->materials) ||
        !gd_build_grow(&m->build->material_path, m->nmaterials, sizeof(char *))) {
        free(pcopy);
        return gd_build_oom(m, err);
    }
    m->materials[m->nmaterials] = mat;
    m->build->material_path[m->nmaterials] = pcopy;
    if (index) *index = m->nmaterials;
    m->nmaterials++;
    return GD_OK;
}

/* ---- globals ---- */

gd_status gd_model_set_dofs(gd_model *m, unsigned dof_mask, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    gd_loc none = {0, 0};
    if (!dof_mask || (dof_mask & ~GD_DOFS_ALL))
        return gd_build_fail(m, err, none, NULL, "dofs", "list at least one DOF, e.g. [rz]",
                             dof_mask ? "unknown DOFs in the mask" : "no DOFs");
    m->dof_mask = dof_mask;
    return GD_OK;
}

gd_status gd_model_set_reference_shaft(gd_model *m, const char *shaft, int rotation, gd_loc loc,
                                       gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    char *c = NULL;
    if (shaft && !(c = gd_build_strdup(shaft))) return gd_build_oom(m, err);
    free(m->build->reference_shaft);
    m->build->reference_shaft = c;
    m->build->rotation = rotation < 0 ? -1 : 1;
    m->build->reference_loc = loc;
    return GD_OK;
}

gd_status gd_model_set_max_nodes(gd_model *m, long max_nodes, gd_loc loc, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    if (max_nodes < 1)
        return gd_build_fail(m, err, loc, "limits.max_nodes", "limits.max_nodes",
                             "give a whole number of 1 or more", "%ld nodes is out of range",
                             max_nodes);
    m->build->max_nodes = max_nodes;
    m->build->max_nodes_loc = loc;
    return GD_OK;
}

gd_status gd_model_set_rayleigh(gd_model *m, double alpha, double beta, gd_error *err)
{
    gd_status st;
    gd_loc none = {0, 0};
    if ((st = gd_build_open(m, err))) return st;
    if (!(alpha < INFINITY) || !(beta < INFINITY))
        return gd_build_fail(m, err, none, "damping.rayleigh", "damping.rayleigh",
                             "give finite values", "alpha %g, beta %g are not finite", alpha, beta);
    if ((st = gd_build_positive(m, err, none, "damping.rayleigh", "alpha", alpha, 1)) ||
        (st = gd_build_positive(m, err, none, "damping.rayleigh", "beta", beta, 1)))
        return st;
    m->rayleigh_alpha = alpha;
    m->rayleigh_beta = beta;
    return GD_OK;
}

gd_status gd_rayleigh_from_ratios(double z1, double z2, double w1, double w2, double *alpha,
                                  double *beta, gd_error *err)
{
    if (!(w1 > 0) || !(w2 > 0) || w1 == w2 || !isfinite(w1) || !isfinite(w2))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "damping.rayleigh.frequencies",
                            "give two different positive frequencies",
                            "frequencies %g and %g rad/s do not fix alpha and beta", w1, w2);
    /* z_i = alpha / (2 w_i) + beta w_i / 2, two equations */
    double d = w2 * w2 - w1 * w1;
    double a = 2 * w1 * w2 * (z1 * w2 - z2 * w1) / d, b = 2 * (z2 * w2 - z1 * w1) / d;
    if (!(a >= 0) || !(b >= 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "damping.rayleigh.ratios",
                            "Rayleigh damping rises with frequency above sqrt(alpha/beta) and "
                            "falls below it: choose ratios it can give",
                            "ratios %g and %g at %g and %g rad/s need alpha %g, beta %g (negative)",
                            z1, z2, w1, w2, a, b);
    *alpha = a;
    *beta = b;
    return GD_OK;
}

gd_status gd_model_set_gravity(gd_model *m, const double direction[3], double g, gd_loc loc,
                               gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    double n = 0, big = 0;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(direction[i]))
            return gd_build_fail(m, err, loc, "gravity.direction", "gravity.direction",
                                 "give three finite numbers, e.g. [0, -1, 0]",
                                 "direction component %d is not finite", i);
        big = fmax(big, fabs(direction[i]));
    }
    /* scaled by the largest component: [0, -1e308, 1e308] squared overflowed to an inf
     * norm, a zero gravity vector and "LU pivot -7" (issue 38 M7) */
    for (int i = 0; big > 0 && i < 3; i++)
        n += (direction[i] / big) * (direction[i] / big);
    if (!(n > 0))
        return gd_build_fail(m, err, loc, "gravity.direction", "gravity.direction",
                             "give the direction gravity pulls in, e.g. [0, -1, 0]",
                             "gravity direction is zero");
    if (!isfinite(g) || g < 0)
        return gd_build_fail(m, err, loc, "gravity.g", "gravity.g",
                             "give g >= 0 in m/s^2, e.g. 9.81", "g = %g is not a finite value >= 0",
                             g);
    /* 1e6 m/s^2 is 1e5 times the Earth's (beyond a centrifuge's); 1e308 gave deflections
     * of 1e307 m and NaN in the static tables with exit 0 */
    if (g > 1e6)
        return gd_build_fail(m, err, loc, "gravity.g", "gravity.g",
                             "give g in m/s^2 (9.81 on the Earth), at most 1e6",
                             "g = %g m/s^2 is over 1e6 m/s^2", g);
    n = sqrt(n);
    for (int i = 0; i < 3; i++)
        m->gravity[i] = g * (direction[i] / big) / n;
    return GD_OK;
}

gd_status gd_model_set_speed(gd_model *m, double speed, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    gd_loc none = {0, 0};
    if ((st = gd_build_positive(m, err, none, "", "speed", speed, 1))) return st;
    m->speed = speed;
    return GD_OK;
}

gd_status gd_model_set_excite_unbalances(gd_model *m, int on, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    m->excite_unbalances = on != 0;
    return GD_OK;
}

/* ---- finish ---- */

/* The reference shaft and its sense. */
static gd_status finish_reference(gd_model *m, gd_error *err)
{
    gd_model_build *b = m->build;
    m->reference_shaft = 0;
    if (b->reference_shaft) {
        m->reference_shaft = gd_model_find_shaft(m, b->reference_shaft);
        if (m->reference_shaft < 0)
            return gd_build_fail(m, err, b->reference_loc, NULL, "reference_shaft",
                                 "name one of the shafts", "unknown shaft '%s'",
                                 b->reference_shaft);
    }
    gd_shaft *rs = &m->shafts[m->reference_shaft];
    if (rs->speed_ratio_given && fabs(fabs(rs->speed_ratio) - 1.0) > 1e-12) {
        char field[200];
        gd_build_path(field, sizeof field, b->shafts[m->reference_shaft].path, "speed_ratio");
        return gd_build_fail(m, err, rs->speed_ratio_loc, NULL, field,
                             "the reference shaft turns at the reference speed; remove "
                             "speed_ratio or use `rotation: cw` for the opposite sense",
                             "reference shaft '%s' has speed_ratio %g", rs->name, rs->speed_ratio);
    }
    if (!rs->speed_ratio_given) rs->speed_ratio = b->rotation;
    rs->speed_ratio_given = 1;
    return GD_OK;
}

gd_status gd_model_finish(gd_model *m, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    gd_loc none = {0, 0};
    if (m->nshafts == 0)
        return gd_build_fail(m, err, none, NULL, "shafts", "describe at least one shaft",
                             "no shafts");
    /* the engaged synchronisers' locks are springs, added while adds are still open */
    st = gd_build_engage_synchronisers(m, err);
    m->build->failed = 1; /* until it succeeds: half-resolved items cannot be redone */
    if (st) return st;
    if ((st = gd_build_discretise_shafts(m, err)) || (st = finish_reference(m, err)) ||
        (st = gd_build_resolve_disks(m, err)) || (st = gd_build_resolve_supports(m, err)) ||
        (st = gd_build_resolve_idlers(m, err)) || (st = gd_build_resolve_meshes(m, err)) ||
        (st = gd_build_resolve_planetary(m, err)) || (st = gd_build_propagate_speeds(m, err)) ||
        (st = gd_build_resolve_dynamics(m, err)) || (st = gd_build_resolve_laws(m, err)))
        return st;
    gd_model_build_free(m);
    return GD_OK;
}
