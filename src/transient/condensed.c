/* The transient integrated on the condensed structure (docs/transient.md, "Condensed
 * transient"; issue 37 item 4): the linear structure's kept modes as the state, the
 * discarded ones as the static correction (algebraic feedthrough), the laws evaluated on
 * the few DOFs they act on, and CVODE's Newton solved by a dense LU of I - gamma J on
 * the small state (J exact for the linear part, the laws' tangent by differences).
 *
 * Model (docs/condense.md, "Time domain": kept modes plus residual flexibility,
 * [CraigKurdila2006]): with S the DOFs any law or unbalance acts on
 * (each a unit coordinate) and u the forces there,
 *   x' = A x + B u,   q_S = C x + G u,   q_S' = C A x + C B u (the static correction's
 *   own rate G u' is left out: zero when every mode is kept),
 *   u = r_S(t, q_S, q_S') + K_L q_S + C_L q_S'
 * r_S the transient's forces at S (laws in their frozen modes, unbalances; the meshes'
 * forces less their assembled linear part) and K_L, C_L the laws' linearisations that
 * the condensed structure holds (gd_system_dense) and the transient's does not. u solves
 * the feedthrough loop u = f(u) by Newton on I - F_q G - F_v C B (F_q, F_v: the forces'
 * derivatives at S), which holds with every mode kept (G = C B = 0) after one
 * evaluation. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_linearsolver.h>

#include "geardyn/condense.h"
#include "geardyn/laws.h"
#include "geardyn/modal.h"
#include "transient/transient_impl.h"

#define TWO_PI 6.28318530717958647692

void gd_tr_condensed_free(gd_tr_condensed *k)
{
    if (!k) return;
    gd_condense_destroy(k->c);
    free(k->dof);
    free(k->CA);
    free(k->CB);
    free(k->dK);
    free(k->dD);
    free(k->u);
    free(k->Fq);
    free(k->Fv);
    free(k->L);
    free(k->lpiv);
    free(k->D);
    free(k->yscale);
    free(k->ewt);
    free(k->CCA);
    free(k->xout);
    free(k->yout);
    free(k->partner);
    if (k->Jm) SUNMatDestroy(k->Jm);
    free(k->work);
    free(k->modes);
    free(k);
}

/* The prescribed motion u_p(t), u_p', u_p'' into q, v, acc at the prescribed DOFs, as the
 * full transient has it (gd_tr_fill). */
static void prescribed_at(const gd_transient *tr, double t, double *q, double *v, double *acc)
{
    for (int p = 0; p < tr->np; p++) {
        const int d = tr->pres[p].dof;
        gd_prescribed_eval(&tr->pres[p].law, t, tr->rate[d], &q[d], &v[d], &acc[d]);
    }
}

/* The transient's forces at S (u without the loop): r_S + K_L q_S + C_L q_S'. */
static void forces_at(gd_transient *tr, double t, const double *qs, const double *vs, double *u)
{
    gd_tr_condensed *k = tr->cond;
    const int nc = k->nc;
    for (int i = 0; i < nc; i++) {
        tr->q[k->dof[i]] = qs[i];
        tr->v[k->dof[i]] = vs[i];
    }
    prescribed_at(tr, t, tr->q, tr->v, tr->acc);
    /* with the prescribed columns: - K_fp u_p - D_fp u_p' - M_fp u_p'' on the coupled free
     * DOFs (coordinates), the structure being clamped at the prescribed DOFs */
    gd_tr_forces(tr, t, tr->q, tr->v, tr->acc, tr->r, 1);
    for (int i = 0; i < nc; i++) {
        double s = tr->r[k->dof[i]];
        for (int j = 0; j < nc; j++)
            s += k->dK[i + (size_t)j * nc] * qs[j] + k->dD[i + (size_t)j * nc] * vs[j];
        u[i] = s;
    }
}

/* y = C x (nc), yv = C A x (yv = y + nc: one product with [C; C A]), the last x's kept:
 * CVODE evaluates the error weights and the switches at the same accepted state */
static void outputs(gd_tr_condensed *k, const double *x, double *y)
{
    const int nc2 = 2 * k->nc, ns = k->ns;
    if (k->have_out && !memcmp(x, k->xout, (size_t)ns * sizeof *x)) {
        memcpy(y, k->yout, (size_t)nc2 * sizeof *y);
        return;
    }
    for (int i = 0; i < nc2; i++)
        y[i] = 0.0;
    for (int j = 0; j < ns; j++) {
        const double xj = x[j];
        const double *c = k->CCA + (size_t)j * nc2;
        for (int i = 0; i < nc2; i++)
            y[i] += c[i] * xj;
    }
    memcpy(k->xout, x, (size_t)ns * sizeof *x);
    memcpy(k->yout, y, (size_t)nc2 * sizeof *y);
    k->have_out = 1;
}

/* q_S = y + G u, v_S = yv + C B u */
static void coords_of(const gd_tr_condensed *k, const double *y, const double *yv, const double *u,
                      double *qs, double *vs)
{
    const int nc = k->nc;
    memcpy(qs, y, (size_t)nc * sizeof *qs);
    memcpy(vs, yv, (size_t)nc * sizeof *vs);
    for (int j = 0; j < nc; j++) {
        const double uj = u[j];
        for (int i = 0; i < nc; i++) {
            qs[i] += k->G[i + (size_t)j * nc] * uj;
            vs[i] += k->CB[i + (size_t)j * nc] * uj;
        }
    }
}

/* F_q, F_v at (qs, vs) by differences (the laws in their frozen modes: affine meshes are
 * exact), and the loop matrix L = I - F_q G - F_v C B factored. */
static void refresh_tangent(gd_transient *tr, double t, const double *qs, const double *vs)
{
    gd_tr_condensed *k = tr->cond;
    const int nc = k->nc;
    double *f0 = k->work, *f1 = f0 + nc, *qp = f1 + nc, *vp = qp + nc;
    forces_at(tr, t, qs, vs, f0);
    memcpy(qp, qs, (size_t)nc * sizeof *qp);
    memcpy(vp, vs, (size_t)nc * sizeof *vp);
    for (int j = 0; j < nc; j++) {
        double h = 1e-8 * (1e-3 + fabs(qs[j]));
        qp[j] = qs[j] + h;
        forces_at(tr, t, qp, vs, f1);
        qp[j] = qs[j];
        for (int i = 0; i < nc; i++)
            k->Fq[i + (size_t)j * nc] = (f1[i] - f0[i]) / h;
        h = 1e-7 * (1e-2 + fabs(vs[j]));
        vp[j] = vs[j] + h;
        forces_at(tr, t, qs, vp, f1);
        vp[j] = vs[j];
        for (int i = 0; i < nc; i++)
            k->Fv[i + (size_t)j * nc] = (f1[i] - f0[i]) / h;
    }
    /* L = I - F_q G - F_v CB */
    double worst = 0.0;
    for (int j = 0; j < nc; j++)
        for (int i = 0; i < nc; i++) {
            double s = 0.0;
            for (int m = 0; m < nc; m++)
                s += k->Fq[i + (size_t)m * nc] * k->G[m + (size_t)j * nc] +
                     k->Fv[i + (size_t)m * nc] * k->CB[m + (size_t)j * nc];
            k->L[i + (size_t)j * nc] = (i == j) - s;
            worst = fmax(worst, fabs(s));
        }
    k->loop = worst > 1e-12;
    k->lok = !k->loop || LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, nc, nc, k->L, nc, k->lpiv) == 0;
    for (int i = 0; i < tr->nlaw; i++)
        k->modes[i] = tr->law[i].mode;
    k->have_tangent = 1;
}

static int modes_changed(const gd_transient *tr)
{
    for (int i = 0; i < tr->nlaw; i++)
        if (tr->cond->modes[i] != tr->law[i].mode) return 1;
    return 0;
}

/* u (k->u) at (t, x) through the feedthrough loop; q_S, v_S in qs, vs. */
static void solve_loop(gd_transient *tr, double t, const double *x, double *qs, double *vs)
{
    gd_tr_condensed *k = tr->cond;
    const int nc = k->nc;
    double *y = k->work + 4 * nc, *yv = y + nc, *z = yv + nc;
    outputs(k, x, y);
    if (!k->have_tangent || modes_changed(tr)) {
        coords_of(k, y, yv, k->u, qs, vs);
        refresh_tangent(tr, t, qs, vs);
    }
    for (int it = 0; it < 30; it++) {
        coords_of(k, y, yv, k->u, qs, vs);
        forces_at(tr, t, qs, vs, z);
        if (!k->loop) {
            memcpy(k->u, z, (size_t)nc * sizeof *z);
            return;
        }
        double rmax = 0.0, zmax = 0.0;
        for (int i = 0; i < nc; i++) {
            z[i] = k->u[i] - z[i]; /* residual */
            rmax = fmax(rmax, fabs(z[i]));
            zmax = fmax(zmax, fabs(k->u[i]));
        }
        if (rmax <= 1e-12 * zmax || rmax == 0.0 || !k->lok) {
            if (rmax > 0) { /* the last evaluation's forces */
                for (int i = 0; i < nc; i++)
                    k->u[i] -= z[i];
                coords_of(k, y, yv, k->u, qs, vs);
            }
            return;
        }
        LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', nc, 1, k->L, nc, k->lpiv, z, nc);
        double dmax = 0.0;
        for (int i = 0; i < nc; i++) {
            k->u[i] -= z[i];
            dmax = fmax(dmax, fabs(z[i]));
        }
        k->loop_iters++;
        /* the laws are affine in their frozen modes (meshes) or weakly coupled through
         * C B (drag on speeds): a small Newton step leaves a residual of its square */
        if (dmax <= 1e-4 * zmax) {
            coords_of(k, y, yv, k->u, qs, vs);
            return;
        }
    }
}

void gd_tr_condensed_rhs(gd_transient *tr, double t, const double *x, double *xdot)
{
    gd_tr_condensed *k = tr->cond;
    const int ns = k->ns, nc = k->nc;
    double *qs = k->work + 7 * nc, *vs = qs + nc;
    solve_loop(tr, t, x, qs, vs);
    /* x' = A x + B u, A block diagonal in the modal basis (each state and its partner) */
    for (int i = 0; i < ns; i++) {
        const int p = k->partner[i];
        xdot[i] =
            k->A[i + (size_t)i * ns] * x[i] + (p != i ? k->A[i + (size_t)p * ns] * x[p] : 0.0);
    }
    if (!k->a_blocks)
        for (int j = 0; j < ns; j++)
            for (int i = 0; i < ns; i++)
                if (i != j && k->partner[i] != j) xdot[i] += k->A[i + (size_t)j * ns] * x[j];
    for (int j = 0; j < nc; j++) {
        const double uj = k->u[j];
        const double *b = k->B + (size_t)j * ns;
        for (int i = 0; i < ns; i++)
            xdot[i] += b[i] * uj;
    }
}

void gd_tr_condensed_fill(gd_transient *tr, double t, const double *x, double *q, double *v,
                          int all)
{
    gd_tr_condensed *k = tr->cond;
    const int nc = k->nc, ns = k->ns;
    double *qs = k->work + 7 * nc, *vs = qs + nc;
    solve_loop(tr, t, x, qs, vs);
    if (all) {
        /* every DOF: q from (x, u), q' from (x', 0) (docs/condense.md, "Recovery") */
        double *xd = k->work + 9 * nc;
        gd_tr_condensed_rhs(tr, t, x, xd);
        gd_condense_recover_state(k->c, x, k->u, q);
        memset(xd + ns, 0, (size_t)nc * sizeof *xd);
        gd_condense_recover_state(k->c, xd, xd + ns, v);
    }
    for (int i = 0; i < nc; i++) {
        q[k->dof[i]] = qs[i];
        v[k->dof[i]] = vs[i];
    }
    if (tr->np) prescribed_at(tr, t, q, v, tr->acc); /* their records: the motion itself */
}

/* ---- CVODE's linear solver: SUNDIALS' dense LU of I - gamma J on the small state ---- */

/* J = A + B du/dx at (t, x) into out (ns x ns, column-major), du/dx = L^-1 (F_q C + F_v C A)
 * (nc x ns) from the feedthrough loop u = f(C x + G u, C A x + C B u) */
static void jacobian(gd_transient *tr, double t, const double *x, double *out)
{
    gd_tr_condensed *k = tr->cond;
    const int ns = k->ns, nc = k->nc;
    double *qs = k->work + 7 * nc, *vs = qs + nc;
    solve_loop(tr, t, x, qs, vs);
    refresh_tangent(tr, t, qs, vs);
    double *D = k->D;
    for (int j = 0; j < ns; j++)
        for (int i = 0; i < nc; i++) {
            double s = 0.0;
            for (int m = 0; m < nc; m++)
                s += k->Fq[i + (size_t)m * nc] * k->C[m + (size_t)j * nc] +
                     k->Fv[i + (size_t)m * nc] * k->CA[m + (size_t)j * nc];
            D[i + (size_t)j * nc] = s;
        }
    if (k->loop && k->lok)
        LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', nc, ns, k->L, nc, k->lpiv, D, nc);
    memcpy(out, k->A, (size_t)ns * ns * sizeof *out);
    for (int j = 0; j < ns; j++)
        for (int m = 0; m < nc; m++) {
            double d = D[m + (size_t)j * nc];
            if (d == 0.0) continue;
            const double *b = k->B + (size_t)m * ns;
            double *Jj = out + (size_t)j * ns;
            for (int i = 0; i < ns; i++)
                Jj[i] += b[i] * d;
        }
    k->setups++;
}

int gd_tr_condensed_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix Jac, void *ud,
                        N_Vector tmp1, N_Vector tmp2, N_Vector tmp3)
{
    (void)fy;
    (void)tmp1;
    (void)tmp2;
    (void)tmp3;
    gd_transient *tr = ud;
    /* SUNDIALS' dense matrix: column-major, leading dimension = rows = ns */
    jacobian(tr, t, N_VGetArrayPointer(y), SUNDenseMatrix_Data(Jac));
    return 0;
}

/* CVODE's direct-solver interface (it keeps J, forms I - gamma J in the dense matrix and
 * calls set-up when gamma or J changed) with LAPACK's LU: SUNLinSol_Dense's own
 * elimination took 5.6e5 instructions per 42 x 42 factorisation and 4.7e4 per solve
 * (callgrind, the 236-DOF box), most of the run. */
static SUNLinearSolver_Type lu_type(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID lu_id(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_CUSTOM;
}

static int lu_setup(SUNLinearSolver S, SUNMatrix A)
{
    const int n = (int)SUNDenseMatrix_Rows(A);
    return LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n, n, SUNDenseMatrix_Data(A), n, S->content)
               ? SUNLS_LUFACT_FAIL /* > 0: recoverable, CVODE cuts the step */
               : SUNLS_SUCCESS;
}

/* x = (P L U)^-1 b with dgetrf's factors: the row interchanges, then the column-oriented
 * triangular solves (dgetrs costs 1.9e4 instructions per call at n = 42, these 4e3) */
static int lu_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype tol)
{
    (void)tol;
    const int n = (int)SUNDenseMatrix_Rows(A);
    const lapack_int *piv = S->content;
    const double *F = SUNDenseMatrix_Data(A);
    double *z = N_VGetArrayPointer(x);
    memcpy(z, N_VGetArrayPointer(b), (size_t)n * sizeof *z);
    for (int i = 0; i < n; i++) {
        const int p = piv[i] - 1;
        if (p != i) {
            const double h = z[i];
            z[i] = z[p];
            z[p] = h;
        }
    }
    for (int j = 0; j < n; j++) { /* L, unit diagonal */
        const double zj = z[j];
        const double *c = F + (size_t)j * n;
        for (int i = j + 1; i < n; i++)
            z[i] -= c[i] * zj;
    }
    for (int j = n - 1; j >= 0; j--) { /* U */
        const double *c = F + (size_t)j * n;
        const double zj = z[j] /= c[j];
        for (int i = 0; i < j; i++)
            z[i] -= c[i] * zj;
    }
    return SUNLS_SUCCESS;
}

static int lu_free(SUNLinearSolver S)
{
    if (!S) return 0;
    free(S->content);
    S->content = NULL;
    SUNLinSolFreeEmpty(S);
    return 0;
}

SUNLinearSolver gd_tr_condensed_solver(gd_transient *tr, N_Vector y, SUNContext ctx)
{
    (void)y;
    gd_tr_condensed *k = tr->cond;
    gd_tr_condensed_solver_free(tr);
    k->Jm = SUNDenseMatrix(k->ns, k->ns, ctx);
    SUNLinearSolver S = k->Jm ? SUNLinSolNewEmpty(ctx) : NULL;
    if (!S) return NULL;
    S->content = malloc((size_t)k->ns * sizeof(lapack_int));
    if (!S->content) {
        SUNLinSolFreeEmpty(S);
        return NULL;
    }
    S->ops->gettype = lu_type;
    S->ops->getid = lu_id;
    S->ops->setup = lu_setup;
    S->ops->solve = lu_solve;
    S->ops->free = lu_free;
    return S;
}

void gd_tr_condensed_solver_free(gd_transient *tr)
{
    if (tr->cond && tr->cond->Jm) SUNMatDestroy(tr->cond->Jm);
    if (tr->cond) tr->cond->Jm = NULL;
}

void gd_tr_condensed_atol(const gd_transient *tr, double atol_q, double atol_v, double *atol)
{
    /* a state's absolute tolerance: what moves the coordinates by atol_q (displacement)
     * or, through its rate |A row|, by atol_v */
    const gd_tr_condensed *k = tr->cond;
    const int ns = k->ns, nc = k->nc;
    double cmax_all = 0.0;
    for (size_t p = 0; p < (size_t)nc * ns; p++)
        cmax_all = fmax(cmax_all, fabs(k->C[p]));
    for (int j = 0; j < ns; j++) {
        double cmax = 0.0, arow = 0.0;
        for (int i = 0; i < nc; i++)
            cmax = fmax(cmax, fabs(k->C[i + (size_t)j * nc]));
        for (int m = 0; m < ns; m++)
            arow += fabs(k->A[j + (size_t)m * ns]);
        if (!(cmax > 1e-12 * cmax_all)) cmax = cmax_all > 0 ? cmax_all : 1.0;
        double a = atol_q / cmax;
        if (arow > 0) a = fmin(a, atol_v / (arow * cmax));
        atol[j] = a;
    }
}

void gd_tr_condensed_tolerances(gd_transient *tr, double rtol, double atol_q, double atol_v)
{
    gd_tr_condensed *k = tr->cond;
    k->rtol = rtol;
    k->atol_q = atol_q;
    k->atol_v = atol_v;
    memset(k->yscale, 0, (size_t)2 * k->nc * sizeof *k->yscale);
    k->have_ewt = 0;
}

/* CVODE's error weights from what the state is integrated for, the coordinates (their
 * displacements and rates feed the laws and the contact metrics): state j's error e_j
 * moves coordinate i by C_ij e_j and its rate by (C A)_ij e_j, and each coordinate is
 * wanted to rtol of its largest excursion so far (Y_i, V_i) plus atol, so
 *   w_j = max_i max(|C_ij| / (rtol Y_i + atol_q), |(C A)_ij| / (rtol V_i + atol_v)),
 * the larger of a mode's two states for both (they exchange amplitude every period).
 * CVODE's default rtol |x_j| + atol_j asks every kept mode for its own relative accuracy:
 * a lightly damped shaft mode ringing at 1e-9 of the coordinates then sets the step. */
int gd_tr_condensed_ewt(N_Vector y, N_Vector ewt, void *ud)
{
    gd_transient *tr = ud;
    gd_tr_condensed *k = tr->cond;
    const int ns = k->ns, nc = k->nc;
    const double *x = N_VGetArrayPointer(y);
    double *w = N_VGetArrayPointer(ewt), *yq = k->work + 4 * nc, *yv = yq + nc;
    double *Y = k->yscale, *V = Y + nc;
    outputs(k, x, yq);
    /* the scales grow in steps of 5 %: the weights are recomputed only then */
    int grew = !k->have_ewt;
    for (int i = 0; i < nc; i++) {
        const double a = fabs(yq[i]), b = fabs(yv[i]);
        if (a > 1.05 * Y[i]) Y[i] = a, grew = 1;
        if (b > 1.05 * V[i]) V[i] = b, grew = 1;
    }
    double *W = k->ewt;
    if (grew) {
        for (int i = 0; i < nc; i++) {
            yq[i] = 1.0 / (k->rtol * Y[i] + k->atol_q);
            yv[i] = 1.0 / (k->rtol * V[i] + k->atol_v);
        }
        for (int j = 0; j < ns; j++) {
            const double *c = k->C + (size_t)j * nc, *ca = k->CA + (size_t)j * nc;
            double m = 0.0;
            for (int i = 0; i < nc; i++) {
                const double a = fabs(c[i]) * yq[i], b = fabs(ca[i]) * yv[i];
                m = a > m ? a : m;
                m = b > m ? b : m;
            }
            W[j] = m;
        }
        for (int j = 0; j < ns; j++) {
            const int p = k->partner[j];
            if (p > j) W[j] = W[p] = W[j] > W[p] ? W[j] : W[p];
        }
        for (int j = 0; j < ns; j++)
            if (!(W[j] > 0)) W[j] = 1.0 / k->atol_q; /* a state no coordinate sees */
        k->have_ewt = 1;
    }
    memcpy(w, W, (size_t)ns * sizeof *w);
    return 0;
}

void gd_tr_condensed_reset(gd_transient *tr)
{
    gd_tr_condensed *k = tr->cond;
    memset(k->u, 0, (size_t)k->nc * sizeof *k->u);
    k->have_tangent = 0;
    k->have_out = 0;
    k->loop_iters = 0;
    k->setups = 0;
}

/* ---- construction ---- */

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The highest frequency the laws impose (loads' orders, tooth-mesh harmonics of TVMS and
 * STE tables), rad/s; 0 when none. */
static double excitation_band(const gd_transient *tr)
{
    double wmax = 0.0, w[64];
    char msg[128];
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        if (!L->type->frequencies) continue;
        int nw = L->type->frequencies(L, w, 64, msg, sizeof msg);
        for (int j = 0; j < nw; j++)
            wmax = fmax(wmax, w[j]);
    }
    for (int i = 0; i < tr->nunb; i++)
        wmax = fmax(wmax, fabs(tr->unb[i].omega));
    for (int p = 0; p < tr->np; p++) { /* its forcing through the coupling blocks */
        int nw = gd_prescribed_frequencies(&tr->pres[p].law, tr->rate[tr->pres[p].dof], w, 64, msg,
                                           sizeof msg);
        for (int j = 0; j < nw; j++)
            wmax = fmax(wmax, fabs(w[j]));
    }
    return wmax;
}

/* The highest contact frequency sqrt(k / m_e) of the backlash meshes, rad/s. */
static double contact_band(gd_transient *tr)
{
    double wmax = 0.0;
    for (int l = 0; l < tr->nmesh; l++) { /* the spec's meshes: law[0 .. nmesh - 1] */
        if (!gd_law_nswitches(&tr->law[l])) continue;
        const gd_mesh_law_data *d = tr->law[l].data;
        double k = fmax(d->stiffness, d->k_lin), me = 0.0; /* TVMS: its mean */
        gd_error e;
        if (gd_transient_mesh_mass(tr, l, &me, &e) || !(me > 0)) continue;
        if (k > 0) wmax = fmax(wmax, sqrt(k / me));
        if (d->coast_scale > 0) wmax = fmax(wmax, sqrt(d->coast_scale * k / me));
    }
    return wmax;
}

/* The coordinates S: the free DOFs the laws and unbalances act on and those a prescribed
 * DOF is coupled to (K, D, M), mark[i] = 1 (n zeroed ints); their count. */
static int law_dofs(const gd_transient *tr, int *mark)
{
    for (int p = 0; p < tr->np; p++) {
        const int d = tr->pres[p].dof;
        const cs *A[3] = {tr->K, tr->D, tr->M};
        for (int a = 0; a < 3; a++)
            for (int e = A[a]->p[d]; e < A[a]->p[d + 1]; e++)
                if (A[a]->x[e] != 0.0) mark[A[a]->i[e]] = 1;
    }
    for (int i = 0; i < tr->nlaw; i++)
        for (int j = 0; j < tr->law[i].ndofs; j++)
            if (tr->law[i].dof[j] >= 0) mark[tr->law[i].dof[j]] = 1;
    for (int i = 0; i < tr->nunb_all; i++) {
        if (tr->unb[i].dx >= 0) mark[tr->unb[i].dx] = 1;
        if (tr->unb[i].dy >= 0) mark[tr->unb[i].dy] = 1;
    }
    int nc = 0;
    for (int i = 0; i < tr->n; i++) {
        if (tr->fidx[i] < 0) mark[i] = 0; /* prescribed: its motion is known */
        nc += mark[i];
    }
    return nc;
}

int gd_transient_condense_pays(const gd_transient *tr, char *why, size_t len)
{
    char lin[160];
    if (tr->cond) {
        snprintf(why, len, "condensed already");
        return 0;
    }
    if (tr->red) {
        snprintf(why, len, "a reduced model");
        return 0;
    }
    if (tr->n < GD_TRANSIENT_CONDENSE_DOFS) {
        snprintf(why, len, "%d DOFs, fewer than %d", tr->n, GD_TRANSIENT_CONDENSE_DOFS);
        return 0;
    }
    if (tr->nin) {
        snprintf(why, len, "cam inertia");
        return 0;
    }
    if (tr->np && tr->n > GD_CONDENSE_DENSE_MAX) {
        snprintf(why, len, "prescribed DOFs on %d DOFs, more than %d (dense only)", tr->n,
                 GD_CONDENSE_DENSE_MAX);
        return 0;
    }
    if (gd_tr_lti_reason(tr, lin, sizeof lin)) {
        snprintf(why, len, "linear: the lti method is exact");
        return 0;
    }
    if (tr->sys->nlaws > 0 && tr->n > GD_TR_CONDENSE_DENSE_MAX) {
        snprintf(why, len, "%d DOFs, more than %d with model laws", tr->n,
                 GD_TR_CONDENSE_DENSE_MAX);
        return 0;
    }
    int *mark = calloc((size_t)tr->n, sizeof *mark);
    if (!mark) {
        snprintf(why, len, "out of memory");
        return 0;
    }
    const int nc = law_dofs(tr, mark);
    free(mark);
    if (nc == 0 || nc * GD_TRANSIENT_CONDENSE_FEW > tr->n) {
        snprintf(why, len, "laws on %d of %d DOFs, more than 1 in %d", nc, tr->n,
                 GD_TRANSIENT_CONDENSE_FEW);
        return 0;
    }
    snprintf(why, len, "%d DOFs, laws on %d", tr->n, nc);
    return 1;
}

gd_status gd_transient_new_condensed(const gd_system *sys, const gd_transient_spec *spec,
                                     double speed, double cutoff, gd_transient **out, gd_error *err)
{
    *out = NULL;
    const char *file = sys->model ? sys->model->file : "";
    gd_transient *tr = NULL;
    gd_status st = gd_transient_new(sys, spec, speed, &tr, err);
    if (st) return st;
    if (tr->np && tr->n > GD_CONDENSE_DENSE_MAX) {
        st = gd_error_set(err, GD_EINPUT, file, 0, 0, "prescribed",
                          "integrate the full model (--condense off)",
                          "the condensed transient clamps prescribed DOFs on the dense "
                          "condensation: up to %d DOFs, not %d",
                          GD_CONDENSE_DENSE_MAX, tr->n);
        goto fail;
    }
    if (tr->nin) {
        st = gd_error_set(err, GD_EINPUT, file, 0, 0, "cam_torques",
                          "integrate the full model (--condense off)",
                          "the condensed transient has no configuration-dependent inertia "
                          "(cam_acceleration)");
        goto fail;
    }
    const int n = tr->n;
    gd_tr_condensed *k = calloc(1, sizeof *k);
    int *mark = calloc((size_t)n, sizeof *mark);
    if (!k || !mark) {
        free(k);
        free(mark);
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        goto fail;
    }
    tr->cond = k;
    tr->cond_fill = gd_tr_condensed_fill;
    tr->cond_rhs = gd_tr_condensed_rhs;
    tr->cond_free = gd_tr_condensed_free;
    const int nc = law_dofs(tr, mark);
    if (nc == 0) {
        free(mark);
        st = gd_error_set(err, GD_EINPUT, file, 0, 0, "laws",
                          "integrate the full model: --method auto runs a linear model exactly",
                          "no law, mesh law or unbalance to condense onto");
        goto fail;
    }
    k->nc = nc;
    k->dof = malloc((size_t)nc * sizeof *k->dof);
    if (!k->dof) {
        free(mark);
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        goto fail;
    }
    for (int i = 0, m = 0; i < n; i++)
        if (mark[i]) k->dof[m++] = i;
    free(mark);
    qsort(k->dof, (size_t)nc, sizeof *k->dof, cmp_int);

    /* the cut-off: every mode when cutoff == 0; the rule when < 0 */
    k->w_exc = excitation_band(tr);
    k->w_contact = contact_band(tr);
    if (cutoff < 0)
        cutoff = fmax(GD_TR_CONDENSE_EXC * k->w_exc, GD_TR_CONDENSE_CONTACT * k->w_contact);
    k->cutoff = cutoff;
    int nmodes = 0;
    if (cutoff > 0) {
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.speed = speed;
        gd_modal_result *mr = NULL;
        if ((st = gd_modal_solve(sys, &mo, &mr, err))) goto fail;
        int total = 0;
        for (int j = 0; j < mr->nmodes; j++) {
            if (mr->modes[j].rigid_body) continue;
            total++;
            if (mr->modes[j].omega_n <= cutoff) nmodes++;
        }
        gd_modal_free(mr);
        if (nmodes == 0) nmodes = 1;
        if (nmodes >= total) nmodes = 0; /* all: exact */
    }

    gd_condense_coords cc;
    gd_condense_coords_init(&cc);
    for (int i = 0; i < nc && !st; i++) {
        char lab[GD_CONDENSE_LABEL_MAX];
        double one = 1.0;
        gd_system_dof_label(sys, k->dof[i], lab, sizeof lab);
        st = gd_condense_coords_add(&cc, sys, lab, 1, &k->dof[i], &one, err);
    }
    gd_condense_options o;
    gd_condense_options_init(&o);
    o.speed = speed;
    o.nmodes = nmodes;
    int *held = NULL;
    if (!st && tr->np) { /* the structure clamped at the prescribed DOFs */
        if (!(held = malloc((size_t)n * sizeof *held)))
            st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        for (int i = 0; held && i < n; i++)
            held[i] = tr->fidx[i] < 0;
        o.held = held;
        o.method = GD_CONDENSE_DENSE;
    }
    if (!st) st = gd_condense_build(sys, &cc, &o, &k->c, err);
    free(held);
    gd_condense_coords_release(&cc);
    if (st) goto fail;
    gd_condense_lti l;
    gd_condense_state_space(k->c, &l);
    const int ns = l.nstates;
    k->ns = ns;
    k->A = l.A;
    k->B = l.B;
    k->C = l.C;
    k->G = l.G;
    gd_condense_info_get(k->c, &k->info);
    k->CA = calloc((size_t)nc * ns, sizeof *k->CA);
    k->CB = calloc((size_t)nc * nc, sizeof *k->CB);
    k->dK = calloc((size_t)nc * nc, sizeof *k->dK);
    k->dD = calloc((size_t)nc * nc, sizeof *k->dD);
    k->u = calloc((size_t)nc, sizeof *k->u);
    k->Fq = calloc((size_t)nc * nc, sizeof *k->Fq);
    k->Fv = calloc((size_t)nc * nc, sizeof *k->Fv);
    k->L = calloc((size_t)nc * nc, sizeof *k->L);
    k->lpiv = calloc((size_t)nc, sizeof *k->lpiv);
    k->D = calloc((size_t)nc * ns, sizeof *k->D);
    k->yscale = calloc((size_t)2 * nc, sizeof *k->yscale);
    k->ewt = calloc((size_t)ns, sizeof *k->ewt);
    k->CCA = calloc((size_t)2 * nc * ns, sizeof *k->CCA);
    k->xout = calloc((size_t)ns, sizeof *k->xout);
    k->yout = calloc((size_t)2 * nc, sizeof *k->yout);
    k->partner = malloc((size_t)ns * sizeof *k->partner);
    k->work = calloc((size_t)9 * nc + ns + nc, sizeof *k->work);
    k->modes = calloc((size_t)(tr->nlaw ? tr->nlaw : 1), sizeof *k->modes);
    if (!k->CA || !k->CB || !k->dK || !k->dD || !k->u || !k->Fq || !k->Fv || !k->L || !k->lpiv ||
        !k->D || !k->yscale || !k->ewt || !k->CCA || !k->xout || !k->yout || !k->partner ||
        !k->work || !k->modes) {
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        goto fail;
    }
    /* a mode's two states (a conjugate pair's real and imaginary part, a rigid mode's
     * amplitude and rate): the other state A couples it to (A is block diagonal) */
    for (int j = 0; j < ns; j++) {
        k->partner[j] = j;
        for (int m = 0; m < ns; m++)
            if (m != j && (k->A[j + (size_t)m * ns] != 0.0 || k->A[m + (size_t)j * ns] != 0.0)) {
                k->partner[j] = m;
                break;
            }
    }
    k->a_blocks = 1;
    for (int j = 0; j < ns; j++)
        for (int i = 0; i < ns; i++)
            if (i != j && k->partner[i] != j && k->A[i + (size_t)j * ns] != 0.0) k->a_blocks = 0;
    /* CA = C A, CB = C B */
    for (int j = 0; j < ns; j++)
        for (int m = 0; m < ns; m++) {
            double a = k->A[m + (size_t)j * ns];
            if (a == 0.0) continue;
            for (int i = 0; i < nc; i++)
                k->CA[i + (size_t)j * nc] += k->C[i + (size_t)m * nc] * a;
        }
    for (int j = 0; j < nc; j++)
        for (int m = 0; m < ns; m++) {
            double b = k->B[m + (size_t)j * ns];
            if (b == 0.0) continue;
            for (int i = 0; i < nc; i++)
                k->CB[i + (size_t)j * nc] += k->C[i + (size_t)m * nc] * b;
        }
    for (int j = 0; j < ns; j++) {
        memcpy(k->CCA + (size_t)j * 2 * nc, k->C + (size_t)j * nc, (size_t)nc * sizeof *k->CCA);
        memcpy(k->CCA + (size_t)j * 2 * nc + nc, k->CA + (size_t)j * nc,
               (size_t)nc * sizeof *k->CCA);
    }
    /* K_L, C_L: what the condensed structure (gd_system_dense) holds beyond the
     * transient's linear part, only on law DOFs (S x S) */
    if (sys->nlaws > 0) {
        if (n > GD_TR_CONDENSE_DENSE_MAX) {
            st = gd_error_set(err, GD_EINPUT, file, 0, 0, "laws",
                              "integrate the full model (--condense off)",
                              "the condensed transient with model laws takes their "
                              "linearisation from the dense matrices: up to %d DOFs, not %d",
                              GD_TR_CONDENSE_DENSE_MAX, n);
            goto fail;
        }
        double *Kd = malloc((size_t)n * n * sizeof *Kd), *Dd = malloc((size_t)n * n * sizeof *Dd);
        int *pos = malloc((size_t)n * sizeof *pos);
        if (!Kd || !Dd || !pos) {
            free(Kd);
            free(Dd);
            free(pos);
            st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
            goto fail;
        }
        gd_system_dense(sys, speed, NULL, Dd, Kd);
        for (int j = 0; j < n; j++) { /* minus the transient's K and D */
            for (int p = tr->K->p[j]; p < tr->K->p[j + 1]; p++)
                Kd[tr->K->i[p] + (size_t)j * n] -= tr->K->x[p];
            for (int p = tr->D->p[j]; p < tr->D->p[j + 1]; p++)
                Dd[tr->D->i[p] + (size_t)j * n] -= tr->D->x[p];
        }
        for (int i = 0; i < n; i++)
            pos[i] = -1;
        for (int i = 0; i < nc; i++)
            pos[k->dof[i]] = i;
        double big = 0.0, outside = 0.0;
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double kv = Kd[i + (size_t)j * n], dv = Dd[i + (size_t)j * n];
                if (tr->fidx[i] < 0 || tr->fidx[j] < 0) continue; /* clamped: the laws' own */
                if (pos[i] >= 0 && pos[j] >= 0) {
                    k->dK[pos[i] + (size_t)pos[j] * nc] = kv;
                    k->dD[pos[i] + (size_t)pos[j] * nc] = dv;
                    big = fmax(big, fmax(fabs(kv), fabs(dv)));
                } else {
                    outside = fmax(outside, fmax(fabs(kv), fabs(dv)));
                }
            }
        free(Kd);
        free(Dd);
        free(pos);
        if (outside > 1e-9 * (big > 0 ? big : 1.0) && outside > 0) {
            st = gd_error_set(err, GD_ENUMERIC, file, 0, 0, "laws", "",
                              "the structure's law linearisation reaches DOFs no law acts on "
                              "(%.3g): cannot condense",
                              outside);
            goto fail;
        }
    }
    /* the truncation estimate at the top of the excitation band, relative to the
     * largest receptance there */
    k->est_rel = 0.0;
    if (k->info.ndiscarded > 0 && k->w_exc > 0) {
        double *H = malloc((size_t)2 * nc * nc * sizeof *H), est = 0.0;
        if (H) {
            gd_condense_receptance(k->c, k->w_exc, H, &est);
            double hmax = 0.0;
            for (size_t p = 0; p < (size_t)nc * nc; p++)
                hmax = fmax(hmax, hypot(H[2 * p], H[2 * p + 1]));
            k->est_rel = hmax > 0 ? est / hmax : 0.0;
            free(H);
        }
    }
    *out = tr;
    return GD_OK;
fail:
    gd_transient_free(tr);
    return st;
}

int gd_transient_condensed_info(const gd_transient *tr, gd_tr_condensed_info *info)
{
    memset(info, 0, sizeof *info);
    if (!tr->cond) return 0;
    const gd_tr_condensed *k = tr->cond;
    info->ncoords = k->nc;
    info->nstates = k->ns;
    info->nkept = k->info.nkept;
    info->ndiscarded = k->info.ndiscarded;
    info->nrigid = k->info.nrigid;
    info->cutoff = k->cutoff;
    info->first_discarded = k->info.first_discarded;
    info->excitation = k->w_exc;
    info->contact = k->w_contact;
    info->static_correction = k->info.residual;
    info->estimate = k->est_rel;
    return 1;
}
