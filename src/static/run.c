/* The static analysis (geardyn/static.h): K q = f with the held DOFs at 0. The free
 * block is solved on its Jacobi scaling (solve.c), so
 * translations and rotations weigh alike; the holds' reactions are R = K q - f there.
 * With laws that carry load (GD_LAW_SUPPORT) it is K q = f + f_law(q), solved by the
 * system's Newton iteration (system/law_state.c), and R = K q - f - f_law(q). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "static/static_impl.h"
#include "system/system_impl.h"

void gd_static_free(gd_static_result *res)
{
    if (!res) return;
    free(res->q);
    free(res->f);
    free(res->u);
    free(res->bearings);
    free(res->springs);
    free(res->meshes);
    free(res->holds);
    free(res->laws);
    free(res->law_forces);
    free(res);
}

static gd_status alloc_result(const gd_system *sys, gd_static_result **out)
{
    const gd_model *m = sys->model;
    gd_static_result *r = calloc(1, sizeof *r);
    if (!r) return GD_ENOMEM;
    r->ndof = sys->ndof;
    r->nnodes = m->nnodes;
    r->nbearings = m->nbearings;
    r->nsprings = m->nsprings;
    r->nmeshes = m->nmeshes;
    size_t n1 = (size_t)(sys->ndof > 0 ? sys->ndof : 1);
    r->q = calloc(n1, sizeof *r->q);
    r->f = calloc(n1, sizeof *r->f);
    r->u = calloc((size_t)(m->nnodes > 0 ? m->nnodes : 1) * GD_NODE_DOFS, sizeof *r->u);
    r->bearings = calloc((size_t)(m->nbearings > 0 ? m->nbearings : 1), sizeof *r->bearings);
    r->springs = calloc((size_t)(m->nsprings > 0 ? m->nsprings : 1), sizeof *r->springs);
    r->meshes = calloc((size_t)(m->nmeshes > 0 ? m->nmeshes : 1), sizeof *r->meshes);
    r->holds = calloc(n1, sizeof *r->holds);
    r->laws = calloc((size_t)(sys->nlaws > 0 ? sys->nlaws : 1), sizeof *r->laws);
    r->law_forces = calloc(n1, sizeof *r->law_forces);
    *out = r;
    if (!r->q || !r->f || !r->u || !r->bearings || !r->springs || !r->meshes || !r->holds ||
        !r->laws || !r->law_forces)
        return GD_ENOMEM;
    return GD_OK;
}

/* The laws' records at the static state q. */
static void law_outputs(const gd_system *sys, gd_static_result *res)
{
    for (int l = 0; l < sys->nlaws; l++) {
        const gd_law *L = &sys->laws[l];
        gd_static_law *o = &res->laws[res->nlaws++];
        o->name = L->name;
        o->type = L->type->name;
        o->nrecords =
            gd_system_law_records(sys, l, res->speed, res->q, o->records, GD_STATIC_LAW_RECORDS);
        for (int k = 0; k < o->nrecords; k++) {
            o->record_names[k] = L->type->records[k].name;
            o->record_units[k] = L->type->records[k].unit;
        }
    }
}

gd_status gd_static_run(const gd_system *sys, const gd_static_options *opt, gd_static_result **out,
                        gd_error *err)
{
    *out = NULL;
    gd_static_options def;
    if (!opt) {
        gd_static_options_init(&def);
        opt = &def;
    }
    const gd_model *m = sys->model;
    gd_status st = gd_st_check_options(m, opt, err);
    if (st) return st;
    const int n = sys->ndof;
    gd_static_result *res = NULL;
    double *K = malloc((size_t)(n > 0 ? n : 1) * (n > 0 ? n : 1) * sizeof *K);
    int *held = malloc((size_t)(n > 0 ? n : 1) * sizeof *held);
    if (!K || !held || alloc_result(sys, &res)) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto out;
    }
    res->speed = opt->speed >= 0 ? opt->speed : m->speed;
    /* the linear stiffness; the laws add their forces, not a linearisation */
    gd_system_dense_linear(sys, res->speed, NULL, NULL, K);
    if ((st = gd_st_loads(sys, opt, res->f, err))) goto out;
    res->input_node = -1;
    if (opt->input_torque != 0) { /* the total there, the model's own loads included */
        int node = gd_st_input_node(m, opt), i = node >= 0 ? gd_system_dof(sys, node, GD_RZ) : -1;
        if (i >= 0) {
            res->input_node = node;
            res->input_torque_total =
                (m->shafts[m->nodes[node].shaft].speed_ratio < 0 ? -1.0 : 1.0) * res->f[i];
        }
    }
    if (sys->nlaws) {
        double *Kd = malloc((size_t)(n > 0 ? n : 1) * (n > 0 ? n : 1) * sizeof *Kd);
        if (!Kd) {
            st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
            goto out;
        }
        gd_st_supported_stiffness(sys, K, Kd);
        st = gd_st_holds(sys, Kd, opt, held, err);
        free(Kd);
        if (st || (st = gd_st_solve_with_laws(sys, K, res->f, held, res->speed, res->q, err)))
            goto out;
        gd_system_law_forces(sys, res->speed, res->q, res->law_forces);
        law_outputs(sys, res);
    } else if ((st = gd_st_holds(sys, K, opt, held, err)) ||
               (st = gd_st_solve_linear(sys, K, res->f, held, res->q, err))) {
        goto out;
    }
    for (int i = 0; i < n; i++) {
        res->u[(size_t)sys->dof_node[i] * GD_NODE_DOFS + sys->dof_type[i]] = res->q[i];
        if (!held[i]) continue;
        double kq = -res->law_forces[i];
        for (int j = 0; j < n; j++)
            kq += K[i + (size_t)j * n] * res->q[j];
        gd_static_hold *h = &res->holds[res->nholds++];
        h->node = sys->dof_node[i];
        h->dof = sys->dof_type[i];
        h->prescribed = held[i] == GD_ST_PRESCRIBED;
        h->reaction = kq - res->f[i];
    }
    gd_st_outputs(sys, res);
out:
    free(K);
    free(held);
    if (st) {
        gd_static_free(res);
        return st;
    }
    *out = res;
    return GD_OK;
}
