/* Pieces shared by the law files of src/laws (law_type.h): the x-y pair layout of the
 * film and rolling-element bearings, and a linearisation read off any law's terms. */
#ifndef GD_LAWS_IMPL_H
#define GD_LAWS_IMPL_H
#include <stddef.h>

#include "geardyn/law_type.h"

/* Directions x, y at each node: local DOFs [x, y] of node, then of node2. */
extern const int gd_law_xy_dirs[2];
/* Term 2 r + c of such a law: u = e_r(node) - e_r(node2), w = e_c(node) - e_c(node2). */
void gd_law_xy_term(const gd_law *law, int k, double *u, double *w);
/* K = -df/dq, C = -df/dq' from the law's force and its rank-one terms (ndofs x ndofs,
 * column-major, added into). */
void gd_law_linearize_terms(const gd_law *law, const gd_law_point *x, double *K, double *C);
/* The film laws' checks: film 0 or 1, eccentricity cap below 1 (0 ok, else field, msg). */
int gd_law_check_film(double film, double max_eccentricity, const char **field, char *msg,
                      size_t cap);

/* The drag laws' odd extension of a drag magnitude g(|w|) >= 0 to a torque that opposes
 * the relative speed w and is smooth through w = 0 (drag_speed.c): T = g(s) w / s with
 * s = sqrt(w^2 + w_r^2), which is g(|w|) sign(w) for |w| >> w_r and linear below w_r.
 * g and dg = g'(s) are evaluated by the caller at s = gd_law_drag_s(w, w_r); *dT receives
 * dT/dw. */
double gd_law_drag_s(double w, double w_r);
double gd_law_drag_odd(double g, double dg, double w, double s, double *dT);
/* The oil's dynamic viscosity of a drag law (Pa s): mu when > 0, else from the kinematic
 * viscosities nu40, nu100 (mm^2/s at 40 and 100 C) at temperature temp_c (C) by Walther's
 * equation (ASTM D341), times rho. */
double gd_law_drag_mu(double mu, double rho, double nu40, double nu100, double temp_c);
/* The drag laws' check of the oil: mu > 0, or nu40 > nu100 > 0 with a temperature above
 * -273.15 C (0 ok, else field and msg). */
int gd_law_drag_check_oil(double mu, double nu40, double nu100, double temp_c, const char **field,
                          char *msg, size_t cap);
/* The relative speed of a drag law's two sides: (rate + v) at node minus at node2. */
double gd_law_drag_speed(const gd_law *law, const gd_law_point *x);

#endif
