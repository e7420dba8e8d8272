/* A bearing table file (geardyn/bearing_table.h): one entry of `bearings:` read into a
 * gd_bearing_geometry, every value with its units, every error located at its key. */
#include <stdio.h>
#include <string.h>

#include "geardyn/bearing_table.h"
#include "model_file/yaml_doc_impl.h"

static const char *const KEYS[] = {"name",
                                   "type",
                                   "elements",
                                   "element_diameter",
                                   "pitch_diameter",
                                   "contact_angle",
                                   "clearance",
                                   "roller_length",
                                   "inner_curvature",
                                   "outer_curvature",
                                   "modulus",
                                   "poisson",
                                   "contact_stiffness",
                                   "phase",
                                   NULL};

static gd_status read_entry(gd_yreader *r, const gd_ynode *e, const char *path,
                            gd_bearing_geometry *g)
{
    gd_status st;
    if ((st = gd_yexpect(r, e, GD_Y_MAP, path)) || (st = gd_ycheck_keys(r, e, path, KEYS)))
        return st;
    gd_bearing_geometry_init(g);
    static const char *const TYPES[] = {"ball", "roller", NULL};
    int type = 0;
    long z = 0;
    if ((st = gd_yread_str(r, e, "type", path, TYPES, GD_YREQ, NULL, &type, NULL)) ||
        (st = gd_yread_int(r, e, "elements", path, 3, 1000, GD_YREQ, &z, NULL)) ||
        (st = gd_yread_qty(r, e, "element_diameter", path, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                           &g->element_diameter, NULL)) ||
        (st = gd_yread_qty(r, e, "pitch_diameter", path, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                           &g->pitch_diameter, NULL)) ||
        (st = gd_yread_qty(r, e, "contact_angle", path, GD_QTY_ANGLE, GD_YNONNEG, &g->contact_angle,
                           NULL)) ||
        (st = gd_yread_qty(r, e, "clearance", path, GD_QTY_LENGTH, 0, &g->clearance, NULL)) ||
        (st = gd_yread_qty(r, e, "roller_length", path, GD_QTY_LENGTH, GD_YPOS, &g->roller_length,
                           NULL)) ||
        (st = gd_yread_qty(r, e, "inner_curvature", path, GD_QTY_DIMLESS, GD_YPOS,
                           &g->inner_curvature, NULL)) ||
        (st = gd_yread_qty(r, e, "outer_curvature", path, GD_QTY_DIMLESS, GD_YPOS,
                           &g->outer_curvature, NULL)) ||
        (st = gd_yread_qty(r, e, "modulus", path, GD_QTY_PRESSURE, GD_YPOS, &g->modulus, NULL)) ||
        (st = gd_yread_qty(r, e, "poisson", path, GD_QTY_DIMLESS, GD_YNONNEG, &g->poisson, NULL)) ||
        (st = gd_yread_qty(r, e, "contact_stiffness", path, GD_QTY_DIMLESS, GD_YNONNEG,
                           &g->contact_stiffness, NULL)) ||
        (st = gd_yread_qty(r, e, "phase", path, GD_QTY_ANGLE, 0, &g->phase, NULL)))
        return st;
    g->kind = type ? GD_BEARING_ROLLER : GD_BEARING_BALL;
    g->elements = (int)z;
    if ((st = gd_bearing_geometry_check(g, r->err))) {
        /* locate the geometry's complaint at its key (or the entry) */
        char key[sizeof r->err->field];
        memcpy(key, r->err->field, sizeof key);
        const gd_ynode *at = gd_ymap_get(e, key);
        gd_ypath_key(r->err->field, sizeof r->err->field, path, key);
        snprintf(r->err->file, sizeof r->err->file, "%s", r->file);
        gd_ylocate(r->err, r->file, at ? at : e);
    }
    return st;
}

gd_status gd_bearing_table_load(const char *path, const char *name, gd_bearing_geometry *g,
                                char *name_out, size_t size, gd_error *err)
{
    if (name_out && size) name_out[0] = '\0';
    gd_ydoc *doc;
    gd_status st = gd_ydoc_load_file(path, &doc, err);
    if (st) return st;
    gd_yreader r = {doc->file, err};
    const gd_ynode *root = doc->root, *list = root ? gd_ymap_get(root, "bearings") : NULL;
    if (!root || root->kind != GD_Y_MAP || !list || list->kind != GD_Y_SEQ || list->n == 0) {
        st = gd_yfail(&r, list ? list : root, "bearings",
                      "write `bearings: [{name: ..., type: ball, elements: ..., ...}]` "
                      "(docs/bearings.md)",
                      "the file has no list of bearings");
        goto out;
    }
    char names[256] = "", p[64];
    for (size_t i = 0; i < list->n; i++) {
        const gd_ynode *e = list->items[i];
        const gd_ynode *nm = e && e->kind == GD_Y_MAP ? gd_ymap_get(e, "name") : NULL;
        const char *n = nm && nm->kind == GD_Y_SCALAR ? nm->text : "";
        size_t used = strlen(names);
        snprintf(names + used, sizeof names - used, "%s'%s'", used ? ", " : "", n);
        if (name && strcmp(name, n)) continue;
        gd_ypath_index(p, sizeof p, "bearings", i);
        st = read_entry(&r, e, p, g);
        if (!st && name_out && size) snprintf(name_out, size, "%s", n[0] ? n : p);
        goto out;
    }
    {
        char hint[320];
        snprintf(hint, sizeof hint, "known bearings: %s", names);
        st = gd_yfail(&r, list, "--bearing", hint, "no bearing named '%s'", name ? name : "");
    }
out:
    gd_ydoc_free(doc);
    return st;
}
