/* Computed order tracking (geardyn/waterfall.h): a run-up record resampled against the
 * reference shaft's angle, so that every shaft order is a constant frequency per
 * revolution, and one order spectrum per block of revolutions, stacked by the block's
 * mean speed into the waterfall the stepped run-up also uses. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/waterfall.h"

#define TWO_PI 6.28318530717958647692

void gd_order_track_options_init(gd_order_track_options *opt)
{
    opt->revs_per_block = 16;
    opt->samples_per_rev = 64;
    opt->overlap = 0.5;
    opt->window = GD_WINDOW_HANN;
}

/* x at angle a by linear interpolation over the samples (angle increasing in sign s);
 * *k is a search start moved forward; *time receives the time there */
static double at_angle(const double *t, const double *x, const double *angle, int n, double s,
                       double a, int *k, double *time)
{
    while (*k + 2 < n && s * angle[*k + 1] < s * a)
        (*k)++;
    int j = *k;
    double da = angle[j + 1] - angle[j], f = da != 0 ? (a - angle[j]) / da : 0;
    *time = t[j] + f * (t[j + 1] - t[j]);
    return x[j] + f * (x[j + 1] - x[j]);
}

gd_status gd_waterfall_order_track(const gd_system *sys, const double *t, const double *x,
                                   const double *angle, int n, const gd_order_track_options *opt,
                                   gd_waterfall **out, gd_error *err)
{
    *out = NULL;
    gd_order_track_options def;
    gd_order_track_options_init(&def);
    if (!opt) opt = &def;
    const int S = opt->samples_per_rev;
    const double R = opt->revs_per_block;
    if (!(R >= 1) || S < 4 || !(opt->overlap >= 0 && opt->overlap <= 0.9) || R * S > 1e8)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "order tracking",
                            "revs_per_block >= 1, samples_per_rev >= 4, overlap 0 .. 0.9",
                            "invalid order-tracking options (%g revolutions, %d samples, "
                            "overlap %g)",
                            R, S, opt->overlap);
    if (n < 2)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "order tracking", "record a longer run",
                            "fewer than two samples");
    const double s = angle[n - 1] >= angle[0] ? 1.0 : -1.0;
    double dmax = 0; /* the largest angle step between samples */
    for (int k = 1; k < n; k++) {
        double d = s * (angle[k] - angle[k - 1]);
        if (!(d >= 0) || !(t[k] > t[k - 1]))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "order tracking",
                                "give a speed profile of one sign and increasing times",
                                "the shaft angle reverses (or time does not increase) at "
                                "sample %d",
                                k);
        dmax = fmax(dmax, d);
    }
    if (dmax > TWO_PI / (2.0 * S))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "order tracking",
                            "record more often (a shorter output interval: --output-interval)",
                            "the record has %.3g samples per revolution at the top speed; "
                            "order tracking at %d samples per revolution needs %d",
                            TWO_PI / dmax, S, 2 * S);
    const int N = (int)floor(R * S + 0.5);
    const double span = s * (angle[n - 1] - angle[0]) / TWO_PI; /* revolutions */
    const double hop = R * (1.0 - opt->overlap);
    int nb = span >= R ? (int)floor((span - R) / hop + 1e-9) + 1 : 0;
    if (nb < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "order tracking",
                            "run longer or give fewer revolutions per block",
                            "the run turns the reference shaft %.3g times, fewer than one block "
                            "of %g",
                            span, R);
    gd_spectrum **sp = calloc((size_t)nb, sizeof *sp);
    double *speeds = malloc((size_t)nb * sizeof *speeds);
    double *buf = malloc((size_t)N * sizeof *buf);
    gd_status st = GD_OK;
    if (!sp || !speeds || !buf) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "order tracking", "", "out of memory");
        goto done;
    }
    int k = 0;
    for (int b = 0; b < nb; b++) {
        double a0 = angle[0] + s * TWO_PI * b * hop, ta = 0, tb = 0, tt;
        while (k > 0 && s * angle[k] > s * a0)
            k--;
        for (int j = 0; j < N; j++) {
            buf[j] = at_angle(t, x, angle, n, s, a0 + s * TWO_PI * j / S, &k, &tt);
            if (j == 0) ta = tt;
        }
        at_angle(t, x, angle, n, s, a0 + s * TWO_PI * R, &k, &tb);
        /* over the angle: dt = 1 / S revolutions, bins are orders */
        if ((st = gd_spectrum_compute(buf, N, 1.0 / S, opt->window, &sp[b], err))) goto done;
        speeds[b] = TWO_PI * R / (tb - ta); /* mean speed over the block, rad/s */
        double hz = speeds[b] / TWO_PI;     /* Hz per order */
        for (int i = 0; i < sp[b]->n; i++)
            sp[b]->freq[i] *= hz;
        sp[b]->df *= hz;
        sp[b]->dt = (tb - ta) / N;
    }
    st = gd_waterfall_new(sys, nb, speeds, sp, out, err);
    if (!st) {
        (*out)->tracked = 1;
        (*out)->revs_per_block = R;
    }
    free(sp);
    sp = NULL;
done:
    for (int b = 0; sp && b < nb; b++)
        gd_spectrum_free(sp[b]);
    free(sp);
    free(speeds);
    free(buf);
    return st;
}
