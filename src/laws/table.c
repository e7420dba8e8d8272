/* Interpolation tables: linear or cubic spline, periodic or not. The periodic spline
 * solves the cyclic tridiagonal system for the second derivatives (Sherman-Morrison on
 * the Thomas algorithm); the non-periodic one is the natural spline. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/remainder_impl.h"
#include "geardyn/laws.h"

static gd_status table_error(gd_error *err, gd_status st, const char *field, const char *msg)
{
    return gd_error_set(err, st, "", 0, 0, field, "", "%s", msg);
}

/* Solves a tridiagonal system with sub a, diagonal b, super c (all length n), rhs d in
 * place. a[0] and c[n-1] are ignored. Work w of length n. Returns 0, or 1 if singular. */
static int thomas(int n, const double *a, const double *b, const double *c, double *d, double *w)
{
    double beta = b[0];
    if (beta == 0.0) return 1;
    d[0] /= beta;
    for (int i = 1; i < n; i++) {
        w[i] = c[i - 1] / beta;
        beta = b[i] - a[i] * w[i];
        if (beta == 0.0) return 1;
        d[i] = (d[i] - a[i] * d[i - 1]) / beta;
    }
    for (int i = n - 2; i >= 0; i--)
        d[i] -= w[i + 1] * d[i + 1];
    return 0;
}

/* Second derivatives m[0..n-1] of the spline through (x, y). Periodic when period > 0:
 * interval i runs from x[i] to x[i+1], the last from x[n-1] to x[0] + period. */
static int spline_moments(int n, const double *x, const double *y, double period, double *m)
{
    int ni = period > 0 ? n : n - 1; /* number of intervals */
    double *h = malloc((size_t)ni * sizeof *h);
    double *a = calloc((size_t)n, sizeof *a), *b = calloc((size_t)n, sizeof *b);
    double *c = calloc((size_t)n, sizeof *c), *w = calloc((size_t)n, sizeof *w);
    double *u = calloc((size_t)n, sizeof *u);
    int rc = 1;
    if (!h || !a || !b || !c || !w || !u) goto done;
    for (int i = 0; i < ni; i++)
        h[i] = (i + 1 < n ? x[i + 1] : x[0] + period) - x[i];
    if (period > 0) {
        /* row i: h[i-1] m[i-1] + 2 (h[i-1] + h[i]) m[i] + h[i] m[i+1] = 6 (slope_i - slope_{i-1})
         */
        for (int i = 0; i < n; i++) {
            int ip = (i + n - 1) % n, in = (i + 1) % n;
            double hp = h[ip], hn = h[i];
            a[i] = hp;
            b[i] = 2.0 * (hp + hn);
            c[i] = hn;
            m[i] = 6.0 * ((y[in] - y[i]) / hn - (y[i] - y[ip]) / hp);
        }
        /* cyclic: corners alpha = a[0] (row 0, col n-1), beta = c[n-1] (row n-1, col 0) */
        double alpha = a[0], beta = c[n - 1], gamma = -b[0];
        double *bb = malloc((size_t)n * sizeof *bb);
        if (!bb) goto done;
        memcpy(bb, b, (size_t)n * sizeof *bb);
        bb[0] -= gamma;
        bb[n - 1] -= alpha * beta / gamma;
        if (thomas(n, a, bb, c, m, w)) {
            free(bb);
            goto done;
        }
        u[0] = gamma;
        u[n - 1] = beta;
        if (thomas(n, a, bb, c, u, w)) {
            free(bb);
            goto done;
        }
        free(bb);
        double fact = (m[0] + alpha * m[n - 1] / gamma) / (1.0 + u[0] + alpha * u[n - 1] / gamma);
        for (int i = 0; i < n; i++)
            m[i] -= fact * u[i];
        rc = 0;
    } else {
        /* natural spline: m[0] = m[n-1] = 0 */
        b[0] = 1.0;
        b[n - 1] = 1.0;
        m[0] = m[n - 1] = 0.0;
        for (int i = 1; i < n - 1; i++) {
            a[i] = h[i - 1];
            b[i] = 2.0 * (h[i - 1] + h[i]);
            c[i] = h[i];
            m[i] = 6.0 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1]);
        }
        rc = thomas(n, a, b, c, m, w);
    }
done:
    free(h);
    free(a);
    free(b);
    free(c);
    free(w);
    free(u);
    return rc;
}

gd_status gd_table_new(int n, const double *x, const double *y, double period, gd_interp interp,
                       gd_table **out, gd_error *err)
{
    *out = NULL;
    if (n < 2 || (interp == GD_INTERP_SPLINE && n < 3))
        return table_error(err, GD_EINPUT, "table",
                           "a table needs at least 2 points (3 for a spline)");
    if (!(period >= 0) || !isfinite(period))
        return table_error(err, GD_EINPUT, "table.period", "the period must be >= 0 and finite");
    for (int i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]))
            return table_error(err, GD_EINPUT, "table", "table values must be finite");
        if (i > 0 && !(x[i] > x[i - 1]))
            return table_error(err, GD_EINPUT, "table.x", "table abscissae must increase");
    }
    if (period > 0 && !(x[n - 1] - x[0] < period))
        return table_error(err, GD_EINPUT, "table.x",
                           "a periodic table must span less than one period");
    gd_table *t = calloc(1, sizeof *t);
    if (!t) return table_error(err, GD_ENOMEM, "", "out of memory");
    t->n = n;
    t->period = period;
    t->interp = interp;
    t->x = malloc((size_t)n * sizeof *t->x);
    t->y = malloc((size_t)n * sizeof *t->y);
    if (interp == GD_INTERP_SPLINE) t->m = malloc((size_t)n * sizeof *t->m);
    if (!t->x || !t->y || (interp == GD_INTERP_SPLINE && !t->m)) {
        gd_table_free(t);
        return table_error(err, GD_ENOMEM, "", "out of memory");
    }
    memcpy(t->x, x, (size_t)n * sizeof *x);
    memcpy(t->y, y, (size_t)n * sizeof *y);
    if (interp == GD_INTERP_SPLINE && spline_moments(n, x, y, period, t->m)) {
        gd_table_free(t);
        return table_error(err, GD_ENUMERIC, "table", "spline system is singular");
    }
    /* uniform spacing (including the closing interval of a periodic table) */
    double h = (x[n - 1] - x[0]) / (n - 1);
    int uni = 1;
    for (int i = 1; i < n && uni; i++)
        if (fabs(x[i] - x[0] - i * h) > 1e-12 * fabs(h) * n) uni = 0;
    if (uni && period > 0 && fabs(x[0] + period - x[n - 1] - h) > 1e-12 * h * n) uni = 0;
    t->uniform = uni ? h : 0.0;
    *out = t;
    return GD_OK;
}

gd_status gd_table_from_tvms(const gd_tvms_result *r, gd_interp interp, gd_table **out,
                             gd_error *err)
{
    *out = NULL;
    if (!r || r->points < 2 || r->n < r->points || !(r->mesh_period_rad > 0))
        return table_error(err, GD_EINPUT, "tvms", "mesh stiffness result has no full cycle");
    return gd_table_new((int)r->points, r->angle_rad, r->stiffness, r->mesh_period_rad, interp, out,
                        err);
}

void gd_table_free(gd_table *t)
{
    if (!t) return;
    free(t->x);
    free(t->y);
    free(t->m);
    free(t);
}

double gd_table_eval(const gd_table *t, double x, double *dy, double *d2y)
{
    const int n = t->n;
    const double *X = t->x, *Y = t->y;
    /* NaN has no interval (and inf none in a period): never an index from it */
    if (isnan(x) || (t->period > 0 && !isfinite(x))) {
        if (dy) *dy = NAN;
        if (d2y) *d2y = NAN;
        return NAN;
    }
    if (t->period > 0) {
        double u = gd_remainder(x - X[0], t->period);
        if (u < 0) u += t->period;
        x = X[0] + u;
    } else if (x <= X[0] || x >= X[n - 1]) {
        /* linear continuation with the end slope */
        int left = x <= X[0];
        int i0 = left ? 0 : n - 2;
        double h = X[i0 + 1] - X[i0];
        double s = (Y[i0 + 1] - Y[i0]) / h;
        if (t->m) {
            if (left)
                s -= h * (2.0 * t->m[0] + t->m[1]) / 6.0;
            else
                s += h * (t->m[n - 2] + 2.0 * t->m[n - 1]) / 6.0;
        }
        double xe = left ? X[0] : X[n - 1], ye = left ? Y[0] : Y[n - 1];
        if (dy) *dy = s;
        if (d2y) *d2y = 0.0;
        return ye + s * (x - xe);
    }
    /* interval i: [X[i], X[i+1]] (periodic: the last one closes to X[0] + period) */
    int i;
    if (t->uniform > 0) {
        i = (int)((x - X[0]) / t->uniform);
        if (i < 0) i = 0;
        if (i > n - 1) i = n - 1;
        if (t->period <= 0 && i > n - 2) i = n - 2;
    } else {
        int lo = 0, hi = n - 1;
        if (x >= X[n - 1]) {
            lo = t->period > 0 ? n - 1 : n - 2;
        } else {
            while (hi - lo > 1) {
                int mid = (lo + hi) / 2;
                if (X[mid] <= x)
                    lo = mid;
                else
                    hi = mid;
            }
        }
        i = lo;
    }
    int j = i + 1;
    double xj;
    if (j == n) { /* periodic closing interval */
        j = 0;
        xj = X[0] + t->period;
    } else {
        xj = X[j];
    }
    double h = xj - X[i];
    double A = (xj - x) / h, B = 1.0 - A;
    if (!t->m) {
        if (dy) *dy = (Y[j] - Y[i]) / h;
        if (d2y) *d2y = 0.0;
        return A * Y[i] + B * Y[j];
    }
    double mi = t->m[i], mj = t->m[j];
    double val = A * Y[i] + B * Y[j] + ((A * A * A - A) * mi + (B * B * B - B) * mj) * h * h / 6.0;
    if (dy)
        *dy = (Y[j] - Y[i]) / h - (3.0 * A * A - 1.0) * h * mi / 6.0 +
              (3.0 * B * B - 1.0) * h * mj / 6.0;
    if (d2y) *d2y = A * mi + B * mj;
    return val;
}
