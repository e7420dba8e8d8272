/* Reading a model file into a validated gd_model (docs/model-format.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model.h"
#include "geardyn/mesh_stiffness.h"
#include "model_file/material_read_impl.h"
#include "model_file/mesh_geometry_read_impl.h"
#include "model_file/model_file_impl.h"
#include "model_file/yaml_doc_impl.h"

#define PI 3.14159265358979323846

static const char *const TOP_KEYS[] = {
    "title",           "description", "materials",  "dofs",        "shafts",
    "disks",           "bearings",    "springs",    "meshes",      "speed",
    "reference_shaft", "rotation",    "unbalances", "excitations", "prescribed",
    "cam_torques",     NULL};

gd_status gd_mp_oom(gd_mparser *p)
{
    return gd_error_set(p->r.err, GD_ENOMEM, p->r.file, 0, 0, "", "", "out of memory");
}

/* A list under a top-level key: NULL/absent gives n = 0. */
gd_status gd_mp_get_list(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                         const gd_ynode **list, int required)
{
    *list = gd_ymap_get(map, key);
    char q[200];
    gd_ypath_key(q, sizeof q, path, key);
    if (!*list) {
        if (required) {
            char hint[160];
            snprintf(hint, sizeof hint,
                     "add `%s:` with a list of entries (see docs/model-format.md)", key);
            return gd_yfail(&p->r, map, q, hint, "required list '%s' is missing", key);
        }
        return GD_OK;
    }
    return gd_yexpect(&p->r, *list, GD_Y_SEQ, q);
}

gd_status gd_mp_read_name(gd_mparser *p, const gd_ynode *map, const char *path, char *out,
                          const char *fallback, int required)
{
    const char *s = NULL;
    gd_status st =
        gd_yread_str(&p->r, map, "name", path, NULL, required ? GD_YREQ : 0, &s, NULL, NULL);
    if (st) return st;
    if (!s) s = fallback;
    if (strlen(s) >= GD_NAME_MAX) {
        char q[200];
        return gd_yfail(&p->r, gd_ymap_get(map, "name"), gd_ypath_key(q, sizeof q, path, "name"),
                        "use a shorter name", "name longer than %d characters", GD_NAME_MAX - 1);
    }
    snprintf(out, GD_NAME_MAX, "%s", s);
    return GD_OK;
}

gd_loc gd_mp_loc(const gd_ynode *n)
{
    gd_loc l = {n ? n->line : 0, n ? n->column : 0};
    return l;
}

/* ---- materials ---- */

static gd_status parse_materials(gd_mparser *p)
{
    const gd_ynode *mats = gd_ymap_get(p->root, "materials");
    if (!mats) return GD_OK;
    gd_status st = gd_yexpect(&p->r, mats, GD_Y_MAP, "materials");
    if (st) return st;
    p->m->materials = calloc(mats->n ? mats->n : 1, sizeof *p->m->materials);
    if (!p->m->materials) return gd_mp_oom(p);
    for (size_t i = 0; i < mats->n; i++) {
        char q[200];
        snprintf(q, sizeof q, "materials.%s", mats->keys[i]->text);
        if (strlen(mats->keys[i]->text) >= GD_NAME_MAX)
            return gd_yfail(&p->r, mats->keys[i], q, "use a shorter name", "name too long");
        if ((st = gd_material_read(&p->r, mats->items[i], q, mats->keys[i]->text, 1,
                                   &p->m->materials[i])))
            return st;
        p->m->nmaterials++;
    }
    return GD_OK;
}

static gd_status material_index(gd_mparser *p, const gd_ynode *ref, const char *path, int *out)
{
    if (!ref || ref->kind != GD_Y_SCALAR)
        return gd_yfail(&p->r, ref, path, "name a material defined under `materials:`",
                        "expected a material name");
    for (int i = 0; i < p->m->nmaterials; i++)
        if (!strcmp(p->m->materials[i].name, ref->text)) {
            *out = i;
            return GD_OK;
        }
    char hint[300];
    if (p->m->nmaterials) {
        int used = snprintf(hint, sizeof hint, "defined materials:");
        for (int i = 0; i < p->m->nmaterials && used < (int)sizeof hint - 70; i++)
            used +=
                snprintf(hint + used, sizeof hint - (size_t)used, " %s", p->m->materials[i].name);
        snprintf(hint + used, sizeof hint - (size_t)used, "; or define '%s' under `materials:`",
                 ref->text);
    } else {
        snprintf(hint, sizeof hint,
                 "define it under `materials: {%s: {density: ..., E: ..., poisson: ...}}`",
                 ref->text);
    }
    return gd_yfail(&p->r, ref, path, hint, "unknown material '%s'", ref->text);
}

/* Shafts, bearings, springs and meshes share one namespace (modal energy is reported
 * per component by name): a new name must not repeat an earlier one. */
static gd_status check_component_name(gd_mparser *p, const char *name, const gd_ynode *map,
                                      const char *path, const char *kind, int index)
{
    const gd_model *m = p->m;
    const char *what = NULL;
    int line = 0;
    for (int i = 0; i < m->nshafts && !what; i++)
        if ((strcmp(kind, "shaft") || i < index) && !strcmp(m->shafts[i].name, name))
            what = "shaft", line = m->shafts[i].loc.line;
    for (int i = 0; i < m->nbearings && !what; i++)
        if ((strcmp(kind, "bearing") || i < index) && !strcmp(m->bearings[i].name, name))
            what = "bearing", line = m->bearings[i].loc.line;
    for (int i = 0; i < m->nsprings && !what; i++)
        if ((strcmp(kind, "spring") || i < index) && !strcmp(m->springs[i].name, name))
            what = "spring", line = m->springs[i].loc.line;
    for (int i = 0; i < m->nmeshes && !what; i++)
        if ((strcmp(kind, "mesh") || i < index) && !strcmp(m->meshes[i].name, name))
            what = "mesh", line = m->meshes[i].loc.line;
    if (!what) return GD_OK;
    char q[200];
    const gd_ynode *nn = gd_ymap_get(map, "name");
    gd_ypath_key(q, sizeof q, path, "name");
    const char *hint = "give every shaft, bearing, spring and mesh its own name";
    if (!strcmp(what, kind))
        return gd_yfail(&p->r, nn ? nn : map, q, hint, "duplicate %s name '%s' (first on line %d)",
                        kind, name, line);
    return gd_yfail(&p->r, nn ? nn : map, q, hint, "name '%s' is already used by the %s on line %d",
                    name, what, line);
}

/* ---- shafts and nodes ---- */

static const char *const SHAFT_KEYS[] = {
    "name",        "material", "sections", "nodes", "elements_per_section", "max_element_length",
    "speed_ratio", NULL};
static const char *const SECTION_KEYS[] = {"length",   "outer_diameter", "inner_diameter",
                                           "material", "elements",       NULL};
static const char *const NODE_KEYS[] = {"name", "at", NULL};

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct station {
    double pos;
    const gd_ynode *node_map; /* named node at this position, or NULL */
    int list_index;           /* its index in `nodes:` */
} station;

static int cmp_station(const void *a, const void *b)
{
    return cmp_double(&((const station *)a)->pos, &((const station *)b)->pos);
}

static gd_status add_node(gd_mparser *p, int shaft, double pos, const char *name, int list_index,
                          gd_loc loc, int *cap)
{
    gd_model *m = p->m;
    if (m->nnodes == *cap) {
        int nc = *cap ? 2 * *cap : 16;
        gd_node *nn = realloc(m->nodes, (size_t)nc * sizeof *nn);
        if (!nn) return gd_mp_oom(p);
        m->nodes = nn;
        *cap = nc;
    }
    gd_node *n = &m->nodes[m->nnodes++];
    memset(n, 0, sizeof *n);
    n->shaft = shaft;
    n->position = pos;
    n->named = name != NULL;
    n->list_index = list_index;
    n->loc = loc;
    if (name)
        snprintf(n->name, sizeof n->name, "%s", name);
    else
        snprintf(n->name, sizeof n->name, "%s@%d", m->shafts[shaft].name,
                 m->nnodes - 1 - m->shafts[shaft].first_node);
    return GD_OK;
}

static gd_status add_element(gd_mparser *p, int shaft, int section, int n1, int n2, int *cap)
{
    gd_model *m = p->m;
    if (m->nelements == *cap) {
        int nc = *cap ? 2 * *cap : 16;
        gd_element *ne = realloc(m->elements, (size_t)nc * sizeof *ne);
        if (!ne) return gd_mp_oom(p);
        m->elements = ne;
        *cap = nc;
    }
    const gd_section *s = &m->shafts[shaft].sections[section];
    gd_element *e = &m->elements[m->nelements++];
    e->shaft = shaft;
    e->section = section;
    e->node1 = n1;
    e->node2 = n2;
    e->length = m->nodes[n2].position - m->nodes[n1].position;
    e->outer_diameter = s->outer_diameter;
    e->inner_diameter = s->inner_diameter;
    e->material = s->material;
    return GD_OK;
}

static gd_status parse_shaft(gd_mparser *p, const gd_ynode *sm, const char *path, int index,
                             int *node_cap, int *elem_cap)
{
    gd_yreader *r = &p->r;
    gd_model *m = p->m;
    gd_shaft *sh = &m->shafts[index];
    gd_status st;
    char q[200], fallback[32];
    if ((st = gd_yexpect(r, sm, GD_Y_MAP, path)) || (st = gd_ycheck_keys(r, sm, path, SHAFT_KEYS)))
        return st;
    snprintf(fallback, sizeof fallback, "shaft%d", index + 1);
    if ((st = gd_mp_read_name(p, sm, path, sh->name, fallback, 0))) return st;
    sh->loc = gd_mp_loc(sm);
    if ((st = check_component_name(p, sh->name, sm, path, "shaft", index))) return st;
    sh->speed_ratio = 1.0;
    if ((st = gd_yread_qty(r, sm, "speed_ratio", path, GD_QTY_DIMLESS, 0, &sh->speed_ratio,
                           &sh->speed_ratio_given)))
        return st;
    sh->speed_ratio_loc = gd_mp_loc(gd_ymap_get(sm, "speed_ratio"));
    long per_section = 1;
    double max_len = 0;
    int has_per = 0, has_max = 0;
    if ((st = gd_yread_int(r, sm, "elements_per_section", path, 1, 10000, 0, &per_section,
                           &has_per)) ||
        (st = gd_yread_qty(r, sm, "max_element_length", path, GD_QTY_LENGTH, GD_YPOS, &max_len,
                           &has_max)))
        return st;
    if (has_per && has_max)
        return gd_yfail(r, sm, path, "keep one of the two",
                        "both elements_per_section and max_element_length given");
    const gd_ynode *default_mat = gd_ymap_get(sm, "material");
    const gd_ynode *sections, *nodes;
    if ((st = gd_mp_get_list(p, sm, "sections", path, &sections, 0)) ||
        (st = gd_mp_get_list(p, sm, "nodes", path, &nodes, 0)))
        return st;
    if ((!sections || sections->n == 0) && (!nodes || nodes->n == 0))
        return gd_yfail(r, sm, path,
                        "give `sections:` for a flexible shaft, or `nodes:` for lumped bodies",
                        "shaft has neither sections nor nodes");

    /* sections */
    double total = 0;
    if (sections && sections->n) {
        sh->sections = calloc(sections->n, sizeof *sh->sections);
        if (!sh->sections) return gd_mp_oom(p);
        for (size_t i = 0; i < sections->n; i++) {
            char sp[200];
            gd_ypath_index(sp, sizeof sp, gd_ypath_key(q, sizeof q, path, "sections"), i);
            const gd_ynode *s = sections->items[i];
            gd_section *sec = &sh->sections[i];
            if ((st = gd_yexpect(r, s, GD_Y_MAP, sp)) ||
                (st = gd_ycheck_keys(r, s, sp, SECTION_KEYS)))
                return st;
            sec->loc = gd_mp_loc(s);
            if ((st = gd_yread_qty(r, s, "length", sp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                                   &sec->length, NULL)) ||
                (st = gd_yread_qty(r, s, "outer_diameter", sp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS,
                                   &sec->outer_diameter, NULL)) ||
                (st = gd_yread_qty(r, s, "inner_diameter", sp, GD_QTY_LENGTH, GD_YNONNEG,
                                   &sec->inner_diameter, NULL)))
                return st;
            if (sec->inner_diameter >= sec->outer_diameter) {
                char fp[220];
                return gd_yfail(r, gd_ymap_get(s, "inner_diameter"),
                                gd_ypath_key(fp, sizeof fp, sp, "inner_diameter"),
                                "the bore must be smaller than the outer diameter",
                                "inner diameter %g m is not less than outer diameter %g m",
                                sec->inner_diameter, sec->outer_diameter);
            }
            const gd_ynode *mat = gd_ymap_get(s, "material");
            if (!mat) mat = default_mat;
            if (!mat)
                return gd_yfail(r, s, sp, "give `material:` on the section or on the shaft",
                                "section has no material");
            char mp[220];
            if ((st = material_index(p, mat, gd_ypath_key(mp, sizeof mp, sp, "material"),
                                     &sec->material)))
                return st;
            long ne = 0;
            int has_ne = 0;
            if ((st = gd_yread_int(r, s, "elements", sp, 1, 10000, 0, &ne, &has_ne))) return st;
            if (has_ne) {
                sec->elements = (int)ne;
            } else if (has_max) {
                sec->max_element_length = max_len;
                sec->elements = (int)ceil(sec->length / max_len - 1e-9);
            } else {
                sec->elements = (int)per_section;
            }
            total += sec->length;
            sh->nsections++;
        }
    }

    /* stations: section ends and named nodes */
    size_t nnamed = nodes ? nodes->n : 0;
    size_t nst = (size_t)sh->nsections + 1 + nnamed;
    station *sts = calloc(nst, sizeof *sts);
    if (!sts) return gd_mp_oom(p);
    size_t k = 0;
    if (sh->nsections) {
        double pos = 0;
        sts[k++].pos = 0;
        for (int i = 0; i < sh->nsections; i++) {
            pos += sh->sections[i].length;
            sts[k++].pos = pos;
        }
    }
    for (size_t i = 0; i < nnamed; i++) {
        char np[200];
        gd_ypath_index(np, sizeof np, gd_ypath_key(q, sizeof q, path, "nodes"), i);
        const gd_ynode *nm = nodes->items[i];
        if ((st = gd_yexpect(r, nm, GD_Y_MAP, np)) || (st = gd_ycheck_keys(r, nm, np, NODE_KEYS))) {
            free(sts);
            return st;
        }
        const char *nn = NULL;
        if ((st = gd_yread_str(r, nm, "name", np, NULL, GD_YREQ, &nn, NULL, NULL))) {
            free(sts);
            return st;
        }
        double at = 0;
        int has_at = 0;
        if ((st = gd_yread_qty(r, nm, "at", np, GD_QTY_LENGTH, 0, &at, &has_at))) {
            free(sts);
            return st;
        }
        char ap[220];
        if (sh->nsections && !has_at) {
            free(sts);
            return gd_yfail(r, nm, np, "give the node's axial position, e.g. `at: 0.25 m`",
                            "node '%s' on a shaft with sections needs `at`", nn);
        }
        if (sh->nsections && (at < -1e-12 || at > total * (1 + 1e-12))) {
            free(sts);
            char hint[120];
            snprintf(hint, sizeof hint, "positions run from 0 to the shaft length %g m", total);
            return gd_yfail(r, gd_ymap_get(nm, "at"), gd_ypath_key(ap, sizeof ap, np, "at"), hint,
                            "position %g m lies outside the shaft", at);
        }
        if (strlen(nn) >= GD_NAME_MAX) {
            free(sts);
            char fp[220];
            return gd_yfail(r, gd_ymap_get(nm, "name"), gd_ypath_key(fp, sizeof fp, np, "name"),
                            "use a shorter name", "name longer than %d characters",
                            GD_NAME_MAX - 1);
        }
        sts[k].pos = at;
        sts[k].node_map = nm;
        sts[k].list_index = (int)i;
        k++;
    }
    qsort(sts, k, sizeof *sts, cmp_station);

    /* merge coincident stations; a named node takes the station */
    sh->first_node = m->nnodes;
    double tol = 1e-9 * (total > 0 ? total : 1.0);
    int last_node = -1;
    for (size_t i = 0; i < k; i++) {
        const gd_ynode *nm = sts[i].node_map;
        int same = last_node >= 0 && sh->nsections &&
                   fabs(sts[i].pos - m->nodes[last_node].position) <= tol;
        if (same) {
            if (nm) {
                gd_node *ln = &m->nodes[last_node];
                if (ln->named) {
                    free(sts);
                    return gd_yfail(r, nm, path, "merge the two names or move one node",
                                    "nodes '%s' and '%s' are at the same position", ln->name,
                                    gd_ymap_get(nm, "name")->text);
                }
                snprintf(ln->name, sizeof ln->name, "%s", gd_ymap_get(nm, "name")->text);
                ln->named = 1;
                ln->list_index = sts[i].list_index;
                ln->loc = gd_mp_loc(nm);
            }
            continue;
        }
        /* elements between the previous station and this one */
        if (last_node >= 0 && sh->nsections) {
            double a = m->nodes[last_node].position, b = sts[i].pos;
            /* the section containing the interval's midpoint */
            double mid = 0.5 * (a + b), acc = 0;
            int sec = 0;
            for (sec = 0; sec < sh->nsections - 1; sec++) {
                if (mid < acc + sh->sections[sec].length) break;
                acc += sh->sections[sec].length;
            }
            const gd_section *s = &sh->sections[sec];
            int nel = s->max_element_length > 0 ? (int)ceil((b - a) / s->max_element_length - 1e-9)
                                                : (int)lround(s->elements * (b - a) / s->length);
            if (nel < 1) nel = 1;
            for (int e = 1; e < nel; e++) {
                if ((st = add_node(p, index, a + (b - a) * e / nel, NULL, -1, s->loc, node_cap)) ||
                    (st = add_element(p, index, sec, m->nnodes - 2, m->nnodes - 1, elem_cap))) {
                    free(sts);
                    return st;
                }
            }
            const char *name = nm ? gd_ymap_get(nm, "name")->text : NULL;
            if ((st = add_node(p, index, b, name, nm ? sts[i].list_index : -1,
                               nm ? gd_mp_loc(nm) : s->loc, node_cap)) ||
                (st = add_element(p, index, sec, m->nnodes - 2, m->nnodes - 1, elem_cap))) {
                free(sts);
                return st;
            }
        } else {
            const char *name = nm ? gd_ymap_get(nm, "name")->text : NULL;
            if ((st = add_node(p, index, sts[i].pos, name, nm ? sts[i].list_index : -1,
                               gd_mp_loc(nm ? nm : sm), node_cap))) {
                free(sts);
                return st;
            }
        }
        last_node = m->nnodes - 1;
    }
    free(sts);
    sh->nnodes = m->nnodes - sh->first_node;
    return GD_OK;
}

static gd_status check_unique_node_names(gd_mparser *p)
{
    gd_model *m = p->m;
    for (int i = 0; i < m->nnodes; i++)
        for (int j = 0; j < i; j++)
            if (!strcmp(m->nodes[i].name, m->nodes[j].name)) {
                /* the later of the two, by its place in the file */
                const gd_node *n =
                    m->nodes[i].loc.line >= m->nodes[j].loc.line ? &m->nodes[i] : &m->nodes[j];
                const gd_node *o = n == &m->nodes[i] ? &m->nodes[j] : &m->nodes[i];
                char field[160];
                if (n->list_index >= 0)
                    snprintf(field, sizeof field, "shafts[%d].nodes[%d].name", n->shaft,
                             n->list_index);
                else
                    snprintf(field, sizeof field, "shafts[%d].name", n->shaft);
                return gd_error_set(p->r.err, GD_EINPUT, p->r.file, n->loc.line, n->loc.column,
                                    field, "give every node its own name",
                                    "node name '%s' is used twice (also on line %d)", n->name,
                                    o->loc.line);
            }
    return GD_OK;
}

static gd_status parse_shafts(gd_mparser *p)
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
    p->m->shafts = calloc(list->n, sizeof *p->m->shafts);
    if (!p->m->shafts) return gd_mp_oom(p);
    int node_cap = 0, elem_cap = 0;
    for (size_t i = 0; i < list->n; i++) {
        char q[64];
        gd_ypath_index(q, sizeof q, "shafts", i);
        p->m->nshafts++;
        if ((st = parse_shaft(p, list->items[i], q, (int)i, &node_cap, &elem_cap))) return st;
    }
    return check_unique_node_names(p);
}

/* A node reference by name, with a helpful list on failure. */
gd_status gd_mp_node_ref(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                         int required, int *out)
{
    const char *name = NULL;
    gd_status st =
        gd_yread_str(&p->r, map, key, path, NULL, required ? GD_YREQ : 0, &name, NULL, NULL);
    if (st) return st;
    if (!name) {
        *out = -1;
        return GD_OK;
    }
    int idx = gd_model_find_node(p->m, name);
    if (idx >= 0) {
        *out = idx;
        return GD_OK;
    }
    char hint[300] = "named nodes:";
    int shown = 0;
    for (int i = 0; i < p->m->nnodes && shown < 12; i++)
        if (p->m->nodes[i].named) {
            size_t u = strlen(hint);
            snprintf(hint + u, sizeof hint - u, " %s", p->m->nodes[i].name);
            shown++;
        }
    size_t u = strlen(hint);
    snprintf(hint + u, sizeof hint - u, "%s (generated nodes are SHAFT@INDEX)",
             shown ? "" : " none");
    char q[200];
    return gd_yfail(&p->r, gd_ymap_get(map, key), gd_ypath_key(q, sizeof q, path, key), hint,
                    "unknown node '%s'", name);
}

/* ---- disks ---- */

static const char *const DISK_KEYS[] = {
    "name", "node", "mass", "polar_inertia", "diametral_inertia", "geometry", NULL};
static const char *const DISK_GEOM_KEYS[] = {"outer_diameter", "inner_diameter", "width",
                                             "material", NULL};

static gd_status parse_disks(gd_mparser *p)
{
    const gd_ynode *list;
    gd_status st = gd_mp_get_list(p, p->root, "disks", "", &list, 0);
    if (st || !list) return st;
    p->m->disks = calloc(list->n ? list->n : 1, sizeof *p->m->disks);
    if (!p->m->disks) return gd_mp_oom(p);
    for (size_t i = 0; i < list->n; i++) {
        char q[64], fb[32], gp[120];
        gd_ypath_index(q, sizeof q, "disks", i);
        const gd_ynode *dm = list->items[i];
        gd_disk *d = &p->m->disks[i];
        if ((st = gd_yexpect(&p->r, dm, GD_Y_MAP, q)) ||
            (st = gd_ycheck_keys(&p->r, dm, q, DISK_KEYS)))
            return st;
        snprintf(fb, sizeof fb, "disk%zu", i + 1);
        if ((st = gd_mp_read_name(p, dm, q, d->name, fb, 0)) ||
            (st = gd_mp_node_ref(p, dm, "node", q, 1, &d->node)))
            return st;
        for (size_t j = 0; j < i; j++)
            if (!strcmp(p->m->disks[j].name, d->name)) {
                char np[100];
                return gd_yfail(
                    &p->r, gd_ymap_get(dm, "name"), gd_ypath_key(np, sizeof np, q, "name"),
                    "give every disk its own name", "duplicate disk name '%s' (also on line %d)",
                    d->name, p->m->disks[j].loc.line);
            }
        d->loc = gd_mp_loc(dm);
        const gd_ynode *geom = gd_ymap_get(dm, "geometry");
        int has_m = 0, has_ip = 0, has_id = 0;
        if (geom) {
            gd_ypath_key(gp, sizeof gp, q, "geometry");
            if (gd_ymap_get(dm, "mass") || gd_ymap_get(dm, "polar_inertia"))
                return gd_yfail(&p->r, dm, q, "give either geometry or mass and inertias",
                                "disk has both geometry and mass/inertia");
            if ((st = gd_yexpect(&p->r, geom, GD_Y_MAP, gp)) ||
                (st = gd_ycheck_keys(&p->r, geom, gp, DISK_GEOM_KEYS)))
                return st;
            double od = 0, id = 0, w = 0;
            int mi;
            char mp[160];
            if ((st = gd_yread_qty(&p->r, geom, "outer_diameter", gp, GD_QTY_LENGTH,
                                   GD_YREQ | GD_YPOS, &od, NULL)) ||
                (st = gd_yread_qty(&p->r, geom, "inner_diameter", gp, GD_QTY_LENGTH, GD_YNONNEG,
                                   &id, NULL)) ||
                (st = gd_yread_qty(&p->r, geom, "width", gp, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &w,
                                   NULL)))
                return st;
            if (!gd_ymap_get(geom, "material"))
                return gd_yfail(&p->r, geom, gp, "add `material: NAME`", "no material");
            if ((st = material_index(p, gd_ymap_get(geom, "material"),
                                     gd_ypath_key(mp, sizeof mp, gp, "material"), &mi)))
                return st;
            if (id >= od) {
                char fp[180];
                return gd_yfail(&p->r, gd_ymap_get(geom, "inner_diameter"),
                                gd_ypath_key(fp, sizeof fp, gp, "inner_diameter"),
                                "the bore must be smaller than the outer diameter",
                                "inner diameter %g m is not less than outer diameter %g m", id, od);
            }
            double rho = p->m->materials[mi].density;
            d->mass = rho * PI / 4.0 * (od * od - id * id) * w;
            /* thick disk: Ip = m (Ro^2 + Ri^2)/2, Id = Ip/2 + m w^2/12 */
            d->polar_inertia = d->mass * (od * od + id * id) / 8.0;
            d->diametral_inertia = 0.5 * d->polar_inertia + d->mass * w * w / 12.0;
            has_m = has_ip = has_id = 1;
        } else {
            if ((st = gd_yread_qty(&p->r, dm, "mass", q, GD_QTY_MASS, GD_YPOS, &d->mass, &has_m)) ||
                (st = gd_yread_qty(&p->r, dm, "polar_inertia", q, GD_QTY_INERTIA, GD_YNONNEG,
                                   &d->polar_inertia, &has_ip)) ||
                (st = gd_yread_qty(&p->r, dm, "diametral_inertia", q, GD_QTY_INERTIA, GD_YNONNEG,
                                   &d->diametral_inertia, &has_id)))
                return st;
            if (!has_m && !has_ip && !has_id)
                return gd_yfail(&p->r, dm, q,
                                "give mass and polar_inertia (kg, kg*m^2), or `geometry:`",
                                "disk has no mass or inertia");
            /* a thin disk unless told otherwise */
            if (!has_id) d->diametral_inertia = 0.5 * d->polar_inertia;
        }
        p->m->ndisks++;
    }
    return GD_OK;
}

/* ---- bearings and springs ---- */

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

static gd_status parse_bearings(gd_mparser *p)
{
    const gd_ynode *list;
    gd_status st = gd_mp_get_list(p, p->root, "bearings", "", &list, 0);
    if (st || !list) return st;
    p->m->bearings = calloc(list->n ? list->n : 1, sizeof *p->m->bearings);
    if (!p->m->bearings) return gd_mp_oom(p);
    for (size_t i = 0; i < list->n; i++) {
        char q[64], fb[32];
        gd_ypath_index(q, sizeof q, "bearings", i);
        const gd_ynode *bm = list->items[i];
        gd_bearing *b = &p->m->bearings[i];
        p->m->nbearings++;
        if ((st = gd_yexpect(&p->r, bm, GD_Y_MAP, q)) ||
            (st = gd_ycheck_keys(&p->r, bm, q, BEARING_KEYS)))
            return st;
        snprintf(fb, sizeof fb, "bearing%zu", i + 1);
        b->loc = gd_mp_loc(bm);
        if ((st = gd_mp_read_name(p, bm, q, b->name, fb, 0)) ||
            (st = check_component_name(p, b->name, bm, q, "bearing", (int)i)) ||
            (st = gd_mp_node_ref(p, bm, "node", q, 1, &b->node)) ||
            (st = gd_mp_node_ref(p, bm, "to", q, 0, &b->node2)))
            return st;
        char tp0[100];
        if (b->node2 == b->node)
            return gd_yfail(&p->r, gd_ymap_get(bm, "to"), gd_ypath_key(tp0, sizeof tp0, q, "to"),
                            "connect two different nodes, or omit `to` for ground",
                            "bearing connects a node to itself");
        int any = 0;
        if ((st = read_coeffs(p, bm, q, &b->coeffs, &any))) return st;
        const gd_ynode *table = gd_ymap_get(bm, "table");
        if (table) {
            char tp[100];
            gd_ypath_key(tp, sizeof tp, q, "table");
            if ((st = gd_yexpect(&p->r, table, GD_Y_SEQ, tp))) return st;
            if (any)
                return gd_yfail(&p->r, table, tp, "put every coefficient in the table rows",
                                "constant coefficients given together with a speed table");
            if (table->n < 2)
                return gd_yfail(&p->r, table, tp, "give at least two rows {speed: ..., kxx: ...}",
                                "a speed table needs two or more rows");
            b->table_speed = calloc(table->n, sizeof *b->table_speed);
            b->table = calloc(table->n, sizeof *b->table);
            if (!b->table_speed || !b->table) return gd_mp_oom(p);
            for (size_t j = 0; j < table->n; j++) {
                char rp[120];
                gd_ypath_index(rp, sizeof rp, tp, j);
                const gd_ynode *row = table->items[j];
                int rany = 0;
                if ((st = gd_yexpect(&p->r, row, GD_Y_MAP, rp)) ||
                    (st = gd_ycheck_keys(&p->r, row, rp, TABLE_ROW_KEYS)) ||
                    (st = gd_yread_qty(&p->r, row, "speed", rp, GD_QTY_ANGULAR_SPEED,
                                       GD_YREQ | GD_YNONNEG, &b->table_speed[j], NULL)) ||
                    (st = read_coeffs(p, row, rp, &b->table[j], &rany)))
                    return st;
                if (j > 0 && !(b->table_speed[j] > b->table_speed[j - 1]))
                    return gd_yfail(&p->r, gd_ymap_get(row, "speed"), rp,
                                    "sort the rows by increasing speed",
                                    "speeds in the table must increase");
                b->ntable++;
            }
            b->coeffs = b->table[0];
            any = 1;
        }
        if ((st = gd_mp_bearing_sfd(p, bm, q, b))) return st;
        if (!any && !b->has_sfd)
            return gd_yfail(&p->r, bm, q, "give at least one of k, kxx, kyy, kzz, c, ..., sfd",
                            "bearing has no stiffness or damping");
    }
    return GD_OK;
}

static const char *const DOF_CHOICES[] = {"x", "y", "z", "rx", "ry", "rz", NULL};
static const char *const SPRING_KEYS[] = {"name",      "node",    "to", "dof",
                                          "stiffness", "damping", NULL};

static gd_status parse_springs(gd_mparser *p)
{
    const gd_ynode *list;
    gd_status st = gd_mp_get_list(p, p->root, "springs", "", &list, 0);
    if (st || !list) return st;
    p->m->springs = calloc(list->n ? list->n : 1, sizeof *p->m->springs);
    if (!p->m->springs) return gd_mp_oom(p);
    for (size_t i = 0; i < list->n; i++) {
        char q[64], fb[32];
        gd_ypath_index(q, sizeof q, "springs", i);
        const gd_ynode *sm = list->items[i];
        gd_spring *s = &p->m->springs[i];
        if ((st = gd_yexpect(&p->r, sm, GD_Y_MAP, q)) ||
            (st = gd_ycheck_keys(&p->r, sm, q, SPRING_KEYS)))
            return st;
        snprintf(fb, sizeof fb, "spring%zu", i + 1);
        s->loc = gd_mp_loc(sm);
        int dof = 0, has_k = 0, has_c = 0;
        if ((st = gd_mp_read_name(p, sm, q, s->name, fb, 0)) ||
            (st = check_component_name(p, s->name, sm, q, "spring", (int)i)) ||
            (st = gd_mp_node_ref(p, sm, "node", q, 1, &s->node1)) ||
            (st = gd_mp_node_ref(p, sm, "to", q, 0, &s->node2)) ||
            (st = gd_yread_str(&p->r, sm, "dof", q, DOF_CHOICES, GD_YREQ, NULL, &dof, NULL)))
            return st;
        s->dof = (gd_dof)dof;
        gd_qty kq = dof >= GD_RX ? GD_QTY_ROT_STIFFNESS : GD_QTY_STIFFNESS;
        gd_qty cq = dof >= GD_RX ? GD_QTY_ROT_DAMPING : GD_QTY_DAMPING;
        if ((st = gd_yread_qty(&p->r, sm, "stiffness", q, kq, GD_YNONNEG, &s->stiffness, &has_k)) ||
            (st = gd_yread_qty(&p->r, sm, "damping", q, cq, GD_YNONNEG, &s->damping, &has_c)))
            return st;
        char tp0[100];
        if (s->node2 == s->node1)
            return gd_yfail(&p->r, gd_ymap_get(sm, "to"), gd_ypath_key(tp0, sizeof tp0, q, "to"),
                            "connect two different nodes, or omit `to` for ground",
                            "spring connects a node to itself");
        if (!(s->stiffness > 0) && !(s->damping > 0))
            return gd_yfail(&p->r, sm, q, "give a positive stiffness or damping",
                            "spring has neither stiffness nor damping");
        p->m->nsprings++;
    }
    return GD_OK;
}

/* ---- gear meshes ---- */

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

static gd_status parse_mesh(gd_mparser *p, const gd_ynode *mm, const char *q, gd_mesh *g)
{
    gd_yreader *r = &p->r;
    gd_status st;
    char fp[200];
    if ((st = gd_yexpect(r, mm, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, mm, q, MESH_KEYS)) ||
        (st = gd_mp_read_name(p, mm, q, g->name, "", 1)) ||
        (st = gd_mp_node_ref(p, mm, "driver", q, 1, &g->driver)) ||
        (st = gd_mp_node_ref(p, mm, "driven", q, 1, &g->driven)))
        return st;
    g->loc = gd_mp_loc(mm);
    if (p->m->nodes[g->driver].shaft == p->m->nodes[g->driven].shaft)
        return gd_yfail(r, gd_ymap_get(mm, "driven"), gd_ypath_key(fp, sizeof fp, q, "driven"),
                        "a gear mesh joins gears on two different shafts",
                        "driver '%s' and driven '%s' are on the same shaft '%s'",
                        p->m->nodes[g->driver].name, p->m->nodes[g->driven].name,
                        p->m->shafts[p->m->nodes[g->driver].shaft].name);
    double teeth[2] = {0, 0}, rb[2] = {0, 0}, rp[2] = {0, 0}, module = 0;
    int has_teeth, has_rb, has_rp, has_mod, has_pa, has_helix;
    g->pressure_angle = 20.0 * PI / 180.0;
    if ((st = read_pair(p, mm, "teeth", q, GD_QTY_DIMLESS, teeth, &has_teeth)) ||
        (st = read_pair(p, mm, "base_radius", q, GD_QTY_LENGTH, rb, &has_rb)) ||
        (st = read_pair(p, mm, "pitch_radius", q, GD_QTY_LENGTH, rp, &has_rp)) ||
        (st = gd_yread_qty(r, mm, "module", q, GD_QTY_LENGTH, GD_YPOS, &module, &has_mod)) ||
        (st = gd_yread_qty(r, mm, "pressure_angle", q, GD_QTY_ANGLE, GD_YNONNEG, &g->pressure_angle,
                           &has_pa)) ||
        (st = gd_yread_qty(r, mm, "helix_angle", q, GD_QTY_ANGLE, GD_YNONNEG, &g->helix_angle,
                           &has_helix)) ||
        (st =
             gd_yread_qty(r, mm, "line_of_centres", q, GD_QTY_ANGLE, 0, &g->line_of_centres, NULL)))
        return st;
    if (has_teeth)
        for (int i = 0; i < 2; i++) {
            if (teeth[i] != floor(teeth[i]) || teeth[i] < 3)
                return gd_yfail(r, gd_ymap_get(mm, "teeth"),
                                gd_ypath_key(fp, sizeof fp, q, "teeth"),
                                "teeth numbers are whole numbers of 3 or more",
                                "invalid teeth number %g", teeth[i]);
            g->teeth[i] = (int)teeth[i];
        }
    if (g->pressure_angle >= 60.0 * PI / 180.0) {
        char hint[80];
        snprintf(hint, sizeof hint, "did you mean '%g deg'?", g->pressure_angle);
        return gd_yfail(r, gd_ymap_get(mm, "pressure_angle"),
                        gd_ypath_key(fp, sizeof fp, q, "pressure_angle"), hint,
                        "pressure angle %g rad is not below 60 deg (plain numbers are radians)",
                        g->pressure_angle);
    }
    if (g->helix_angle >= 60.0 * PI / 180.0) {
        char hint[80];
        snprintf(hint, sizeof hint, "did you mean '%g deg'?", g->helix_angle);
        return gd_yfail(
            r, gd_ymap_get(mm, "helix_angle"), gd_ypath_key(fp, sizeof fp, q, "helix_angle"), hint,
            "helix angle %g rad is not below 60 deg (plain numbers are radians)", g->helix_angle);
    }
    /* gear geometry (docs/mesh-stiffness.md): validated here so `check` catches it, and
     * the source of the gear sizes when the mesh gives none */
    const gd_ynode *geom_node = gd_ymap_get(mm, "geometry");
    gd_gear_pair_geometry geom;
    gd_tvms_options tvms_opt;
    gd_gear_pair_derived der;
    gd_tvms_options_init(&tvms_opt);
    if (geom_node) {
        if ((st = gd_gear_pair_read(r, p->root, mm, q, &geom, &tvms_opt))) return st;
        if ((st = gd_gear_pair_derive(&geom, &der, r->err))) {
            gd_gear_pair_error_locate(r->file, mm, q, r->err);
            return st;
        }
        const char *dup = has_teeth   ? "teeth"
                          : has_pa    ? "pressure_angle"
                          : has_helix ? "helix_angle"
                                      : NULL;
        if (dup)
            return gd_yfail(r, gd_ymap_get(mm, dup), gd_ypath_key(fp, sizeof fp, q, dup),
                            "with `geometry:` the teeth and angles come from it; remove this key",
                            "'%s' given together with `geometry:`", dup);
    }
    int ngiven = has_rb + has_rp + has_mod + (geom_node != NULL);
    if (ngiven != 1)
        return gd_yfail(r, mm, q,
                        "give exactly one of base_radius: [rb1, rb2], pitch_radius: [r1, r2], "
                        "module with teeth, or geometry:",
                        ngiven ? "gear size given more than once" : "gear size missing");
    if (has_mod && !has_teeth)
        return gd_yfail(r, gd_ymap_get(mm, "module"), q, "add `teeth: [z1, z2]`",
                        "module needs the teeth numbers");
    double ca = cos(g->pressure_angle);
    for (int i = 0; i < 2; i++) {
        if (has_rb) g->base_radius[i] = rb[i];
        if (has_rp) g->base_radius[i] = rp[i] * ca;
        if (has_mod) g->base_radius[i] = 0.5 * module * g->teeth[i] * ca;
    }
    if (has_teeth && (has_rb || has_rp)) {
        double rr = g->base_radius[1] / g->base_radius[0], tr = teeth[1] / teeth[0];
        if (fabs(rr - tr) > 1e-3 * tr)
            return gd_yfail(r, gd_ymap_get(mm, "teeth"), gd_ypath_key(fp, sizeof fp, q, "teeth"),
                            "radii and teeth numbers must give the same gear ratio",
                            "radius ratio %.6g differs from teeth ratio %.6g", rr, tr);
    }
    int hand = 0, coupling = GD_COUPLING_FULL;
    if ((st = gd_yread_str(r, mm, "hand", q, HANDS, 0, NULL, &hand, NULL)) ||
        (st = gd_yread_str(r, mm, "coupling", q, COUPLINGS, 0, NULL, &coupling, NULL)))
        return st;
    g->hand = hand == 0 ? 1 : -1;
    g->coupling = (gd_coupling)coupling;
    g->base_helix_angle = atan(tan(g->helix_angle) * cos(g->pressure_angle));
    if (geom_node) {
        for (int i = 0; i < 2; i++) {
            g->teeth[i] = geom.gear[i].teeth;
            g->base_radius[i] = der.base_radius[i];
        }
        g->pressure_angle = der.working_pressure_angle;
        g->helix_angle = geom.helix_angle;
        g->base_helix_angle = der.base_helix_angle;
        g->hand = geom.hand;
    }
    const gd_ynode *stiff = gd_ymap_get(mm, "stiffness");
    int from_table = 0;
    if (stiff && stiff->kind == GD_Y_MAP) {
        /* {from: geometry, ...}: the mean of k(angle) for linear analyses, the table kept */
        if (!geom_node)
            return gd_yfail(r, stiff, gd_ypath_key(fp, sizeof fp, q, "stiffness"),
                            "add a `geometry:` map to the mesh (docs/mesh-stiffness.md)",
                            "stiffness from geometry needs the mesh's geometry");
        if ((st = gd_tvms_compute(&geom, &tvms_opt, &g->tvms, r->err))) {
            gd_gear_pair_error_locate(r->file, mm, q, r->err);
            return st;
        }
        g->stiffness = g->tvms->mean;
    }
    /* time-integration keys; a tvms table gives the mean stiffness when none is given */
    if ((st = gd_mp_mesh_dynamics(p, mm, q, g, &from_table))) return st;
    if (!(stiff && stiff->kind == GD_Y_MAP) &&
        (st = gd_yread_qty(r, mm, "stiffness", q, GD_QTY_STIFFNESS,
                           GD_YPOS | (from_table ? 0 : GD_YREQ), &g->stiffness, NULL)))
        return st;
    return GD_OK;
}

/* Shaft speeds follow the gear ratios from the reference shaft: an external mesh
 * reverses the sense, omega_driven = -omega_driver * rb_driver / rb_driven. */
static gd_status propagate_speeds(gd_mparser *p, const gd_ynode *list)
{
    gd_model *m = p->m;
    int *seen = calloc((size_t)m->nshafts, sizeof *seen);
    int *queue = calloc((size_t)m->nshafts, sizeof *queue);
    if (!seen || !queue) {
        free(seen);
        free(queue);
        return gd_mp_oom(p);
    }
    gd_status st = GD_OK;
    /* every connected group starts from its own root: the reference shaft first */
    for (int start = -1; start < m->nshafts && !st; start++) {
        /* a shaft not geared to the reference keeps its own speed_ratio (default 1) */
        int root = start < 0 ? m->reference_shaft : start;
        if (seen[root]) continue;
        seen[root] = 1;
        int head = 0, tail = 0;
        queue[tail++] = root;
        while (head < tail && !st) {
            int s = queue[head++];
            for (int k = 0; k < m->nmeshes && !st; k++) {
                const gd_mesh *g = &m->meshes[k];
                int sa = m->nodes[g->driver].shaft, sb = m->nodes[g->driven].shaft;
                int other;
                double ratio;
                if (sa == s) {
                    other = sb;
                    ratio = -m->shafts[s].speed_ratio * g->base_radius[0] / g->base_radius[1];
                } else if (sb == s) {
                    other = sa;
                    ratio = -m->shafts[s].speed_ratio * g->base_radius[1] / g->base_radius[0];
                } else {
                    continue;
                }
                gd_shaft *o = &m->shafts[other];
                if (!seen[other]) {
                    if (o->speed_ratio_given && fabs(o->speed_ratio - ratio) > 1e-6 * fabs(ratio)) {
                        char field[100];
                        snprintf(field, sizeof field, "shafts[%d].speed_ratio", other);
                        st = gd_error_set(p->r.err, GD_EINPUT, p->r.file, o->speed_ratio_loc.line,
                                          o->speed_ratio_loc.column, field,
                                          "remove speed_ratio: it follows from the gear meshes",
                                          "shaft '%s' has speed_ratio %g but its meshes give %g",
                                          o->name, o->speed_ratio, ratio);
                    }
                    o->speed_ratio = ratio;
                    seen[other] = 1;
                    queue[tail++] = other;
                } else if (fabs(o->speed_ratio - ratio) > 1e-6 * fabs(ratio)) {
                    char field[100];
                    snprintf(field, sizeof field, "meshes[%d]", k);
                    st = gd_error_set(p->r.err, GD_EINPUT, p->r.file, g->loc.line, g->loc.column,
                                      field, "check the radii or teeth of the meshes in the loop",
                                      "mesh '%s' closes a loop with inconsistent gear ratios "
                                      "(%g vs %g for shaft '%s')",
                                      g->name, ratio, o->speed_ratio, o->name);
                }
            }
        }
    }
    free(seen);
    free(queue);
    if (st) return st;
    for (int k = 0; k < m->nmeshes; k++) {
        gd_mesh *g = &m->meshes[k];
        double ratio = m->shafts[m->nodes[g->driver].shaft].speed_ratio;
        g->driver_sense = ratio < 0 ? -1 : 1;
        const gd_ynode *mm = list->items[k];
        int rot = 0, given = 0;
        char q[64];
        gd_ypath_index(q, sizeof q, "meshes", (size_t)k);
        if ((st = gd_yread_str(&p->r, mm, "driver_rotation", q, ROTATIONS, 0, NULL, &rot, &given)))
            return st;
        if (given && (rot == 0 ? 1 : -1) != g->driver_sense) {
            char fp[100];
            return gd_yfail(&p->r, gd_ymap_get(mm, "driver_rotation"),
                            gd_ypath_key(fp, sizeof fp, q, "driver_rotation"),
                            "the sense follows from the reference shaft's `rotation` and the "
                            "meshes; change `rotation:` at the top or remove this key",
                            "driver turns %s here, but the gear train makes it turn %s",
                            ROTATIONS[rot], g->driver_sense > 0 ? "ccw" : "cw");
        }
    }
    return GD_OK;
}

static gd_status parse_meshes(gd_mparser *p)
{
    const gd_ynode *list;
    gd_status st = gd_mp_get_list(p, p->root, "meshes", "", &list, 0);
    if (st) return st;
    if (list && list->n) {
        p->m->meshes = calloc(list->n, sizeof *p->m->meshes);
        if (!p->m->meshes) return gd_mp_oom(p);
        for (size_t i = 0; i < list->n; i++) {
            char q[64];
            gd_ypath_index(q, sizeof q, "meshes", i);
            p->m->nmeshes++; /* counted first: gd_model_free releases a half-read mesh */
            if ((st = parse_mesh(p, list->items[i], q, &p->m->meshes[i])) ||
                (st = check_component_name(p, p->m->meshes[i].name, list->items[i], q, "mesh",
                                           (int)i)))
                return st;
        }
    }
    static const gd_ynode empty = {GD_Y_SEQ, 0, 0, NULL, 0, 0, 0, NULL, NULL};
    return propagate_speeds(p, list ? list : &empty);
}

/* ---- unbalances ---- */

static const char *const UNBALANCE_KEYS[] = {"name",         "node",  "amount", "mass",
                                             "eccentricity", "phase", NULL};

static gd_status parse_unbalances(gd_mparser *p)
{
    const gd_ynode *list;
    gd_status st = gd_mp_get_list(p, p->root, "unbalances", "", &list, 0);
    if (st || !list) return st;
    p->m->unbalances = calloc(list->n ? list->n : 1, sizeof *p->m->unbalances);
    if (!p->m->unbalances) return gd_mp_oom(p);
    for (size_t i = 0; i < list->n; i++) {
        char q[64], fb[32];
        gd_ypath_index(q, sizeof q, "unbalances", i);
        const gd_ynode *um = list->items[i];
        gd_unbalance *u = &p->m->unbalances[i];
        if ((st = gd_yexpect(&p->r, um, GD_Y_MAP, q)) ||
            (st = gd_ycheck_keys(&p->r, um, q, UNBALANCE_KEYS)))
            return st;
        snprintf(fb, sizeof fb, "unbalance%zu", i + 1);
        u->loc = gd_mp_loc(um);
        double mass = 0, ecc = 0;
        int has_amount = 0, has_mass = 0, has_ecc = 0;
        if ((st = gd_mp_read_name(p, um, q, u->name, fb, 0)) ||
            (st = gd_mp_node_ref(p, um, "node", q, 1, &u->node)) ||
            (st = gd_yread_qty(&p->r, um, "amount", q, GD_QTY_MASS_LENGTH, GD_YPOS, &u->amount,
                               &has_amount)) ||
            (st = gd_yread_qty(&p->r, um, "mass", q, GD_QTY_MASS, GD_YPOS, &mass, &has_mass)) ||
            (st = gd_yread_qty(&p->r, um, "eccentricity", q, GD_QTY_LENGTH, GD_YPOS, &ecc,
                               &has_ecc)) ||
            (st = gd_yread_qty(&p->r, um, "phase", q, GD_QTY_ANGLE, 0, &u->phase, NULL)))
            return st;
        if (has_amount == (has_mass || has_ecc) || has_mass != has_ecc)
            return gd_yfail(&p->r, um, q, "give `amount` (kg*m), or both `mass` and `eccentricity`",
                            has_amount ? "amount given together with mass/eccentricity"
                                       : "unbalance amount missing");
        if (!has_amount) u->amount = mass * ecc;
        p->m->nunbalances++;
    }
    return GD_OK;
}

/* ---- top level ---- */

static gd_status parse_globals(gd_mparser *p)
{
    gd_yreader *r = &p->r;
    gd_model *m = p->m;
    gd_status st;
    m->dof_mask = GD_DOFS_ALL;
    const gd_ynode *dofs = gd_ymap_get(p->root, "dofs");
    if (dofs) {
        if ((st = gd_yexpect(r, dofs, GD_Y_SEQ, "dofs"))) return st;
        m->dof_mask = 0;
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
            m->dof_mask |= GD_DOF_BIT(found);
        }
        if (!m->dof_mask)
            return gd_yfail(r, dofs, "dofs", "list at least one DOF, e.g. [rz]", "no DOFs");
    }
    if ((st = gd_yread_qty(r, p->root, "speed", "", GD_QTY_ANGULAR_SPEED, GD_YNONNEG, &m->speed,
                           NULL)))
        return st;
    const char *ref = NULL;
    if ((st = gd_yread_str(r, p->root, "reference_shaft", "", NULL, 0, &ref, NULL, NULL)))
        return st;
    m->reference_shaft = 0;
    if (ref) {
        m->reference_shaft = gd_model_find_shaft(m, ref);
        if (m->reference_shaft < 0)
            return gd_yfail(r, gd_ymap_get(p->root, "reference_shaft"), "reference_shaft",
                            "name one of the shafts", "unknown shaft '%s'", ref);
    }
    int rot = 0;
    if ((st = gd_yread_str(r, p->root, "rotation", "", ROTATIONS, 0, NULL, &rot, NULL))) return st;
    gd_shaft *rs = &m->shafts[m->reference_shaft];
    if (rs->speed_ratio_given && fabs(fabs(rs->speed_ratio) - 1.0) > 1e-12) {
        char field[100];
        snprintf(field, sizeof field, "shafts[%d].speed_ratio", m->reference_shaft);
        return gd_error_set(r->err, GD_EINPUT, r->file, rs->speed_ratio_loc.line,
                            rs->speed_ratio_loc.column, field,
                            "the reference shaft turns at the reference speed; remove "
                            "speed_ratio or use `rotation: cw` for the opposite sense",
                            "reference shaft '%s' has speed_ratio %g", rs->name, rs->speed_ratio);
    }
    if (!rs->speed_ratio_given) rs->speed_ratio = rot == 0 ? 1.0 : -1.0;
    rs->speed_ratio_given = 1;
    return GD_OK;
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
        (st = parse_materials(p)) || (st = parse_shafts(p)) || (st = parse_globals(p)) ||
        (st = parse_disks(p)) || (st = parse_bearings(p)) || (st = parse_springs(p)) ||
        (st = parse_meshes(p)) || (st = parse_unbalances(p)) || (st = gd_mp_dynamics(p)))
        return st;
    return GD_OK;
}

gd_status gd_model_from_ydoc(const gd_ydoc *doc, const char *name, gd_model **out, gd_error *err)
{
    gd_mparser p = {{name, err}, doc->root, calloc(1, sizeof(gd_model))};
    if (!p.m) return gd_error_set(err, GD_ENOMEM, name, 0, 0, "", "", "out of memory");
    snprintf(p.m->file, sizeof p.m->file, "%s", name);
    gd_status st = parse(&p);
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
