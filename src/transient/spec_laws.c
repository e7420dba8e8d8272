/* The laws of a transient spec as registry instances (gd_transient_spec_laws): the
 * dampers and loads of the typed spec made into gd_law_sfd and gd_law_load instances,
 * then the spec's own laws, each with its nominal rates at the reference speed. The one
 * place where a spec becomes the list every solver loops over. */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/model.h"
#include "geardyn/transient.h"

static double dof_rate(const gd_system *sys, int dof, double speed)
{
    if (dof < 0 || sys->dof_type[dof] != GD_RZ) return 0.0;
    const gd_model *m = sys->model;
    return m->shafts[m->nodes[sys->dof_node[dof]].shaft].speed_ratio * speed;
}

gd_status gd_transient_spec_laws(const gd_system *sys, const gd_transient_spec *spec, double speed,
                                 gd_law **out, int *n, gd_error *err)
{
    *out = NULL;
    *n = 0;
    int total = spec->nsfds + spec->nloads + spec->nlaws;
    if (spec->nlaws < 0 || (spec->nlaws && !spec->laws))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "laws", "", "laws missing");
    if (total == 0) return GD_OK;
    gd_law *L = calloc((size_t)total, sizeof *L);
    if (!L) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    int k = 0;
    for (int i = 0; i < spec->nsfds; i++, k++) {
        const gd_tr_sfd *s = &spec->sfds[i];
        char name[GD_LAW_NAME_MAX];
        snprintf(name, sizeof name, "sfds[%d]", i);
        gd_law_init(&L[k], &gd_law_sfd, name);
        gd_sfd_law_values(&s->params, &L[k]);
        L[k].dof[0] = gd_system_dof(sys, s->node, GD_X);
        L[k].dof[1] = gd_system_dof(sys, s->node, GD_Y);
        L[k].dof[2] = s->node2 >= 0 ? gd_system_dof(sys, s->node2, GD_X) : -1;
        L[k].dof[3] = s->node2 >= 0 ? gd_system_dof(sys, s->node2, GD_Y) : -1;
    }
    for (int i = 0; i < spec->nloads; i++, k++) {
        char name[GD_LAW_NAME_MAX];
        snprintf(name, sizeof name, "loads[%d]", i);
        gd_law_init(&L[k], &gd_law_load, name);
        L[k].data = &spec->loads[i].law;
        L[k].dof[0] = spec->loads[i].dof;
    }
    for (int i = 0; i < spec->nlaws; i++, k++) {
        L[k] = spec->laws[i];
        const gd_law_type *t = L[k].type;
        if (!t) {
            free(L);
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "laws", "start from gd_law_init",
                                "law %d has no type", i);
        }
        for (int j = 0; j < L[k].ndofs && j < GD_LAW_MAX_DOFS; j++)
            if (L[k].dof[j] < -1 || L[k].dof[j] >= sys->ndof) {
                gd_status st =
                    gd_error_set(err, GD_EINPUT, "", 0, 0, "laws", "use gd_system_dof",
                                 "law '%s' acts on DOF %d, which the system does not have",
                                 L[k].name, L[k].dof[j]);
                free(L);
                return st;
            }
    }
    for (k = 0; k < total; k++) {
        gd_status st = gd_law_check(&L[k], err);
        if (st) {
            free(L);
            return st;
        }
        for (int j = 0; j < L[k].ndofs; j++)
            L[k].rate[j] = dof_rate(sys, L[k].dof[j], speed);
        /* the spin of each side's node: its shaft's nominal speed */
        const gd_law_type *t = L[k].type;
        int per = t->ndirs > 0 ? t->ndirs : 1;
        for (int side = 0; side < (t->two_nodes ? 2 : 1); side++) {
            int d = L[k].dof[side * per];
            const gd_model *m = sys->model;
            L[k].spin[side] =
                d >= 0 ? m->shafts[m->nodes[sys->dof_node[d]].shaft].speed_ratio * speed : 0.0;
        }
    }
    *out = L;
    *n = total;
    return GD_OK;
}
