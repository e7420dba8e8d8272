/* `--method auto` per value (issue 33 item 3; gd_per_run_per_value, periodic_impl.h): on a
 * model whose laws are linear in the state at fixed time, with --harmonics auto, each
 * value is solved by harmonic balance where its truncation estimate is within
 * --harmonic-tol by the pair (hc, hf) of gd_per_probe_harmonics (591 against 1183 on seed
 * 002), else by reduced shooting, which has no harmonic truncation. The choice at a value
 * comes from the points before, not from the first value for the whole curve (a 100-8000
 * rpm curve started at 100 rpm ran reduced shooting at every speed):
 *  - every value where harmonic balance ran leaves its estimate, carried to the pair
 *    (hc, hf): a point within the tolerance at H_c < hc scaled by (H_c / hc)^2, one that
 *    failed as it is;
 *  - the estimate at the next speed is extrapolated as v^-s from the measurement nearest
 *    in speed (on a sweep the last one; on the return run the outward run's at that
 *    speed): s from the last two where that is the last and both were within the
 *    tolerance (clamped to 1..3), else S_SPEED (the estimate at H = 591 on seed 002's
 *    0-deg curve falls as v^-1.96 from 100 to 2000 rpm); in a model parameter, that
 *    estimate as it is;
 *  - over the tolerance: reduced shooting at once (no harmonic balance solve); within it:
 *    harmonic balance from the least rung of the ladder the estimate allows, capped at hf,
 *    which confirms it (stalled below the pair, solved again at the pair); a point not
 *    within the tolerance at hf goes to reduced shooting (the one double solve, where the
 *    trend erred); the first value has no trend: harmonic balance at the pair.
 * Reduced shooting's own spectrum cut at hc was tried as the estimate on its points and
 * dropped: its peak-to-peak change (the sampled Gibbs overshoot at the stiffness steps)
 * stayed 0.04-0.11 at 2000-3000 rpm where harmonic balance's is 0.002-0.006.
 * Counts and estimates only, no clock: the same run decides the same way. Each point's
 * reason says which method solved it and why; the result's note counts them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

/* The estimate's fall with the speed, v^-S_SPEED, where the points do not give it, and the
 * bounds of the one they give (a resonance between two points bends it). */
#define S_SPEED 2.0
#define S_MIN 1.0
#define S_MAX 3.0
#define MAX_RUNGS 40

typedef struct {
    const gd_system *sys;
    const gd_transient_spec *spec;
    const gd_periodic_param *param;
    const gd_periodic_options *opt;
    gd_tr_record *rec; /* the caller's records, then every mesh force not among them */
    int nrec_user, nrec;
    int hc, hf;                 /* the deciding pair */
    int rung[MAX_RUNGS], nrung; /* the ladder order, 2 order + 1, ..., hc */
    /* every value harmonic balance ran at, its estimate at (hc, hf), within the tolerance
     * or not, in the order solved */
    int nhist, *hok;
    double *hv, *he;
    int near; /* the measurement the last prediction came from */
    gd_periodic_result *res;
    int cap_points;
    int n_hb, n_rs_trend, n_rs_after, hb_solves, n_failed;
} pv;

static void free_records(gd_per_record_stats *r, int from, int to)
{
    for (int k = from; k < to; k++) {
        free(r[k].amplitude);
        free(r[k].phase_deg);
        r[k].amplitude = r[k].phase_deg = NULL;
    }
}

/* The estimate at value v (NAN with none), from the measurement nearest in value (the
 * latest of equals: on a sweep the one before, on the return run the outward run's at the
 * same speed); c->near says which. */
static double predict(pv *c, double v)
{
    if (c->nhist == 0) return NAN;
    int n = c->nhist - 1;
    for (int i = c->nhist - 2; i >= 0; i--)
        if (fabs(c->hv[i] - v) < fabs(c->hv[n] - v)) n = i;
    c->near = n;
    if (c->param || !(c->hv[n] > 0) || !(v > 0)) return c->he[n];
    double s = S_SPEED;
    const int l = c->nhist - 1;
    if (n == l && l > 0 && c->hok[l] && c->hok[l - 1] && c->hv[l - 1] > 0 &&
        c->hv[l - 1] != c->hv[l]) {
        s = -(log(c->he[l]) - log(c->he[l - 1])) / (log(c->hv[l]) - log(c->hv[l - 1]));
        s = s < S_MIN ? S_MIN : s > S_MAX ? S_MAX : s;
    }
    return c->he[n] * pow(c->hv[n] / v, s);
}

/* (the arrays hold a measurement per value solved: nvalues x directions) */
static void remember(pv *c, double v, double e, int ok)
{
    if (!isfinite(e)) return;
    c->hv[c->nhist] = v;
    c->he[c->nhist] = fmax(e, 1e-12);
    c->hok[c->nhist++] = ok;
}

/* A harmonic balance point's estimate carried to the pair (hc, hf): within the tolerance
 * at H_c below hc, scaled by (H_c / hc)^S_SPEED (the same fall in H as in the speed: the
 * harmonics' frequency H w is what resolves the response); one that failed as it is (a
 * stalled series does not fall). */
static double at_pair(const pv *c, const gd_periodic_point *p)
{
    const double e = fmax(p->harmonic_error_p2p, p->harmonic_error_amp);
    const int h = p->harmonics_ref;
    return p->harmonic_ok == 1 && h > 0 && h < c->hc ? e * pow((double)h / c->hc, S_SPEED) : e;
}

/* The records the caller did not ask for dropped (their estimate kept out of the point's:
 * the largest over the caller's records, where there are any). */
static void strip(const pv *c, gd_periodic_point *p)
{
    if (!p->records || c->nrec == c->nrec_user) return;
    free_records(p->records, c->nrec_user, c->nrec);
    if (c->nrec_user == 0 || !p->converged) return;
    double ep = 0.0, ea = 0.0;
    for (int k = 0; k < c->nrec_user; k++) {
        ep = fmax(ep, p->records[k].p2p_error);
        ea = fmax(ea, p->records[k].amp_error);
    }
    if (isfinite(p->harmonic_error_p2p)) p->harmonic_error_p2p = ep;
    if (isfinite(p->harmonic_error_amp)) p->harmonic_error_amp = ea;
    if (p->harmonic_ok >= 0)
        p->harmonic_ok = ep <= c->opt->harmonic_tol && ea <= c->opt->harmonic_tol;
}

/* One value by method k alone: *r its one-point result (NULL on an input error: why). */
static gd_status solve_one(const pv *c, gd_per_kind k, int from, double v, gd_periodic_result **r,
                           char *why, size_t cap)
{
    gd_periodic_options o = *c->opt;
    o.kind = k;
    o.method = GD_PER_SEQUENTIAL; /* one value: linear in the state, no folds to follow */
    o.both_directions = 0;
    o.on_point = NULL;
    o.on_step = NULL;
    o.user = NULL;
    if (k == GD_PER_HB) {
        o.adaptive = 1;
        o.harmonics_from = from;
        o.max_harmonics = c->hf;
    } else {
        o.harmonics_from = 0;
    }
    gd_error e;
    gd_status st = gd_per_run_kind(c->sys, c->spec, c->param, &v, 1, &o, c->rec, c->nrec, r, &e);
    if (st == GD_ENOMEM) return st;
    if (st || (*r)->npoints < 1) {
        snprintf(why, cap, "%.200s", st ? e.message : "no point");
        gd_periodic_result_free(*r);
        *r = NULL;
    }
    return GD_OK;
}

/* The solves harmonic balance made: the rungs from `from` to the point's H. */
static int solves(const pv *c, int from, const gd_periodic_point *p)
{
    int n = 0;
    for (int i = 0; i < c->nrung; i++)
        if (c->rung[i] >= from && c->rung[i] <= p->harmonics) n++;
    return n + (p->harmonics > c->hc); /* hf */
}

/* Point src appended to the result (its arrays moved), direction dir, reason prefixed by
 * why. 0 ok, 1 out of memory. */
static int take(pv *c, gd_periodic_point *src, int dir, const char *why)
{
    strip(c, src);
    gd_periodic_point *p = gd_per_point_new(c->res, &c->cap_points, dir, src->method);
    if (!p) return 1;
    *p = *src;
    p->direction = dir;
    memset(src, 0, sizeof *src);
    char own[256], msg[640];
    snprintf(own, sizeof own, "%s", p->reason);
    snprintf(msg, sizeof msg, "%s%s%s", why, own[0] ? "; " : "", own);
    snprintf(p->reason, sizeof p->reason, "%.255s", msg);
    return 0;
}

/* The value v: its method, its point appended. 0 ok, 1 out of memory. */
static int value(pv *c, double v, int dir)
{
    const double tol = c->opt->harmonic_tol, pred = predict(c, v);
    char why[256], fail[224] = "", trend[96] = "the first value";
    gd_periodic_result *hbr = NULL, *rs = NULL;
    /* the first value at the pair itself (the ladder from the order stalls on the way at
     * 147 against 295 on seed 002 at 2500 rpm, estimate 0.33, where the pair's is 0.0071) */
    int from = c->hc;
    if (isfinite(pred)) { /* the least rung whose estimate, by (H / hc)^-S_SPEED, is within */
        for (int i = c->nrung - 1; i >= 0 && pred * pow((double)c->hc / c->rung[i], S_SPEED) <= tol;
             i--)
            from = c->rung[i];
        snprintf(trend, sizeof trend, "%.2g extrapolated from %.2g at %.6g", pred, c->he[c->near],
                 c->hv[c->near]);
    }
    if (isfinite(pred) && pred > tol) {
        c->n_rs_trend++;
        snprintf(why, sizeof why,
                 "reduced shooting: harmonic balance's estimate at H = %d (against %d) %s, "
                 "over %g",
                 c->hc, c->hf, trend, tol);
    } else {
        if (solve_one(c, GD_PER_HB, from, v, &hbr, fail, sizeof fail)) return 1;
        gd_periodic_point *p = hbr ? &hbr->points[0] : NULL;
        if (p && p->converged) c->hb_solves += solves(c, from, p);
        if (p && p->converged && p->harmonic_ok != 1 && p->harmonics_ref < c->hc) {
            /* stalled below the pair (the series need not fall steadily on the way):
             * the pair decides */
            gd_periodic_result_free(hbr);
            hbr = NULL;
            from = c->hc;
            if (solve_one(c, GD_PER_HB, from, v, &hbr, fail, sizeof fail)) return 1;
            p = hbr ? &hbr->points[0] : NULL;
            if (p && p->converged) c->hb_solves += solves(c, from, p);
        }
        if (p && p->converged && p->harmonic_ok == 1) {
            c->n_hb++;
            snprintf(why, sizeof why,
                     "harmonic balance: its estimate %.2g at H = %d against %d, within %g "
                     "(trend: %s)",
                     fmax(p->harmonic_error_p2p, p->harmonic_error_amp), p->harmonics_ref,
                     p->harmonics, tol, trend);
            remember(c, v, at_pair(c, p), 1);
            const int rc = take(c, p, dir, why);
            gd_periodic_result_free(hbr);
            return rc;
        }
        if (p && p->converged) {
            remember(c, v, at_pair(c, p), 0);
            snprintf(fail, sizeof fail, "estimate %.2g at H = %d against %d",
                     fmax(p->harmonic_error_p2p, p->harmonic_error_amp), p->harmonics_ref,
                     p->harmonics);
        } else if (p) {
            c->hb_solves++;
            snprintf(fail, sizeof fail, "%.200s", p->reason);
        }
        c->n_rs_after++;
        snprintf(why, sizeof why,
                 "reduced shooting: harmonic balance's %.120s, over %g (trend: %.60s)", fail, tol,
                 trend);
    }
    char rfail[224] = "";
    if (solve_one(c, GD_PER_REDUCED_SHOOTING, 0, v, &rs, rfail, sizeof rfail)) {
        gd_periodic_result_free(hbr);
        return 1;
    }
    gd_periodic_point *q = rs ? &rs->points[0] : NULL;
    int rc = 0;
    if (q && q->converged) {
        rc = take(c, q, dir, why);
    } else {
        /* reduced shooting failed: harmonic balance's point where it converged, else the
         * failure of both */
        gd_periodic_point *p = hbr ? &hbr->points[0] : NULL;
        c->n_failed++;
        if (!p) {
            if (solve_one(c, GD_PER_HB, from, v, &hbr, fail, sizeof fail)) {
                gd_periodic_result_free(rs);
                return 1;
            }
            p = hbr ? &hbr->points[0] : NULL;
        }
        char msg[400];
        snprintf(msg, sizeof msg, "reduced shooting failed (%.120s): harmonic balance's point",
                 q ? q->reason : rfail);
        if (p)
            rc = take(c, p, dir, msg);
        else if (q)
            rc = take(c, q, dir, "reduced shooting and harmonic balance failed");
        else {
            gd_periodic_point *f =
                gd_per_point_new(c->res, &c->cap_points, dir, GD_PER_REDUCED_SHOOTING);
            if (!f)
                rc = 1;
            else {
                f->speed = c->param ? c->param->speed : v;
                f->parameter = c->param ? v : NAN;
                snprintf(f->reason, sizeof f->reason, "%.120s; %.120s", rfail, fail);
            }
        }
    }
    if (hbr) gd_per_point_free(&hbr->points[0], hbr->nrecords);
    if (rs) gd_per_point_free(&rs->points[0], rs->nrecords);
    gd_periodic_result_free(hbr);
    gd_periodic_result_free(rs);
    return rc;
}

gd_status gd_per_run_per_value(const gd_system *sys, const gd_transient_spec *spec,
                               const gd_periodic_param *param, const double *values, int nvalues,
                               const gd_periodic_options *opt, const gd_tr_record *records,
                               int nrecords, const char *note, gd_periodic_result **out,
                               gd_error *err)
{
    *out = NULL;
    pv c;
    memset(&c, 0, sizeof c);
    c.sys = sys;
    c.spec = spec;
    c.param = param;
    c.opt = opt;
    c.nrec_user = nrecords;
    /* the excitations' order (the ladder's first rung) at the first value */
    int order = 1;
    {
        double w0;
        gd_error e;
        const double sp = param ? param->speed : values[0];
        if (!param && gd_periodic_fundamental(sys, spec, sp, &w0, &order, &e)) order = 1;
        if (param && !param->load_frequency) { /* the model at the first value */
            gd_model *m = NULL;
            gd_system *s = NULL;
            gd_transient_model *tm = NULL;
            if (!param->rebuild(values[0], param->data, &m, &s, &tm, &e)) {
                if (gd_periodic_fundamental(s, &tm->spec, sp, &w0, &order, &e)) order = 1;
                gd_transient_model_free(tm);
                gd_system_free(s);
                gd_model_free(m);
            }
        }
    }
    c.hf = gd_per_probe_harmonics(order, opt);
    c.hc = (c.hf - 1) / 2;
    {
        long h = (long)order * opt->subharmonic;
        if (h < 1) h = 1;
        for (; h < c.hc && c.nrung < MAX_RUNGS - 1; h = 2 * h + 1)
            c.rung[c.nrung++] = (int)h;
        c.rung[c.nrung++] = c.hc;
    }
    /* the records: the caller's, then every mesh force (with a stepping stiffness their
     * peak-to-peaks converge slowest in H) */
    const int nm = spec ? spec->nmeshes : 0;
    c.rec = calloc((size_t)nrecords + (size_t)nm + 1, sizeof *c.rec);
    c.res = calloc(1, sizeof *c.res);
    const size_t nh = 2 * (size_t)nvalues + 1;
    c.hv = malloc(nh * sizeof *c.hv);
    c.he = malloc(nh * sizeof *c.he);
    c.hok = malloc(nh * sizeof *c.hok);
    if (!c.rec || !c.res || !c.hv || !c.he || !c.hok) goto oom;
    if (nrecords) memcpy(c.rec, records, (size_t)nrecords * sizeof *records);
    c.nrec = nrecords;
    for (int k = 0; k < nm; k++) {
        int have = 0;
        for (int r = 0; r < nrecords; r++)
            have |= records[r].kind == GD_REC_MESH_FORCE && records[r].index == k &&
                    records[r].index2 == 0;
        if (!have) c.rec[c.nrec++] = (gd_tr_record){GD_REC_MESH_FORCE, k, 0};
    }
    c.res->nrecords = nrecords;
    const int ndir = opt->both_directions ? 2 : 1;
    for (int d = 0; d < ndir; d++)
        for (int i = 0; i < nvalues; i++) {
            const int j = d ? nvalues - 1 - i : i;
            if (value(&c, values[j], d ? -1 : 1)) goto oom;
            if (opt->on_point)
                opt->on_point(&c.res->points[c.res->npoints - 1], c.res->npoints - 1,
                              (d + (i + 1.0) / nvalues) / ndir, opt->user);
        }
    const int nrs = c.n_rs_trend + c.n_rs_after;
    c.res->method = nrs > c.n_hb ? GD_PER_REDUCED_SHOOTING : GD_PER_HB;
    char msg[600];
    snprintf(msg, sizeof msg,
             "%.200s: %d points by harmonic balance (%d solves), %d by reduced shooting (%d by "
             "the trend, %d after harmonic balance's estimate)%s",
             note, c.n_hb, c.hb_solves, nrs, c.n_rs_trend, c.n_rs_after,
             c.n_failed ? "; reduced shooting failed at some" : "");
    snprintf(c.res->method_note, sizeof c.res->method_note, "%.255s", msg);
    free(c.rec);
    free(c.hv);
    free(c.he);
    free(c.hok);
    *out = c.res;
    return GD_OK;
oom:
    free(c.rec);
    free(c.hv);
    free(c.he);
    free(c.hok);
    gd_periodic_result_free(c.res);
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
}
