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
    free(k->J);
    free(k->P);
    free(k->ppiv);
    free(k->work);
    free(k->modes);
    free(k);
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
    gd_tr_forces(tr, t, tr->q, tr->v, tr->acc, tr->r, 1);
    for (int i = 0; i < nc; i++) {
        double s = tr->r[k->dof[i]];
        for (int j = 0; j < nc; j++)
            s += k->dK[i + (size_t)j * nc] * qs[j] + k->dD[i + (size_t)j * nc] * vs[j];
        u[i] = s;
    }
}

/* y = C x (nc), yv = C A x */
static void outputs(const gd_tr_condensed *k, const double *x, double *y, double *yv)
{
    const int nc = k->nc, ns = k->ns;
    for (int i = 0; i < nc; i++)
        y[i] = yv[i] = 0.0;
    for (int j = 0; j < ns; j++) {
        const double xj = x[j];
        if (xj == 0.0) continue;
        const double *c = k->C + (size_t)j * nc, *ca = k->CA + (size_t)j * nc;
        for (int i = 0; i < nc; i++) {
            y[i] += c[i] * xj;
            yv[i] += ca[i] * xj;
        }
    }
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
        if (uj == 0.0) continue;
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
    outputs(k, x, y, yv);
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
    /* x' = A x + B u */
    for (int i = 0; i < ns; i++)
        xdot[i] = 0.0;
    for (int j = 0; j < ns; j++) {
        const double xj = x[j];
        if (xj == 0.0) continue;
        const double *a = k->A + (size_t)j * ns;
        for (int i = 0; i < ns; i++)
            xdot[i] += a[i] * xj;
    }
    for (int j = 0; j < nc; j++) {
        const double uj = k->u[j];
        if (uj == 0.0) continue;
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
}

/* ---- CVODE's linear solver: P = I - gamma J, J = A + B du/dx, dense LU ---- */
int gd_tr_condensed_psetup(sunrealtype t, N_Vector y, N_Vector fy, sunbooleantype jok,
                           sunbooleantype *jcur, sunrealtype gamma, void *ud)
{
    (void)fy;
    gd_transient *tr = ud;
    gd_tr_condensed *k = tr->cond;
    const int ns = k->ns, nc = k->nc;
    if (!jok || !k->have_J) {
        const double *x = N_VGetArrayPointer(y);
        double *qs = k->work + 7 * nc, *vs = qs + nc;
        solve_loop(tr, t, x, qs, vs);
        refresh_tangent(tr, t, qs, vs);
        /* du/dx = L^-1 (F_q C + F_v C A) (nc x ns) */
        double *D = k->P; /* scratch, ns x ns >= nc x ns */
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
        memcpy(k->J, k->A, (size_t)ns * ns * sizeof *k->J);
        for (int j = 0; j < ns; j++)
            for (int m = 0; m < nc; m++) {
                double d = D[m + (size_t)j * nc];
                if (d == 0.0) continue;
                const double *b = k->B + (size_t)m * ns;
                double *Jj = k->J + (size_t)j * ns;
                for (int i = 0; i < ns; i++)
                    Jj[i] += b[i] * d;
            }
        k->have_J = 1;
        *jcur = SUNTRUE;
    } else {
        *jcur = SUNFALSE;
    }
    for (size_t p = 0; p < (size_t)ns * ns; p++)
        k->P[p] = -gamma * k->J[p];
    for (int i = 0; i < ns; i++)
        k->P[i + (size_t)i * ns] += 1.0;
    k->setups++;
    return LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, ns, ns, k->P, ns, k->ppiv) ? 1 : 0;
}

int gd_tr_condensed_psolve(sunrealtype t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z,
                           sunrealtype gamma, sunrealtype delta, int lr, void *ud)
{
    (void)t;
    (void)y;
    (void)fy;
    (void)gamma;
    (void)delta;
    (void)lr;
    gd_transient *tr = ud;
    gd_tr_condensed *k = tr->cond;
    const int ns = k->ns;
    double *zd = N_VGetArrayPointer(z);
    memcpy(zd, N_VGetArrayPointer(r), (size_t)ns * sizeof *zd);
    return LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', ns, 1, k->P, ns, k->ppiv, zd, ns) ? -1 : 0;
}

/* J v with the Jacobian of the last set-up: GMRES then solves the same matrix the
 * preconditioner inverts, in one iteration (CVODE's modified Newton with a dense solve). */
int gd_tr_condensed_jtimes(N_Vector v, N_Vector Jv, sunrealtype t, N_Vector y, N_Vector fy,
                           void *ud, N_Vector tmp)
{
    (void)t;
    (void)y;
    (void)fy;
    (void)tmp;
    const gd_transient *tr = ud;
    const gd_tr_condensed *k = tr->cond;
    const int ns = k->ns;
    const double *x = N_VGetArrayPointer(v);
    double *o = N_VGetArrayPointer(Jv);
    for (int i = 0; i < ns; i++)
        o[i] = 0.0;
    for (int j = 0; j < ns; j++) {
        const double xj = x[j];
        if (xj == 0.0) continue;
        const double *c = k->J + (size_t)j * ns;
        for (int i = 0; i < ns; i++)
            o[i] += c[i] * xj;
    }
    return 0;
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

void gd_tr_condensed_reset(gd_transient *tr)
{
    gd_tr_condensed *k = tr->cond;
    memset(k->u, 0, (size_t)k->nc * sizeof *k->u);
    k->have_tangent = 0;
    k->have_J = 0;
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

gd_status gd_transient_new_condensed(const gd_system *sys, const gd_transient_spec *spec,
                                     double speed, double cutoff, gd_transient **out, gd_error *err)
{
    *out = NULL;
    const char *file = sys->model ? sys->model->file : "";
    gd_transient *tr = NULL;
    gd_status st = gd_transient_new(sys, spec, speed, &tr, err);
    if (st) return st;
    if (tr->np) {
        st = gd_error_set(err, GD_EINPUT, file, 0, 0, "prescribed",
                          "integrate the full model (--condense none), or replace the "
                          "prescribed motion by a load or a spring to ground",
                          "the condensed transient keeps the structure's own modes: no "
                          "prescribed DOF (%d given)",
                          tr->np);
        goto fail;
    }
    if (tr->nin) {
        st = gd_error_set(err, GD_EINPUT, file, 0, 0, "cam_torques",
                          "integrate the full model (--condense none)",
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
    for (int i = 0; i < tr->nlaw; i++)
        for (int j = 0; j < tr->law[i].ndofs; j++)
            if (tr->law[i].dof[j] >= 0) mark[tr->law[i].dof[j]] = 1;
    for (int i = 0; i < tr->nunb_all; i++) {
        if (tr->unb[i].dx >= 0) mark[tr->unb[i].dx] = 1;
        if (tr->unb[i].dy >= 0) mark[tr->unb[i].dy] = 1;
    }
    int nc = 0;
    for (int i = 0; i < n; i++)
        nc += mark[i];
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
    if (!st) st = gd_condense_build(sys, &cc, &o, &k->c, err);
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
    k->J = calloc((size_t)ns * ns, sizeof *k->J);
    k->P = calloc((size_t)ns * (ns > nc ? ns : nc), sizeof *k->P);
    k->ppiv = calloc((size_t)ns, sizeof *k->ppiv);
    k->work = calloc((size_t)9 * nc + ns + nc, sizeof *k->work);
    k->modes = calloc((size_t)(tr->nlaw ? tr->nlaw : 1), sizeof *k->modes);
    if (!k->CA || !k->CB || !k->dK || !k->dD || !k->u || !k->Fq || !k->Fv || !k->L || !k->lpiv ||
        !k->J || !k->P || !k->ppiv || !k->work || !k->modes) {
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        goto fail;
    }
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
    /* K_L, C_L: what the condensed structure (gd_system_dense) holds beyond the
     * transient's linear part, only on law DOFs (S x S) */
    if (sys->nlaws > 0) {
        if (n > GD_TR_CONDENSE_DENSE_MAX) {
            st = gd_error_set(err, GD_EINPUT, file, 0, 0, "laws",
                              "integrate the full model (--condense none)",
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
