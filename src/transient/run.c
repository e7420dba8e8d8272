/* Integration of a transient problem with SUNDIALS CVODE: BDF or Adams, Newton with
 * GMRES preconditioned by the exact inverse of the linear part, root-finding on the
 * contact changes of backlash meshes with the contact state frozen between events and a
 * restart at every event; fixed-interval records and summary statistics. */
#include <cvode/cvode.h>
#include <math.h>
#include <nvector/nvector_serial.h>
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

static int cv_psetup(sunrealtype t, N_Vector y, N_Vector fy, sunbooleantype jok,
                     sunbooleantype *jcur, sunrealtype gamma, void *ud)
{
    (void)t;
    (void)y;
    (void)fy;
    (void)jok;
    *jcur = SUNTRUE;
    return gd_tr_prec_setup(ud, gamma) ? 1 : 0; /* > 0: recoverable */
}

static int cv_psolve(sunrealtype t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z,
                     sunrealtype gamma, sunrealtype delta, int lr, void *ud)
{
    (void)t;
    (void)y;
    (void)fy;
    (void)gamma;
    (void)delta;
    (void)lr;
    gd_tr_prec_solve(ud, N_VGetArrayPointer(r), N_VGetArrayPointer(z));
    return 0;
}

static void cv_err(int code, const char *module, const char *function, char *msg, void *ud)
{
    (void)module;
    gd_transient *tr = ud;
    if (code < 0) snprintf(tr->msg, sizeof tr->msg, "%s: %s", function, msg);
}

/* Record value r at time t with full q, v. */
double gd_tr_record_value(gd_transient *tr, const gd_tr_record *rec, double t, const double *q,
                          const double *v)
{
    const gd_model *model = tr->sys->model;
    int i = rec->index;
    switch (rec->kind) {
    case GD_REC_DISP:
        return q[i];
    case GD_REC_VEL:
        return v[i];
    case GD_REC_ANGLE:
        return tr->rate[i] * t + q[i];
    case GD_REC_SPEED:
        return tr->rate[i] + v[i];
    case GD_REC_SPEED_RATIO: {
        double den = tr->rate[rec->index2] + v[rec->index2];
        return den != 0.0 ? (tr->rate[i] + v[i]) / den : 0.0;
    }
    case GD_REC_MESH_FORCE:
    case GD_REC_MESH_DEFLECTION:
    case GD_REC_MESH_STATE:
    case GD_REC_MESH_STIFFNESS: {
        int nl = tr->nl_of_mesh[i];
        double d, dd, k, F;
        gd_contact state = GD_CONTACT_DRIVE;
        if (nl >= 0) {
            const tr_mesh *m = &tr->mesh[nl];
            state = m->state;
            F = gd_tr_mesh_force(tr, m, state, t, q, v, &d, &dd, &k, NULL);
        } else {
            const gd_mesh_vector *a = &tr->model_a[i];
            d = dd = 0.0;
            for (int j = 0; j < a->n; j++) {
                d += a->a[j] * q[a->dof[j]];
                dd += a->a[j] * v[a->dof[j]];
            }
            k = model->meshes[i].stiffness;
            F = k * d + model->meshes[i].damping * dd;
        }
        if (rec->kind == GD_REC_MESH_FORCE) return F;
        if (rec->kind == GD_REC_MESH_DEFLECTION) return d;
        if (rec->kind == GD_REC_MESH_STATE) return (double)state;
        return k;
    }
    case GD_REC_SFD_FX:
    case GD_REC_SFD_FY:
    case GD_REC_SFD_ECCENTRICITY: {
        const tr_sfd *s = &tr->sfd[i];
        double x = q[s->dx] - (s->dx2 >= 0 ? q[s->dx2] : 0.0);
        double y = q[s->dy] - (s->dy2 >= 0 ? q[s->dy2] : 0.0);
        double vx = v[s->dx] - (s->dx2 >= 0 ? v[s->dx2] : 0.0);
        double vy = v[s->dy] - (s->dy2 >= 0 ? v[s->dy2] : 0.0);
        if (rec->kind == GD_REC_SFD_ECCENTRICITY) return hypot(x, y) / s->p.clearance;
        double fx, fy;
        gd_sfd_force(&s->p, x, y, vx, vy, &fx, &fy);
        return rec->kind == GD_REC_SFD_FX ? fx : fy;
    }
    }
    return 0.0;
}

static gd_status check_record(const gd_transient *tr, const gd_tr_record *r, gd_error *err)
{
    int ok = 1;
    switch (r->kind) {
    case GD_REC_DISP:
    case GD_REC_VEL:
    case GD_REC_ANGLE:
    case GD_REC_SPEED:
        ok = r->index >= 0 && r->index < tr->n;
        break;
    case GD_REC_SPEED_RATIO:
        ok = r->index >= 0 && r->index < tr->n && r->index2 >= 0 && r->index2 < tr->n;
        break;
    case GD_REC_MESH_FORCE:
    case GD_REC_MESH_DEFLECTION:
    case GD_REC_MESH_STATE:
    case GD_REC_MESH_STIFFNESS:
        ok = r->index >= 0 && r->index < tr->nmodel_mesh;
        break;
    case GD_REC_SFD_FX:
    case GD_REC_SFD_FY:
    case GD_REC_SFD_ECCENTRICITY:
        ok = r->index >= 0 && r->index < tr->nsfd;
        break;
    default:
        ok = 0;
    }
    if (ok) return GD_OK;
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "record", "", "record refers to nothing");
}

/* Static equilibrium at t: modified Newton with the linear stiffness (meshes at their
 * model stiffness, always in contact) as the iteration matrix. Backlash meshes are held
 * on a flank (each flank's law continued beyond its interval, so the problem is smooth):
 * all start on the drive flank; after convergence a mesh whose force pulls (F < 0) moves
 * to the coast flank and one pushing on the coast flank back to the drive flank, until
 * no flank changes. A mesh carrying no load is left in the gap by the caller's
 * gd_transient_set_contacts. */
static gd_status static_state(gd_transient *tr, double t, double *y, gd_error *err)
{
    const int nf = tr->nf;
    css *S = cs_sqr(1, tr->Kff, 0);
    csn *N = S ? cs_lu(tr->Kff, S, 1.0) : NULL;
    if (!N) {
        cs_sfree(S);
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "init",
                            "start from rest, or prescribe a DOF (e.g. the input) or add "
                            "a support",
                            "static initial state: the stiffness of the free DOFs is singular "
                            "(a free rigid-body motion)");
    }
    memset(y, 0, (size_t)2 * nf * sizeof *y);
    gd_status st = GD_OK;
    double *b = tr->w1, *x = tr->w2;
    for (int i = 0; i < tr->nmesh; i++)
        tr->mesh[i].state = GD_CONTACT_DRIVE;
    int converged = 0;
    for (int outer = 0; outer < 20 && !converged; outer++) {
        int it;
        for (it = 0; it < 500; it++) {
            gd_tr_fill(tr, t, y, tr->q, tr->v, tr->acc);
            memset(tr->acc, 0, (size_t)tr->n * sizeof *tr->acc);
            gd_tr_residual(tr, t, tr->q, tr->v, tr->acc, tr->r);
            for (int i = 0; i < nf; i++)
                b[i] = tr->r[tr->free_dof[i]];
            cs_ipvec(N->pinv, b, x, nf);
            cs_lsolve(N->L, x);
            cs_usolve(N->U, x);
            cs_ipvec(S->q, x, b, nf);
            double dn = 0, qn = 0;
            for (int i = 0; i < nf; i++) {
                y[i] += b[i];
                dn = fmax(dn, fabs(b[i]));
                qn = fmax(qn, fabs(y[i]));
            }
            if (dn <= 1e-13 * qn || dn == 0.0) break;
        }
        if (it == 500) break;
        converged = 1;
        gd_tr_fill(tr, t, y, tr->q, tr->v, NULL);
        for (int i = 0; i < tr->nmesh; i++) {
            tr_mesh *m = &tr->mesh[i];
            if (!m->spec.backlash) continue;
            double F = gd_tr_mesh_force(tr, m, m->state, t, tr->q, tr->v, NULL, NULL, NULL, NULL);
            if (m->state == GD_CONTACT_DRIVE && F < 0) {
                m->state = GD_CONTACT_COAST;
                converged = 0;
            } else if (m->state == GD_CONTACT_COAST && F > 0) {
                m->state = GD_CONTACT_DRIVE;
                converged = 0;
            }
        }
    }
    if (!converged)
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "init", "start from rest",
                          "static initial state did not converge");
    cs_sfree(S);
    cs_nfree(N);
    return st;
}

static void stats_of(const double *x, int n, gd_tr_stats *s)
{
    memset(s, 0, sizeof *s);
    if (n <= 0) return;
    double mn = x[0], mx = x[0], sum = 0, sq = 0;
    for (int k = 0; k < n; k++) {
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
    free(r->q_end);
    free(r->v_end);
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
}

/* Bookkeeping of contact states over [record_from, t_end]. */
typedef struct contact_track {
    double since;
} contact_track;

static void account(gd_tr_contact_stats *cs_, gd_contact state, double t0, double t1, double from)
{
    if (t0 < from) t0 = from;
    if (t1 <= t0) return;
    if (state == GD_CONTACT_SEPARATED)
        cs_->separated_time += t1 - t0;
    else if (state == GD_CONTACT_COAST)
        cs_->coast_time += t1 - t0;
    else
        cs_->drive_time += t1 - t0;
}

static void change_state(gd_transient *tr, int i, gd_contact ns, double t, double from,
                         gd_tr_contact_stats *st, contact_track *track)
{
    tr_mesh *m = &tr->mesh[i];
    if (ns == m->state) return;
    account(&st[i], m->state, track[i].since, t, from);
    if (t >= from) {
        if (m->state == GD_CONTACT_DRIVE && ns != GD_CONTACT_DRIVE) st[i].contact_losses++;
        if (ns == GD_CONTACT_COAST) st[i].coast_impacts++;
        if (ns == GD_CONTACT_DRIVE) st[i].drive_impacts++;
    }
    track[i].since = t;
    m->state = ns;
}

gd_status gd_transient_run(gd_transient *tr, const gd_transient_options *opt,
                           const gd_tr_record *records, int nrecords, gd_transient_result **out,
                           gd_error *err)
{
    *out = NULL;
    const int nf = tr->nf, n = tr->n;
    double from = opt->record_from > opt->t_start ? opt->record_from : opt->t_start;
    if (!(opt->t_end > opt->t_start) || !(from <= opt->t_end) || !(opt->rtol > 0) ||
        !(opt->atol_q > 0) || !(opt->atol_v > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options",
                            "need t_end > t_start, record_from <= t_end, tolerances > 0",
                            "invalid time span or tolerances");
    if (opt->init == GD_TR_INIT_GIVEN && (!opt->q0 || !opt->v0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options.q0", "", "initial state missing");
    for (int r = 0; r < nrecords; r++) {
        gd_status st = check_record(tr, &records[r], err);
        if (st) return st;
    }
    double dt = opt->output_interval > 0 ? opt->output_interval : (opt->t_end - from) / 1000.0;
    if (!(dt > 0)) dt = opt->t_end - opt->t_start;
    long nl = (long)floor((opt->t_end - from) / dt * (1.0 + 1e-12)) + 1;
    if (nl > 100000000L)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "options.output_interval",
                            "use a longer output interval", "too many output samples");
    int nout = (int)nl;

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
    contact_track *track = calloc((size_t)(tr->nmesh > 0 ? tr->nmesh : 1), sizeof *track);
    int *rootsfound = calloc((size_t)(tr->nroot > 0 ? tr->nroot : 1), sizeof *rootsfound);
    if (!res->t || !res->records || !res->values || !res->stats || !res->contacts || !res->q_end ||
        !res->v_end || !track || !rootsfound) {
        free(track);
        free(rootsfound);
        gd_transient_result_free(res);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    if (nrecords) memcpy(res->records, records, (size_t)nrecords * sizeof *records);

    gd_status st = GD_OK;
    SUNContext ctx = NULL;
    N_Vector y = NULL, atol = NULL;
    SUNLinearSolver LS = NULL;
    void *mem = NULL;
    clock_t c0 = clock();
    tr->msg[0] = 0;
    if (SUNContext_Create(NULL, &ctx)) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "SUNDIALS context");
        goto done;
    }
    y = N_VNew_Serial(2 * nf, ctx);
    atol = N_VNew_Serial(2 * nf, ctx);
    if (!y || !atol) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    double *yd = N_VGetArrayPointer(y), *ad = N_VGetArrayPointer(atol);
    for (int i = 0; i < nf; i++) {
        ad[i] = opt->atol_q;
        ad[nf + i] = opt->atol_v;
    }
    memset(yd, 0, (size_t)2 * nf * sizeof *yd);
    if (opt->init == GD_TR_INIT_GIVEN) {
        for (int i = 0; i < nf; i++) {
            yd[i] = opt->q0[tr->free_dof[i]];
            yd[nf + i] = opt->v0[tr->free_dof[i]];
        }
    } else if (opt->init == GD_TR_INIT_STATIC) {
        st = static_state(tr, opt->t_start, yd, err);
        if (st) goto done;
    }
    gd_transient_set_contacts(tr, opt->t_start, yd);
    for (int i = 0; i < tr->nmesh; i++)
        track[i].since = opt->t_start;

    mem = CVodeCreate(opt->method == GD_TR_ADAMS ? CV_ADAMS : CV_BDF, ctx);
    if (!mem) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "CVODE");
        goto done;
    }
    CVodeSetErrHandlerFn(mem, cv_err, tr);
    int flag = CVodeInit(mem, cv_rhs, opt->t_start, y);
    if (!flag) flag = CVodeSVtolerances(mem, opt->rtol, atol);
    if (!flag) flag = CVodeSetUserData(mem, tr);
    LS = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 20, ctx);
    if (!LS) flag = -1;
    if (!flag) flag = CVodeSetLinearSolver(mem, LS, NULL);
    if (!flag) flag = CVodeSetPreconditioner(mem, cv_psetup, cv_psolve);
    if (!flag) flag = CVodeSetMaxNumSteps(mem, opt->max_steps > 0 ? opt->max_steps : 50000000L);
    if (!flag && opt->max_step > 0) flag = CVodeSetMaxStep(mem, opt->max_step);
    if (!flag) flag = CVodeSetStopTime(mem, opt->t_end);
    if (!flag && opt->method == GD_TR_BDF) flag = CVodeSetStabLimDet(mem, SUNTRUE);
    if (!flag && opt->max_order > 0) flag = CVodeSetMaxOrd(mem, opt->max_order);
    if (!flag && tr->nroot && opt->locate_events) {
        flag = CVodeRootInit(mem, tr->nroot, cv_root);
        if (!flag) flag = CVodeSetNoInactiveRootWarn(mem);
    }
    if (flag) {
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "", "", "CVODE set-up failed (%d) %s", flag,
                          tr->msg);
        goto done;
    }

    double t = opt->t_start;
    for (int k = 0; k < nout; k++) {
        double tk = from + k * dt;
        if (tk > opt->t_end || k == nout - 1) tk = fmin(tk, opt->t_end);
        while (t < tk) {
            /* with a progress report, the stretch before record_from is split (CVODE
             * interpolates at the intermediate times; its steps are the same) */
            double tout = tk, chunk = (opt->t_end - opt->t_start) / 200.0;
            if (opt->progress && tk - t > 1.5 * chunk) tout = t + chunk;
            flag = CVode(mem, tout, y, &t, CV_NORMAL);
            if (opt->progress) opt->progress(t, opt->t_start, opt->t_end, opt->progress_data);
            if (flag == CV_ROOT_RETURN) {
                CVodeGetRootInfo(mem, rootsfound);
                int changed = 0, kr = 0;
                for (int i = 0; i < tr->nmesh; i++) {
                    tr_mesh *m = &tr->mesh[i];
                    if (!m->spec.backlash) continue;
                    int r0 = rootsfound[kr++], r1 = rootsfound[kr++];
                    gd_contact ns = m->state;
                    if (r1 < 0)
                        ns = GD_CONTACT_COAST;
                    else if (r0 > 0)
                        ns = GD_CONTACT_DRIVE;
                    else if (r0 < 0 || r1 > 0)
                        ns = GD_CONTACT_SEPARATED;
                    if (ns != m->state) {
                        change_state(tr, i, ns, t, from, res->contacts, track);
                        changed = 1;
                    }
                    if (r0 || r1) res->events++;
                }
                if (changed) {
                    add_counters(mem, res);
                    CVodeReInit(mem, t, y);
                    res->reinits++;
                }
                continue;
            }
            if (flag < 0) {
                st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "",
                                  "tighten or loosen the "
                                  "tolerances, or limit the step",
                                  "CVODE failed at t = %g s (flag %d): %s", t, flag, tr->msg);
                goto done;
            }
            /* a contact change the root-finding missed (two crossings in one step) */
            if (tr->nroot) {
                gd_tr_fill(tr, t, yd, tr->q, tr->v, NULL);
                int changed = 0;
                for (int i = 0; i < tr->nmesh; i++) {
                    tr_mesh *m = &tr->mesh[i];
                    if (!m->spec.backlash) continue;
                    double de;
                    gd_tr_mesh_force(tr, m, m->state, t, tr->q, tr->v, NULL, NULL, NULL, &de);
                    gd_contact ns = gd_backlash_state(de, m->spec.gap);
                    double tol = 1e-6 * m->spec.gap + 1e-15;
                    if (ns != m->state && fabs(fabs(de) - m->spec.gap) > tol) {
                        change_state(tr, i, ns, t, from, res->contacts, track);
                        changed = 1;
                        res->events++;
                    }
                }
                if (changed) {
                    add_counters(mem, res);
                    CVodeReInit(mem, t, y);
                    res->reinits++;
                }
            }
        }
        res->t[k] = tk;
        gd_tr_fill(tr, tk, yd, tr->q, tr->v, NULL);
        for (int r = 0; r < nrecords; r++)
            res->values[(size_t)r * nout + k] =
                gd_tr_record_value(tr, &records[r], tk, tr->q, tr->v);
    }
    for (int i = 0; i < tr->nmesh; i++)
        account(&res->contacts[i], tr->mesh[i].state, track[i].since, opt->t_end, from);
    gd_tr_fill(tr, opt->t_end, yd, res->q_end, res->v_end, NULL);
    for (int r = 0; r < nrecords; r++)
        stats_of(res->values + (size_t)r * nout, nout, &res->stats[r]);
    add_counters(mem, res);
done:
    res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
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
