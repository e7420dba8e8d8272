/* Continuation of the harmonic balance solution over speed or a model parameter:
 * pseudo-arclength (Keller 1977) with a bordered Newton corrector in scaled variables,
 * tangent from the bordered Jacobian, step control by the corrector's iteration count,
 * the requested values hit exactly by a fixed-parameter Newton at each crossing, adaptive
 * harmonic count, Floquet multipliers at every step and bifurcations located between
 * steps (fold: zero of the tangent's parameter component on the cubic Hermite arc; period
 * doubling, Neimark-Sacker, branch point: the critical multiplier's modulus through 1,
 * by secant iterations on points of the branch). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/periodic_impl.h"

#define TWO_PI 6.28318530717958647692

void gd_periodic_options_init(gd_periodic_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->harmonics = 10;
    opt->harmonic_tol = 1e-6;
    opt->max_harmonics = 80;
    opt->subharmonic = 1;
    opt->tol = 1e-10;
    opt->max_iter = 30;
    opt->stability = 1;
    opt->method = GD_PER_ARCLENGTH;
}

const char *gd_bifurcation_name(gd_bifurcation_type t)
{
    switch (t) {
    case GD_BIF_FOLD:
        return "fold";
    case GD_BIF_PERIOD_DOUBLING:
        return "period_doubling";
    case GD_BIF_NEIMARK_SACKER:
        return "neimark_sacker";
    default:
        return "branch_point";
    }
}

/* ---------------------------------------------------------------- problems per value */

typedef struct stage {
    int valid;
    long id; /* distinct for every problem made (factorisation reuse) */
    double key;
    gd_model *m;
    gd_system *s;
    gd_transient_model *tm;
    gd_transient *tr;
    double w; /* HB frequency */
    int bad;  /* the problem could not be made: reason in msg */
    char msg[320];
} stage;

typedef struct ctx {
    const gd_system *sys;
    const gd_transient_spec *spec;
    const gd_periodic_param *param;
    const gd_periodic_options *opt;
    stage st[2];
    int next;
    int nf;
    hb h;
    int H;
    double sx, sl; /* scales of X and of the parameter */
    double rate0;  /* w / lambda of the branch (speed continuation), or w (parameter) */
    int ratio_mode;
    char reason[320];
    char floquet_msg[200]; /* why the last Floquet multipliers were not computed */
    gd_periodic_result *res;
    int cap_points, cap_bif;
    const gd_tr_record *rec;
    int nrec;
    int dir;
    int steps;
    int near_fold; /* a fold on this step or the last: a real multiplier at +1 is it */
    long serial;   /* stages made */
} ctx;

static void stage_clear(stage *s)
{
    gd_transient_free(s->tr);
    if (s->m) { /* parameter stages own their model */
        gd_transient_model_free(s->tm);
        gd_system_free(s->s);
        gd_model_free(s->m);
    }
    memset(s, 0, sizeof *s);
}

static int make_stage(ctx *c, stage *s, double key)
{
    gd_error err;
    s->valid = 1;
    s->key = key;
    const gd_system *sys = c->sys;
    const gd_transient_spec *spec = c->spec;
    double speed = key;
    if (c->param) {
        const gd_periodic_param *p = c->param;
        int nb = p->base ? p->base->nset : 0;
        const char **sets = malloc((size_t)(nb + 1) * sizeof *sets);
        char assign[512];
        snprintf(assign, sizeof assign, "%s=%.17g%s", p->path, key, p->unit ? p->unit : "");
        if (!sets) return 1;
        for (int i = 0; i < nb; i++)
            sets[i] = p->base->set[i];
        sets[nb] = assign;
        gd_load_options lo = {nb + 1, sets};
        gd_status st = gd_model_load_opts(p->model_path, &lo, &s->m, &err);
        free(sets);
        if (!st) st = gd_system_build(s->m, &s->s, &err);
        if (!st) st = gd_transient_model_build(s->s, &s->tm, &err);
        if (st) {
            s->bad = 1;
            snprintf(s->msg, sizeof s->msg, "%.60s at %.60s: %.180s", p->path, assign, err.message);
            return 1;
        }
        sys = s->s;
        spec = &s->tm->spec;
        speed = p->speed;
    }
    double w0;
    int order;
    if (gd_periodic_fundamental(sys, spec, speed, &w0, &order, &err)) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg, "%.300s", err.message);
        return 1;
    }
    if ((long)order * c->opt->subharmonic > c->H) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg,
                 "an excitation is harmonic %ld of the period (fundamental %.6g rad/s, "
                 "subharmonic %d) but H = %d: raise --harmonics",
                 (long)order * c->opt->subharmonic, w0 / c->opt->subharmonic, c->opt->subharmonic,
                 c->H);
        return 1;
    }
    s->w = w0 / c->opt->subharmonic;
    if (gd_transient_new(sys, spec, speed, &s->tr, &err)) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg, "%.300s", err.message);
        return 1;
    }
    if (gd_transient_terms(s->tr, NULL) < 0) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg,
                 "cam torques with include_acceleration are not supported by harmonic balance");
        return 1;
    }
    if (gd_transient_nstates(s->tr) / 2 != c->nf && c->nf) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg, "the number of free DOFs changes with the parameter");
        return 1;
    }
    return 0;
}

/* The problem at parameter value key; NULL with c->reason set when it cannot be made. */
static stage *get_stage(ctx *c, double key)
{
    for (int i = 0; i < 2; i++)
        if (c->st[i].valid && c->st[i].key == key) {
            if (c->st[i].bad) {
                snprintf(c->reason, sizeof c->reason, "%.300s", c->st[i].msg);
                return NULL;
            }
            return &c->st[i];
        }
    stage *s = &c->st[c->next];
    c->next ^= 1;
    stage_clear(s);
    s->id = ++c->serial;
    if (make_stage(c, s, key)) {
        snprintf(c->reason, sizeof c->reason, "%.300s", s->msg);
        return NULL;
    }
    return s;
}

/* ---------------------------------------------------------------- Newton corrector */

static double norm2(const double *x, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += x[i] * x[i];
    return sqrt(s);
}

/* Newton on R(X, lam) = 0 and, with tan (scaled tangent, n + 1), the hyperplane
 * tan . ((X, lam) - yp) = 0 in scaled variables; without, lam fixed. 0 converged. */
static int newton(ctx *c, double *X, double *lam, const double *tan, const double *yp, int *iters,
                  double *resid)
{
    hb *h = &c->h;
    const int n = h->n;
    double *R = malloc((size_t)(n + 1) * sizeof *R), *R2 = malloc((size_t)n * sizeof *R2);
    double *row = calloc((size_t)n + 1, sizeof *row);
    int rc = 1;
    *resid = NAN;
    if (!R || !R2 || !row) {
        snprintf(c->reason, sizeof c->reason, "out of memory");
        goto done;
    }
    double prev = INFINITY, have_scale = 0.0;
    int have = 0;  /* the line search left R2 = R(X) with its term derivatives */
    int chord = 0; /* reuse the factorization for this step */
    for (int it = 0; it <= c->opt->max_iter; it++) {
        *iters = it;
        double dl = 0.0;
        if (tan) {
            dl = 1e-7 * (fabs(*lam) > c->sl * 1e-3 ? fabs(*lam) : c->sl * 1e-3);
            stage *s2 = get_stage(c, *lam + dl);
            if (!s2) goto done;
            if (gd_hb_residual(h, s2->tr, s2->w, X, R2, 0, NULL)) goto nonfinite;
        }
        stage *s = get_stage(c, *lam);
        if (!s) goto done;
        double scale;
        if (have) {
            memcpy(R, R2, (size_t)n * sizeof *R);
            scale = have_scale;
            have = 0;
        } else if (gd_hb_residual(h, s->tr, s->w, X, R, 1, &scale)) {
            goto nonfinite;
        }
        double rn = norm2(R, n), rel = scale > 0 ? rn / scale : rn;
        double g = 0.0;
        if (tan) {
            for (int i = 0; i < n; i++)
                g += tan[i] * (X[i] - yp[i]) / c->sx;
            g += tan[n] * (*lam - yp[n]) / c->sl;
        }
        *resid = rel;
        if ((rel <= c->opt->tol || rn == 0.0) && fabs(g) <= 1e-9) {
            rc = 0;
            goto done;
        }
        if (it == c->opt->max_iter) break;
        if (!(rel < 1e6 * (prev < 1 ? 1 : prev)) && it > 3) break; /* diverging */
        prev = rel;
        if (tan) {
            for (int i = 0; i < n; i++) {
                R2[i] = (R2[i] - R[i]) / dl;
                row[i] = tan[i] / c->sx;
            }
            row[n] = tan[n] / c->sl;
        } else {
            memset(row, 0, (size_t)n * sizeof *row);
            row[n] = 1.0;
        }
        h->stage_id = s->id;
        /* chord step (fixed value only): after a step that cut |R| 100-fold the iterate
         * is close and the Jacobian barely changes, so its factorization is kept (the TVMS
         * pairs of seed 002: 3e-3 -> 2e-6 -> 3e-10 -> 3e-14 on one factorization, where a
         * fresh one costs the dense LU again); a step that contracts less is followed by
         * a fresh Jacobian */
        if (!(chord && !tan) &&
            (gd_hb_factor(h, s->tr, s->w, tan ? R2 : NULL, row) || h->com.status != KLU_OK)) {
            snprintf(c->reason, sizeof c->reason, "singular harmonic balance Jacobian");
            goto done;
        }
        for (int i = 0; i < n; i++)
            R[i] = -R[i];
        R[n] = -g;
        if (tan)
            gd_hb_solve(h, R);
        else /* R is the residual at X, the last one evaluated */
            gd_hb_solve_newton(h, X, R);
        if (tan) {
            for (int i = 0; i < n; i++)
                X[i] += R[i];
            *lam += R[n];
            continue;
        }
        /* fixed value: backtracking on |R| (contact laws make the residual only piecewise
         * smooth, and a full step from a poor start can overshoot) */
        double alpha = 1.0;
        for (int i = 0; i < n; i++)
            X[i] += R[i];
        chord = 0;
        for (int ls = 0; ls < 12; ls++) {
            double sc, rn2;
            if (!gd_hb_residual(h, s->tr, s->w, X, R2, 1, &sc) &&
                (rn2 = norm2(R2, n)) < (1.0 - 1e-4 * alpha) * rn) {
                have = 1; /* the next iteration starts from this residual */
                have_scale = sc;
                chord = ls == 0 && rn2 < 1e-2 * rn;
                break;
            }
            alpha *= 0.5; /* X = start + alpha step */
            for (int i = 0; i < n; i++)
                X[i] -= alpha * R[i];
        }
    }
    snprintf(c->reason, sizeof c->reason,
             "Newton did not converge in %d iterations (relative residual %.3g > tol %.3g)",
             c->opt->max_iter, *resid, c->opt->tol);
    goto done;
nonfinite:
    snprintf(c->reason, sizeof c->reason, "a force is not finite along the trial solution");
done:
    free(R);
    free(R2);
    free(row);
    return rc;
}

/* Unit tangent (scaled, n + 1) at a converged (X, lam): the bordered system with last row
 * prev (scaled; NULL: e_lam) and right-hand side e_{n+1}; oriented along prev or sign. */
static int tangent(ctx *c, const double *X, double lam, const double *prev, double sign, double *t)
{
    hb *h = &c->h;
    const int n = h->n;
    double *R = malloc((size_t)n * sizeof *R), *R2 = malloc((size_t)n * sizeof *R2);
    double *row = calloc((size_t)n + 1, sizeof *row);
    int rc = 1;
    if (!R || !R2 || !row) goto done;
    double dl = 1e-7 * (fabs(lam) > c->sl * 1e-3 ? fabs(lam) : c->sl * 1e-3);
    stage *s2 = get_stage(c, lam + dl);
    if (!s2 || gd_hb_residual(h, s2->tr, s2->w, X, R2, 0, NULL)) goto done;
    stage *s = get_stage(c, lam);
    if (!s || gd_hb_residual(h, s->tr, s->w, X, R, 1, NULL)) goto done;
    for (int i = 0; i < n; i++) {
        R2[i] = (R2[i] - R[i]) / dl;
        row[i] = prev ? prev[i] / c->sx : 0.0;
    }
    row[n] = prev ? prev[n] / c->sl : 1.0;
    h->stage_id = s->id;
    if (gd_hb_factor(h, s->tr, s->w, R2, row) || h->com.status != KLU_OK) goto done;
    memset(t, 0, (size_t)(n + 1) * sizeof *t);
    t[n] = 1.0;
    gd_hb_solve(h, t);
    for (int i = 0; i < n; i++)
        t[i] /= c->sx;
    t[n] /= c->sl;
    double nt = norm2(t, n + 1), dot = 0.0;
    if (!(nt > 0) || !isfinite(nt)) goto done;
    for (int i = 0; i <= n; i++) {
        t[i] /= nt;
        if (prev) dot += t[i] * prev[i];
    }
    if ((prev && dot < 0) || (!prev && t[n] * sign < 0))
        for (int i = 0; i <= n; i++)
            t[i] = -t[i];
    rc = 0;
done:
    free(R);
    free(R2);
    free(row);
    return rc;
}

/* ---------------------------------------------------------------- harmonic count */

static int samples_for(const gd_periodic_options *o, int H)
{
    if (o->samples > 0) return o->samples;
    int N = 16;
    while (N < 4 * (H + 1))
        N *= 2;
    return N;
}

static int hb_setup(ctx *c, int H)
{
    gd_hb_free(&c->h);
    c->H = H;
    int N = samples_for(c->opt, H);
    if (N < 2 * H + 2) N = 2 * H + 2;
    int rc = gd_hb_init(&c->h, c->nf, H, N);
    c->h.solver = c->opt->solver;
    return rc;
}

/* Share of the top quarter of the harmonics (k >= 1) in the response norm. */
static double top_share(const ctx *c, const double *X)
{
    const int nf = c->nf, H = c->H;
    int k0 = H - (H / 4 > 1 ? H / 4 : 1) + 1;
    double all = 0.0, top = 0.0;
    for (int k = 1; k <= H; k++)
        for (int i = 0; i < 2 * nf; i++) {
            double v = X[(size_t)(2 * k - 1) * nf + i];
            all += v * v;
            if (k >= k0) top += v * v;
        }
    return all > 0 ? sqrt(top / all) : 0.0;
}

/* Grows X (and t, with its parameter entry last) to H2 harmonics. */
static int grow(ctx *c, double **X, double **t, int H2)
{
    const int nf = c->nf, n1 = nf * (2 * c->H + 1), n2 = nf * (2 * H2 + 1);
    double *x = realloc(*X, (size_t)(n2 + 1) * sizeof *x);
    if (!x) return 1;
    *X = x;
    memset(x + n1, 0, (size_t)(n2 + 1 - n1) * sizeof *x);
    if (t && *t) {
        double *y = realloc(*t, (size_t)(n2 + 1) * sizeof *y);
        if (!y) return 1;
        *t = y;
        double tl = y[n1];
        memset(y + n1, 0, (size_t)(n2 + 1 - n1) * sizeof *y);
        y[n2] = tl;
    }
    return hb_setup(c, H2);
}

/* ---------------------------------------------------------------- points */

typedef struct pstate {
    double *X; /* n + 1 (parameter last unused) */
    double lam;
    int iters;
    double resid;
    int stable;
    double mu_max;
    double *mre, *mim;
} pstate;

static void floquet(ctx *c, const double *X, double lam, double *mre, double *mim, int *stable,
                    double *mu_max)
{
    *stable = -1;
    *mu_max = NAN;
    c->floquet_msg[0] = '\0';
    if (!c->opt->stability) return;
    stage *s = get_stage(c, lam);
    if (!s) return;
    int steps = c->opt->monodromy_steps > 0 ? c->opt->monodromy_steps : 4 * c->h.N;
    if (steps < 256 && c->opt->monodromy_steps <= 0) steps = 256;
    const gd_transient_spec *spec = c->param ? &s->tm->spec : c->spec;
    gd_tr_record bl[64];
    int nbl = 0;
    for (int i = 0; i < spec->nmeshes && nbl < 64; i++)
        if (spec->meshes[i].backlash)
            bl[nbl++] = (gd_tr_record){GD_REC_MESH_STATE, spec->meshes[i].mesh, 0};
    int rc = gd_hb_floquet(&c->h, s->tr, s->w, X, steps, bl, nbl, mre, mim);
    if (rc == 2)
        snprintf(c->floquet_msg, sizeof c->floquet_msg,
                 "stability not computed: the monodromy matrix over the period %.3g s overflowed "
                 "with %d Magnus steps (a long period needs more: monodromy_steps)",
                 TWO_PI / s->w, steps);
    if (rc) return;
    double m = 0.0;
    for (int i = 0; i < 2 * c->nf; i++) {
        double a = hypot(mre[i], mim[i]);
        m = a > m ? a : m;
    }
    *mu_max = m;
    *stable = m <= 1.0 + 1e-6;
}

static gd_periodic_point *new_point(ctx *c)
{
    gd_periodic_result *r = c->res;
    if (r->npoints == c->cap_points) {
        int cap = c->cap_points ? 2 * c->cap_points : 64;
        gd_periodic_point *p = realloc(r->points, (size_t)cap * sizeof *p);
        if (!p) return NULL;
        r->points = p;
        c->cap_points = cap;
    }
    gd_periodic_point *p = &r->points[r->npoints++];
    memset(p, 0, sizeof *p);
    p->direction = c->dir;
    p->stable = -1;
    p->mu_max = NAN;
    p->residual = NAN;
    return p;
}

static void set_value(const ctx *c, gd_periodic_point *p, double lam)
{
    p->speed = c->param ? c->param->speed : lam;
    p->parameter = c->param ? lam : NAN;
}

static int fail_point(ctx *c, double lam, const char *why)
{
    gd_periodic_point *p = new_point(c);
    if (!p) return 1;
    set_value(c, p, lam);
    p->converged = 0;
    p->harmonics = c->H;
    snprintf(p->reason, sizeof p->reason, "%.250s", why);
    return 0;
}

/* Record statistics over one period sampled at Nr points. */
static int record_stats(ctx *c, stage *s, const double *X, gd_periodic_point *p)
{
    const int nf = c->nf, H = c->H, nr = c->nrec;
    int Nr = 256;
    while (Nr < 8 * (H + 1))
        Nr *= 2;
    p->records = calloc((size_t)(nr > 0 ? nr : 1), sizeof *p->records);
    double *vals = malloc((size_t)(nr > 0 ? nr : 1) * Nr * sizeof *vals);
    double *buf = fftw_malloc((size_t)Nr * sizeof *buf),
           *out = fftw_malloc((size_t)Nr * sizeof *out);
    double *y = calloc(2 * (size_t)nf, sizeof *y), *qs = NULL, *vs = NULL;
    /* only the DOFs the records read are sampled (the others stay zero in y) */
    int *dofs = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *dofs), nd = 0;
    double *rv = malloc((size_t)(nr > 0 ? nr : 1) * sizeof *rv);
    unsigned char *seen = calloc((size_t)(nf > 0 ? nf : 1), 1);
    int *tmp = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *tmp);
    for (int r = 0; r < nr && dofs && seen && tmp && nd >= 0; r++) {
        int k = gd_transient_record_dofs(s->tr, &c->rec[r], tmp, nf);
        for (int q = 0; q < k; q++)
            if (!seen[tmp[q]]) {
                seen[tmp[q]] = 1;
                dofs[nd++] = tmp[q];
            }
        if (k < 0) nd = -1;
    }
    const int listed = dofs && seen && tmp;
    free(seen);
    free(tmp);
    int ok = p->records && vals && buf && out && y && listed && rv &&
             (!nr || !gd_hb_samples(&c->h, s->w, X, Nr, nd >= 0 ? dofs : NULL, nd, &qs, &vs));
    const int all = nd < 0; /* a record that reads every DOF: all sampled, in order */
    if (all) nd = nf;
    if (!ok) {
        free(vals);
        fftw_free(buf);
        fftw_free(out);
        free(y);
        free(dofs);
        free(rv);
        return 1;
    }
    /* the state once per sample, every record from it */
    for (int j = 0; j < Nr && nr; j++) {
        double tau = TWO_PI * j / Nr;
        for (int m = 0; m < nd; m++) {
            int i = all ? m : dofs[m];
            y[i] = qs[(size_t)j * nd + m];
            y[nf + i] = vs[(size_t)j * nd + m];
        }
        gd_transient_record_values(s->tr, c->rec, nr, tau / s->w, y, rv);
        for (int r = 0; r < nr; r++)
            vals[(size_t)r * Nr + j] = rv[r];
    }
    free(dofs);
    free(rv);
    fftw_plan plan = fftw_plan_r2r_1d(Nr, buf, out, FFTW_R2HC, FFTW_ESTIMATE);
    for (int r = 0; r < nr; r++) {
        gd_per_record_stats *st = &p->records[r];
        st->amplitude = calloc((size_t)H + 1, sizeof *st->amplitude);
        st->phase_deg = calloc((size_t)H + 1, sizeof *st->phase_deg);
        if (!st->amplitude || !st->phase_deg) continue;
        double mn = INFINITY, mx = -INFINITY, sum = 0.0, sq = 0.0;
        for (int j = 0; j < Nr; j++) {
            double v = buf[j] = vals[(size_t)r * Nr + j];
            mn = v < mn ? v : mn;
            mx = v > mx ? v : mx;
            sum += v;
            sq += v * v;
        }
        st->mean = sum / Nr;
        st->rms = sqrt(sq / Nr);
        st->peak_to_peak = mx - mn;
        fftw_execute(plan);
        st->amplitude[0] = out[0] / Nr;
        for (int k = 1; k <= H && k < Nr / 2; k++) {
            double a = 2.0 * out[k] / Nr, b = -2.0 * out[Nr - k] / Nr;
            st->amplitude[k] = hypot(a, b);
            st->phase_deg[k] = -atan2(b, a) * 360.0 / TWO_PI;
        }
    }
    fftw_destroy_plan(plan);
    free(vals);
    fftw_free(buf);
    fftw_free(out);
    free(y);
    return 0;
}

static int emit_point(ctx *c, const double *X, double lam, int iters, double resid)
{
    stage *s = get_stage(c, lam);
    gd_periodic_point *p = new_point(c);
    if (!p) return 1;
    set_value(c, p, lam);
    if (!s) {
        snprintf(p->reason, sizeof p->reason, "%.250s", c->reason);
        return 0;
    }
    p->converged = 1;
    p->harmonics = c->H;
    p->omega = s->w;
    p->residual = resid;
    p->iterations = iters;
    p->nfree = c->nf;
    size_t n = (size_t)c->h.n;
    p->coef = malloc(n * sizeof *p->coef);
    p->mu_re = malloc(2 * (size_t)c->nf * sizeof *p->mu_re);
    p->mu_im = malloc(2 * (size_t)c->nf * sizeof *p->mu_im);
    if (!p->coef || !p->mu_re || !p->mu_im) return 1;
    memcpy(p->coef, X, n * sizeof *X);
    floquet(c, X, lam, p->mu_re, p->mu_im, &p->stable, &p->mu_max);
    p->nmult = p->stable >= 0 ? 2 * c->nf : 0;
    if (p->stable < 0 && c->floquet_msg[0])
        snprintf(p->reason, sizeof p->reason, "%s", c->floquet_msg);
    s = get_stage(c, lam);
    return s ? record_stats(c, s, X, p) : 1;
}

/* ---------------------------------------------------------------- bifurcations */

/* multiplier categories outside the unit circle: 0 real > 0, 1 real < 0, 2 complex;
 * rho[k]: largest modulus in category k (NaN if none) */
static void categorise(const ctx *c, const double *mre, const double *mim, int out[3],
                       double rho[3])
{
    out[0] = out[1] = out[2] = 0;
    rho[0] = rho[1] = rho[2] = NAN;
    for (int i = 0; i < 2 * c->nf; i++) {
        double a = hypot(mre[i], mim[i]);
        int k = fabs(mim[i]) > 1e-9 * (a > 1e-300 ? a : 1) ? 2 : mre[i] >= 0 ? 0 : 1;
        if (a > 1.0 + 1e-6) out[k]++;
        if (!(rho[k] >= a)) rho[k] = a;
    }
}

static int add_bif(ctx *c, gd_bifurcation_type type, double lam, double mre, double mim)
{
    gd_periodic_result *r = c->res;
    /* a real multiplier through +1 next to a fold is the fold itself (located a step
     * apart when the fold falls near a step end) */
    const double near = 1e-3 * (c->sl > 0 ? c->sl : 1.0);
    for (int i = r->nbifurcations - 1; i >= 0 && i >= r->nbifurcations - 3; i--) {
        gd_bifurcation *b = &r->bifurcations[i];
        if (b->direction != c->dir || fabs((c->param ? b->parameter : b->speed) - lam) > near)
            continue;
        if (type == GD_BIF_BRANCH_POINT && b->type == GD_BIF_FOLD) return 0;
        if (type == GD_BIF_FOLD && b->type == GD_BIF_BRANCH_POINT) {
            *b = r->bifurcations[--r->nbifurcations]; /* replace it by the fold */
            break;
        }
    }
    if (r->nbifurcations == c->cap_bif) {
        int cap = c->cap_bif ? 2 * c->cap_bif : 16;
        gd_bifurcation *b = realloc(r->bifurcations, (size_t)cap * sizeof *b);
        if (!b) return 1;
        r->bifurcations = b;
        c->cap_bif = cap;
    }
    gd_bifurcation *b = &r->bifurcations[r->nbifurcations++];
    b->type = type;
    b->speed = c->param ? c->param->speed : lam;
    b->parameter = c->param ? lam : NAN;
    b->direction = c->dir;
    b->mu_re = mre;
    b->mu_im = mim;
    return 0;
}

/* The branch point at fraction sig between a (Xa, la) and b (Xb, lb): Newton on the
 * hyperplane normal to tan through the linear interpolate. X receives it. */
static int point_between(ctx *c, const double *Xa, double la, const double *Xb, double lb,
                         const double *tan, double sig, double *X, double *lam)
{
    const int n = c->h.n;
    double *yp = malloc((size_t)(n + 1) * sizeof *yp);
    if (!yp) return 1;
    for (int i = 0; i < n; i++)
        X[i] = yp[i] = (1 - sig) * Xa[i] + sig * Xb[i];
    *lam = yp[n] = (1 - sig) * la + sig * lb;
    int it;
    double res;
    int rc = newton(c, X, lam, tan, yp, &it, &res);
    free(yp);
    return rc;
}

/* The m-th largest multiplier modulus (m >= 1) and its index. */
static double ranked(const ctx *c, const double *mre, const double *mim, int m, int *at)
{
    int nm = 2 * c->nf, used[512] = {0};
    double v = NAN;
    *at = -1;
    for (int r = 0; r < m && r < nm && nm <= 512; r++) {
        int bi = -1;
        for (int i = 0; i < nm; i++)
            if (!used[i] && (bi < 0 || hypot(mre[i], mim[i]) > hypot(mre[bi], mim[bi]))) bi = i;
        used[bi] = 1;
        v = hypot(mre[bi], mim[bi]);
        *at = bi;
    }
    return v;
}

/* A multiplier crossed the unit circle between two steps (m - 1 outside on one side, m on
 * the other): regula falsi (Illinois) on |mu|_(m) - 1, the m-th largest modulus, over
 * points of the branch between the steps; the type from the crossing multiplier at the
 * located point: real > 0 branch point (a fold is reported by its tangent), real < 0
 * period doubling, complex Neimark-Sacker. */
static int locate(ctx *c, int m, const double *Xa, double la, double ga, const double *Xb,
                  double lb, double gb, const double *tan, const double *mre_b, const double *mim_b)
{
    const int n = c->h.n;
    double *X = malloc((size_t)(n + 1) * sizeof *X);
    double *mre = malloc(2 * (size_t)c->nf * sizeof *mre),
           *mim = malloc(2 * (size_t)c->nf * sizeof *mim);
    if (!X || !mre || !mim) {
        free(X);
        free(mre);
        free(mim);
        return 1;
    }
    double s0 = 0.0, s1 = 1.0, g0 = ga, g1 = gb, lam = la + 0.5 * (lb - la);
    int at;
    ranked(c, mre_b, mim_b, m, &at);
    double best_re = at >= 0 ? mre_b[at] : NAN, best_im = at >= 0 ? fabs(mim_b[at]) : NAN;
    int ok = isfinite(g0) && isfinite(g1) && g0 != g1, found = 0;
    double sig = ok ? -g0 / (g1 - g0) : 0.5;
    for (int it = 0; it < 30 && ok; it++) {
        if (!(sig > 0 && sig < 1)) sig = 0.5;
        if (point_between(c, Xa, la, Xb, lb, tan, sig, X, &lam)) break;
        int stable;
        double mu_max;
        floquet(c, X, lam, mre, mim, &stable, &mu_max);
        if (stable < 0) break;
        double g = ranked(c, mre, mim, m, &at) - 1.0;
        if (!isfinite(g) || at < 0) break;
        best_re = mre[at];
        best_im = fabs(mim[at]);
        found = 1;
        if (fabs(g) < 1e-10) break;
        if ((g < 0) == (g0 < 0)) {
            s0 = sig;
            g0 = g;
            g1 *= 0.5;
        } else {
            s1 = sig;
            g1 = g;
            g0 *= 0.5;
        }
        sig = s0 - g0 * (s1 - s0) / (g1 - g0);
    }
    if (!found || !(lam >= fmin(la, lb) && lam <= fmax(la, lb)))
        /* the search left the step (a branch nearby): interpolate between the steps */
        lam = gb != ga ? la + (lb - la) * (-ga / (gb - ga)) : 0.5 * (la + lb);
    double a = hypot(best_re, best_im);
    gd_bifurcation_type type = best_im > 1e-9 * a ? GD_BIF_NEIMARK_SACKER
                               : best_re < 0      ? GD_BIF_PERIOD_DOUBLING
                                                  : GD_BIF_BRANCH_POINT;
    int rc = 0;
    /* reported only when located (the critical multiplier on the circle to 1e-4): a
     * search that cannot close in on it (several multipliers moving at once) says
     * nothing rather than something wrong */
    if (!(type == GD_BIF_BRANCH_POINT && c->near_fold) && found && fabs(a - 1.0) < 1e-4)
        rc = add_bif(c, type, lam, best_re, best_im);
    free(X);
    free(mre);
    free(mim);
    return rc;
}

/* ---------------------------------------------------------------- branches */

static double inf_norm(const double *x, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m = fabs(x[i]) > m ? fabs(x[i]) : m;
    return m;
}

/* Newton from rest through a contact homotopy: every backlash mesh first held on its
 * drive flank (h = 1: smooth), then released step by step to the backlash law (h = 0),
 * each Newton starting from the last solution; a failed release halves the step. Without
 * backlash meshes h changes nothing and the first solve is the answer. */
static int solve_from_rest(ctx *c, double *X, double lam, int *it, double *res)
{
    stage *s = get_stage(c, lam);
    if (!s) return 1;
    const int n = c->h.n;
    double *Xok = malloc((size_t)n * sizeof *Xok);
    if (!Xok) return 1;
    double h = 1.0, step = 0.5;
    int rc = 1, nbl = 0;
    const gd_transient_spec *spec = c->param ? &s->tm->spec : c->spec;
    for (int i = 0; i < spec->nmeshes; i++)
        nbl += spec->meshes[i].backlash != 0;
    if (!nbl) {
        free(Xok);
        return newton(c, X, &lam, NULL, NULL, it, res);
    }
    gd_transient_hold_drive(s->tr, h);
    if (newton(c, X, &lam, NULL, NULL, it, res)) goto done;
    memcpy(Xok, X, (size_t)n * sizeof *X);
    while (h > 0) {
        double h2 = h - step < 1e-3 ? 0.0 : h - step;
        gd_transient_hold_drive(s->tr, h2);
        if (newton(c, X, &lam, NULL, NULL, it, res)) {
            memcpy(X, Xok, (size_t)n * sizeof *X);
            step *= 0.5;
            if (step < 1e-3) goto done;
            continue;
        }
        memcpy(Xok, X, (size_t)n * sizeof *X);
        h = h2;
        step = step * 2 < 0.5 ? step * 2 : 0.5;
    }
    rc = 0;
done:
    gd_transient_hold_drive(s->tr, 0.0);
    if (rc && h < 1.0)
        snprintf(c->reason + strlen(c->reason), sizeof c->reason - strlen(c->reason),
                 " (releasing the backlash contacts from the drive flank, at %.3g)", h);
    free(Xok);
    return rc;
}

/* Fixed-value Newton with adaptive H; X grows with H (t too, if given). rest: X is zero. */
static int solve_fixed(ctx *c, double **X, double **t, double lam, int *it, double *res, int rest)
{
    for (;;) {
        if (rest ? solve_from_rest(c, *X, lam, it, res) : newton(c, *X, &lam, NULL, NULL, it, res))
            return 1;
        if (!c->opt->adaptive || top_share(c, *X) <= c->opt->harmonic_tol ||
            c->H >= c->opt->max_harmonics)
            return 0;
        int H2 = c->H + (c->H / 2 > 1 ? c->H / 2 : 1);
        if (H2 > c->opt->max_harmonics) H2 = c->opt->max_harmonics;
        if (grow(c, X, t, H2)) return 1;
    }
}

static int run_branch(ctx *c, const double *vals, int nv)
{
    int n = c->h.n, it = 0, rc = 1, i0;
    double res = NAN, lam = 0.0, reached = 0.0, sign = 1.0;
    double *X = calloc((size_t)n + 1, sizeof *X), *t = NULL, *t1 = NULL, *X1 = NULL, *Xg = NULL,
           *yp = NULL;
    double *mre = NULL, *mim = NULL, *mre1 = NULL, *mim1 = NULL;
    if (!X) return 1;
    for (i0 = 0; i0 < nv; i0++) {
        lam = vals[i0];
        memset(X, 0, (size_t)(c->h.n + 1) * sizeof *X);
        if (!get_stage(c, lam) || solve_fixed(c, &X, NULL, lam, &it, &res, 1)) {
            if (fail_point(c, lam, c->reason)) goto done;
            continue;
        }
        break;
    }
    if (i0 == nv) {
        rc = 0;
        goto done;
    }
    if (emit_point(c, X, lam, it, res)) goto done;
    if (c->opt->method == GD_PER_SEQUENTIAL) {
        /* each speed from the secant through the last two solutions (the plain last
         * solution if the secant start fails): on a smooth curve its error is second
         * order in the step (the seed-002 curve: starting residual 4.5e-3 -> 1e-3, Newton
         * iterations 601 -> 584 over 300 speeds) */
        double *Xp = NULL, lamx = lam, lamp = lam;
        for (int i = i0 + 1; i < nv; i++) {
            double *Xs = malloc((size_t)(c->h.n + 1) * sizeof *Xs);
            if (!Xs) {
                free(Xp);
                goto done;
            }
            memcpy(Xs, X, (size_t)(c->h.n + 1) * sizeof *Xs);
            c->steps++;
            int staged = get_stage(c, vals[i]) != NULL, ok = 0;
            if (staged && Xp && lamx != lamp) {
                double f = (vals[i] - lamx) / (lamx - lamp);
                for (int j = 0; j < n; j++)
                    Xs[j] += f * (X[j] - Xp[j]);
                ok = !solve_fixed(c, &Xs, NULL, vals[i], &it, &res, 0);
                if (!ok && c->h.n == n) {
                    memcpy(Xs, X, (size_t)(n + 1) * sizeof *Xs);
                    staged = get_stage(c, vals[i]) != NULL;
                } else if (!ok) {
                    staged = 0; /* H grew on the way: no second start */
                }
            }
            if (staged && !ok) ok = !solve_fixed(c, &Xs, NULL, vals[i], &it, &res, 0);
            if (!ok) {
                free(Xs);
                if (fail_point(c, vals[i], c->reason)) {
                    free(Xp);
                    goto done;
                }
                continue;
            }
            free(Xp);
            Xp = X;
            lamp = lamx;
            lamx = vals[i];
            if (c->h.n != n) { /* H grew: the last solution no longer matches */
                free(Xp);
                Xp = NULL;
            }
            X = Xs;
            n = c->h.n;
            if (emit_point(c, X, vals[i], it, res)) {
                free(Xp);
                goto done;
            }
        }
        free(Xp);
        rc = 0;
        goto done;
    }
    if (i0 == nv - 1) {
        rc = 0;
        goto done;
    }
    /* pseudo-arclength */
    sign = vals[nv - 1] > vals[i0] ? 1.0 : -1.0;
    reached = lam;
    const double lend = vals[nv - 1], lstart = vals[i0];
    c->sl = fabs(lend - lstart);
    c->sx = inf_norm(X, c->h.n);
    if (!(c->sx > 0)) c->sx = 1.0;
    int cap = 0;
#define ALLOC_ALL()                                                                                \
    do {                                                                                           \
        n = c->h.n;                                                                                \
        cap = n + 1;                                                                               \
        double **arr[4] = {&t1, &X1, &Xg, &yp};                                                    \
        for (int a = 0; a < 4; a++) {                                                              \
            free(*arr[a]);                                                                         \
            *arr[a] = calloc((size_t)cap, sizeof **arr[a]);                                        \
            if (!*arr[a]) goto done;                                                               \
        }                                                                                          \
    } while (0)
    ALLOC_ALL();
    t = calloc((size_t)cap, sizeof *t);
    mre = malloc(2 * (size_t)c->nf * sizeof *mre);
    mim = malloc(2 * (size_t)c->nf * sizeof *mim);
    mre1 = malloc(2 * (size_t)c->nf * sizeof *mre1);
    mim1 = malloc(2 * (size_t)c->nf * sizeof *mim1);
    if (!t || !mre || !mim || !mre1 || !mim1) goto done;
    if (tangent(c, X, lam, NULL, sign, t)) {
        snprintf(c->reason, sizeof c->reason, "no tangent at the start of the branch");
        goto stop;
    }
    int stable, out[3], out1[3];
    double mu_max, rho[3], rho1[3];
    (void)rho;
    (void)rho1;
    floquet(c, X, lam, mre, mim, &stable, &mu_max);
    int have_mu = stable >= 0, fold_prev = 0;
    if (have_mu) categorise(c, mre, mim, out, rho);
    double ds = 1.0 / (nv - 1), dsmax = 2.0 / (nv - 1), dsmin = 1e-7;
    if (ds > 0.05) ds = 0.05;
    if (dsmax > 0.1) dsmax = 0.1;
    int maxsteps = c->opt->max_steps > 0 ? c->opt->max_steps : 50 * nv + 200;
    for (int step = 0;; step++) {
        if (step >= maxsteps) {
            snprintf(c->reason, sizeof c->reason,
                     "continuation stopped after %d steps (raise max_steps)", maxsteps);
            goto stop;
        }
        c->steps++;
        for (int i = 0; i < n; i++)
            yp[i] = X1[i] = X[i] + ds * t[i] * c->sx;
        double l1 = yp[n] = lam + ds * t[n] * c->sl;
        if (newton(c, X1, &l1, t, yp, &it, &res)) {
            ds *= 0.5;
            if (ds < dsmin) goto stop;
            continue;
        }
        if (c->opt->adaptive && top_share(c, X1) > c->opt->harmonic_tol &&
            c->H < c->opt->max_harmonics) {
            int H2 = c->H + (c->H / 2 > 1 ? c->H / 2 : 1);
            if (H2 > c->opt->max_harmonics) H2 = c->opt->max_harmonics;
            if (grow(c, &X, &t, H2)) goto done;
            ALLOC_ALL();
            if (solve_fixed(c, &X, &t, lam, &it, &res, 0)) goto stop;
            continue;
        }
        if (tangent(c, X1, l1, t, sign, t1)) {
            ds *= 0.5;
            if (ds < dsmin) goto stop;
            continue;
        }
        {
            /* step control by the turn of the tangent and the chord's direction: a step
             * that turned more than ~25 deg, or whose corrector fell back behind the
             * start (retracing a branch past a fold), is retried shorter */
            double tt = 0.0, tc = 0.0;
            for (int i = 0; i < n; i++) {
                tt += t[i] * t1[i];
                tc += t[i] * (X1[i] - X[i]) / c->sx;
            }
            tt += t[n] * t1[n];
            tc += t[n] * (l1 - lam) / c->sl;
            if ((tt < 0.9 || tc <= 0.0) && ds > 16 * dsmin) {
                ds *= 0.5;
                continue;
            }
        }
        int stable1 = -1;
        if (have_mu) {
            floquet(c, X1, l1, mre1, mim1, &stable1, &mu_max);
            if (stable1 >= 0) categorise(c, mre1, mim1, out1, rho1);
        }
        /* requested values crossed on this step, in the step's order */
        for (int q = 0; q < nv; q++) {
            int i = l1 >= lam ? q : nv - 1 - q;
            double v = vals[i];
            if (i == i0 && step == 0) continue;
            int crossed = l1 >= lam ? (v > lam && v <= l1) : (v < lam && v >= l1);
            if (!crossed) continue;
            double sig = (v - lam) / (l1 - lam);
            for (int k = 0; k < n; k++)
                Xg[k] = (1 - sig) * X[k] + sig * X1[k];
            int itg;
            double resg;
            int bad = newton(c, Xg, &v, NULL, NULL, &itg, &resg);
            for (int end = 0; bad && end < 2; end++) { /* near a fold: from either step */
                memcpy(Xg, end ? X1 : X, (size_t)n * sizeof *Xg);
                v = vals[i];
                bad = newton(c, Xg, &v, NULL, NULL, &itg, &resg);
            }
            if (bad) {
                if (fail_point(c, v, c->reason)) goto done;
            } else if (emit_point(c, Xg, v, itg, resg)) {
                goto done;
            }
        }
        /* bifurcations between the two steps */
        int fold = t[n] * t1[n] < 0;
        if (fold) {
            double s = t[n] / (t[n] - t1[n]), s2 = s * s, s3 = s2 * s;
            double lf = (2 * s3 - 3 * s2 + 1) * lam + (s3 - 2 * s2 + s) * ds * t[n] * c->sl +
                        (-2 * s3 + 3 * s2) * l1 + (s3 - s2) * ds * t1[n] * c->sl;
            if (add_bif(c, GD_BIF_FOLD, lf, NAN, NAN)) goto done;
        }
        if (have_mu && stable1 >= 0) {
            int tot = out[0] + out[1] + out[2], tot1 = out1[0] + out1[1] + out1[2];
            if (tot != tot1) {
                /* a multiplier crossed the circle (two meeting on the real axis only move
                 * between categories); a real one through +1 at a fold is the fold */
                int m = tot < tot1 ? tot1 : tot, ia, ib;
                double ga = ranked(c, mre, mim, m, &ia) - 1.0;
                double gb = ranked(c, mre1, mim1, m, &ib) - 1.0;
                c->near_fold = fold || fold_prev;
                if (locate(c, m, X, lam, ga, X1, l1, gb, t, mre1, mim1)) goto done;
            }
            memcpy(out, out1, sizeof out);
            memcpy(mre, mre1, 2 * (size_t)c->nf * sizeof *mre);
            memcpy(mim, mim1, 2 * (size_t)c->nf * sizeof *mim);
        }
        have_mu = have_mu && stable1 >= 0;
        fold_prev = fold;
        memcpy(X, X1, (size_t)n * sizeof *X);
        memcpy(t, t1, (size_t)(n + 1) * sizeof *t);
        {
            /* rescale X to its present size, so that a growing resonance does not eat the
             * arclength: re-express the tangent in the new scale */
            double sx2 = inf_norm(X, n);
            if (sx2 > 0) {
                double nt = 0.0;
                for (int i = 0; i < n; i++) {
                    t[i] *= c->sx / sx2;
                    nt += t[i] * t[i];
                }
                nt = sqrt(nt + t[n] * t[n]);
                for (int i = 0; i <= n; i++)
                    t[i] /= nt;
                c->sx = sx2;
            }
        }
        lam = l1;
        if (sign * (lam - reached) > 0) reached = lam;
        if (it <= 3) ds = ds * 1.6 < dsmax ? ds * 1.6 : dsmax;
        if (it > 6) ds *= 0.6;
        if (sign * (lam - lend) >= 0) break;
        if (sign * (lam - lstart) < -0.5 * c->sl || (!c->param && lam <= 0)) {
            snprintf(c->reason, sizeof c->reason, "the branch turned back out of the range");
            goto stop;
        }
    }
    rc = 0;
    goto done;
stop:
    /* values beyond the furthest point reached get the reason */
    for (int i = i0 + 1; i < nv; i++)
        if (sign * (vals[i] - reached) > 0 && fail_point(c, vals[i], c->reason)) goto done;
    rc = 0;
done:
#undef ALLOC_ALL
    free(X);
    free(t);
    free(t1);
    free(X1);
    free(Xg);
    free(yp);
    free(mre);
    free(mim);
    free(mre1);
    free(mim1);
    return rc;
}

gd_status gd_periodic_run(const gd_system *sys, const gd_transient_spec *spec,
                          const gd_periodic_param *param, const double *values, int nvalues,
                          const gd_periodic_options *opt, const gd_tr_record *records, int nrecords,
                          gd_periodic_result **out, gd_error *err)
{
    *out = NULL;
    clock_t c0 = clock();
#define BAD(field, hint, ...)                                                                      \
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint, __VA_ARGS__)
    if (nvalues < 1 || !values) BAD("speeds", "give FROM:TO:COUNT", "no values to solve at");
    for (int i = 0; i < nvalues; i++)
        if (!isfinite(values[i])) BAD("speeds", "", "values must be finite");
    if (opt->harmonics < 1 || opt->harmonics > 1000)
        BAD("harmonics", "give 1..1000", "harmonic count %d out of range", opt->harmonics);
    if (opt->subharmonic < 1 || opt->subharmonic > 1000)
        BAD("subharmonic", "give N from 1 to 1000 (period N times the fundamental)",
            "subharmonic order %d is outside 1..1000", opt->subharmonic);
    if (!(opt->tol > 0) || opt->tol < 1e-15)
        BAD("tol", "give a tolerance in [1e-15, 1)",
            "tolerance %g is unreachable in double precision", opt->tol);
    if (opt->max_iter < 1) BAD("max_iter", "", "max_iter must be at least 1");
    if (opt->samples < 0 || opt->samples > GD_PERIODIC_MAX_SAMPLES)
        BAD("samples", "give 0 (automatic) or 4..1048576 (2^20)",
            "%d AFT samples per period is outside 0..%d", opt->samples, GD_PERIODIC_MAX_SAMPLES);
    if (opt->monodromy_steps < 0 || opt->monodromy_steps > GD_PERIODIC_MAX_SAMPLES)
        BAD("monodromy_steps", "give 0 (automatic) or 1..1048576 (2^20)",
            "%d Magnus steps per period is outside 0..%d", opt->monodromy_steps,
            GD_PERIODIC_MAX_SAMPLES);
    if (opt->samples && opt->samples < 2 * opt->harmonics + 2)
        BAD("samples", "give at least 2 H + 2", "%d samples cannot resolve %d harmonics",
            opt->samples, opt->harmonics);
    if (opt->adaptive && !(opt->harmonic_tol > 0))
        BAD("harmonic_tol", "", "the adaptive harmonic tolerance must be > 0");
    for (int r = 0; r < nrecords; r++)
        if (records[r].kind == GD_REC_ANGLE)
            BAD("record", "record the DOF's displacement (perturbation) instead",
                "a total angle grows with time and has no periodic steady state");
#undef BAD
    ctx c;
    memset(&c, 0, sizeof c);
    c.sys = sys;
    c.spec = spec;
    c.param = param;
    c.opt = opt;
    c.rec = records;
    c.nrec = nrecords;
    c.H = opt->harmonics;
    gd_periodic_result *res = calloc(1, sizeof *res);
    if (!res) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    c.res = res;
    res->nrecords = nrecords;
    /* the number of free DOFs, from a problem at the first value */
    {
        gd_transient *tr = NULL;
        gd_status st;
        if (param) {
            stage s = {0};
            c.opt = opt;
            if (make_stage(&c, &s, values[0]) && !s.tr) {
                gd_error_set(err, GD_EINPUT, "", 0, 0, param->path, "", "%s", s.msg);
                stage_clear(&s);
                gd_periodic_result_free(res);
                return GD_EINPUT;
            }
            c.nf = gd_transient_nstates(s.tr) / 2;
            stage_clear(&s);
        } else {
            if ((st = gd_transient_new(sys, spec, values[0], &tr, err))) {
                gd_periodic_result_free(res);
                return st;
            }
            int nt = gd_transient_terms(tr, NULL);
            c.nf = gd_transient_nstates(tr) / 2;
            gd_transient_free(tr);
            if (nt < 0) {
                gd_periodic_result_free(res);
                return gd_error_set(err, GD_EINPUT, "", 0, 0, "cam_torques",
                                    "set include_acceleration: false",
                                    "cam torques with include_acceleration are not supported by "
                                    "harmonic balance");
            }
        }
    }
    int rc = 0;
    double *rev = malloc((size_t)nvalues * sizeof *rev);
    if (!rev || hb_setup(&c, opt->harmonics)) rc = 1;
    for (int d = 0; d < (opt->both_directions ? 2 : 1) && !rc; d++) {
        c.dir = d ? -1 : 1;
        for (int i = 0; i < nvalues; i++)
            rev[i] = d ? values[nvalues - 1 - i] : values[i];
        if (d && hb_setup(&c, opt->harmonics)) rc = 1;
        if (!rc) rc = run_branch(&c, rev, nvalues);
    }
    free(rev);
    stage_clear(&c.st[0]);
    stage_clear(&c.st[1]);
    gd_hb_free(&c.h);
    res->steps = c.steps;
    res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (rc) {
        gd_periodic_result_free(res);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    *out = res;
    return GD_OK;
}

void gd_periodic_result_free(gd_periodic_result *r)
{
    if (!r) return;
    for (int i = 0; i < r->npoints; i++) {
        gd_periodic_point *p = &r->points[i];
        free(p->coef);
        free(p->mu_re);
        free(p->mu_im);
        if (p->records)
            for (int k = 0; k < r->nrecords; k++) {
                free(p->records[k].amplitude);
                free(p->records[k].phase_deg);
            }
        free(p->records);
    }
    free(r->points);
    free(r->bifurcations);
    free(r);
}
