/* Amplitude spectra with FFTW3 (r2c, FFTW_ESTIMATE, plan local to the call). */
#include "geardyn/spectrum.h"
#include "signal/fft_planner_impl.h"

#include <fftw3.h>
#include <math.h>
#include <stdlib.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

const char *const gd_window_names[2] = {"hann", "rect"};

static double window_at(gd_window w, int j, int n)
{
    if (w == GD_WINDOW_RECT) return 1.0;
    return 0.5 * (1.0 - cos(2.0 * M_PI * j / n));
}

gd_status gd_spectrum_compute(const double *x, int nsamples, double dt, gd_window window,
                              gd_spectrum **out, gd_error *err)
{
    *out = NULL;
    if (nsamples < 4)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "spectrum",
                            "record a longer steady part or a shorter output interval",
                            "a spectrum needs at least 4 samples (got %d)", nsamples);
    if (!(dt > 0) || !isfinite(dt))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "spectrum", "",
                            "sampling interval must be > 0");
    if (window != GD_WINDOW_HANN && window != GD_WINDOW_RECT)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "spectrum", "use hann or rect",
                            "unknown window");
    double mean = 0.0;
    for (int j = 0; j < nsamples; j++) {
        if (!isfinite(x[j]))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "spectrum", "",
                                "the signal has a non-finite sample (%d)", j);
        mean += x[j];
    }
    mean /= nsamples;
    const int nb = nsamples / 2 + 1;
    gd_spectrum *s = calloc(1, sizeof *s);
    double *in = fftw_malloc((size_t)nsamples * sizeof *in);
    fftw_complex *X = fftw_malloc((size_t)nb * sizeof *X);
    if (s) {
        s->freq = malloc((size_t)nb * sizeof *s->freq);
        s->amplitude = malloc((size_t)nb * sizeof *s->amplitude);
    }
    fftw_plan plan = NULL;
    gd_fft_planner_init();
    if (s && in && X && s->freq && s->amplitude)
        plan = fftw_plan_dft_r2c_1d(nsamples, in, X, FFTW_ESTIMATE);
    if (!plan) {
        fftw_free(in);
        fftw_free(X);
        gd_spectrum_free(s);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "spectrum", "", "out of memory (FFTW)");
    }
    double wsum = 0.0;
    for (int j = 0; j < nsamples; j++) {
        double w = window_at(window, j, nsamples);
        wsum += w;
        in[j] = w * (x[j] - mean);
    }
    fftw_execute(plan);
    fftw_destroy_plan(plan);
    s->nsamples = nsamples;
    s->dt = dt;
    s->window = window;
    s->n = nb;
    s->df = 1.0 / (nsamples * dt);
    for (int k = 0; k < nb; k++) {
        double c = (k == 0 || (nsamples % 2 == 0 && k == nb - 1)) ? 1.0 : 2.0;
        s->freq[k] = k * s->df;
        s->amplitude[k] = c * hypot(X[k][0], X[k][1]) / wsum;
    }
    fftw_free(in);
    fftw_free(X);
    *out = s;
    return GD_OK;
}

void gd_spectrum_free(gd_spectrum *s)
{
    if (!s) return;
    free(s->freq);
    free(s->amplitude);
    free(s);
}

/* window response at dk bins from the tone, relative to the centre */
static double response(gd_window w, double dk)
{
    double a = fabs(dk);
    if (a < 1e-9) return 1.0;
    double sinc = sin(M_PI * a) / (M_PI * a);
    if (w == GD_WINDOW_RECT) return sinc;
    return sinc / (1.0 - a * a);
}

static void refine(const gd_spectrum *s, int k, gd_spectrum_peak *p)
{
    const double *A = s->amplitude;
    p->bin = k;
    p->frequency = s->freq[k];
    p->amplitude = A[k];
    if (k <= 0 || k >= s->n - 1 || !(A[k] > 0)) return;
    int side = A[k + 1] >= A[k - 1] ? 1 : -1;
    double a = A[k + side] / A[k];
    double dk = s->window == GD_WINDOW_RECT ? a / (1.0 + a) : (2.0 * a - 1.0) / (a + 1.0);
    if (dk < 0) dk = 0;
    if (dk > 0.5) dk = 0.5;
    p->frequency = (k + side * dk) * s->df;
    p->amplitude = A[k] / response(s->window, dk);
}

int gd_spectrum_peaks(const gd_spectrum *s, double min_rel, int max, gd_spectrum_peak *out)
{
    if (max <= 0 || s->n < 3) return 0;
    double top = 0.0;
    for (int k = 1; k < s->n; k++)
        top = fmax(top, s->amplitude[k]);
    if (!(top > 0)) return 0;
    int count = 0;
    const double *A = s->amplitude;
    for (int k = 1; k < s->n - 1; k++) {
        if (!(A[k] > A[k - 1] && A[k] >= A[k + 1] && A[k] >= min_rel * top)) continue;
        gd_spectrum_peak p;
        refine(s, k, &p);
        /* insert in decreasing amplitude, keeping at most max */
        int pos = count;
        while (pos > 0 && out[pos - 1].amplitude < p.amplitude)
            pos--;
        if (pos >= max) continue;
        int last = count < max ? count : max - 1;
        for (int j = last; j > pos; j--)
            out[j] = out[j - 1];
        out[pos] = p;
        if (count < max) count++;
    }
    return count;
}

double gd_spectrum_band_max(const gd_spectrum *s, double f_lo, double f_hi, double *f_at)
{
    double best = 0.0, fb = 0.0;
    for (int k = 0; k < s->n; k++)
        if (s->freq[k] >= f_lo && s->freq[k] <= f_hi && s->amplitude[k] > best) {
            best = s->amplitude[k];
            fb = s->freq[k];
        }
    if (f_at) *f_at = fb;
    return best;
}
