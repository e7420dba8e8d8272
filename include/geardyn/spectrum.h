/* One-sided amplitude spectrum of a uniformly sampled real signal (FFTW3), for the
 * steady part of a transient record: sub-harmonics, super-harmonics, mesh orders.
 *
 * The mean is removed, the window applied, and the DFT X_k of the n samples scaled so
 * that a sinusoid of amplitude A whose frequency falls on a bin reads A at that bin:
 *   amplitude_k = c_k |X_k| / sum(w),  c_k = 2 (c_0 = 1, and c_{n/2} = 1 for even n).
 * Bins are df = 1 / (n dt) apart (Hz), k = 0 .. n/2.
 *
 * Thread safety: FFTW's planner is not thread-safe. Every plan here is made with
 * FFTW_ESTIMATE (no measurement, no wisdom written), used once and destroyed inside the
 * call; calls from several threads at the same time must still be serialised by the
 * caller (as FFTW requires for the planner). The execution itself is re-entrant.
 *
 * Ownership: gd_spectrum_compute returns a result the caller frees with
 * gd_spectrum_free; the samples are borrowed for the call only.
 */
#ifndef GEARDYN_SPECTRUM_H
#define GEARDYN_SPECTRUM_H
#include "geardyn/export.h"
#include "geardyn/error.h"

typedef enum gd_window {
    GD_WINDOW_HANN = 0, /* w_j = 0.5 (1 - cos(2 pi j / n)), periodic Hann (default) */
    GD_WINDOW_RECT = 1  /* no window */
} gd_window;
GD_API extern const char *const gd_window_names[2]; /* "hann", "rect" */

typedef struct gd_spectrum {
    int nsamples;
    double dt; /* s */
    gd_window window;
    int n;             /* bins: nsamples / 2 + 1 */
    double df;         /* Hz */
    double *freq;      /* n, Hz */
    double *amplitude; /* n, units of the signal */
} gd_spectrum;

/* nsamples >= 4, dt > 0, finite samples. */
GD_API gd_status gd_spectrum_compute(const double *x, int nsamples, double dt, gd_window window,
                                     gd_spectrum **out, gd_error *err);
GD_API void gd_spectrum_free(gd_spectrum *s);

/* A spectral peak, refined between bins from the two largest bins (exact for a single
 * tone of the window's shape: Hann dk = (2a - 1) / (a + 1), rectangular dk = a / (1 + a),
 * a = |X_{k+1}| / |X_k|; the amplitude corrected for the window's response at dk). */
typedef struct gd_spectrum_peak {
    int bin;          /* bin of the local maximum */
    double frequency; /* Hz, refined */
    double amplitude; /* refined */
} gd_spectrum_peak;

/* The largest local maxima of the amplitude (bins 1 .. n-2, at least min_rel times the
 * largest amplitude), at most max of them, in decreasing amplitude. Returns how many. */
GD_API int gd_spectrum_peaks(const gd_spectrum *s, double min_rel, int max, gd_spectrum_peak *out);

/* Largest amplitude over bins with f_lo <= f <= f_hi (0 if none); *f_at its frequency. */
GD_API double gd_spectrum_band_max(const gd_spectrum *s, double f_lo, double f_hi, double *f_at);

#endif
