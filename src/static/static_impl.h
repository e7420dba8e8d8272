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

/* Bad options (node out of range, non-finite torque or speed): GD_EINPUT. */
gd_status gd_st_check_options(const gd_model *m, const gd_static_options *opt, gd_error *err);
/* q (zeroed) on the free DOFs from K_FF q_F = f_F (Jacobi-scaled LU). */
gd_status gd_st_solve_linear(const gd_system *sys, const double *K, const double *f,
                             const int *held, double *q, gd_error *err);
/* Kd = K plus a small grounded stiffness on every direction a supporting law acts on
 * (the hold search then counts those directions as held). */
void gd_st_supported_stiffness(const gd_system *sys, const double *K, double *Kd);
/* q from K q = f + f_law(q) with the held DOFs at 0 (law_equilibrium.c), from the linear
 * solution where the linear stiffness alone holds the model, else from rest; the located
 * error of gd_st_no_equilibrium when there is none. */
gd_status gd_st_solve_with_laws(const gd_system *sys, const double *K, const double *f,
                                const int *held, double speed, double *q, gd_error *err);
/* The static analysis's holds (held, ndof) for the model's stiffness at speed, and, when
 * solve is set, its equilibrium q (ndof) under the loads f by gd_st_solve_with_laws: the one
 * sequence `geardyn static`'s linearisation (gd_static_operating_point) and the transient's
 * static start share. */
gd_status gd_st_equilibrium(const gd_system *sys, const gd_static_options *opt, double speed,
                            const double *f, int solve, int *held, double *q, gd_error *err);
/* GD_EINPUT located at the law that cannot hold the load at the best state q (relative
 * residual res), with the fix for its kind. */
gd_status gd_st_no_equilibrium(const gd_system *sys, double speed, const double *q, double res,
                               gd_error *err);

#endif
