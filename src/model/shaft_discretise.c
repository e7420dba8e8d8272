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

typedef struct named {
    const char *name;
    int index;
} named;

static int cmp_named(const void *a, const void *b)
{
    const named *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    return c ? c : (x->index > y->index) - (x->index < y->index);
}

/* Node names are unique: sorted by (name, index), O(n log n) (a pairwise test took 70 %
 * of `check` at 100 000 DOFs). The pair reported is the one the pairwise scan finds
 * first: the smallest index i that repeats an earlier name, with its first holder j. */
static gd_status check_unique_node_names(gd_model *m, gd_error *err)
{
    int n = m->nnodes;
    named *ord = malloc((size_t)(n > 0 ? n : 1) * sizeof *ord);
    if (!ord) return gd_build_oom(m, err);
    for (int k = 0; k < n; k++)
        ord[k] = (named){m->nodes[k].name, k};
    qsort(ord, (size_t)n, sizeof *ord, cmp_named);
    int bi = -1, bj = -1;
    for (int k = 1; k < n; k++)
        if (!strcmp(ord[k].name, ord[k - 1].name) &&
            (k < 2 || strcmp(ord[k - 1].name, ord[k - 2].name)) && (bi < 0 || ord[k].index < bi)) {
            bi = ord[k].index;
            bj = ord[k - 1].index;
        }
    free(ord);
    if (bi < 0) return GD_OK;
    int i = bi, j = bj;
    /* the later of the two, by its place in the file */
    const gd_node *nd = m->nodes[i].loc.line >= m->nodes[j].loc.line ? &m->nodes[i] : &m->nodes[j];
    const gd_node *o = nd == &m->nodes[i] ? &m->nodes[j] : &m->nodes[i];
    const gd_bshaft *bs = &m->build->shafts[nd->shaft];
    char field[240];
    if (nd->list_index >= 0)
        gd_build_path(field, sizeof field, bs->stations[nd->list_index].path, "name");
    else
        gd_build_path(field, sizeof field, bs->path, "name");
    return gd_build_fail(m, err, nd->loc, NULL, field, "give every node its own name",
                         "node name '%s' is used twice (also on line %d)", nd->name, o->loc.line);
}

gd_status gd_build_discretise_shafts(gd_model *m, gd_error *err)
{
    int node_cap = 0, elem_cap = 0;
    gd_status st;
    for (int i = 0; i < m->nshafts; i++) {
        if ((st = gd_build_component_name(m, err, "shaft", i, m->shafts[i].loc,
                                          m->build->shafts[i].path)) ||
            (st = section_materials(m, i, err)) ||
            (st = discretise(m, i, &node_cap, &elem_cap, err)))
            return st;
    }
    return check_unique_node_names(m, err);
}
