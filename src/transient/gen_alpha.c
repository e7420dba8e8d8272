/* Fixed-step generalized-alpha integration (Chung & Hulbert 1993, J. Appl. Mech. 60,
 * 371-375) of M q'' + D q' + K q = f(t, q, q') on the free DOFs:
 *
 *   M a_{n+1-am} + (forces at the alpha point t_{n+1-af}, q_{n+1-af}, v_{n+1-af}) = 0,
 *   x_{n+1-alpha} = (1 - alpha) x_{n+1} + alpha x_n,
 *   q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1}),
 *   v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1}),
 *
 * with am = (2 rho - 1) / (rho + 1), af = rho / (rho + 1), gamma = 1/2 - am + af,
 * beta = (1 - am + af)^2 / 4 (their Eqs. 17 and 25): second order, unconditionally
 * stable for linear systems, spectral radius rho_inf at infinite step (rho = 1: Newmark's
 * average acceleration; am = 0: HHT-alpha family).
 *
 * Newton on a_{n+1} with the matrix S = (1 - am) M + (1 - af) (gamma h D + beta h^2 K),
 * factored once per step size (sparse LU, CSparse). The force laws enter through their
 * tangent: a mesh whose law's stiffness or damping differs from the linear k a a^T,
 * c a a^T assembled in K and D (backlash flank, separation, time-varying stiffness)
 * adds a rank-one term c_m a a^T, solved exactly by the Woodbury identity with the
 * vectors S^-1 a computed once per factorisation, so contact changes never refactor.
 * The backlash contact state follows the iterate (semi-smooth Newton). Squeeze film
 * dampers and angle-dependent loads keep S as their tangent (modified Newton). A linear
 * system (no such law) takes exactly one solve per step. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "transient/transient_impl.h"

typedef struct ga {
    gd_transient *tr;
    int nf, nw, linear, piecewise;
    double am, af, gamma, beta, h, atol;
    csn *N;
    int *wlaw;     /* nw: laws with a tangent update (GD_LAW_TANGENT: a mesh) */
    double *wu;    /* nw x GD_LAW_MAX_DOFS: their term 0's local u (= w) */
    int *wsw;      /* nw: their switch counts (gd_law_nswitches) */
    double *W;     /* nf x nw: S^-1 a_m (free part) */
    double *B, *z; /* nw x nw, nw */
    double *cm;    /* nw: rank-one coefficients of the current iterate */
    double *q, *v, *a, *q1, *v1, *a1, *y2, *R, *x;
} ga;

static void ga_free(ga *g)
{
    cs_nfree(g->N);
    free(g->wlaw);
    free(g->wu);
    free(g->wsw);
    free(g->W);
    free(g->B);
    free(g->z);
    free(g->cm);
    free(g->q);
    free(g->y2);
}

static int ga_alloc(ga *g, gd_transient *tr)
{
    memset(g, 0, sizeof *g);
    g->tr = tr;
    g->nf = tr->nf;
    int nf = tr->nf, nm = tr->nlaw > 0 ? tr->nlaw : 1;
    g->wlaw = malloc((size_t)nm * sizeof *g->wlaw);
    g->wu = calloc((size_t)nm * GD_LAW_MAX_DOFS, sizeof *g->wu);
    g->wsw = malloc((size_t)nm * sizeof *g->wsw);
    g->W = malloc((size_t)nm * (nf > 0 ? nf : 1) * sizeof *g->W);
    g->B = malloc((size_t)nm * nm * sizeof *g->B);
    g->z = malloc((size_t)nm * sizeof *g->z);
    g->cm = malloc((size_t)nm * sizeof *g->cm);
    g->q = malloc((size_t)8 * (nf > 0 ? nf : 1) * sizeof *g->q);
    g->y2 = malloc((size_t)2 * (nf > 0 ? nf : 1) * sizeof *g->y2);
    if (!g->wlaw || !g->wu || !g->wsw || !g->W || !g->B || !g->z || !g->cm || !g->q || !g->y2)
        return 1;
    g->v = g->q + nf;
    g->a = g->v + nf;
    g->q1 = g->a + nf;
    g->v1 = g->q1 + nf;
    g->a1 = g->v1 + nf;
    g->R = g->a1 + nf;
    g->x = g->R + nf;
    /* linear: every law linear and time-invariant (a mesh at its assembled stiffness);
     * piecewise linear: affine in (q, q') within each mode (laws of time only, such as
     * loads of time; mesh laws whose angle is the driver's nominal or prescribed
     * motion); the laws that differ from their assembled k a a^T, c a a^T get a
     * rank-one tangent update (their term 0) */
    g->linear = 1;
    g->piecewise = 1;
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        unsigned f = gd_law_flags(L);
        if (!(f & GD_LAW_LINEAR)) g->linear = 0;
        if (!(f & (GD_LAW_TIME_ONLY | GD_LAW_PIECEWISE))) g->piecewise = 0;
        if (f & GD_LAW_TANGENT) {
            double w[GD_LAW_MAX_DOFS] = {0};
            L->type->term(L, 0, g->wu + (size_t)g->nw * GD_LAW_MAX_DOFS, w);
            g->wsw[g->nw] = gd_law_nswitches(L);
            g->wlaw[g->nw++] = i;
        }
    }
    /* a run-up: the gyroscopic and speed-table bearing terms at W(t) are not in the
     * tangent (it holds them at the reference speed): iterate to convergence */
    if (tr->prof) g->linear = g->piecewise = 0;
    return 0;
}

/* x = S^-1 b (b overwritten). */
static void s_solve(ga *g, double *b, double *x)
{
    const gd_transient *tr = g->tr;
    cs_ipvec(g->N->pinv, b, x, g->nf);
    cs_lsolve(g->N->L, x);
    cs_usolve(g->N->U, x);
    cs_ipvec(tr->Ssym->q, x, b, g->nf);
    memcpy(x, b, (size_t)g->nf * sizeof *x);
}

/* Free part of tangent vector w (law g->wlaw[w]'s u), dotted with x (length nf). */
static double a_dot(const ga *g, int w, const double *x)
{
    const gd_transient *tr = g->tr;
    const gd_law *L = &tr->law[g->wlaw[w]];
    const double *u = g->wu + (size_t)w * GD_LAW_MAX_DOFS;
    double s = 0;
    for (int j = 0; j < L->ndofs; j++) {
        int f = L->dof[j] >= 0 ? tr->fidx[L->dof[j]] : -1;
        if (f >= 0) s += u[j] * x[f];
    }
    return s;
}

/* Factors S for step h and solves S W = A. 0 ok, 1 singular. */
static int ga_factor(ga *g, double h)
{
    gd_transient *tr = g->tr;
    const int nf = g->nf;
    double cM = 1.0 - g->am, cD = (1.0 - g->af) * g->gamma * h,
           cK = (1.0 - g->af) * g->beta * h * h;
    cs *S = tr->S;
    memset(S->x, 0, (size_t)S->p[S->n] * sizeof *S->x);
    for (int p = 0; p < tr->Mff->p[nf]; p++)
        S->x[tr->mapM[p]] += cM * tr->Mff->x[p];
    for (int p = 0; p < tr->Dff->p[nf]; p++)
        S->x[tr->mapD[p]] += cD * tr->Dff->x[p];
    for (int p = 0; p < tr->Kff->p[nf]; p++)
        S->x[tr->mapK[p]] += cK * tr->Kff->x[p];
    cs_nfree(g->N);
    g->N = cs_lu(S, tr->Ssym, 1e-3);
    if (!g->N) return 1;
    g->h = h;
    for (int w = 0; w < g->nw; w++) {
        const gd_law *L = &tr->law[g->wlaw[w]];
        const double *u = g->wu + (size_t)w * GD_LAW_MAX_DOFS;
        double *b = g->R, *col = g->W + (size_t)w * nf;
        memset(b, 0, (size_t)nf * sizeof *b);
        for (int j = 0; j < L->ndofs; j++) {
            int f = L->dof[j] >= 0 ? tr->fidx[L->dof[j]] : -1;
            if (f >= 0) b[f] += u[j];
        }
        s_solve(g, b, col);
    }
    return 0;
}

/* Law L's tangent stiffness and damping along its term 0 in its current mode at x (the
 * alpha point), less the assembled linear terms: -df/dq, -df/dq'. */
static void law_tangent(gd_transient *tr, const gd_law *L, const gd_law_point *x, double *dk,
                        double *dc)
{
    double jq[GD_LAW_MAX_TERMS], jv[GD_LAW_MAX_TERMS];
    memset(tr->lf, 0, (size_t)L->ndofs * sizeof *tr->lf);
    L->type->force(L, x, tr->lf, jq, jv);
    *dk = -jq[0];
    *dc = -jv[0];
}

/* x = S_t^-1 R with S_t = S + sum_w cm_w a_w a_w^T (Woodbury); R overwritten. */
static int tangent_solve(ga *g, double *R, double *x)
{
    const int nf = g->nf, nw = g->nw;
    s_solve(g, R, x);
    int any = 0;
    for (int w = 0; w < nw; w++)
        any |= g->cm[w] != 0.0;
    if (!any) return 0;
    /* (I + C A^T W) z = C A^T x,  x -= W z */
    for (int i = 0; i < nw; i++) {
        g->z[i] = g->cm[i] * a_dot(g, i, x);
        for (int j = 0; j < nw; j++)
            g->B[i + j * nw] = (i == j ? 1.0 : 0.0) + g->cm[i] * a_dot(g, i, g->W + (size_t)j * nf);
    }
    lapack_int ipiv[64], *piv = nw <= 64 ? ipiv : malloc((size_t)nw * sizeof *piv);
    if (!piv) return 1;
    lapack_int info = LAPACKE_dgesv(LAPACK_COL_MAJOR, nw, 1, g->B, nw, piv, g->z, nw);
    if (piv != ipiv) free(piv);
    if (info) return 1;
    for (int j = 0; j < nw; j++) {
        const double *col = g->W + (size_t)j * nf;
        double zj = g->z[j];
        for (int i = 0; i < nf; i++)
            x[i] -= col[i] * zj;
    }
    return 0;
}

/* Net force on the free DOFs (without their inertia) at (t, q, v) into out. */
static void free_force(ga *g, double t, const double *q, const double *v, double *out)
{
    gd_transient *tr = g->tr;
    const int nf = g->nf;
    memcpy(g->y2, q, (size_t)nf * sizeof *q);
    memcpy(g->y2 + nf, v, (size_t)nf * sizeof *v);
    gd_tr_fill(tr, t, g->y2, tr->q, tr->v, tr->acc);
    gd_tr_residual(tr, t, tr->q, tr->v, tr->acc, tr->r);
    for (int i = 0; i < nf; i++)
        out[i] = tr->r[tr->free_dof[i]];
}

/* 1 when every law with switches (a backlash mesh) is, at the alpha point of the
 * current a1, in the mode the last iterate used. */
static int same_states(ga *g, double ta)
{
    gd_transient *tr = g->tr;
    const int nf = g->nf;
    const double h = g->h, af = g->af, be = g->beta, ga_ = g->gamma;
    for (int i = 0; i < nf; i++) {
        double qn = g->q[i] + h * g->v[i] + h * h * ((0.5 - be) * g->a[i] + be * g->a1[i]);
        double vn = g->v[i] + h * ((1.0 - ga_) * g->a[i] + ga_ * g->a1[i]);
        g->y2[i] = (1.0 - af) * qn + af * g->q[i];
        g->y2[nf + i] = (1.0 - af) * vn + af * g->v[i];
    }
    gd_tr_fill(tr, ta, g->y2, tr->q, tr->v, NULL);
    for (int w = 0; w < g->nw; w++) {
        const gd_law *L = &tr->law[g->wlaw[w]];
        if (!g->wsw[w]) continue;
        gd_law_point x;
        gd_tr_law_here(tr, L, ta, &x);
        if (L->type->mode_at(L, &x) != L->mode) return 0;
    }
    return 1;
}

/* One step from (t, q, v, a) to t + h into q1, v1, a1. Returns the Newton iterations,
 * or -1 when they did not converge. */
static int ga_step(ga *g, double t, long *nres)
{
    gd_transient *tr = g->tr;
    const int nf = g->nf;
    const double h = g->h, am = g->am, af = g->af, be = g->beta, ga_ = g->gamma;
    const double ta = t + (1.0 - af) * h;
    memcpy(g->a1, g->a, (size_t)nf * sizeof *g->a1);
    for (int it = 1; it <= 50; it++) {
        double *qa = g->q1, *va = g->v1; /* alpha-point state, then the new state */
        for (int i = 0; i < nf; i++) {
            double qn = g->q[i] + h * g->v[i] + h * h * ((0.5 - be) * g->a[i] + be * g->a1[i]);
            double vn = g->v[i] + h * ((1.0 - ga_) * g->a[i] + ga_ * g->a1[i]);
            qa[i] = (1.0 - af) * qn + af * g->q[i];
            va[i] = (1.0 - af) * vn + af * g->v[i];
        }
        memcpy(g->y2, qa, (size_t)nf * sizeof *qa);
        memcpy(g->y2 + nf, va, (size_t)nf * sizeof *va);
        gd_tr_fill(tr, ta, g->y2, tr->q, tr->v, tr->acc);
        for (int w = 0; w < g->nw; w++) {
            gd_law *L = &tr->law[g->wlaw[w]];
            gd_law_point x;
            gd_tr_law_here(tr, L, ta, &x);
            if (g->wsw[w]) L->mode = L->type->mode_at(L, &x);
            double dk, dc;
            law_tangent(tr, L, &x, &dk, &dc);
            g->cm[w] = (1.0 - af) * (be * h * h * dk + ga_ * h * dc);
        }
        gd_tr_residual(tr, ta, tr->q, tr->v, tr->acc, tr->r);
        (*nres)++;
        /* R = M ((1 - am) a1 + am a) - f */
        for (int i = 0; i < nf; i++) {
            g->x[i] = (1.0 - am) * g->a1[i] + am * g->a[i];
            g->R[i] = -tr->r[tr->free_dof[i]];
        }
        const cs *M = tr->Mff;
        for (int j = 0; j < nf; j++)
            for (int p = M->p[j]; p < M->p[j + 1]; p++)
                g->R[M->i[p]] += M->x[p] * g->x[j];
        if (tangent_solve(g, g->R, g->x)) return -1;
        /* converged when the update moves no displacement by more than atol_q + 1e-10
         * of it (DOF by DOF: accelerations mix m/s^2 with the rad/s^2 of light tilts,
         * whose round-off would stall a relative test on a) */
        int conv = 1;
        for (int i = 0; i < nf; i++) {
            g->a1[i] -= g->x[i];
            double qn = fabs(g->q[i]) + h * fabs(g->v[i]);
            if (be * h * h * fabs(g->x[i]) > g->atol + 1e-10 * qn) conv = 0;
        }
        /* piecewise linear: the step is exact once the contact states it assumed hold
         * at the new alpha point (saves the checking iteration) */
        if (!conv && g->piecewise && same_states(g, ta)) conv = 1;
        if (g->linear || conv) {
            for (int i = 0; i < nf; i++) {
                g->q1[i] = g->q[i] + h * g->v[i] + h * h * ((0.5 - be) * g->a[i] + be * g->a1[i]);
                g->v1[i] = g->v[i] + h * ((1.0 - ga_) * g->a[i] + ga_ * g->a1[i]);
            }
            return it;
        }
    }
    return -1;
}

gd_status gd_tr_run_gen_alpha(gd_transient *tr, const gd_transient_options *opt,
                              const gd_tr_record *records, int nrecords, double from, double dt,
                              double *y, gd_transient_result *res, gd_tr_contact_track *track,
                              gd_error *err)
{
    const int nf = tr->nf, nout = res->nout;
    double rho = opt->rho_inf;
    if (!(rho >= 0.0 && rho <= 1.0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "rho_inf", "give a value from 0 to 1",
                            "spectral radius at infinity %g is not in [0, 1]", rho);
    if (!(opt->step >= 0.0) || !isfinite(opt->step))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "step", "give a positive step",
                            "invalid time step %g", opt->step);
    if (tr->nin > 0)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method",
                            "use bdf or adams, or leave out the cam acceleration term",
                            "the generalized-alpha method does not take the cams' "
                            "angle-dependent inertia (a law's configuration-dependent mass, "
                            "GD_LAW_INERTIA)");
    ga g;
    gd_status st = GD_OK;
    if (ga_alloc(&g, tr)) {
        ga_free(&g);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    g.am = (2.0 * rho - 1.0) / (rho + 1.0);
    g.af = rho / (rho + 1.0);
    g.gamma = 0.5 - g.am + g.af;
    g.beta = 0.25 * (1.0 - g.am + g.af) * (1.0 - g.am + g.af);
    g.atol = opt->atol_q;
    double hmax = opt->step > 0 ? opt->step : dt / 10.0;
    int *s0 = malloc((size_t)(tr->nlaw > 0 ? tr->nlaw : 1) * sizeof *s0);
    if (!s0) {
        ga_free(&g);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    memcpy(g.q, y, (size_t)nf * sizeof *g.q);
    memcpy(g.v, y + nf, (size_t)nf * sizeof *g.v);
    /* consistent initial acceleration: M a0 = f(t0, q0, v0) */
    free_force(&g, opt->t_start, g.q, g.v, g.R);
    gd_tr_mass_solve(tr, g.R, g.a);
    res->rhs_evals++;
    double t = opt->t_start;
    for (int k = 0; k < nout && !st; k++) {
        double tk = from + k * dt;
        if (tk > opt->t_end || k == nout - 1) tk = fmin(tk, opt->t_end);
        if (tk > t) {
            double span = tk - t;
            long ns = (long)ceil(span / hmax * (1.0 - 1e-12));
            if (ns < 1) ns = 1;
            double h = span / ns;
            if (!g.N || fabs(h - g.h) > 1e-12 * h) {
                if (ga_factor(&g, h)) {
                    st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "step", "change the step",
                                      "generalized-alpha: the effective matrix is singular");
                    break;
                }
                res->prec_setups++;
            }
            for (long s = 0; s < ns; s++) {
                for (int i = 0; i < tr->nlaw; i++)
                    s0[i] = tr->law[i].mode;
                double tn = s == ns - 1 ? tk : t + h;
                int it = ga_step(&g, t, &res->rhs_evals);
                if (it < 0) {
                    st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "step",
                                      "use a smaller --step, or the bdf method",
                                      "generalized-alpha: Newton did not converge at t = %g s", t);
                    break;
                }
                res->steps++;
                res->lin_iters += it;
                memcpy(g.q, g.q1, (size_t)nf * sizeof *g.q);
                memcpy(g.v, g.v1, (size_t)nf * sizeof *g.v);
                memcpy(g.a, g.a1, (size_t)nf * sizeof *g.a);
                /* contact statistics: the state at the end of the step */
                if (tr->nroot) {
                    memcpy(g.y2, g.q, (size_t)nf * sizeof *g.q);
                    memcpy(g.y2 + nf, g.v, (size_t)nf * sizeof *g.v);
                    gd_tr_fill(tr, tn, g.y2, tr->q, tr->v, NULL);
                    for (int i = 0; i < tr->nlaw; i++) {
                        gd_law *L = &tr->law[i];
                        if (!gd_law_nswitches(L)) continue;
                        gd_law_point x;
                        gd_tr_law_here(tr, L, tn, &x);
                        int ns_ = L->type->mode_at(L, &x);
                        L->mode = s0[i];
                        if (ns_ != s0[i]) {
                            gd_tr_change_state(tr, i, ns_, tn, from, res, track);
                            res->events++;
                        }
                    }
                }
                t = tn;
            }
        }
        if (st) break;
        if (opt->progress) opt->progress(t, opt->t_start, opt->t_end, opt->progress_data);
        res->t[k] = tk;
        memcpy(y, g.q, (size_t)nf * sizeof *y);
        memcpy(y + nf, g.v, (size_t)nf * sizeof *y);
        gd_tr_fill(tr, tk, y, tr->q, tr->v, NULL);
        for (int r = 0; r < nrecords; r++)
            res->values[(size_t)r * nout + k] =
                gd_tr_record_value(tr, &records[r], tk, tr->q, tr->v);
    }
    free(s0);
    ga_free(&g);
    return st;
}
