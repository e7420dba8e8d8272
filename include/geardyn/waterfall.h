/* Run-up waterfall (cascade) and order cuts: the amplitude spectrum of one record at each
 * speed of a stepped (quasi-steady) run-up, i.e. one steady run per speed started from
 * the previous speed's end state (geardyn transient --sweep-speeds --waterfall), with the
 * excitation orders of the model (1x of each shaft, tooth-mesh orders: the Campbell
 * diagram's, gd_campbell) and the amplitude of each order against speed.
 *
 * Order cut: at speed W the amplitude of order o is the largest spectral amplitude within
 * 1.5 bins of o W / 2 pi (Hz), so a tone between two bins (a run that is not a whole
 * number of periods of that order) is still found; NaN when o W / 2 pi is above the
 * spectrum's last bin (Nyquist).
 *
 * Ownership and threads: gd_waterfall_new takes ownership of the n spectra (freed by
 * gd_waterfall_free, also when it fails) and copies the speeds; the system is read
 * during the call only. A result may be read from several threads at once.
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
} gd_waterfall;

/* n >= 1 spectra with their speeds (> 0, finite). GD_EINPUT otherwise. */
GD_API gd_status gd_waterfall_new(const gd_system *sys, int n, const double *speeds,
                                  gd_spectrum **spectra, gd_waterfall **out, gd_error *err);
GD_API void gd_waterfall_free(gd_waterfall *w);

#endif
