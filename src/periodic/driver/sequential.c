/* The branch of every method of the table (method.h), in each direction: the first point,
 * then the natural continuation of --sequential (one fixed-value solve per requested value
 * from the points before it) or the pseudo-arclength (arclength.c). Before (2026-12-02)
 * harmonic balance (continuation.c) and shooting (shooting/shooting_natural.c) each had
 * their own loop; where they differed, one rule was chosen, each said below with why. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/method.h"

/* Whether the method stops trying further starts of this point (its budget ran out). */
static int gave_up(const gd_per_arc *a)
{
    return a->ops->give_up && a->ops->give_up(a->m);
}

/* The method's own start at v after the starts from neighbours failed (tried: one was
 * tried, its reason in a->why): both reasons kept when they differ. 0 solved. */
static int cold_start(const gd_per_arc *a, double **y, double v, int tried, int *it, double *res)
{
    const gd_per_arc_ops *o = a->ops;
    char first[320];
    snprintf(first, sizeof first, "%s", tried ? a->why : "");
    if (!o->prepare(a->m, v) && !o->cold(a->m, y, v, it, res)) return 0;
    if (first[0] && strcmp(first, a->why)) {
        char both[320];
        snprintf(both, sizeof both, "%.110s; from %s: %.110s", first, o->cold_name, a->why);
        snprintf(a->why, a->why_cap, "%s", both);
    }
    return 1;
}

/* (Re)allocates the n + 1 entries of each array. 0 ok. */
static int resize(int n, double **arr[], int na)
{
    for (int i = 0; i < na; i++) {
        double *p = realloc(*arr[i], ((size_t)n + 1) * sizeof *p);
        if (!p) return 1;
        *arr[i] = p;
    }
    return 0;
}

/* Natural continuation from *yio (solved at vals[i0]) to vals[nv - 1]: each value solved
 * at fixed value, emitted or failed with the reason. 0 done, 1 an error.
 *
 * The starts, in this order, each only when the one before failed and the method did not
 * give up (a point's budget covers all its starts):
 * 1. the secant through the last two converged points, extrapolated to the value: on a
 *    smooth curve its error is second order in the step (the [JMSTHelical] curve by
 *    harmonic balance: starting residual 4.5e-3 -> 1e-3, Newton iterations 601 -> 584
 *    over 300 speeds);
 * 2. the last converged point (harmonic balance's fallback: a secant that overshoots near a
 *    fold or a resonance peak can leave Newton's basin where the plain last point does
 *    not; shooting went to 3. directly);
 * 3. the method's own start (harmonic balance: rest, then a transient; shooting: a
 *    transient), as shooting did: a run-up past a fold has no solution near the last one,
 *    and a slow run-up jumps to the orbit the transient settles on (harmonic balance
 *    failed the point instead).
 * A failed value keeps the history (harmonic balance's rule; shooting cleared it and
 * started the next value from a transient): the two last converged points are still the
 * best start known, and 3. is still there when they fail. The bifurcation rule of the
 * method (between) sees only consecutive points: across a failed value its solves would
 * have to pass where one already failed. */
static int sequential(const gd_per_arc *a, const double *vals, int nv, int i0, double **yio)
{
    const gd_per_arc_ops *o = a->ops;
    void *m = a->m;
    int n = o->size(m), rc = 1, hist = 1, consecutive = 1;
    double *y = *yio, *yq = NULL, *ys = NULL; /* the last point, the one before, the trial */
    double lx = vals[i0], lq = lx;            /* their values */
    if (resize(n, (double **[]){&yq, &ys}, 2)) goto done;
    for (int i = i0 + 1; i < nv; i++) {
        const double v = vals[i];
        int it = 0, ok = 0, tried = 0;
        double res = NAN;
        o->step(m);
        if (!o->prepare(m, v)) {
            if (hist == 2 && lx != lq) {
                const double f = (v - lx) / (lx - lq);
                for (int k = 0; k < n; k++)
                    ys[k] = y[k] + f * (y[k] - yq[k]);
                ys[n] = y[n];
                ok = !o->solve_at(m, ys, v, &it, &res);
                tried = 1;
            }
            if (!ok && !gave_up(a)) {
                memcpy(ys, y, ((size_t)n + 1) * sizeof *ys);
                ok = !o->prepare(m, v) && !o->solve_at(m, ys, v, &it, &res);
                tried = 1;
            }
            if (!ok && !gave_up(a)) ok = !cold_start(a, &ys, v, tried, &it, &res);
        }
        if (!ok) {
            if (o->fail(m, v)) goto done;
            consecutive = 0;
            continue;
        }
        if (o->emit(m, ys, v, it, res)) goto done;
        if (o->between && consecutive && o->between(m, y, lx, ys, v)) goto done;
        double *t = yq;
        yq = y;
        y = ys;
        ys = t;
        lq = lx;
        lx = v;
        hist = 2;
        consecutive = 1;
        if (o->grow) {
            /* more unknowns (harmonics): the point padded, not solved again, as the next
             * value's solve starts from it anyway; the secant spans two sizes: none */
            const int g = o->grow(m, &y, NULL, NULL, v, NULL);
            if (g < 0) goto done;
            if (g > 0) {
                n = o->size(m);
                if (resize(n, (double **[]){&yq, &ys}, 2)) goto done;
                hist = 1;
            }
        }
    }
    rc = 0;
done:
    *yio = y;
    free(yq);
    free(ys);
    return rc;
}

int gd_per_branch(const gd_per_arc *a, const double *vals, int nv, int seq)
{
    const gd_per_arc_ops *o = a->ops;
    void *m = a->m;
    int it = 0, rc = 1, i0;
    double res = NAN;
    double *y = calloc((size_t)o->size(m) + 1, sizeof *y);
    if (!y) return 1;
    /* the first point: from the method's own start (the values before it fail) */
    for (i0 = 0; i0 < nv; i0++) {
        if (o->begin) o->begin(m);
        if (!cold_start(a, &y, vals[i0], 0, &it, &res)) break;
        if (o->fail(m, vals[i0])) goto done;
    }
    if (i0 == nv) {
        rc = 0;
        goto done;
    }
    if (o->emit(m, y, vals[i0], it, res)) goto done;
    if (o->grow) {
        /* the first point needed more unknowns: the branch starts from it solved again
         * with them (padded with zeros it is no solution there: harmonic balance on the
         * backlash pair over 300..2500 rad/s went from 300 to 292 rad/s on a step of 1e-6,
         * a false fold at 241.85 and 300 rad/s reported twice) */
        const int g = o->grow(m, &y, NULL, NULL, vals[i0], &it);
        if (g < 0) goto done;
        if (g == 2) {
            rc = 0;
            for (int i = i0 + 1; i < nv; i++)
                if (o->fail(m, vals[i])) rc = 1;
            goto done;
        }
    }
    if (seq)
        rc = sequential(a, vals, nv, i0, &y);
    else if (i0 == nv - 1)
        rc = 0;
    else
        rc = gd_per_arclength(a, vals, nv, i0, &y, vals[i0]);
done:
    free(y);
    return rc;
}

int gd_per_directions(const gd_per_arc *a, const double *vals, int nv, int both, int seq)
{
    const gd_per_arc_ops *o = a->ops;
    double *rev = malloc((size_t)nv * sizeof *rev);
    int rc = !rev;
    for (int d = 0; d < (both ? 2 : 1) && !rc; d++) {
        for (int i = 0; i < nv; i++)
            rev[i] = d ? vals[nv - 1 - i] : vals[i];
        rc = o->direction && o->direction(a->m, d ? -1 : 1, rev[0], rev[nv - 1]);
        if (!rc) rc = gd_per_branch(a, rev, nv, seq);
        if (!rc && o->branch_end) o->branch_end(a->m);
    }
    free(rev);
    return rc;
}
