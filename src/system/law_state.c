/* The laws of the registry (geardyn/law_type.h) in the linear analyses: each law with a
 * `linearize` op adds its stiffness K = -df/dq and damping C = -df/dq' about the static
 * equilibrium at the reference speed W to the system's K and D (gd_system_dense and the
 * sparse dynamic matrix, so modal, campbell, frf and unbalance see them without knowing
 * one law from another).
 *
 * The static equilibrium at W solves K(W) q = f0 + sum f_law(q) (velocities zero,
 * t = 0) by Newton's method with a backtracking line search, the Jacobian
 * K(W) + sum K_law(q) from the laws' own linearisation, from q = 0. f0 is the mean
 * load of the static analysis (docs/static.md): the excitation loads at their mean and
 * gravity on the masses. A journal bearing's equilibrium thus follows its Sommerfeld
 * number over speed (eccentricity and attitude angle, Childs, Turbomachinery
 * Rotordynamics, 1993, ch. 3). Where no equilibrium exists (a journal bearing at rest
 * carries no load) or the iteration does not converge, the laws are linearised about
 * q = 0 and gd_system_law_state says so.
 *
 * Singular Jacobians (a free torsion of a gear train, a rotor held by the laws alone at
 * a state where they carry nothing) are solved in the least-squares, minimum-norm sense
 * (LAPACK dgelsd): free rigid-body motions that no load drives stay at zero. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "system/system_impl.h"

gd_status gd_system_make_laws(gd_system *s, gd_error *err)
{
    const gd_model *m = s->model;
    s->nlaws = 0;
    s->law_block = 0;
    if (!m->nlaws) return GD_OK;
    s->laws = calloc((size_t)m->nlaws, sizeof *s->laws);
    if (!s->laws) return gd_error_set(err, GD_ENOMEM, m->file, 0, 0, "", "", "out of memory");
    for (int i = 0; i < m->nlaws; i++) {
        gd_law *L = &s->laws[s->nlaws];
        gd_status st = gd_system_law_instance(s, i, L, err);
        if (st) return st;
        if (!L->type->linearize) continue; /* checked, but no part of K and D */
        s->law_block += L->ndofs * L->ndofs;
        s->nlaws++;
    }
    return GD_OK;
}

/* Instance i at reference speed W: rates and spins scaled. */
static void law_at(const gd_system *s, int i, double W, gd_law *L)
{
    *L = s->laws[i];
    for (int j = 0; j < L->ndofs; j++)
        L->rate[j] *= W;
    L->spin[0] *= W;
    L->spin[1] *= W;
}

static void local_q(const gd_law *L, const double *q, double *ql)
{
    for (int j = 0; j < L->ndofs; j++)
        ql[j] = L->dof[j] >= 0 ? q[L->dof[j]] : 0.0;
}

void gd_system_mean_loads(const gd_system *sys, int loads, int gravity, double *f)
{
    const gd_model *m = sys->model;
    const int n = sys->ndof;
    memset(f, 0, (size_t)n * sizeof *f);
    if (loads)
        for (int k = 0; k < m->nexcitations; k++) {
            const gd_excitation *e = &m->excitations[k];
            int i = e->node >= 0 && e->node < m->nnodes && (int)e->dof >= 0 && e->dof < GD_NODE_DOFS
                        ? sys->node_dof[6 * e->node + e->dof]
                        : -1;
            if (i >= 0) f[i] += gd_load_law_mean(&e->law);
        }
    const double *g = m->gravity;
    if (gravity && (g[0] != 0 || g[1] != 0 || g[2] != 0)) {
        /* f += M t, column by column over the translation DOFs */
        for (int j = 0; j < n; j++) {
            gd_dof d = sys->dof_type[j];
            if (d > GD_Z || g[d] == 0) continue;
            for (int p = sys->M.colptr[j]; p < sys->M.colptr[j + 1]; p++)
                f[sys->M.rowind[p]] += sys->M.values[p] * g[d];
        }
    }
}

/* r = K q - f0 - sum f_law(q); J (may be NULL) = K + sum K_law(q). Over the held DOFs
 * (held NULL: none) r is 0 and J the identity, so Newton leaves them where they are.
 * Returns |r|_2. */
static double residual(const gd_system *s, double W, const double *K, const double *f0,
                       const int *held, const double *q, double *r, double *J)
{
    const int n = s->ndof;
    for (int i = 0; i < n; i++)
        r[i] = -f0[i];
    for (int j = 0; j < n; j++) {
        double qj = q[j];
        if (qj == 0.0) continue;
        const double *col = K + (size_t)j * n;
        for (int i = 0; i < n; i++)
            r[i] += col[i] * qj;
    }
    if (J) memcpy(J, K, (size_t)n * n * sizeof *J);
    for (int i = 0; i < s->nlaws; i++) {
        gd_law L;
        law_at(s, i, W, &L);
        double ql[GD_LAW_MAX_DOFS], v[GD_LAW_MAX_DOFS] = {0}, f[GD_LAW_MAX_DOFS] = {0};
        local_q(&L, q, ql);
        gd_law_point x = {0.0, ql, v};
        double Kl[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS] = {0}, Cl[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS];
        if (J) {
            memset(Cl, 0, sizeof Cl);
            gd_law_force_tangent(&L, &x, f, Kl, Cl); /* one evaluation for both */
        } else {
            L.type->force(&L, &x, f, NULL, NULL);
        }
        for (int a = 0; a < L.ndofs; a++)
            if (L.dof[a] >= 0) r[L.dof[a]] -= f[a];
        if (!J) continue;
        for (int b = 0; b < L.ndofs; b++)
            for (int a = 0; a < L.ndofs; a++)
                if (L.dof[a] >= 0 && L.dof[b] >= 0)
                    J[L.dof[a] + (size_t)L.dof[b] * n] += Kl[a + L.ndofs * b];
    }
    if (held)
        for (int i = 0; i < n; i++) {
            if (!held[i]) continue;
            r[i] = 0.0;
            if (!J) continue;
            for (int j = 0; j < n; j++)
                J[i + (size_t)j * n] = J[j + (size_t)i * n] = 0.0;
            J[i + (size_t)i * n] = 1.0;
        }
    double s2 = 0;
    for (int i = 0; i < n; i++)
        s2 += r[i] * r[i];
    return sqrt(s2);
}

void gd_system_law_forces(const gd_system *s, double speed, const double *q, double *f)
{
    memset(f, 0, (size_t)s->ndof * sizeof *f);
    for (int i = 0; i < s->nlaws; i++) {
        gd_law L;
        law_at(s, i, speed, &L);
        double ql[GD_LAW_MAX_DOFS], v[GD_LAW_MAX_DOFS] = {0}, fl[GD_LAW_MAX_DOFS] = {0};
        local_q(&L, q, ql);
        gd_law_point x = {0.0, ql, v};
        L.type->force(&L, &x, fl, NULL, NULL);
        for (int a = 0; a < L.ndofs; a++)
            if (L.dof[a] >= 0) f[L.dof[a]] += fl[a];
    }
}

int gd_system_law_records(const gd_system *s, int i, double speed, const double *q, double *out,
                          int cap)
{
    gd_law L;
    law_at(s, i, speed, &L);
    double ql[GD_LAW_MAX_DOFS], v[GD_LAW_MAX_DOFS] = {0};
    local_q(&L, q, ql);
    gd_law_point x = {0.0, ql, v};
    int n = !L.type->record ? 0 : L.type->nrecords < cap ? L.type->nrecords : cap;
    for (int k = 0; k < n; k++)
        out[k] = L.type->record(&L, k, &x);
    return n;
}

/* Solves J x = b in place (b <- x), J destroyed: LU when J is well conditioned
 * (reciprocal condition number above 1e-13), else the minimum-norm least-squares
 * solution with singular values below 1e-12 of the largest dropped (a free motion held
 * only by roundoff moves nowhere). 0 ok. */
/* The reciprocal 1-norm condition number of the LU-factored LU (n x n, pivots piv) of a
 * matrix of 1-norm anorm: exact from the inverse for n <= 8 (LAPACK's estimator costs ten
 * times a small system's solve: 14 % of a 2-DOF journal-bearing Campbell sweep), else
 * LAPACK's estimate. 1 when computed. */
static int rcond_lu(int n, const double *LU, const lapack_int *piv, double anorm, double *rcond)
{
    if (n > 8) return LAPACKE_dgecon(LAPACK_COL_MAJOR, '1', n, LU, n, anorm, rcond) == 0;
    double inv[64] = {0}, ainv = 0;
    for (int i = 0; i < n; i++)
        inv[i + n * i] = 1.0;
    if (LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', n, n, LU, n, piv, inv, n)) return 0;
    for (int j = 0; j < n; j++) {
        double c = 0;
        for (int i = 0; i < n; i++)
            c += fabs(inv[i + n * j]);
        ainv = c > ainv ? c : ainv;
    }
    *rcond = anorm > 0 && ainv > 0 && isfinite(ainv) ? 1.0 / (anorm * ainv) : 0.0;
    return 1;
}

static int solve(int n, double *J, double *b, double *Jc, lapack_int *piv)
{
    memcpy(Jc, J, (size_t)n * n * sizeof *Jc);
    double anorm = LAPACKE_dlange(LAPACK_COL_MAJOR, '1', n, n, Jc, n), rcond = 0.0;
    if (LAPACKE_dgetrf(LAPACK_COL_MAJOR, n, n, Jc, n, piv) == 0 &&
        rcond_lu(n, Jc, piv, anorm, &rcond) && rcond > 1e-13)
        return LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', n, 1, Jc, n, piv, b, n) != 0;
    double *sv = Jc; /* n singular values */
    lapack_int rank;
    return LAPACKE_dgelsd(LAPACK_COL_MAJOR, n, n, 1, J, n, b, n, sv, 1e-12, &rank) != 0;
}

/* M_ii (0 for a massless DOF). */
static double diag_mass(const gd_system *s, int i)
{
    for (int p = s->M.colptr[i]; p < s->M.colptr[i + 1]; p++)
        if (s->M.rowind[p] == i) return s->M.values[p];
    return 0.0;
}

/* Backtracking along dq from q: qt = q + a dq with the first a = 2^-k (k < halvings)
 * whose residual is below (1 - 1e-4 a) res. Returns that residual, or res if none. */
static double search(const gd_system *s, double W, const double *K, const double *f0,
                     const int *held, const double *q, const double *dq, double *qt, double *r,
                     double res, int halvings, double *taken)
{
    double a = 1.0;
    for (int k = 0; k < halvings; k++, a *= 0.5) {
        for (int i = 0; i < s->ndof; i++)
            qt[i] = q[i] + a * dq[i];
        double rt = residual(s, W, K, f0, held, qt, r, NULL);
        if (rt < (1.0 - 1e-4 * a) * res) {
            if (taken) *taken = a;
            return rt;
        }
    }
    return res;
}

/* g(a) = dq . r(q + a dq): the slope of the potential along the ray (r is the gradient of
 * the potential of K and of the conservative laws: Hertzian contacts, springs). */
static double slope(const gd_system *s, double W, const double *K, const double *f0,
                    const int *held, const double *q, const double *dq, double a, double *qt,
                    double *r)
{
    for (int i = 0; i < s->ndof; i++)
        qt[i] = q[i] + a * dq[i];
    residual(s, W, K, f0, held, qt, r, NULL);
    double g = 0;
    for (int i = 0; i < s->ndof; i++)
        g += dq[i] * r[i];
    return g;
}

/* The minimum of the potential along dq from q, where g(0) = dq . r(q) < 0: the step
 * doubles from 1e-12 until the slope turns positive, then bisects on the slope's sign.
 * This crosses a clearance dead zone (no stiffness, flat potential) into the contact
 * however narrow the load's window of deflection is, which halving a long step misses
 * (a roller's 10/9 contact carries 200 N within 1 um beyond a 5 um clearance: issue 38
 * M2), and it decreases the potential where the residual's norm, which weighs forces
 * and torques alike, would refuse the step (a train whose input torque stretches the
 * mesh before the bearings touch). Leaves the state at the last step with a negative
 * slope in qt (the potential decreased all along: it is convex for the conservative
 * laws) and returns 1, or 0 when there is none. */
static int energy_search(const gd_system *s, double W, const double *K, const double *f0,
                         const int *held, const double *q, const double *dq, double *qt, double *r)
{
    double lo = 0, hi = 1e-12;
    int up = 0;
    if (!(slope(s, W, K, f0, held, q, dq, 0.0, qt, r) < 0)) return 0;
    for (int k = 0; k < 200 && !up; k++) {
        double g = slope(s, W, K, f0, held, q, dq, hi, qt, r);
        if (!isfinite(g)) break;
        if (g > 0)
            up = 1;
        else
            lo = hi, hi *= 2;
    }
    if (!up) return 0;
    for (int k = 0; k < 200 && hi - lo > 1e-14 * hi; k++) {
        double mid = 0.5 * (lo + hi);
        if (slope(s, W, K, f0, held, q, dq, mid, qt, r) > 0)
            hi = mid;
        else
            lo = mid;
    }
    if (!(lo > 0)) return 0;
    for (int i = 0; i < s->ndof; i++)
        qt[i] = q[i] + lo * dq[i];
    return 1;
}

int gd_system_law_equilibrium(const gd_system *s, double speed, const double *K, const double *f0,
                              const int *held, double *q, double *resnorm)
{
    const int n = s->ndof;
    size_t nn = (size_t)n * n;
    double *r = malloc((size_t)n * 3 * sizeof *r);
    double *J = malloc(nn * 2 * sizeof *J);
    lapack_int *piv = malloc((size_t)n * sizeof *piv);
    int found = 0;
    double res = INFINITY, fnorm = 0;
    if (!r || !J || !piv) goto out;
    double *dq = r + n, *qt = dq + n, *Jc = J + nn;
    for (int i = 0; i < n; i++)
        if (!held || !held[i]) fnorm += f0[i] * f0[i];
    fnorm = sqrt(fnorm);
    res = residual(s, speed, K, f0, held, q, r, J);
    /* converged: the residual a few ulps of the load (or of the linear forces at 0 load) */
    double tol = 1e-10 * (fnorm > 0 ? fnorm : 1.0);
    int energy = 0; /* potential-minimising steps taken (at most 50) */
    for (int it = 0; it < 150 && !found; it++) {
        int moved = 0;
        if (res <= tol) {
            found = 1;
            break;
        }
        for (int i = 0; i < n; i++)
            dq[i] = -r[i];
        int newton = !solve(n, J, dq, Jc, piv);
        double a = 1.0;
        double rt = newton ? search(s, speed, K, f0, held, q, dq, qt, r, res, 30, &a) : res;
        if ((!(rt < res) || a < 0.125) && newton && energy < 50) {
            /* the residual's norm refuses the Newton step, or takes a sliver of it (a
               crawl where Hertz contacts stiffen from nothing): minimise the potential
               along it instead */
            if (energy_search(s, speed, K, f0, held, q, dq, qt, r))
                rt = residual(s, speed, K, f0, held, qt, r, NULL), energy++, moved = 1;
            else if (rt < res) /* the sliver, recomputed (the search overwrote qt) */
                for (int i = 0; i < n; i++)
                    qt[i] = q[i] + a * dq[i];
        }
        if (!(rt < res) && !moved) {
            /* no Newton descent: the laws are stiffless where they stand (a Hertzian
             * contact at zero deflection, a journal bearing at rest). Step along the
             * mass-scaled residual, which points the way the load pushes, from a step of
             * the load's own acceleration over 1/s^2 down through 60 halvings, else to
             * the potential's minimum along it. */
            residual(s, speed, K, f0, held, q, r, NULL); /* r, overwritten by the search */
            for (int i = 0; i < n; i++)
                dq[i] = diag_mass(s, i) > 0 ? -r[i] / diag_mass(s, i) : 0.0;
            rt = search(s, speed, K, f0, held, q, dq, qt, r, res, 60, NULL);
            if (!(rt < res) && energy < 50) {
                residual(s, speed, K, f0, held, q, r, NULL);
                if (energy_search(s, speed, K, f0, held, q, dq, qt, r))
                    rt = residual(s, speed, K, f0, held, qt, r, NULL), energy++, moved = 1;
            }
        }
        if (moved) {
            memcpy(q, qt, (size_t)n * sizeof *q);
            res = residual(s, speed, K, f0, held, q, r, J);
            continue;
        }
        if (!(rt < res)) break; /* no descent either way: no equilibrium */
        memcpy(q, qt, (size_t)n * sizeof *q);
        res = residual(s, speed, K, f0, held, q, r, J);
    }
out:
    if (resnorm) *resnorm = fnorm > 0 ? res / fnorm : res;
    free(r);
    free(J);
    free(piv);
    return found;
}

int gd_system_law_state_loads(const gd_system *s, double speed, const double *f0, double *q)
{
    const int n = s->ndof;
    memset(q, 0, (size_t)n * sizeof *q);
    if (!s->nlaws) return 1;
    double *K = malloc((size_t)n * n * sizeof *K);
    int found = 0;
    if (K) {
        gd_system_dense_linear(s, speed, NULL, NULL, K);
        found = gd_system_law_equilibrium(s, speed, K, f0, NULL, q, NULL);
    }
    if (!found) memset(q, 0, (size_t)n * sizeof *q);
    free(K);
    return found;
}

gd_status gd_system_set_operating_point(gd_system *s, gd_operating_kind kind, const double *f0,
                                        const int *held, gd_error *err)
{
    const int n = s->ndof;
    if (kind != GD_OPERATING_STATIC && kind != GD_OPERATING_ZERO)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "operating point", "static or zero",
                            "unknown operating point kind %d", (int)kind);
    for (int i = 0; f0 && i < n; i++)
        if (!isfinite(f0[i]))
            return gd_error_set(err, GD_EINPUT, s->model->file, 0, 0, "operating point",
                                "give finite loads", "the operating point's load is not finite");
    size_t n1 = (size_t)(n > 0 ? n : 1);
    double *f = f0 ? malloc(n1 * sizeof *f) : NULL;
    int *h = held ? malloc(n1 * sizeof *h) : NULL;
    if ((f0 && !f) || (held && !h)) {
        free(f);
        free(h);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    if (f) memcpy(f, f0, (size_t)n * sizeof *f);
    if (h) memcpy(h, held, (size_t)n * sizeof *h);
    free(s->op_f0);
    free(s->op_held);
    s->op_kind = kind;
    s->op_f0 = f;
    s->op_held = h;
    return GD_OK;
}

int gd_system_law_state_from(const gd_system *s, double speed, const double *q0, double *q)
{
    const int n = s->ndof;
    memset(q, 0, (size_t)n * sizeof *q);
    if (!s->nlaws || s->op_kind == GD_OPERATING_ZERO) return 1;
    double *f0 = malloc((size_t)n * sizeof *f0), *K = malloc((size_t)n * n * sizeof *K);
    int found = 0;
    if (f0 && K) {
        if (s->op_f0)
            memcpy(f0, s->op_f0, (size_t)n * sizeof *f0);
        else
            gd_system_mean_loads(s, 1, 1, f0);
        gd_system_dense_linear(s, speed, NULL, NULL, K);
        if (q0) {
            /* the neighbouring speed's state: a few Newton steps from there */
            memcpy(q, q0, (size_t)n * sizeof *q);
            found = gd_system_law_equilibrium(s, speed, K, f0, s->op_held, q, NULL);
            if (!found) memset(q, 0, (size_t)n * sizeof *q);
        }
        if (!found) found = gd_system_law_equilibrium(s, speed, K, f0, s->op_held, q, NULL);
        if (!found) memset(q, 0, (size_t)n * sizeof *q);
    }
    free(f0);
    free(K);
    return found;
}

int gd_system_law_state(const gd_system *s, double speed, double *q)
{
    return gd_system_law_state_from(s, speed, NULL, q);
}

void gd_system_law_blocks_at(const gd_system *s, double speed, const double *state, double *Kb,
                             double *Cb)
{
    if (!s->nlaws) return;
    memset(Kb, 0, (size_t)s->law_block * sizeof *Kb);
    memset(Cb, 0, (size_t)s->law_block * sizeof *Cb);
    double *q = NULL;
    if (!state) {
        q = malloc((size_t)s->ndof * sizeof *q);
        if (!q) return;
        gd_system_law_state(s, speed, q);
        state = q;
    }
    size_t at = 0;
    for (int i = 0; i < s->nlaws; i++) {
        gd_law L;
        law_at(s, i, speed, &L);
        double ql[GD_LAW_MAX_DOFS], v[GD_LAW_MAX_DOFS] = {0};
        local_q(&L, state, ql);
        gd_law_point x = {0.0, ql, v};
        L.type->linearize(&L, &x, Kb + at, Cb + at);
        at += (size_t)L.ndofs * L.ndofs;
    }
    free(q);
}

void gd_system_law_blocks(const gd_system *s, double speed, double *Kb, double *Cb)
{
    gd_system_law_blocks_at(s, speed, NULL, Kb, Cb);
}

/* D += the laws' C, K += their K about state (NULL: solved at speed). */
static void add_laws_dense_at(const gd_system *s, double speed, const double *state, double *D,
                              double *K)
{
    if (!s->nlaws || (!D && !K)) return;
    double *Kb = malloc((size_t)s->law_block * 2 * sizeof *Kb);
    if (!Kb) return;
    double *Cb = Kb + s->law_block;
    gd_system_law_blocks_at(s, speed, state, Kb, Cb);
    size_t n = (size_t)s->ndof, at = 0;
    for (int i = 0; i < s->nlaws; i++) {
        const gd_law *L = &s->laws[i];
        int nd = L->ndofs;
        for (int b = 0; b < nd; b++)
            for (int a = 0; a < nd; a++)
                if (L->dof[a] >= 0 && L->dof[b] >= 0) {
                    size_t p = (size_t)L->dof[a] + (size_t)L->dof[b] * n;
                    if (K) K[p] += Kb[at + a + nd * b];
                    if (D) D[p] += Cb[at + a + nd * b];
                }
        at += (size_t)nd * nd;
    }
    free(Kb);
}

void gd_system_add_laws_dense(const gd_system *s, double speed, double *D, double *K)
{
    add_laws_dense_at(s, speed, NULL, D, K);
}

void gd_system_dense_at(const gd_system *s, double speed, const double *state, double *M, double *D,
                        double *K)
{
    gd_system_dense_linear(s, speed, M, D, K);
    add_laws_dense_at(s, speed, state, D, K);
}

void gd_system_dense(const gd_system *s, double speed, double *M, double *D, double *K)
{
    gd_system_dense_at(s, speed, NULL, M, D, K);
}
