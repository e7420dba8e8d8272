/* Test-analysis correlation and model updating (docs/testing.md).
 * - A test setup maps the test's point labels to model nodes (a small YAML file:
 *   `points: {2: gear32, 3: brg_n1}`); without one, label N is the model's node N
 *   (1-based). A UFF direction (+-1..6) picks the node's x..rz DOF, its sign the sense.
 * - Correlation pairs measured modes (frequencies, and shapes where several points were
 *   measured) with the model's undamped modes: an order-keeping assignment minimising
 *   |ln(f_test / f_model)| + (1 - MAC), so two measured modes never share one model
 *   mode. % difference is (f_model - f_test) / f_model x 100, as [MMT2018] Tables 4-5
 *   give it.
 * - Updating fits parameters of the model file, named by --set paths, within bounds,
 *   to the measured frequencies: bounded Levenberg-Marquardt on the relative frequency
 *   residuals, the Jacobian from the eigenvalue derivatives
 *   d lambda / dp = phi^T (dK/dp - lambda dM/dp) phi ([FoxKapoor1968], undamped,
 *   mass-normalised phi) with dK/dp and dM/dp by a difference of the assembled
 *   matrices; the confidence of each value from the Jacobian at the solution
 *   ([Friswell1995]): sigma^2 = s^2 diag((J^T J)^-1), s^2 the residual variance.
 *
 * Ownership and threads: results are owned by the caller (the matching _free); inputs
 * are borrowed for the call. Reentrant: no global state.
 */
#ifndef GEARDYN_CORRELATE_H
#define GEARDYN_CORRELATE_H
#include "geardyn/ema.h"
#include "geardyn/error.h"
#include "geardyn/export.h"
#include "geardyn/frf.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "geardyn/testdata.h"

typedef struct gd_test_setup {
    int npoints;
    int *label;       /* the test's point labels */
    char (*node)[64]; /* the model node of each */
    int *line;        /* where each is in the file */
    char file[256];
} gd_test_setup;

GD_API gd_status gd_test_setup_load(const char *path, gd_test_setup **out, gd_error *err);
GD_API void gd_test_setup_free(gd_test_setup *s);

/* The active DOF of point `label`, direction `dir` (UFF code) on sys (setup may be
 * NULL), and its sign (+1 or -1). GD_EINPUT naming the point when the node is not in
 * the model or the DOF is not active; where = the file and line of the measurement. */
GD_API gd_status gd_test_point_dof(const gd_system *sys, const gd_test_setup *setup, int label,
                                   int dir, const char *where_file, int where_line, int *dof,
                                   double *sign, gd_error *err);

/* Measured modes: frequencies, optionally damping ratios and shapes at ndofs points. */
typedef struct gd_measured_modes {
    int nmodes;
    double *hz;                  /* nmodes */
    double *zeta;                /* nmodes or NULL */
    int ndofs;                   /* 0: frequencies only */
    int *dof;                    /* ndofs model DOFs */
    double *sign;                /* ndofs */
    double *shape_re, *shape_im; /* ndofs x nmodes, column-major */
} gd_measured_modes;

/* Measured modes from an EMA of FRFs (geardyn/ema.h; r made from frfs): frequencies,
 * damping ratios, and shapes from the residues of the FRFs of the most common
 * reference, at their response DOFs on sys. The arrays are allocated: free them with
 * gd_measured_modes_free (not for a struct of the caller's own arrays). */
GD_API gd_status gd_measured_from_ema(const gd_system *sys, const gd_test_setup *setup, int nfrf,
                                      const gd_td_function *const *frfs, const gd_ema_result *r,
                                      gd_measured_modes *out, gd_error *err);
/* Measured frequencies (and damping ratios) of a modes CSV, no shapes; arrays allocated
 * as above. */
GD_API gd_status gd_measured_from_testdata(const gd_testdata *td, gd_measured_modes *out,
                                           gd_error *err);
GD_API void gd_measured_modes_free(gd_measured_modes *m);

typedef struct gd_corr_pair {
    int measured, model; /* indices: measured mode, model mode (of the elastic modes) */
    double f_test, f_model, diff_pct;
    double mac;       /* NAN without measured shapes */
    double zeta_test; /* NAN when not measured */
} gd_corr_pair;

typedef struct gd_corr_table {
    int npairs;
    gd_corr_pair *pairs; /* in the order of the measured modes */
    double rms_pct;      /* root mean square of the % differences */
} gd_corr_table;

/* Pairs the measured modes with the undamped modes of sys at rest. */
GD_API gd_status gd_correlate_modes(const gd_system *sys, const gd_measured_modes *mm,
                                    gd_corr_table **out, gd_error *err);
GD_API void gd_corr_table_free(gd_corr_table *t);

/* The model's FRF (quantity q) at the measured points of f (response and reference),
 * at f's frequencies: re, im (f->n each, caller's arrays). */
GD_API gd_status gd_correlate_frf(const gd_system *sys, const gd_test_setup *setup,
                                  const gd_td_function *f, gd_frf_quantity q, double *re,
                                  double *im, gd_error *err);

typedef struct gd_update_param {
    const char *key; /* --set path; several joined by ',' move together */
    double lo, hi;   /* bounds, SI */
} gd_update_param;

typedef struct gd_update_options {
    int nparams;
    const gd_update_param *params;
    gd_load_options load; /* fixed overrides applied before the parameters */
    int max_iter;         /* 40 */
    double tol;           /* stop when the step changes the parameters by less (1e-8) */
    double step;          /* relative step of the matrices' difference (1e-6) */
    int fd_check;         /* also differentiate the frequencies by finite differences */
} gd_update_options;

typedef struct gd_update_result {
    int nparams, ntargets, iterations;
    double *initial, *value, *sigma; /* nparams, SI; sigma NAN without redundancy */
    /* d f_model / d p of the paired modes at the start (Hz per SI unit), ntargets x
     * nparams row-major: from the eigenvalue derivatives, and by central differences
     * of the frequencies when fd_check was set (else NULL) */
    double *sens, *sens_fd;
    gd_corr_table *before, *after;
    int at_bound; /* some parameter ends on a bound */
} gd_update_result;

GD_API void gd_update_options_init(gd_update_options *opt);
/* GD_EINPUT for a key that reaches no number, bounds that are not lo < hi with both
 * above zero, or a parameter that changes no target frequency (named). */
GD_API gd_status gd_model_update(const gd_model_source *src, const gd_measured_modes *mm,
                                 const gd_update_options *opt, gd_update_result **out,
                                 gd_error *err);
GD_API void gd_update_free(gd_update_result *r);

#endif
