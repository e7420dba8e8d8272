/* Unbalance response: the steady response to the model's rotating unbalances over a
 * range of reference speeds, one harmonic per distinct shaft speed, with orbits.
 *
 * Ownership and threads: gd_unbalance_response returns a result the caller frees with
 * gd_unbalance_free; the options' arrays are borrowed for the call only. Speeds are
 * solved in parallel (OpenMP), bitwise the same on any number of threads; separate
 * calls may run concurrently on one system.
 */
#ifndef GEARDYN_UNBALANCE_H
#define GEARDYN_UNBALANCE_H
#include "geardyn/export.h"
#include "geardyn/modal.h"
#include "geardyn/probe.h"

typedef struct gd_unbalance_options {
    int nspeeds;
    const double *speeds; /* reference speeds, rad/s */
    int noutputs;
    const gd_probe *outputs;
    int norbits;
    const int *orbit_nodes; /* nodes with x and y active */
    int nthreads;
} gd_unbalance_options;

typedef struct gd_orbit {
    double major, minor; /* semi-axes, m */
    double angle;        /* of the major axis from +x, rad */
    gd_whirl whirl;      /* relative to the node's shaft rotation */
} gd_orbit;

/* Unbalances on shafts turning at different |speed ratio| give different harmonics:
 * one harmonic per distinct |ratio|, frequency = order x reference speed. */
typedef struct gd_unbalance_harmonic {
    double order; /* |speed_ratio| of the shafts whose unbalances make it */
    int nunbalances;
} gd_unbalance_harmonic;

typedef struct gd_unbalance_result {
    int nspeeds, noutputs, norbits, nharmonics;
    double *speeds;
    gd_unbalance_harmonic *harmonics;
    /* response[(h * noutputs + o) * nspeeds + s]: complex amplitude, x = Re(X e^{i w t}) */
    double *re, *im;
    gd_orbit *orbits; /* [(h * norbits + k) * nspeeds + s] */
    int *singular;    /* nspeeds */
} gd_unbalance_result;

GD_API void gd_unbalance_options_init(gd_unbalance_options *opt);
GD_API gd_status gd_unbalance_response(const gd_system *sys, const gd_unbalance_options *opt,
                                       gd_unbalance_result **out, gd_error *err);
GD_API void gd_unbalance_free(gd_unbalance_result *r);

/* Orbit of a node from the complex amplitudes X, Y of its x and y motion; sense is the
 * sign of its shaft's speed ratio (+1 turns about +z). */
GD_API void gd_orbit_from(double xr, double xi, double yr, double yi, double sense, gd_orbit *o);

#endif
