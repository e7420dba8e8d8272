/* Experimental modal analysis: modal parameters from measured FRFs.
 * - Peak picking with half-power damping, for a first look: zeta = (f2 - f1) / (2 f_r)
 *   at the -3 dB points of the summed magnitude ([Ewins2000] Sec. 4.3).
 * - LSCF, the least-squares complex-frequency method ([Guillaume2003], [Peeters2004]):
 *   a common-denominator rational model of every FRF in the z-domain, z = e^{i w dt},
 *   dt = 1 / (2 f_max), its denominator from the reduced normal equations
 *   M = sum_o (T_o - S_o^T R^-1 S_o) with the highest coefficient fixed to 1, at every
 *   model order up to max_order: the stabilisation diagram (frequency, damping, and
 *   whether each pole is stable against the order below). Poles stable over most of
 *   the upper orders are the modes; their residues (mode shapes) come from a least-
 *   squares fit in the frequency domain (LSFD) of every FRF to
 *   sum_r A_r/(iw - l_r) + conj(A_r)/(iw - conj(l_r)) + U + L/w^2.
 *   With several references (every response measured for each) the denominator is a
 *   matrix polynomial over them (poly-reference), which separates close modes one
 *   reference sees as one; otherwise one scalar polynomial common to every FRF.
 *
 * Ownership and threads: the FRFs are borrowed for the call; the result is owned by the
 * caller (gd_ema_free). Reentrant: no global state.
 */
#ifndef GEARDYN_EMA_H
#define GEARDYN_EMA_H
#include "geardyn/error.h"
#include "geardyn/export.h"
#include "geardyn/testdata.h"

typedef struct gd_ema_options {
    double band_lo_hz, band_hi_hz; /* lines used; 0, 0: every line above 0 Hz */
    int max_order;                 /* LSCF's highest denominator order (default 40) */
    double stab_freq;              /* stable: frequency within this fraction (0.01) */
    double stab_damp;              /* and damping within this fraction (0.05) */
    double max_damping;            /* poles more damped are not modes (0.2) */
    double stable_share;           /* a mode is stable at this share of the upper
                                      half of the orders (0.6) */
    double peak_threshold;         /* peak picking: peaks above this share of the
                                      largest (0.02) */
    int poly_reference;            /* 1 (default): a matrix denominator over the
                                      references when every response was measured once
                                      for each of two or more; 0: one scalar denominator */
} gd_ema_options;

/* One pole of the stabilisation diagram, compared with the nearest pole of the order
 * below: 'o' new, 'f' its frequency within stab_freq, 's' and its damping within
 * stab_damp. */
typedef struct gd_ema_pole {
    int order;
    double frequency_hz, damping_ratio;
    char status; /* 'o' new, 'f' frequency stable, 's' frequency and damping stable */
} gd_ema_pole;

typedef struct gd_ema_mode {
    double frequency_hz, damping_ratio;
    double lambda_re, lambda_im; /* pole, rad/s */
    int stable_count;            /* orders of the cluster (LSCF); 0 for peak picking */
} gd_ema_mode;

typedef struct gd_ema_result {
    int nfrf, nmodes;
    gd_ema_mode *modes; /* ascending frequency */
    /* residues A_r of every FRF, nfrf x nmodes column-major (LSCF); NULL for peaks.
     * The shape of mode r over the FRFs of one reference is its column. */
    double *residue_re, *residue_im;
    int npoles; /* the stabilisation diagram, LSCF only */
    gd_ema_pole *poles;
    int max_order;
    int nreferences;               /* inputs of LSCF's denominator (1: scalar) */
    double band_lo_hz, band_hi_hz; /* the band used */
    int nlines;
} gd_ema_result;

GD_API void gd_ema_options_init(gd_ema_options *opt);
/* The FRFs must share one frequency axis (GD_EINPUT otherwise, naming the first that
 * does not); at least 2 * max_order lines lie in the band. */
GD_API gd_status gd_ema_lscf(int nfrf, const gd_td_function *const *frfs, const gd_ema_options *opt,
                             gd_ema_result **out, gd_error *err);
GD_API gd_status gd_ema_peaks(int nfrf, const gd_td_function *const *frfs,
                              const gd_ema_options *opt, gd_ema_result **out, gd_error *err);
/* Modal assurance criterion of complex vectors a, b of length n:
 * |a^H b|^2 / ((a^H a)(b^H b)); 0 when either is zero. */
GD_API double gd_ema_mac(int n, const double *a_re, const double *a_im, const double *b_re,
                         const double *b_im);
GD_API void gd_ema_free(gd_ema_result *r);

#endif
