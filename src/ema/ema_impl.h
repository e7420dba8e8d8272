/* Shared pieces of the modal-parameter estimators: the band of a common frequency
 * axis, and the result's allocation. */
#ifndef GD_EMA_IMPL_H
#define GD_EMA_IMPL_H
#include "geardyn/ema.h"

/* The lines [*k0, *k1) of the FRFs' common axis inside opt's band (above 0 Hz);
 * GD_EINPUT when the FRFs' axes differ, a function is not an FRF, or fewer than
 * min_lines lines remain. */
gd_status gd_ema_band(int nfrf, const gd_td_function *const *frfs, const gd_ema_options *opt,
                      int min_lines, int *k0, int *k1, gd_error *err);

/* LSFD: the residues of every FRF for the modes' poles (plus a constant and a 1/w^2
 * residual per FRF) over lines [k0, k1); fills r->residue_re/_im. */
gd_status gd_ema_lsfd(int nfrf, const gd_td_function *const *frfs, int k0, int k1, gd_ema_result *r,
                      gd_error *err);

#endif
