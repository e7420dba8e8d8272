/* Reading `meshes:` into builder specs: the gear pair, its size (radii, module and
 * teeth, or `geometry:`), angles, stiffness and damping, and the time-integration
 * keys (model_parse_dynamics.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/mesh_stiffness.h"
#include "model_file/mesh_geometry_read_impl.h"
#include "model_file/model_file_impl.h"

static const char *const MESH_KEYS[] = {"name",
                                        "driver",
                                        "driven",
                                        "teeth",
                                        "base_radius",
                                        "pitch_radius",
                                        "module",
                                        "pressure_angle",
                                        "helix_angle",
                                        "hand",
                                        "line_of_centres",
                                        "driver_rotation",
                                        "stiffness",
                                        "damping",
                                        "face_width",
                                        "coupling",
                                        "geometry",
                                        "tvms",
                                        "transmission_error",
                                        "backlash",
                                        NULL};
static const char *const HANDS[] = {"right", "left", NULL};
static const char *const ROTATIONS[] = {"ccw", "cw", NULL};
static const char *const COUPLINGS[] = {"torsional", "lateral-torsional", "full", NULL};

/* Reads a two-element list [driver, driven] of quantities. */
static gd_status read_pair(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                           gd_qty qty, double out[2], int *present)
{
    const gd_ynode *v = gd_ymap_get(map, key);
    *present = v != NULL;
    if (!v) return GD_OK;
    char q[200];
    gd_ypath_key(q, sizeof q, path, key);
    if (v->kind != GD_Y_SEQ || v->n != 2)
        return gd_yfail(&p->r, v, q, "write [driver, driven], e.g. [48, 32]",
                        "expected a list of two values");
    for (int i = 0; i < 2; i++) {
        char ip[220];
        gd_status st = gd_yread_node_qty(
            &p->r, v->items[i], gd_ypath_index(ip, sizeof ip, q, (size_t)i), qty, GD_YPOS, &out[i]);
        if (st) return st;
    }
    return GD_OK;
}

/* The mesh's keys other than the time-integration ones; geom and the options are
 * filled when the mesh has `geometry:`. */
static gd_status read_mesh_keys(gd_mparser *p, const gd_ynode *mm, const char *q, gd_mesh_spec *g,
                                gd_gear_pair_geometry *geom)
{
    gd_yreader *r = &p->r;
    gd_status st;
    char fp[200];
    double teeth[2] = {0, 0};
    int has_teeth, has_rb, has_rp, has_pa, has_helix;
    if ((st = gd_mp_node_name(p, mm, "driver", q, 1, &g->driver)) ||
        (st = gd_mp_node_name(p, mm, "driven", q, 1, &g->driven)) ||
        (st = read_pair(p, mm, "teeth", q, GD_QTY_DIMLESS, teeth, &has_teeth)) ||
        (st = read_pair(p, mm, "base_radius", q, GD_QTY_LENGTH, g->base_radius, &has_rb)) ||
        (st = read_pair(p, mm, "pitch_radius", q, GD_QTY_LENGTH, g->pitch_radius, &has_rp)) ||
        (st = gd_yread_qty(r, mm, "module", q, GD_QTY_LENGTH, GD_YPOS, &g->module, NULL)) ||
        (st = gd_yread_qty(r, mm, "pressure_angle", q, GD_QTY_ANGLE, GD_YNONNEG, &g->pressure_angle,
                           &has_pa)) ||
        (st = gd_yread_qty(r, mm, "helix_angle", q, GD_QTY_ANGLE, GD_YNONNEG, &g->helix_angle,
                           &has_helix)) ||
        (st = gd_yread_qty(r, mm, "face_width", q, GD_QTY_LENGTH, GD_YNONNEG, &g->face_width,
                           NULL)) ||
        (st =
             gd_yread_qty(r, mm, "line_of_centres", q, GD_QTY_ANGLE, 0, &g->line_of_centres, NULL)))
        return st;
    if (has_teeth)
        for (int i = 0; i < 2; i++) {
            /* range-checked before the conversion to int (a double beyond INT_MAX
               would be undefined behaviour); 100000 as for `geometry.teeth` */
            if (!(teeth[i] >= 3 && teeth[i] <= 100000) || teeth[i] != floor(teeth[i]))
                return gd_yfail(r, gd_ymap_get(mm, "teeth"),
                                gd_ypath_key(fp, sizeof fp, q, "teeth"),
                                "teeth numbers are whole numbers from 3 to 100000",
                                "invalid teeth number %g", teeth[i]);
            g->teeth[i] = (int)teeth[i];
        }
    if (gd_ymap_get(mm, "geometry")) {
        /* the geometry is validated here, located in the file, and again by the builder */
        if ((st = gd_gear_pair_read(r, p->root, mm, q, geom, &g->tvms_options))) return st;
        g->geometry = geom;
        const char *dup = has_teeth   ? NULL
                          : has_pa    ? "pressure_angle"
                          : has_helix ? "helix_angle"
                                      : NULL;
        if (dup)
            return gd_yfail(r, gd_ymap_get(mm, dup), gd_ypath_key(fp, sizeof fp, q, dup),
                            "with `geometry:` the teeth and angles come from it; remove this key",
                            "'%s' given together with `geometry:`", dup);
    }
    int hand = 0, coupling = GD_COUPLING_FULL, rot = 0, has_rot = 0;
    if ((st = gd_yread_str(r, mm, "hand", q, HANDS, 0, NULL, &hand, NULL)) ||
        (st = gd_yread_str(r, mm, "coupling", q, COUPLINGS, 0, NULL, &coupling, NULL)) ||
        (st = gd_yread_str(r, mm, "driver_rotation", q, ROTATIONS, 0, NULL, &rot, &has_rot)))
        return st;
    g->hand = hand == 0 ? 1 : -1;
    g->coupling = (gd_coupling)coupling;
    g->driver_rotation = has_rot ? (rot == 0 ? 1 : -1) : 0;
    return GD_OK;
}

static gd_status read_mesh(gd_mparser *p, const gd_ynode *mm, const char *q, size_t index)
{
    (void)index;
    gd_yreader *r = &p->r;
    gd_status st;
    char name[GD_NAME_MAX];
    gd_mesh_spec g;
    gd_gear_pair_geometry geom;
    gd_mesh_spec_init(&g);
    if ((st = gd_yexpect(r, mm, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, mm, q, MESH_KEYS)) ||
        (st = gd_mp_read_name(p, mm, q, name, "", 1)) || (st = read_mesh_keys(p, mm, q, &g, &geom)))
        return st;
    g.name = name;
    g.loc = gd_mp_loc(mm);
    g.path = q;
    const gd_ynode *stiff = gd_ymap_get(mm, "stiffness");
    /* {from: geometry, ...}: the options were read with the geometry (the builder
       reports a missing geometry) */
    if (stiff && stiff->kind == GD_Y_MAP) g.stiffness_from_geometry = 1;
    /* time-integration keys; a tvms table gives the mean stiffness when none is given */
    gd_table *tvms = NULL, *ste = NULL;
    int teeth = g.geometry ? geom.gear[0].teeth : g.teeth[0];
    if (!(st = gd_mp_mesh_dynamics(p, mm, q, teeth, &g, &tvms, &ste)) &&
        !(stiff && stiff->kind == GD_Y_MAP))
        st = gd_yread_qty(r, mm, "stiffness", q, GD_QTY_STIFFNESS, GD_YPOS | (tvms ? 0 : GD_YREQ),
                          &g.stiffness, NULL);
    if (!st) st = gd_model_add_mesh(p->m, &g, NULL, r->err);
    gd_table_free(tvms);
    gd_table_free(ste);
    return st;
}

gd_status gd_mp_meshes(gd_mparser *p)
{
    return gd_mp_each(p, "meshes", read_mesh);
}
