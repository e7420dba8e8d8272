/* The model builder (include/geardyn/builder.h): its error and name helpers, a model
 * under construction, materials, globals, and gd_model_finish. Shafts and their
 * stations: builder_shafts.c; disks, bearings, springs: builder_items.c; meshes:
 * builder_mesh.c; unbalances and time-integration items: builder_dynamics.c. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

gd_status gd_build_fail(const gd_model *m, gd_error *err, gd_loc loc, const char *locate_path,
                        const char *field, const char *hint, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    gd_status st = gd_error_set(err, GD_EINPUT, m->file, loc.line, loc.column, field ? field : "",
                                hint, "%s", msg);
    if (locate_path && m->build && m->build->locator.locate)
        m->build->locator.locate(m->build->locator.ctx, locate_path, err);
    return st;
}

gd_status gd_build_oom(const gd_model *m, gd_error *err)
{
    return gd_error_set(err, GD_ENOMEM, m->file, 0, 0, "", "", "out of memory");
}

const char *gd_build_path(char *buf, size_t size, const char *path, const char *key)
{
    /* joined by hand: a path longer than buf is cut */
    size_t n = 0;
    const char *parts[3] = {path && path[0] ? path : "", path && path[0] ? "." : "", key};
    for (int i = 0; i < 3; i++)
        for (const char *c = parts[i]; *c && n + 1 < size; c++)
            buf[n++] = *c;
    if (size) buf[n] = '\0';
    return buf;
}

char *gd_build_strdup(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c) memcpy(c, s, n);
    return c;
}

gd_status gd_build_open(const gd_model *m, gd_error *err)
{
    if (m->build && m->build->failed)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "", "free it and build a new model",
                            "gd_model_finish failed on this model: it can only be freed");
    if (m->build) return GD_OK;
    return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "",
                        "add everything before gd_model_finish, or build a new model",
                        "the model is finished: it can no longer be changed by the builder");
}

/* Grows *array of *n items of size sz by one zeroed item; 0 on failure. */
int gd_build_grow(void *array, int n, size_t sz)
{
    void **a = array;
    char *p = realloc(*a, (size_t)(n + 1) * sz);
    if (!p) return 0;
    memset(p + (size_t)n * sz, 0, sz);
    *a = p;
    return 1;
}

gd_status gd_build_name(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                        const char *name, const char *fallback, char out[GD_NAME_MAX])
{
    if (!name) name = fallback;
    if (!name || !name[0]) {
        char q[200];
        return gd_build_fail(m, err, loc, NULL, gd_build_path(q, sizeof q, path, "name"),
                             "give the item a name", "name missing");
    }
    if (strlen(name) >= GD_NAME_MAX) {
        char q[200];
        gd_build_path(q, sizeof q, path, "name");
        return gd_build_fail(m, err, loc, q, q, "use a shorter name",
                             "name longer than %d characters", GD_NAME_MAX - 1);
    }
    if (out) snprintf(out, GD_NAME_MAX, "%s", name);
    return GD_OK;
}

gd_status gd_build_positive(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                            const char *key, double v, int allow_zero)
{
    if (allow_zero ? v >= 0 : v > 0) return GD_OK;
    char q[200];
    gd_build_path(q, sizeof q, path, key);
    if (allow_zero)
        return gd_build_fail(m, err, loc, q, q, "give a value of zero or more",
                             "must not be negative (got %g)", v);
    return gd_build_fail(m, err, loc, q, q, "give a value greater than zero",
                         "must be positive (got %g)", v);
}

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

static void free_table(gd_btable *t)
{
    free(t->x);
    free(t->y);
}

static void free_items(gd_bitem *items, int n)
{
    for (int i = 0; i < n && items; i++) {
        free(items[i].path);
        free(items[i].node);
        free(items[i].node2);
        free(items[i].material);
    }
    free(items);
}

void gd_model_build_free(gd_model *m)
{
    gd_model_build *b = m->build;
    if (!b) return;
    for (int i = 0; i < m->nmaterials && b->material_path; i++)
        free(b->material_path[i]);
    free(b->material_path);
    for (int i = 0; i < m->nshafts && b->shafts; i++)
        gd_build_free_shaft(&b->shafts[i], m->shafts[i].nsections);
    free(b->shafts);
    free_items(b->disks, m->ndisks);
    free_items(b->bearings, m->nbearings);
    free_items(b->springs, m->nsprings);
    free_items(b->unbalances, m->nunbalances);
    free_items(b->excitations, m->nexcitations);
    free_items(b->prescribed, m->nprescribed);
    free_items(b->cams, m->ncams);
    free_items(b->laws, m->nlaws);
    for (int i = 0; i < m->nmeshes && b->meshes; i++) {
        gd_bmesh *g = &b->meshes[i];
        free(g->path);
        free(g->driver);
        free(g->driven);
        free_table(&g->tvms);
        free_table(&g->ste);
    }
    free(b->meshes);
    for (int i = 0; i < m->nexcitations && b->excitation_tables; i++)
        free_table(&b->excitation_tables[i]);
    for (int i = 0; i < m->nprescribed && b->prescribed_tables; i++)
        free_table(&b->prescribed_tables[i]);
    for (int i = 0; i < m->ncams && b->cam_tables; i++)
        free_table(&b->cam_tables[i]);
    free(b->excitation_tables);
    free(b->prescribed_tables);
    free(b->cam_tables);
    free(b->reference_shaft);
    free(b);
    m->build = NULL;
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
    double n = 0;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(direction[i]))
            return gd_build_fail(m, err, loc, "gravity.direction", "gravity.direction",
                                 "give three finite numbers, e.g. [0, -1, 0]",
                                 "direction component %d is not finite", i);
        n += direction[i] * direction[i];
    }
    if (!(n > 0))
        return gd_build_fail(m, err, loc, "gravity.direction", "gravity.direction",
                             "give the direction gravity pulls in, e.g. [0, -1, 0]",
                             "gravity direction is zero");
    if (!isfinite(g) || g < 0)
        return gd_build_fail(m, err, loc, "gravity.g", "gravity.g",
                             "give g >= 0 in m/s^2, e.g. 9.81", "g = %g is not a finite value >= 0",
                             g);
    n = sqrt(n);
    for (int i = 0; i < 3; i++)
        m->gravity[i] = g * direction[i] / n;
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
    m->build->failed = 1; /* until it succeeds: half-resolved items cannot be redone */
    if ((st = gd_build_discretise_shafts(m, err)) || (st = finish_reference(m, err)) ||
        (st = gd_build_resolve_disks(m, err)) || (st = gd_build_resolve_supports(m, err)) ||
        (st = gd_build_resolve_meshes(m, err)) || (st = gd_build_propagate_speeds(m, err)) ||
        (st = gd_build_resolve_dynamics(m, err)) || (st = gd_build_resolve_laws(m, err)))
        return st;
    gd_model_build_free(m);
    return GD_OK;
}
