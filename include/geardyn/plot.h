/* Plots: the standard figure of each analysis, built from its result struct and written
 * as static SVG (drawn by geardyn itself, for papers and CI artefacts) or as one
 * self-contained interactive HTML file (plotly.js inlined, opens offline) with the
 * numbers behind every plot downloadable as CSV from the page. docs/plots.md.
 *
 * A gd_plot is a document: one or more sections (a title, panels of curves, tables, a
 * CSV of its numbers). Each gd_plot_<analysis> builds one section; gd_plot_append moves
 * the sections of one document to the end of another (the report is made this way). A
 * new analysis gets its figure by one more gd_plot_<analysis> function.
 *
 * Writing: the format follows the file name (".svg" or ".html"); the file is written to
 * a temporary name beside it and renamed into place, so a failure leaves nothing.
 * HTML needs plotly.min.js, found in this order: gd_plot_write_options.plotly_js, the
 * environment variable GEARDYN_PLOTLY_JS, the installed copy (DATADIR/geardyn/
 * plotly.min.js beside the library or program, `make install` puts it there), and the
 * source tree's node_modules (an uninstalled build).
 *
 * Ownership and threads: every gd_plot_<analysis> returns a document the caller frees
 * with gd_plot_free; the results, systems and options passed in are only read, during
 * the call (the document keeps copies of the numbers it plots). Distinct documents may
 * be built and written from different threads at once.
 */
#ifndef GEARDYN_PLOT_H
#define GEARDYN_PLOT_H
#include "geardyn/export.h"
#include "geardyn/campbell.h"
#include "geardyn/correlate.h"
#include "geardyn/ema.h"
#include "geardyn/error.h"
#include "geardyn/frf.h"
#include "geardyn/mesh_stiffness.h"
#include "geardyn/modal.h"
#include "geardyn/periodic.h"
#include "geardyn/rattle.h"
#include "geardyn/static.h"
#include "geardyn/system.h"
#include "geardyn/transient.h"
#include "geardyn/unbalance.h"
#include "geardyn/waterfall.h"

typedef struct gd_plot gd_plot;

/* PNG and PDF are the SVG rendered by librsvg and cairo (one image; one PDF page per
 * section, long sections split between panels), when the library was built with them. */
typedef enum gd_plot_format { GD_PLOT_SVG, GD_PLOT_HTML, GD_PLOT_PNG, GD_PLOT_PDF } gd_plot_format;

/* The format of a file name by its extension (".svg", ".html" or ".htm", ".png", ".pdf",
 * any case). GD_EINPUT naming the known extensions otherwise. */
GD_API gd_status gd_plot_format_of(const char *path, gd_plot_format *fmt, gd_error *err);
/* Checks, before any computing, that path has a known extension and that its folder
 * exists and can be written into; for HTML also that plotly.js can be found, for PNG and
 * PDF that this build can write them (GD_EINPUT naming the missing packages otherwise);
 * opts may be NULL. Writes nothing. */
typedef struct gd_plot_write_options {
    const char *plotly_js; /* path of plotly.min.js; NULL: look for it (see top) */
} gd_plot_write_options;
GD_API void gd_plot_write_options_init(gd_plot_write_options *opt);
GD_API gd_status gd_plot_check_path(const char *path, const gd_plot_write_options *opt,
                                    gd_error *err);
/* Writes the document to path (format by extension). Nothing is left at path on
 * failure. */
GD_API gd_status gd_plot_write(const gd_plot *p, const char *path, const gd_plot_write_options *opt,
                               gd_error *err);
/* The plotly.min.js that would be inlined (see top), or GD_EIO listing where it looked. */
GD_API gd_status gd_plot_find_plotly(const gd_plot_write_options *opt, char *path, size_t size,
                                     gd_error *err);

/* An empty document with a title (the page title of the HTML). */
GD_API gd_status gd_plot_new(const char *title, gd_plot **out, gd_error *err);
/* Appends a section holding only a title and a paragraph. */
GD_API gd_status gd_plot_add_note(gd_plot *p, const char *title, const char *text, gd_error *err);
/* Moves every section of src to the end of dst and frees src. */
GD_API gd_status gd_plot_append(gd_plot *dst, gd_plot *src, gd_error *err);
/* Changes the unit of every x axis labelled "(from)" (e.g. "Hz") to "(to)" (e.g.
 * "rad/s"): its values times factor, its label rewritten; and every "<number> from" in
 * a hover label of any trace to "<number x factor> to". For --units; returns the number
 * of axes changed. The CSV keeps its own units. */
GD_API int gd_plot_convert_x(gd_plot *p, const char *from, const char *to, double factor);
/* Sections and plotted curves (traces) of a document, for tests and callers. */
GD_API int gd_plot_nsections(const gd_plot *p);
GD_API int gd_plot_npanels(const gd_plot *p, int section);
GD_API int gd_plot_ntraces(const gd_plot *p, int section, int panel);
GD_API void gd_plot_free(gd_plot *p);

/* Modes: the shape of each elastic mode along each shaft (lateral x and y, axial,
 * torsion; gears and bearings drawn on the axis), an animated 3-D view of the whirl (HTML
 * only) and the strain-energy table by motion type and by component ([JMSTHelical] Tables 4-7).
 * GD_EINPUT when every mode is a rigid-body mode (nothing to plot). */
GD_API gd_status gd_plot_modal(const gd_system *sys, const gd_modal_result *r, gd_plot **out,
                               gd_error *err);

/* Campbell diagram: damped natural frequency (Hz) over speed (rpm) of each tracked mode,
 * coloured by whirl (forward blue, backward red, mixed purple, none grey; each point
 * by its whirl at that speed, the line by the mode's most frequent whirl), the
 * excitation orders (1x of each shaft, user orders, tooth-mesh orders) as lines, the
 * critical speeds marked and listed, and a log-decrement panel with the instability
 * onset. GD_EINPUT when no mode was tracked. */
GD_API gd_status gd_plot_campbell(const gd_campbell_result *r, gd_plot **out, gd_error *err);
/* What gd_plot_campbell_opt draws beyond the defaults of gd_plot_campbell. */
typedef struct gd_plot_campbell_options {
    double max_frequency_hz;           /* > 0: the frequency axis ends here; modes wholly above
                                          it and critical speeds above it are left out */
    double operating_lo, operating_hi; /* rad/s; lo < hi: the operating range shaded and the
                                          separation margin of each critical speed to it */
    int speed_rad_s;                   /* speed axis in rad/s (default rpm) */
    int frequency_rad_s; /* frequency axis in rad/s (default Hz; max_frequency_hz stays Hz) */
} gd_plot_campbell_options;
GD_API void gd_plot_campbell_options_init(gd_plot_campbell_options *opt);
/* gd_plot_campbell with options (opt may be NULL: the defaults). The separation margin
 * of a critical speed N to the range [lo, hi] is (lo - N) / lo below it, (N - hi) / hi
 * above it, and 0 inside it (API 684 style). */
GD_API gd_status gd_plot_campbell_opt(const gd_campbell_result *r,
                                      const gd_plot_campbell_options *opt, gd_plot **out,
                                      gd_error *err);

/* Frequency response: Bode (magnitude, log scale; phase) over frequency (Hz) and
 * Nyquist (real vs imaginary) of every output; with a directional input (ninputs == 2,
 * outputs in x, y pairs) the forward and backward FRFs (gd_frf_directional) instead.
 * opt is the one the result was computed with (its outputs name the curves). */
GD_API gd_status gd_plot_frf(const gd_system *sys, const gd_frf_options *opt,
                             const gd_frf_result *r, gd_plot **out, gd_error *err);

/* Unbalance response: amplitude (log) and phase of every output and harmonic over speed
 * (rpm), polar plot, and the orbits of the orbit nodes at orbit_speed (rad/s; <= 0:
 * the speed where the largest orbit is largest). */
GD_API gd_status gd_plot_unbalance(const gd_system *sys, const gd_unbalance_options *opt,
                                   const gd_unbalance_result *r, double orbit_speed, gd_plot **out,
                                   gd_error *err);

/* Transient: time history of every record (grouped by quantity), orbits of nodes whose
 * x and y displacements are both recorded, the amplitude spectrum of each record
 * (FFTW, Hann window) and the contact state of each recorded mesh (drive / separated /
 * coast). GD_EINPUT when there is no record or fewer than 4 samples. */
/* Curves of a parameter study (`geardyn study --plot`): one panel per output, the output
 * over x (nx values), one curve per family (nfam, labelled). y[(o * nfam + f) * nx + i]
 * is output o of family f at x[i] (NaN: no such case, left out). GD_EINPUT when nx < 1,
 * nfam < 1 or nout < 1. */
GD_API gd_status gd_plot_lines(const char *title, const char *xlabel, int nx, const double *x,
                               int nfam, const char *const *families, int nout,
                               const char *const *outputs, const double *y, gd_plot **out,
                               gd_error *err);
/* The rattle metrics of n meshes (geardyn/rattle.h; names[k] labels metrics k): a table
 * of the metrics with their confidence half-widths and the impact-speed histograms of
 * the drive and the coast flank (docs/rattle.md). GD_EINPUT when n < 1. */
GD_API gd_status gd_plot_rattle(const char *const *names, const gd_rattle_metrics *metrics, int n,
                                gd_plot **out, gd_error *err);
GD_API gd_status gd_plot_transient(const gd_system *sys, const gd_transient_result *r,
                                   gd_plot **out, gd_error *err);

/* Time-varying mesh stiffness over the sampled mesh cycles (driver angle, deg) with
 * the single- and double-contact zones shaded, the stiffness of each tooth pair in
 * contact (its load share x k), the ISO 6336 values and the Fourier harmonics. With
 * n > 1 results (e.g. other helix angles) a comparison panel over the mesh cycle
 * overlays them; labels (may be NULL) name them. name: the mesh's name (may be NULL). */
GD_API gd_status gd_plot_tvms(const gd_tvms_result *const *r, const char *const *labels, int n,
                              const char *name, gd_plot **out, gd_error *err);

/* The model drawn to scale in a side view: shaft sections, gears (pitch diameters),
 * disks, bearings, meshes, with a summary table of shafts, bearings and meshes. Shafts
 * joined by a mesh are placed one centre distance apart. */
GD_API gd_status gd_plot_model(const gd_model *m, gd_plot **out, gd_error *err);

/* Periodic steady state (harmonic balance): per record, the peak-to-peak value and the
 * amplitudes of the first harmonics over the speed (rpm), or over the continuation
 * parameter (gd_periodic_param), along the branch: stable stretches solid, unstable ones
 * dashed red, the return run (both_directions) as its own curves; the bifurcations
 * marked by type (fold, period doubling, Neimark-Sacker, branch point) and listed in a
 * table; the largest Floquet multiplier modulus with the line |mu| = 1. records: the
 * r->nrecords records the run was given (they name the curves). GD_EINPUT when no point
 * converged or there is no record. */
GD_API gd_status gd_plot_periodic(const gd_system *sys, const gd_periodic_result *r,
                                  const gd_tr_record *records, gd_plot **out, gd_error *err);

/* Static analysis: x and y deflection and the slopes (rx, ry) along every shaft, the
 * bearings marked (hover: their reactions), and tables of the bearing reactions and of
 * each mesh's force and misalignment (docs/static.md). GD_EINPUT without shafts. */
GD_API gd_status gd_plot_static(const gd_system *sys, const gd_static_result *r, gd_plot **out,
                                gd_error *err);

/* Run-up waterfall (geardyn/waterfall.h) of the record rec: the cascade of the spectra
 * stacked by speed (each drawn from its speed up, the largest amplitude = 3 speed steps;
 * hover: the amplitude), the colour map over speed and frequency (6 dB levels down to
 * 48 dB below the largest amplitude) and the order cuts (log), with the orders (1x of each
 * shaft red, tooth-mesh green) as lines f = order x speed / 2 pi named on the plot.
 * GD_EINPUT when there is no spectrum. */
typedef struct gd_plot_waterfall_options {
    double max_frequency_hz; /* > 0: the frequency axis ends here; 0: 1.2 x the highest
                                order at the top speed (within the spectra's last bin) */
    int speed_rad_s;         /* speed axes in rad/s (default rpm) */
    int frequency_rad_s;     /* frequency axes in rad/s (default Hz) */
} gd_plot_waterfall_options;
GD_API void gd_plot_waterfall_options_init(gd_plot_waterfall_options *opt);
GD_API gd_status gd_plot_waterfall(const gd_system *sys, const gd_waterfall *w,
                                   const gd_tr_record *rec, const gd_plot_waterfall_options *opt,
                                   gd_plot **out, gd_error *err);

/* Test data (docs/testing.md): the stabilisation diagram of an LSCF fit r of the FRFs
 * frfs (poles over model order by stability, the summed |H| on the right-hand axis,
 * the chosen modes dashed); the overlay of the model's FRFs (model_re/_im[o]: frfs[o]'s
 * lines) on the measured ones, magnitude and phase, after the correlation table t (may
 * be NULL). */
GD_API gd_status gd_plot_stabilisation(const gd_ema_result *r, int nfrf,
                                       const gd_td_function *const *frfs, gd_plot **out,
                                       gd_error *err);
GD_API gd_status gd_plot_correlation(int nfrf, const gd_td_function *const *frfs,
                                     const double *const *model_re, const double *const *model_im,
                                     const gd_corr_table *t, gd_plot **out, gd_error *err);

#endif
