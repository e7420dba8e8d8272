/* Rattle metrics of a backlash gear mesh (docs/rattle.md): from the log of its contact
 * changes over a window (a transient's gd_transient_result.contact_events of that mesh),
 * the fraction of time the teeth are apart, the impacts per second on the drive and on
 * the coast flank, the distribution of the impact speeds and an impact-energy rattle
 * intensity, each with a confidence interval from batch means (the window cut into equal
 * batches; Student's t on the batch values), and the window length that would reach a
 * wanted precision.
 *
 * Ownership and threads: the functions read their arguments for the call only, allocate
 * nothing and keep no state: thread-safe on distinct results.
 */
#ifndef GEARDYN_RATTLE_H
#define GEARDYN_RATTLE_H
#include "geardyn/error.h"
#include "geardyn/export.h"

#define GD_RATTLE_BINS 16

/* One contact change: time (s), the contact states before and after (-1 coast flank, 0
 * separated, 1 drive flank) and the approach speed d_e' at the change (m/s). */
typedef struct gd_rattle_event {
    double t;
    int from, to;
    double velocity;
} gd_rattle_event;

typedef struct gd_rattle_options {
    double t0, t1;     /* the window, s (t1 > t0) */
    int state0;        /* the contact state at t0 when the log is empty (else the first
                          event's `from`) */
    int batches;       /* batch means: batches of equal length (default 10, >= 2) */
    double confidence; /* two-sided level of the intervals (default 0.95) */
    double mass;       /* the mesh's effective mass along its line of action, kg: the
                          intensity is sum(m v^2 / 2) per second, W; 0: sum(v^2) per second,
                          m^2/s^3 */
    double vmax;       /* histogram range of |v|: [0, vmax) in GD_RATTLE_BINS bins, larger
                          speeds in the last (0: the largest impact speed) */
    double target;     /* the relative half-width wanted (default 0.1) */
} gd_rattle_options;
GD_API void gd_rattle_options_init(gd_rattle_options *o);

/* A mean over the window (= the mean of the batch values) and its confidence
 * half-width t_{B-1} s_B / sqrt(B). */
typedef struct gd_rattle_estimate {
    double mean, half_width;
} gd_rattle_estimate;

typedef struct gd_rattle_metrics {
    double duration;                           /* t1 - t0 */
    int batches;                               /* B */
    double confidence, t_quantile;             /* the level and t_{B-1} */
    gd_rattle_estimate separated;              /* fraction of time apart (0..1) */
    gd_rattle_estimate drive_rate, coast_rate; /* impacts per second on each flank */
    gd_rattle_estimate intensity;              /* W (or m^2/s^3 with mass 0) */
    int drive_impacts, coast_impacts;          /* counts in the window */
    double v_mean, v_rms, v_max;               /* |impact speed| over both flanks, m/s */
    double bin_width;                          /* histogram bin, m/s */
    int hist_drive[GD_RATTLE_BINS], hist_coast[GD_RATTLE_BINS];
    /* the largest relative half-width of separated, the total impact rate and the
     * intensity (those with a nonzero mean; 0 when nothing rattles) */
    double precision;
    /* the window that would reach target: duration (precision / target)^2 (the half-width
     * falls as 1/sqrt(duration)); duration when already reached */
    double suggested_duration;
    int converged; /* precision <= target */
} gd_rattle_metrics;

/* The metrics of the events ev[0 .. n-1] (in time order; those outside [t0, t1] are
 * skipped) over the window. An impact is a change from 0 (separated) to a flank.
 * GD_EINPUT: a window not t1 > t0, batches < 2, confidence outside (0, 1), a negative mass
 * or vmax, events out of time order or with a non-finite time or speed, or a state not
 * -1, 0, 1. */
GD_API gd_status gd_rattle_metrics_eval(const gd_rattle_event *ev, int n,
                                        const gd_rattle_options *o, gd_rattle_metrics *out,
                                        gd_error *err);

/* The quantile of Student's t distribution with dof > 0 degrees of freedom at probability
 * p in (0, 1) (the regularised incomplete beta function inverted by bisection to 1e-12
 * relative; NAN outside the domain). */
GD_API double gd_student_t_quantile(double p, double dof);

#endif
