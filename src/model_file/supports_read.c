/* Reading `disks:`, `bearings:`, `springs:` and `unbalances:` into builder specs. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/model_file_impl.h"

/* ---- disks ---- */

static const char *const DISK_KEYS[] = {
    "name", "node", "mass", "polar_inertia", "diametral_inertia", "geometry", NULL};
static const char *const DISK_GEOM_KEYS[] = {"outer_diameter", "inner_diameter", "width",
                                             "material", NULL};

static gd_status read_disk(gd_mparser *p, const gd_ynode *dm, const char *q, size_t i)
{
    gd_status st;
    char fb[32], gp[120], name[GD_NAME_MAX];
    gd_disk_spec d;
    gd_disk_spec_init(&d);
    if ((st = gd_yexpect(&p->r, dm, GD_Y_MAP, q)) || (st = gd_ycheck_keys(&p->r, dm, q, DISK_KEYS)))
        return st;
    snprintf(fb, sizeof fb, "disk%zu", i + 1);
    if ((st = gd_mp_read_name(p, dm, q, name, fb, 0)) ||
        (st = gd_mp_node_name(p, dm, "node", q, 1, &d.node)))
        return st;
    d.name = name;
    d.loc = gd_mp_loc(dm);
    d.path = q;
    const gd_ynode *geom = gd_ymap_get(dm, "geometry");
    if (geom) {
        gd_ypath_key(gp, sizeof gp, q, "geometry");
        if (gd_ymap_get(dm, "mass") || gd_ymap_get(dm, "polar_inertia"))
            return gd_yfail(&p->r, dm, q, "give either geometry or mass and inertias",
                            "disk has both geometry and mass/inertia");
        char mp[160];
        if ((st = gd_yexpect(&p->r, geom, GD_Y_MAP, gp)) ||
            (st = gd_ycheck_keys(&p->r, geom, gp, DISK_GEOM_KEYS)) ||
            (st = gd_yread_qty(&p->r, geom, "outer_diameter", gp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                               &d.outer_diameter, NULL)) ||
            (st = gd_yread_qty(&p->r, geom, "inner_diameter", gp, GD_QTY_LENGTH, GD_YNONNEG,
                               &d.inner_diameter, NULL)) ||
            (st = gd_yread_qty(&p->r, geom, "width", gp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &d.width,
                               NULL)) ||
            (st = gd_mp_material_name(p, gd_ymap_get(geom, "material"),
                                      gd_ypath_key(mp, sizeof mp, gp, "material"), &d.material)))
            return st;
        d.from_geometry = 1;
    } else if ((st = gd_yread_qty(&p->r, dm, "mass", q, GD_QTY_MASS, GD_YPOS, &d.mass, NULL)) ||
               (st = gd_yread_qty(&p->r, dm, "polar_inertia", q, GD_QTY_INERTIA, GD_YNONNEG,
                                  &d.polar_inertia, NULL)) ||
               (st = gd_yread_qty(&p->r, dm, "diametral_inertia", q, GD_QTY_INERTIA, GD_YNONNEG,
                                  &d.diametral_inertia, NULL))) {
        return st;
    }
    return gd_model_add_disk(p->m, &d, NULL, p->r.err);
}

gd_status gd_mp_disks(gd_mparser *p)
{
    return gd_mp_each(p, "disks", read_disk);
}

/* ---- bearings ---- */

static const char *const BEARING_KEYS[] = {
    "name", "node",   "to",        "k",         "c",   "kxx", "kxy", "kyx",
    "kyy",  "kzz",    "k_tilt",    "k_torsion", "cxx", "cxy", "cyx", "cyy",
    "czz",  "c_tilt", "c_torsion", "table",     "sfd", NULL};
static const char *const TABLE_ROW_KEYS[] = {
    "speed",     "k",   "c",   "kxx", "kxy", "kyx", "kyy",    "kzz",       "k_tilt",
    "k_torsion", "cxx", "cxy", "cyx", "cyy", "czz", "c_tilt", "c_torsion", NULL};

static gd_status read_coeffs(gd_mparser *p, const gd_ynode *map, const char *path,
                             gd_bearing_coeffs *c, int *any)
{
    gd_status st;
    double k = 0, cc = 0;
    int has_k = 0, has_c = 0, h;
    if ((st = gd_yread_qty(&p->r, map, "k", path, GD_QTY_STIFFNESS, GD_YNONNEG, &k, &has_k)) ||
        (st = gd_yread_qty(&p->r, map, "c", path, GD_QTY_DAMPING, GD_YNONNEG, &cc, &has_c)))
        return st;
    if (has_k) c->kxx = c->kyy = k;
    if (has_c) c->cxx = c->cyy = cc;
    *any = has_k || has_c;
    struct {
        const char *key;
        double *v;
        gd_qty q;
        int flags;
        const char *iso; /* the isotropic key that conflicts */
    } f[] = {
        {"kxx", &c->kxx, GD_QTY_STIFFNESS, GD_YNONNEG, "k"},
        {"kyy", &c->kyy, GD_QTY_STIFFNESS, GD_YNONNEG, "k"},
        {"kxy", &c->kxy, GD_QTY_STIFFNESS, 0, NULL},
        {"kyx", &c->kyx, GD_QTY_STIFFNESS, 0, NULL},
        {"kzz", &c->kzz, GD_QTY_STIFFNESS, GD_YNONNEG, NULL},
        {"k_tilt", &c->ktilt, GD_QTY_ROT_STIFFNESS, GD_YNONNEG, NULL},
        {"k_torsion", &c->ktorsion, GD_QTY_ROT_STIFFNESS, GD_YNONNEG, NULL},
        {"cxx", &c->cxx, GD_QTY_DAMPING, GD_YNONNEG, "c"},
        {"cyy", &c->cyy, GD_QTY_DAMPING, GD_YNONNEG, "c"},
        {"cxy", &c->cxy, GD_QTY_DAMPING, 0, NULL},
        {"cyx", &c->cyx, GD_QTY_DAMPING, 0, NULL},
        {"czz", &c->czz, GD_QTY_DAMPING, GD_YNONNEG, NULL},
        {"c_tilt", &c->ctilt, GD_QTY_ROT_DAMPING, GD_YNONNEG, NULL},
        {"c_torsion", &c->ctorsion, GD_QTY_ROT_DAMPING, GD_YNONNEG, NULL},
    };
    for (size_t i = 0; i < sizeof f / sizeof f[0]; i++) {
        if (f[i].iso && gd_ymap_get(map, f[i].key) && gd_ymap_get(map, f[i].iso)) {
            char q[200];
            return gd_yfail(&p->r, gd_ymap_get(map, f[i].key),
                            gd_ypath_key(q, sizeof q, path, f[i].key),
                            "use the isotropic shorthand or the individual terms, not both",
                            "'%s' given together with '%s'", f[i].key, f[i].iso);
        }
        if ((st = gd_yread_qty(&p->r, map, f[i].key, path, f[i].q, f[i].flags, f[i].v, &h)))
            return st;
        *any |= h;
    }
    return GD_OK;
}

/* The speed table's rows into speeds and coeffs (allocated by the caller). */
static gd_status read_table_rows(gd_mparser *p, const gd_ynode *table, const char *tp,
                                 double *speed, gd_bearing_coeffs *rows)
{
    gd_status st;
    for (size_t j = 0; j < table->n; j++) {
        char rp[120];
        gd_ypath_index(rp, sizeof rp, tp, j);
        const gd_ynode *row = table->items[j];
        int rany = 0;
        if ((st = gd_yexpect(&p->r, row, GD_Y_MAP, rp)) ||
            (st = gd_ycheck_keys(&p->r, row, rp, TABLE_ROW_KEYS)) ||
            (st = gd_yread_qty(&p->r, row, "speed", rp, GD_QTY_ANGULAR_SPEED, GD_YREQ | GD_YNONNEG,
                               &speed[j], NULL)) ||
            (st = read_coeffs(p, row, rp, &rows[j], &rany)))
            return st;
    }
    return GD_OK;
}

static gd_status read_bearing(gd_mparser *p, const gd_ynode *bm, const char *q, size_t i)
{
    gd_status st;
    char fb[32], name[GD_NAME_MAX], tp[100];
    gd_bearing_spec b;
    gd_bearing_spec_init(&b);
    if ((st = gd_yexpect(&p->r, bm, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, bm, q, BEARING_KEYS)))
        return st;
    snprintf(fb, sizeof fb, "bearing%zu", i + 1);
    if ((st = gd_mp_read_name(p, bm, q, name, fb, 0)) ||
        (st = gd_mp_node_name(p, bm, "node", q, 1, &b.node)) ||
        (st = gd_mp_node_name(p, bm, "to", q, 0, &b.to)))
        return st;
    b.name = name;
    b.loc = gd_mp_loc(bm);
    b.path = q;
    int any = 0;
    if ((st = read_coeffs(p, bm, q, &b.coeffs, &any))) return st;
    const gd_ynode *table = gd_ymap_get(bm, "table");
    double *speed = NULL;
    gd_bearing_coeffs *rows = NULL;
    if (table) {
        gd_ypath_key(tp, sizeof tp, q, "table");
        if ((st = gd_yexpect(&p->r, table, GD_Y_SEQ, tp))) return st;
        if (any)
            return gd_yfail(&p->r, table, tp, "put every coefficient in the table rows",
                            "constant coefficients given together with a speed table");
        speed = calloc(table->n + 1, sizeof *speed);
        rows = calloc(table->n + 1, sizeof *rows);
        if (!speed || !rows) {
            free(speed);
            free(rows);
            return gd_mp_oom(p);
        }
        b.ntable = (int)table->n;
        b.table_speed = speed;
        b.table = rows;
        /* a table of fewer than two rows is the builder's to report */
        if (!b.ntable) b.ntable = 1;
        st = read_table_rows(p, table, tp, speed, rows);
    }
    if (!st) st = gd_mp_bearing_sfd(p, bm, q, &b);
    if (!st) st = gd_model_add_bearing(p->m, &b, NULL, p->r.err);
    free(speed);
    free(rows);
    return st;
}

gd_status gd_mp_bearings(gd_mparser *p)
{
    return gd_mp_each(p, "bearings", read_bearing);
}

/* ---- springs ---- */

static const char *const DOF_CHOICES[] = {"x", "y", "z", "rx", "ry", "rz", NULL};
static const char *const SPRING_KEYS[] = {"name",      "node",    "to", "dof",
                                          "stiffness", "damping", NULL};

static gd_status read_spring(gd_mparser *p, const gd_ynode *sm, const char *q, size_t i)
{
    gd_status st;
    char fb[32], name[GD_NAME_MAX];
    gd_spring_spec s;
    gd_spring_spec_init(&s);
    if ((st = gd_yexpect(&p->r, sm, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, sm, q, SPRING_KEYS)))
        return st;
    snprintf(fb, sizeof fb, "spring%zu", i + 1);
    int dof = 0;
    if ((st = gd_mp_read_name(p, sm, q, name, fb, 0)) ||
        (st = gd_mp_node_name(p, sm, "node", q, 1, &s.node)) ||
        (st = gd_mp_node_name(p, sm, "to", q, 0, &s.to)) ||
        (st = gd_yread_str(&p->r, sm, "dof", q, DOF_CHOICES, GD_YREQ, NULL, &dof, NULL)))
        return st;
    s.name = name;
    s.loc = gd_mp_loc(sm);
    s.path = q;
    s.dof = (gd_dof)dof;
    gd_qty kq = dof >= GD_RX ? GD_QTY_ROT_STIFFNESS : GD_QTY_STIFFNESS;
    gd_qty cq = dof >= GD_RX ? GD_QTY_ROT_DAMPING : GD_QTY_DAMPING;
    if ((st = gd_yread_qty(&p->r, sm, "stiffness", q, kq, GD_YNONNEG, &s.stiffness, NULL)) ||
        (st = gd_yread_qty(&p->r, sm, "damping", q, cq, GD_YNONNEG, &s.damping, NULL)))
        return st;
    return gd_model_add_spring(p->m, &s, NULL, p->r.err);
}

gd_status gd_mp_springs(gd_mparser *p)
{
    return gd_mp_each(p, "springs", read_spring);
}

/* ---- unbalances ---- */

static const char *const UNBALANCE_KEYS[] = {"name",         "node",  "amount", "mass",
                                             "eccentricity", "phase", NULL};

static gd_status read_unbalance(gd_mparser *p, const gd_ynode *um, const char *q, size_t i)
{
    gd_status st;
    char fb[32], name[GD_NAME_MAX];
    gd_unbalance_spec u;
    gd_unbalance_spec_init(&u);
    if ((st = gd_yexpect(&p->r, um, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, um, q, UNBALANCE_KEYS)))
        return st;
    snprintf(fb, sizeof fb, "unbalance%zu", i + 1);
    double mass = 0, ecc = 0;
    int has_amount = 0, has_mass = 0, has_ecc = 0;
    if ((st = gd_mp_read_name(p, um, q, name, fb, 0)) ||
        (st = gd_mp_node_name(p, um, "node", q, 1, &u.node)) ||
        (st = gd_yread_qty(&p->r, um, "amount", q, GD_QTY_MASS_LENGTH, GD_YPOS, &u.amount,
                           &has_amount)) ||
        (st = gd_yread_qty(&p->r, um, "mass", q, GD_QTY_MASS, GD_YPOS, &mass, &has_mass)) ||
        (st = gd_yread_qty(&p->r, um, "eccentricity", q, GD_QTY_LENGTH, GD_YPOS, &ecc, &has_ecc)) ||
        (st = gd_yread_qty(&p->r, um, "phase", q, GD_QTY_ANGLE, 0, &u.phase, NULL)))
        return st;
    if (has_amount == (has_mass || has_ecc) || has_mass != has_ecc)
        return gd_yfail(&p->r, um, q, "give `amount` (kg*m), or both `mass` and `eccentricity`",
                        has_amount ? "amount given together with mass/eccentricity"
                                   : "unbalance amount missing");
    if (!has_amount) u.amount = mass * ecc;
    u.name = name;
    u.loc = gd_mp_loc(um);
    u.path = q;
    return gd_model_add_unbalance(p->m, &u, NULL, p->r.err);
}

gd_status gd_mp_unbalances(gd_mparser *p)
{
    return gd_mp_each(p, "unbalances", read_unbalance);
}
