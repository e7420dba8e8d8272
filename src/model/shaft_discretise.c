/* Shafts into nodes and Timoshenko elements: the section ends and the named stations
 * of a shaft, sorted by position, become its nodes (coincident ones merged; a named
 * station takes the place); each interval between them is split into elements after
 * its section's rule (a count per section, or a maximum element length). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

typedef struct station {
    double pos;
    const gd_bstation *named; /* or NULL for a section end */
    int list_index;
} station;

static int cmp_station(const void *a, const void *b)
{
    double x = ((const station *)a)->pos, y = ((const station *)b)->pos;
    return (x > y) - (x < y);
}

static int add_node(gd_model *m, int shaft, double pos, const char *name, int list_index,
                    gd_loc loc, int *cap)
{
    if (m->nnodes == *cap) {
        int nc = *cap ? 2 * *cap : 16;
        gd_node *nn = realloc(m->nodes, (size_t)nc * sizeof *nn);
        if (!nn) return 0;
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
    return 1;
}

static int add_element(gd_model *m, int shaft, int section, int n1, int n2, int *cap)
{
    if (m->nelements == *cap) {
        int nc = *cap ? 2 * *cap : 16;
        gd_element *ne = realloc(m->elements, (size_t)nc * sizeof *ne);
        if (!ne) return 0;
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
    return 1;
}

static gd_status section_materials(gd_model *m, int index, gd_error *err)
{
    gd_shaft *sh = &m->shafts[index];
    const gd_bshaft *bs = &m->build->shafts[index];
    for (int i = 0; i < sh->nsections; i++) {
        char sp[220], field[240], at[240];
        snprintf(sp, sizeof sp, "%s.sections[%d]", bs->path, i);
        gd_build_path(field, sizeof field, sp, "material");
        const char *name = bs->section_material[i];
        if (name)
            snprintf(at, sizeof at, "%s", field);
        else
            gd_build_path(at, sizeof at, bs->path, "material");
        gd_status st = gd_build_material_ref(m, err, sh->sections[i].loc, at, field,
                                             name ? name : bs->material, &sh->sections[i].material);
        if (st) return st;
    }
    return GD_OK;
}

static gd_status discretise(gd_model *m, int index, int *node_cap, int *elem_cap, gd_error *err)
{
    gd_shaft *sh = &m->shafts[index];
    const gd_bshaft *bs = &m->build->shafts[index];
    double total = 0;
    for (int i = 0; i < sh->nsections; i++)
        total += sh->sections[i].length;
    size_t nst = (size_t)sh->nsections + 1 + (size_t)bs->nstations;
    station *sts = calloc(nst, sizeof *sts);
    if (!sts) return gd_build_oom(m, err);
    size_t k = 0;
    if (sh->nsections) {
        double pos = 0;
        sts[k++].pos = 0;
        for (int i = 0; i < sh->nsections; i++) {
            pos += sh->sections[i].length;
            sts[k++].pos = pos;
        }
    }
    for (int i = 0; i < bs->nstations; i++) {
        sts[k].pos = bs->stations[i].at;
        sts[k].named = &bs->stations[i];
        sts[k].list_index = i;
        k++;
    }
    qsort(sts, k, sizeof *sts, cmp_station);

    gd_status st = GD_OK;
    sh->first_node = m->nnodes;
    double tol = 1e-9 * (total > 0 ? total : 1.0);
    int last_node = -1;
    for (size_t i = 0; i < k && !st; i++) {
        const gd_bstation *nm = sts[i].named;
        int same = last_node >= 0 && sh->nsections &&
                   fabs(sts[i].pos - m->nodes[last_node].position) <= tol;
        if (same) {
            if (nm) {
                gd_node *ln = &m->nodes[last_node];
                if (ln->named) {
                    st = gd_build_fail(
                        m, err, nm->loc, NULL, bs->path, "merge the two names or move one node",
                        "nodes '%s' and '%s' are at the same position", ln->name, nm->name);
                    break;
                }
                snprintf(ln->name, sizeof ln->name, "%s", nm->name);
                ln->named = 1;
                ln->list_index = sts[i].list_index;
                ln->loc = nm->loc;
            }
            continue;
        }
        const char *name = nm ? nm->name : NULL;
        int li = nm ? sts[i].list_index : -1;
        if (last_node >= 0 && sh->nsections) {
            /* elements between the previous station and this one, after the rule of the
               section containing the interval's midpoint */
            double a = m->nodes[last_node].position, b = sts[i].pos;
            double mid = 0.5 * (a + b), acc = 0;
            int sec;
            for (sec = 0; sec < sh->nsections - 1; sec++) {
                if (mid < acc + sh->sections[sec].length) break;
                acc += sh->sections[sec].length;
            }
            const gd_section *s = &sh->sections[sec];
            int nel = s->max_element_length > 0 ? (int)ceil((b - a) / s->max_element_length - 1e-9)
                                                : (int)lround(s->elements * (b - a) / s->length);
            if (nel < 1) nel = 1;
            int ok = 1;
            for (int e = 1; e < nel && ok; e++)
                ok = add_node(m, index, a + (b - a) * e / nel, NULL, -1, s->loc, node_cap) &&
                     add_element(m, index, sec, m->nnodes - 2, m->nnodes - 1, elem_cap);
            ok = ok && add_node(m, index, b, name, li, nm ? nm->loc : s->loc, node_cap) &&
                 add_element(m, index, sec, m->nnodes - 2, m->nnodes - 1, elem_cap);
            if (!ok) st = gd_build_oom(m, err);
        } else if (!add_node(m, index, sts[i].pos, name, li, nm ? nm->loc : sh->loc, node_cap)) {
            st = gd_build_oom(m, err);
        }
        last_node = m->nnodes - 1;
    }
    free(sts);
    sh->nnodes = m->nnodes - sh->first_node;
    return st;
}

static int cmp_node_name(const void *a, const void *b)
{
    const gd_node *x = *(const gd_node *const *)a, *y = *(const gd_node *const *)b;
    int c = strcmp(x->name, y->name);
    return c ? c : (x > y) - (x < y);
}

/* Sorted by name (not all pairs: a model may have 1e5 nodes); the first repeated name
 * in that order is reported. */
static gd_status check_unique_node_names(gd_model *m, gd_error *err)
{
    if (m->nnodes < 2) return GD_OK;
    const gd_node **by_name = malloc((size_t)m->nnodes * sizeof *by_name);
    if (!by_name) return gd_build_oom(m, err);
    for (int i = 0; i < m->nnodes; i++)
        by_name[i] = &m->nodes[i];
    qsort(by_name, (size_t)m->nnodes, sizeof *by_name, cmp_node_name);
    const gd_node *a = NULL, *b = NULL;
    for (int i = 1; i < m->nnodes && !a; i++)
        if (!strcmp(by_name[i - 1]->name, by_name[i]->name)) {
            a = by_name[i - 1];
            b = by_name[i];
        }
    free(by_name);
    if (!a) return GD_OK;
    /* the later of the two, by its place in the file */
    const gd_node *n = a->loc.line >= b->loc.line ? a : b;
    const gd_node *o = n == a ? b : a;
    const gd_bshaft *bs = &m->build->shafts[n->shaft];
    char field[240];
    if (n->list_index >= 0)
        gd_build_path(field, sizeof field, bs->stations[n->list_index].path, "name");
    else
        gd_build_path(field, sizeof field, bs->path, "name");
    return gd_build_fail(m, err, n->loc, NULL, field, "give every node its own name",
                         "node name '%s' is used twice (also on line %d)", n->name, o->loc.line);
}

/* The model's size bound (gd_model_set_max_nodes), checked on an upper bound of the
 * node count before any node is allocated: every element adds a node, every station
 * at most one more. Counted in double: 2e9 nodes must not wrap an int. */
static gd_status check_size(gd_model *m, gd_error *err)
{
    long limit = m->build->max_nodes > 0 ? m->build->max_nodes : GD_MAX_NODES_DEFAULT;
    double nodes = 0;
    for (int i = 0; i < m->nshafts; i++) {
        const gd_shaft *sh = &m->shafts[i];
        const gd_bshaft *bs = &m->build->shafts[i];
        nodes += 1.0 + bs->nstations;
        for (int k = 0; k < sh->nsections; k++)
            nodes += sh->sections[k].elements;
        if (nodes > (double)limit)
            return gd_build_fail(
                m, err, sh->loc, NULL, bs->path,
                "coarsen the shafts (fewer elements, a longer max_element_length), or raise the "
                "limit with `limits: {max_nodes: N}` in the model (or --set 'limits={max_nodes: "
                "N}')",
                "the shafts up to and including '%s' would have %.0f nodes (%.0f DOFs), more than "
                "the limit "
                "of %ld nodes",
                sh->name, nodes, 6 * nodes, limit);
    }
    return GD_OK;
}

gd_status gd_build_discretise_shafts(gd_model *m, gd_error *err)
{
    int node_cap = 0, elem_cap = 0;
    gd_status st;
    if ((st = check_size(m, err))) return st;
    for (int i = 0; i < m->nshafts; i++) {
        if ((st = gd_build_component_name(m, err, "shaft", i, m->shafts[i].loc,
                                          m->build->shafts[i].path)) ||
            (st = section_materials(m, i, err)) ||
            (st = discretise(m, i, &node_cap, &elem_cap, err)))
            return st;
    }
    return check_unique_node_names(m, err);
}
