/* Reading `materials:` and `shafts:` (sections and named nodes) into builder specs. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/material_read_impl.h"
#include "model_file/model_file_impl.h"

/* ---- materials ---- */

gd_status gd_mp_materials(gd_mparser *p)
{
    const gd_ynode *mats = gd_ymap_get(p->root, "materials");
    if (!mats) return GD_OK;
    gd_status st = gd_yexpect(&p->r, mats, GD_Y_MAP, "materials");
    if (st) return st;
    for (size_t i = 0; i < mats->n; i++) {
        char q[200];
        snprintf(q, sizeof q, "materials.%s", mats->keys[i]->text);
        if (strlen(mats->keys[i]->text) >= GD_NAME_MAX)
            return gd_yfail(&p->r, mats->keys[i], q, "use a shorter name", "name too long");
        gd_material mat;
        if ((st = gd_material_read(&p->r, mats->items[i], q, mats->keys[i]->text, 1, &mat)))
            return st;
        gd_material_spec s;
        gd_material_spec_init(&s);
        s.name = mat.name;
        s.density = mat.density;
        s.E = mat.E;
        s.G = mat.G;
        s.poisson = mat.poisson;
        s.loc = gd_mp_loc(mats->items[i]);
        s.path = q;
        if ((st = gd_model_add_material(p->m, &s, NULL, p->r.err))) return st;
    }
    return GD_OK;
}

/* ---- shafts ---- */

static const char *const SHAFT_KEYS[] = {
    "name",        "material", "sections", "nodes", "elements_per_section", "max_element_length",
    "speed_ratio", NULL};
static const char *const SECTION_KEYS[] = {"length",   "outer_diameter", "inner_diameter",
                                           "material", "elements",       NULL};
static const char *const NODE_KEYS[] = {"name", "at", NULL};

static gd_status read_sections(gd_mparser *p, const gd_ynode *sections, const char *path,
                               gd_section_spec *out)
{
    gd_yreader *r = &p->r;
    gd_status st;
    char q[200];
    for (size_t i = 0; sections && i < sections->n; i++) {
        char sp[220];
        gd_ypath_index(sp, sizeof sp, gd_ypath_key(q, sizeof q, path, "sections"), i);
        const gd_ynode *s = sections->items[i];
        gd_section_spec *sec = &out[i];
        gd_section_spec_init(sec);
        if ((st = gd_yexpect(r, s, GD_Y_MAP, sp)) || (st = gd_ycheck_keys(r, s, sp, SECTION_KEYS)))
            return st;
        sec->loc = gd_mp_loc(s);
        long ne = 0;
        char mp[240];
        if ((st = gd_yread_qty(r, s, "length", sp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &sec->length,
                               NULL)) ||
            (st = gd_yread_qty(r, s, "outer_diameter", sp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                               &sec->outer_diameter, NULL)) ||
            (st = gd_yread_qty(r, s, "inner_diameter", sp, GD_QTY_LENGTH, GD_YNONNEG,
                               &sec->inner_diameter, NULL)) ||
            (st = gd_mp_material_name(p, gd_ymap_get(s, "material"),
                                      gd_ypath_key(mp, sizeof mp, sp, "material"),
                                      &sec->material)) ||
            (st = gd_yread_int(r, s, "elements", sp, 1, 10000, 0, &ne, NULL)))
            return st;
        sec->elements = (int)ne;
    }
    return GD_OK;
}

static gd_status read_stations(gd_mparser *p, const gd_ynode *nodes, const char *path,
                               int with_sections, gd_station_spec *out)
{
    gd_yreader *r = &p->r;
    gd_status st;
    char q[200];
    for (size_t i = 0; nodes && i < nodes->n; i++) {
        char np[220];
        gd_ypath_index(np, sizeof np, gd_ypath_key(q, sizeof q, path, "nodes"), i);
        const gd_ynode *nm = nodes->items[i];
        gd_station_spec *s = &out[i];
        gd_station_spec_init(s);
        int has_at = 0;
        if ((st = gd_yexpect(r, nm, GD_Y_MAP, np)) || (st = gd_ycheck_keys(r, nm, np, NODE_KEYS)) ||
            (st = gd_yread_str(r, nm, "name", np, NULL, GD_YREQ, &s->name, NULL, NULL)) ||
            (st = gd_yread_qty(r, nm, "at", np, GD_QTY_LENGTH, 0, &s->at, &has_at)))
            return st;
        if (with_sections && !has_at)
            return gd_yfail(r, nm, np, "give the node's axial position, e.g. `at: 0.25 m`",
                            "node '%s' on a shaft with sections needs `at`", s->name);
        s->loc = gd_mp_loc(nm);
    }
    return GD_OK;
}

static gd_status read_shaft(gd_mparser *p, const gd_ynode *sm, const char *path, int index)
{
    gd_yreader *r = &p->r;
    gd_status st;
    char name[GD_NAME_MAX], fallback[32], mp[200];
    gd_shaft_spec s;
    gd_shaft_spec_init(&s);
    if ((st = gd_yexpect(r, sm, GD_Y_MAP, path)) || (st = gd_ycheck_keys(r, sm, path, SHAFT_KEYS)))
        return st;
    snprintf(fallback, sizeof fallback, "shaft%d", index + 1);
    if ((st = gd_mp_read_name(p, sm, path, name, fallback, 0))) return st;
    s.name = name;
    s.loc = gd_mp_loc(sm);
    s.path = path;
    long per_section = 0;
    int has_per = 0, has_max = 0;
    if ((st = gd_yread_qty(r, sm, "speed_ratio", path, GD_QTY_DIMLESS, 0, &s.speed_ratio,
                           &s.has_speed_ratio)) ||
        (st = gd_yread_int(r, sm, "elements_per_section", path, 1, 10000, 0, &per_section,
                           &has_per)) ||
        (st = gd_yread_qty(r, sm, "max_element_length", path, GD_QTY_LENGTH, GD_YPOS,
                           &s.max_element_length, &has_max)) ||
        (st = gd_mp_material_name(p, gd_ymap_get(sm, "material"),
                                  gd_ypath_key(mp, sizeof mp, path, "material"), &s.material)))
        return st;
    s.speed_ratio_loc = gd_mp_loc(gd_ymap_get(sm, "speed_ratio"));
    s.elements_per_section = (int)per_section;
    const gd_ynode *sections, *nodes;
    if ((st = gd_mp_get_list(p, sm, "sections", path, &sections, 0)) ||
        (st = gd_mp_get_list(p, sm, "nodes", path, &nodes, 0)))
        return st;
    s.nsections = sections ? (int)sections->n : 0;
    s.nstations = nodes ? (int)nodes->n : 0;
    gd_section_spec *secs = calloc((size_t)s.nsections + 1, sizeof *secs);
    gd_station_spec *sts = calloc((size_t)s.nstations + 1, sizeof *sts);
    if (!secs || !sts) {
        free(secs);
        free(sts);
        return gd_mp_oom(p);
    }
    s.sections = secs;
    s.stations = sts;
    if (!(st = read_sections(p, sections, path, secs)) &&
        !(st = read_stations(p, nodes, path, s.nsections > 0, sts)))
        st = gd_model_add_shaft(p->m, &s, NULL, r->err);
    free(secs);
    free(sts);
    return st;
}

gd_status gd_mp_shafts(gd_mparser *p)
{
    const gd_ynode *list;
    if (!gd_ymap_get(p->root, "shafts") && gd_ymap_get(p->root, "meshes"))
        return gd_yfail(&p->r, p->root, "shafts",
                        "a file with only gear meshes is an input of `geardyn mesh-stiffness`; "
                        "a model also needs `shafts:` (docs/model-format.md)",
                        "required list 'shafts' is missing");
    gd_status st = gd_mp_get_list(p, p->root, "shafts", "", &list, 1);
    if (st) return st;
    if (list->n == 0)
        return gd_yfail(&p->r, list, "shafts", "describe at least one shaft", "no shafts");
    for (size_t i = 0; i < list->n; i++) {
        char q[64];
        gd_ypath_index(q, sizeof q, "shafts", i);
        if ((st = read_shaft(p, list->items[i], q, (int)i))) return st;
    }
    return GD_OK;
}
