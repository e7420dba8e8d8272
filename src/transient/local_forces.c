/* The local form of the forces, f(t, q, q') = M_ff q'' + D_ff q' + K_ff q, with its
 * derivatives as rank-one terms (transient.h): what harmonic balance evaluates in the
 * time domain (alternating frequency-time) and what the variational equations need. The
 * forces are the integrator's own (gd_tr_residual); only the contact state is taken from
 * the deformation instead of being frozen between located events. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "transient/transient_impl.h"

/* Appends the free part of coef * e_dof to a term vector. */
static void vec_add(int *n, int *idx, double *val, const gd_transient *tr, int dof, double coef)
{
    if (dof < 0 || tr->fidx[dof] < 0 || coef == 0.0) return;
    int f = tr->fidx[dof];
    for (int k = 0; k < *n; k++)
        if (idx[k] == f) {
            val[k] += coef;
            return;
        }
    idx[*n] = f;
    val[*n] = coef;
    (*n)++;
}

static void term_u(gd_tr_term *t, const gd_transient *tr, int dof, double coef)
{
    vec_add(&t->nu, t->u_idx, t->u, tr, dof, coef);
}

static void term_w(gd_tr_term *t, const gd_transient *tr, int dof, double coef)
{
    vec_add(&t->nw, t->w_idx, t->w, tr, dof, coef);
}

/* Appends law L's terms. */
static void law_terms(gd_transient *tr, const gd_law *L, int *n)
{
    for (int k = 0; k < L->type->nterms; k++) {
        double u[GD_LAW_MAX_DOFS] = {0}, w[GD_LAW_MAX_DOFS] = {0};
        L->type->term(L, k, u, w);
        gd_tr_term *t = &tr->term[(*n)++];
        for (int j = 0; j < L->ndofs; j++) {
            term_u(t, tr, L->dof[j], u[j]);
            term_w(t, tr, L->dof[j], w[j]);
        }
    }
}

/* 1 when law L has an assembled linear part (its terms come first). */
static int assembled(const gd_law *L)
{
    return (L->type->flags & GD_LAW_ASSEMBLED) != 0;
}

/* Terms in the order: laws with an assembled part (meshes), then the others in law
 * order. -1 with a configuration-dependent inertia on a free DOF (the local form has
 * the constant M_ff only). */
static int build_terms(gd_transient *tr)
{
    if (tr->nin) return -1;
    int cap = 0;
    for (int i = 0; i < tr->nlaw; i++)
        cap += tr->law[i].type->nterms;
    tr->term = calloc((size_t)(cap > 0 ? cap : 1), sizeof *tr->term);
    if (!tr->term) return -2;
    int n = 0;
    for (int i = 0; i < tr->nlaw; i++)
        if (assembled(&tr->law[i])) law_terms(tr, &tr->law[i], &n);
    for (int i = 0; i < tr->nlaw; i++)
        if (!assembled(&tr->law[i])) law_terms(tr, &tr->law[i], &n);
    return n;
}

int gd_transient_terms(gd_transient *tr, const gd_tr_term **terms)
{
    if (!tr->term && tr->nterm == 0) tr->nterm = build_terms(tr);
    if (terms) *terms = tr->term;
    return tr->nterm;
}

static gd_csc csc_view(const cs *A)
{
    gd_csc v = {A->n, A->p, A->i, A->x};
    return v;
}

void gd_transient_matrices(const gd_transient *tr, gd_csc *M, gd_csc *D, gd_csc *K)
{
    if (M) *M = csc_view(tr->Mff);
    if (D) *D = csc_view(tr->Dff);
    if (K) *K = csc_view(tr->Kff);
}

/* The term coefficients of the laws with (assembled = 1) or without an assembled part,
 * in build_terms' order, from sq[*n], sv[*n]. */
static void law_coefs(gd_transient *tr, double t, int with_assembled, double *sq, double *sv,
                      int *n)
{
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        if (assembled(L) != with_assembled) continue;
        int nt = L->type->nterms;
        double jq[GD_LAW_MAX_TERMS], jv[GD_LAW_MAX_TERMS];
        gd_law_point x;
        gd_tr_law_point(L, gd_tr_law_t(tr, i, t), tr->q, tr->v, tr->lq, tr->lv, &x);
        memset(tr->lf, 0, (size_t)L->ndofs * sizeof *tr->lf);
        L->type->force(L, &x, tr->lf, jq, jv);
        for (int k = 0; k < nt; k++, (*n)++) {
            if (sq) sq[*n] = jq[k];
            if (sv) sv[*n] = jv[k];
        }
    }
}

void gd_transient_local(gd_transient *tr, double t, const double *y, double *f, double *sq,
                        double *sv)
{
    const int nf = tr->nf;
    gd_tr_fill(tr, t, y, tr->q, tr->v, tr->acc);
    /* the laws' modes from the motion (not frozen between located events) */
    for (int i = 0; i < tr->nlaw; i++) {
        gd_law *L = &tr->law[i];
        if (!L->type->mode_at) continue;
        gd_law_point x;
        gd_tr_law_here(tr, L, gd_tr_law_t(tr, i, t), &x);
        L->mode = L->type->mode_at(L, &x);
    }
    if (f) {
        gd_tr_forces(tr, t, tr->q, tr->v, tr->acc, tr->r, 1);
        for (int i = 0; i < nf; i++)
            f[i] = tr->r[tr->free_dof[i]];
    }
    if (!sq && !sv) return;
    if (gd_transient_terms(tr, NULL) < 0) return;
    int n = 0;
    law_coefs(tr, t, 1, sq, sv, &n);
    law_coefs(tr, t, 0, sq, sv, &n);
}

double gd_transient_record_value(gd_transient *tr, const gd_tr_record *rec, double t,
                                 const double *y)
{
    double v;
    gd_transient_record_values(tr, rec, 1, t, y, &v);
    return v;
}

void gd_transient_record_values(gd_transient *tr, const gd_tr_record *rec, int nrec, double t,
                                const double *y, double *out)
{
    gd_transient_local(tr, t, y, NULL, NULL, NULL);
    for (int r = 0; r < nrec; r++)
        out[r] = gd_tr_record_value(tr, &rec[r], t, tr->q, tr->v);
}

/* Appends the free index of full DOF d (if free). 0 ok, 1 full. */
static int put_dof(const gd_transient *tr, int d, int *idx, int cap, int *n)
{
    if (d < 0 || tr->fidx[d] < 0) return 0;
    if (*n >= cap) return 1;
    idx[(*n)++] = tr->fidx[d];
    return 0;
}

int gd_transient_record_dofs(const gd_transient *tr, const gd_tr_record *rec, int *idx, int cap)
{
    if (tr->red) return -1;
    int n = 0, full = 0, i = rec->index;
    switch (rec->kind) {
    case GD_REC_SPEED_RATIO:
        full |= put_dof(tr, rec->index2, idx, cap, &n);
        /* fall through */
    case GD_REC_DISP:
    case GD_REC_VEL:
    case GD_REC_ANGLE:
    case GD_REC_SPEED:
        full |= put_dof(tr, i, idx, cap, &n);
        break;
    case GD_REC_MESH_FORCE:
    case GD_REC_MESH_DEFLECTION:
    case GD_REC_MESH_STATE:
    case GD_REC_MESH_STIFFNESS: {
        int nl = tr->nl_of_mesh[i];
        if (nl < 0) {
            const gd_mesh_vector *a = &tr->model_a[i];
            for (int j = 0; j < a->n; j++)
                full |= put_dof(tr, a->dof[j], idx, cap, &n);
            break;
        }
        /* the mesh vector's DOFs, then the driver's (its angle) */
        const gd_law *L = &tr->law[nl];
        const gd_mesh_law_data *m = L->data;
        for (int j = 0; j < m->na; j++)
            full |= put_dof(tr, L->dof[j], idx, cap, &n);
        if (m->drv >= 0) full |= put_dof(tr, L->dof[m->drv], idx, cap, &n);
        break;
    }
    case GD_REC_SFD_FX:
    case GD_REC_SFD_FY:
    case GD_REC_SFD_ECCENTRICITY:
    case GD_REC_LAW: {
        const gd_law *L = &tr->law[rec->kind == GD_REC_LAW ? tr->law_spec0 + i : tr->nmesh + i];
        for (int j = 0; j < L->ndofs; j++)
            full |= put_dof(tr, L->dof[j], idx, cap, &n);
        break;
    }
    default:
        return -1;
    }
    return full ? -1 : n;
}

void gd_transient_hold_drive(gd_transient *tr, double hold)
{
    for (int i = 0; i < tr->nlaw; i++)
        if (tr->law[i].type->nswitches > 0)
            tr->law[i].hold = hold > 0 ? (hold < 1 ? hold : 1.0) : 0.0;
}
