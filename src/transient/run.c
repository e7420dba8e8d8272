/* Integration of a transient problem with SUNDIALS CVODE: BDF or Adams, Newton with
 * GMRES preconditioned by the exact inverse of the linear part, root-finding on the
 * contact changes of backlash meshes with the contact state frozen between events and a
 * restart at every event; fixed-interval records and summary statistics. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <time.h>

#include "transient/transient_impl.h"

void gd_transient_options_init(gd_transient_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->rtol = 1e-6;
    opt->atol_q = 1e-12;
    opt->atol_v = 1e-9;
    opt->method = GD_TR_BDF;
    opt->init = GD_TR_INIT_REST;
    opt->locate_events = 1;
    opt->rho_inf = 0.9;
}

static int cv_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *ud)
{
    gd_transient_rhs(ud, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    return 0;
}

static int cv_root(sunrealtype t, N_Vector y, sunrealtype *g, void *ud)
{
    gd_tr_roots(ud, t, N_VGetArrayPointer(y), g);
    return 0;
}

int gd_tr_cv_psetup(sunrealtype t, N_Vector y, N_Vector fy, sunbooleantype jok,
                    sunbooleantype *jcur, sunrealtype gamma, void *ud)
{
    (void)t;
    (void)y;
    (void)fy;
    (void)jok;
    *jcur = SUNTRUE;
    return gd_tr_prec_setup(ud, gamma) ? 1 : 0; /* > 0: recoverable */
}

int gd_tr_cv_psolve(sunrealtype t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z,
                    sunrealtype gamma, sunrealtype delta, int lr, void *ud)
{
    (void)t;
    (void)y;
    (void)fy;
    (void)gamma;
    (void)delta;
    (void)lr;
    gd_transient *tr = ud;
    const double *rd = N_VGetArrayPointer(r);
    double *zd = N_VGetArrayPointer(z);
    const sunindextype N = 2 * tr->nf, nb = N > 0 ? N_VGetLength(r) / N : 0;
    for (sunindextype j = 0; j < nb; j++)
        gd_tr_prec_solve(tr, rd + N * j, zd + N * j);
    return 0;
}

void gd_tr_cv_err(int code, const char *module, const char *function, char *msg, void *ud)
{
    (void)module;
    gd_transient *tr = ud;
    if (code < 0) snprintf(tr->msg, sizeof tr->msg, "%s: %s", function, msg);
}

void *gd_tr_cvode_new(SUNContext ctx, const gd_transient_options *opt, double t0, double t_stop,
                      N_Vector y, N_Vector atol, CVRhsFn rhs, CVRootFn root, int nroot,
                      CVLsPrecSetupFn psetup, CVLsPrecSolveFn psolve, void *ud, gd_transient *tr,
                      SUNLinearSolver *LS, int *flag)
{
    *LS = NULL;
    void *mem = CVodeCreate(opt->method == GD_TR_ADAMS ? CV_ADAMS : CV_BDF, ctx);
    if (!mem) {
        *flag = -1;
        return NULL;
    }
    CVodeSetErrHandlerFn(mem, gd_tr_cv_err, tr);
    int f = CVodeInit(mem, rhs, t0, y);
    if (!f) f = CVodeSVtolerances(mem, opt->rtol, atol);
    if (!f) f = CVodeSetUserData(mem, ud);
    if (tr->cond && !psetup) {
        /* the condensed model (tens of states): a dense LU of I - gamma J with the exact
         * Jacobian, kept by CVODE over steps, costs less than a Krylov solve (condensed.c) */
        *LS = gd_tr_condensed_solver(tr, y, ctx);
        if (!*LS) f = -1;
        if (!f) f = CVodeSetLinearSolver(mem, *LS, tr->cond->Jm);
        if (!f) f = CVodeSetJacFn(mem, gd_tr_condensed_jac);
        /* below a cut-off, the error weights from the coordinates (condensed.c); with
         * every mode kept (the exact condensation, a check of the full model) CVODE's own
         * per-state weights */
        if (!f && tr->cond->info.ndiscarded > 0) f = CVodeWFtolerances(mem, gd_tr_condensed_ewt);
    } else {
        *LS = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 20, ctx);
        if (!*LS) f = -1;
        if (!f) f = CVodeSetLinearSolver(mem, *LS, NULL);
        if (!f) f = CVodeSetPreconditioner(mem, psetup, psolve);
    }
    if (!f) f = CVodeSetMaxNumSteps(mem, opt->max_steps > 0 ? opt->max_steps : 50000000L);
    if (!f && opt->max_step > 0) f = CVodeSetMaxStep(mem, opt->max_step);
    if (!f) f = CVodeSetStopTime(mem, t_stop);
    if (!f && opt->method == GD_TR_BDF) f = CVodeSetStabLimDet(mem, SUNTRUE);
    if (!f && opt->max_order > 0) f = CVodeSetMaxOrd(mem, opt->max_order);
    if (!f && nroot) {
        f = CVodeRootInit(mem, nroot, root);
        if (!f) f = CVodeSetNoInactiveRootWarn(mem);
    }
    *flag = f;
    return mem;
}

static gd_status check_record(const gd_transient *tr, const gd_tr_record *r, gd_error *err)
{
    int ok = 1, nfull = tr->red ? tr->red->nfull : tr->n;
    switch (r->kind) {
    case GD_REC_DISP:
    case GD_REC_VEL:
    case GD_REC_ANGLE:
    case GD_REC_SPEED:
        ok = r->index >= 0 && r->index < nfull;
        break;
    case GD_REC_SPEED_RATIO:
        ok = r->index >= 0 && r->index < nfull && r->index2 >= 0 && r->index2 < nfull;
        break;
    case GD_REC_MESH_FORCE:
    case GD_REC_MESH_DEFLECTION:
    case GD_REC_MESH_STATE:
    case GD_REC_MESH_STIFFNESS:
        ok = r->index >= 0 && (r->index < tr->nmodel_mesh ||
                               (r->index < tr->nall_mesh && tr->nl_of_mesh[r->index] >= 0));
        break;
    case GD_REC_SFD_FX:
    case GD_REC_SFD_FY:
    case GD_REC_SFD_ECCENTRICITY:
        ok = r->index >= 0 && r->index < tr->nsfd_law;
        break;
    case GD_REC_LAW:
        ok = r->index >= 0 && r->index < tr->nlaw - tr->law_spec0 && r->index2 >= 0 &&
             r->index2 < tr->law[tr->law_spec0 + r->index].type->nrecords;
        break;
    default:
        ok = 0;
    }
    if (ok) return GD_OK;
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "record", "", "record refers to nothing");
}

static void stats_of(const double *x, int n, gd_tr_stats *s)
{
    memset(s, 0, sizeof *s);
    if (n <= 0) return;
    double mn = x[0], mx = x[0], sum = 0, sq = 0;
    for (int k = 0; k < n; k++) {
        if (isnan(x[k])) { /* no statistics of a record with a gap (issue 38 L5: -inf) */
            s->min = s->max = s->mean = s->rms = s->peak_to_peak = s->std = NAN;
            return;
        }
        mn = fmin(mn, x[k]);
        mx = fmax(mx, x[k]);
        sum += x[k];
        sq += x[k] * x[k];
    }
    s->min = mn;
    s->max = mx;
    s->mean = sum / n;
    s->rms = sqrt(sq / n);
    s->peak_to_peak = mx - mn;
    double var = sq / n - s->mean * s->mean;
    s->std = var > 0 ? sqrt(var) : 0.0;
}

void gd_transient_result_free(gd_transient_result *r)
{
    if (!r) return;
    free(r->t);
    free(r->records);
    free(r->values);
    free(r->stats);
    free(r->contacts);
    free(r->contact_events);
    free(r->q_end);
    free(r->v_end);
    free(r->sample_t);
    free(r->sample_values);
    free(r->sample_q);
    free(r->sample_v);
    free(r);
}

/* CVODE's counters restart at every CVodeReInit: add them up before each one. */
static void add_counters(void *mem, gd_transient_result *res)
{
    long v;
    if (!CVodeGetNumSteps(mem, &v)) res->steps += v;
    if (!CVodeGetNumRhsEvals(mem, &v)) res->rhs_evals += v;
    if (!CVodeGetNumLinRhsEvals(mem, &v)) res->rhs_evals += v;
    if (!CVodeGetNumLinIters(mem, &v)) res->lin_iters += v;
    if (!CVodeGetNumPrecEvals(mem, &v)) res->prec_setups += v;
    if (!CVodeGetNumJacEvals(mem, &v)) res->prec_setups += v; /* the dense solver's set-ups */
}

/* The system's DOFs (q, v of length ndof) from the problem's coordinates (xq, xv). */
static void full_state(const gd_transient *tr, const double *xq, const double *xv, double *q,
                       double *v)
{
    int n = tr->red ? tr->red->nfull : tr->n;
    for (int i = 0; i < n; i++) {
        q[i] = gd_tr_full_value(tr, i, xq);
        v[i] = gd_tr_full_value(tr, i, xv);
    }
}

/* Poincare sample ks at time t (the integrator's output there): records and state. */
static void store_sample(gd_transient *tr, gd_transient_result *res, const gd_tr_record *records,
                         int ks, double t, const double *yd)
{
    const int ns = res->nsamples, n = res->ndof;
    double *q = res->sample_q + (size_t)ks * n, *v = res->sample_v + (size_t)ks * n;
    res->sample_t[ks] = t;
    gd_tr_fill(tr, t, yd, tr->q, tr->v, NULL);
    for (int r = 0; r < res->nrecords; r++)
        res->sample_values[(size_t)r * ns + ks] =
            gd_tr_record_value(tr, &records[r], t, tr->q, tr->v);
    full_state(tr, tr->q, tr->v, q, v);
}

/* The integration state of a run, shared by its output loop and advance(). */
typedef struct run_work {
    void *mem;
    N_Vector y;
    int *rootsfound;
    gd_transient_result *res;
    gd_tr_contact_track *track;
    double from;
    int slow; /* windows of GD_TR_WINDOW steps in a row projecting past the step limit */
} run_work;

#define GD_TR_WINDOW 20000 /* steps per CVODE call at most: the pace check's window */

/* Integrates from *t to tk (CVODE's output at tk), handling the contact events on the
 * way. */
static gd_status advance(gd_transient *tr, run_work *w, const gd_transient_options *opt, double *t,
                         double tk, gd_error *err)
{
    while (*t < tk) {
        /* with a progress report, the stretch before record_from is split (CVODE
         * interpolates at the intermediate times; its steps are the same) */
        double tout = tk, chunk = (opt->t_end - opt->t_start) / 200.0;
        if (opt->progress && tk - *t > 1.5 * chunk) tout = *t + chunk;
        /* the step limit counts every step of the run, not each call's (CVODE's own
         * mxstep), and CVODE returns every GD_TR_WINDOW steps so that a run whose steps
         * have collapsed (a contact stiffness of 1e308: 1e5 steps stuck at one t) ends
         * with the limit named once its pace projects past it, instead of running for
         * days (issue 38 M4) */
        const long limit = opt->max_steps > 0 ? opt->max_steps : 50000000L;
        long used = 0;
        CVodeGetNumSteps(w->mem, &used);
        const long budget = limit - w->res->steps - used;
        double t0 = *t;
        if (budget <= 0 ||
            CVodeSetMaxNumSteps(w->mem, budget < GD_TR_WINDOW ? budget : GD_TR_WINDOW))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "max_steps",
                                "shorten the run, loosen rtol, or raise max_steps (transient "
                                "--max-steps, a study's max_steps) if it is meant",
                                "the integrator used the step limit of %ld steps by t = %.6g s "
                                "of %.6g s",
                                limit, *t, opt->t_end);
        int flag = CVode(w->mem, tout, w->y, t, CV_NORMAL);
        if (flag == CV_TOO_MUCH_WORK) {
            /* a window's pace: three in a row projecting past the limit end the run */
            double need = (opt->t_end - *t) / fmax(*t - t0, 1e-300) * GD_TR_WINDOW;
            w->slow = need > (double)budget ? w->slow + 1 : 0;
            if (w->slow >= 3)
                return gd_error_set(err, GD_EINPUT, "", 0, 0, "max_steps",
                                    "shorten the run, loosen rtol, check for a stiffness "
                                    "far beyond the others, or raise max_steps (transient "
                                    "--max-steps, a study's max_steps) if it is meant",
                                    "at t = %.6g s of %.6g s the last %d steps advanced %.3g s: "
                                    "the rest needs about %.3g steps at that pace, over the "
                                    "step limit of %ld",
                                    *t, opt->t_end, GD_TR_WINDOW, *t - t0, need, limit);
            continue;
        }
        if (opt->progress) opt->progress(*t, opt->t_start, opt->t_end, opt->progress_data);
        if (flag == CV_ROOT_RETURN) {
            CVodeGetRootInfo(w->mem, w->rootsfound);
            int changed = 0, kr = 0;
            for (int i = 0; i < tr->nlaw; i++) {
                const gd_law *L = &tr->law[i];
                int nsw = gd_law_nswitches(L);
                if (!nsw) continue;
                const int *dir = w->rootsfound + kr;
                kr += nsw;
                int ns = L->type->mode_after(L, L->mode, dir), any = 0;
                if (ns != L->mode) {
                    /* the state at the root for the event's approach speed (of a
                     * condensed model the laws' DOFs only: the others are not read) */
                    if (tr->cond)
                        tr->cond_fill(tr, *t, N_VGetArrayPointer(w->y), tr->q, tr->v, 0);
                    else
                        gd_tr_fill(tr, *t, N_VGetArrayPointer(w->y), tr->q, tr->v, NULL);
                    gd_tr_change_state(tr, i, ns, *t, w->from, w->res, w->track);
                    changed = 1;
                }
                for (int k = 0; k < nsw; k++)
                    any |= dir[k] != 0;
                if (any) w->res->events++;
                changed |= any; /* a crossing back into the same mode (chatter at grazing)
                                   restarts too: CVODE would stop at its zero next step */
            }
            if (changed) {
                add_counters(w->mem, w->res);
                CVodeReInit(w->mem, *t, w->y);
                w->res->reinits++;
            }
            continue;
        }
        if (flag < 0) {
            return gd_error_set(err, GD_ENUMERIC, "", 0, 0, "",
                                "tighten or loosen the "
                                "tolerances, or limit the step",
                                "CVODE failed at t = %g s (flag %d): %s", *t, flag, tr->msg);
        }
        /* a contact change the root-finding missed (two crossings in one step) */
        if (tr->nroot) {
            if (tr->cond)
                tr->cond_fill(tr, *t, N_VGetArrayPointer(w->y), tr->q, tr->v, 0);
            else
                gd_tr_fill(tr, *t, N_VGetArrayPointer(w->y), tr->q, tr->v, NULL);
            int changed = 0;
            for (int i = 0; i < tr->nlaw; i++) {
                const gd_law *L = &tr->law[i];
                if (!gd_law_nswitches(L)) continue;
                int ns = gd_tr_missed_mode(tr, L, *t);
                if (ns != L->mode) {
                    gd_tr_change_state(tr, i, ns, *t, w->from, w->res, w->track);
                    changed = 1;
                    w->res->events++;
                }
            }
            if (changed) {
                add_counters(w->mem, w->res);
                CVodeReInit(w->mem, *t, w->y);
                w->res->reinits++;
            }
        }
    }
    return GD_OK;
}

/* The method that ran and what controlled its error, in res (why: the reason auto
 * chose it, NULL when the method was given). */
static void method_note(const gd_transient *cond, const gd_transient_options *opt, const char *why,
                        double dt, gd_transient_result *res)
{
    static const char *const names[] = {"bdf", "adams", "galpha", "auto", "lti"};
    char *b = res->method_note;
    const size_t len = sizeof res->method_note;
    res->method_used = opt->method;
    int k = 0;
    if (why) k = snprintf(b, len, "auto: ");
    if (opt->method == GD_TR_LTI) {
        snprintf(b + k, len - k,
                 "lti (exact harmonic forcing, Pade(%d,%d) free motion), step %.3g s, estimated "
                 "error %.2g %s rtol %g",
                 GD_TR_LTI_PADE, GD_TR_LTI_PADE, res->step, res->error_estimate,
                 res->error_estimate <= opt->rtol ? "<=" : ">", opt->rtol);
        return;
    }
    res->error_estimate = -1.0;
    if (opt->method == GD_TR_GEN_ALPHA) {
        res->step = opt->step > 0 ? fmin(opt->step, dt) : dt / 10.0;
        snprintf(b + k, len - k, "galpha, step %.3g s, rho_inf %g (no error estimate)", res->step,
                 opt->rho_inf);
        return;
    }
    k += snprintf(b + k, len - k, "%s, CVODE local error control, rtol %g%s%s%s",
                  names[opt->method], opt->rtol, why ? " (" : "", why ? why : "", why ? ")" : "");
    if (cond && k < (int)len) {
        gd_tr_condensed_info ci;
        gd_transient_condensed_info(cond, &ci);
        if (ci.ndiscarded)
            snprintf(b + k, len - k,
                     "; condensed: %d states on %d law DOFs, %d modes to %.4g Hz + static "
                     "correction, estimate %.2g",
                     ci.nstates, ci.ncoords, ci.nkept, ci.cutoff / 6.283185307179586, ci.estimate);
        else
            snprintf(b + k, len - k, "; condensed: %d states on %d law DOFs, every mode kept",
                     ci.nstates, ci.ncoords);
    }
}

/* Refuses a run that cannot finish within the step limit (max_steps, default 50
 * million) from a lower bound on its step count known before it starts: the fixed step
 * of generalized-alpha (never longer than the output interval), and for CVODE the
 * revolutions of the fastest DOF (each turn of a gear brings its mesh and unbalance
 * forces round once: no accurate step spans a revolution). A run that would take days
 * is an input error naming the limit, not a hang. */
static gd_status check_step_count(const gd_transient *tr, const gd_transient_options *opt,
                                  double dt, gd_error *err)
{
    const double span = opt->t_end - opt->t_start;
    const double limit = opt->max_steps > 0 ? (double)opt->max_steps : 50e6;
    if (opt->method == GD_TR_LTI) return GD_OK; /* its own limit (linear.c) */
    if (opt->method == GD_TR_GEN_ALPHA) {
        double h = opt->step > 0 ? fmin(opt->step, dt) : dt / 10.0;
        double steps = span / h;
        if (!(steps <= limit))
            return gd_error_set(
                err, GD_EINPUT, "", 0, 0, "step",
                "give a longer step or a shorter run, or raise max_steps (transient --max-steps, "
                "a study's max_steps) if it is meant",
                "%.3g s in steps of %.3g s is %.3g steps, over the limit of %.0f", span, h, steps,
                limit);
        return GD_OK;
    }
    double wmax = 0.0, pmax = 0.0;
    const gd_speed_profile *p = opt->profile;
    if (p && p->kind == GD_SPEED_RAMP) pmax = fmax(fabs(p->from), fabs(p->to));
    for (int k = 0; p && p->kind == GD_SPEED_TABLE && k < p->n; k++)
        pmax = fmax(pmax, fabs(p->speed[k]));
    for (int i = 0; i < tr->n; i++)
        wmax = fmax(wmax, p ? fabs(tr->ratio[i]) * pmax : fabs(tr->rate[i]));
    /* a model driven at a fixed frequency turns no shaft: its loads' and prescribed
     * motions' periods bound the steps the same way (issue 38 M4: Duffing for 1e30 s) */
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_load_law *L = tr->law[i].type == &gd_law_load ? tr->law[i].data : NULL;
        if (L && L->kind == GD_LOAD_HARMONIC_TIME && L->amplitude != 0)
            wmax = fmax(wmax, fabs(L->frequency));
    }
    for (int k = 0; k < tr->np; k++)
        if (tr->pres[k].law.kind == GD_PRESCRIBED_HARMONIC && tr->pres[k].law.amplitude != 0)
            wmax = fmax(wmax, fabs(tr->pres[k].law.frequency));
    double turns = span * wmax / 6.28318530717958647692;
    if (!(turns <= limit))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "t_end",
                            "shorten the run, or raise max_steps (transient --max-steps, a study's "
                            "max_steps) if it is meant",
                            "%.3g s at %.4g rad/s (the fastest shaft or forcing) is %.3g "
                            "revolutions or forcing periods, each needing steps: over the step "
                            "limit of %.0f",
                            span, wmax, turns, limit);
    return GD_OK;
}

/* What a run-up cannot do (GD_EINPUT naming the option): the LTI method (one constant
 * speed), a reduced problem (its modes and rates at the reference speed), a prescribed
 * speed or angle table (an absolute motion that ignores the profile), a law whose clock
 * runs at the reference speed (GD_LAW_CONSTANT_SPEED: a rolling bearing's cage). */
static gd_status profile_refusals(const gd_transient *tr, const gd_transient_options *opt,
                                  gd_error *err)
{
    gd_status st = gd_speed_profile_check(opt->profile, err);
    if (st) return st;
    if (opt->method == GD_TR_LTI)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method", "use auto, bdf, adams or galpha",
                            "the linear time-invariant method needs a constant speed, not a "
                            "speed profile");
    if (tr->red)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "reduce",
                            "integrate the full model for a run-up",
                            "a reduced model keeps its modes at the reference speed: no speed "
                            "profile");
    for (int k = 0; k < tr->np; k++)
        if (tr->pres[k].law.kind == GD_PRESCRIBED_SPEED ||
            tr->pres[k].law.kind == GD_PRESCRIBED_TABLE)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "prescribed",
                                "prescribe a harmonic motion, or give the speed as the profile",
                                "a prescribed speed or angle table fixes the absolute motion: "
                                "it cannot follow a speed profile");
    for (int i = 0; i < tr->nlaw; i++)
        if (gd_law_flags(&tr->law[i]) & GD_LAW_CONSTANT_SPEED)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "laws",
                                "run at constant speeds (--sweep-speeds) instead",
                                "law '%s' (%s) turns at the constant reference speed: not with "
                                "a speed profile",
                                tr->law[i].name, tr->law[i].type->name);
    return GD_OK;
}

gd_status gd_tr_run_once(gd_transient *tr, const gd_transient_options *opt,
                         const gd_tr_record *records, int nrecords, gd_transient_result **out,
                         gd_error *err)
{
    *out = NULL;
    const int nf = tr->nf, n = tr->red ? tr->red->nfull : tr->n;
    /* auto: the linear time-invariant method when the model is one (and no Poincare
     * sample times are asked), else CVODE BDF */
    gd_transient_options resolved;
    char why[160] = "";
    if (opt->profile) {
        gd_status pst = profile_refusals(tr, opt, err);
        if (pst) return pst;
    }
    if (opt->method == GD_TR_AUTO && opt->profile) {
        /* the LTI method's harmonic forcing needs one constant speed */
        resolved = *opt;
        snprintf(why, sizeof why, "speed profile: the speed varies, not LTI");
        resolved.method = GD_TR_BDF;
        opt = &resolved;
    } else if (opt->method == GD_TR_AUTO) {
        resolved = *opt;
        if (opt->nsample_times > 0) snprintf(why, sizeof why, "Poincare sample times");
        resolved.method = opt->nsample_times == 0 && gd_tr_lti_reason(tr, why, sizeof why)
                              ? GD_TR_LTI
                              : GD_TR_BDF;
        if (tr->cond && tr->cond->info.ndiscarded > 0) {
            /* the condensed model below its cut-off is not stiff (the stiff modes are the
             * static correction) but oscillatory and lightly damped: Adams (orders to 12)
             * takes 0.66 x the steps of BDF (orders to 5) at the same error on the
             * 236-DOF box (docs/rattle.md) */
            snprintf(why, sizeof why, "condensed model below its cut-off: not stiff");
            resolved.method = GD_TR_ADAMS;
        }
        opt = &resolved;
    }
    const int is_auto = why[0] != 0;
    if (tr->cond && (opt->method == GD_TR_GEN_ALPHA || opt->method == GD_TR_LTI))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method", "use auto, bdf or adams",
                            "the condensed model runs with CVODE (bdf or adams) only");
    if (tr->cond && opt->init != GD_TR_INIT_REST)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "start",
                            "start at rest, or integrate the full model (--condense off)",
                            "the condensed model starts at rest only");
    double from = opt->record_from > opt->t_start ? opt->record_from : opt->t_start;
    if (!(opt->t_end > opt->t_start) || !isfinite(opt->t_end) || !isfinite(opt->t_start) ||
        !(from <= opt->t_end) || !(opt->rtol > 0) || !(opt->atol_q > 0) || !(opt->atol_v > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options",
                            "need finite t_end > t_start, record_from <= t_end, tolerances > 0",
                            "invalid time span or tolerances");
    if (opt->init == GD_TR_INIT_GIVEN && (!opt->q0 || !opt->v0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options.q0", "", "initial state missing");
    for (int r = 0; r < nrecords; r++) {
        gd_status st = check_record(tr, &records[r], err);
        if (st) return st;
    }
    if (opt->nsample_times < 0 || (opt->nsample_times > 0 && !opt->sample_times))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options.sample_times", "",
                            "sample times missing");
    for (int k = 0; k < opt->nsample_times; k++) {
        double ts = opt->sample_times[k];
        if (!(ts >= opt->t_start && ts <= opt->t_end) || (k && !(ts > opt->sample_times[k - 1])))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "options.sample_times",
                                "give increasing times within [t_start, t_end]",
                                "sample time %d (%g s) is out of order or outside the run", k, ts);
    }
    double dt = opt->output_interval > 0 ? opt->output_interval : (opt->t_end - from) / 1000.0;
    if (!(dt > 0)) dt = opt->t_end - opt->t_start;
    long nl = (long)floor((opt->t_end - from) / dt * (1.0 + 1e-12)) + 1;
    if (nl > 100000000L)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options.output_interval",
                            "use a longer output interval", "too many output samples");
    int nout = (int)nl;
    {
        gd_status st = check_step_count(tr, opt, dt, err);
        if (st) return st;
    }

    gd_transient_result *res = calloc(1, sizeof *res);
    if (!res) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    res->nout = nout;
    res->nrecords = nrecords;
    res->nmeshes = tr->nmesh;
    res->ndof = n;
    res->t = malloc((size_t)nout * sizeof *res->t);
    res->records = malloc((size_t)(nrecords > 0 ? nrecords : 1) * sizeof *res->records);
    res->values = malloc((size_t)(nrecords > 0 ? nrecords : 1) * nout * sizeof *res->values);
    res->stats = calloc((size_t)(nrecords > 0 ? nrecords : 1), sizeof *res->stats);
    res->contacts = calloc((size_t)(tr->nmesh > 0 ? tr->nmesh : 1), sizeof *res->contacts);
    res->q_end = calloc((size_t)n, sizeof *res->q_end);
    res->v_end = calloc((size_t)n, sizeof *res->v_end);
    int ns = opt->nsample_times;
    res->nsamples = ns;
    res->sample_t = calloc((size_t)(ns > 0 ? ns : 1), sizeof *res->sample_t);
    res->sample_values = calloc((size_t)(ns > 0 ? ns : 1) * (nrecords > 0 ? nrecords : 1),
                                sizeof *res->sample_values);
    res->sample_q = calloc((size_t)(ns > 0 ? ns : 1) * n, sizeof *res->sample_q);
    res->sample_v = calloc((size_t)(ns > 0 ? ns : 1) * n, sizeof *res->sample_v);
    gd_tr_contact_track *track = calloc((size_t)(tr->nmesh > 0 ? tr->nmesh : 1), sizeof *track);
    int *rootsfound = calloc((size_t)(tr->nroot > 0 ? tr->nroot : 1), sizeof *rootsfound);
    if (!res->t || !res->records || !res->values || !res->stats || !res->contacts || !res->q_end ||
        !res->v_end || !res->sample_t || !res->sample_values || !res->sample_q || !res->sample_v ||
        !track || !rootsfound) {
        free(track);
        free(rootsfound);
        gd_transient_result_free(res);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    if (nrecords) memcpy(res->records, records, (size_t)nrecords * sizeof *records);

    gd_status st = GD_OK;
    int flag = 0;
    SUNContext ctx = NULL;
    N_Vector y = NULL, atol = NULL;
    SUNLinearSolver LS = NULL;
    void *mem = NULL;
    clock_t c0 = clock();
    tr->msg[0] = 0;
    if (gd_tr_profile_set(tr, opt->profile)) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                          "out of memory (speed profile, speed-table bearings)");
        goto done;
    }
    if (SUNContext_Create(NULL, &ctx)) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "SUNDIALS context");
        goto done;
    }
    const int N = tr->cond ? tr->cond->ns : 2 * nf;
    y = N_VNew_Serial(N, ctx);
    atol = N_VNew_Serial(N, ctx);
    if (!y || !atol) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    double *yd = N_VGetArrayPointer(y), *ad = N_VGetArrayPointer(atol);
    for (int i = 0; !tr->cond && i < nf; i++) {
        ad[i] = opt->atol_q;
        ad[nf + i] = opt->atol_v;
    }
    if (tr->cond) {
        gd_tr_condensed_atol(tr, opt->atol_q, opt->atol_v, ad);
        gd_tr_condensed_reset(tr);
        gd_tr_condensed_tolerances(tr, opt->rtol, opt->atol_q, opt->atol_v);
    }
    memset(yd, 0, (size_t)N * sizeof *yd);
    if (opt->init == GD_TR_INIT_GIVEN && tr->red) {
        gd_tr_project(tr, opt->q0, tr->w1);
        gd_tr_project(tr, opt->v0, tr->w2);
        for (int i = 0; i < nf; i++) {
            yd[i] = tr->w1[tr->free_dof[i]];
            yd[nf + i] = tr->w2[tr->free_dof[i]];
        }
    } else if (opt->init == GD_TR_INIT_GIVEN) {
        for (int i = 0; i < nf; i++) {
            yd[i] = opt->q0[tr->free_dof[i]];
            yd[nf + i] = opt->v0[tr->free_dof[i]];
        }
    } else if (opt->init == GD_TR_INIT_STATIC) {
        st = gd_tr_static_state(tr, opt->t_start, yd, err);
        if (st) goto done;
    }
    gd_transient_set_contacts(tr, opt->t_start, yd);
    for (int i = 0; i < tr->nmesh; i++)
        track[i].since = opt->t_start;

    if (opt->method == GD_TR_GEN_ALPHA) {
        if (opt->nsample_times > 0) {
            st = gd_error_set(err, GD_EINPUT, "", 0, 0, "method", "use bdf or adams",
                              "Poincare sample times need a CVODE method");
            goto done;
        }
        st = gd_tr_run_gen_alpha(tr, opt, records, nrecords, from, dt, yd, res, track, err);
        if (st) goto done;
        goto finish;
    }
    if (opt->method == GD_TR_LTI) {
        if (opt->nsample_times > 0) {
            st = gd_error_set(err, GD_EINPUT, "", 0, 0, "method", "use bdf or adams",
                              "Poincare sample times need a CVODE method");
            goto done;
        }
        st = gd_tr_run_lti(tr, opt, records, nrecords, from, dt, yd, res, err);
        if (st) goto done;
        goto finish;
    }
    mem = gd_tr_cvode_new(ctx, opt, opt->t_start, opt->t_end, y, atol, cv_rhs, cv_root,
                          tr->nroot && opt->locate_events ? tr->nroot : 0,
                          tr->cond ? NULL : gd_tr_cv_psetup, tr->cond ? NULL : gd_tr_cv_psolve, tr,
                          tr, &LS, &flag);
    if (!mem || flag) {
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "", "", "CVODE set-up failed (%d) %s", flag,
                          tr->msg);
        goto done;
    }

    run_work w = {mem, y, rootsfound, res, track, from, 0};
    double t = opt->t_start;
    int ks = 0;
    for (int k = 0; k < nout; k++) {
        double tk = from + k * dt;
        if (tk > opt->t_end || k == nout - 1) tk = fmin(tk, opt->t_end);
        /* Poincare samples before tk, then tk itself, then samples at tk */
        for (; ks < opt->nsample_times && opt->sample_times[ks] < tk; ks++) {
            if ((st = advance(tr, &w, opt, &t, opt->sample_times[ks], err))) goto done;
            store_sample(tr, res, records, ks, t, yd);
        }
        if ((st = advance(tr, &w, opt, &t, tk, err))) goto done;
        res->t[k] = tk;
        gd_tr_fill(tr, tk, yd, tr->q, tr->v, NULL);
        for (int r = 0; r < nrecords; r++)
            res->values[(size_t)r * nout + k] =
                gd_tr_record_value(tr, &records[r], tk, tr->q, tr->v);
        for (; ks < opt->nsample_times && opt->sample_times[ks] <= tk; ks++)
            store_sample(tr, res, records, ks, t, yd);
    }
    /* samples after the last record time (its rounding), and the end itself */
    for (; ks < opt->nsample_times; ks++) {
        if ((st = advance(tr, &w, opt, &t, opt->sample_times[ks], err))) goto done;
        store_sample(tr, res, records, ks, t, yd);
    }
    if ((st = advance(tr, &w, opt, &t, opt->t_end, err))) goto done;
finish:
    method_note(tr->cond ? tr : NULL, opt, is_auto ? why : NULL, dt, res);
    if (opt->profile && tr->sys->has_speed_dependent) {
        size_t k = strlen(res->method_note);
        snprintf(res->method_note + k, sizeof res->method_note - k,
                 "; speed-table bearings at W(t) (linear between %d speeds)", GD_TR_SD_SPEEDS);
    }
    for (int i = 0; i < tr->nmesh; i++)
        gd_tr_contact_account(&res->contacts[i], (gd_contact)tr->law[i].mode, track[i].since,
                              opt->t_end, from);
    gd_tr_fill(tr, opt->t_end, yd, tr->q, tr->v, NULL);
    full_state(tr, tr->q, tr->v, res->q_end, res->v_end);
    for (int r = 0; r < nrecords; r++)
        stats_of(res->values + (size_t)r * nout, nout, &res->stats[r]);
    if (mem) add_counters(mem, res);
done:
    gd_tr_profile_set(tr, NULL);
    res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (tr->cond) gd_tr_condensed_solver_free(tr);
    if (y) N_VDestroy(y);
    if (atol) N_VDestroy(atol);
    if (ctx) SUNContext_Free(&ctx);
    free(track);
    free(rootsfound);
    if (st) {
        gd_transient_result_free(res);
        return st;
    }
    *out = res;
    return GD_OK;
}
