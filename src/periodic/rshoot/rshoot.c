/* Reduced shooting, a row of the method table (method.h; docs/periodic.md, "Reduced
 * shooting"): for a model whose laws are linear in the state at fixed time (gear meshes
 * without backlash, their TVMS and STE; loads constant in time), each point is a linear
 * time-periodic problem about its static state, and one Magnus sweep in the reduced basis
 * gives the monodromy Phi and the forced response p; the orbit starts at (I - Phi)^-1 p
 * (gd_hb_orbit_reduced_out, floquet/floquet_reduced.c). No harmonic truncation: the
 * orbit is exact in time to the steps, so a point is solved at S and 2 S steps and the
 * change of its records is its error column; the finer run is reported.
 *
 * Continuation: natural (driver/sequential.c) always. The problem is linear, so each value
 * is one direct solve, independent of its neighbours, and there is no fold to follow; the
 * arclength is not run (the run's note says so). Bifurcations: none located (a multiplier
 * through the unit circle shows as the points' verdicts changing). */
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/law_type.h"
#include "geardyn/transient_model.h"
#include "periodic/method.h"
#include "periodic/periodic_impl.h"

#define TWO_PI 6.28318530717958647692
/* The settings measured on [JMSTHelical] at 100-1000 rpm (docs/periodic.md, "Reduced
 * shooting at low speed"): the modes up to 30 kHz (20 kHz left mesh 2 at 600 rpm 1.3 %
 * high; 45 kHz equal to 1e-4), a Magnus step of 17 us at most (its coupling of the kept
 * modes converges there), the records on a grid of 2.5 us at most (the sharp peaks of
 * the forces) and 2^18 points at most. */
#define RS_CUTOFF_HZ 30e3
#define RS_STEP_S 17e-6
#define RS_GRID_S 2.5e-6
#define RS_GRID_MAX (1 << 18)

typedef struct rs {
    const gd_system *sys0;
    const gd_transient_spec *spec0;
    const gd_periodic_param *param;
    const gd_periodic_options *opt;
    const gd_tr_record *rec;
    int nrec;
    gd_periodic_result *res;
    int cap_points;
    /* the problem at the current value */
    gd_model *m;
    gd_system *s;
    gd_transient_model *tm;
    gd_transient *tr;
    hb h;
    int nf;
    double key, speed, w, wexc;
    int order, H;
    /* the solution at the current value (solve), emitted by emit */
    int solved, S, grid, nbasis;
    double *mean[2], *p2p[2];
    gd_orbit_samples x[2];
    int failed; /* this point's solve failed: no second start (it would be the same) */
    int dir, ndir;
    double v0, v1;
    char why[256];
} rs;

static void drop_solution(rs *c)
{
    for (int i = 0; i < 2; i++) {
        free(c->x[i].values);
        free(c->x[i].mu);
        c->x[i].values = c->x[i].mu = NULL;
        free(c->mean[i]); /* p2p[i] points into it */
        c->mean[i] = c->p2p[i] = NULL;
    }
    c->solved = 0;
}

static void drop_problem(rs *c)
{
    gd_transient_free(c->tr);
    c->tr = NULL;
    gd_transient_model_free(c->tm);
    gd_system_free(c->s);
    gd_model_free(c->m);
    c->tm = NULL;
    c->s = NULL;
    c->m = NULL;
}

/* 1 (msg) when a law of the problem is not linear in the state at fixed time or the
 * forces at rest change over the period T: the orbit is linearised about a static state
 * under constant loads (gd_hb_orbit_reduced). */
static int refusal(const gd_system *sys, const gd_transient_spec *spec, double speed, double T,
                   char *msg, size_t cap)
{
    if (spec->ncams > 0) {
        snprintf(msg, cap, "a cam torque (a lift law of the cam angle) is not linear in the state");
        return 1;
    }
    gd_law *laws = NULL;
    int nlaws = 0, bad = -1;
    gd_error e;
    if (gd_transient_spec_laws(sys, spec, speed, &laws, &nlaws, &e)) {
        snprintf(msg, cap, "%.200s", e.message);
        return 1;
    }
    for (int i = 0; i < nlaws && bad < 0; i++) {
        const unsigned f = gd_law_flags(&laws[i]);
        const int ok = (f & (GD_LAW_LINEAR | GD_LAW_TIME_ONLY)) ||
                       (laws[i].type == &gd_law_backlash_mesh && gd_law_nswitches(&laws[i]) == 0);
        if (!ok) bad = i;
    }
    if (bad >= 0) {
        const gd_law *l = &laws[bad];
        snprintf(msg, cap, "law '%.48s' (%.40s) is not linear in the state at fixed time (%s)",
                 l->name, l->type->name,
                 gd_law_nswitches(l) > 0              ? "a switch: backlash or contact"
                 : !(gd_law_flags(l) & GD_LAW_SMOOTH) ? "a kink"
                                                      : "a nonlinear force");
    }
    free(laws);
    if (bad >= 0) return 1;
    /* the forces at rest (loads, unbalances, prescribed couplings) constant over T */
    gd_transient *tr = NULL;
    if (gd_transient_new(sys, spec, speed, &tr, &e)) {
        snprintf(msg, cap, "%.200s", e.message);
        return 1;
    }
    const int nf = gd_transient_nstates(tr) / 2;
    double *y = calloc(2 * (size_t)nf + 1, sizeof *y), *f0 = malloc(((size_t)nf + 1) * sizeof *f0),
           *f = malloc(((size_t)nf + 1) * sizeof *f), big = 0.0, dif = 0.0;
    int rc = 0;
    if (!y || !f0 || !f) {
        snprintf(msg, cap, "out of memory");
        rc = 1;
    }
    if (!rc && gd_transient_terms(tr, NULL) < 0) {
        snprintf(msg, cap, "a law has no local form (cams with include_acceleration)");
        rc = 1;
    }
    if (!rc) {
        gd_transient_local(tr, 0.0, y, f0, NULL, NULL);
        for (int i = 0; i < nf; i++)
            big = fmax(big, fabs(f0[i]));
        for (int k = 1; k < 8; k++) {
            gd_transient_local(tr, T * k / 8.0 * 0.987, y, f, NULL, NULL);
            for (int i = 0; i < nf; i++)
                dif = fmax(dif, fabs(f[i] - f0[i]));
        }
        if (dif > 1e-9 * big) {
            snprintf(msg, cap,
                     "the forces at rest change over the period (%.3g of %.3g: an unbalance, a "
                     "time-varying load or a prescribed motion); the orbit is linearised about "
                     "a static state under constant loads",
                     dif, big);
            rc = 1;
        }
    }
    free(y);
    free(f0);
    free(f);
    gd_transient_free(tr);
    return rc;
}

int gd_per_rs_refusal(const gd_system *sys, const gd_transient_spec *spec, double speed,
                      const gd_periodic_options *opt, char *msg, size_t cap)
{
    double w0 = 0.0;
    int order = 0;
    gd_error e;
    if (gd_periodic_fundamental(sys, spec, speed, &w0, &order, &e)) {
        snprintf(msg, cap, "%.200s", e.message);
        return 1;
    }
    return refusal(sys, spec, speed, TWO_PI * opt->subharmonic / w0, msg, cap);
}

/* ---------------------------------------------------------------- the row's operations */

static int op_size(void *m)
{
    (void)m;
    return 0; /* no unknowns carried from point to point: each is one direct solve */
}

static void op_step(void *m)
{
    ((rs *)m)->failed = 0;
}

static int op_prepare(void *mm, double v)
{
    rs *c = mm;
    drop_solution(c);
    drop_problem(c);
    const gd_system *sys = c->sys0;
    const gd_transient_spec *spec = c->spec0;
    gd_error err;
    c->key = v;
    c->speed = v;
    if (c->param) {
        const gd_periodic_param *p = c->param;
        if (p->rebuild(v, p->data, &c->m, &c->s, &c->tm, &err)) {
            snprintf(c->why, sizeof c->why, "%.40s = %.10g: %.160s", p->name ? p->name : "value", v,
                     err.message);
            return 1;
        }
        sys = c->s;
        spec = &c->tm->spec;
        c->speed = p->speed;
    }
    double w0;
    if (gd_periodic_fundamental(sys, spec, c->speed, &w0, &c->order, &err) ||
        gd_transient_new(sys, spec, c->speed, &c->tr, &err)) {
        snprintf(c->why, sizeof c->why, "%.250s", err.message);
        return 1;
    }
    c->w = w0 / c->opt->subharmonic;
    c->wexc = w0 * c->order;
    /* the harmonics reported: as harmonic balance and shooting report them */
    const long need = (long)c->order * c->opt->subharmonic;
    c->H = c->opt->harmonics;
    if (c->opt->adaptive && need > c->H) c->H = need > 1 << 20 ? 1 << 20 : (int)need;
    const int nf = gd_transient_nstates(c->tr) / 2;
    if (c->nf != nf) {
        gd_hb_free(&c->h);
        c->nf = 0;
        if (gd_hb_init(&c->h, nf, 1, 4)) {
            snprintf(c->why, sizeof c->why, "out of memory (%d DOFs)", nf);
            return 1;
        }
        c->nf = nf;
    }
    if (c->param && refusal(c->s, spec, c->speed, TWO_PI / c->w, c->why, sizeof c->why)) return 1;
    return 0;
}

/* The least power of 2 at least x, within [lo, hi]. */
static int pow2_at_least(double x, int lo, int hi)
{
    int n = lo;
    while (n < x && n < hi)
        n *= 2;
    return n;
}

/* The point at the prepared value: the orbit at S and 2 S steps. 0 ok, 1 failed (why). */
static int solve(rs *c)
{
    drop_solution(c);
    const double T = TWO_PI / c->w;
    /* the basis: the modes up to RS_CUTOFF_HZ, or --floquet-cutoff times the highest
     * excitation frequency where given; the step shrinks with a higher cut-off */
    double wcut = TWO_PI * RS_CUTOFF_HZ;
    if (c->opt->floquet_cutoff > 0) wcut = c->opt->floquet_cutoff * c->wexc;
    const double dt = RS_STEP_S * TWO_PI * RS_CUTOFF_HZ / wcut;
    const int smax = GD_PERIODIC_MAX_SAMPLES / 2;
    int S = c->opt->monodromy_steps > 0 ? c->opt->monodromy_steps : pow2_at_least(T / dt, 1, smax);
    const int s0 = gd_floquet_reduced_first_steps((long)c->order * c->opt->subharmonic);
    if (c->opt->monodromy_steps <= 0 && S < s0) S = s0;
    if (S > smax) S = smax;
    int grid = pow2_at_least(T / RS_GRID_S, 1, RS_GRID_MAX);
    if (grid < 2 * S) grid = 2 * S;
    c->S = S;
    c->grid = grid;
    for (int i = 0; i < 2; i++) {
        c->mean[i] = calloc(2 * (size_t)c->nrec + 1, sizeof *c->mean[i]);
        if (!c->mean[i]) {
            snprintf(c->why, sizeof c->why, "out of memory");
            return 1;
        }
        c->p2p[i] = c->mean[i] + c->nrec;
    }
    char msg[160];
    for (int i = 0; i < 2; i++) {
        int nb = 0;
        const int rc =
            gd_hb_orbit_reduced_out(&c->h, c->tr, c->w, S << i, grid, wcut, c->rec, c->nrec,
                                    c->mean[i], c->p2p[i], &nb, NULL, &c->x[i], msg);
        if (rc) {
            snprintf(c->why, sizeof c->why, "reduced shooting at %d steps: %.160s", S << i,
                     rc == 1 ? "out of memory or a failed factorisation" : msg);
            return 1;
        }
        c->nbasis = nb;
    }
    c->solved = 1;
    return 0;
}

static int op_solve(void *m, double **y, double v, int *it, double *res)
{
    rs *c = m;
    (void)y;
    (void)v;
    *it = 1;
    *res = NAN;
    if (c->failed) return 1;
    if (solve(c)) {
        c->failed = 1;
        return 1;
    }
    return 0;
}

static int op_solve_at(void *m, double *y, double v, int *it, double *res)
{
    return op_solve(m, &y, v, it, res);
}

static int op_give_up(void *m)
{
    return ((rs *)m)->failed;
}

static int op_direction(void *m, int dir, double v0, double v1)
{
    rs *c = m;
    c->dir = dir;
    c->v0 = v0;
    c->v1 = v1;
    return 0;
}

static gd_periodic_point *new_point(rs *c)
{
    gd_periodic_point *p =
        gd_per_point_new(c->res, &c->cap_points, c->dir, GD_PER_REDUCED_SHOOTING);
    if (!p) return NULL;
    p->speed = c->param ? c->param->speed : c->key;
    p->parameter = c->param ? c->key : NAN;
    p->harmonics = c->H;
    return p;
}

static void announce(rs *c)
{
    if (!c->opt->on_point) return;
    double f = c->v1 != c->v0 ? (c->key - c->v0) / (c->v1 - c->v0) : 1.0;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    c->opt->on_point(&c->res->points[c->res->npoints - 1], c->res->npoints - 1,
                     ((c->dir < 0 ? 1 : 0) + f) / c->ndir, c->opt->user);
}

static int op_fail(void *m, double v)
{
    rs *c = m;
    c->key = v;
    gd_periodic_point *p = new_point(c);
    if (!p) return 1;
    snprintf(p->reason, sizeof p->reason, "%.250s", c->why);
    announce(c);
    return 0;
}

static double rel_change(double a, double b)
{
    return a == b ? 0.0 : fabs(b) > 0 ? fabs(a - b) / fabs(b) : INFINITY;
}

/* The point from the runs at S and 2 S: the finer one's records (their statistics and
 * harmonics by an FFT of the grid), its multipliers, and the change from S as the error
 * (relative, as harmonic balance's truncation estimate: per record the peak-to-peak's
 * and the largest harmonic amplitude's, the point's the largest over the records). */
static int op_emit(void *m, const double *y, double v, int it, double res)
{
    rs *c = m;
    (void)y;
    c->key = v;
    gd_periodic_point *p = new_point(c);
    if (!p) return 1;
    const int n = c->x[1].n, nr = c->nrec, H = c->H;
    p->converged = 1;
    p->omega = c->w;
    p->residual = res;
    p->iterations = it;
    p->records = calloc((size_t)(nr > 0 ? nr : 1), sizeof *p->records);
    gd_per_record_stats coarse = {0};
    double *buf = fftw_malloc((size_t)n * sizeof *buf), *out = fftw_malloc((size_t)n * sizeof *out);
    int rc = 1;
    if (!p->records || !buf || !out) goto done;
    fftw_plan plan = fftw_plan_r2r_1d(n, buf, out, FFTW_R2HC, FFTW_ESTIMATE);
    double ep = 0.0, ea = 0.0;
    for (int k = 0; k < nr; k++) {
        gd_per_record_stats *s = &p->records[k];
        if (gd_per_sample_stats(c->x[1].values + (size_t)k * n, n, H, plan, buf, out, s) ||
            gd_per_sample_stats(c->x[0].values + (size_t)k * n, n, H, plan, buf, out, &coarse)) {
            free(coarse.amplitude);
            free(coarse.phase_deg);
            fftw_destroy_plan(plan);
            goto done;
        }
        s->p2p_error = rel_change(coarse.peak_to_peak, s->peak_to_peak);
        double big = 0.0, d = 0.0;
        for (int h = 1; h <= H; h++) {
            big = fmax(big, s->amplitude[h]);
            d = fmax(d, fabs(coarse.amplitude[h] - s->amplitude[h]));
        }
        s->amp_error = big > 0 ? d / big : 0.0;
        ep = fmax(ep, s->p2p_error);
        ea = fmax(ea, s->amp_error);
        free(coarse.amplitude);
        free(coarse.phase_deg);
        coarse.amplitude = coarse.phase_deg = NULL;
    }
    fftw_destroy_plan(plan);
    p->harmonics_ref = c->S; /* the steps of the coarser run compared */
    p->harmonic_error_p2p = ep;
    p->harmonic_error_amp = ea;
    p->harmonic_ok = ep <= c->opt->harmonic_tol && ea <= c->opt->harmonic_tol;
    p->floquet_basis = c->nbasis;
    p->floquet_steps = 2 * c->S;
    int len = snprintf(p->reason, sizeof p->reason,
                       "reduced shooting: %d vectors, records on %d points; %d against %d Magnus "
                       "steps: peak-to-peak %.2g, amplitudes %.2g",
                       c->nbasis, n, c->S, 2 * c->S, ep, ea);
    if (!p->harmonic_ok && len > 0 && (size_t)len < sizeof p->reason)
        snprintf(p->reason + len, sizeof p->reason - (size_t)len, " (over --harmonic-tol %g)",
                 c->opt->harmonic_tol);
    if (c->opt->stability) {
        const int nm = c->x[1].nmu;
        p->mu_re = malloc(((size_t)nm + 1) * sizeof *p->mu_re);
        p->mu_im = malloc(((size_t)nm + 1) * sizeof *p->mu_im);
        if (!p->mu_re || !p->mu_im) goto done;
        memcpy(p->mu_re, c->x[1].mu, (size_t)nm * sizeof *p->mu_re);
        memcpy(p->mu_im, c->x[1].mu + nm, (size_t)nm * sizeof *p->mu_im);
        gd_hb_sort_multipliers(p->mu_re, p->mu_im, nm);
        double mx = 0.0;
        for (int i = 0; i < nm; i++)
            mx = fmax(mx, hypot(p->mu_re[i], p->mu_im[i]));
        p->nmult = nm;
        p->mu_max = mx;
        p->stable = mx <= 1.0 + 1e-6; /* as harmonic balance's verdict (points.c) */
        p->stability_method = GD_PER_REDUCED_SHOOTING;
    }
    rc = 0;
done:
    fftw_free(buf);
    fftw_free(out);
    drop_solution(c);
    if (!rc) announce(c);
    return rc;
}

const gd_per_arc_ops gd_per_rs_ops = {
    .size = op_size,
    .step = op_step,
    .begin = op_step,
    .prepare = op_prepare,
    .cold = op_solve,
    .cold_name = "the direct solve",
    .give_up = op_give_up,
    .solve_at = op_solve_at,
    .emit = op_emit,
    .fail = op_fail,
    .direction = op_direction,
    /* no arclength (start, correct, tangent, detect, rescale): the entry runs natural
     * continuation; no bifurcation search between points (between NULL) */
};

gd_status gd_per_rs_run(const gd_per_arc_ops *ops, const gd_system *sys,
                        const gd_transient_spec *spec, const gd_periodic_param *param,
                        const double *values, int nvalues, const gd_periodic_options *opt,
                        const gd_tr_record *records, int nrecords, gd_periodic_result *res,
                        gd_error *err)
{
    static const char *hint = "use --method hb, shooting or auto";
    if (param && param->load_frequency)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method", hint,
                            "reduced shooting takes constant loads only: a load whose frequency "
                            "is continued varies in time");
    rs c;
    memset(&c, 0, sizeof c);
    c.sys0 = sys;
    c.spec0 = spec;
    c.param = param;
    c.opt = opt;
    c.rec = records;
    c.nrec = nrecords;
    c.res = res;
    c.ndir = opt->both_directions ? 2 : 1;
    /* the laws at the first value: a located refusal before any point */
    if (op_prepare(&c, values[0])) {
        drop_problem(&c);
        gd_hb_free(&c.h);
        return gd_error_set(err, GD_EINPUT, "", 0, 0, param && param->name ? param->name : "speeds",
                            "", "%s", c.why);
    }
    char why[300];
    const int refused = refusal(c.param ? c.s : sys, c.param ? &c.tm->spec : spec, c.speed,
                                TWO_PI / c.w, why, sizeof why);
    drop_problem(&c);
    if (refused) {
        gd_hb_free(&c.h);
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method", hint,
                            "reduced shooting needs laws linear in the state at fixed time (gear "
                            "meshes without backlash, constant loads): %s",
                            why);
    }
    if (opt->method == GD_PER_ARCLENGTH)
        snprintf(res->method_note, sizeof res->method_note,
                 "reduced shooting, natural continuation: one direct solve per point (a linear "
                 "problem, no folds)");
    gd_per_arc a = {.ops = ops,
                    .m = &c,
                    .why = c.why,
                    .why_cap = sizeof c.why,
                    .speed = !param,
                    .max_steps = opt->max_steps};
    const int rc = gd_per_directions(&a, values, nvalues, opt->both_directions, 1);
    drop_solution(&c);
    drop_problem(&c);
    gd_hb_free(&c.h);
    if (rc) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    return GD_OK;
}
