/* The builder's disks, bearings and springs, and the name look-ups every item uses:
 * nodes, materials, and the one namespace of shafts, bearings, springs and meshes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

#define PI 3.14159265358979323846

/* ---- names ---- */

gd_status gd_build_node_ref(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                            const char *key, const char *name, int *out)
{
    char q[240];
    gd_build_path(q, sizeof q, path, key);
    if (!name)
        return gd_build_fail(m, err, loc, NULL, q, "name a node of a shaft", "no %s given", key);
    int idx = gd_model_find_node(m, name);
    if (idx >= 0) {
        *out = idx;
        return GD_OK;
    }
    char hint[300] = "named nodes:";
    int shown = 0;
    for (int i = 0; i < m->nnodes && shown < 12; i++)
        if (m->nodes[i].named) {
            size_t u = strlen(hint);
            snprintf(hint + u, sizeof hint - u, " %s", m->nodes[i].name);
            shown++;
        }
    size_t u = strlen(hint);
    snprintf(hint + u, sizeof hint - u, "%s (generated nodes are SHAFT@INDEX)",
             shown ? "" : " none");
    return gd_build_fail(m, err, loc, q, q, hint, "unknown node '%s'", name);
}

gd_status gd_build_material_ref(const gd_model *m, gd_error *err, gd_loc loc,
                                const char *locate_path, const char *field, const char *name,
                                int *out)
{
    if (!name)
        return gd_build_fail(m, err, loc, locate_path, field,
                             "name a material defined under `materials:`",
                             "expected a material name");
    for (int i = 0; i < m->nmaterials; i++)
        if (!strcmp(m->materials[i].name, name)) {
            *out = i;
            return GD_OK;
        }
    char hint[300];
    if (m->nmaterials) {
        int used = snprintf(hint, sizeof hint, "defined materials:");
        for (int i = 0; i < m->nmaterials && used < (int)sizeof hint - 70; i++)
            used += snprintf(hint + used, sizeof hint - (size_t)used, " %s", m->materials[i].name);
        snprintf(hint + used, sizeof hint - (size_t)used, "; or define '%s' under `materials:`",
                 name);
    } else {
        snprintf(hint, sizeof hint,
                 "define it under `materials: {%s: {density: ..., E: ..., poisson: ...}}`", name);
    }
    return gd_build_fail(m, err, loc, locate_path, field, hint, "unknown material '%s'", name);
}

/* In the order the kinds are resolved: a name clashes with the kinds before it and
 * with the earlier items of its own kind. */
gd_status gd_build_component_name(const gd_model *m, gd_error *err, const char *kind, int index,
                                  gd_loc loc, const char *path)
{
    static const char *const KINDS[] = {"shaft", "bearing", "spring", "mesh"};
    int rank = 0;
    while (rank < 3 && strcmp(KINDS[rank], kind))
        rank++;
    const char *name = rank == 0   ? m->shafts[index].name
                       : rank == 1 ? m->bearings[index].name
                       : rank == 2 ? m->springs[index].name
                                   : m->meshes[index].name;
    const char *what = NULL;
    int line = 0;
    for (int i = 0; i < (rank > 0 ? m->nshafts : index) && !what; i++)
        if (!strcmp(m->shafts[i].name, name)) what = "shaft", line = m->shafts[i].loc.line;
    for (int i = 0; rank >= 1 && i < (rank > 1 ? m->nbearings : index) && !what; i++)
        if (!strcmp(m->bearings[i].name, name)) what = "bearing", line = m->bearings[i].loc.line;
    for (int i = 0; rank >= 2 && i < (rank > 2 ? m->nsprings : index) && !what; i++)
        if (!strcmp(m->springs[i].name, name)) what = "spring", line = m->springs[i].loc.line;
    for (int i = 0; rank >= 3 && i < index && !what; i++)
        if (!strcmp(m->meshes[i].name, name)) what = "mesh", line = m->meshes[i].loc.line;
    if (!what) return GD_OK;
    char q[240];
    gd_build_path(q, sizeof q, path, "name");
    const char *hint = "give every shaft, bearing, spring and mesh its own name";
    if (!strcmp(what, kind))
        return gd_build_fail(m, err, loc, q, q, hint, "duplicate %s name '%s' (first on line %d)",
                             kind, name, line);
    return gd_build_fail(m, err, loc, q, q, hint, "name '%s' is already used by the %s on line %d",
                         name, what, line);
}

int gd_build_item_init(gd_bitem *it, const char *path, const char *node, const char *node2,
                       const char *material)
{
    memset(it, 0, sizeof *it);
    it->path = gd_build_strdup(path);
    it->node = gd_build_strdup(node);
    it->node2 = gd_build_strdup(node2);
    it->material = gd_build_strdup(material);
    if (!it->path || (node && !it->node) || (node2 && !it->node2) || (material && !it->material)) {
        free(it->path);
        free(it->node);
        free(it->node2);
        free(it->material);
        return 0;
    }
    return 1;
}

const char *gd_build_item_path(char *buf, size_t size, const char *given, const char *kind, int i)
{
    if (given)
        snprintf(buf, size, "%s", given);
    else
        snprintf(buf, size, "%s[%d]", kind, i);
    return buf;
}

/* ---- disks ---- */

void gd_disk_spec_init(gd_disk_spec *s)
{
    memset(s, 0, sizeof *s);
    s->diametral_inertia = -1;
}

gd_status gd_model_add_disk(gd_model *m, const gd_disk_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->ndisks;
    char path[160], fb[32], gp[200];
    gd_build_item_path(path, sizeof path, s->path, "disks", idx);
    gd_build_path(gp, sizeof gp, path, "geometry");
    gd_disk d;
    memset(&d, 0, sizeof d);
    snprintf(fb, sizeof fb, "disk%d", idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, d.name))) return st;
    d.loc = s->loc;
    d.node = -1;
    if (s->from_geometry) {
        if ((st = gd_build_positive(m, err, s->loc, gp, "outer_diameter", s->outer_diameter, 0)) ||
            (st = gd_build_positive(m, err, s->loc, gp, "inner_diameter", s->inner_diameter, 1)) ||
            (st = gd_build_positive(m, err, s->loc, gp, "width", s->width, 0)))
            return st;
        if (!s->material)
            return gd_build_fail(m, err, s->loc, gp, gp, "add `material: NAME`", "no material");
        if (s->inner_diameter >= s->outer_diameter) {
            char fp[220];
            gd_build_path(fp, sizeof fp, gp, "inner_diameter");
            return gd_build_fail(m, err, s->loc, fp, fp,
                                 "the bore must be smaller than the outer diameter",
                                 "inner diameter %g m is not less than outer diameter %g m",
                                 s->inner_diameter, s->outer_diameter);
        }
    } else {
        if ((st = gd_build_positive(m, err, s->loc, path, "mass", s->mass, 1)) ||
            (st = gd_build_positive(m, err, s->loc, path, "polar_inertia", s->polar_inertia, 1)))
            return st;
        if (!(s->mass > 0) && !(s->polar_inertia > 0) && !(s->diametral_inertia > 0))
            return gd_build_fail(m, err, s->loc, NULL, path,
                                 "give mass and polar_inertia (kg, kg*m^2), or `geometry:`",
                                 "disk has no mass or inertia");
        /* a mass or inertia next to nothing is not a disk: beside the shafts' and
         * bearings' values it leaves the mass matrix singular to working precision and
         * every mode comes out 0 Hz or 1e300 Hz (issue 23); 0 is the massless node */
        static const char *const MKEY[3] = {"mass", "polar_inertia", "diametral_inertia"};
        static const char *const MUNIT[3] = {"kg", "kg*m^2", "kg*m^2"};
        const double mv[3] = {s->mass, s->polar_inertia, s->diametral_inertia};
        const double mlo[3] = {1e-9, 1e-15, 1e-15};
        for (int k = 0; k < 3; k++)
            if (mv[k] > 0 && mv[k] < mlo[k]) {
                char fp[220];
                gd_build_path(fp, sizeof fp, path, MKEY[k]);
                return gd_build_fail(m, err, s->loc, fp, fp,
                                     "give 0 (none) or at least the bound: smaller values make "
                                     "the mass matrix singular to working precision",
                                     "%s %g %s is below %g %s", MKEY[k], mv[k], MUNIT[k], mlo[k],
                                     MUNIT[k]);
            }
        d.mass = s->mass;
        d.polar_inertia = s->polar_inertia;
        /* a thin disk unless told otherwise */
        d.diametral_inertia =
            s->diametral_inertia >= 0 ? s->diametral_inertia : 0.5 * s->polar_inertia;
    }
    gd_bitem it;
    if (!gd_build_item_init(&it, path, s->node, NULL, s->from_geometry ? s->material : NULL))
        return gd_build_oom(m, err);
    it.from_geometry = s->from_geometry != 0;
    it.od = s->outer_diameter;
    it.id = s->inner_diameter;
    it.width = s->width;
    if (!gd_build_grow(&m->disks, m->ndisks, sizeof *m->disks) ||
        !gd_build_grow(&m->build->disks, m->ndisks, sizeof *m->build->disks)) {
        free(it.path);
        free(it.node);
        free(it.material);
        return gd_build_oom(m, err);
    }
    m->disks[idx] = d;
    m->build->disks[idx] = it;
    m->ndisks++;
    if (index) *index = idx;
    return GD_OK;
}

gd_status gd_build_resolve_disks(gd_model *m, gd_error *err)
{
    gd_status st;
    for (int i = 0; i < m->ndisks; i++) {
        gd_disk *d = &m->disks[i];
        const gd_bitem *it = &m->build->disks[i];
        if ((st = gd_build_node_ref(m, err, d->loc, it->path, "node", it->node, &d->node)))
            return st;
        for (int j = 0; j < i; j++)
            if (!strcmp(m->disks[j].name, d->name)) {
                char np[200];
                gd_build_path(np, sizeof np, it->path, "name");
                return gd_build_fail(m, err, d->loc, np, np, "give every disk its own name",
                                     "duplicate disk name '%s' (also on line %d)", d->name,
                                     m->disks[j].loc.line);
            }
        if (it->from_geometry) {
            char mp[240];
            int mi;
            gd_build_path(mp, sizeof mp, it->path, "geometry.material");
            if ((st = gd_build_material_ref(m, err, d->loc, mp, mp, it->material, &mi))) return st;
            double od = it->od, id = it->id, w = it->width;
            double rho = m->materials[mi].density;
            d->mass = rho * PI / 4.0 * (od * od - id * id) * w;
            /* thick disk: Ip = m (Ro^2 + Ri^2)/2, Id = Ip/2 + m w^2/12 */
            d->polar_inertia = d->mass * (od * od + id * id) / 8.0;
            d->diametral_inertia = 0.5 * d->polar_inertia + d->mass * w * w / 12.0;
        }
    }
    return GD_OK;
}

/* ---- bearings ---- */

void gd_bearing_spec_init(gd_bearing_spec *s)
{
    memset(s, 0, sizeof *s);
}

static int coeffs_any(const gd_bearing_coeffs *c)
{
    const double v[] = {c->kxx, c->kxy, c->kyx, c->kyy, c->kzz, c->ktilt, c->ktorsion,
                        c->cxx, c->cxy, c->cyx, c->cyy, c->czz, c->ctilt, c->ctorsion};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        if (v[i] != 0) return 1;
    return 0;
}

static gd_status check_coeffs(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                              const gd_bearing_coeffs *c)
{
    const struct {
        const char *key;
        double v;
    } f[] = {{"kxx", c->kxx},
             {"kyy", c->kyy},
             {"kzz", c->kzz},
             {"k_tilt", c->ktilt},
             {"k_torsion", c->ktorsion},
             {"cxx", c->cxx},
             {"cyy", c->cyy},
             {"czz", c->czz},
             {"c_tilt", c->ctilt},
             {"c_torsion", c->ctorsion}};
    for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
        gd_status st = gd_build_positive(m, err, loc, path, f[i].key, f[i].v, 1);
        if (st) return st;
    }
    return GD_OK;
}

static gd_status check_sfd(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                           const gd_sfd_params *s)
{
    char q[200], fp[220];
    gd_build_path(q, sizeof q, path, "sfd");
    gd_status st;
    if ((st = gd_build_positive(m, err, loc, q, "viscosity", s->viscosity, 0)) ||
        (st = gd_build_positive(m, err, loc, q, "diameter", s->radius, 0)) ||
        (st = gd_build_positive(m, err, loc, q, "length", s->length, 0)) ||
        (st = gd_build_positive(m, err, loc, q, "clearance", s->clearance, 0)) ||
        (st = gd_build_positive(m, err, loc, q, "max_eccentricity", s->max_eccentricity, 1)))
        return st;
    if (s->max_eccentricity >= 1.0)
        return gd_build_fail(m, err, loc, gd_build_path(fp, sizeof fp, q, "max_eccentricity"), fp,
                             "an eccentricity ratio below 1, e.g. 0.995", "must be below 1");
    if (s->clearance >= s->radius)
        return gd_build_fail(m, err, loc, gd_build_path(fp, sizeof fp, q, "clearance"), fp,
                             "the radial clearance is a small fraction of the radius",
                             "clearance %g m is not below the radius %g m", s->clearance,
                             s->radius);
    return GD_OK;
}

gd_status gd_model_add_bearing(gd_model *m, const gd_bearing_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nbearings;
    char path[160], fb[32], tp[200];
    gd_build_item_path(path, sizeof path, s->path, "bearings", idx);
    gd_build_path(tp, sizeof tp, path, "table");
    gd_bearing b;
    memset(&b, 0, sizeof b);
    snprintf(fb, sizeof fb, "bearing%d", idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, b.name))) return st;
    b.loc = s->loc;
    b.node = b.node2 = -1;
    if ((st = check_coeffs(m, err, s->loc, path, &s->coeffs))) return st;
    if (s->ntable) {
        if (coeffs_any(&s->coeffs))
            return gd_build_fail(m, err, s->loc, tp, tp, "put every coefficient in the table rows",
                                 "constant coefficients given together with a speed table");
        if (s->ntable < 2)
            return gd_build_fail(m, err, s->loc, tp, tp,
                                 "give at least two rows {speed: ..., kxx: ...}",
                                 "a speed table needs two or more rows");
        for (int j = 0; j < s->ntable; j++) {
            char rp[220], sp[240];
            snprintf(rp, sizeof rp, "%s[%d]", tp, j);
            if ((st = gd_build_positive(m, err, s->loc, rp, "speed", s->table_speed[j], 1)) ||
                (st = check_coeffs(m, err, s->loc, rp, &s->table[j])))
                return st;
            if (j > 0 && !(s->table_speed[j] > s->table_speed[j - 1]))
                return gd_build_fail(m, err, s->loc, gd_build_path(sp, sizeof sp, rp, "speed"), rp,
                                     "sort the rows by increasing speed",
                                     "speeds in the table must increase");
        }
    }
    if (s->has_sfd && (st = check_sfd(m, err, s->loc, path, &s->sfd))) return st;
    if (!coeffs_any(&s->coeffs) && !s->ntable && !s->has_sfd)
        return gd_build_fail(m, err, s->loc, NULL, path,
                             "give at least one of k, kxx, kyy, kzz, c, ..., sfd",
                             "bearing has no stiffness or damping");
    b.coeffs = s->coeffs;
    b.has_sfd = s->has_sfd != 0;
    if (b.has_sfd) b.sfd = s->sfd;
    gd_bitem it;
    if (s->ntable) {
        b.table_speed = malloc((size_t)s->ntable * sizeof *b.table_speed);
        b.table = malloc((size_t)s->ntable * sizeof *b.table);
        if (b.table_speed && b.table) {
            memcpy(b.table_speed, s->table_speed, (size_t)s->ntable * sizeof *b.table_speed);
            memcpy(b.table, s->table, (size_t)s->ntable * sizeof *b.table);
            b.ntable = s->ntable;
            b.coeffs = b.table[0];
        }
    }
    if ((s->ntable && !b.ntable) || !gd_build_item_init(&it, path, s->node, s->to, NULL)) {
        free(b.table_speed);
        free(b.table);
        return gd_build_oom(m, err);
    }
    if (!gd_build_grow(&m->bearings, m->nbearings, sizeof *m->bearings) ||
        !gd_build_grow(&m->build->bearings, m->nbearings, sizeof *m->build->bearings)) {
        free(b.table_speed);
        free(b.table);
        free(it.path);
        free(it.node);
        free(it.node2);
        return gd_build_oom(m, err);
    }
    m->bearings[idx] = b;
    m->build->bearings[idx] = it;
    m->nbearings++;
    if (index) *index = idx;
    return GD_OK;
}

/* ---- springs ---- */

void gd_spring_spec_init(gd_spring_spec *s)
{
    memset(s, 0, sizeof *s);
    s->dof = GD_RZ;
}

gd_status gd_model_add_spring(gd_model *m, const gd_spring_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nsprings;
    char path[160], fb[32], q[200];
    gd_build_item_path(path, sizeof path, s->path, "springs", idx);
    gd_spring sp;
    memset(&sp, 0, sizeof sp);
    snprintf(fb, sizeof fb, "spring%d", idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, sp.name))) return st;
    sp.loc = s->loc;
    sp.node1 = sp.node2 = -1;
    if ((int)s->dof < 0 || (int)s->dof >= GD_NODE_DOFS)
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "dof"),
                             "use one of GD_X ... GD_RZ", "unknown DOF %d", (int)s->dof);
    if ((st = gd_build_positive(m, err, s->loc, path, "stiffness", s->stiffness, 1)) ||
        (st = gd_build_positive(m, err, s->loc, path, "damping", s->damping, 1)))
        return st;
    if (!(s->stiffness > 0) && !(s->damping > 0))
        return gd_build_fail(m, err, s->loc, NULL, path, "give a positive stiffness or damping",
                             "spring has neither stiffness nor damping");
    sp.dof = s->dof;
    sp.stiffness = s->stiffness;
    sp.damping = s->damping;
    gd_bitem it;
    if (!gd_build_item_init(&it, path, s->node, s->to, NULL)) return gd_build_oom(m, err);
    if (!gd_build_grow(&m->springs, m->nsprings, sizeof *m->springs) ||
        !gd_build_grow(&m->build->springs, m->nsprings, sizeof *m->build->springs)) {
        free(it.path);
        free(it.node);
        free(it.node2);
        return gd_build_oom(m, err);
    }
    m->springs[idx] = sp;
    m->build->springs[idx] = it;
    m->nsprings++;
    if (index) *index = idx;
    return GD_OK;
}

/* node and `to` of a bearing or spring */
static gd_status resolve_pair(gd_model *m, gd_error *err, const char *kind, gd_loc loc,
                              const gd_bitem *it, int *n1, int *n2)
{
    gd_status st;
    if ((st = gd_build_node_ref(m, err, loc, it->path, "node", it->node, n1))) return st;
    *n2 = -1;
    if (it->node2 && (st = gd_build_node_ref(m, err, loc, it->path, "to", it->node2, n2)))
        return st;
    if (*n2 == *n1) {
        char tp[200];
        gd_build_path(tp, sizeof tp, it->path, "to");
        return gd_build_fail(m, err, loc, tp, tp,
                             "connect two different nodes, or omit `to` for ground",
                             "%s connects a node to itself", kind);
    }
    return GD_OK;
}

gd_status gd_build_resolve_supports(gd_model *m, gd_error *err)
{
    gd_status st;
    for (int i = 0; i < m->nbearings; i++) {
        gd_bearing *b = &m->bearings[i];
        const gd_bitem *it = &m->build->bearings[i];
        if ((st = gd_build_component_name(m, err, "bearing", i, b->loc, it->path)) ||
            (st = resolve_pair(m, err, "bearing", b->loc, it, &b->node, &b->node2)))
            return st;
    }
    for (int i = 0; i < m->nsprings; i++) {
        gd_spring *s = &m->springs[i];
        const gd_bitem *it = &m->build->springs[i];
        if ((st = gd_build_component_name(m, err, "spring", i, s->loc, it->path)) ||
            (st = resolve_pair(m, err, "spring", s->loc, it, &s->node1, &s->node2)))
            return st;
    }
    return GD_OK;
}
