/* The `laws:` list of a model file (docs/laws.md): each item names a law type of the
 * registry and gives the parameters of that type's own table, read with their units.
 * Nothing here knows one law from another. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/builder.h"
#include "model_file/model_file_impl.h"
#include "model_file/yaml_doc_impl.h"

static const char *const DOFS[] = {"x", "y", "z", "rx", "ry", "rz", NULL};

static gd_status read_law(gd_mparser *p, const gd_ynode *lm, const char *q, size_t i)
{
    gd_status st;
    gd_yreader *r = &p->r;
    const char *tname = NULL;
    if ((st = gd_yexpect(r, lm, GD_Y_MAP, q)) ||
        (st = gd_yread_str(r, lm, "type", q, NULL, GD_YREQ, &tname, NULL, NULL)))
        return st;
    const gd_law_type *t = gd_law_type_find(tname);
    if (!t) {
        char list[400] = "";
        size_t len = 0;
        for (int k = 0; k < gd_nlaw_types && len + 40 < sizeof list; k++) {
            int w = snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "",
                             gd_law_types[k]->name);
            if (w > 0) len += (size_t)w;
        }
        char hint[480];
        snprintf(hint, sizeof hint, "use one of: %s (docs/laws.md)", list);
        char fq[220];
        snprintf(fq, sizeof fq, "%s.type", q);
        return gd_yfail(r, gd_ymap_get(lm, "type"), fq, hint, "unknown law type '%s'", tname);
    }
    /* the keys: the item's own, then the type's parameters */
    const char *keys[6 + GD_LAW_MAX_PARAMS];
    int nk = 0;
    keys[nk++] = "type";
    keys[nk++] = "name";
    keys[nk++] = "node";
    if (t->two_nodes) keys[nk++] = "to";
    if (!t->ndirs) keys[nk++] = "dof";
    for (int k = 0; k < t->nparams; k++)
        keys[nk++] = t->params[k].name;
    keys[nk] = NULL;
    if ((st = gd_ycheck_keys(r, lm, q, keys))) return st;
    char fb[GD_NAME_MAX], name[GD_NAME_MAX];
    snprintf(fb, sizeof fb, "%s%zu", t->name, i + 1);
    gd_law_spec s;
    gd_law_spec_init(&s);
    int dof = 0;
    if ((st = gd_mp_read_name(p, lm, q, name, fb, 0)) ||
        (st = gd_mp_node_name(p, lm, "node", q, 1, &s.node)) ||
        (t->two_nodes && (st = gd_mp_node_name(p, lm, "to", q, 0, &s.node2))) ||
        (!t->ndirs && (st = gd_yread_str(r, lm, "dof", q, DOFS, GD_YREQ, NULL, &dof, NULL))))
        return st;
    double values[GD_LAW_MAX_PARAMS];
    for (int k = 0; k < t->nparams; k++) {
        const gd_law_param *pp = &t->params[k];
        int flags = isnan(pp->def) ? GD_YREQ : 0, present = 0;
        if (pp->bound == GD_LAW_POSITIVE) flags |= GD_YPOS;
        if (pp->bound == GD_LAW_NONNEG) flags |= GD_YNONNEG;
        if ((st = gd_yread_qty(r, lm, pp->name, q, pp->qty, flags, &values[k], &present)))
            return st;
        if (!present) values[k] = NAN;
    }
    s.name = name;
    s.type = t;
    s.dof = (gd_dof)dof;
    s.values = values;
    s.loc = gd_mp_loc(lm);
    s.path = q;
    return gd_model_add_law(p->m, &s, NULL, r->err);
}

gd_status gd_mp_laws(gd_mparser *p)
{
    return gd_mp_each(p, "laws", read_law);
}
