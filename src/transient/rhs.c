/* The right-hand side y' = f(t, y) of the first-order form y = [q_f; q_f'], the root
 * functions (the laws' switches: a backlash mesh's flanks) and the preconditioner. Nothing here
 * allocates. */
#include <math.h>
#include <string.h>

#include "transient/transient_impl.h"

void gd_tr_fill(gd_transient *tr, double t, const double *y, double *q, double *v, double *acc)
{
    const int nf = tr->nf;
    if (tr->cond) { /* the state is the condensed model's (condensed.c) */
        tr->cond_fill(tr, t, y, q, v, 1);
        if (acc) memset(acc, 0, (size_t)tr->n * sizeof *acc);
    }
    for (int f = 0; !tr->cond && f < nf; f++) {
        int i = tr->free_dof[f];
        q[i] = y[f];
        v[i] = y[nf + f];
        if (acc) acc[i] = 0.0;
    }
    for (int k = 0; k < tr->np; k++) {
        int d = tr->pres[k].dof;
        double a;
        gd_prescribed_eval(&tr->pres[k].law, t, tr->rate[d], &q[d], &v[d], &a);
        if (acc) acc[d] = a;
    }
}

void gd_tr_law_point(const gd_law *L, double t, const double *q, const double *v, double *lq,
                     double *lv, gd_law_point *x)
{
    for (int j = 0; j < L->ndofs; j++) {
        int d = L->dof[j];
        lq[j] = d >= 0 ? q[d] : 0.0;
        lv[j] = d >= 0 ? v[d] : 0.0;
    }
    x->t = t;
    x->q = lq;
    x->v = lv;
}

void gd_tr_law_here(gd_transient *tr, const gd_law *L, double t, gd_law_point *x)
{
    gd_tr_law_point(L, t, tr->q, tr->v, tr->lq, tr->lv, x);
}

/* r -= A[:, j] x_j */
static void sub_col(const cs *A, int j, const double *x, double *r)
{
    double xj = x[j];
    if (xj == 0.0) return;
    for (int p = A->p[j]; p < A->p[j + 1]; p++)
        r[A->i[p]] -= A->x[p] * xj;
}

/* r -= A x over the whole matrix */
static void sub_mul(const cs *A, const double *x, double *r)
{
    for (int j = 0; j < A->n; j++)
        sub_col(A, j, x, r);
}

/* r -= A x over the columns of the prescribed DOFs (the others are fixed at zero or
 * free) */
static void sub_mul_prescribed(const gd_transient *tr, const cs *A, const double *x, double *r)
{
    for (int k = 0; k < tr->np; k++)
        sub_col(A, tr->pres[k].dof, x, r);
}

/* r += the registry laws' forces at (t, q, q') (and their inertias, GD_LAW_INERTIA, on
 * the absolute acceleration: q'' and, in a run-up, the nominal ratio W' where dw = W' is
 * not 0): those with an assembled linear part (GD_LAW_ASSEMBLED: the difference from it, after
 * the linear terms) when assembled, else the others. */
static void add_law_forces(gd_transient *tr, double t, const double *q, const double *v,
                           const double *acc, double dw, double *r, int assembled)
{
    double lq[GD_LAW_MAX_DOFS], lv[GD_LAW_MAX_DOFS], lf[GD_LAW_MAX_DOFS]; /* no aliasing */
    const int k0 = assembled ? tr->nlaw_plain : 0, k1 = assembled ? tr->nlaw : tr->nlaw_plain;
    for (int k = k0; k < k1; k++) {
        const int i = tr->law_order[k];
        const gd_law *L = &tr->law[i];
        const double tl = gd_tr_law_t(tr, i, t); /* the law's own time */
        const gd_law_point x = {tl, lq, lv};
        const int n = L->ndofs;
        const int inert = tr->in_code ? tr->in_code[i] : 0; /* 0: no inertia */
        if (n == 1) { /* one DOF (a load, a cam): its force added to r in place */
            const int d = L->dof[0];
            if (d < 0) continue; /* on an absent DOF: no force */
            const gd_law_point x1 = {tl, q + d, v + d};
            if (!inert) {
                L->type->force(L, &x1, r + d, NULL, NULL);
                continue;
            }
            double m = 0.0;
            L->type->inertia(L, &x1, r + d, &m);
            if (dw != 0.0) r[d] -= m * tr->ratio[d] * dw;
            if (inert >= 2)
                tr->mu[inert - 2] += m;
            else
                r[d] -= m * acc[d];
            continue;
        }
        for (int j = 0; j < n; j++) {
            int d = L->dof[j];
            lq[j] = d >= 0 ? q[d] : 0.0;
            lv[j] = d >= 0 ? v[d] : 0.0;
            lf[j] = 0.0;
        }
        if (!inert) {
            L->type->force(L, &x, lf, NULL, NULL);
            for (int j = 0; j < n; j++)
                if (L->dof[j] >= 0) r[L->dof[j]] += lf[j];
            continue;
        }
        /* with its inertia: on a free DOF into tr->mu (the right-hand side solves with
         * it), on a prescribed one as the force -m q'' */
        const int *slot = tr->in_slot + (size_t)i * GD_LAW_MAX_DOFS;
        double m[GD_LAW_MAX_DOFS] = {0};
        L->type->inertia(L, &x, lf, m);
        for (int j = 0; j < n; j++) {
            const int d = L->dof[j];
            if (d < 0) continue;
            r[d] += lf[j];
            if (dw != 0.0) r[d] -= m[j] * tr->ratio[d] * dw;
            if (slot[j] >= 0)
                tr->mu[slot[j]] += m[j];
            else
                r[d] -= m[j] * acc[d];
        }
    }
}

/* gd_tr_forces of a run-up (gd_transient_options.profile): every nominal angle ratio
 * phi(t), speed ratio W(t), and the gyroscopic term's change from the reference speed
 * the matrices hold, -(W(t) - W) G q'. */
static void profile_forces(gd_transient *tr, double t, const double *q, const double *v,
                           const double *acc, double *r, int skip_free_linear)
{
    double phi, w, dw;
    gd_tr_profile_eval(tr->prof, tr->prof_cum, t, &phi, &w, &dw);
    if (tr->nlaw) gd_tr_profile_laws(tr, t, phi, w);
    add_law_forces(tr, t, q, v, acc, dw, r, 0);
    for (int i = 0; i < tr->nunb_all; i++) {
        /* heavy spot at psi = ratio phi + phase (mirrored for a shaft turning about -z):
         * -m r'' = U (psi'^2 cos + psi'' sin, psi'^2 sin - psi'' cos) */
        const tr_unb *u = &tr->unb[i];
        double s = u->ratio * tr->prof_sign;
        double psi = u->ratio * phi + (s > 0 ? u->phase0 : -u->phase0);
        double w1 = u->ratio * w, w2 = u->ratio * dw, c = cos(psi), sn = sin(psi);
        if (u->dx >= 0) r[u->dx] += u->amount * (w1 * w1 * c + w2 * sn);
        if (u->dy >= 0) r[u->dy] += u->amount * (w1 * w1 * sn - w2 * c);
    }
    if (skip_free_linear) {
        sub_mul_prescribed(tr, tr->K, q, r);
        sub_mul_prescribed(tr, tr->D, v, r);
        sub_mul_prescribed(tr, tr->M, acc, r);
    } else {
        sub_mul(tr->K, q, r);
        sub_mul(tr->D, v, r);
        if (tr->np) sub_mul(tr->M, acc, r);
    }
    gd_tr_profile_bearing_forces(tr, w, q, v, r); /* speed-table bearings at W(t) */
    {
        /* r -= (W(t) - W) G v: the time-varying gyroscopic term */
        double dW = w - tr->speed;
        const cs *G = tr->Gy;
        for (int j = 0; j < G->n; j++) {
            double x = dW * v[j];
            if (x == 0.0) continue;
            for (int p = G->p[j]; p < G->p[j + 1]; p++)
                r[G->i[p]] -= G->x[p] * x;
        }
    }
    add_law_forces(tr, t, q, v, acc, 0.0, r, 1);
}

void gd_tr_residual(gd_transient *tr, double t, const double *q, const double *v, const double *acc,
                    double *r)
{
    gd_tr_forces(tr, t, q, v, acc, r, 0);
}

void gd_tr_forces(gd_transient *tr, double t, const double *q, const double *v, const double *acc,
                  double *r, int skip_free_linear)
{
    const int n = tr->n;
    memset(r, 0, (size_t)n * sizeof *r);
    if (tr->nin) memset(tr->mu, 0, (size_t)tr->nin * sizeof *tr->mu);
    if (tr->prof) {
        profile_forces(tr, t, q, v, acc, r, skip_free_linear);
        return;
    }
    add_law_forces(tr, t, q, v, acc, 0.0, r, 0);
    for (int i = 0; i < tr->nunb; i++) {
        const tr_unb *u = &tr->unb[i];
        double psi = u->omega * t + u->phase;
        if (u->dx >= 0) r[u->dx] += u->force * cos(psi);
        if (u->dy >= 0) r[u->dy] += u->force * sin(psi);
    }
    if (skip_free_linear) {
        sub_mul_prescribed(tr, tr->K, q, r);
        sub_mul_prescribed(tr, tr->D, v, r);
        sub_mul_prescribed(tr, tr->M, acc, r);
    } else {
        sub_mul(tr->K, q, r);
        sub_mul(tr->D, v, r);
        if (tr->np) sub_mul(tr->M, acc, r);
    }
    add_law_forces(tr, t, q, v, acc, 0.0, r, 1);
}

void gd_tr_mass_solve(gd_transient *tr, double *b, double *x)
{
    const int nf = tr->nf;
    cs_ipvec(tr->Msym->pinv, b, x, nf);
    cs_lsolve(tr->Mnum->L, x);
    cs_ltsolve(tr->Mnum->L, x);
    cs_pvec(tr->Msym->pinv, x, b, nf);
    memcpy(x, b, (size_t)nf * sizeof *x);
}

/* Solves the small dense system A z = b (k x k, column-major) in place by Gaussian
 * elimination with partial pivoting. */
static void small_solve(int k, double *A, double *b)
{
    for (int c = 0; c < k; c++) {
        int p = c;
        for (int i = c + 1; i < k; i++)
            if (fabs(A[i + c * k]) > fabs(A[p + c * k])) p = i;
        if (p != c) {
            for (int j = 0; j < k; j++) {
                double t = A[c + j * k];
                A[c + j * k] = A[p + j * k];
                A[p + j * k] = t;
            }
            double t = b[c];
            b[c] = b[p];
            b[p] = t;
        }
        double piv = A[c + c * k];
        if (piv == 0.0) continue;
        for (int i = c + 1; i < k; i++) {
            double f = A[i + c * k] / piv;
            if (f == 0.0) continue;
            for (int j = c; j < k; j++)
                A[i + j * k] -= f * A[c + j * k];
            b[i] -= f * b[c];
        }
    }
    for (int c = k - 1; c >= 0; c--) {
        double s = b[c];
        for (int j = c + 1; j < k; j++)
            s -= A[c + j * k] * b[j];
        b[c] = A[c + c * k] != 0.0 ? s / A[c + c * k] : 0.0;
    }
}

void gd_transient_rhs(gd_transient *tr, double t, const double *y, double *ydot)
{
    const int nf = tr->nf;
    if (tr->cond) {
        tr->cond_rhs(tr, t, y, ydot);
        return;
    }
    gd_tr_fill(tr, t, y, tr->q, tr->v, tr->acc);
    gd_tr_residual(tr, t, tr->q, tr->v, tr->acc, tr->r);
    for (int i = 0; i < nf; i++)
        tr->w1[i] = tr->r[tr->free_dof[i]];
    double *x = ydot + nf;
    gd_tr_mass_solve(tr, tr->w1, x);
    if (tr->nin) {
        /* (M + E D E^T)^-1 r = x - Z (I + D G)^-1 D E^T x */
        const int k = tr->nin;
        int any = 0;
        for (int i = 0; i < k; i++) {
            tr->wv[i] = tr->mu[i] * x[tr->in_free[i]];
            if (tr->mu[i] != 0.0) any = 1;
            for (int j = 0; j < k; j++)
                tr->A[i + j * k] = (i == j ? 1.0 : 0.0) + tr->mu[i] * tr->G[i + j * k];
        }
        if (any) {
            small_solve(k, tr->A, tr->wv);
            for (int j = 0; j < k; j++) {
                const double *z = tr->Z + (size_t)j * nf;
                double c = tr->wv[j];
                for (int i = 0; i < nf; i++)
                    x[i] -= z[i] * c;
            }
        }
    }
    memcpy(ydot, y + nf, (size_t)nf * sizeof *ydot);
}

void gd_tr_roots(gd_transient *tr, double t, const double *y, double *g)
{
    if (tr->cond) /* the switches need only the laws' DOFs */
        tr->cond_fill(tr, t, y, tr->q, tr->v, 0);
    else
        gd_tr_fill(tr, t, y, tr->q, tr->v, NULL);
    int k = 0;
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        if (L->type->nswitches <= 0) continue; /* a smooth type: no call */
        int ns = gd_law_nswitches(L);
        if (!ns) continue;
        gd_law_point x;
        gd_tr_law_here(tr, L, t, &x);
        L->type->switches(L, &x, g + k);
        k += ns;
    }
}

void gd_transient_set_contacts(gd_transient *tr, double t, const double *y)
{
    gd_tr_fill(tr, t, y, tr->q, tr->v, NULL);
    for (int i = 0; i < tr->nlaw; i++) {
        gd_law *L = &tr->law[i];
        if (!L->type->mode_at) continue;
        gd_law_point x;
        gd_tr_law_here(tr, L, t, &x);
        L->mode = L->type->mode_at(L, &x);
    }
}

int gd_tr_prec_setup(gd_transient *tr, double gamma)
{
    cs *S = tr->S;
    memset(S->x, 0, (size_t)S->p[S->n] * sizeof *S->x);
    for (int p = 0; p < tr->Mff->p[tr->nf]; p++)
        S->x[tr->mapM[p]] += tr->Mff->x[p];
    for (int p = 0; p < tr->Dff->p[tr->nf]; p++)
        S->x[tr->mapD[p]] += gamma * tr->Dff->x[p];
    for (int p = 0; p < tr->Kff->p[tr->nf]; p++)
        S->x[tr->mapK[p]] += gamma * gamma * tr->Kff->x[p];
    cs_nfree(tr->Snum);
    tr->Snum = cs_lu(S, tr->Ssym, 1e-3);
    tr->gamma = gamma;
    return tr->Snum ? 0 : 1;
}

/* (I - g J) z = r with J = [0 I; -M^-1 K, -M^-1 D]:
 * (M + g D + g^2 K) z_v = M r_v - g K r_q, z_q = r_q + g z_v. */
void gd_tr_prec_solve(gd_transient *tr, const double *r, double *z)
{
    const int nf = tr->nf;
    const double g = tr->gamma;
    const double *rq = r, *rv = r + nf;
    double *b = tr->w1, *x = tr->w2;
    memset(b, 0, (size_t)nf * sizeof *b);
    const cs *M = tr->Mff, *K = tr->Kff;
    for (int j = 0; j < nf; j++) {
        for (int p = M->p[j]; p < M->p[j + 1]; p++)
            b[M->i[p]] += M->x[p] * rv[j];
        for (int p = K->p[j]; p < K->p[j + 1]; p++)
            b[K->i[p]] -= g * K->x[p] * rq[j];
    }
    cs_ipvec(tr->Snum->pinv, b, x, nf);
    cs_lsolve(tr->Snum->L, x);
    cs_usolve(tr->Snum->U, x);
    cs_ipvec(tr->Ssym->q, x, z + nf, nf);
    for (int i = 0; i < nf; i++)
        z[i] = rq[i] + g * z[nf + i];
}

int gd_tr_missed_mode(gd_transient *tr, const gd_law *L, double t)
{
    gd_law_point x;
    gd_tr_law_here(tr, L, t, &x);
    int ns = L->type->mode_at(L, &x);
    if (ns == L->mode) return ns;
    /* on a switch (within its tolerance): not a missed crossing */
    double tol = L->type->switch_tol ? L->type->switch_tol(L) : 0.0;
    double g[GD_LAW_MAX_SWITCHES];
    L->type->switches(L, &x, g);
    for (int k = 0; k < gd_law_nswitches(L); k++)
        if (!(fabs(g[k]) > tol)) return L->mode;
    return ns;
}
