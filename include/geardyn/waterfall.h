/* Run-up waterfall (cascade) and order cuts: the amplitude spectrum of one record at each
 * speed of a stepped (quasi-steady) run-up, i.e. one steady run per speed started from
 * the previous speed's end state (geardyn transient --sweep-speeds --waterfall), or of
 * each block of revolutions of one run through a speed profile (computed order
 * tracking, gd_waterfall_order_track; geardyn transient --speed-ramp --waterfall), with
 * the excitation orders of the model (1x of each shaft, tooth-mesh orders: the Campbell
 * diagram's, gd_campbell) and the amplitude of each order against speed.
 *
 * Order cut: at speed W the amplitude of order o is the largest spectral amplitude within
 * 1.5 bins of o W / 2 pi (Hz), so a tone between two bins (a run that is not a whole
 * number of periods of that order) is still found; NaN when o W / 2 pi is above the
 * spectrum's last bin (Nyquist).
 *
 * Ownership and threads: gd_waterfall_new takes ownership of the n spectra (freed by
 * gd_waterfall_free, also when it fails) and copies the speeds; gd_waterfall_order_track
 * borrows its arrays for the call and returns a waterfall the caller frees with
 * gd_waterfall_free; calls may run on several threads at once (FFTW's planner is
 * serialised by the library). The system is read during the call only. A result may be
 * read from several threads at once.
 */
#ifndef GEARDYN_WATERFALL_H
#define GEARDYN_WATERFALL_H
#include "geardyn/export.h"
#include "geardyn/campbell.h"
#include "geardyn/error.h"
#include "geardyn/spectrum.h"
#include "geardyn/system.h"

typedef struct gd_waterfall {
    int nspeeds;
    double *speeds;        /* reference speed of each spectrum, rad/s */
    gd_spectrum **spectra; /* nspeeds, owned */
    int norders;
    gd_order *orders;        /* 1x of each shaft, tooth-mesh orders (gd_campbell's) */
    double *order_amplitude; /* norders x nspeeds: [o * nspeeds + s], units of the record */
    double *order_frequency; /* same layout: Hz where that amplitude was found */
    /* order tracking (gd_waterfall_order_track): 1, and the revolutions of the reference
     * shaft per spectrum (bins are 1 / revs_per_block orders apart; a spectrum's freq is
     * order x its block's mean speed / 2 pi); 0 for a stepped run-up */
    int tracked;
    double revs_per_block;
} gd_waterfall;

/* n >= 1 spectra with their speeds (> 0, finite). GD_EINPUT otherwise. */
GD_API gd_status gd_waterfall_new(const gd_system *sys, int n, const double *speeds,
                                  gd_spectrum **spectra, gd_waterfall **out, gd_error *err);
GD_API void gd_waterfall_free(gd_waterfall *w);

/* Computed order tracking of a run-up record: x (n samples at increasing times t) is
 * resampled at samples_per_rev equal steps of the reference shaft's angle (angle, rad, at
 * the same samples, monotonic: the profile's phi(t)) by linear interpolation, cut into
 * blocks of revs_per_block revolutions (overlapping by `overlap`), and each block's
 * amplitude spectrum (gd_spectrum_compute over the angle: bins are orders) taken as the
 * spectrum at the block's mean speed (its angle span over its duration). Orders of a
 * shaft are exact bins (no leakage for a constant order); a block's speed changes by
 * the ramp's acceleration x its duration, its resolution. Needs the record sampled at
 * least 2 x samples_per_rev per revolution at the top speed to avoid interpolation loss
 * (checked: GD_EINPUT). GD_EINPUT also for fewer than one block or a reversing angle. */
typedef struct gd_order_track_options {
    double revs_per_block; /* default 16 */
    int samples_per_rev;   /* default 64 (orders up to 32 per block) */
    double overlap;        /* 0 .. 0.9, default 0.5 */
    gd_window window;      /* default Hann */
} gd_order_track_options;
GD_API void gd_order_track_options_init(gd_order_track_options *opt);
GD_API gd_status gd_waterfall_order_track(const gd_system *sys, const double *t, const double *x,
                                          const double *angle, int n,
                                          const gd_order_track_options *opt, gd_waterfall **out,
                                          gd_error *err);

#endif
