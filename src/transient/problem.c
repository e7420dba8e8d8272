/* Building the transient problem once: matrices at the speed, free/prescribed
 * partition, sparse Cholesky of the free mass block, preconditioner pattern, element
 * data (mesh vectors, DOF indices, unbalance forces, the laws' inertia update). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model.h"
#include "transient/transient_impl.h"

static gd_status fail(gd_error *err, gd_status st, const char *field, const char *hint,
                      const char *msg)
{
    return gd_error_set(err, st, "", 0, 0, field, hint, "%s", msg);
}

void gd_tr_mesh_init(const gd_system *sys, int mesh, gd_tr_mesh *m)
{
    memset(m, 0, sizeof *m);
    m->mesh = mesh;
    m->coast_scale = 1.0;
    const gd_model *model = sys->model;
    int set, ring, n;
    if (gd_model_planetary_mesh(model, mesh, &set, &ring, &n)) {
        m->stiffness = model->planetary[set].mesh_stiffness[ring];
        m->damping = model->planetary[set].mesh_damping[ring];
        return;
    }
    if (mesh < 0 || mesh >= model->nmeshes) return;
    const gd_mesh *gm = &model->meshes[mesh];
    m->stiffness = gm->stiffness;
    m->damping = gm->damping;
}

/* Dense column-major n x n to CSC, dropping zeros. */
cs *gd_tr_cs_from_dense(int n, const double *A)
{
    int nz = 0;
    for (long k = 0; k < (long)n * n; k++)
        if (A[k] != 0.0) nz++;
    cs *T = cs_spalloc(n, n, nz > 0 ? nz : 1, 1, 1);
    if (!T) return NULL;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            if (A[(long)j * n + i] != 0.0) cs_entry(T, i, j, A[(long)j * n + i]);
    cs *C = cs_compress(T);
    cs_spfree(T);
    return C;
}

cs *gd_tr_cs_block(const cs *A, const int *rmap, const int *cmap, int nr, int nc)
{
    cs *T = cs_spalloc(nr, nc, A->p[A->n] > 0 ? A->p[A->n] : 1, 1, 1);
    if (!T) return NULL;
    for (int j = 0; j < A->n; j++) {
        if (cmap[j] < 0) continue;
        for (int p = A->p[j]; p < A->p[j + 1]; p++)
            if (rmap[A->i[p]] >= 0 && !cs_entry(T, rmap[A->i[p]], cmap[j], A->x[p])) {
                cs_spfree(T);
                return NULL;
            }
    }
    cs *C = cs_compress(T);
    cs_spfree(T);
    if (C && !cs_dupl(C)) {
        cs_spfree(C);
        return NULL;
    }
    return C;
}

/* map[k] = position in S of entry k of A (same pattern subset). */
static int *pattern_map(const cs *A, const cs *S, int *mark)
{
    int *map = malloc((size_t)(A->p[A->n] > 0 ? A->p[A->n] : 1) * sizeof *map);
    if (!map) return NULL;
    for (int j = 0; j < A->n; j++) {
        for (int p = S->p[j]; p < S->p[j + 1]; p++)
            mark[S->i[p]] = p;
        for (int p = A->p[j]; p < A->p[j + 1]; p++)
            map[p] = mark[A->i[p]];
    }
    return map;
}

static int is_prescribed(const gd_transient_spec *spec, int dof)
{
    for (int i = 0; i < spec->nprescribed; i++)
        if (spec->prescribed[i].dof == dof) return 1;
    return 0;
}

/* The free blocks of M, K, D, the Cholesky factor of M_ff and the pattern of
 * M_ff + g D_ff + g^2 K_ff with its symbolic LU, from tr->M, K, D and the partition. */
gd_status gd_tr_linear_setup(gd_transient *tr, gd_error *err)
{
    tr->Mff = gd_tr_cs_block(tr->M, tr->fidx, tr->fidx, tr->nf, tr->nf);
    tr->Kff = gd_tr_cs_block(tr->K, tr->fidx, tr->fidx, tr->nf, tr->nf);
    tr->Dff = gd_tr_cs_block(tr->D, tr->fidx, tr->fidx, tr->nf, tr->nf);
    if (!tr->Mff || !tr->Kff || !tr->Dff) return GD_ENOMEM;
    tr->Msym = cs_schol(1, tr->Mff);
    if (!tr->Msym) return GD_ENOMEM;
    tr->Mnum = cs_chol(tr->Mff, tr->Msym);
    if (!tr->Mnum)
        return fail(err, GD_ENUMERIC, "dofs", "check the masses and inertias",
                    "the mass matrix of the free DOFs is not positive definite");
    /* preconditioner pattern */
    {
        cs *MD = cs_add(tr->Mff, tr->Dff, 1.0, 1.0);
        if (!MD) return GD_ENOMEM;
        tr->S = cs_add(MD, tr->Kff, 1.0, 1.0);
        cs_spfree(MD);
        int *mark = malloc((size_t)tr->nf * sizeof *mark);
        if (!tr->S || !mark) {
            free(mark);
            return GD_ENOMEM;
        }
        tr->mapM = pattern_map(tr->Mff, tr->S, mark);
        tr->mapD = pattern_map(tr->Dff, tr->S, mark);
        tr->mapK = pattern_map(tr->Kff, tr->S, mark);
        free(mark);
        if (!tr->mapM || !tr->mapD || !tr->mapK) return GD_ENOMEM;
        tr->Ssym = cs_sqr(1, tr->S, 0);
        if (!tr->Ssym) return GD_ENOMEM;
    }

    return GD_OK;
}

gd_status gd_transient_new(const gd_system *sys, const gd_transient_spec *spec, double speed,
                           gd_transient **out, gd_error *err)
{
    *out = NULL;
    const gd_model *model = sys->model;
    const int n = sys->ndof;
    char buf[GD_NODE_NAME_MAX + 8], msg[256];
    if (!isfinite(speed)) return fail(err, GD_EINPUT, "speed", "", "speed must be finite");
    for (int i = 0; i < spec->nprescribed; i++) {
        int d = spec->prescribed[i].dof;
        if (d < 0 || d >= n)
            return fail(err, GD_EINPUT, "prescribed", "use gd_system_dof", "no such DOF");
        if (spec->prescribed[i].law.kind == GD_PRESCRIBED_TABLE && !spec->prescribed[i].law.table)
            return fail(err, GD_EINPUT, "prescribed", "", "prescribed table missing");
        for (int j = 0; j < i; j++)
            if (spec->prescribed[j].dof == d)
                return fail(err, GD_EINPUT, "prescribed", "", "a DOF is prescribed twice");
    }
    for (int i = 0; i < spec->nmeshes; i++) {
        const gd_tr_mesh *m = &spec->meshes[i];
        if (m->mesh < 0 || m->mesh >= gd_model_mesh_count(model))
            return fail(err, GD_EINPUT, "meshes", "", "no such mesh");
        if (m->backlash && !(m->gap >= 0))
            return fail(err, GD_EINPUT, "meshes.backlash", "", "backlash gap must be >= 0");
        for (int j = 0; j < i; j++)
            if (spec->meshes[j].mesh == m->mesh)
                return fail(err, GD_EINPUT, "meshes", "", "a mesh is described twice");
    }
    for (int i = 0; i < spec->nloads; i++)
        if (spec->loads[i].dof < 0 || spec->loads[i].dof >= n ||
            (spec->loads[i].law.kind == GD_LOAD_TABLE_ANGLE && !spec->loads[i].law.table))
            return fail(err, GD_EINPUT, "loads", "", "load on no DOF, or table missing");
    for (int i = 0; i < spec->nsfds; i++) {
        const gd_tr_sfd *s = &spec->sfds[i];
        if (s->node < 0 || s->node >= model->nnodes || s->node2 >= model->nnodes ||
            s->node == s->node2)
            return fail(err, GD_EINPUT, "sfd", "", "damper node missing");
        const gd_sfd_params *p = &s->params;
        if (!(p->viscosity > 0 && p->radius > 0 && p->length > 0 && p->clearance > 0))
            return fail(err, GD_EINPUT, "sfd", "give viscosity, radius, length, clearance > 0",
                        "damper parameters must be positive");
        if (gd_system_dof(sys, s->node, GD_X) < 0 || gd_system_dof(sys, s->node, GD_Y) < 0)
            return fail(err, GD_EINPUT, "sfd", "keep x and y in the model's dofs",
                        "damper node has no active x and y DOFs");
    }

    gd_transient *tr = calloc(1, sizeof *tr);
    if (!tr) return fail(err, GD_ENOMEM, "", "", "out of memory");
    gd_status st = GD_ENOMEM;
    tr->sys = sys;
    tr->n = n;
    tr->speed = speed;
    tr->fidx = malloc((size_t)n * sizeof *tr->fidx);
    tr->rate = calloc((size_t)n, sizeof *tr->rate);
    tr->ratio = calloc((size_t)n, sizeof *tr->ratio);
    tr->q = calloc((size_t)n, sizeof *tr->q);
    tr->v = calloc((size_t)n, sizeof *tr->v);
    tr->acc = calloc((size_t)n, sizeof *tr->acc);
    tr->r = calloc((size_t)n, sizeof *tr->r);
    tr->w1 = calloc((size_t)n, sizeof *tr->w1);
    tr->w2 = calloc((size_t)n, sizeof *tr->w2);
    if (!tr->fidx || !tr->rate || !tr->ratio || !tr->q || !tr->v || !tr->acc || !tr->r || !tr->w1 ||
        !tr->w2)
        goto fail;
    for (int i = 0; i < n; i++) {
        tr->fidx[i] = is_prescribed(spec, i) ? -1 : tr->nf++;
        if (sys->dof_type[i] == GD_RZ) {
            tr->ratio[i] = model->shafts[model->nodes[sys->dof_node[i]].shaft].speed_ratio;
            tr->rate[i] = tr->ratio[i] * speed;
        }
    }
    tr->np = n - tr->nf;
    if (tr->nf == 0) {
        st =
            fail(err, GD_EINPUT, "prescribed", "", "every DOF is prescribed: nothing to integrate");
        goto fail;
    }
    tr->free_dof = malloc((size_t)tr->nf * sizeof *tr->free_dof);
    if (!tr->free_dof) goto fail;
    for (int i = 0; i < n; i++)
        if (tr->fidx[i] >= 0) tr->free_dof[tr->fidx[i]] = i;
    for (int i = 0; i < n; i++)
        if (tr->fidx[i] >= 0 && sys->massless[i]) {
            gd_system_dof_label(sys, i, buf, (int)sizeof buf);
            snprintf(msg, sizeof msg,
                     "DOF %s has no mass: time integration needs mass on every free DOF", buf);
            st = fail(err, GD_EINPUT, "dofs",
                      "give the node a mass or inertia, or prescribe the DOF", msg);
            goto fail;
        }
    if (spec->nprescribed) {
        tr->pres = malloc((size_t)spec->nprescribed * sizeof *tr->pres);
        if (!tr->pres) goto fail;
        memcpy(tr->pres, spec->prescribed, (size_t)spec->nprescribed * sizeof *tr->pres);
    }

    /* matrices at the speed */
    cs Kv = gd_tr_cs_view(&sys->K), Cv = gd_tr_cs_view(&sys->C), Gv = gd_tr_cs_view(&sys->G),
       Mv = gd_tr_cs_view(&sys->M);
    tr->M = cs_add(&Mv, &Mv, 1.0, 0.0);
    tr->Gy = cs_add(&Gv, &Gv, 1.0, 0.0); /* a run-up's (W(t) - W) G */
    if (!tr->Gy) goto fail;
    if (sys->has_speed_dependent) {
        /* sparse K + K_b(W), C + C_b(W): memory linear in the DOFs */
        gd_csc Ks = {0}, Cs = {0};
        if (!gd_system_matrices(sys, speed, NULL, &Ks, &Cs, NULL, NULL)) {
            cs Kb = gd_tr_cs_view(&Ks), Cb = gd_tr_cs_view(&Cs);
            tr->K = cs_add(&Kb, &Kb, 1.0, 0.0);
            tr->D = cs_add(&Cb, &Gv, 1.0, speed);
        }
        gd_csc_free(&Ks);
        gd_csc_free(&Cs);
    } else {
        tr->K = cs_add(&Kv, &Kv, 1.0, 0.0);
        tr->D = cs_add(&Cv, &Gv, 1.0, speed);
    }
    if (!tr->M || !tr->K || !tr->D) goto fail;
    if ((st = gd_tr_linear_setup(tr, err))) goto fail;
    st = GD_ENOMEM;
    /* meshes */
    tr->nmodel_mesh = model->nmeshes;
    if (model->nmeshes) {
        tr->model_a = malloc((size_t)model->nmeshes * sizeof *tr->model_a);
        if (!tr->model_a) goto fail;
        for (int k = 0; k < model->nmeshes; k++)
            gd_system_mesh_vector(sys, k, &tr->model_a[k]);
    }
    tr->nall_mesh = gd_model_mesh_count(model);
    tr->nl_of_mesh =
        malloc((size_t)(tr->nall_mesh > 0 ? tr->nall_mesh : 1) * sizeof *tr->nl_of_mesh);
    if (!tr->nl_of_mesh) goto fail;
    for (int k = 0; k < tr->nall_mesh; k++)
        tr->nl_of_mesh[k] = -1;
    /* the laws of the registry: meshes, dampers, loads, the spec's laws */
    if ((st = gd_transient_spec_laws(sys, spec, speed, &tr->law, &tr->nlaw, err))) goto fail;
    st = GD_ENOMEM;
    tr->nmesh = spec->nmeshes;
    tr->nsfd_law = spec->nsfds;
    tr->law_spec0 = spec->nmeshes + spec->nsfds + spec->nloads;
    for (int i = 0; i < tr->nmesh; i++)
        tr->nl_of_mesh[spec->meshes[i].mesh] = i;
    for (int i = 0; i < tr->nlaw; i++)
        tr->nroot += gd_law_nswitches(&tr->law[i]);
    tr->law_order = malloc((size_t)(tr->nlaw > 0 ? tr->nlaw : 1) * sizeof *tr->law_order);
    if (!tr->law_order) goto fail;
    for (int pass = 0, k = 0; pass < 2; pass++)
        for (int i = 0; i < tr->nlaw; i++)
            if (!(tr->law[i].type->flags & GD_LAW_ASSEMBLED) == !pass) {
                tr->law_order[k++] = i;
                if (!pass) tr->nlaw_plain = k;
            }
    if (tr->nlaw) { /* the ratios of the laws' rates and spins (a run-up's) */
        const int stride = GD_LAW_MAX_DOFS + 2;
        tr->law_ratio = calloc((size_t)tr->nlaw * stride, sizeof *tr->law_ratio);
        if (!tr->law_ratio) goto fail;
        for (int i = 0; i < tr->nlaw; i++) {
            const gd_law *L = &tr->law[i];
            double *r = tr->law_ratio + (size_t)i * stride;
            for (int j = 0; j < L->ndofs; j++)
                r[j] = L->dof[j] >= 0 ? tr->ratio[L->dof[j]] : 0.0;
            int per = L->type->ndirs > 0 ? L->type->ndirs : 1;
            for (int side = 0; side < (L->type->two_nodes ? 2 : 1); side++) {
                int d = L->dof[side * per];
                r[GD_LAW_MAX_DOFS + side] =
                    d >= 0 ? model->shafts[model->nodes[sys->dof_node[d]].shaft].speed_ratio : 0.0;
            }
        }
    }
    /* unbalances */
    if (spec->unbalances && model->nunbalances) {
        tr->unb = calloc((size_t)model->nunbalances, sizeof *tr->unb);
        if (!tr->unb) goto fail;
        for (int i = 0; i < model->nunbalances; i++) {
            const gd_unbalance *u = &model->unbalances[i];
            double ratio = model->shafts[model->nodes[u->node].shaft].speed_ratio;
            double w = ratio * speed;
            int dx = gd_system_dof(sys, u->node, GD_X), dy = gd_system_dof(sys, u->node, GD_Y);
            /* a run-up turns a shaft at reference speed 0: keep it (nunb_all) */
            if (ratio == 0.0 || (dx < 0 && dy < 0)) continue;
            tr_unb *b = &tr->unb[tr->nunb_all++];
            b->ratio = ratio;
            b->amount = u->amount;
            b->phase0 = u->phase;
            b->dx = dx;
            b->dy = dy;
            b->omega = w;
            b->force = u->amount * w * w;
            b->phase = w > 0 ? u->phase : -u->phase;
        }
        tr->nunb = speed != 0.0 ? tr->nunb_all : 0;
    }
    /* the laws' inertias (GD_LAW_INERTIA): a slot per distinct free DOF, and the
     * Woodbury identity's M_ff^-1 e_j (Z) and E^T Z (G) */
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        if (!L->type->inertia || !(gd_law_flags(L) & GD_LAW_INERTIA)) continue;
        if (!tr->in_code) {
            tr->in_code = calloc((size_t)tr->nlaw, sizeof *tr->in_code);
            tr->in_slot = malloc((size_t)tr->nlaw * GD_LAW_MAX_DOFS * sizeof *tr->in_slot);
            tr->in_free = malloc((size_t)tr->nf * sizeof *tr->in_free);
            if (!tr->in_code || !tr->in_slot || !tr->in_free) goto fail;
        }
        int *slot = tr->in_slot + (size_t)i * GD_LAW_MAX_DOFS;
        for (int j = 0; j < L->ndofs; j++) {
            int f = L->dof[j] >= 0 ? tr->fidx[L->dof[j]] : -1;
            slot[j] = -1;
            if (f < 0) continue;
            for (int k = 0; k < tr->nin; k++)
                if (tr->in_free[k] == f) slot[j] = k;
            if (slot[j] < 0) {
                slot[j] = tr->nin;
                tr->in_free[tr->nin++] = f;
            }
        }
        tr->in_code[i] = 2 + slot[0];
    }
    if (tr->nin) {
        int k = tr->nin;
        tr->Z = calloc((size_t)tr->nf * k, sizeof *tr->Z);
        tr->G = calloc((size_t)k * k, sizeof *tr->G);
        tr->mu = calloc((size_t)k, sizeof *tr->mu);
        tr->A = calloc((size_t)k * k, sizeof *tr->A);
        tr->wv = calloc((size_t)k, sizeof *tr->wv);
        if (!tr->Z || !tr->G || !tr->mu || !tr->A || !tr->wv) goto fail;
        for (int j = 0; j < k; j++) {
            memset(tr->w1, 0, (size_t)tr->nf * sizeof *tr->w1);
            tr->w1[tr->in_free[j]] = 1.0;
            gd_tr_mass_solve(tr, tr->w1, tr->Z + (size_t)j * tr->nf);
        }
        for (int i = 0; i < k; i++)
            for (int j = 0; j < k; j++)
                tr->G[i + j * k] = tr->Z[(size_t)j * tr->nf + tr->in_free[i]];
    }
    *out = tr;
    return GD_OK;
fail:
    gd_transient_free(tr);
    if (st == GD_ENOMEM) return fail(err, GD_ENOMEM, "", "", "out of memory");
    return st;
}

void gd_tr_release_linear(gd_transient *tr)
{
    cs_spfree(tr->K);
    cs_spfree(tr->D);
    cs_spfree(tr->M);
    cs_spfree(tr->Mff);
    cs_spfree(tr->Kff);
    cs_spfree(tr->Dff);
    cs_sfree(tr->Msym);
    cs_nfree(tr->Mnum);
    cs_spfree(tr->S);
    free(tr->mapM);
    free(tr->mapD);
    free(tr->mapK);
    cs_sfree(tr->Ssym);
    cs_nfree(tr->Snum);
    tr->K = tr->D = tr->M = tr->Mff = tr->Kff = tr->Dff = tr->S = NULL;
    tr->Msym = tr->Ssym = NULL;
    tr->Mnum = tr->Snum = NULL;
    tr->mapM = tr->mapD = tr->mapK = NULL;
}

void gd_transient_free(gd_transient *tr)
{
    if (!tr) return;
    free(tr->fidx);
    free(tr->free_dof);
    free(tr->pres);
    free(tr->rate);
    free(tr->ratio);
    free(tr->prof_cum);
    free(tr->law_ratio);
    for (int j = 0; j < tr->nsd; j++) { /* a run-up's, normally freed at its end */
        cs_spfree(tr->sd_K[j]);
        cs_spfree(tr->sd_C[j]);
    }
    free(tr->sd_K);
    free(tr->sd_C);
    cs_spfree(tr->Gy);
    gd_tr_release_linear(tr);
    gd_tr_reduction_free(tr->red);
    if (tr->cond) tr->cond_free(tr->cond);
    free(tr->model_a);
    free(tr->nl_of_mesh);
    free(tr->law_order);
    free(tr->law);
    free(tr->unb);
    free(tr->in_code);
    free(tr->in_slot);
    free(tr->in_free);
    free(tr->Z);
    free(tr->G);
    free(tr->mu);
    free(tr->A);
    free(tr->wv);
    free(tr->q);
    free(tr->v);
    free(tr->acc);
    free(tr->r);
    free(tr->w1);
    free(tr->w2);
    free(tr->term);
    free(tr);
}

int gd_transient_nstates(const gd_transient *tr)
{
    if (tr->cond) return tr->cond->ns;
    return 2 * tr->nf;
}

int gd_transient_nswitches(const gd_transient *tr)
{
    return tr->nroot;
}

int gd_transient_mode_records(const gd_transient *tr, gd_tr_record *rec, int cap)
{
    int n = 0;
    for (int i = 0; i < tr->nmesh && n < cap; i++) {
        if (!gd_law_nswitches(&tr->law[i])) continue;
        for (int m = 0; m < tr->nall_mesh; m++)
            if (tr->nl_of_mesh[m] == i) rec[n++] = (gd_tr_record){GD_REC_MESH_STATE, m, 0};
    }
    return n;
}

/* The reduction the problem owns (reduce.c makes it). */
void gd_tr_reduction_free(gd_tr_reduction *r)
{
    if (!r) return;
    free(r->kept);
    free(r->irow);
    free(r->rate);
    free(r->TI);
    free(r->MTI);
    free(r);
}
