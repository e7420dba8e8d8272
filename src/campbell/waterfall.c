/* The run-up waterfall: spectra over speed and the order cuts (geardyn/waterfall.h). */
#include "geardyn/waterfall.h"

#include <math.h>
#include <stdlib.h>

#include "campbell/campbell_impl.h"

#define PI 3.14159265358979323846

void gd_waterfall_free(gd_waterfall *w)
{
    if (!w) return;
    for (int s = 0; s < w->nspeeds; s++)
        gd_spectrum_free(w->spectra[s]);
    free(w->spectra);
    free(w->speeds);
    free(w->orders);
    free(w->order_amplitude);
    free(w->order_frequency);
    free(w);
}

gd_status gd_waterfall_new(const gd_system *sys, int n, const double *speeds, gd_spectrum **spectra,
                           gd_waterfall **out, gd_error *err)
{
    *out = NULL;
    gd_waterfall *w = calloc(1, sizeof *w);
    if (w) w->spectra = calloc((size_t)(n > 0 ? n : 1), sizeof *w->spectra);
    if (!w || !w->spectra) {
        for (int s = 0; s < n; s++)
            gd_spectrum_free(spectra[s]);
        free(w);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "waterfall", "", "out of memory");
    }
    for (int s = 0; s < n; s++) {
        w->spectra[s] = spectra[s];
        spectra[s] = NULL;
    }
    w->nspeeds = n;
    gd_status st = GD_OK;
    if (n < 1) {
        st = gd_error_set(err, GD_EINPUT, "", 0, 0, "waterfall", "give at least one speed",
                          "a waterfall needs at least one spectrum");
        goto fail;
    }
    for (int s = 0; s < n; s++)
        if (!(speeds[s] > 0) || !isfinite(speeds[s]) || !w->spectra[s]) {
            st = gd_error_set(err, GD_EINPUT, "", 0, 0, "waterfall", "speeds must be > 0",
                              "speed %d is %g rad/s or has no spectrum", s, speeds[s]);
            goto fail;
        }
    gd_campbell_options copt;
    gd_campbell_options_init(&copt);
    w->speeds = malloc((size_t)n * sizeof *w->speeds);
    w->norders = gd_campbell_orders(sys->model, &copt, &w->orders);
    if (!w->speeds || w->norders < 0) goto nomem;
    size_t no = (size_t)(w->norders > 0 ? w->norders : 1) * (size_t)n;
    w->order_amplitude = malloc(no * sizeof *w->order_amplitude);
    w->order_frequency = malloc(no * sizeof *w->order_frequency);
    if (!w->order_amplitude || !w->order_frequency) goto nomem;
    for (int s = 0; s < n; s++) {
        w->speeds[s] = speeds[s];
        const gd_spectrum *sp = w->spectra[s];
        for (int o = 0; o < w->norders; o++) {
            double f = w->orders[o].order * speeds[s] / (2 * PI), at = NAN, a = NAN;
            if (f <= sp->freq[sp->n - 1])
                a = gd_spectrum_band_max(sp, f - 1.5 * sp->df, f + 1.5 * sp->df, &at);
            w->order_amplitude[(size_t)o * n + s] = a;
            w->order_frequency[(size_t)o * n + s] = at;
        }
    }
    *out = w;
    return GD_OK;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "waterfall", "", "out of memory");
fail:
    gd_waterfall_free(w);
    return st;
}
