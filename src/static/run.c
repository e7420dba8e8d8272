/* The static analysis (geardyn/static.h): K q = f with the held DOFs at 0. The free
 * block is solved on its Jacobi scaling D K_FF D y = D f_F, q_F = D y (LU, LAPACK), so
 * translations and rotations weigh alike; the holds' reactions are R = K q - f there.
 * With laws that carry load (GD_LAW_SUPPORT) it is K q = f + f_law(q), solved by the
 * system's Newton iteration (system/law_state.c), and R = K q - f - f_law(q). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "static/static_impl.h"
#include "system/system_impl.h"

void gd_static_options_init(gd_static_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->speed = -1;
    opt->input_node = -1;
    opt->hold_node = -1;
    opt->loads = 1;
    opt->gravity = 1;
}

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

static gd_status check_options(const gd_model *m, const gd_static_options *opt, gd_error *err)
{
    if (opt->input_node < -1 || opt->input_node >= m->nnodes)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "input_node", "give a node of the model",
                            "input node %d out of range", opt->input_node);
    if (opt->hold_node < -1 || opt->hold_node >= m->nnodes)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "hold_node", "give a node of the model",
                            "hold node %d out of range", opt->hold_node);
    if (!isfinite(opt->input_torque) || !isfinite(opt->speed))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "", "give finite values",
                            "input torque %g or speed %g is not finite", opt->input_torque,
                            opt->speed);
    return GD_OK;
}

/* q (zeroed) on the free DOFs from K_FF q_F = f_F. */
static gd_status solve(const gd_system *sys, const double *K, const double *f, const int *held,
                       double *q, gd_error *err)
{
    const int n = sys->ndof;
    int nf = 0;
    memset(q, 0, (size_t)n * sizeof *q);
    int *fr = malloc((size_t)(n > 0 ? n : 1) * sizeof *fr);
    double *A = NULL, *d = NULL, *b = NULL;
    lapack_int *piv = NULL;
    gd_status st = GD_OK;
    if (!fr) goto oom;
    for (int i = 0; i < n; i++)
        if (!held[i]) fr[nf++] = i;
    if (nf == 0) goto out;
    A = malloc((size_t)nf * nf * sizeof *A);
    d = malloc((size_t)nf * sizeof *d);
    b = malloc((size_t)nf * sizeof *b);
    piv = malloc((size_t)nf * sizeof *piv);
    if (!A || !d || !b || !piv) goto oom;
    for (int a = 0; a < nf; a++) {
        double kaa = K[fr[a] + (size_t)fr[a] * n];
        d[a] = kaa > 0 ? 1 / sqrt(kaa) : 1;
    }
    for (int c = 0; c < nf; c++)
        for (int a = 0; a < nf; a++)
            A[a + (size_t)c * nf] = d[a] * K[fr[a] + (size_t)fr[c] * n] * d[c];
    for (int a = 0; a < nf; a++)
        b[a] = d[a] * f[fr[a]];
    lapack_int info = LAPACKE_dgesv(LAPACK_COL_MAJOR, nf, 1, A, nf, piv, b, nf);
    if (info != 0) {
        st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "", "",
                          "the held stiffness is singular (LU pivot %d)", (int)info);
        goto out;
    }
    for (int a = 0; a < nf; a++)
        q[fr[a]] = d[a] * b[a];
    goto out;
oom:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
out:
    free(fr);
    free(A);
    free(d);
    free(b);
    free(piv);
    return st;
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

/* Kd = K with a small grounded stiffness on every direction a supporting law acts on, so
 * that the hold search counts those directions as held (a rotor on journal bearings has
 * no bearing element but is not free): 1e-6 of the largest diagonal, far above the
 * null-space threshold of holds.c (1e-10) and far below any real stiffness's effect on
 * it. */
static void supported_stiffness(const gd_system *sys, const double *K, double *Kd)
{
    const size_t n = (size_t)sys->ndof;
    memcpy(Kd, K, n * n * sizeof *Kd);
    double kmax = 0;
    for (size_t i = 0; i < n; i++)
        kmax = fmax(kmax, fabs(K[i + i * n]));
    const double kreg = 1e-6 * (kmax > 0 ? kmax : 1.0);
    for (int l = 0; l < sys->nlaws; l++) {
        const gd_law *L = &sys->laws[l];
        if (!(L->type->flags & GD_LAW_SUPPORT)) continue;
        for (int a = 0; a < L->ndofs; a++)
            if (L->dof[a] >= 0) Kd[(size_t)L->dof[a] * (n + 1)] += kreg;
    }
}

/* q from K q = f + f_law(q) with the held DOFs at 0, from the linear solution where
 * the linear stiffness alone holds the model, else from rest. */
static gd_status solve_with_laws(const gd_system *sys, const double *K, const double *f,
                                 const int *held, double speed, double *q, gd_error *err)
{
    gd_error quiet = {0};
    if (solve(sys, K, f, held, q, &quiet)) memset(q, 0, (size_t)sys->ndof * sizeof *q);
    double res = 0;
    if (gd_system_law_equilibrium(sys, speed, K, f, held, q, &res)) return GD_OK;
    double *q0 = calloc((size_t)(sys->ndof > 0 ? sys->ndof : 1), sizeof *q0);
    if (!q0) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    double res0 = 0;
    int found = gd_system_law_equilibrium(sys, speed, K, f, held, q0, &res0);
    if (found || res0 < res) memcpy(q, q0, (size_t)sys->ndof * sizeof *q);
    free(q0);
    if (found) return GD_OK;
    return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "laws",
                        "a journal bearing carries load only while the shaft turns: give a "
                        "speed (--speed) or a bearing that holds the shaft at rest",
                        "the laws find no static equilibrium at %g rad/s (relative residual "
                        "%.3g after Newton's iterations)",
                        speed, fmin(res, res0));
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
    gd_status st = check_options(m, opt, err);
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
        supported_stiffness(sys, K, Kd);
        st = gd_st_holds(sys, Kd, opt, held, err);
        free(Kd);
        if (st || (st = solve_with_laws(sys, K, res->f, held, res->speed, res->q, err))) goto out;
        gd_system_law_forces(sys, res->speed, res->q, res->law_forces);
        law_outputs(sys, res);
    } else if ((st = gd_st_holds(sys, K, opt, held, err)) ||
               (st = solve(sys, K, res->f, held, res->q, err))) {
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
