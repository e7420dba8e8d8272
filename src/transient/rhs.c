/* The right-hand side y' = f(t, y) of the first-order form y = [q_f; q_f'], the root
 * functions of the backlash meshes and the preconditioner. Nothing here allocates. */
#include <math.h>
#include <string.h>

#include "transient/transient_impl.h"

void gd_tr_fill(gd_transient *tr, double t, const double *y, double *q, double *v, double *acc)
{
    const int nf = tr->nf;
    for (int f = 0; f < nf; f++) {
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

double gd_tr_mesh_law(const tr_mesh *m, gd_contact state, double t, const double *q,
                      const double *v, double *d_out, double *dd_out, double *k_out, double *de_out,
                      double grad[4])
{
    double d = 0.0, dd = 0.0;
    for (int j = 0; j < m->a.n; j++) {
        d += m->a.a[j] * q[m->a.dof[j]];
        dd += m->a.a[j] * v[m->a.dof[j]];
    }
    if (d_out) *d_out = d;
    if (dd_out) *dd_out = dd;
    const gd_tr_mesh *s = &m->spec;
    double k = s->stiffness, dk = 0.0, e1 = 0.0, e2 = 0.0, thd = 0.0;
    if (s->tvms || s->ste) {
        double qd = m->drv_dof >= 0 ? q[m->drv_dof] : 0.0;
        double vd = m->drv_dof >= 0 ? v[m->drv_dof] : 0.0;
        double th, wd;
        if (m->prof) { /* run-up: the driver's nominal angle ratio phi(t) */
            double phi, w;
            gd_tr_profile_eval(m->prof, m->prof_cum, t, &phi, &w, NULL);
            th = s->angle_offset + m->sense * (m->drv_ratio * phi + qd);
            wd = m->drv_ratio * w;
        } else {
            th = s->angle_offset + m->sense * (m->drv_rate * t + qd);
            wd = m->drv_rate;
        }
        thd = m->sense * (wd + vd);
        if (s->tvms) k = gd_table_eval(s->tvms, th, &dk, NULL);
        if (s->ste) {
            double e = gd_table_eval(s->ste, th, &e1, &e2);
            d -= e;
            dd -= e1 * thd;
        }
    }
    if (k_out) *k_out = k;
    if (de_out) *de_out = d;
    double c = s->damping + s->damping_per_k * k;
    gd_backlash_params p;
    p.b = s->backlash ? s->gap : 0.0;
    p.k_drive = k;
    p.k_coast = s->coast_scale * k;
    p.c_drive = c;
    p.c_coast = s->damping + s->damping_per_k * p.k_coast;
    p.c_free = s->damping_free;
    gd_contact st = s->backlash ? state : GD_CONTACT_DRIVE;
    /* contact homotopy (frequency-domain starts only): blend with the drive flank */
    double h = st != GD_CONTACT_DRIVE ? m->hold : 0.0;
    if (grad) {
        /* chain rule through the state's k(theta), c(theta) and the STE e(theta) */
        for (int b = 0; b < 4; b++)
            grad[b] = 0.0;
        for (int pass = 0; pass < (h > 0 ? 2 : 1); pass++) {
            gd_contact sp = pass ? GD_CONTACT_DRIVE : st;
            double wgt = pass ? h : 1.0 - h, g[4];
            gd_backlash_force_grad(&p, sp, d, dd, g);
            double dks = sp == GD_CONTACT_COAST ? s->coast_scale * dk : dk;
            double dcs = sp == GD_CONTACT_SEPARATED ? 0.0 : s->damping_per_k * dks;
            double dth = g[2] * dks + g[3] * dcs - g[0] * e1 - g[1] * e2 * thd;
            grad[0] += wgt * g[0];
            grad[1] += wgt * g[1];
            grad[2] += m->drv_dof >= 0 ? wgt * m->sense * dth : 0.0;
            grad[3] += m->drv_dof >= 0 ? -wgt * m->sense * g[1] * e1 : 0.0;
        }
    }
    if (!s->backlash) return k * d + c * dd;
    double F = gd_backlash_force(&p, state, d, dd);
    if (h > 0) F = (1.0 - h) * F + h * gd_backlash_force(&p, GD_CONTACT_DRIVE, d, dd);
    return F;
}

double gd_tr_mesh_force(const gd_transient *tr, const tr_mesh *m, gd_contact state, double t,
                        const double *q, const double *v, double *d_out, double *dd_out,
                        double *k_out, double *de_out)
{
    (void)tr;
    return gd_tr_mesh_law(m, state, t, q, v, d_out, dd_out, k_out, de_out, NULL);
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

/* r += every registry law's force at (t, q, q'). */
static void add_law_forces(gd_transient *tr, double t, const double *q, const double *v, double *r)
{
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        gd_law_point x;
        gd_tr_law_point(L, t, q, v, tr->lq, tr->lv, &x);
        memset(tr->lf, 0, (size_t)L->ndofs * sizeof *tr->lf);
        L->type->force(L, &x, tr->lf, NULL, NULL);
        for (int j = 0; j < L->ndofs; j++)
            if (L->dof[j] >= 0) r[L->dof[j]] += tr->lf[j];
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
    add_law_forces(tr, t, q, v, r);
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
    if (tr->ncd) memset(tr->mu, 0, (size_t)tr->ncd * sizeof *tr->mu);
    for (int i = 0; i < tr->ncam; i++) {
        const tr_cam *c = &tr->cam[i];
        int d = c->spec.dof, sense = c->ratio * tr->prof_sign >= 0 ? 1 : -1;
        double th = sense * (c->ratio * phi + q[d]);
        double wc = sense * (c->ratio * w + v[d]);
        double s1, s2;
        gd_lift_eval(c->spec.law, th - c->spec.phase, &s1, &s2);
        double m = c->spec.mass;
        r[d] -= sense * m * s1 * s2 * wc * wc;
        if (!tr->cam_acc) continue;
        /* W' = sense (ratio W' + q''): the nominal part here, q'' as in gd_tr_forces */
        r[d] -= m * s1 * s1 * c->ratio * dw;
        if (c->slot < 0)
            r[d] -= m * s1 * s1 * acc[d];
        else
            tr->mu[c->slot] += m * s1 * s1;
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
    for (int i = 0; i < tr->nmesh; i++) {
        const tr_mesh *m = &tr->mesh[i];
        double d, dd;
        double F = gd_tr_mesh_force(tr, m, m->state, t, q, v, &d, &dd, NULL, NULL);
        double g = F - m->k_lin * d - m->c_lin * dd;
        for (int j = 0; j < m->a.n; j++)
            r[m->a.dof[j]] -= m->a.a[j] * g;
    }
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
    if (tr->prof) {
        profile_forces(tr, t, q, v, acc, r, skip_free_linear);
        return;
    }
    add_law_forces(tr, t, q, v, r);
    for (int i = 0; i < tr->nunb; i++) {
        const tr_unb *u = &tr->unb[i];
        double psi = u->omega * t + u->phase;
        if (u->dx >= 0) r[u->dx] += u->force * cos(psi);
        if (u->dy >= 0) r[u->dy] += u->force * sin(psi);
    }
    if (tr->ncd) memset(tr->mu, 0, (size_t)tr->ncd * sizeof *tr->mu);
    for (int i = 0; i < tr->ncam; i++) {
        const tr_cam *c = &tr->cam[i];
        int d = c->spec.dof;
        double th = c->sense * (c->rate * t + q[d]);
        double w = c->sense * (c->rate + v[d]);
        double s1, s2;
        gd_lift_eval(c->spec.law, th - c->spec.phase, &s1, &s2);
        double m = c->spec.mass;
        /* T = m s' (s'' W^2 + s' W'), W' = sense q''; generalised force -sense T */
        r[d] -= c->sense * m * s1 * s2 * w * w;
        if (c->slot < 0) {
            if (tr->cam_acc) r[d] -= m * s1 * s1 * acc[d];
        } else if (tr->cam_acc) {
            tr->mu[c->slot] += m * s1 * s1;
        }
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
    for (int i = 0; i < tr->nmesh; i++) {
        const tr_mesh *m = &tr->mesh[i];
        double d, dd;
        double F = gd_tr_mesh_force(tr, m, m->state, t, q, v, &d, &dd, NULL, NULL);
        double g = F - m->k_lin * d - m->c_lin * dd;
        for (int j = 0; j < m->a.n; j++)
            r[m->a.dof[j]] -= m->a.a[j] * g;
    }
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
    gd_tr_fill(tr, t, y, tr->q, tr->v, tr->acc);
    gd_tr_residual(tr, t, tr->q, tr->v, tr->acc, tr->r);
    for (int i = 0; i < nf; i++)
        tr->w1[i] = tr->r[tr->free_dof[i]];
    double *x = ydot + nf;
    gd_tr_mass_solve(tr, tr->w1, x);
    if (tr->ncd && tr->cam_acc) {
        /* (M + E D E^T)^-1 r = x - Z (I + D G)^-1 D E^T x */
        const int k = tr->ncd;
        int any = 0;
        for (int i = 0; i < k; i++) {
            tr->wv[i] = tr->mu[i] * x[tr->cd_free[i]];
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
    gd_tr_fill(tr, t, y, tr->q, tr->v, NULL);
    int k = 0;
    for (int i = 0; i < tr->nmesh; i++) {
        const tr_mesh *m = &tr->mesh[i];
        if (!m->spec.backlash) continue;
        double de;
        gd_tr_mesh_force(tr, m, m->state, t, tr->q, tr->v, NULL, NULL, NULL, &de);
        g[k++] = de - m->spec.gap;
        g[k++] = de + m->spec.gap;
    }
}

void gd_transient_set_contacts(gd_transient *tr, double t, const double *y)
{
    gd_tr_fill(tr, t, y, tr->q, tr->v, NULL);
    for (int i = 0; i < tr->nmesh; i++) {
        tr_mesh *m = &tr->mesh[i];
        if (!m->spec.backlash) {
            m->state = GD_CONTACT_DRIVE;
            continue;
        }
        double de;
        gd_tr_mesh_force(tr, m, m->state, t, tr->q, tr->v, NULL, NULL, NULL, &de);
        m->state = gd_backlash_state(de, m->spec.gap);
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

gd_contact gd_tr_root_state(gd_contact cur, int r0, int r1)
{
    if (r1 < 0) return GD_CONTACT_COAST;
    if (r0 > 0) return GD_CONTACT_DRIVE;
    if (r0 < 0 || r1 > 0) return GD_CONTACT_SEPARATED;
    return cur;
}

gd_contact gd_tr_missed_state(gd_transient *tr, const tr_mesh *m, double t)
{
    double de;
    gd_tr_mesh_force(tr, m, m->state, t, tr->q, tr->v, NULL, NULL, NULL, &de);
    gd_contact ns = gd_backlash_state(de, m->spec.gap);
    double tol = 1e-6 * m->spec.gap + 1e-15;
    return ns != m->state && fabs(fabs(de) - m->spec.gap) > tol ? ns : m->state;
}
