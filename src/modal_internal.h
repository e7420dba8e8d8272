/* Internals shared by the undamped and state-space modal solvers. */
#ifndef GD_MODAL_INTERNAL_H
#define GD_MODAL_INTERNAL_H
#include <complex.h>

#include "geardyn/modal.h"

/* Static condensation of massless DOFs: master = DOFs with mass, slave = without. */
typedef struct gd_condense {
    int N, nm, ns;
    int *master, *slave;
    double *kss_lu; /* LU of K_ss */
    int *ipiv;
    double *ksm;   /* ns x nm */
    double *kms_t; /* ns x nm: K_ms^T */
} gd_condense;

gd_status gd_condense_setup(const gd_system *sys, const double *K, const double *D, gd_condense *c,
                            gd_error *err);
double *gd_condense_matrix(const gd_condense *c, const double *A, int is_stiffness);
void gd_condense_expand(const gd_condense *c, const double *um, double *u, int left, double *work);
void gd_condense_free(gd_condense *c);

/* Energy shares, dominant motion/component and whirl of a mode with full shape u. */
void gd_mode_finish(const gd_system *sys, double speed, gd_mode *md, const double *re,
                    const double *im, double *comp_share);
double complex gd_normalise_max(double *re, double *im, int n);

gd_status gd_modal_undamped(const gd_system *sys, const gd_modal_options *opt, const gd_condense *c,
                            const double *M, const double *K, gd_modal_result **out, gd_error *err);
gd_status gd_modal_state_space(const gd_system *sys, const gd_modal_options *opt,
                               const gd_condense *c, const double *M, const double *D,
                               const double *K, gd_modal_result **out, gd_error *err);

/* Allocates a result for nmodes modes (shapes zeroed). */
gd_modal_result *gd_modal_result_new(const gd_system *sys, int nmodes, int with_left);

#endif
