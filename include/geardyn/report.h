/* A whole study in one self-contained HTML file (or SVG): the model drawn to scale and
 * summarised, its modes, the Campbell diagram with critical speeds and stability, the
 * FRFs at the meshes and bearings, the unbalance response, and the time-varying mesh
 * stiffness of every mesh whose stiffness comes from its geometry, and a run-up waterfall
 * when asked (runup_from, runup_to). Each analysis runs
 * with the options below; the document is made of the gd_plot_<analysis> figures
 * (geardyn/plot.h). docs/plots.md.
 *
 * Ownership and threads: gd_report_build returns a document the caller frees with
 * gd_plot_free; the model, the system and the options are only read during the call.
 * Analyses run in parallel inside (OpenMP, opt.nthreads); separate reports may be built
 * at once from one system.
 */
#ifndef GEARDYN_REPORT_H
#define GEARDYN_REPORT_H
#include "geardyn/export.h"
#include "geardyn/error.h"
#include "geardyn/plot.h"
#include "geardyn/system.h"

typedef struct gd_report_options {
    int nspeeds;          /* Campbell and unbalance speeds; 0: 41 speeds from 0 to twice the */
    const double *speeds; /* model's speed (10000 rpm when it has none), rad/s */
    double speed;         /* modes and FRFs at this reference speed, rad/s; < 0: the model's */
    int nmodes;           /* modes tracked in the Campbell diagram (default 8) */
    int nfreq;            /* FRF frequencies (default 400), up to 1.3 x the highest mode shown */
    int nthreads;         /* OpenMP threads of the sweeps; 0: the OpenMP default */
    /* Run-up waterfall (docs/plots.md, "Report"): when runup_to != runup_from (rad/s, one
     * sign), a transient through the ramp from runup_from to runup_to lasting
     * runup_revolutions turns of the reference shaft at the mean speed (default 200),
     * forced by the model's unbalances, transmission errors and laws (none: a note says
     * so), its record (the first unbalance's node x, else the first mesh force, else the
     * first disk's x) order-tracked in blocks of 8 turns at S points per turn (the power
     * of two >= 2.5 x the highest mesh-law order, at least 32), integrated by
     * generalized-alpha at 2 S steps per turn at the top speed: the waterfall, order map
     * and cuts (over 2e7 steps: a note instead). */
    double runup_from, runup_to;
    double runup_revolutions;
} gd_report_options;

GD_API void gd_report_options_init(gd_report_options *opt);
/* Runs the analyses on sys (built from its model) and assembles the document. */
GD_API gd_status gd_report_build(const gd_system *sys, const gd_report_options *opt, gd_plot **out,
                                 gd_error *err);

#endif
