/* Reading a model file into a validated gd_model (docs/model-format.md): the reader's
 * machinery, the top level and the globals. The document's sections are read into
 * builder specs by shafts_read.c, supports_read.c, meshes_read.c and
 * model_parse_dynamics.c with the reader's shared helpers (model_parse_support.c);
 * gd_model_finish completes the model. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/builder.h"
#include "model/build_impl.h"
#include "model_file/mesh_geometry_read_impl.h"
#include "model_file/model_file_impl.h"
#include "model_file/yaml_doc_impl.h"

static const char *const TOP_KEYS[] = {
    "title",           "description", "materials",     "dofs",        "shafts",
    "disks",           "bearings",    "springs",       "meshes",      "speed",
    "reference_shaft", "rotation",    "unbalances",    "excitations", "prescribed",
    "cam_torques",     "limits",      "damping",       "gravity",     "laws",
    "planetary_sets",  "idlers",      "synchronisers", "gears",       "gear",
    "shift",           NULL};
static const char *const GRAVITY_KEYS[] = {"direction", "g", NULL};
static const char *const LIMIT_KEYS[] = {"max_nodes", NULL};
static const char *const DAMPING_KEYS[] = {"rayleigh", NULL};
static const char *const RAYLEIGH_KEYS[] = {"alpha", "beta", "ratios", "frequencies", NULL};
static const char *const ROTATIONS[] = {"ccw", "cw", NULL};

/* ---- where the builder's fields are in the document ---- */

const gd_ynode *gd_mp_find(const gd_ynode *root, const char *field)
{
    const gd_ynode *n = root;
    const char *s = field;
    while (n && *s) {
        if (*s == '[') {
            char *end;
            long i = strtol(s + 1, &end, 10);
            if (*end != ']' || n->kind != GD_Y_SEQ || i < 0 || (size_t)i >= n->n) return NULL;
            n = n->items[i];
            s = end + 1;
        } else {
            if (*s == '.') s++;
            size_t len = strcspn(s, ".[");
            char key[160];
            if (!len || len >= sizeof key || n->kind != GD_Y_MAP) return NULL;
            memcpy(key, s, len);
            key[len] = '\0';
            n = gd_ymap_get(n, key);
            s += len;
        }
    }
    return n;
}

static int locate(void *ctx, const char *field, gd_error *err)
{
    gd_mparser *p = ctx;
    const gd_ynode *n = gd_mp_find(p->root, field);
    if (!n) return 0;
    gd_ylocate(err, p->r.file, n);
    return 1;
}

static int locate_geometry(void *ctx, const char *mesh_path, gd_error *err)
{
    gd_mparser *p = ctx;
    const gd_ynode *mm = gd_mp_find(p->root, mesh_path);
    if (!mm) return 0;
    gd_gear_pair_error_locate(p->r.file, mm, mesh_path, err);
    return 1;
}

/* ---- top level ---- */

/* A list of exactly two quantities at map.key. */
static gd_status read_two(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                          gd_qty qty, int flags, double out[2])
{
    char q[200], ip[220];
    const gd_ynode *v = gd_ymap_get(map, key);
    gd_ypath_key(q, sizeof q, path, key);
    gd_status st = gd_yexpect(&p->r, v, GD_Y_SEQ, q);
    if (st) return st;
    if (v->n != 2)
        return gd_yfail(&p->r, v, q, "give two values, e.g. [0.02, 0.05]",
                        "expected 2 values, found %zu", v->n);
    for (size_t i = 0; i < 2; i++)
        if ((st = gd_yread_node_qty(&p->r, v->items[i], gd_ypath_index(ip, sizeof ip, q, i), qty,
                                    flags, &out[i])))
            return st;
    return GD_OK;
}

/* damping: {rayleigh: {alpha, beta} | {ratios: [z1, z2], frequencies: [w1, w2]}} */
static gd_status parse_damping(gd_mparser *p)
{
    gd_yreader *r = &p->r;
    const gd_ynode *dm = gd_ymap_get(p->root, "damping");
    if (!dm) return GD_OK;
    const char *rp = "damping.rayleigh";
    gd_status st;
    if ((st = gd_yexpect(r, dm, GD_Y_MAP, "damping")) ||
        (st = gd_ycheck_keys(r, dm, "damping", DAMPING_KEYS)))
        return st;
    const gd_ynode *rm = gd_ymap_get(dm, "rayleigh");
    if (!rm) return GD_OK;
    if ((st = gd_yexpect(r, rm, GD_Y_MAP, rp)) || (st = gd_ycheck_keys(r, rm, rp, RAYLEIGH_KEYS)))
        return st;
    double alpha = 0, beta = 0;
    int has_a = 0, has_b = 0, by_ratios = gd_ymap_get(rm, "ratios") != NULL;
    if ((st = gd_yread_qty(r, rm, "alpha", rp, GD_QTY_ANGULAR_SPEED, GD_YNONNEG, &alpha, &has_a)) ||
        (st = gd_yread_qty(r, rm, "beta", rp, GD_QTY_TIME, GD_YNONNEG, &beta, &has_b)))
        return st;
    if (by_ratios == (has_a || has_b))
        return gd_yfail(r, rm, rp,
                        "give `alpha:` and `beta:`, or `ratios: [z1, z2]` with "
                        "`frequencies: [w1, w2]`",
                        by_ratios ? "both alpha/beta and ratios given"
                                  : "neither alpha/beta nor ratios given");
    if (by_ratios) {
        double z[2], w[2];
        if ((st = read_two(p, rm, "ratios", rp, GD_QTY_DIMLESS, GD_YNONNEG, z)) ||
            (st = read_two(p, rm, "frequencies", rp, GD_QTY_ANGULAR_SPEED, GD_YPOS, w)))
            return st;
        if ((st = gd_rayleigh_from_ratios(z[0], z[1], w[0], w[1], &alpha, &beta, r->err))) {
            gd_ylocate(r->err, r->file, gd_ymap_get(rm, w[0] == w[1] ? "frequencies" : "ratios"));
            return st;
        }
    }
    if ((st = gd_model_set_rayleigh(p->m, alpha, beta, r->err))) gd_ylocate(r->err, r->file, rm);
    return st;
}

/* gravity: {direction: [x, y, z], g: 9.81}: g in m/s^2, default standard gravity */
static gd_status parse_gravity(gd_mparser *p)
{
    gd_yreader *r = &p->r;
    const gd_ynode *gm = gd_ymap_get(p->root, "gravity");
    if (!gm) return GD_OK;
    gd_status st;
    if ((st = gd_yexpect(r, gm, GD_Y_MAP, "gravity")) ||
        (st = gd_ycheck_keys(r, gm, "gravity", GRAVITY_KEYS)))
        return st;
    const gd_ynode *dn = gd_ymap_get(gm, "direction");
    if (!dn)
        return gd_yfail(r, gm, "gravity.direction", "add `direction: [0, -1, 0]` (model axes)",
                        "gravity without a direction");
    if (dn->kind != GD_Y_SEQ || dn->n != 3)
        return gd_yfail(r, dn, "gravity.direction", "write three numbers, e.g. [0, -1, 0]",
                        "expected a list of three values");
    double dir[3], g = 9.80665;
    for (size_t i = 0; i < 3; i++) {
        char ip[64];
        if ((st = gd_yread_node_qty(r, dn->items[i],
                                    gd_ypath_index(ip, sizeof ip, "gravity.direction", i),
                                    GD_QTY_DIMLESS, 0, &dir[i])))
            return st;
    }
    if ((st = gd_yread_qty(r, gm, "g", "gravity", GD_QTY_DIMLESS, GD_YNONNEG, &g, NULL))) return st;
    if ((st = gd_model_set_gravity(p->m, dir, g, gd_mp_loc(gm), r->err)))
        gd_ylocate(r->err, r->file, dn);
    return st;
}

static gd_status parse_globals(gd_mparser *p)
{
    gd_yreader *r = &p->r;
    gd_model *m = p->m;
    gd_status st;
    const gd_ynode *dofs = gd_ymap_get(p->root, "dofs");
    if (dofs) {
        if ((st = gd_yexpect(r, dofs, GD_Y_SEQ, "dofs"))) return st;
        unsigned mask = 0;
        for (size_t i = 0; i < dofs->n; i++) {
            const gd_ynode *d = dofs->items[i];
            char q[64];
            gd_ypath_index(q, sizeof q, "dofs", i);
            int found = -1;
            if (d->kind == GD_Y_SCALAR)
                for (int k = 0; k < GD_NODE_DOFS; k++)
                    if (!strcmp(d->text, gd_dof_names[k])) found = k;
            if (found < 0)
                return gd_yfail(r, d, q, "use names from: x, y, z, rx, ry, rz", "unknown DOF '%s'",
                                d->kind == GD_Y_SCALAR ? d->text : "?");
            mask |= GD_DOF_BIT(found);
        }
        if (!mask) return gd_yfail(r, dofs, "dofs", "list at least one DOF, e.g. [rz]", "no DOFs");
        if ((st = gd_model_set_dofs(m, mask, r->err))) return st;
    }
    const gd_ynode *limits = gd_ymap_get(p->root, "limits");
    if (limits) {
        long max_nodes = 0;
        int has = 0;
        if ((st = gd_yexpect(r, limits, GD_Y_MAP, "limits")) ||
            (st = gd_ycheck_keys(r, limits, "limits", LIMIT_KEYS)) ||
            (st =
                 gd_yread_int(r, limits, "max_nodes", "limits", 1, 100000000, 0, &max_nodes, &has)))
            return st;
        if (has && (st = gd_model_set_max_nodes(
                        m, max_nodes, gd_mp_loc(gd_ymap_get(limits, "max_nodes")), r->err)))
            return st;
    }
    double speed = 0;
    if ((st = gd_yread_qty(r, p->root, "speed", "", GD_QTY_ANGULAR_SPEED, GD_YNONNEG, &speed,
                           NULL)) ||
        (st = gd_model_set_speed(m, speed, r->err)))
        return st;
    const char *ref = NULL;
    int rot = 0;
    if ((st = gd_yread_str(r, p->root, "reference_shaft", "", NULL, 0, &ref, NULL, NULL)) ||
        (st = gd_yread_str(r, p->root, "rotation", "", ROTATIONS, 0, NULL, &rot, NULL)))
        return st;
    return gd_model_set_reference_shaft(m, ref, rot == 0 ? 1 : -1,
                                        gd_mp_loc(gd_ymap_get(p->root, "reference_shaft")), r->err);
}

static gd_status parse(gd_mparser *p)
{
    gd_status st;
    const gd_ynode *rt = p->root;
    if (!rt || (rt->kind == GD_Y_SCALAR && !rt->quoted &&
                (!rt->text[0] || !strcmp(rt->text, "~") || !strcmp(rt->text, "null"))))
        return gd_error_set(p->r.err, GD_EINPUT, p->r.file, rt ? rt->line : 1, 1, "",
                            "see docs/model-format.md for a complete example",
                            "the file is empty: no model in it");
    if ((st = gd_yexpect(&p->r, p->root, GD_Y_MAP, "")) ||
        (st = gd_ycheck_keys(&p->r, p->root, "", TOP_KEYS)))
        return st;
    const char *s;
    if ((st = gd_yread_str(&p->r, p->root, "title", "", NULL, 0, &s, NULL, NULL)) ||
        (st = gd_yread_str(&p->r, p->root, "description", "", NULL, 0, &s, NULL, NULL)) ||
        (st = gd_mp_materials(p)) || (st = gd_mp_shafts(p)) || (st = parse_globals(p)) ||
        (st = parse_damping(p)) || (st = parse_gravity(p)) || (st = gd_mp_disks(p)) ||
        (st = gd_mp_bearings(p)) || (st = gd_mp_springs(p)) || (st = gd_mp_meshes(p)) ||
        (st = gd_mp_planetary(p)) || (st = gd_mp_idlers(p)) || (st = gd_mp_unbalances(p)) ||
        (st = gd_mp_dynamics(p)) || (st = gd_mp_laws(p)))
        return st;
    return gd_model_finish(p->m, p->r.err);
}

gd_status gd_model_from_ydoc(const gd_ydoc *doc, const char *name, gd_model **out, gd_error *err)
{
    *out = NULL;
    gd_mparser p = {{name, err}, doc->root, NULL};
    gd_status st = gd_model_new(name, &p.m, err);
    if (st) return st;
    gd_field_locator loc = {locate, locate_geometry, &p};
    gd_model_set_locator(p.m, &loc);
    st = parse(&p);
    if (st) {
        gd_model_free(p.m);
        return st;
    }
    *out = p.m;
    return GD_OK;
}

gd_status gd_model_load(const char *path, gd_model **out, gd_error *err)
{
    *out = NULL;
    gd_ydoc *doc;
    gd_status st = gd_ydoc_load_file(path, &doc, err);
    if (st) return st;
    st = gd_model_from_ydoc(doc, path, out, err);
    gd_ydoc_free(doc);
    return st;
}

gd_status gd_model_load_string(const char *yaml, const char *name, gd_model **out, gd_error *err)
{
    *out = NULL;
    gd_ydoc *doc;
    gd_status st = gd_ydoc_load_string(yaml, name, &doc, err);
    if (st) return st;
    st = gd_model_from_ydoc(doc, name, out, err);
    gd_ydoc_free(doc);
    return st;
}
