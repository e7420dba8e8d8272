/* Per-period statistics of a sampled record: each whole period's peak-to-peak, mean and
 * RMS, then their median, 5-95 % band and extremes over the periods. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/cycles.h"

static gd_status bad(gd_error *err, const char *fix, const char *msg)
{
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "cycle statistics", fix, "%s", msg);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* percentile p in [0, 1] of sorted s[0..n-1], linear between order statistics (type 7) */
static double percentile(const double *s, int n, double p)
{
    double h = (n - 1) * p;
    int i = (int)floor(h);
    if (i >= n - 1) return s[n - 1];
    return s[i] + (h - i) * (s[i + 1] - s[i]);
}

static void band(double *v, int n, gd_cycle_band *b)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    b->median = percentile(v, n, 0.5);
    b->p05 = percentile(v, n, 0.05);
    b->p95 = percentile(v, n, 0.95);
    b->min = v[0];
    b->max = v[n - 1];
}

gd_status gd_cycle_stats_compute(const double *x, int n, double t0, double dt, double period,
                                 double from, gd_cycle_stats *out, gd_error *err)
{
    if (n < 2) return bad(err, "record at least two samples", "fewer than 2 samples");
    if (!(dt > 0) || !isfinite(dt) || !(period > 0) || !isfinite(period) || !isfinite(t0) ||
        !isfinite(from))
        return bad(err, "give a finite sampling interval and period > 0",
                   "the sampling interval, the period or a time is not finite and positive");
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i])) return bad(err, "", "a sample is not finite");
    double eps = 1e-3 * dt, t_last = t0 + (n - 1) * dt;
    /* the first whole period starts at or after the first sample */
    double j0 = ceil((t0 - from) / period - eps / period);
    if (j0 < 0) j0 = 0;
    double j1 = floor((t_last - from) / period + eps / period); /* last period's end */
    if (!(j1 - j0 >= 1))
        return bad(err, "record longer, or settle less",
                   "the samples do not cover one whole period");
    if (j1 - j0 > 1e8) return bad(err, "give fewer periods", "more than 1e8 periods");
    int np = (int)(j1 - j0);
    double *pp = malloc(3 * (size_t)np * sizeof *pp);
    if (!pp) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "cycle statistics", "", "out of memory");
    double *mean = pp + np, *rms = mean + np;
    int min_samples = n;
    for (int j = 0; j < np; j++) {
        double a = from + (j0 + j) * period, b = a + period;
        int i0 = (int)ceil((a - t0 - eps) / dt), i1 = (int)floor((b - t0 + eps) / dt);
        if (i0 < 0) i0 = 0;
        if (i1 > n - 1) i1 = n - 1;
        int m = i1 - i0 + 1;
        if (m < min_samples) min_samples = m;
        if (m < 3) {
            free(pp);
            return bad(err, "sample at least 2 times per period (a shorter output interval)",
                       "fewer than 3 samples in a period");
        }
        double lo = x[i0], hi = x[i0], s = 0, s2 = 0;
        for (int i = i0; i <= i1; i++) {
            lo = fmin(lo, x[i]);
            hi = fmax(hi, x[i]);
            double w = (i == i0 || i == i1) ? 0.5 : 1.0; /* trapezoid */
            s += w * x[i];
            s2 += w * x[i] * x[i];
        }
        pp[j] = hi - lo;
        mean[j] = s / (m - 1);
        rms[j] = sqrt(s2 / (m - 1));
    }
    out->periods = np;
    out->min_samples = min_samples;
    band(pp, np, &out->peak_to_peak);
    band(mean, np, &out->mean);
    band(rms, np, &out->rms);
    free(pp);
    return GD_OK;
}
