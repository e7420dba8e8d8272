/* Campbell diagram: damped modes over a range of speeds, tracked across speeds by mode
 * shape (MAC), critical speeds where a tracked mode meets an excitation order (1x of
 * each shaft, user orders, tooth-mesh orders), log decrement and the onset speed of
 * instability.
 *
 * Ownership and threads: gd_campbell returns a result the caller frees with
 * gd_campbell_free; the options and their arrays are borrowed for the call only. The
 * speeds are solved in parallel (OpenMP, opt.nthreads) with bitwise the same result on
 * any number of threads; separate calls may run concurrently on the same system.
 */
#ifndef GEARDYN_CAMPBELL_H
#define GEARDYN_CAMPBELL_H
#include "geardyn/export.h"
#include "geardyn/modal.h"

/* An excitation order: frequency = order x reference speed. */
typedef enum gd_order_kind {
    GD_ORDER_SHAFT, /* 1x of a shaft: |speed_ratio| */
    GD_ORDER_USER,  /* given by the user, multiples of the reference speed */
    GD_ORDER_MESH   /* tooth-mesh: teeth x shaft speed */
} gd_order_kind;

typedef struct gd_order {
    gd_order_kind kind;
    double order;   /* multiple of the reference speed */
    char label[96]; /* e.g. "1x driving", "2x", "mesh 48x driving" */
} gd_order;

typedef struct gd_campbell_options {
    int nspeeds;
    const double *speeds; /* reference speeds, rad/s, increasing */
    int nmodes;           /* elastic modes tracked, > 0; 0: all (dense) */
    gd_modal_kind kind;   /* damped (default AUTO) or undamped */
    gd_eig_method method; /* AUTO: the cheaper by gd_modal_solve's cost model */
    double shift;         /* sparse shift, rad/s; 0: automatic */
    int norders;
    const double *orders; /* user orders (multiples of the reference speed) */
    int shaft_orders;     /* add 1x of every shaft (default 1) */
    int mesh_orders;      /* add tooth-mesh orders of meshes with teeth (default 1) */
    double mac_min;       /* below this, a mode starts a new track (default 0.1) */
    int nthreads;         /* OpenMP threads; 0: the OpenMP default */
} gd_campbell_options;

typedef struct gd_critical_speed {
    int mode;     /* track id */
    int order;    /* index into orders */
    double speed; /* reference speed, rad/s */
    double speed_rpm;
    double frequency_hz;
} gd_critical_speed;

typedef struct gd_campbell_track {
    int id;
    gd_whirl whirl;            /* most frequent at speeds > 0 (none if never whirling) */
    gd_motion dominant_motion; /* most frequent over the speeds */
} gd_campbell_track;

typedef struct gd_campbell_result {
    int nspeeds, ntracks, ndof;
    double *speeds; /* rad/s */
    gd_campbell_track *tracks;
    /* ntracks x nspeeds (track-major: [t * nspeeds + s]); rigid_body = -1 marks a speed
     * where the track does not exist (its numbers are NaN) */
    gd_mode *modes;
    int norders;
    gd_order *orders;
    int ncritical;
    gd_critical_speed *critical; /* by speed */
    double instability_onset;    /* rad/s, interpolated; NAN when stable throughout */
    int instability_track;       /* -1 when stable */
    int nrigid;                  /* rigid-body modes left out of the tracks */
    int sparse;                  /* the sparse eigensolver was used */
    /* nspeeds flags, 1 where the laws find no static equilibrium at that speed (they are
     * linearised at q = 0 there; docs/bearings.md); NULL for a model without laws to
     * linearise (or --operating-point zero). Owned by the result. */
    int *no_equilibrium;
} gd_campbell_result;

GD_API void gd_campbell_options_init(gd_campbell_options *opt);
GD_API gd_status gd_campbell(const gd_system *sys, const gd_campbell_options *opt,
                             gd_campbell_result **out, gd_error *err);
GD_API void gd_campbell_free(gd_campbell_result *r);

/* The number of modes to track when the user gives none: every elastic mode up to
 * *limit = 1.25 x the highest order of opt (shaft, user and tooth-mesh orders) times the
 * top speed of opt->speeds, plus 2, at least 12 and at most 400 (counted at rest,
 * undamped). Solves an undamped modal problem (dense up to 1500 DOFs, sparse doubling
 * counts above). Thread-safe for distinct results. */
GD_API gd_status gd_campbell_default_modes(const gd_system *sys, const gd_campbell_options *opt,
                                           int *nmodes, double *limit, gd_error *err);

/* Complex MAC |a^H b|^2 / (|a|^2 |b|^2) of two shapes of n entries. */
GD_API double gd_mac(const double *are, const double *aim, const double *bre, const double *bim,
                     int n);

#endif
