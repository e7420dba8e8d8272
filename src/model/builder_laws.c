/* Laws of the registry in a model (gd_model_add_law): the type's parameters checked
 * against its own table (include/geardyn/law_type.h), the nodes resolved at finish.
 * Nothing here knows one law from another. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/builder.h"
#include "model/build_impl.h"

void gd_law_spec_init(gd_law_spec *s)
{
    memset(s, 0, sizeof *s);
    s->dof = GD_X;
}

gd_status gd_model_add_law(gd_model *m, const gd_law_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nlaws;
    char path[160], fb[GD_NAME_MAX], q[200];
    gd_build_item_path(path, sizeof path, s->path, "laws", idx);
    if (!s->type)
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "type"),
                             "give one of the law types (docs/laws.md)", "the law has no type");
    gd_error e;
    if (gd_law_type_validate(s->type, &e))
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "type"), e.hint,
                             "%s", e.message);
    gd_model_law L;
    memset(&L, 0, sizeof L);
    snprintf(fb, sizeof fb, "%s%d", s->type->name, idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, L.name))) return st;
    /* records and messages name a law (law:NAME:RECORD): two of one name gave two
     * columns of one heading (issue 38 L2) */
    for (int k = 0; k < idx; k++)
        if (!strcmp(m->laws[k].name, L.name))
            return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "name"),
                                 "give every law its own name",
                                 "duplicate law name '%s' (first on line %d)", L.name,
                                 m->laws[k].loc.line);
    if (s->node2 && !s->type->two_nodes)
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "to"),
                             "remove it: this law acts on one node",
                             "law type '%s' acts on one node, not between two", s->type->name);
    if (!s->type->ndirs && ((int)s->dof < 0 || s->dof >= GD_NODE_DOFS))
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, "dof"),
                             "use x, y, z, rx, ry or rz", "unknown DOF %d", (int)s->dof);
    /* the values checked by the type's own table, through an instance */
    gd_law inst;
    gd_law_init(&inst, s->type, L.name);
    for (int k = 0; k < s->type->nparams; k++)
        if (s->values && !isnan(s->values[k])) inst.value[k] = s->values[k];
    if (gd_law_check(&inst, &e))
        return gd_build_fail(m, err, s->loc, NULL, gd_build_path(q, sizeof q, path, e.field),
                             e.hint, "%s", e.message);
    L.type = s->type;
    L.node = L.node2 = -1;
    L.dof = s->type->ndirs ? GD_X : s->dof;
    memcpy(L.value, inst.value, sizeof L.value);
    L.loc = s->loc;
    gd_bitem it;
    if (!gd_build_item_init(&it, path, s->node, s->node2, NULL)) return gd_build_oom(m, err);
    if (!gd_build_grow(&m->laws, idx, sizeof *m->laws) ||
        !gd_build_grow(&m->build->laws, idx, sizeof *m->build->laws)) {
        free(it.path);
        free(it.node);
        free(it.node2);
        return gd_build_oom(m, err);
    }
    m->laws[idx] = L;
    m->build->laws[idx] = it;
    m->nlaws++;
    if (index) *index = idx;
    return GD_OK;
}

gd_status gd_build_resolve_laws(gd_model *m, gd_error *err)
{
    gd_status st;
    for (int i = 0; i < m->nlaws; i++) {
        gd_model_law *L = &m->laws[i];
        const gd_bitem *it = &m->build->laws[i];
        if ((st = gd_build_node_ref(m, err, L->loc, it->path, "node", it->node, &L->node)))
            return st;
        if (it->node2 &&
            (st = gd_build_node_ref(m, err, L->loc, it->path, "to", it->node2, &L->node2)))
            return st;
        if (L->node2 == L->node) {
            char q[200];
            return gd_build_fail(m, err, L->loc, NULL, gd_build_path(q, sizeof q, it->path, "to"),
                                 "name another node, or leave `to` out for ground",
                                 "the law acts between node '%s' and itself",
                                 m->nodes[L->node].name);
        }
    }
    return GD_OK;
}
