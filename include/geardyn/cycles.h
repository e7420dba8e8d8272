/* Responses over many periods: per-period statistics of uniformly sampled records, and a
 * verdict on once-per-period (Poincare) samples: periodic, period-N, quasi-periodic or
 * irregular. For responses with no stable periodic orbit (rattling gear trains), where
 * one period's peak-to-peak is not representative (docs/transient.md).
 *
 * Ownership and threads: every function reads its arguments for the call only, allocates
 * only temporaries it frees, writes only the result struct it is given and keeps no
 * state: all are thread-safe on distinct results.
 */
#ifndef GEARDYN_CYCLES_H
#define GEARDYN_CYCLES_H
#include "geardyn/error.h"
#include "geardyn/export.h"

/* A quantity over the periods: median, the 5 % and 95 % percentiles (linear
 * interpolation between order statistics, Hyndman & Fan 1996 type 7) and the extremes. */
typedef struct gd_cycle_band {
    double median, p05, p95, min, max;
} gd_cycle_band;

typedef struct gd_cycle_stats {
    int periods;                /* whole periods in the record */
    int min_samples;            /* fewest samples in one period (both ends included) */
    gd_cycle_band peak_to_peak; /* of each period's max - min */
    gd_cycle_band mean;         /* of each period's mean (trapezoidal over the period) */
    gd_cycle_band rms;          /* of each period's RMS (trapezoidal over the period) */
} gd_cycle_stats;

/* Statistics of x (n samples at t0 + i dt) over the whole periods [from + j T,
 * from + (j + 1) T], j = 0, 1, ..., that the samples cover (both ends within dt / 1000 of a
 * sample time count; a period is closed: its end sample is also the next one's start).
 * Samples aligned with the periods (dt = T / m, from on the grid) give every period the
 * same m + 1 samples. Peak-to-peak is that of the samples: sample finely enough for the
 * peaks (impacts). Errors (GD_EINPUT): n < 2, dt or T not > 0 and finite, a non-finite
 * sample, no whole period, or fewer than 3 samples in a period. */
GD_API gd_status gd_cycle_stats_compute(const double *x, int n, double t0, double dt, double period,
                                        double from, gd_cycle_stats *out, gd_error *err);

typedef enum gd_poincare_class {
    GD_POINCARE_PERIODIC = 0,       /* period-N, N >= 1 (period-1: the periodic orbit) */
    GD_POINCARE_QUASI_PERIODIC = 1, /* the points lie on an invariant closed curve (torus) */
    GD_POINCARE_IRREGULAR = 2       /* none of these: chaotic, or not settled */
} gd_poincare_class;

typedef struct gd_poincare_options {
    /* two points are the same when every record differs by at most tol times its scale
     * (e.g. its peak-to-peak over the run); default 1e-3 */
    double tol;
    /* quasi-periodic when some shift q returns every point, and the second half of the
     * points covers the first, within torus_tol of each record's spread over the section
     * (max - min of its points); default 0.2 */
    double torus_tol;
    int min_points; /* fewest points for the quasi-periodic test (default 32) */
} gd_poincare_options;

typedef struct gd_poincare_verdict {
    gd_poincare_class cls;
    int period;   /* N of period-N (1: periodic), 0 otherwise */
    int points;   /* n */
    int distinct; /* clusters at tol (greedy: a point joins the first cluster it equals) */
    double tol, torus_tol;
    /* the close-return test (0 when not run: periodic, or fewer than min_points points):
     * q in 1 .. n / 2 minimising return_distance = max over k of |x_{k+q} - x_k| (the
     * largest over the records of the difference over the record's spread over the
     * section); halves_distance: Hausdorff distance of the two halves of the points in
     * the same units */
    int return_shift;
    double return_distance, halves_distance;
    /* 1: the points repeat every N >= 2 at the tolerance but the differences between
     * points N apart still shrink (the last third's largest below half the first
     * third's): a decaying transient turning by about 2 pi / N per period, not a
     * period-N orbit; the verdict is then irregular (settle longer) */
    int converging;
} gd_poincare_verdict;

GD_API void gd_poincare_options_init(gd_poincare_options *o);

/* Verdict on n points of nrec records (record r, point k: values[r * n + k]), scale[r] > 0
 * the record's own size for the tolerance (its peak-to-peak over the run; a record with
 * scale 0 is compared to 1e-12 of its largest magnitude). o NULL: defaults.
 *  - period-N: the smallest N <= n / 2 with point k + N equal to point k for every k and
 *    exactly N distinct points;
 *  - quasi-periodic: a rotation on an invariant curve brings every point back near itself
 *    after some q steps (Dirichlet: some q <= Q has |q rho - p| < 1 / Q for the rotation
 *    number rho), uniformly along the curve (the close-return test of Lathrop & Kostelich
 *    1989 holds for every k, where chaos separates nearby points), and the set is
 *    recurrent (its two halves cover each other: not a drift or a slow approach);
 *    records that only take the values -1, 0 and 1 (contact states) and records constant
 *    at the tolerance are left out of these distances;
 *  - irregular: otherwise (chaos, noise-like rattle, a transient not settled; see
 *    converging).
 * Errors (GD_EINPUT): n < 1, nrec < 1, a non-finite value, bad options. */
GD_API gd_status gd_poincare_classify(const double *values, int nrec, int n, const double *scale,
                                      const gd_poincare_options *o, gd_poincare_verdict *v,
                                      gd_error *err);

/* "periodic", "period-N", "quasi-periodic" or "irregular" into buf. */
GD_API void gd_poincare_verdict_name(const gd_poincare_verdict *v, char *buf, int size);

#endif
