/* Harmonic balance's bifurcation rules (continuation_impl.h; its row's, method_table.c):
 * between two arclength steps (gd_per_hb_detect, the driver's detect), the critical
 * multiplier's modulus through 1 located by secant iterations on points of the branch
 * (period doubling, Neimark-Sacker, branch point), folds at the parameter's extremum
 * where it turns (a contact law's at the highest tooth of the sampled saw), and close runs
 * of folds merged into one turn. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/continuation_impl.h"
#include "periodic/method.h"
#include "periodic/periodic_impl.h"

/* multiplier categories outside the unit circle: 0 real > 0, 1 real < 0, 2 complex;
 * rho[k]: largest modulus in category k (NaN if none) */
void gd_per_categorise(const ctx *c, const double *mre, const double *mim, int out[3],
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

int gd_per_add_bif(ctx *c, gd_bifurcation_type type, double lam, double mre, double mim)
{
    gd_periodic_result *r = c->res;
    /* a real multiplier through +1 next to a fold is the fold itself (located a step
     * apart when the fold falls near a step end). With a contact law the sampled branch
     * zigzags near its turn (a tooth per sample switching contact) and the multiplier
     * crosses +1 at a tooth, not at the turn: there "next to" is the zigzag's reach (1 %
     * of the range, as gd_per_merge_zigzags; the backlash pair at H = 20, 128 samples
     * and 26 speeds: the crossing at 479.23 rad/s, the turn at 480.38, the crossing
     * reported as a branch point before) */
    const double near = (c->min_samples > 0 ? 1e-2 : 1e-3) * (c->sl > 0 ? c->sl : 1.0);
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
    int rc = gd_per_newton(c, X, lam, tan, yp, &it, &res);
    free(yp);
    return rc;
}

/* The m-th largest multiplier modulus (m >= 1) and its index. */
double gd_per_ranked(const ctx *c, const double *mre, const double *mim, int m, int *at)
{
    int nm = 2 * c->nf, used[512] = {0};
    /* Krylov: at most 257 found; reduced: 2 r; largest first, then 0 */
    if (nm > 512 && (c->floquet_krylov || c->floquet_basis)) nm = 512;
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

/* The point of the branch at fraction sig between the steps, accepted only near the
 * step: the corrector moved it no farther from its start (the chord's interpolate) than
 * the chord is long, scaled as the tangent (a corrector that went farther jumped to
 * another part of the branch). 0 ok; 1 failed or jumped. */
static int point_near(ctx *c, const double *Xa, double la, const double *Xb, double lb,
                      const double *tan, double sig, double *X, double *lam)
{
    const int n = c->h.n;
    if (point_between(c, Xa, la, Xb, lb, tan, sig, X, lam)) return 1;
    double d = 0.0, h = 0.0;
    for (int i = 0; i < n; i++) {
        const double e = (X[i] - ((1 - sig) * Xa[i] + sig * Xb[i])) / c->sx,
                     f = (Xb[i] - Xa[i]) / c->sx;
        d += e * e;
        h += f * f;
    }
    const double el = (*lam - ((1 - sig) * la + sig * lb)) / c->sl, fl = (lb - la) / c->sl;
    return !(d + el * el <= h + fl * fl);
}

/* A multiplier crossed the unit circle between two steps (m - 1 outside on one side, m on
 * the other): regula falsi (Illinois) on |mu|_(m) - 1, the m-th largest modulus, over
 * points of the branch between the steps (the fraction sig of the chord, each point a
 * corrector on the hyperplane normal to the tangent through the chord's interpolate), the
 * bracket [s0, s1] of sig kept: where the Illinois step leaves it, or its corrector fails or
 * jumps off the step (point_near), the step is a bisection of the bracket instead, and
 * where that fails too the search stops. Located when the parameter at the bracket's two
 * ends agrees to 1e-8 relative or |mu| - 1 is below 1e-10 (refined on until either, or
 * the parameter to 1e-10, within 40 points). The parameter of a point can
 * lie just outside the steps' [la, lb] when a fold lies between the steps (the Chen SFD
 * pair at e_u/C = 1/2: the real multiplier through +1 at its fold, 5549.14735 rad/s, found
 * between steps at 5548.178 and 5549.136 with |mu| - 1 = 4e-7; before, a point outside
 * was replaced by the linear interpolate between the steps). The type from the crossing multiplier
 * at the located point: real > 0 branch point (a fold is reported by its tangent), real < 0 period
 * doubling, complex Neimark-Sacker. */
int gd_per_locate(ctx *c, int m, const double *Xa, double la, double ga, const double *Xb,
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
    /* the bracket: fractions s0, s1, their |mu| - 1 (Illinois-scaled) and parameters */
    double s0 = 0.0, s1 = 1.0, g0 = ga, g1 = gb, l0 = la, l1 = lb, lam = NAN;
    int at;
    gd_per_ranked(c, mre_b, mim_b, m, &at);
    double best_re = at >= 0 ? mre_b[at] : NAN, best_im = at >= 0 ? fabs(mim_b[at]) : NAN;
    int ok = isfinite(g0) && isfinite(g1) && (g0 < 0) != (g1 < 0), located = 0;
    double sig = ok ? -g0 / (g1 - g0) : 0.5;
    for (int it = 0; it < 40 && ok; it++) {
        int bisect = !(sig > s0 && sig < s1);
        if (bisect) sig = 0.5 * (s0 + s1);
        double l;
        int bad = point_near(c, Xa, la, Xb, lb, tan, sig, X, &l);
        if (bad && !bisect) { /* the Illinois point failed or jumped: bisection instead */
            sig = 0.5 * (s0 + s1);
            bad = point_near(c, Xa, la, Xb, lb, tan, sig, X, &l);
        }
        if (bad) break;
        int stable;
        double mu_max;
        gd_per_floquet(c, X, l, mre, mim, &stable, &mu_max);
        if (stable < 0) break;
        double g = gd_per_ranked(c, mre, mim, m, &at) - 1.0;
        if (!isfinite(g) || at < 0) break;
        lam = l;
        best_re = mre[at];
        best_im = fabs(mim[at]);
        if (fabs(g) < 1e-10) {
            located = 1;
            break;
        }
        const double s_in = sig;
        sig = gd_per_illinois(sig, g, &s0, &g0, &s1, &g1);
        if (s0 == s_in)
            l0 = l;
        else
            l1 = l;
        /* located once the bracket holds the parameter to 1e-8; refined on to 1e-10 (or
         * |mu| - 1 below 1e-10) as long as the iterations allow */
        located = fabs(l1 - l0) <= 1e-8 * fabs(l);
        if (fabs(l1 - l0) <= 1e-10 * fabs(l)) break;
    }
    double a = hypot(best_re, best_im);
    gd_bifurcation_type type = best_im > 1e-9 * a ? GD_BIF_NEIMARK_SACKER
                               : best_re < 0      ? GD_BIF_PERIOD_DOUBLING
                                                  : GD_BIF_BRANCH_POINT;
    int rc = 0;
    /* reported only when located, with the critical multiplier on the circle to 1e-4: a
     * search that cannot close in on it (a corrector that fails in the whole bracket,
     * several multipliers moving at once) says nothing rather than something wrong */
    if (!(type == GD_BIF_BRANCH_POINT && c->near_fold) && located && fabs(a - 1.0) < 1e-4)
        rc = gd_per_add_bif(c, type, lam, best_re, best_im);
    free(X);
    free(mre);
    free(mim);
    return rc;
}

/* The point at s in [0, 2] of the path P -> X -> X1 (pt[0..2], their parameters l):
 * Newton on the hyperplane normal to the chord (ch[0]: P -> X, ch[1]: X -> X1) through
 * the chord's interpolate. */
static int path_point(ctx *c, const double *const pt[3], const double l[3], double *const ch[2],
                      double s, double *Y, double *lam)
{
    const int k = s < 1.0 ? 0 : 1;
    return point_between(c, pt[k], l[k], pt[k + 1], l[k + 1], ch[k], s - k, Y, lam);
}

/* The bracket of gd_per_locate_turn: x[1] < x[2] < x[3] with f[2] the best, and the
 * next evaluated points beyond them (x[0] < x[1], x[4] > x[3]; NaN: none). */
typedef struct brk {
    double x[5], f[5];
} brk;

/* Evaluates the path at x and updates the bracket (and Yb, ub with a new best). */
static int probe(ctx *c, const double *const pt[3], const double lv[3], double *const ch[2],
                 double sg, double x, double *Y, double *Yb, double *ub, brk *k)
{
    const int n = c->h.n;
    double lam;
    if (path_point(c, pt, lv, ch, x, Y, &lam)) return 1;
    const double fx = sg * lam;
    if (fx > k->f[2] && Yb) {
        memcpy(Yb, Y, (size_t)n * sizeof *Yb);
        Yb[n] = lam;
        memcpy(ub, ch[x < 1.0 ? 0 : 1], (size_t)(n + 1) * sizeof *ub);
    }
    int at; /* where x goes: 1 (new a), 2 (new best), 3 (new e) */
    if (fx > k->f[2]) {
        at = 2;
        if (x < k->x[2]) { /* b becomes e */
            k->x[4] = k->x[3];
            k->f[4] = k->f[3];
            k->x[3] = k->x[2];
            k->f[3] = k->f[2];
        } else { /* b becomes a */
            k->x[0] = k->x[1];
            k->f[0] = k->f[1];
            k->x[1] = k->x[2];
            k->f[1] = k->f[2];
        }
    } else if (x < k->x[2]) {
        at = 1;
        k->x[0] = k->x[1];
        k->f[0] = k->f[1];
    } else {
        at = 3;
        k->x[4] = k->x[3];
        k->f[4] = k->f[3];
    }
    k->x[at] = x;
    k->f[at] = fx;
    return 0;
}

/* The fold at a turn of the parameter: l[1] (the point X) beyond both neighbours P and
 * X1 (l[0], l[2]), so the path P -> X -> X1 of the branch holds an extremum of the
 * parameter. Located by golden-section steps mixed with parabolic ones (every other
 * step golden, so the bracket shrinks by 0.618 at least every two steps) on the
 * parameter along that path: on a smooth branch the parabola converges to the zero of
 * the tangent's parameter component; at a corner of a sampled non-smooth branch (a
 * sample switching contact) the parameter is only piecewise smooth and the tangent
 * jumps over zero, and golden section still closes in on the corner. Stops when both
 * ends of the bracket are within 1e-12 of the best value (relative to it): at a corner
 * the parameter is linear in the path, so the bracket is then 1e-12 / slope wide; at a
 * smooth fold it is quadratic, and the best value is exact to far below that. The value
 * depends on the branch only, not on where the steps fell. *lf receives the best value
 * found (l[1] if no refinement could run); Yb (if not NULL) its state (n + 1, the
 * parameter last) and ub the unit direction of the path there (scaled as the tangent);
 * 0: located, 1: a corrector failed first (*lf is then the best so far), -1 out of
 * memory. */
int gd_per_locate_turn(ctx *c, const double *Xp, double lp, const double *X, double l,
                       const double *X1, double l1, double *lf, double *Yb, double *ub)
{
    const int n = c->h.n;
    const double *const pt[3] = {Xp, X, X1};
    const double lv[3] = {lp, l, l1};
    const double sg = l >= lp ? 1.0 : -1.0; /* +1: a maximum */
    double *ch[2] = {malloc((size_t)(n + 1) * sizeof(double)),
                     malloc((size_t)(n + 1) * sizeof(double))};
    double *Y = malloc((size_t)(n + 1) * sizeof *Y);
    *lf = l;
    int rc = -1;
    if (!ch[0] || !ch[1] || !Y) goto done;
    for (int k = 0; k < 2; k++) {
        for (int i = 0; i < n; i++)
            ch[k][i] = (pt[k + 1][i] - pt[k][i]) / c->sx;
        ch[k][n] = (lv[k + 1] - lv[k]) / c->sl;
        double nc = gd_per_norm2(ch[k], n + 1);
        if (!(nc > 0)) {
            rc = 1;
            goto done;
        }
        for (int i = 0; i <= n; i++)
            ch[k][i] /= nc;
    }
    if (Yb) {
        memcpy(Yb, X, (size_t)n * sizeof *Yb);
        Yb[n] = l;
        memcpy(ub, ch[1], (size_t)(n + 1) * sizeof *ub);
    }
    brk k = {{NAN, 0.0, 1.0, 2.0, NAN}, {NAN, sg * lp, sg * l, sg * l1, NAN}};
    const double gold = 0.3819660112501051; /* 2 - golden ratio */
    rc = 0;
    for (int it = 0; it < 200 && !rc; it++) {
        const double a = k.x[1], b = k.x[2], e = k.x[3], fa = k.f[1], fb = k.f[2], fe = k.f[3];
        const double tol = 1e-12 * fabs(fb) + 1e-300;
        if ((fb - fa <= tol && fb - fe <= tol) || e - a < 1e-15) break;
        double x = NAN, slope = 0.0;
        if (it % 3 == 1) { /* a kink: the lines through the neighbours on either side */
            double pf = -INFINITY;
            for (int side = 0; side < 2; side++) {
                /* side 0: the kink right of b (lines a-b and e-e2); 1: left (a2-a, b-e) */
                const int l0 = side ? 0 : 1, r0 = side ? 2 : 3;
                if (isnan(k.x[l0]) || isnan(k.x[r0 + 1])) continue;
                const double sL = (k.f[l0 + 1] - k.f[l0]) / (k.x[l0 + 1] - k.x[l0]);
                const double sR = (k.f[r0 + 1] - k.f[r0]) / (k.x[r0 + 1] - k.x[r0]);
                if (!(sL > 0 && sR < 0)) continue;
                const double xk =
                    (k.f[r0] - k.f[l0 + 1] + sL * k.x[l0 + 1] - sR * k.x[r0]) / (sL - sR);
                const double fk = k.f[l0 + 1] + sL * (xk - k.x[l0 + 1]);
                if (xk > (side ? a : b) && xk < (side ? b : e) && fk > pf) {
                    x = xk;
                    pf = fk;
                    slope = fmax(sL, -sR);
                }
            }
        } else if (it % 3 == 2) { /* the vertex of the parabola through the three */
            double p = (b - a) * (b - a) * (fb - fe) - (b - e) * (b - e) * (fb - fa);
            double q = (b - a) * (fb - fe) - (b - e) * (fb - fa);
            if (q != 0.0) x = b - 0.5 * p / q;
            /* inside, and not on top of the best point */
            const double gap = 1e-3 * (e - a);
            if (!(x > a + gap && x < e - gap && fabs(x - b) > gap)) x = NAN;
        }
        if (isnan(x)) /* golden section of the longer side */
            x = b - a > e - b ? b - gold * (b - a) : b + gold * (e - b);
        rc = probe(c, pt, lv, ch, sg, x, Y, Yb, ub, &k);
        if (slope > 0 && !rc) {
            /* a kink estimate: its neighbours within the tolerance, so that a right
             * one closes the bracket at once */
            const double d = 0.5 * tol / slope;
            if (x - d > k.x[1] && x - d < k.x[3])
                rc = probe(c, pt, lv, ch, sg, x - d, Y, Yb, ub, &k);
            if (!rc && x + d > k.x[1] && x + d < k.x[3])
                rc = probe(c, pt, lv, ch, sg, x + d, Y, Yb, ub, &k);
        }
    }
    const double fb = k.f[2];
    *lf = sg * fb;
done:
    free(ch[0]);
    free(ch[1]);
    free(Y);
    return rc;
}

/* The highest tooth of a sampled contact law's turn. Near its turn the branch of a
 * contact law sampled at N points is a saw: a tooth for every sample that switches
 * contact, the parameter rising along each and dropping at its end (NLvib's example 03
 * at 1024 samples: teeth 7e-5 deep, the top ones 4e-7 apart), so the turn located from
 * the steps is the tooth they came near, and moves with the grid. From the located
 * tooth (Y0: state and parameter, u0 the branch's direction there) the branch is walked
 * both ways in steps of h (scaled arclength), every tooth it passes located
 * (gd_per_locate_turn), until three teeth in a row are no higher than the best, the
 * parameter fell back by ten times the deepest tooth (1 % of the range if none), or 32
 * steps (two continuation steps) passed no tooth (a smooth turn, the located one):
 * *best receives the highest. 0 ok, -1 out of memory. */
int gd_per_climb_teeth(ctx *c, const double *Y0, const double *u0, double h, double sg,
                       double *best)
{
    const int n = c->h.n;
    double *buf = malloc(5 * (size_t)(n + 1) * sizeof *buf);
    if (!buf) return -1;
    double *Ya = buf, *Yb = buf + (n + 1), *Yc = buf + 2 * (n + 1), *u = buf + 3 * (n + 1),
           *yp = buf + 4 * (n + 1);
    for (int side = -1; side <= 1; side += 2) {
        memcpy(Yb, Y0, (size_t)(n + 1) * sizeof *Yb);
        for (int i = 0; i <= n; i++)
            u[i] = side * u0[i];
        int have_a = 0, stale = 0, teeth = 0;
        double depth = 0.0, top = sg * Y0[n], low = top; /* the last tooth, lowest since */
        for (int k = 0; k < 400; k++) {
            for (int i = 0; i < n; i++)
                Yc[i] = yp[i] = Yb[i] + h * u[i] * c->sx;
            double lc = yp[n] = Yb[n] + h * u[n] * c->sl;
            int it;
            double res;
            if (gd_per_newton(c, Yc, &lc, u, yp, &it, &res)) break;
            Yc[n] = lc;
            double nc = 0.0, dot = 0.0;
            for (int i = 0; i < n; i++) {
                double d = (Yc[i] - Yb[i]) / c->sx;
                nc += d * d;
                dot += d * u[i];
            }
            nc += (lc - Yb[n]) * (lc - Yb[n]) / (c->sl * c->sl);
            dot += u[n] * (lc - Yb[n]) / c->sl;
            if (!(nc > 0) || dot <= 0.0) break; /* fell back: not the same branch */
            nc = sqrt(nc);
            for (int i = 0; i < n; i++)
                u[i] = (Yc[i] - Yb[i]) / c->sx / nc;
            u[n] = (lc - Yb[n]) / c->sl / nc;
            const double fa = sg * Ya[n], fb = sg * Yb[n], fc = sg * lc;
            if (have_a && fb > fa && fb >= fc) { /* a tooth at Yb */
                teeth++;
                /* its top lies within a step's rise of Yb (linear sides at most):
                 * located only if that could beat the best */
                double v = Yb[n];
                if (fb + fmax(fb - fa, fb - fc) > sg * *best &&
                    gd_per_locate_turn(c, Ya, Ya[n], Yb, Yb[n], Yc, lc, &v, NULL, NULL) < 0) {
                    free(buf);
                    return -1;
                }
                if (sg * v > sg * *best) {
                    *best = v;
                    stale = 0;
                } else {
                    stale++;
                }
                if (top - low > depth) depth = top - low;
                top = low = sg * v;
                if (stale >= 3) break;
            }
            if (fc < low) low = fc;
            if (!teeth && k >= 32) break; /* two steps and no tooth: a smooth turn */
            const double drop = depth > 0 ? 10 * depth : 1e-2 * c->sl;
            if (sg * *best - fc > drop) break;
            memcpy(Ya, Yb, (size_t)(n + 1) * sizeof *Ya);
            memcpy(Yb, Yc, (size_t)(n + 1) * sizeof *Yb);
            have_a = 1;
        }
    }
    free(buf);
    return 0;
}

/* Folds from nb0 on that come as a zigzag: consecutive folds less than 1 % of the range
 * apart. With contact laws the sampled contact switches make the discretised residual
 * only piecewise smooth, and where the branch is nearly vertical it can turn back and
 * forth within a few rad/s (the backlash test near 478 rad/s: 479.36, 476.18, 477.37);
 * an odd run is one turn of the branch, kept at its extreme value, an even run none. */
void gd_per_merge_zigzags(ctx *c, int nb0)
{
    gd_periodic_result *r = c->res;
    const double near = 0.01 * c->sl;
    int i = nb0;
    while (i < r->nbifurcations) {
        gd_bifurcation *b = r->bifurcations;
        if (b[i].type != GD_BIF_FOLD) {
            i++;
            continue;
        }
        int j = i + 1;
        while (j < r->nbifurcations && b[j].type == GD_BIF_FOLD &&
               fabs((c->param ? b[j].parameter - b[j - 1].parameter
                              : b[j].speed - b[j - 1].speed)) < near)
            j++;
        int run = j - i;
        if (run == 1) {
            i++;
            continue;
        }
#define VAL(k) (c->param ? b[k].parameter : b[k].speed)
        int keep = -1;
        if (run % 2) { /* the turn of the first: a maximum if it lies beyond the second */
            int max = VAL(i) > VAL(i + 1);
            keep = i;
            for (int k = i; k < j; k += 2)
                if (max ? VAL(k) > VAL(keep) : VAL(k) < VAL(keep)) keep = k;
        }
#undef VAL
        gd_bifurcation kept;
        if (keep >= 0) kept = b[keep];
        memmove(b + i, b + j, (size_t)(r->nbifurcations - j) * sizeof *b);
        r->nbifurcations -= run;
        if (keep >= 0) {
            memmove(b + i + 1, b + i, (size_t)(r->nbifurcations - i) * sizeof *b);
            b[i] = kept;
            r->nbifurcations++;
            i++;
        }
    }
}

/* ---------------------------------------------------------------- branches */

/* A fold where the parameter itself turns: the chords before and after X (Xb, lamp: the
 * point before, have_p: it exists at this H; X1, l1: the step's end) move it in opposite
 * directions, so the branch from the point before X through X to X1 holds its extremum,
 * located there by gd_per_locate_turn (Yt, ut: work) and added. Not the sign of the
 * tangent's parameter component: with a contact law the sampled residual is only
 * piecewise smooth and the tangent is not trusted near a turn (NLvib's example 03 at
 * 2048 samples: 12 flips and one turn; at auto H a turn at 0.75560 with the component at
 * +0.007 on both sides; the backlash pair at H = 20, 1024 samples and 81 speeds: a flip
 * between 479.630 and 479.768 rad/s with the branch's maximum beyond both, a fold the
 * tangent rule dropped). A step that turns within itself and back is refused by the step
 * control (the tangent turned more than 25 deg). 1 a fold, 0 none, -1 an error. */
static int fold_at_turn(ctx *c, const double *Xb, double lamp, int have_p, const double *X,
                        double lam, const double *X1, double l1, double ds, double *Yt, double *ut)
{
    const double cl = l1 - lam, cp = have_p ? lam - lamp : 0.0;
    const double tiny = 1e-13 * c->sl;
    if (!(fabs(cl) > tiny && fabs(cp) > tiny && cp * cl < 0)) return 0;
    double lf;
    if (gd_per_locate_turn(c, Xb, lamp, X, lam, X1, l1, &lf, Yt, ut) < 0) return -1;
    const double sg = lam >= lamp ? 1.0 : -1.0;
    if (c->min_samples > 0) {
        /* a contact law: the turn is the highest tooth of the saw there, once
         * per zigzag (a turn within its reach and no higher takes it) */
        const int reach =
            c->climb_dir != 0 && c->climb_H == c->H && fabs(lf - c->climbed) < 1e-2 * c->sl;
        const int same = reach && c->climb_dir == sg * c->dir;
        if (same && sg * lf > sg * c->climbed) c->climbed = lf;
        if (!reach) {
            double best = lf;
            if (gd_per_climb_teeth(c, Yt, ut, ds / 16, sg, &best) < 0) return -1;
            c->climbed = best;
            c->climb_dir = (int)sg * c->dir;
            c->climb_H = c->H;
        }
        /* a turn the other way within the zigzag's reach is one of its
         * teeth: left as located, gd_per_merge_zigzags takes the run */
        if (!reach || same) lf = c->climbed;
    }
    if (gd_per_add_bif(c, GD_BIF_FOLD, lf, NAN, NAN)) return -1;
    return 1;
}

/* Harmonic balance's bifurcation rule between two arclength steps (method.h, detect; the
 * row's rule, method_table.c): a fold where the parameter turns (fold_at_turn), and a
 * multiplier through the circle (two meeting on the real axis only move between
 * categories), located on the branch; a real one through +1 at a fold is the fold. */
int gd_per_hb_detect(void *m, const gd_per_arc_step *s)
{
    hb_arc *a = m;
    ctx *c = a->c;
    const int n = s->n;
    double *Yt = NULL, *ut = NULL;
    int fold = 0;
    {
        const double cl = s->l1 - s->lam, cp = s->have_b ? s->lam - s->lb : 0.0;
        const double tiny = 1e-13 * c->sl;
        if (fabs(cl) > tiny && fabs(cp) > tiny && cp * cl < 0) { /* its work only then */
            Yt = calloc((size_t)n + 1, sizeof *Yt);
            ut = calloc((size_t)n + 1, sizeof *ut);
            fold = !Yt || !ut ? -1
                              : fold_at_turn(c, s->yb, s->lb, s->have_b, s->y, s->lam, s->y1, s->l1,
                                             s->ds, Yt, ut);
            free(Yt);
            free(ut);
        }
    }
    if (fold < 0) return -1;
    if (a->have_mu && a->stable1 >= 0) {
        int tot = a->out[0] + a->out[1] + a->out[2], tot1 = a->out1[0] + a->out1[1] + a->out1[2];
        if (tot != tot1) {
            int mm = tot < tot1 ? tot1 : tot, ia, ib;
            double ga = gd_per_ranked(c, a->mre, a->mim, mm, &ia) - 1.0;
            double gb = gd_per_ranked(c, a->mre1, a->mim1, mm, &ib) - 1.0;
            /* a tangent that flipped on this step: the turn is seen on the next */
            c->near_fold = fold || s->fold_prev || s->t[n] * s->t1[n] < 0;
            if (gd_per_locate(c, mm, s->y, s->lam, ga, s->y1, s->l1, gb, s->t, a->mre1, a->mim1))
                return -1;
        }
        memcpy(a->out, a->out1, sizeof a->out);
        memcpy(a->mre, a->mre1, 2 * (size_t)c->nf * sizeof *a->mre);
        memcpy(a->mim, a->mim1, 2 * (size_t)c->nf * sizeof *a->mim);
    }
    a->have_mu = a->have_mu && a->stable1 >= 0;
    return fold;
}
