/* Frequency response: receptance, mobility or accelerance from a unit harmonic force
 * or moment at a DOF to DOF displacements and to derived forces (dynamic mesh force,
 * bearing force), solved directly (one sparse complex factorisation per frequency) or
 * by modal summation over left and right eigenvectors ([MMT2018] Eqs. 14-15); directional
 * (forward/backward) FRFs of lateral node pairs ([Kumar2011] Eqs. 2.5-2.8).
 *
 * Ownership and threads: gd_frf returns a result the caller frees with gd_frf_free;
 * the options' arrays are borrowed for the call only. Frequencies are solved in
 * parallel (OpenMP, opt.nthreads), bitwise the same on any number of threads; separate
 * calls may run concurrently on one system.
 */
#ifndef GEARDYN_FRF_H
#define GEARDYN_FRF_H
#include "geardyn/export.h"
#include "geardyn/modal.h"
#include "geardyn/probe.h"

typedef enum gd_frf_quantity {
    GD_FRF_RECEPTANCE, /* displacement / force */
    GD_FRF_MOBILITY,   /* velocity / force */
    GD_FRF_ACCELERANCE /* acceleration / force */
} gd_frf_quantity;
GD_API extern const char *const gd_frf_quantity_names[3];

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

GD_API void gd_frf_options_init(gd_frf_options *opt);
GD_API gd_status gd_frf(const gd_system *sys, const gd_frf_options *opt, gd_frf_result **out,
                        gd_error *err);
GD_API void gd_frf_free(gd_frf_result *r);
/* The response to one complex load vector F (load_re, load_im: ndof, the caller's; load_im
 * may be NULL): H(o) = sum_j F_j H(o, j), e.g. a planetary set's phased mesh excitation
 * (gd_planetary_mesh_excitation). opt's inputs are ignored; the result has ninputs 1.
 * GD_EINPUT when F is zero on every DOF. */
GD_API gd_status gd_frf_load(const gd_system *sys, const gd_frf_options *opt, const double *load_re,
                             const double *load_im, gd_frf_result **out, gd_error *err);

/* Directional FRFs from the complex coordinates p = x + i y of the output node and
 * g = f_x + i f_y of the input node: forward H_f = (H_xx + H_yy + i (H_yx - H_xy)) / 2
 * is the response of p to a forward-rotating force g e^{iwt}; backward
 * H_b = (H_xx + H_yy - i (H_yx - H_xy)) / 2 to a backward-rotating one ([Kumar2011] Eqs.
 * 2.5-2.8; Lee's dFRFs). Directions are about +z. r holds the four H of inputs
 * (x, y) and outputs (x, y) of a gd_frf run with inputs {x_in, y_in} and outputs
 * {x_out, y_out}; fwd/bwd get nfreq complex values each (re, im). */
GD_API void gd_frf_directional(const gd_frf_result *r, int out_x, int out_y, double *fwd_re,
                               double *fwd_im, double *bwd_re, double *bwd_im);

#endif
