/* Periodic steady state by shooting (docs/periodic.md, "Shooting"): the orbit is the fixed
 * point of the period map P, the state after one period T of transient's own integrator
 * (CVODE with located contact events) started from y0 at t = 0,
 *
 *   F(y0) = P(y0) - y0 = 0,
 *
 * solved by Newton with the monodromy matrix Phi = dP/dy0 (gd_transient_monodromy: the
 * variational equations integrated with the state, saltation at every contact change;
 * Leine & Nijmeijer 2004, Sec. 3.5): (Phi - I) dy = -F, with a backtracking line search on
 * the scaled |F| (Seydel 2010, Sec. 7.3). The Floquet multipliers are the eigenvalues of
 * Phi at the converged orbit; the records' statistics come from one more integrated period
 * sampled at the times harmonic balance samples its records (so both report the same
 * quantities). This file holds the problem per value, the period map, Newton (dense and
 * Newton-Krylov), the warm start and the points; the continuation is in
 * shooting_arclength.c (pseudo-arclength) and shooting_natural.c (natural, and the
 * entry gd_per_shoot_run). */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "linalg/linalg_impl.h"
#include "periodic/continuation_impl.h"
#include "periodic/shooting/shooting_impl.h"
#include "periodic/periodic_impl.h"

/* Most periods of the warm-start transient (it stops once a period changes the state by
 * less than 1e-3): enough for a damped resonance to come near its orbit, Newton removes
 * the rest (the Chen pair's first point then converges in 2 to 5 iterations). */
#define WARM_PERIODS 12

/* Releases the problem of slot q. */
static void release_slot(shoot_prob *q)
{
    gd_transient_free(q->tr);
    gd_transient_model_free(q->tm);
    free(q->loads);
    gd_system_free(q->s);
    gd_model_free(q->m);
    memset(q, 0, sizeof *q);
}

static int grow(shoot *sh)
{
    size_t N = (size_t)sh->N, NN = sh->dense ? N * N : 0;
    if (N > sh->capN) {
        free(sh->mem);
        free(sh->ipiv);
        sh->mem = malloc((2 * NN + 10 * N + 2) * sizeof *sh->mem);
        sh->ipiv = malloc((N + 1) * sizeof *sh->ipiv);
        if (!sh->mem || !sh->ipiv) {
            sh->capN = 0;
            return 1;
        }
        sh->capN = N;
    }
    sh->phi = sh->mem;
    sh->A = sh->mem + NN;
    sh->yT = sh->A + NN;
    sh->r = sh->yT + N;
    sh->dy = sh->r + N;
    sh->yt = sh->dy + N;
    sh->mre = sh->yt + N;
    sh->mim = sh->mre + N;
    sh->racc = sh->mim + N; /* F at the accepted iterate */
    sh->ytmp = sh->racc + N;
    if (sh->ndof > sh->capdof) {
        free(sh->q0);
        sh->q0 = calloc(2 * (size_t)sh->ndof, sizeof *sh->q0);
        if (!sh->q0) return 1;
        sh->capdof = sh->ndof;
    }
    sh->qv0 = sh->q0 + sh->ndof;
    return 0;
}

/* The problem at value key (a speed, or the parameter through the caller's rebuild).
 * 0 ok; 1 with sh->why. */
int gd_per_sh_problem(shoot *sh, double key)
{
    if (!sh->p) sh->p = &sh->slot[0];
    if (sh->p->have && sh->p->key == key) return 0;
    /* the other slot holds it (the bordered corrector alternates the value and the value
     * plus its difference step), else it is made there: the last problem stays */
    shoot_prob *o = sh->p == &sh->slot[0] ? &sh->slot[1] : &sh->slot[0];
    sh->p = o;
    if (o->have && o->key == key) return 0;
    release_slot(o);
    gd_error err;
    double speed = key;
    sh->p->sys = sh->sys0;
    sh->p->spec = sh->spec0;
    if (sh->param && sh->param->load_frequency) {
        if (gd_per_frequency_spec(sh->spec0, key, &sh->p->loads, &sh->p->fspec, sh->why,
                                  sizeof sh->why))
            return 1;
        sh->p->spec = &sh->p->fspec;
        speed = sh->param->speed;
    } else if (sh->param) {
        const gd_periodic_param *p = sh->param;
        gd_status st = p->rebuild ? p->rebuild(key, p->data, &sh->p->m, &sh->p->s, &sh->p->tm, &err)
                                  : gd_error_set(&err, GD_EINPUT, "", 0, 0, "param", "",
                                                 "no rebuild function");
        if (!st && (!sh->p->m || !sh->p->s || !sh->p->tm))
            st =
                gd_error_set(&err, GD_EINPUT, "", 0, 0, "param", "", "rebuild returned no problem");
        if (st) {
            snprintf(sh->why, sizeof sh->why, "%.40s = %.10g: %.160s", p->name ? p->name : "value",
                     key, err.message);
            return 1;
        }
        sh->p->sys = sh->p->s;
        sh->p->spec = &sh->p->tm->spec;
        speed = p->speed;
    }
    double w0;
    int order;
    if (gd_periodic_fundamental(sh->p->sys, sh->p->spec, speed, &w0, &order, &err)) {
        snprintf(sh->why, sizeof sh->why, "%.250s", err.message);
        return 1;
    }
    sh->p->w = w0 / sh->opt->subharmonic;
    sh->p->T = TWO_PI / sh->p->w;
    /* the harmonics reported: as harmonic balance would use them (at least every
     * excitation's multiple of the period) */
    long need = (long)order * sh->opt->subharmonic;
    sh->p->H = sh->opt->harmonics;
    if (sh->opt->adaptive && need > sh->p->H) sh->p->H = need > 1 << 20 ? 1 << 20 : (int)need;
    sh->p->Nr = 256;
    while (sh->p->Nr < 8 * (sh->p->H + 1))
        sh->p->Nr *= 2;
    if (gd_transient_new(sh->p->sys, sh->p->spec, speed, &sh->p->tr, &err)) {
        snprintf(sh->why, sizeof sh->why, "%.250s", err.message);
        return 1;
    }
    int N = gd_transient_nstates(sh->p->tr);
    if (sh->N && N != sh->N) {
        snprintf(sh->why, sizeof sh->why, "the number of free DOFs changes with the parameter");
        return 1;
    }
    sh->N = N;
    sh->nf = N / 2;
    sh->dense = N <= (sh->opt->shoot_dense_max > 0 ? sh->opt->shoot_dense_max : 64);
    sh->ndof = sh->p->sys->ndof;
    if (grow(sh)) {
        snprintf(sh->why, sizeof sh->why, "out of memory (%d states)", N);
        return 1;
    }
    free(sh->free_dof);
    sh->free_dof = malloc((size_t)(sh->nf > 0 ? sh->nf : 1) * sizeof *sh->free_dof);
    if (!sh->free_dof) return 1;
    for (int i = 0; i < sh->nf; i++)
        sh->free_dof[i] = -1;
    for (int d = 0; d < sh->ndof; d++) {
        gd_tr_record rec = {GD_REC_DISP, d, 0};
        int k = -1;
        if (gd_transient_record_dofs(sh->p->tr, &rec, &k, 1) == 1 && k >= 0 && k < sh->nf)
            sh->free_dof[k] = d;
    }
    for (int i = 0; i < sh->nf; i++)
        if (sh->free_dof[i] < 0) {
            snprintf(sh->why, sizeof sh->why,
                     "shooting needs the physical DOFs (a reduced model is not supported)");
            return 1;
        }
    sh->p->key = key;
    sh->p->have = 1;
    return 0;
}

/* The sizes of the displacements and of the velocities of the orbit through y: the
 * largest of each block, each at least the other over (times) the frequency w, since an
 * oscillation of amplitude a has velocities w a. The state at t = 0 is one sample of the
 * orbit: a displacement there can pass through zero while the orbit does not shrink (the
 * backlash pair's unstable branch near 419 rad/s: q(0) 2e-7 rad with velocities of 0.58
 * rad/s at w = 8380 rad/s), and scales from it alone made the residual test and the
 * arclength's variables hang on that sample. */
static void block_size(const shoot *sh, const double *y, double *sq, double *sv)
{
    double q = 0.0, v = 0.0;
    for (int i = 0; i < sh->nf; i++) {
        q = fmax(q, fabs(y[i]));
        v = fmax(v, fabs(y[sh->nf + i]));
    }
    const double w = sh->p && sh->p->have ? sh->p->w : 0.0;
    *sq = w > 0 ? fmax(q, v / w) : q;
    *sv = w > 0 ? fmax(v, w * q) : v;
}

/* Integration tolerances from the size of the orbit through y (atol a thousandth of rtol
 * times the displacements' and the velocities' sizes): the orbit, not its units, sets
 * them. */
void gd_per_sh_tolerances(shoot *sh, const double *y)
{
    double sq, sv;
    block_size(sh, y, &sq, &sv);
    sh->rtol = sh->opt->shoot_rtol > 0 ? sh->opt->shoot_rtol : 1e-9;
    sh->atol_q = sh->rtol * (sq > 0 ? 1e-3 * sq : 1e-6);
    sh->atol_v = sh->rtol * (sv > 0 ? 1e-3 * sv : 1e-3);
    /* Newton cannot resolve the fixed point better than the integrator: a hundred times its
     * tolerance, or the caller's when looser */
    sh->tol = fmax(sh->opt->tol, 100.0 * sh->rtol);
}

static void tr_options(const shoot *sh, gd_transient_options *o)
{
    gd_transient_options_init(o);
    o->rtol = sh->rtol;
    o->atol_q = sh->atol_q;
    o->atol_v = sh->atol_v;
    o->t_start = 0.0;
    o->t_end = sh->p->T;
    o->output_interval = sh->p->T;
}

/* |F| scaled: per block (displacements, velocities) the largest entry relative to the
 * block's size (block_size, or its tolerance scale). */
double gd_per_sh_norm(const shoot *sh, const double *y, const double *f)
{
    const int nf = sh->nf;
    double yq, yv, fq = 0.0, fv = 0.0;
    block_size(sh, y, &yq, &yv);
    yq = fmax(yq, sh->atol_q / sh->rtol);
    yv = fmax(yv, sh->atol_v / sh->rtol);
    for (int i = 0; i < nf; i++) {
        fq = fmax(fq, fabs(f[i]));
        fv = fmax(fv, fabs(f[nf + i]));
    }
    double r = fmax(fq / yq, fv / yv);
    return isfinite(r) ? r : INFINITY;
}

static void to_dofs(shoot *sh, const double *y)
{
    memset(sh->q0, 0, 2 * (size_t)sh->ndof * sizeof *sh->q0);
    for (int i = 0; i < sh->nf; i++) {
        sh->q0[sh->free_dof[i]] = y[i];
        sh->qv0[sh->free_dof[i]] = y[sh->nf + i];
    }
}

/* One period from y (records and samples as asked): the result, or NULL with sh->why. */
/* One right-hand side of the current problem in seconds of counted work (work.c). */
static double rhs_seconds(shoot *sh)
{
    if (!(sh->p->rhs_s > 0))
        sh->p->rhs_s = gd_per_work_seconds(gd_per_rhs_flops(sh->p->tr, sh->p->spec));
    return sh->p->rhs_s;
}

static gd_transient_result *integrate(shoot *sh, const double *y, double t_end, const double *ts,
                                      int nts, const gd_tr_record *rec, int nrec)
{
    gd_transient_options o;
    tr_options(sh, &o);
    o.t_end = t_end;
    o.output_interval = t_end;
    o.sample_times = ts;
    o.nsample_times = nts;
    if (y) {
        to_dofs(sh, y);
        o.init = GD_TR_INIT_GIVEN;
        o.q0 = sh->q0;
        o.v0 = sh->qv0;
    } else {
        o.init = sh->p->spec->nloads ? GD_TR_INIT_STATIC : GD_TR_INIT_REST;
    }
    gd_transient_result *r = NULL;
    gd_error err;
    if (gd_transient_run(sh->p->tr, &o, rec, nrec, &r, &err)) {
        snprintf(sh->why, sizeof sh->why, "integration failed: %.220s", err.message);
        return NULL;
    }
    sh->last_work = (double)r->rhs_evals * rhs_seconds(sh);
    sh->work += sh->last_work;
    return r;
}

static void from_dofs(const shoot *sh, const gd_transient_result *r, double *y)
{
    for (int i = 0; i < sh->nf; i++) {
        y[i] = r->q_end[sh->free_dof[i]];
        y[sh->nf + i] = r->v_end[sh->free_dof[i]];
    }
}

/* The cost of a monodromy: the last one's counted right-hand sides, else (2 n + 1) plain
 * periods at 0.7 each (the augmented system's right-hand side costs 2 n + 1 evaluations;
 * measured on the Ducati train, 22 states: 20.4 s against 0.63 s per period), counted
 * from the last plain period. */
static double mono_cost(const shoot *sh)
{
    return sh->t_mono > 0 ? sh->t_mono : 0.7 * (2.0 * sh->N + 1.0) * sh->t_period;
}

/* 1 when the next job (predicted cost next) would take the point past its CPU budget:
 * sh->why says so, with what the warm start saw. */
int gd_per_sh_over_budget(shoot *sh, double next, const char *what)
{
    const double budget = sh->opt->shoot_budget, used = sh->work;
    if (!(budget > 0) || used + next <= budget) return 0;
    sh->budget_hit = 1;
    char settle[160] = "";
    if (isfinite(sh->warm_change))
        snprintf(settle, sizeof settle,
                 "; from rest the transient still changes by %.2g per period after %d "
                 "periods%s",
                 sh->warm_change, sh->warm_periods,
                 sh->warm_change > 1e-2
                     ? ": no stable period-1 orbit attracts it (see geardyn transient)"
                     : "");
    /* kept under the 256 characters of gd_periodic_point.reason, the longest `what` and
     * the settle note included (the Ducati train's message was cut before) */
    int len = snprintf(sh->why, sizeof sh->why,
                       "shooting stopped at %.1f s: %s needs about %.2g s more (budget %.3g s, "
                       "counted)%.130s",
                       used, what, next, budget, settle);
    if (len < 0) sh->why[0] = '\0';
    return 1;
}

/* yT = P(y) by a plain integration. 0 ok. */
int gd_per_sh_period(shoot *sh, const double *y, double *yT)
{
    if (sh->t_period > 0 && gd_per_sh_over_budget(sh, sh->t_period, "a period of the line search"))
        return 1;
    gd_transient_result *r = integrate(sh, y, sh->p->T, NULL, 0, NULL, 0);
    if (!r) return 1;
    sh->t_period = sh->last_work;
    from_dofs(sh, r, yT);
    gd_transient_result_free(r);
    return 0;
}

/* Phi and yT = P(y). 0 ok. The monodromy runs under the point's budget in counted
 * right-hand sides (what the budget leaves over one right-hand side's counted work), so
 * the budget stops it inside one matrix as well as between matrices; its work is what it
 * counted. */
int gd_per_sh_monodromy(shoot *sh, const double *y, double *phi, double *yT)
{
    gd_transient_options o;
    tr_options(sh, &o);
    gd_error err;
    if (sh->t_period > 0 && gd_per_sh_over_budget(sh, mono_cost(sh), "the next monodromy matrix"))
        return 1;
    const double budget = sh->opt->shoot_budget, rs = rhs_seconds(sh);
    long max_rhs = 0, used = 0;
    if (budget > 0 && rs > 0) {
        const double left = fmax(budget - sh->work, 0.0) / rs;
        max_rhs = left > 1e15 ? (long)1e15 : (long)ceil(left) + 1;
    }
    gd_status st = gd_transient_monodromy_limited(sh->p->tr, 0.0, sh->p->T, y, &o, max_rhs, &used,
                                                  phi, yT, &err);
    sh->t_mono = (double)used * rs;
    sh->work += sh->t_mono;
    if (st && max_rhs > 0 && used >= max_rhs) {
        sh->budget_hit = 1;
        snprintf(sh->why, sizeof sh->why,
                 "shooting stopped at %.1f s (budget %.3g s, counted, --shoot-budget): %.180s",
                 sh->work, budget, err.message);
        return 1;
    }
    if (st) {
        snprintf(sh->why, sizeof sh->why, "monodromy failed: %.220s", err.message);
        return 1;
    }
    for (size_t k = 0; k < (size_t)sh->N * sh->N; k++)
        if (!isfinite(phi[k])) {
            snprintf(sh->why, sizeof sh->why, "the monodromy matrix is not finite");
            return 1;
        }
    return 0;
}

/* The state y after up to WARM_PERIODS periods of a transient from rest (or the static
 * state under the loads), one period at a time: it stops once a period changes the state
 * by less than 1e-3 (scaled as the Newton residual; Newton takes it from there), and
 * keeps the last change for the messages (a rattling train never settles). 0 ok. */
int gd_per_sh_warm(shoot *sh, double *y)
{
    memset(sh->yt, 0, (size_t)sh->N * sizeof *sh->yt);
    gd_per_sh_tolerances(sh, sh->yt); /* the orbit's size is not known yet */
    sh->warm_change = NAN;
    sh->warm_periods = 0;
    gd_transient_result *r = integrate(sh, NULL, sh->p->T, NULL, 0, NULL, 0);
    if (!r) return 1;
    sh->t_period = sh->last_work;
    from_dofs(sh, r, y);
    gd_transient_result_free(r);
    sh->warm_periods = 1;
    for (int k = 1; k < WARM_PERIODS; k++) {
        if (gd_per_sh_over_budget(sh, sh->t_period, "the warm-start transient")) break;
        gd_per_sh_tolerances(sh, y);
        if (gd_per_sh_period(sh, y, sh->yT)) return 1;
        for (int i = 0; i < sh->N; i++)
            sh->r[i] = sh->yT[i] - y[i];
        sh->warm_change = gd_per_sh_norm(sh, sh->yT, sh->r);
        memcpy(y, sh->yT, (size_t)sh->N * sizeof *y);
        sh->warm_periods = k + 1;
        if (sh->warm_change < 1e-3) break;
    }
    /* not settled: does an orbit attract it at all? (probe.c; a rattling train: none) */
    if (sh->warm_change >= 1e-3 && !sh->budget_hit &&
        gd_per_sh_probe(sh, y, sh->p->spec->nloads ? "the static state" : "rest"))
        return 1;
    return 0;
}

/* The residual below which a Newton that stalls has met the integrator's own noise: the
 * period map at the iterate y integrated again without the variational equations (another
 * step sequence) differs from the monodromy's by about the integration error; ten times
 * that, at least 1e4 rtol (contact events restart the integrator tens of times a period:
 * the backlash pair at rtol 1e-10 stalls between 1e-8 and 2e-7, the orbit then equal to
 * harmonic balance's within 1e-6), and never above 1e-5 (nor below the tolerance): a
 * strongly unstable orbit amplifies the difference itself (the Ducati train at 3000 rpm,
 * multipliers up to 1e27, gave a "noise" of order 1) and must not pass for converged.
 * F at y from the monodromy is in sh->racc (NULL: the fixed part only). */
#define NOISE_CAP 1e-5
double gd_per_sh_noise(shoot *sh, const double *y)
{
    double fl = fmin(1e4 * sh->rtol, NOISE_CAP);
    if (y && !gd_per_sh_period(sh, y, sh->ytmp)) {
        for (int i = 0; i < sh->N; i++)
            sh->ytmp[i] -= y[i] + sh->racc[i];
        fl = fmin(fmax(fl, 10.0 * gd_per_sh_norm(sh, y, sh->ytmp)), NOISE_CAP);
    }
    return fmax(sh->tol, fl);
}

/* ---------------------------------------------------------------- Newton-Krylov */

/* Matrix-free monodromy in scaled variables z = y / d (d the block scales of
 * scaled_norm): w = Phi z by a forward difference of the period map about y (py = P(y)),
 * the step sqrt(rtol) of the scales: the truncation error (h |P''|) and the integration
 * noise (rtol / h) balance at about sqrt(rtol) relative (3e-5 at rtol 1e-9). With
 * k->central a central difference over cbrt(rtol) (truncation h^2 |P'''|, the balance at
 * about rtol^(2/3)) for one more period: the multipliers' Arnoldi, whose forward-difference
 * bias moved the damped Mathieu pair's period doublings by 2.3e-6 and 4.1e-6 relative at
 * rtol 1e-10 (central: 5.3e-8, 7.9e-8). 0 ok. */
static int phi_vec(shoot *sh, kry *k, const double *z, double *w)
{
    const int N = sh->N;
    double nz = 0.0;
    for (int i = 0; i < N; i++)
        nz = fmax(nz, fabs(z[i]));
    if (nz == 0.0) {
        memset(w, 0, (size_t)N * sizeof *w);
        return 0;
    }
    const double h = (k->central ? cbrt(sh->rtol) : sqrt(sh->rtol)) / nz;
    for (int i = 0; i < N; i++)
        k->yt[i] = k->y[i] + h * k->d[i] * z[i];
    if (gd_per_sh_period(sh, k->yt, k->pt)) return 1;
    if (k->central) {
        for (int i = 0; i < N; i++)
            k->yt[i] = k->y[i] - h * k->d[i] * z[i];
        if (gd_per_sh_period(sh, k->yt, w)) return 1;
        for (int i = 0; i < N; i++)
            w[i] = (k->pt[i] - w[i]) / (2.0 * h * k->d[i]);
        return 0;
    }
    for (int i = 0; i < N; i++)
        w[i] = (k->pt[i] - k->py[i]) / (h * k->d[i]);
    return 0;
}

/* The operator of k on z (k->n entries): Phi z - shift z, and with a border (k->f) the
 * bordered matrix [Phi - shift I, f; row^T] of the arclength corrector. 0 ok. */
static int kry_apply(shoot *sh, kry *k, const double *z, double *w)
{
    const int N = sh->N;
    if (phi_vec(sh, k, z, w)) return 1;
    for (int i = 0; i < N; i++)
        w[i] -= k->shift * z[i];
    if (k->f) {
        double g = 0.0;
        for (int i = 0; i < N; i++) {
            w[i] += k->f[i] * z[N];
            g += k->row[i] * z[i];
        }
        w[N] = g + k->row[N] * z[N];
    }
    return 0;
}

void gd_per_sh_scales(const shoot *sh, const double *y, double *d)
{
    double yq, yv;
    block_size(sh, y, &yq, &yv);
    yq = fmax(yq, sh->atol_q / sh->rtol);
    yv = fmax(yv, sh->atol_v / sh->rtol);
    for (int i = 0; i < sh->N; i++)
        d[i] = i < sh->nf ? yq : yv;
}

/* kry_apply as linalg's operator (gmres.c) */
typedef struct kry_op {
    shoot *sh;
    kry *k;
} kry_op;

static int kry_product(void *data, const double *z, double *w)
{
    kry_op *o = data;
    return kry_apply(o->sh, o->k, z, w);
}

/* GMRES(KRYLOV_M) on the operator of k (k->n unknowns): A x = b, each cycle to tol |b| in
 * its least-squares residual, at most `cycles` cycles, restarts stopped once the true
 * residual's square is below stop2 |b|^2 (linalg/gmres.c). Used by Newton-Krylov and by
 * the arclength's bordered corrector and tangent (shooting_arclength.c). 0 ok, 1 an
 * integration failed or out of memory. */
int gd_per_sh_gmres(shoot *sh, kry *k, const double *b, double *x, double tol, double stop2,
                    int cycles)
{
    const int n = k->n, m = n < KRYLOV_M ? n : KRYLOV_M;
    kry_op o = {sh, k};
    const int rc = gd_gmres(kry_product, &o, n, m, b, x, tol, stop2, cycles);
    if (rc == 2) snprintf(sh->why, sizeof sh->why, "out of memory");
    return rc != 0;
}

/* Newton-Krylov on F(y) = P(y) - y: each step GMRES(KRYLOV_M) on (Phi - I) dy = -F in
 * scaled variables to 1e-3 of |F| (inexact Newton), at most three restarts, every product
 * one period integrated; the same line search and tolerances as the dense Newton. */
static int newton_krylov(shoot *sh, double *y, int *iters, double *resid)
{
    const int N = sh->N, maxit = sh->opt->max_iter;
    gd_per_sh_tolerances(sh, y);
    *iters = 0;
    double *d = malloc(4 * (size_t)N * sizeof *d);
    if (!d) {
        snprintf(sh->why, sizeof sh->why, "out of memory");
        return 1;
    }
    double *b = d + N, *py = b + N, *pt = py + N;
    int rc = 1;
    if (gd_per_sh_period(sh, y, py)) goto done;
    for (int i = 0; i < N; i++)
        sh->r[i] = py[i] - y[i];
    double res = gd_per_sh_norm(sh, y, sh->r);
    for (int it = 0;; it++) {
        *resid = res;
        if (res <= sh->tol) {
            rc = 0;
            break;
        }
        if (it >= maxit) {
            snprintf(sh->why, sizeof sh->why,
                     "shooting (Newton-Krylov): not converged in %d iterations (residual %.2g)",
                     maxit, res);
            break;
        }
        gd_per_sh_scales(sh, y, d);
        kry k = {.y = y, .py = py, .d = d, .yt = sh->yt, .pt = pt, .n = N, .shift = 1.0};
        for (int i = 0; i < N; i++)
            b[i] = -sh->r[i] / d[i];
        /* GMRES with restarts: the residual of the correction recomputed each cycle */
        if (gd_per_sh_gmres(sh, &k, b, sh->dy, 1e-3, 1e-6, 4)) goto done;
        for (int i = 0; i < N; i++)
            sh->dy[i] *= d[i];
        double alpha = 1.0, rt = INFINITY;
        for (int ls = 0; ls < 7; ls++, alpha *= 0.5) {
            for (int i = 0; i < N; i++)
                sh->yt[i] = y[i] + alpha * sh->dy[i];
            if (gd_per_sh_period(sh, sh->yt, pt)) goto done;
            for (int i = 0; i < N; i++)
                sh->yT[i] = pt[i] - sh->yt[i];
            rt = gd_per_sh_norm(sh, sh->yt, sh->yT);
            if (rt < res) break;
        }
        *iters = it + 1;
        if (!(rt < res)) {
            if (res <= gd_per_sh_noise(sh, NULL)) {
                rc = 0;
                break;
            }
            snprintf(sh->why, sizeof sh->why,
                     "shooting (Newton-Krylov): stalls at residual %.2g (tolerance %.2g)", res,
                     sh->tol);
            break;
        }
        memcpy(y, sh->yt, (size_t)N * sizeof *y);
        memcpy(py, pt, (size_t)N * sizeof *py);
        memcpy(sh->r, sh->yT, (size_t)N * sizeof *sh->r);
        res = rt;
    }
done:
    free(d);
    return rc;
}

/* Arnoldi steps for a stability verdict the first KRYLOV_M Ritz values leave open: up to
 * every state when there are at most this many (2 N periods integrated). */
#define KRYLOV_FULL 400

/* The largest Floquet multipliers of the orbit through y without the dense monodromy: the
 * Ritz values of m Arnoldi steps on Phi (monodromy-vector products by central
 * differences, two periods each) from a fixed start vector; the outer ones, which decide
 * stability, converge first. With res (m entries) also each one's residual (gd_ritz, which
 * solves for the eigenvectors too: its values, equal to rounding, in vre, vim), the
 * reported ones staying those of dgeev without vectors as before. Their count, or -1 when
 * an integration failed. */
static int krylov_multipliers(shoot *sh, const double *y, int m, double *mre, double *mim,
                              double *vre, double *vim, double *res)
{
    const int N = sh->N;
    double *V = malloc(((size_t)N * (m + 1) + (size_t)(m + 1) * m + 4 * (size_t)N + (size_t)m * m) *
                       sizeof *V);
    if (!V) return -1;
    double *H = V + (size_t)N * (m + 1), *d = H + (size_t)(m + 1) * m, *py = d + N, *pt = py + N,
           *v0 = pt + N, *Hs = v0 + N;
    int n = -1, steps = 0;
    gd_per_sh_tolerances(sh, y);
    gd_per_sh_scales(sh, y, d);
    if (!gd_per_sh_period(sh, y, py)) {
        kry k = {
            .y = y, .py = py, .d = d, .yt = sh->yt, .pt = pt, .n = N, .shift = 0.0, .central = 1};
        for (int i = 0; i < N; i++) /* every state excited, none by symmetry left out */
            v0[i] = 1.0 + 0.5 * sin(1.0 + i);
        kry_op o = {sh, &k};
        if (!gd_arnoldi(kry_product, &o, N, v0, m, V, H, &steps, 0.0, NULL) && steps > 0) {
            for (int c = 0; c < steps; c++)
                for (int r = 0; r < steps; r++)
                    Hs[(size_t)c * steps + r] = H[(size_t)c * (m + 1) + r];
            double dummy[1];
            if (!LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', steps, Hs, steps, mre, mim, dummy, 1,
                               dummy, 1) &&
                (!res || !gd_ritz(H, m + 1, steps, vre, vim, res)))
                n = steps;
        }
    }
    free(V);
    return n;
}

/* Multipliers of the orbit through y: the eigenvalues of sh->phi (destroyed), or the
 * Krylov estimate of the largest. Their count, -1 on failure. */
int gd_per_sh_multipliers(shoot *sh, const double *y, double *mre, double *mim)
{
    if (!sh->dense) {
        const int m = sh->N < KRYLOV_M ? sh->N : KRYLOV_M;
        return krylov_multipliers(sh, y, m, mre, mim, NULL, NULL, NULL);
    }
    double dummy[1];
    return LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', sh->N, sh->phi, sh->N, mre, mim, dummy, 1,
                         dummy, 1)
               ? -1
               : sh->N;
}

/* The counted cost of m Arnoldi steps on central-difference products at y: P(y) and two
 * periods a product, (2 m + 1) periods of the last one's counted work (work.c). */
static double arnoldi_cost(const shoot *sh, int m)
{
    return (2.0 * m + 1.0) * sh->t_period;
}

/* 1 when m more Arnoldi steps fit the verdict's budget (spent: what its earlier steps
 * took): the point's multipliers within opt->floquet_budget and the point within
 * opt->shoot_budget (seconds of counted work, 0: no limit; never a clock, so the verdict
 * is the same every run). Else 0 and why (cap bytes) names the cost and the option. */
static int verdict_fits(const shoot *sh, int m, double spent, char *why, size_t cap)
{
    const double next = arnoldi_cost(sh, m), fb = sh->opt->floquet_budget,
                 sb = sh->opt->shoot_budget;
    if (!(sh->t_period > 0)) return 1; /* nothing integrated yet: nothing to predict from */
    if (fb > 0 && spent + next > fb) {
        snprintf(why, cap,
                 "%d Arnoldi steps need about %.2g s (counted) over the multipliers' "
                 "budget of %.3g s (--floquet-budget)",
                 m, spent + next, fb);
        return 0;
    }
    if (sb > 0 && sh->work + next > sb) {
        snprintf(why, cap,
                 "%d Arnoldi steps need about %.2g s more (counted) than the point's "
                 "budget of %.3g s leaves (--shoot-budget)",
                 m, next, sb);
        return 0;
    }
    return 1;
}

int gd_per_sh_verdict(shoot *sh, const double *y, double *mre, double *mim, int *stable, char *note,
                      size_t cap)
{
    const int N = sh->N;
    note[0] = '\0';
    *stable = -1;
    if (sh->dense) {
        int nm = gd_per_sh_multipliers(sh, y, mre, mim);
        if (nm > 0) {
            double m = 0.0;
            for (int i = 0; i < nm; i++)
                m = fmax(m, hypot(mre[i], mim[i]));
            *stable = m <= 1.0 + 1e-6;
        }
        return nm;
    }
    double *w = malloc(3 * (size_t)N * sizeof *w);
    if (!w) {
        snprintf(sh->why, sizeof sh->why, "out of memory");
        return -1;
    }
    double *vre = w + N, *vim = vre + N;
    int m = N < KRYLOV_M ? N : KRYLOV_M, nm = 0;
    double spent = 0.0;
    char over[200] = "";
    /* KRYLOV_M steps, then (the verdict open) once more to every state, each run only where
     * the counted budget holds it: a run stopped by it would discard its products */
    for (;;) {
        if (!verdict_fits(sh, m, spent, over, sizeof over)) break;
        const double w0 = sh->work;
        nm = krylov_multipliers(sh, y, m, mre, mim, vre, vim, w);
        spent += sh->work - w0;
        if (nm < 0) break;
        *stable = gd_ritz_verdict(vre, vim, w, nm, 1.0 + 1e-6);
        if (*stable >= 0 || m >= N || N > KRYLOV_FULL) break;
        m = N; /* the cluster needs the whole space: Arnoldi again to every state */
    }
    if (nm == 0 && over[0]) /* not even the first run fitted */
        snprintf(note, cap, "stability not determined: %s", over);
    else if (nm > 0) {
        int open = -1; /* the largest value whose residual straddles the circle */
        for (int j = 0; j < nm; j++) {
            double a = hypot(vre[j], vim[j]);
            if (a + w[j] > 1.0 + 1e-6 && (open < 0 || a > hypot(vre[open], vim[open]))) open = j;
        }
        if (*stable < 0 && open >= 0)
            snprintf(note, cap,
                     "stability not determined: %d Arnoldi steps leave the Ritz value "
                     "%.6g%+.4gi (|mu| %.6f) within its residual %.2g of the unit circle (%d "
                     "states; %s)",
                     nm, vre[open], vim[open], hypot(vre[open], vim[open]), w[open], N,
                     over[0] ? over : "--floquet reduced or a smaller model");
        else if (*stable < 0)
            snprintf(note, cap, "stability not determined: %d Arnoldi steps (%d states)", nm, N);
        else
            snprintf(note, cap,
                     "multipliers: the %d largest of %d, Ritz values of Arnoldi on "
                     "monodromy-vector products%s",
                     nm, N,
                     m > KRYLOV_M ? " (the first 40 left the verdict open: Arnoldi to every "
                                    "state)"
                                  : "");
    }
    free(w);
    return nm;
}

/* Before Newton from a start no transient led to (sh->t_period 0: the harmonic balance
 * orbit of a stability correction): one plain period prices the monodromy (the budget's
 * prediction, shooting.c) and measures how far the start is from an orbit; a start the
 * period map moves by more than PROBE_START (1 %) is probed (probe.c) from there, and a
 * response that is not periodic ends the correction at the cost of a probe, before any
 * monodromy (examples/gearbox_neutral_rattle.yaml: the first monodromy did not end in
 * 480349 right-hand sides). 0 go on from y (restored), 1 not (sh->why). */
#define PROBE_START 1e-2
static int start_check(shoot *sh, double *y)
{
    const int N = sh->N;
    if (gd_per_sh_period(sh, y, sh->yT)) return 1;
    for (int i = 0; i < N; i++)
        sh->r[i] = sh->yT[i] - y[i];
    const double r0 = gd_per_sh_norm(sh, y, sh->r);
    if (!(r0 > PROBE_START)) return 0;
    double *y1 = malloc((size_t)N * sizeof *y1);
    if (!y1) {
        snprintf(sh->why, sizeof sh->why, "out of memory");
        return 1;
    }
    memcpy(y1, sh->yT, (size_t)N * sizeof *y1);
    sh->warm_periods = 1;
    char from[48];
    snprintf(from, sizeof from, "the orbit (moved %.2g a period)", r0);
    const int rc = gd_per_sh_probe(sh, y1, from);
    free(y1);
    return rc != 0;
}

/* Newton on F(y) = P(y) - y from y (in place). On success sh->phi is the monodromy at y.
 * 0 converged; 1 not, with sh->why. */
int gd_per_sh_newton(shoot *sh, double *y, int *iters, double *resid)
{
    if (!sh->dense) return newton_krylov(sh, y, iters, resid);
    const int N = sh->N, maxit = sh->opt->max_iter;
    gd_per_sh_tolerances(sh, y);
    *iters = 0;
    /* a start from elsewhere (a harmonic balance orbit to correct): nothing integrated yet
     * to price the monodromy by, and maybe no orbit near it (a rattling train) */
    if (!(sh->t_period > 0) && start_check(sh, y)) return 1;
    if (gd_per_sh_monodromy(sh, y, sh->phi, sh->yT)) return 1;
    for (int i = 0; i < N; i++)
        sh->r[i] = sh->yT[i] - y[i];
    double res = gd_per_sh_norm(sh, y, sh->r);
    memcpy(sh->racc, sh->r, (size_t)N * sizeof *sh->racc);
    int slow = 0;
    for (int it = 0;; it++) {
        *resid = res;
        if (res <= sh->tol) return 0;
        if (it >= maxit) {
            snprintf(sh->why, sizeof sh->why,
                     "shooting: Newton did not converge in %d iterations (residual %.2g, "
                     "tolerance %.2g)",
                     maxit, res, sh->tol);
            return 1;
        }
        /* (Phi - I) dy = -F */
        memcpy(sh->A, sh->phi, (size_t)N * N * sizeof *sh->A);
        for (int i = 0; i < N; i++) {
            sh->A[(size_t)i * N + i] -= 1.0;
            sh->dy[i] = -sh->r[i];
        }
        if (LAPACKE_dgesv(LAPACK_COL_MAJOR, N, 1, sh->A, N, sh->ipiv, sh->dy, N)) {
            snprintf(sh->why, sizeof sh->why,
                     "shooting: Phi - I is singular (a multiplier at +1: a fold or a free "
                     "rigid-body motion)");
            return 1;
        }
        /* full step with the monodromy there; backtracking by plain periods if |F| grows */
        double alpha = 1.0, rt = INFINITY;
        for (int i = 0; i < N; i++)
            sh->yt[i] = y[i] + sh->dy[i];
        if (gd_per_sh_monodromy(sh, sh->yt, sh->A, sh->yT)) return 1;
        for (int i = 0; i < N; i++)
            sh->r[i] = sh->yT[i] - sh->yt[i];
        rt = gd_per_sh_norm(sh, sh->yt, sh->r);
        int full = rt < res;
        while (!full && alpha > 1.0 / 64) {
            alpha *= 0.5;
            for (int i = 0; i < N; i++)
                sh->yt[i] = y[i] + alpha * sh->dy[i];
            if (gd_per_sh_period(sh, sh->yt, sh->yT)) return 1;
            for (int i = 0; i < N; i++)
                sh->r[i] = sh->yT[i] - sh->yt[i];
            rt = gd_per_sh_norm(sh, sh->yt, sh->r);
            if (rt < res) break;
        }
        *iters = it + 1;
        if (!(rt < res) && res <= gd_per_sh_noise(sh, y)) return 0;
        if (!(rt < res)) {
            snprintf(sh->why, sizeof sh->why,
                     "shooting: Newton stalls at residual %.2g (tolerance %.2g): no isolated "
                     "periodic orbit near the start",
                     res, sh->tol);
            return 1;
        }
        memcpy(y, sh->yt, (size_t)N * sizeof *y);
        if (full) {
            double *t = sh->phi;
            sh->phi = sh->A;
            sh->A = t;
        } else if (gd_per_sh_monodromy(sh, y, sh->phi, sh->yT)) {
            return 1;
        } else {
            for (int i = 0; i < N; i++)
                sh->r[i] = sh->yT[i] - y[i];
            rt = gd_per_sh_norm(sh, y, sh->r);
        }
        memcpy(sh->racc, sh->r, (size_t)N * sizeof *sh->racc);
        /* a residual that no longer falls is a stall (a chattering orbit): stop early
         * instead of spending the iterations */
        slow = rt > 0.5 * res ? slow + 1 : 0;
        res = rt;
        if (slow >= 4 && res > sh->tol) {
            if (res <= gd_per_sh_noise(sh, y)) return 0;
            *resid = res;
            snprintf(sh->why, sizeof sh->why,
                     "shooting: Newton stalls at residual %.2g (tolerance %.2g) after %d "
                     "iterations: no isolated periodic orbit near the start",
                     res, sh->tol, it + 1);
            return 1;
        }
    }
}

/* ---------------------------------------------------------------- points */

static gd_periodic_point *new_point(shoot *sh, double key)
{
    gd_periodic_point *p = gd_per_point_new(sh->res, &sh->cap_points, sh->dir, GD_PER_SHOOTING);
    if (!p) return NULL;
    p->speed = sh->param ? sh->param->speed : key;
    p->parameter = sh->param ? key : NAN;
    p->harmonics = sh->p->H;
    return p;
}

static void announce(shoot *sh, double key)
{
    if (!sh->opt->on_point) return;
    double f = sh->v1 != sh->v0 ? (key - sh->v0) / (sh->v1 - sh->v0) : 1.0;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    sh->opt->on_point(&sh->res->points[sh->res->npoints - 1], sh->res->npoints - 1,
                      ((sh->dir < 0 ? 1 : 0) + f) / sh->ndir, sh->opt->user);
}

/* The point at the converged state y: records and coefficients from one integrated period
 * sampled at Nr times, multipliers from sh->phi. 0 ok, 1 out of memory. */
int gd_per_sh_emit(shoot *sh, double key, const double *y, int iters, double resid)
{
    const int nf = sh->nf, H = sh->p->H, Nr = sh->p->Nr, nr = sh->nrec;
    gd_periodic_point *p = new_point(sh, key);
    if (!p) return 1;
    double *ts = malloc((size_t)Nr * sizeof *ts);
    if (!ts) return 1;
    for (int j = 0; j < Nr; j++)
        ts[j] = sh->p->T * j / Nr;
    gd_transient_result *r = integrate(sh, y, sh->p->T, ts, Nr, sh->rec, nr);
    free(ts);
    if (!r || r->nsamples != Nr) {
        gd_transient_result_free(r);
        p->converged = 0;
        snprintf(p->reason, sizeof p->reason, "%.250s", sh->why);
        announce(sh, key);
        return 0;
    }
    p->converged = 1;
    p->omega = sh->p->w;
    p->residual = resid;
    p->iterations = iters;
    p->nfree = nf;
    const size_t nh = 2 * (size_t)H + 1;
    p->coef = calloc(nh * nf, sizeof *p->coef);
    p->records = calloc((size_t)(nr > 0 ? nr : 1), sizeof *p->records);
    double *buf = fftw_malloc((size_t)Nr * sizeof *buf),
           *out = fftw_malloc((size_t)Nr * sizeof *out);
    int rc = 1;
    if (!p->coef || !p->records || !buf || !out) goto done;
    fftw_plan plan = fftw_plan_r2r_1d(Nr, buf, out, FFTW_R2HC, FFTW_ESTIMATE);
    for (int k = 0; k < nr; k++)
        if (gd_per_sample_stats(&r->sample_values[(size_t)k * Nr], Nr, H, plan, buf, out,
                                &p->records[k])) {
            fftw_destroy_plan(plan);
            goto done;
        }
    /* Fourier coefficients of the free DOFs (coef[h * nf + i], as harmonic balance) */
    for (int i = 0; i < nf; i++) {
        int d = sh->free_dof[i];
        for (int j = 0; j < Nr; j++)
            buf[j] = r->sample_q[(size_t)j * r->ndof + d];
        fftw_execute(plan);
        p->coef[i] = out[0] / Nr;
        for (int k = 1; k <= H && k < Nr / 2; k++) {
            p->coef[(size_t)(2 * k - 1) * nf + i] = 2.0 * out[k] / Nr;
            p->coef[(size_t)(2 * k) * nf + i] = -2.0 * out[Nr - k] / Nr;
        }
    }
    fftw_destroy_plan(plan);
    if (sh->opt->stability) {
        p->mu_re = malloc((size_t)sh->N * sizeof *p->mu_re);
        p->mu_im = malloc((size_t)sh->N * sizeof *p->mu_im);
        if (!p->mu_re || !p->mu_im) goto done;
        int stable,
            nm = gd_per_sh_verdict(sh, y, p->mu_re, p->mu_im, &stable, p->reason, sizeof p->reason);
        if (nm < 0) {
            snprintf(p->reason, sizeof p->reason, "stability not computed: %.200s",
                     sh->dense ? "dgeev failed" : sh->why);
        } else if (stable >= 0) {
            double m = 0.0;
            for (int i = 0; i < nm; i++)
                m = fmax(m, hypot(p->mu_re[i], p->mu_im[i]));
            p->mu_max = m;
            p->stable = stable;
            p->stability_method = GD_PER_SHOOTING;
            p->nmult = nm;
        }
    }
    rc = 0;
done:
    fftw_free(buf);
    fftw_free(out);
    gd_transient_result_free(r);
    if (!rc) announce(sh, key);
    return rc;
}

int gd_per_sh_fail(shoot *sh, double key)
{
    gd_periodic_point *p = new_point(sh, key);
    if (!p) return 1;
    snprintf(p->reason, sizeof p->reason, "%.250s", sh->why);
    announce(sh, key);
    return 0;
}

/* ---------------------------------------------------------------- bifurcations */

int gd_per_sh_add_bif(shoot *sh, gd_bifurcation_type type, double key, double mre, double mim)
{
    gd_periodic_result *r = sh->res;
    if (r->nbifurcations == sh->cap_bif) {
        int cap = sh->cap_bif ? 2 * sh->cap_bif : 16;
        gd_bifurcation *b = realloc(r->bifurcations, (size_t)cap * sizeof *b);
        if (!b) return 1;
        r->bifurcations = b;
        sh->cap_bif = cap;
    }
    gd_bifurcation *b = &r->bifurcations[r->nbifurcations++];
    b->type = type;
    b->speed = sh->param ? sh->param->speed : key;
    b->parameter = sh->param ? key : NAN;
    b->direction = sh->dir;
    b->mu_re = mre;
    b->mu_im = mim;
    return 0;
}

/* The largest |mu| of each kind: 0 real positive, 1 real negative, 2 complex. */
void gd_per_sh_kinds(const double *re, const double *im, int n, double g[3], int at[3])
{
    for (int k = 0; k < 3; k++) {
        g[k] = 0.0;
        at[k] = -1;
    }
    for (int i = 0; i < n; i++) {
        int k = fabs(im[i]) > 1e-9 * fmax(1.0, fabs(re[i])) ? 2 : re[i] >= 0 ? 0 : 1;
        double a = hypot(re[i], im[i]);
        if (a > g[k]) {
            g[k] = a;
            at[k] = i;
        }
    }
}

void gd_per_sh_free(shoot *sh)
{
    release_slot(&sh->slot[0]);
    release_slot(&sh->slot[1]);
    free(sh->mem);
    free(sh->ipiv);
    free(sh->q0);
    free(sh->free_dof);
}

/* ---- the periodicity probe ---- (in this file: it and shooting's start call each other) */
/* Does a periodic orbit attract the transient at the period T? A Poincare probe (issue 33:
 * "every point converged or explained"). An idling gear in rattle often has no periodic
 * orbit at all: its transient never settles, and Newton on the period map from its state
 * then spends monodromy matrices (minutes each through the impacts) on an orbit that is
 * not there. So when a transient has not settled it is carried on over PROBE_PERIODS
 * more periods, and its once-per-period states y_k (the section) are compared with the
 * states p = 1 .. PROBE_PMAX periods earlier, component by component against the
 * section's own spread (as `geardyn transient --periods` compares its Poincare points with
 * each record's range):
 *
 *   d_p(k) = max_i |y_k,i - y_k-p,i| / s_i,   s_i = max_k y_k,i - min_k y_k,i
 *
 * (s_i at least 1e-3 of its block's size: a component that does not move is not
 * compared). A periodic attractor of period p T makes d_p fall towards 0 while the spread
 * keeps the early transient; a motion that no orbit attracts keeps every d_p of order 1.
 * The verdict asks for both: the smallest d_p over the last half above PROBE_FLOOR for
 * every p, and neither decay nor growth (d_1's mean over the last quarter within a factor
 * 2 of its mean over the first: a growing transient leaves an unstable orbit, which
 * Newton finds, as in the parametric resonance of a damped Mathieu pair). Anything else goes on to
 * Newton from the same start as before. The block norm of Newton's residual would not do: on
 * examples/manual_5speed.yaml the driveline's wind-up sets the scale and the idlers' rattle moves
 * the state by 0.004-0.12 of it a period, below any floor. Counted, never timed: the same states
 * and verdict on every run. */

/* periods of the probe (about one dense monodromy of a 12-state train, 0.7 (2 N + 1)
 * periods, where the rattle's impacts do not make the monodromy dearer still) */
#define PROBE_PERIODS 24
/* periods compared (period-1 .. period-8 orbits) */
#define PROBE_PMAX 8
/* a return within this fraction of the section's spread in every component */
#define PROBE_FLOOR 5e-2

/* d_p(k) over the section Y with the spreads s */
static double dist(const shoot *sh, const double *Y, const double *s, int k, int p)
{
    const int N = sh->N;
    double d = 0.0;
    for (int i = 0; i < N; i++)
        d = fmax(d, fabs(Y[(size_t)k * N + i] - Y[(size_t)(k - p) * N + i]) / s[i]);
    return d;
}

static double mean_d1(const shoot *sh, const double *Y, const double *s, int a, int b)
{
    double m = 0.0;
    for (int k = a; k < b; k++)
        m += dist(sh, Y, s, k, 1);
    return b > a ? m / (b - a) : NAN;
}

int gd_per_sh_probe(shoot *sh, double *y, const char *from)
{
    const int N = sh->N, n = PROBE_PERIODS;
    /* rattle needs contact: a smooth or time-varying linear train settles, if slowly (the
     * damped Mathieu pair below its parametric resonance turns a complex pair of |mu| near
     * 1, and 24 of its periods neither decay nor return) */
    if (gd_transient_nswitches(sh->p->tr) == 0) return 0;
    double *Y = malloc(((size_t)(n + 1) * N + 2 * (size_t)N) * sizeof *Y);
    if (!Y) {
        snprintf(sh->why, sizeof sh->why, "out of memory");
        return -1;
    }
    double *s = Y + (size_t)(n + 1) * N, *lo = s + N;
    memcpy(Y, y, (size_t)N * sizeof *Y);
    int k, rc = 0;
    for (k = 1; k <= n; k++) {
        if (sh->t_period > 0 && gd_per_sh_over_budget(sh, sh->t_period, "the periodicity probe"))
            break;
        gd_per_sh_tolerances(sh, Y + (size_t)(k - 1) * N);
        if (gd_per_sh_period(sh, Y + (size_t)(k - 1) * N, Y + (size_t)k * N)) {
            rc = -1;
            goto done;
        }
    }
    k--;                  /* the last state integrated */
    if (k < n) goto done; /* the budget cut it: no verdict from a short probe */
    gd_per_sh_scales(sh, Y + (size_t)n * N, lo); /* the block sizes: the spreads' floor */
    for (int i = 0; i < N; i++) {
        double a = INFINITY, b = -INFINITY;
        for (int j = 0; j <= n; j++) {
            a = fmin(a, Y[(size_t)j * N + i]);
            b = fmax(b, Y[(size_t)j * N + i]);
        }
        s[i] = fmax(b - a, 1e-3 * lo[i]);
    }
    double dmin = INFINITY, d1lo = INFINITY, d1hi = 0.0;
    for (int p = 1; p <= PROBE_PMAX; p++)
        for (int j = n / 2; j <= n; j++) {
            const double d = dist(sh, Y, s, j, p);
            dmin = fmin(dmin, d);
            if (p == 1) {
                d1lo = fmin(d1lo, d);
                d1hi = fmax(d1hi, d);
            }
        }
    const double first = mean_d1(sh, Y, s, 1, 1 + n / 4),
                 last = mean_d1(sh, Y, s, n + 1 - n / 4, n + 1);
    /* no verdict: Newton goes on from the start as before (the probe's states are not the
     * better start: on a period-2 attractor the last one lies on it, not near the
     * unstable period-1 orbit Newton is after) */
    if (dmin > PROBE_FLOOR && last >= 0.5 * first && last <= 2.0 * first) {
        memcpy(y, Y + (size_t)n * N, (size_t)N * sizeof *y);
        sh->warm_periods += n;
        /* the evidence first: auto's hand-over keeps the first 110 characters */
        snprintf(sh->why, sizeof sh->why,
                 "no periodic orbit attracts the transient at T = %.4g s: %d periods after %d "
                 "from %.40s, none returns within %.2g of the spread (1-%d T; per period "
                 "%.2g-%.2g, neither decaying nor growing): rattle?",
                 sh->p->T, n, sh->warm_periods - n, from, dmin, PROBE_PMAX, d1lo, d1hi);
        sh->not_periodic = 1;
        rc = 1;
    }
done:
    free(Y);
    return rc;
}
