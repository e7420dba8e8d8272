/* Private pieces of correlation and updating: the model's undamped elastic modes
 * (mass-normalised) and the pairing on them. */
#ifndef GD_CORRELATE_IMPL_H
#define GD_CORRELATE_IMPL_H
#include "geardyn/correlate.h"

typedef struct gd_corr_modes {
    int n, ndof;
    double *lambda; /* n: omega^2, ascending */
    double *phi;    /* ndof x n, column-major: phi^T M phi = 1 */
} gd_corr_modes;

gd_status gd_corr_model_modes(const gd_system *sys, gd_corr_modes *out, gd_error *err);
void gd_corr_modes_free(gd_corr_modes *m);
double gd_corr_hz(const gd_corr_modes *m, int j);
gd_status gd_corr_pair_modes(const gd_corr_modes *md, const gd_measured_modes *mm,
                             gd_corr_table **out, gd_error *err);

#endif
