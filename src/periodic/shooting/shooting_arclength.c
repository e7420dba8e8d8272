/* Shooting's row of the method table (method.h): the entry gd_per_shoot_method and its
 * operations gd_per_sh_ops, which the shared drivers (driver/: the first point, --sequential,
 * the pseudo-arclength) call.
 *
 * Pseudo-arclength continuation of shooting's orbits (docs/periodic.md, "Shooting"; Keller
 * 1977, Seydel 2010 Sec. 4.5): the unknowns are the initial state y0 and the value lambda
 * (speed or parameter), the equations
 *
 *   F(y0; lambda) = P(y0; lambda) - y0 = 0,   t . ((y0, lambda) - (y_p, lambda_p)) = 0,
 *
 * the second the hyperplane through the predictor y_p = y + ds t normal to the unit tangent
 * t. The bordered Newton corrector takes dF/dy0 = Phi - I from the monodromy
 * (gd_transient_monodromy, the saltation matrices included) and dF/dlambda by a forward
 * difference of the period map (the problem at lambda + dl, with its own period T), both in
 * the variables scaled as harmonic balance's continuation scales them: each block of y0
 * (displacements, velocities) by its largest entry, lambda by the requested range. The
 * predictor, the step control, the turn limit and the outputs at the requested values (a
 * Newton at that fixed value from the step's interpolate) are the shared driver's
 * (arclength.c), over the operations defined here (method.h). The fold rule: where the
 * tangent's lambda component changes sign. Folds, period doublings, Neimark-Sacker and branch
 * points are located on the branch between two steps by Illinois iterations over points of the
 * branch (each a corrector on the hyperplane normal to the chord), on the tangent's lambda
 * component or on the critical multiplier's modulus minus 1.
 *
 * Above --shoot-dense-max states (sh->dense 0) nothing dense is formed: the bordered system
 * is solved by GMRES (gd_per_sh_gmres) on the products of [D^-1 (Phi - I) D, f; row^T] with a
 * vector, each Phi z one period integrated about the point (the Newton-Krylov path's
 * products), for the corrector (to 1e-3, inexact Newton) and for the tangent (to 1e-6);
 * the multipliers are then the Ritz values of Arnoldi on Phi (gd_per_sh_multipliers). */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/method.h"
#include "periodic/shooting/shooting_impl.h"

/* The branch's scales and work arrays. */
typedef struct arc {
    shoot *sh;
    int N;
    double sl;                       /* scale of lambda: the requested range */
    double *D;                       /* N: the block scales of y (gd_per_sh_scales; the driver's) */
    double *Dold;                    /* N: the last scales (rescale) */
    double *Fl;                      /* N: dF/dlambda at the last point */
    double *J;                       /* (N + 1)^2: dense only */
    double *b;                       /* N + 1 */
    double *P2;                      /* N */
    int *ipiv;                       /* N + 1 */
    int kry;                         /* matrix-free (sh->dense 0) */
    double *f;                       /* N: the border D^-1 Fl sl (Krylov) */
    double *x;                       /* N + 1: GMRES's solution (Krylov) */
    double *pt;                      /* N: the products' work (Krylov) */
    double *mre, *mim, *mre1, *mim1; /* N each: the step's start's and end's multipliers */
    int nmu, nmu1;                   /* their counts (0: none) */
    int fails;                       /* failed steps since the last one taken */
    double lam_ok;                   /* the value of the last point of the branch */
} arc;

/* Failed steps in a row (each a corrector of up to max_iter monodromies, the step halved
 * after each) after which the branch stops: a rattling idler's stable branch
 * (examples/rattle_idle.yaml) ends near 64.8 rad/s in a fold its corrector cannot pass
 * (30 iterations at residual 5e-4, then a jump to -53 rad/s), and halving on to dsmin took
 * minutes of CPU at about 5 s a failed step; a count, never a clock. */
#define ARC_FAILS 6

/* P(y) at lam into sh->yT, and (dense) the monodromy into sh->phi. 0 ok. */
static int evaluate(arc *a, const double *y, double lam)
{
    shoot *sh = a->sh;
    if (gd_per_sh_problem(sh, lam)) return 1;
    return a->kry ? gd_per_sh_period(sh, y, sh->yT) : gd_per_sh_monodromy(sh, y, sh->phi, sh->yT);
}

/* dF/dlambda at (y, lam) into a->Fl, py = P(y; lam) given: a forward difference over dl =
 * sqrt(rtol) of the larger of |lam| and 1e-3 of the range (the truncation error and the
 * integration noise balance there, as for the monodromy-vector products). The problem is
 * left at lam. 0 ok. */
static int d_lambda(arc *a, const double *y, double lam, const double *py)
{
    shoot *sh = a->sh;
    const double dl = sqrt(sh->rtol) * fmax(fabs(lam), 1e-3 * a->sl);
    if (gd_per_sh_problem(sh, lam + dl) || gd_per_sh_period(sh, y, a->P2)) return 1;
    for (int i = 0; i < a->N; i++)
        a->Fl[i] = (a->P2[i] - py[i]) / dl;
    return gd_per_sh_problem(sh, lam);
}

/* Solves the bordered system in scaled variables with the monodromy at the point y (whose
 * P(y) is sh->yT: dense, sh->phi) and a->Fl: [D^-1 (Phi - I) D, D^-1 Fl sl; row] x = a->b
 * (in place); matrix-free by GMRES to tol. 0 ok. */
static int bordered(arc *a, const double *y, const double *row, double tol)
{
    shoot *sh = a->sh;
    const int N = a->N, n1 = N + 1;
    if (a->kry) {
        for (int i = 0; i < N; i++)
            a->f[i] = a->Fl[i] * a->sl / a->D[i];
        kry k = {.y = y,
                 .py = sh->yT,
                 .d = a->D,
                 .yt = sh->yt,
                 .pt = a->pt,
                 .n = n1,
                 .shift = 1.0,
                 .f = a->f,
                 .row = row};
        /* restarts stop at the products' own error, about sqrt(rtol) relative (phi_vec):
         * below it a cycle only moves the solution within that noise (the backlash pair at
         * rtol 1e-7: the true residual after one cycle 1e-4 to 2e-3, after two and three
         * the same) */
        const double stop = fmax(tol, 10.0 * sqrt(sh->rtol));
        if (gd_per_sh_gmres(sh, &k, a->b, a->x, tol, stop * stop, 4)) return 1;
        memcpy(a->b, a->x, (size_t)n1 * sizeof *a->b);
        return 0;
    }
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            a->J[(size_t)j * n1 + i] =
                (sh->phi[(size_t)j * N + i] - (i == j ? 1.0 : 0.0)) * a->D[j] / a->D[i];
    for (int i = 0; i < N; i++)
        a->J[(size_t)N * n1 + i] = a->Fl[i] * a->sl / a->D[i];
    for (int j = 0; j <= N; j++)
        a->J[(size_t)j * n1 + N] = row[j];
    return LAPACKE_dgesv(LAPACK_COL_MAJOR, n1, 1, a->J, n1, a->ipiv, a->b, n1) != 0;
}

/* The bordered Newton from (y, *lam) on the hyperplane normal to tan (scaled, N + 1)
 * through yp (N + 1, unscaled: y then lambda). On success sh->phi is the monodromy at the
 * converged point and sh->yT its P(y). 0 converged; 1 not, with sh->why. */
static int corrector(arc *a, double *y, double *lam, const double *tan, const double *yp,
                     int *iters, double *resid)
{
    shoot *sh = a->sh;
    const int N = a->N, maxit = sh->opt->max_iter;
    double prev = INFINITY;
    int slow = 0;
    gd_per_sh_tolerances(sh, yp);
    for (int it = 0;; it++) {
        *iters = it;
        if (!(*lam > 0) && !sh->param) {
            snprintf(sh->why, sizeof sh->why, "the corrector left the positive speeds");
            return 1;
        }
        if (evaluate(a, y, *lam)) return 1;
        for (int i = 0; i < N; i++)
            sh->r[i] = sh->yT[i] - y[i];
        const double res = gd_per_sh_norm(sh, y, sh->r);
        *resid = res;
        double g = tan[N] * (*lam - yp[N]) / a->sl;
        for (int i = 0; i < N; i++)
            g += tan[i] * (y[i] - yp[i]) / a->D[i];
        if (res <= sh->tol && fabs(g) <= 1e-9) return 0;
        /* a residual that no longer halves is at the integrator's noise (contact events),
         * accepted below it as the fixed-value Newton accepts it */
        slow = res > 0.5 * prev ? slow + 1 : 0;
        if (slow >= 2 && fabs(g) <= 1e-9) {
            memcpy(sh->racc, sh->r, (size_t)N * sizeof *sh->racc);
            /* (matrix-free: P(y) came from the plain integration the noise test repeats) */
            if (res <= gd_per_sh_noise(sh, a->kry ? NULL : y)) return 0;
        }
        if (it >= maxit || (it > 3 && !(res < 1e3 * prev)) || slow >= 4) {
            snprintf(sh->why, sizeof sh->why,
                     "shooting (arclength): the corrector did not converge in %d iterations "
                     "(residual %.2g, tolerance %.2g)",
                     it, res, sh->tol);
            return 1;
        }
        prev = res;
        if (d_lambda(a, y, *lam, sh->yT)) return 1;
        for (int i = 0; i < N; i++)
            a->b[i] = -sh->r[i] / a->D[i];
        a->b[N] = -g;
        if (bordered(a, y, tan, 1e-3)) {
            /* (matrix-free: an integration failed or the budget ran out, sh->why says) */
            if (!a->kry)
                snprintf(sh->why, sizeof sh->why,
                         "shooting (arclength): singular bordered Jacobian");
            return 1;
        }
        for (int i = 0; i < N; i++)
            y[i] += a->b[i] * a->D[i];
        *lam += a->b[N] * a->sl;
    }
}

/* The unit tangent (scaled, N + 1) at a converged (y, lam) whose P(y) is sh->yT (dense:
 * its monodromy sh->phi): the bordered system with last row prev (NULL: e_lambda), right-hand side
 * e_{N+1}; oriented along prev, or so that lambda moves by sign. 0 ok. */
static int tangent(arc *a, const double *y, double lam, const double *prev, double sign, double *t)
{
    const int N = a->N;
    if (d_lambda(a, y, lam, a->sh->yT)) return 1;
    double *row = calloc((size_t)N + 1, sizeof *row);
    if (!row) return 1;
    if (prev)
        memcpy(row, prev, (size_t)(N + 1) * sizeof *row);
    else
        row[N] = 1.0;
    memset(a->b, 0, (size_t)N * sizeof *a->b);
    a->b[N] = 1.0;
    int rc = bordered(a, y, row, 1e-6);
    free(row);
    if (rc) return 1;
    double nt = 0.0, dot = 0.0;
    for (int i = 0; i <= N; i++)
        nt += a->b[i] * a->b[i];
    nt = sqrt(nt);
    if (!(nt > 0) || !isfinite(nt)) return 1;
    for (int i = 0; i <= N; i++) {
        t[i] = a->b[i] / nt;
        if (prev) dot += t[i] * prev[i];
    }
    if ((prev && dot < 0) || (!prev && t[N] * sign < 0))
        for (int i = 0; i <= N; i++)
            t[i] = -t[i];
    return 0;
}

/* The multipliers at the converged point y (dense: from its monodromy sh->phi, destroyed;
 * matrix-free: the Ritz values of Arnoldi on Phi), their count in *n. 0 ok. */
static int point_multipliers(arc *a, const double *y, double *mre, double *mim, int *n)
{
    shoot *sh = a->sh;
    double dummy[1];
    *n = 0;
    if (a->kry) {
        *n = gd_per_sh_multipliers(sh, y, mre, mim);
        if (*n >= 0) return 0;
        *n = 0;
        return 1;
    }
    if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', sh->N, sh->phi, sh->N, mre, mim, dummy, 1, dummy,
                      1))
        return 1;
    *n = sh->N;
    return 0;
}

/* A point of the branch between (ya, la) and (yb, lb) at fraction s of the chord ch
 * (scaled, unit): the corrector on the hyperplane normal to the chord through the
 * interpolate. 0 ok. */
static int between(arc *a, const double *ya, double la, const double *yb, double lb,
                   const double *ch, double s, double *y, double *lam)
{
    const int N = a->N;
    double *yp = malloc((size_t)(N + 1) * sizeof *yp);
    if (!yp) return 1;
    for (int i = 0; i < N; i++)
        yp[i] = y[i] = (1 - s) * ya[i] + s * yb[i];
    yp[N] = *lam = (1 - s) * la + s * lb;
    int it;
    double res;
    int rc = corrector(a, y, lam, ch, yp, &it, &res);
    free(yp);
    return rc;
}

/* What locate() zeroes along the branch: the tangent's lambda component (kind -1, a fold)
 * or the largest modulus of the multipliers of kind k (0 real positive, 1 real negative,
 * 2 complex) minus 1, with that multiplier in (re, im). */
static int criterion(arc *a, int kind, const double *y, double lam, const double *ta, double *tt,
                     double *g, double *re, double *im)
{
    shoot *sh = a->sh;
    if (kind < 0) {
        if (tangent(a, y, lam, ta, 1.0, tt)) return 1;
        *g = tt[a->N];
        return 0;
    }
    int n;
    if (point_multipliers(a, y, sh->mre, sh->mim, &n)) return 1;
    double gg[3];
    int at[3];
    gd_per_sh_kinds(sh->mre, sh->mim, n, gg, at);
    *g = gg[kind] - 1.0;
    *re = at[kind] >= 0 ? sh->mre[at[kind]] : NAN;
    *im = at[kind] >= 0 ? sh->mim[at[kind]] : NAN;
    return 0;
}

/* The zero of the criterion between two steps (ga, gb of opposite signs), located on the
 * branch by Illinois iterations on the fraction of the chord, until lambda moves by less
 * than 1e-8 relative (near a fold lambda is quadratic in the position, so the fold's value
 * is found far more precisely than the point; below that the integration noise moves it:
 * the backlash pair's folds at rtol 1e-7 wander by 4e-8 relative, and a stricter test took
 * 22 corrector solves per fold instead of 7). The located value, or NAN (a corrector or the
 * criterion failed first, or 40 points did not settle it); for a multiplier *off is its
 * distance |mu| - 1 there. */
static double locate(arc *a, int kind, const double *ya, double la, const double *ta, double ga,
                     const double *yb, double lb, double gb, double *re, double *im, double *off)
{
    const int N = a->N;
    double *ch = malloc((size_t)(3 * N + 2) * sizeof *ch), *y = ch + N + 1, *tt = y + N;
    double best = NAN;
    int located = 0;
    *off = INFINITY;
    if (!ch) return NAN;
    double nc = 0.0;
    for (int i = 0; i < N; i++) {
        ch[i] = (yb[i] - ya[i]) / a->D[i];
        nc += ch[i] * ch[i];
    }
    ch[N] = (lb - la) / a->sl;
    nc = sqrt(nc + ch[N] * ch[N]);
    if (!(nc > 0)) goto done;
    for (int i = 0; i <= N; i++)
        ch[i] /= nc;
    double s0 = 0.0, s1 = 1.0, g0 = ga, g1 = gb, sig = g0 / (g0 - g1), lprev = NAN;
    for (int it = 0; it < 40; it++) {
        if (!(sig > s0 && sig < s1)) sig = 0.5 * (s0 + s1);
        double lam, g, r = NAN, m = NAN;
        if (between(a, ya, la, yb, lb, ch, sig, y, &lam) ||
            criterion(a, kind, y, lam, ta, tt, &g, &r, &m))
            break;
        best = lam;
        if (kind >= 0) {
            *re = r;
            *im = m;
            *off = fabs(g);
        }
        if (fabs(lam - lprev) <= 1e-8 * fabs(lam) || g == 0.0 || s1 - s0 < 1e-14) {
            located = 1;
            break;
        }
        lprev = lam;
        sig = gd_per_illinois(sig, g, &s0, &g0, &s1, &g1);
    }
done:
    free(ch);
    return located ? best : NAN;
}

/* ------------------------------------------ shooting's operations for arclength.c */

static int op_size(void *m)
{
    return ((arc *)m)->N;
}

/* A point's solve begins: its budget, and no warm start seen yet (a budget message cites
 * only this point's). */
static void op_begin(void *m)
{
    shoot *sh = ((arc *)m)->sh;
    sh->work = 0.0;
    sh->t_mono = 0.0;
    sh->warm_change = NAN;
    sh->budget_hit = 0;
    sh->not_periodic = 0;
}

static void op_step(void *m)
{
    ((arc *)m)->sh->steps++;
    op_begin(m);
}

static int op_prepare(void *m, double v)
{
    return gd_per_sh_problem(((arc *)m)->sh, v);
}

/* A short transient from rest (or the static state under the loads), which a stable orbit
 * attracts, then Newton. */
static int op_cold(void *m, double **y, double v, int *it, double *res)
{
    shoot *sh = ((arc *)m)->sh;
    (void)v;
    return gd_per_sh_warm(sh, *y) || gd_per_sh_newton(sh, *y, it, res);
}

static int op_between(void *m, const double *ya, double la, const double *yb, double lb)
{
    return gd_per_sh_between(((arc *)m)->sh, ya, la, yb, lb);
}

/* The start's multipliers (the crossings compare like with like), its scales and tangent. */
static int op_start(void *m, const double *y, double lam, double sign, double sl, double *D,
                    double *t)
{
    arc *a = m;
    shoot *sh = a->sh;
    const gd_periodic_point *p0 = &sh->res->points[sh->res->npoints - 1];
    a->nmu = sh->opt->stability ? p0->nmult : 0;
    if (sh->opt->stability && a->kry && p0->converged &&
        (p0->stable < 0 || a->nmu > (a->N < KRYLOV_M ? a->N : KRYLOV_M))) {
        /* the start's verdict took Arnoldi to every state, or had none: the crossings
         * compare the same KRYLOV_M Ritz values as every step's */
        if (point_multipliers(a, y, a->mre, a->mim, &a->nmu)) a->nmu = 0;
    } else if (a->nmu) {
        memcpy(a->mre, p0->mu_re, (size_t)a->nmu * sizeof *a->mre);
        memcpy(a->mim, p0->mu_im, (size_t)a->nmu * sizeof *a->mim);
    }
    a->sl = sl;
    a->fails = 0;
    a->lam_ok = lam;
    a->D = D;
    gd_per_sh_tolerances(sh, y);
    gd_per_sh_scales(sh, y, a->D);
    if (evaluate(a, y, lam) || tangent(a, y, lam, NULL, sign, t)) {
        snprintf(sh->why, sizeof sh->why, "shooting (arclength): no tangent at the start");
        return 1;
    }
    return 0;
}

static int op_correct(void *m, double *y, double *lam, const double *t, const double *yp, int *it,
                      double *res)
{
    return corrector(m, y, lam, t, yp, it, res);
}

static int op_tangent(void *m, const double *y, double lam, const double *prev, double sign,
                      double *t)
{
    return tangent(m, y, lam, prev, sign, t);
}

static int op_direction(void *m, int dir, double v0, double v1)
{
    shoot *sh = ((arc *)m)->sh;
    sh->dir = dir;
    sh->v0 = v0;
    sh->v1 = v1;
    return 0;
}

static int op_give_up(void *m)
{
    arc *a = m;
    shoot *sh = a->sh;
    if (sh->budget_hit) return 1;
    if (++a->fails < ARC_FAILS) return 0;
    char last[160];
    snprintf(last, sizeof last, "%.150s", sh->why);
    snprintf(sh->why, sizeof sh->why,
             "the branch stops at %.6g%s after %d failed steps in a row; --sequential solves "
             "each value alone (the last: %.100s)",
             a->lam_ok, sh->param && !sh->param->load_frequency ? "" : " rad/s", ARC_FAILS, last);
    return 1;
}

/* The multipliers at the step (dense: sh->phi is its monodromy). */
static void op_measure(void *m, const double *y1, double l1)
{
    arc *a = m;
    a->fails = 0;
    a->lam_ok = l1;
    if (a->nmu && point_multipliers(a, y1, a->mre1, a->mim1, &a->nmu1)) a->nmu1 = 0;
}

static int op_solve_at(void *m, double *y, double v, int *it, double *res)
{
    shoot *sh = ((arc *)m)->sh;
    return gd_per_sh_problem(sh, v) || gd_per_sh_newton(sh, y, it, res);
}

static int op_emit(void *m, const double *y, double v, int it, double res)
{
    return gd_per_sh_emit(((arc *)m)->sh, v, y, it, res);
}

static int op_fail(void *m, double v)
{
    return gd_per_sh_fail(((arc *)m)->sh, v);
}

/* A fold where the tangent's lambda component changes sign, and multipliers through the
 * unit circle: a real one through -1 (period doubling), a complex pair (Neimark-Sacker), a
 * real one through +1 away from a fold (a branch point), each located on the branch and
 * reported when |mu| is 1 to 1e-4 there. */
static int op_detect(void *m, const gd_per_arc_step *s)
{
    arc *a = m;
    shoot *sh = a->sh;
    const int N = a->N;
    const double *y = s->y, *y1 = s->y1, *t = s->t, *t1 = s->t1, lam = s->lam, l1 = s->l1;
    int fold = 0;
    if (t[N] * t1[N] < 0) {
        double off, re, im;
        double lf = locate(a, -1, y, lam, t, t[N], y1, l1, t1[N], &re, &im, &off);
        if (isnan(lf)) { /* not located: the extremum of the cubic through the steps */
            const double ds = s->ds, sq = t[N] / (t[N] - t1[N]), s2 = sq * sq, s3 = s2 * sq;
            lf = (2 * s3 - 3 * s2 + 1) * lam + (s3 - 2 * s2 + sq) * ds * t[N] * a->sl +
                 (-2 * s3 + 3 * s2) * l1 + (s3 - s2) * ds * t1[N] * a->sl;
        }
        fold = 1;
        if (gd_per_sh_add_bif(sh, GD_BIF_FOLD, lf, NAN, NAN)) return -1;
    }
    if (a->nmu && a->nmu1) {
        double ga[3], gb[3];
        int aa[3], ab[3];
        gd_per_sh_kinds(a->mre, a->mim, a->nmu, ga, aa);
        gd_per_sh_kinds(a->mre1, a->mim1, a->nmu1, gb, ab);
        static const gd_bifurcation_type type[3] = {GD_BIF_BRANCH_POINT, GD_BIF_PERIOD_DOUBLING,
                                                    GD_BIF_NEIMARK_SACKER};
        for (int k = 0; k < 3; k++) {
            if ((ga[k] > 1.0) == (gb[k] > 1.0) || (k == 0 && (fold || s->fold_prev))) continue;
            double re = NAN, im = NAN, off;
            double lx = locate(a, k, y, lam, t, ga[k] - 1.0, y1, l1, gb[k] - 1.0, &re, &im, &off);
            if (!isnan(lx) && off < 1e-4 &&
                gd_per_sh_add_bif(sh, type[k], lx, k == 0 ? NAN : re, k == 0 ? NAN : im))
                return -1;
        }
    }
    if (a->nmu) {
        a->nmu = a->nmu1;
        memcpy(a->mre, a->mre1, (size_t)N * sizeof *a->mre);
        memcpy(a->mim, a->mim1, (size_t)N * sizeof *a->mim);
    }
    return fold;
}

/* The scales follow the orbit's size: the tangent re-expressed in them. */
static void op_rescale(void *m, const double *y, double *D, double *t)
{
    arc *a = m;
    const int N = a->N;
    double nt = t[N] * t[N];
    memcpy(a->Dold, D, (size_t)N * sizeof *D);
    gd_per_sh_tolerances(a->sh, y);
    gd_per_sh_scales(a->sh, y, D);
    for (int i = 0; i < N; i++) {
        t[i] *= a->Dold[i] / D[i];
        nt += t[i] * t[i];
    }
    nt = sqrt(nt);
    for (int i = 0; i <= N; i++)
        t[i] /= nt;
}

const gd_per_arc_ops gd_per_sh_ops = {.size = op_size,
                                      .step = op_step,
                                      .begin = op_begin,
                                      .prepare = op_prepare,
                                      .cold = op_cold,
                                      .cold_name = "a transient",
                                      .start = op_start,
                                      .correct = op_correct,
                                      .tangent = op_tangent,
                                      .direction = op_direction,
                                      .branch_end = NULL,
                                      .give_up = op_give_up,
                                      .measure = op_measure,
                                      .solve_at = op_solve_at,
                                      .emit = op_emit,
                                      .fail = op_fail,
                                      .detect = op_detect,
                                      .between = op_between,
                                      .rescale = op_rescale,
                                      .grow = NULL};

/* Both directions' branch by the shared drivers (method.h) over ops. 0 done, 1 out of
 * memory. */
static int branch(shoot *sh, const gd_per_arc_ops *ops, const double *vals, int nv)
{
    /* the state's size and the dense or matrix-free path from the first problem that can
     * be made (none: every value fails with its reason, by the driver) */
    for (int k = 0; k < nv && gd_per_sh_problem(sh, vals[k]); k++)
        ;
    const int N = sh->N;
    int rc = 1;
    arc a = {.sh = sh, .N = N, .kry = !sh->dense};
    /* Fl, P2, Dold, b (N + 1), J (dense) or f, x (N + 1) and pt (Krylov), multipliers 4 N */
    const size_t nJ = a.kry ? 3 * (size_t)N + 1 : (size_t)(N + 1) * (N + 1);
    double *w = malloc(((size_t)8 * N + 1 + nJ) * sizeof *w);
    a.ipiv = malloc((size_t)(N + 1) * sizeof *a.ipiv);
    if (!w || !a.ipiv) goto done;
    a.Fl = w;
    a.P2 = a.Fl + N;
    a.Dold = a.P2 + N;
    a.b = a.Dold + N;
    a.J = a.b + N + 1;
    a.mre = a.J + nJ;
    a.mim = a.mre + N;
    a.mre1 = a.mim + N;
    a.mim1 = a.mre1 + N;
    if (a.kry) {
        a.f = a.J;
        a.x = a.f + N;
        a.pt = a.x + N + 1;
        a.J = NULL;
    }
    const gd_per_arc br = {.ops = ops,
                           .m = &a,
                           .why = sh->why,
                           .why_cap = sizeof sh->why,
                           .speed = !sh->param,
                           .max_steps = sh->opt->max_steps,
                           .on_step = sh->opt->on_step,
                           .user = sh->opt->user,
                           .dsmin = 1e-6,
                           .corners = 0};
    rc = gd_per_directions(&br, vals, nv, sh->opt->both_directions,
                           sh->opt->method == GD_PER_SEQUENTIAL);
done:
    free(w);
    free(a.ipiv);
    return rc;
}

/* The method table's row for shooting (method.h): both directions by the shared drivers
 * over ops. */
gd_status gd_per_shoot_method(const gd_per_arc_ops *ops, const gd_system *sys,
                              const gd_transient_spec *spec, const gd_periodic_param *param,
                              const double *values, int nvalues, const gd_periodic_options *opt,
                              const gd_tr_record *records, int nrecords, gd_periodic_result *res,
                              gd_error *err)
{
    shoot sh;
    memset(&sh, 0, sizeof sh);
    sh.sys0 = sys;
    sh.spec0 = spec;
    sh.param = param;
    sh.opt = opt;
    sh.rec = records;
    sh.nrec = nrecords;
    sh.res = res;
    sh.ndir = opt->both_directions ? 2 : 1;
    const int rc = branch(&sh, ops, values, nvalues);
    res->steps += sh.steps;
    gd_per_sh_free(&sh);
    if (rc) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    return GD_OK;
}
