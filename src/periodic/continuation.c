/* Harmonic balance's branch (continuation_impl.h) by the shared drivers (method.h:
 * driver/sequential.c, the first point and --sequential; driver/arclength.c) over harmonic
 * balance's operations defined here (gd_per_hb_ops: its start from rest, corrector,
 * tangent, multipliers, the scale of X, adaptive H; its bifurcation rule is
 * bifurcation.c's gd_per_hb_detect). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/continuation_impl.h"
#include "periodic/method.h"
#include "periodic/periodic_impl.h"

static int hb_size(void *m)
{
    return ((hb_arc *)m)->c->h.n;
}

static void hb_step(void *m)
{
    ((hb_arc *)m)->c->steps++;
}

static int hb_prepare(void *m, double v)
{
    return !gd_per_get_stage(((hb_arc *)m)->c, v);
}

/* From rest, then from a short transient's last period (its reason kept). */
static int hb_cold(void *m, double **X, double v, int *it, double *res)
{
    ctx *c = ((hb_arc *)m)->c;
    memset(*X, 0, (size_t)(c->h.n + 1) * sizeof **X);
    return gd_per_solve_fixed(c, X, NULL, v, it, res, 1) && gd_per_solve_warm(c, *X, v, it, res);
}

/* X's scale: its largest coefficient (1 when all are 0), the same for every unknown. */
static void hb_fill_scales(const ctx *c, double *D, int n)
{
    for (int i = 0; i < n; i++)
        D[i] = c->sx;
}

static int hb_start(void *m, const double *X, double lam, double sign, double sl, double *D,
                    double *t)
{
    hb_arc *a = m;
    ctx *c = a->c;
    c->sl = sl;
    c->sx = gd_per_inf_norm(X, c->h.n);
    if (!(c->sx > 0)) c->sx = 1.0;
    hb_fill_scales(c, D, c->h.n);
    if (gd_per_tangent(c, X, lam, NULL, sign, t)) {
        snprintf(c->reason, sizeof c->reason, "no tangent at the start of the branch");
        return 1;
    }
    int stable;
    double mu_max, rho[3];
    gd_per_floquet(c, X, lam, a->mre, a->mim, &stable, &mu_max);
    a->have_mu = stable >= 0;
    if (a->have_mu) gd_per_categorise(c, a->mre, a->mim, a->out, rho);
    return 0;
}

static int hb_correct(void *m, double *X, double *lam, const double *t, const double *yp, int *it,
                      double *res)
{
    return gd_per_newton(((hb_arc *)m)->c, X, lam, t, yp, it, res);
}

static int hb_tangent(void *m, const double *X, double lam, const double *prev, double sign,
                      double *t)
{
    return gd_per_tangent(((hb_arc *)m)->c, X, lam, prev, sign, t);
}

static void hb_measure(void *m, const double *X1, double l1)
{
    hb_arc *a = m;
    double mu_max, rho1[3];
    a->stable1 = -1;
    if (!a->have_mu) return;
    gd_per_floquet(a->c, X1, l1, a->mre1, a->mim1, &a->stable1, &mu_max);
    if (a->stable1 >= 0) gd_per_categorise(a->c, a->mre1, a->mim1, a->out1, rho1);
}

static int hb_solve_at(void *m, double *X, double v, int *it, double *res)
{
    return gd_per_newton(((hb_arc *)m)->c, X, &v, NULL, NULL, it, res);
}

static int hb_emit(void *m, const double *X, double v, int it, double res)
{
    return gd_per_emit_point(((hb_arc *)m)->c, X, v, it, res);
}

static int hb_fail(void *m, double v)
{
    ctx *c = ((hb_arc *)m)->c;
    return gd_per_fail_point(c, v, c->reason);
}

/* X's scale to its present size: the tangent re-expressed in it. */
static void hb_rescale(void *m, const double *X, double *D, double *t)
{
    ctx *c = ((hb_arc *)m)->c;
    const int n = c->h.n;
    double sx2 = gd_per_inf_norm(X, n);
    if (!(sx2 > 0)) return;
    double nt = 0.0;
    for (int i = 0; i < n; i++) {
        t[i] *= c->sx / sx2;
        nt += t[i] * t[i];
    }
    nt = sqrt(nt + t[n] * t[n]);
    for (int i = 0; i <= n; i++)
        t[i] /= nt;
    c->sx = sx2;
    hb_fill_scales(c, D, n);
}

/* Adaptive H: a requested point needed more harmonics, the branch goes on with them. */
static int hb_grow(void *m, double **X, double **t, double **D, double lam, int *it)
{
    ctx *c = ((hb_arc *)m)->c;
    if (!c->opt->adaptive || c->want_H <= c->H) return 0;
    if (gd_per_follow_H(c, X, t)) return -1;
    if (D) {
        free(*D);
        *D = malloc(((size_t)c->h.n + 1) * sizeof **D);
        if (!*D) return -1;
        hb_fill_scales(c, *D, c->h.n);
    }
    if (!it) return 1;
    double res;
    if (!gd_per_solve_fixed(c, X, t, lam, it, &res, 0)) return 1;
    char why[320];
    snprintf(why, sizeof why, "%s", c->reason);
    snprintf(c->reason, sizeof c->reason,
             "the point at %.6g did not converge again at H = %d: %.200s", lam, c->H, why);
    return 2;
}

/* A direction begins: its range, the branch's H back to the first (the backward branch
 * starts at the run's first H, as the forward one did). */
static int hb_direction(void *m, int dir, double v0, double v1)
{
    hb_arc *a = m;
    ctx *c = a->c;
    c->dir = dir;
    c->v0 = v0;
    c->v1 = v1;
    c->want_H = 0;
    a->nb0 = c->res->nbifurcations;
    return dir < 0 && gd_per_hb_setup(c, a->H0);
}

/* A contact law's zigzags of folds merged into one turn, for the direction's branch. */
static void hb_branch_end(void *m)
{
    hb_arc *a = m;
    gd_per_merge_zigzags(a->c, a->nb0);
}

const gd_per_arc_ops gd_per_hb_ops = {.size = hb_size,
                                      .step = hb_step,
                                      .begin = NULL,
                                      .prepare = hb_prepare,
                                      .cold = hb_cold,
                                      .cold_name = "rest",
                                      .start = hb_start,
                                      .correct = hb_correct,
                                      .tangent = hb_tangent,
                                      .direction = hb_direction,
                                      .branch_end = hb_branch_end,
                                      .give_up = NULL,
                                      .measure = hb_measure,
                                      .solve_at = hb_solve_at,
                                      .emit = hb_emit,
                                      .fail = hb_fail,
                                      .detect = gd_per_hb_detect,
                                      /* none: docs/periodic.md, "Continuation" */
                                      .between = NULL,
                                      .rescale = hb_rescale,
                                      .grow = hb_grow};

/* Both directions' branch of harmonic balance by the shared drivers, its operations ops
 * (the method table's row), H0 the first H. 0 done, 1 an error. */
int gd_per_run_branch(ctx *c, const gd_per_arc_ops *ops, const double *vals, int nv, int H0)
{
    hb_arc a = {.c = c, .H0 = H0};
    const size_t nm = 2 * (size_t)c->nf;
    int rc = 1;
    a.mre = malloc(nm * sizeof *a.mre);
    a.mim = malloc(nm * sizeof *a.mim);
    a.mre1 = malloc(nm * sizeof *a.mre1);
    a.mim1 = malloc(nm * sizeof *a.mim1);
    if (a.mre && a.mim && a.mre1 && a.mim1) {
        const gd_per_arc br = {.ops = ops,
                               .m = &a,
                               .why = c->reason,
                               .why_cap = sizeof c->reason,
                               .speed = !c->param,
                               .max_steps = c->opt->max_steps,
                               .on_step = c->opt->on_step,
                               .user = c->opt->user,
                               .dsmin = 1e-7,
                               .corners = c->corners};
        rc = gd_per_directions(&br, vals, nv, c->opt->both_directions,
                               c->opt->method == GD_PER_SEQUENTIAL);
    }
    free(a.mre);
    free(a.mim);
    free(a.mre1);
    free(a.mim1);
    return rc;
}
