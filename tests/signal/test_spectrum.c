/* Amplitude spectra (src/spectrum.c) against analytic sinusoids: amplitude and frequency
 * of on-bin and off-bin tones with the Hann and rectangular windows, mean removal,
 * sub-harmonic detection, peak ordering, errors. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/spectrum.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double *tone(int n, double dt, double mean, double a1, double f1, double a2, double f2)
{
    double *x = malloc((size_t)n * sizeof *x);
    for (int j = 0; j < n; j++)
        x[j] = mean + a1 * sin(2 * M_PI * f1 * j * dt + 0.3) + a2 * cos(2 * M_PI * f2 * j * dt);
    return x;
}

static gd_spectrum *spectrum(const double *x, int n, double dt, gd_window w)
{
    gd_spectrum *s = NULL;
    gd_error err;
    if (gd_spectrum_compute(x, n, dt, w, &s, &err)) fprintf(stderr, "  %s\n", err.message);
    return s;
}

/* A tone on bin 100 reads its amplitude exactly at that bin, both windows; mean gone. */
TEST(on_bin_tone)
{
    int n = 4096;
    double dt = 1e-4, df = 1.0 / (n * dt), f = 100 * df;
    double *x = tone(n, dt, 5.0, 2.5, f, 0.0, 0.0);
    for (int w = 0; w < 2; w++) {
        gd_spectrum *s = spectrum(x, n, dt, (gd_window)w);
        CHECK(s != NULL);
        if (!s) continue;
        CHECK(s->n == n / 2 + 1);
        CHECK_REL(s->df, df, 1e-12);
        CHECK_REL(s->freq[100], f, 1e-12);
        CHECK_REL(s->amplitude[100], 2.5, 1e-12);
        CHECK(s->amplitude[0] < 1e-12); /* mean removed */
        if (w == GD_WINDOW_RECT) {
            CHECK(s->amplitude[99] < 1e-10);
            CHECK(s->amplitude[103] < 1e-10);
        } else {
            /* Hann: the neighbours read half, leakage stops two bins away */
            CHECK_REL(s->amplitude[99], 1.25, 1e-9);
            CHECK(s->amplitude[102] < 1e-10);
        }
        gd_spectrum_peak pk[3];
        int np = gd_spectrum_peaks(s, 1e-6, 3, pk);
        CHECK(np >= 1);
        CHECK(pk[0].bin == 100);
        CHECK_REL(pk[0].frequency, f, 1e-9);
        CHECK_REL(pk[0].amplitude, 2.5, 1e-9);
        gd_spectrum_free(s);
    }
    free(x);
}

/* Off-bin tone (bin 123.37): the refined peak recovers frequency and amplitude; the raw
 * bin shows the scalloping loss of each window. */
TEST(off_bin_tone)
{
    int n = 8192;
    double dt = 5e-5, df = 1.0 / (n * dt), f = 123.37 * df;
    double *x = tone(n, dt, 0.0, 1.7, f, 0.0, 0.0);
    gd_spectrum *h = spectrum(x, n, dt, GD_WINDOW_HANN);
    gd_spectrum *r = spectrum(x, n, dt, GD_WINDOW_RECT);
    CHECK(h && r);
    if (h && r) {
        gd_spectrum_peak p;
        CHECK(gd_spectrum_peaks(h, 0.01, 1, &p) == 1);
        CHECK(p.bin == 123);
        CHECK_REL(p.frequency, f, 2e-5);
        CHECK_REL(p.amplitude, 1.7, 2e-4);
        /* Hann response at 0.37 bin: sinc(0.37) / (1 - 0.37^2) */
        double a = 0.37, hr = sin(M_PI * a) / (M_PI * a) / (1 - a * a);
        CHECK_REL(h->amplitude[123], 1.7 * hr, 2e-3);
        CHECK(gd_spectrum_peaks(r, 0.01, 1, &p) == 1);
        CHECK_REL(p.frequency, f, 5e-4);
        CHECK_REL(p.amplitude, 1.7, 5e-3);
        /* rectangular scalloping is much larger than Hann's */
        CHECK(r->amplitude[123] < 0.82 * 1.7);
    }
    gd_spectrum_free(h);
    gd_spectrum_free(r);
    free(x);
}

/* A response at w plus a weak 1/2 sub-harmonic: the peaks come out in decreasing
 * amplitude, the sub-harmonic at order 0.5 with its amplitude; band maxima. */
TEST(subharmonic)
{
    int n = 6000;
    double dt = 1.0 / 20000, f1 = 863.4, fs = f1 / 2;
    double *x = tone(n, dt, 1e-5, 40e-6, f1, 3e-6, fs);
    gd_spectrum *s = spectrum(x, n, dt, GD_WINDOW_HANN);
    CHECK(s != NULL);
    if (s) {
        gd_spectrum_peak pk[4];
        int np = gd_spectrum_peaks(s, 0.01, 4, pk);
        CHECK(np == 2);
        CHECK_REL(pk[0].frequency, f1, 1e-4);
        CHECK_REL(pk[0].amplitude, 40e-6, 2e-3);
        CHECK_REL(pk[1].frequency, fs, 1e-4);
        CHECK_REL(pk[1].amplitude, 3e-6, 5e-3);
        double fat;
        double below = gd_spectrum_band_max(s, 3 * s->df, 0.95 * f1, &fat);
        CHECK(below > 2.5e-6 && below <= 3.01e-6);
        CHECK(fabs(fat - fs) < 1.5 * s->df);
        /* without the sub-harmonic nothing above leakage level below 0.95x */
        free(x);
        x = tone(n, dt, 1e-5, 40e-6, f1, 0.0, fs);
        gd_spectrum_free(s);
        s = spectrum(x, n, dt, GD_WINDOW_HANN);
        CHECK(gd_spectrum_band_max(s, 3 * s->df, 0.95 * f1, NULL) < 1e-9);
    }
    gd_spectrum_free(s);
    free(x);
}

/* max limits the count and keeps the largest; min_rel filters. */
TEST(peak_selection)
{
    int n = 2048;
    double dt = 1e-3, df = 1.0 / (n * dt);
    double *x = malloc((size_t)n * sizeof *x);
    double amp[5] = {1.0, 0.5, 0.25, 0.125, 0.01};
    for (int j = 0; j < n; j++) {
        x[j] = 0;
        for (int k = 0; k < 5; k++)
            x[j] += amp[k] * cos(2 * M_PI * (50 + 60 * k) * df * j * dt);
    }
    gd_spectrum *s = spectrum(x, n, dt, GD_WINDOW_HANN);
    gd_spectrum_peak pk[5];
    CHECK(gd_spectrum_peaks(s, 0.0, 3, pk) == 3);
    CHECK(pk[0].bin == 50 && pk[1].bin == 110 && pk[2].bin == 170);
    CHECK(gd_spectrum_peaks(s, 0.05, 5, pk) == 4); /* 0.01 is below 5 % of the top */
    CHECK_REL(pk[3].amplitude, 0.125, 1e-9);
    gd_spectrum_free(s);
    free(x);
}

TEST(errors)
{
    double x[8] = {0, 1, 0, -1, 0, 1, 0, -1};
    gd_spectrum *s = NULL;
    gd_error err;
    CHECK(gd_spectrum_compute(x, 3, 1e-3, GD_WINDOW_HANN, &s, &err) == GD_EINPUT);
    CHECK(s == NULL);
    CHECK(gd_spectrum_compute(x, 8, 0.0, GD_WINDOW_HANN, &s, &err) == GD_EINPUT);
    CHECK(gd_spectrum_compute(x, 8, -1.0, GD_WINDOW_HANN, &s, &err) == GD_EINPUT);
    x[2] = NAN;
    CHECK(gd_spectrum_compute(x, 8, 1e-3, GD_WINDOW_HANN, &s, &err) == GD_EINPUT);
    x[2] = 0;
    CHECK(gd_spectrum_compute(x, 8, 1e-3, GD_WINDOW_RECT, &s, &err) == GD_OK);
    /* 8 samples of period 4: bin 2 holds amplitude 1 (odd length: 7 samples also fine) */
    CHECK_REL(s->amplitude[2], 1.0, 1e-12);
    CHECK_STR(gd_window_names[GD_WINDOW_HANN], "hann");
    gd_spectrum_free(s);
    CHECK(gd_spectrum_compute(x, 7, 1e-3, GD_WINDOW_HANN, &s, &err) == GD_OK);
    CHECK(s && s->n == 4);
    gd_spectrum_free(s);
}

RUN_TESTS(T(on_bin_tone), T(off_bin_tone), T(subharmonic), T(peak_selection), T(errors))
