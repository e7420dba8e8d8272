/* One rule from a model's law (`laws:`) to its instance (issue 35 item 5): every
 * analysis makes its instances here, the linear ones through gd_system_build
 * (law_state.c), transient and periodic through the transient spec (model_spec.c). A
 * law on a direction the model does not keep as an active DOF is a located error, the
 * same text whichever analysis runs: dropping it silently (what the linear analyses
 * did) gave modes without a bearing the user had written. A law flagged
 * GD_LAW_MODEL_DIRS leaves out the directions the model has nowhere (`dofs:`). */
#include <stdio.h>
#include <string.h>

#include "geardyn/system.h"

gd_status gd_system_law_instance(const gd_system *s, int i, gd_law *L, gd_error *err)
{
    const gd_model *m = s->model;
    const gd_model_law *ml = &m->laws[i];
    const gd_law_type *t = ml->type;
    gd_law_init(L, t, ml->name);
    memcpy(L->value, ml->value, sizeof L->value);
    int nd = t->ndirs ? t->ndirs : 1;
    for (int side = 0; side < (t->two_nodes ? 2 : 1); side++) {
        int node = side ? ml->node2 : ml->node; /* node2 < 0: ground */
        for (int k = 0; k < nd && node >= 0; k++) {
            gd_dof d = t->ndirs ? (gd_dof)t->dirs[k] : ml->dof;
            int dof = s->node_dof[6 * node + d]; /* node and d checked by the builder */
            if (dof < 0 && (gd_law_flags(L) & GD_LAW_MODEL_DIRS) && !(m->dof_mask & GD_DOF_BIT(d)))
                continue; /* the model has no such motion anywhere: held at zero */
            if (dof < 0) {
                char field[32];
                snprintf(field, sizeof field, "laws[%d]", i);
                return gd_error_set(err, GD_EINPUT, m->file, ml->loc.line, ml->loc.column, field,
                                    "keep the DOF type in 'dofs:' and give the node something "
                                    "that acts on it (an inertia, a spring, a mesh or a bearing)",
                                    "law '%s' (%s) acts on %s.%s, which is not an active DOF of "
                                    "the model",
                                    ml->name, t->name, m->nodes[node].name, gd_dof_names[d]);
            }
            L->dof[side * nd + k] = dof;
        }
        /* per unit reference speed: the shaft's nominal spin, each torsional DOF's rate */
        int d0 = L->dof[side * nd];
        L->spin[side] = d0 >= 0 ? m->shafts[m->nodes[s->dof_node[d0]].shaft].speed_ratio : 0.0;
    }
    for (int j = 0; j < L->ndofs; j++) {
        int d = L->dof[j];
        L->rate[j] = d >= 0 && s->dof_type[d] == GD_RZ
                         ? m->shafts[m->nodes[s->dof_node[d]].shaft].speed_ratio
                         : 0.0;
    }
    return GD_OK;
}
