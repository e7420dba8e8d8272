/* Monodromy matrix by integrating the variational equations with the state:
 *
 *   y' = f(t, y),  Phi' = J(t, y) Phi,  Phi(t0) = I,  J = df/dy,
 *
 * as one augmented system [y; Phi e_1; ...; Phi e_N] for CVODE (what CVODES's simultaneous
 * corrector does; CVODES cannot be linked next to the CVODE the runs use). J v is a
 * central directional difference of the right-hand side, (f(y + h v) - f(y - h v)) / 2h,
 * on the piecewise-smooth field with the contact states frozen: exact on the linear part
 * up to rounding, O(h^2) on the laws. The step makes the largest component of h v a
 * fraction eps^(1/3) (6e-6) of that component's scale |y_i| + atol_i / rtol, which
 * balances the truncation error (h^2 f''') against rounding (eps / h): both ~1e-11
 * relative, far below the 1e-6 the Floquet multipliers need.
 *
 * A contact change of a backlash mesh switches the vector field on the surface
 * g(t, y) = d_e -/+ b = 0; the sensitivities jump by the saltation matrix
 * (Aizerman & Gantmakher 1958; Leine & Nijmeijer 2004, Eq. 3.22):
 *
 *   Phi+ = [I + (f+ - f-) grad g^T / (grad g . f- + dg/dt)] Phi-,
 *
 * with grad g . v and the total rate of g along the flow by the same central differences
 * of the root functions. The block of Phi in the Newton matrix is J, so every block is
 * preconditioned by the problem's own preconditioner (gd_tr_cv_psolve). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include "transient/transient_impl.h"

typedef struct mono {
    gd_transient *tr;
    int N;                          /* states 2 nf */
    double *scale;                  /* N: typical size of each state, atol / rtol */
    double *yp, *ym, *fp, *fm, *f0; /* N each */
    double *gp, *gm;                /* nroot each */
    double tscale;                  /* s: a time over which the explicit t-dependence is smooth */
    long nrhs; /* the model's right-hand sides evaluated (the budget's count) */
} mono;

/* Step h for the direction v about y: max_i |h v_i| / (|y_i| + scale_i) = eps^(1/3);
 * 0 for a zero direction. */
static double fd_step(const mono *m, const double *y, const double *v)
{
    double r = 0.0;
    for (int i = 0; i < m->N; i++)
        r = fmax(r, fabs(v[i]) / (fabs(y[i]) + m->scale[i]));
    return r > 0.0 ? cbrt(DBL_EPSILON) / r : 0.0;
}

/* out = J(t, y) v by central differences (out may not alias y or v). */
static void jac_vec(mono *m, double t, const double *y, const double *v, double *out)
{
    const int N = m->N;
    double h = fd_step(m, y, v);
    if (h == 0.0) {
        memset(out, 0, (size_t)N * sizeof *out);
        return;
    }
    for (int i = 0; i < N; i++) {
        m->yp[i] = y[i] + h * v[i];
        m->ym[i] = y[i] - h * v[i];
    }
    gd_transient_rhs(m->tr, t, m->yp, m->fp);
    gd_transient_rhs(m->tr, t, m->ym, m->fm);
    m->nrhs += 2;
    for (int i = 0; i < N; i++)
        out[i] = (m->fp[i] - m->fm[i]) / (2.0 * h);
}

/* Derivative of root function k along (dt, v) about (t, y): central difference. */
static double root_rate(mono *m, double t, const double *y, double dt, const double *v, int k)
{
    double h = fd_step(m, y, v);
    double ht = cbrt(DBL_EPSILON) * m->tscale / (fabs(dt) > 0 ? fabs(dt) : 1.0);
    if (dt != 0.0 && (h == 0.0 || ht < h)) h = ht;
    if (h == 0.0) return 0.0;
    for (int i = 0; i < m->N; i++) {
        m->yp[i] = y[i] + h * v[i];
        m->ym[i] = y[i] - h * v[i];
    }
    gd_tr_roots(m->tr, t + h * dt, m->yp, m->gp);
    gd_tr_roots(m->tr, t - h * dt, m->ym, m->gm);
    return (m->gp[k] - m->gm[k]) / (2.0 * h);
}

static int aug_rhs(sunrealtype t, N_Vector Y, N_Vector Yd, void *ud)
{
    mono *m = ((gd_transient *)ud)->mono;
    const int N = m->N;
    const double *y = N_VGetArrayPointer(Y);
    double *yd = N_VGetArrayPointer(Yd);
    gd_transient_rhs(m->tr, t, y, yd);
    m->nrhs++;
    for (int j = 0; j < N; j++)
        jac_vec(m, t, y, y + (size_t)N * (j + 1), yd + (size_t)N * (j + 1));
    return 0;
}

static int aug_root(sunrealtype t, N_Vector Y, sunrealtype *g, void *ud)
{
    gd_tr_roots(ud, t, N_VGetArrayPointer(Y), g);
    return 0;
}

/* Law i switches to mode ns at (t, y) through root function k: the saltation update of
 * the columns of Phi (Y + N). */
static void saltation(mono *m, int i, int ns, int k, double t, double *Y)
{
    const int N = m->N;
    gd_law *law = &m->tr->law[i];
    gd_transient_rhs(m->tr, t, Y, m->f0); /* f- */
    double rate = root_rate(m, t, Y, 1.0, m->f0, k);
    law->mode = ns;
    if (!(fabs(rate) > 0.0)) return; /* grazing: the jump is undefined, leave Phi */
    double *df = m->f0;
    /* f+ - f- (f+ into fm: root_rate does not use it) */
    gd_transient_rhs(m->tr, t, Y, m->fm);
    m->nrhs += 2;
    for (int p = 0; p < N; p++)
        df[p] = m->fm[p] - df[p];
    for (int j = 0; j < N; j++) {
        double *col = Y + (size_t)N * (j + 1);
        double c = root_rate(m, t, Y, 0.0, col, k) / rate;
        if (c == 0.0) continue;
        for (int p = 0; p < N; p++)
            col[p] += df[p] * c;
    }
}

gd_status gd_transient_monodromy(gd_transient *tr, double t0, double period, const double *y0,
                                 const gd_transient_options *opt, double *phi, double *y_end,
                                 gd_error *err)
{
    return gd_transient_monodromy_limited(tr, t0, period, y0, opt, 0, NULL, phi, y_end, err);
}

gd_status gd_transient_monodromy_limited(gd_transient *tr, double t0, double period,
                                         const double *y0, const gd_transient_options *opt,
                                         long max_rhs, long *nrhs, double *phi, double *y_end,
                                         gd_error *err)
{
    if (nrhs) *nrhs = 0;
    const int N = 2 * tr->nf;
    if (!(period > 0) || !isfinite(period) || !isfinite(t0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "period", "give a finite period > 0",
                            "invalid period %g s", period);
    if (!y0 || !phi || !opt)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "y0", "", "state or output missing");
    if (tr->cond)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "condense", "use the full problem",
                            "no monodromy matrix of a condensed problem");
    if (opt->profile)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "profile", "run at a constant speed",
                            "a monodromy matrix needs a periodic motion: no speed profile");
    if (!(opt->rtol > 0) || !(opt->atol_q > 0) || !(opt->atol_v > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options", "tolerances > 0",
                            "invalid tolerances");
    if (N == 0) return GD_OK;
    const size_t NA = (size_t)N * (N + 1);
    mono m;
    memset(&m, 0, sizeof m);
    m.tr = tr;
    m.N = N;
    m.scale = malloc((size_t)7 * N * sizeof *m.scale);
    int nr = tr->nroot > 0 ? tr->nroot : 1;
    m.gp = malloc((size_t)2 * nr * sizeof *m.gp);
    int *found = calloc((size_t)nr, sizeof *found);
    gd_status st = GD_OK;
    SUNContext ctx = NULL;
    N_Vector Y = NULL, atol = NULL;
    SUNLinearSolver LS = NULL;
    void *mem = NULL;
    if (!m.scale || !m.gp || !found) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    m.yp = m.scale + N;
    m.ym = m.yp + N;
    m.fp = m.ym + N;
    m.fm = m.fp + N;
    m.f0 = m.fm + N;
    m.gm = m.gp + nr;
    /* the explicit time dependence (mesh angle, unbalance) is smooth over a fraction of a
     * revolution of the fastest DOF; the period otherwise */
    double rmax = 0.0;
    for (int i = 0; i < tr->n; i++)
        rmax = fmax(rmax, fabs(tr->rate[i]));
    m.tscale = rmax > 0 ? fmin(period, 1.0 / rmax) : period;
    if (SUNContext_Create(NULL, &ctx) || !(Y = N_VNew_Serial((sunindextype)NA, ctx)) ||
        !(atol = N_VNew_Serial((sunindextype)NA, ctx))) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory (%zu states)", NA);
        goto done;
    }
    double *Yd = N_VGetArrayPointer(Y), *ad = N_VGetArrayPointer(atol);
    for (int i = 0; i < N; i++) {
        ad[i] = i < tr->nf ? opt->atol_q : opt->atol_v;
        m.scale[i] = ad[i] / opt->rtol;
    }
    /* column j is the response to a perturbation of y0_j: a perturbation of its typical
     * size scale_j moves y_i by about scale_i, held to atol_i, so Phi_ij to atol_i /
     * scale_j */
    memcpy(Yd, y0, (size_t)N * sizeof *Yd);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            Yd[(size_t)N * (j + 1) + i] = i == j ? 1.0 : 0.0;
            ad[(size_t)N * (j + 1) + i] = ad[i] / m.scale[j];
        }
    gd_transient_set_contacts(tr, t0, Yd);
    tr->mono = &m;
    int flag = 0;
    double t1 = t0 + period;
    tr->msg[0] = 0;
    mem = gd_tr_cvode_new(ctx, opt, t0, t1, Y, atol, aug_rhs, aug_root,
                          opt->locate_events ? tr->nroot : 0, gd_tr_cv_psetup, gd_tr_cv_psolve, tr,
                          tr, &LS, &flag);
    if (!mem || flag) {
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "", "", "CVODE set-up failed (%d) %s", flag,
                          tr->msg);
        goto done;
    }
    double t = t0;
    long events = 0;
    while (t < t1) {
        /* the counted limit, checked after every step (a step evaluates the augmented
         * system a few times, each 1 + 2 N of the model's): one matrix through a rattling
         * train can take minutes (examples/manual_5speed.yaml: 461914 right-hand sides
         * without one matrix ending), and a budget checked only between matrices never
         * stops it */
        if (max_rhs > 0 && m.nrhs >= max_rhs) {
            st =
                gd_error_set(err, GD_ENUMERIC, "", 0, 0, "", "raise the budget, or run a transient",
                             "monodromy stopped at t = %.6g s, %.0f %% of the period %.6g s: "
                             "%ld right-hand sides of the model (limit %ld; %ld contact "
                             "changes so far)",
                             t, 100.0 * (t - t0) / period, period, m.nrhs, max_rhs, events);
            goto done;
        }
        flag = CVode(mem, t1, Y, &t, CV_ONE_STEP);
        if (flag < 0) {
            st =
                gd_error_set(err, GD_ENUMERIC, "", 0, 0, "",
                             "tighten or loosen the tolerances, or limit the step",
                             "monodromy: CVODE failed at t = %g s (flag %d): %s", t, flag, tr->msg);
            goto done;
        }
        int changed = 0, kr = 0;
        if (flag == CV_ROOT_RETURN) CVodeGetRootInfo(mem, found);
        if (tr->nroot) gd_tr_fill(tr, t, Yd, tr->q, tr->v, NULL);
        for (int i = 0; i < tr->nlaw; i++) {
            const gd_law *L = &tr->law[i];
            int nsw = gd_law_nswitches(L);
            if (!nsw) continue;
            int ns = flag == CV_ROOT_RETURN ? L->type->mode_after(L, L->mode, found + kr)
                                            : gd_tr_missed_mode(tr, L, t);
            if (ns != L->mode) {
                /* the surface crossed (a mesh: d_e = +b when entering or leaving the drive
                 * flank, else d_e = -b) */
                int k = kr + L->type->switch_of(L, L->mode, ns);
                saltation(&m, i, ns, k, t, Yd);
                changed = 1;
                gd_tr_fill(tr, t, Yd, tr->q, tr->v, NULL);
            }
            kr += nsw;
        }
        if (changed) {
            events++;
            CVodeReInit(mem, t, Y);
        }
    }
    for (int j = 0; j < N; j++)
        memcpy(phi + (size_t)N * j, Yd + (size_t)N * (j + 1), (size_t)N * sizeof *phi);
    if (y_end) memcpy(y_end, Yd, (size_t)N * sizeof *y_end);
done:
    if (nrhs) *nrhs = m.nrhs;
    tr->mono = NULL;
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (Y) N_VDestroy(Y);
    if (atol) N_VDestroy(atol);
    if (ctx) SUNContext_Free(&ctx);
    free(m.scale);
    free(m.gp);
    free(found);
    return st;
}
