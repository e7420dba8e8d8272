/* The verdict on once-per-period (Poincare) samples: period-N by exact repetition at a
 * tolerance; quasi-periodic by uniform close returns (Lathrop & Kostelich 1989) on a
 * recurrent set; irregular otherwise. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geardyn/cycles.h"

void gd_poincare_options_init(gd_poincare_options *o)
{
    o->tol = 1e-3;
    o->torus_tol = 0.2;
    o->min_points = 32;
}

/* max over records of |a_r - b_r| / tol_r <= 1 */
static int same(const double *values, int nrec, int n, const double *tol, int a, int b)
{
    for (int r = 0; r < nrec; r++)
        if (fabs(values[(size_t)r * n + a] - values[(size_t)r * n + b]) > tol[r]) return 0;
    return 1;
}

/* distance in units of each record's spread over the section (w[r] = 1 / spread, 0 for a
 * record constant at the tolerance) */
static double dist(const double *values, int nrec, int n, const double *w, int a, int b)
{
    double d = 0;
    for (int r = 0; r < nrec; r++)
        d = fmax(d, w[r] * fabs(values[(size_t)r * n + a] - values[(size_t)r * n + b]));
    return d;
}

/* directed Hausdorff distance from points [a0, a1) to points [b0, b1) */
static double directed(const double *values, int nrec, int n, const double *w, int a0, int a1,
                       int b0, int b1)
{
    double h = 0;
    for (int a = a0; a < a1; a++) {
        double m = INFINITY;
        for (int b = b0; b < b1 && m > h; b++)
            m = fmin(m, dist(values, nrec, n, w, a, b));
        h = fmax(h, m);
    }
    return h;
}

/* Whether the points still converge onto a p-cycle: the largest difference between points
 * p apart (in tolerances) over the last third of the points is below half that over the
 * first third, the first being above a tenth of the tolerance (else rounding) */
static int converging(const double *values, int nrec, int n, const double *tol, int p)
{
    int m = (n - p) / 3;
    if (m < 2) return 0;
    double first = 0, last = 0;
    for (int k = 0; k < n - p; k++) {
        double d = 0;
        for (int r = 0; r < nrec; r++)
            d = fmax(d, fabs(values[(size_t)r * n + k] - values[(size_t)r * n + k + p]) / tol[r]);
        if (k < m) first = fmax(first, d);
        if (k >= n - p - m) last = fmax(last, d);
    }
    return first > 0.1 && last < 0.5 * first;
}

static void torus_test(const double *values, int nrec, int n, const double *w,
                       gd_poincare_verdict *v)
{
    v->return_shift = 0;
    v->return_distance = INFINITY;
    for (int q = 1; q <= n / 2; q++) {
        double rq = 0;
        for (int k = 0; k + q < n && rq < v->return_distance; k++)
            rq = fmax(rq, dist(values, nrec, n, w, k, k + q));
        if (rq < v->return_distance) {
            v->return_distance = rq;
            v->return_shift = q;
        }
    }
    int h = n / 2;
    v->halves_distance =
        fmax(directed(values, nrec, n, w, 0, h, h, n), directed(values, nrec, n, w, h, n, 0, h));
}

gd_status gd_poincare_classify(const double *values, int nrec, int n, const double *scale,
                               const gd_poincare_options *o, gd_poincare_verdict *v, gd_error *err)
{
    gd_poincare_options def;
    if (!o) {
        gd_poincare_options_init(&def);
        o = &def;
    }
    if (n < 1 || nrec < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "poincare", "give at least one point",
                            "%d points of %d records", n, nrec);
    if (!(o->tol > 0 && o->tol < 1) || !(o->torus_tol > 0 && o->torus_tol < 1) || o->min_points < 4)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "poincare",
                            "tol and torus_tol in (0, 1), min_points >= 4",
                            "bad options (tol %g, torus_tol %g, min_points %d)", o->tol,
                            o->torus_tol, o->min_points);
    for (size_t i = 0; i < (size_t)nrec * n; i++)
        if (!isfinite(values[i]))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "poincare", "",
                                "a point of record %d is not finite", (int)(i / n));
    v->cls = GD_POINCARE_IRREGULAR;
    v->period = 0;
    v->points = n;
    v->distinct = 0;
    v->tol = o->tol;
    v->torus_tol = o->torus_tol;
    v->return_shift = 0;
    v->return_distance = v->halves_distance = 0;
    v->converging = 0;
    double *tol = malloc(2 * (size_t)nrec * sizeof *tol);
    int *rep = malloc((size_t)n * sizeof *rep);
    if (!tol || !rep) {
        free(tol);
        free(rep);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "poincare", "", "out of memory");
    }
    double *w = tol + nrec;
    for (int r = 0; r < nrec; r++) {
        double mag = 0, lo = INFINITY, hi = -INFINITY;
        for (int k = 0; k < n; k++) {
            double x = values[(size_t)r * n + k];
            mag = fmax(mag, fabs(x));
            lo = fmin(lo, x);
            hi = fmax(hi, x);
        }
        /* a constant record: its rounding */
        tol[r] = scale && scale[r] > 0 ? o->tol * scale[r] : 1e-12 * mag;
        w[r] = hi - lo > tol[r] ? 1.0 / (hi - lo) : 0.0;
        /* a contact state (-1, 0, 1) jumps where a smooth invariant curve crosses a contact
         * change: it counts for repetition, not in the distances of the torus test */
        int state = 1;
        for (int k = 0; k < n && state; k++) {
            double x = values[(size_t)r * n + k];
            state = x == -1.0 || x == 0.0 || x == 1.0;
        }
        if (state) w[r] = 0.0;
    }
    for (int p = 1; p <= n / 2 && !v->period; p++) {
        int ok = 1;
        for (int k = 0; k + p < n && ok; k++)
            ok = same(values, nrec, n, tol, k, k + p);
        if (ok) v->period = p;
    }
    /* greedy clustering: representatives are the first points of their clusters */
    for (int k = 0; k < n; k++) {
        int found = 0;
        for (int c = 0; c < v->distinct && !found; c++)
            found = same(values, nrec, n, tol, rep[c], k);
        if (!found) rep[v->distinct++] = k;
    }
    /* a slow drift passes the shift test but spreads the points: not settled */
    if (v->distinct != v->period) v->period = 0;
    /* a transient decaying while it turns by about 2 pi / p per period passes for a
     * p-cycle at the tolerance: not settled either */
    if (v->period >= 2 && converging(values, nrec, n, tol, v->period)) {
        v->period = 0;
        v->converging = 1;
    }
    if (v->period > 0)
        v->cls = GD_POINCARE_PERIODIC;
    else if (n >= o->min_points) {
        torus_test(values, nrec, n, w, v);
        if (v->return_distance <= o->torus_tol && v->halves_distance <= o->torus_tol)
            v->cls = GD_POINCARE_QUASI_PERIODIC;
    }
    free(rep);
    free(tol);
    return GD_OK;
}

void gd_poincare_verdict_name(const gd_poincare_verdict *v, char *buf, int size)
{
    if (size <= 0) return;
    if (v->cls == GD_POINCARE_PERIODIC)
        snprintf(buf, (size_t)size, v->period == 1 ? "periodic" : "period-%d", v->period);
    else
        snprintf(buf, (size_t)size, "%s",
                 v->cls == GD_POINCARE_QUASI_PERIODIC ? "quasi-periodic" : "irregular");
}
