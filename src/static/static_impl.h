/* Private parts of the static analysis (geardyn/static.h): the mean loads, the held
 * DOFs (prescribed and torque-balance holds) and the outputs made from a solution. */
#ifndef GEARDYN_STATIC_IMPL_H
#define GEARDYN_STATIC_IMPL_H
#include "geardyn/static.h"

/* Hold kinds in the held[] flags over the active DOFs. */
enum { GD_ST_FREE = 0, GD_ST_PRESCRIBED = 1, GD_ST_TORQUE_HOLD = 2 };

/* The input node of opt (its own, or the reference shaft's first node). */
int gd_st_input_node(const gd_model *m, const gd_static_options *opt);
/* f (ndof, zeroed here): the mean excitation loads, the input torque and gravity. */
/* The planets' pin-error loads (planetary_sharing.c), added into f. */
void gd_st_planetary_loads(const gd_system *sys, double *f);
gd_status gd_st_loads(const gd_system *sys, const gd_static_options *opt, double *f, gd_error *err);
/* held (ndof, zeroed here): the prescribed DOFs, then one torsion DOF per free gear train
 * of the stiffness K (dense, column-major, ndof^2). GD_EINPUT naming any other free
 * rigid-body motion. */
gd_status gd_st_holds(const gd_system *sys, const double *K, const gd_static_options *opt,
                      int *held, gd_error *err);
/* The reactions, mesh forces and misalignments of res from res->q (speed res->speed). */
void gd_st_outputs(const gd_system *sys, gd_static_result *res);

#endif
