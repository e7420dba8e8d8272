/* Frequency response: receptance, mobility or accelerance from a unit harmonic force
 * or moment at a DOF to DOF displacements and to derived forces (dynamic mesh force,
 * bearing force), solved directly (one sparse complex factorisation per frequency) or
 * by modal summation over left and right eigenvectors (004 Eqs. 14-15); directional
 * (forward/backward) FRFs of lateral node pairs (000 Eqs. 2.5-2.8); and the steady
 * response to the model's unbalances over a speed range. */
#ifndef GEARDYN_FRF_H
#define GEARDYN_FRF_H
#include "geardyn/modal.h"

/* What a response is measured on. */
typedef enum gd_probe_kind {
    GD_PROBE_DOF,    /* displacement of an active DOF (m or rad) */
    GD_PROBE_MESH,   /* dynamic mesh force k d + c d' along the contact normal (N) */
    GD_PROBE_BEARING /* force the bearing transmits, K dq + C dq' in one direction (N or N m) */
} gd_probe_kind;

typedef struct gd_probe {
    gd_probe_kind kind;
    int index;  /* DOF index, mesh index or bearing index */
    gd_dof dir; /* bearing direction */
    char name[160];
} gd_probe;

/* A probe as a linear functional of the complex amplitudes q at frequency w:
 * value = sum_j (k[j] + i w c[j]) q[dof[j]]. */
typedef struct gd_functional {
    int n;
    int dof[24];
    double k[24], c[24];
    int is_force; /* a force, not a displacement */
} gd_functional;
/* The functional of a probe at reference speed W (bearing tables are evaluated there). */
void gd_probe_functional(const gd_system *sys, const gd_probe *p, double speed, gd_functional *out);

typedef enum gd_frf_quantity {
    GD_FRF_RECEPTANCE, /* displacement / force */
    GD_FRF_MOBILITY,   /* velocity / force */
    GD_FRF_ACCELERANCE /* acceleration / force */
} gd_frf_quantity;
extern const char *const gd_frf_quantity_names[3];

typedef enum gd_frf_method { GD_FRF_DIRECT, GD_FRF_MODAL } gd_frf_method;

typedef struct gd_frf_options {
    int nfreq;
    const double *freqs; /* rad/s, >= 0 */
    double speed;        /* reference speed, rad/s */
    int ninputs;
    const int *inputs; /* active DOF indices of unit forces/moments */
    int noutputs;
    const gd_probe *outputs;
    gd_frf_quantity quantity; /* applies to DOF outputs; force outputs stay force/force */
    gd_frf_method method;
    int nmodes;   /* modal: lowest modes summed; 0: all */
    int nthreads; /* 0: OpenMP default */
} gd_frf_options;

typedef struct gd_frf_result {
    int nfreq, ninputs, noutputs;
    double *freqs;
    /* H[(o * ninputs + i) * nfreq + f]: output o per unit input i at freqs[f] */
    double *re, *im;
    int *singular; /* nfreq: 1 where the dynamic stiffness is singular (values NaN) */
    int nsingular;
    int nmodes_used; /* modal: elastic modes summed (+ rigid-body modes, analytically) */
    int nrigid;
} gd_frf_result;

void gd_frf_options_default(gd_frf_options *opt);
gd_status gd_frf(const gd_system *sys, const gd_frf_options *opt, gd_frf_result **out,
                 gd_error *err);
void gd_frf_free(gd_frf_result *r);

/* Directional FRFs from the complex coordinates p = x + i y of the output node and
 * g = f_x + i f_y of the input node: forward H_f = (H_xx + H_yy + i (H_yx - H_xy)) / 2
 * is the response of p to a forward-rotating force g e^{iwt}; backward
 * H_b = (H_xx + H_yy - i (H_yx - H_xy)) / 2 to a backward-rotating one (000 Eqs.
 * 2.5-2.8; Lee's dFRFs). Directions are about +z. r holds the four H of inputs
 * (x, y) and outputs (x, y) of a gd_frf run with inputs {x_in, y_in} and outputs
 * {x_out, y_out}; fwd/bwd get nfreq complex values each (re, im). */
void gd_frf_directional(const gd_frf_result *r, int out_x, int out_y, double *fwd_re,
                        double *fwd_im, double *bwd_re, double *bwd_im);

/* ---- unbalance response ---- */

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

void gd_unbalance_options_default(gd_unbalance_options *opt);
gd_status gd_unbalance_response(const gd_system *sys, const gd_unbalance_options *opt,
                                gd_unbalance_result **out, gd_error *err);
void gd_unbalance_free(gd_unbalance_result *r);

/* Orbit of a node from the complex amplitudes X, Y of its x and y motion; sense is the
 * sign of its shaft's speed ratio (+1 turns about +z). */
void gd_orbit_from(double xr, double xi, double yr, double yi, double sense, gd_orbit *o);

#endif
