/* Rolling bearings from their geometry (docs/bearings.md): the stiffness matrix of a ball
 * or roller bearing at its load, from the Hertz contact of every element ([LimSingh1990];
 * [HarrisKotzalas2006] ch. 6-7).
 *
 * The inner ring moves by d = (dx, dy, dz, bx, by) relative to the outer ring (m, rad;
 * z along the shaft axis, bx, by tilts about x and y). Element j at psi_j = 2 pi j / Z
 * (+ phase) sees the radial and axial approach of the raceways at its place,
 *   dr_j = dx cos psi_j + dy sin psi_j - c_r,   dz_j = dz + R (bx sin psi_j - by cos psi_j),
 * c_r the radial clearance (negative: an interference preload), R the radius of the inner
 * raceway's groove-curvature centre (pitch radius + (f_i - 1/2) d cos alpha0 for balls).
 *   - Ball: the groove-curvature centres are A0 = (f_i + f_o - 1) d apart at the unloaded
 *     contact angle alpha0; loaded, A_j = |(A0 sin alpha0 + dz_j, A0 cos alpha0 + dr_j)|,
 *     the contact angle turns to tan alpha_j = (A0 sin alpha0 + dz_j) / (A0 cos alpha0 +
 *     dr_j), and the element carries Q_j = K_n (A_j - A0)^(3/2) ([LimSingh1990] Eqs. 9-13).
 *   - Roller: the contact angle stays alpha0 and Q_j = K_n (dr_j cos alpha0 + dz_j sin
 *     alpha0)^(10/9) ([LimSingh1990] Eq. 14).
 * The bearing's load on the inner ring's mean position, F(d) = sum_j Q_j (cos alpha_j cos
 * psi_j, cos alpha_j sin psi_j, sin alpha_j, R sin alpha_j sin psi_j, -R sin alpha_j cos
 * psi_j), balances the applied load; its stiffness is the 5 x 5 K = dF/dd, symmetric,
 * coupling radial, axial and tilt motion.
 *
 * The contact constant K_n (N/m^n) is given, or made from the geometry: balls by Hertz's
 * point contact on each raceway with the Hamrock-Brewe approximations of the ellipticity
 * and the elliptic integrals (Hamrock & Brewe, J. Lubr. Technol. 105 (1983) 171), the two
 * contacts in series; rollers by Palmgren's line contact of steel, delta = 3.84e-5 Q^0.9 /
 * l^0.8 (mm, N) per contact ([HarrisKotzalas2006] ch. 6).
 *
 * Ownership and threads: plain values; every function is pure (no state, no allocation
 * but its own scratch), safe from any number of threads. */
#ifndef GEARDYN_BEARING_GEOMETRY_H
#define GEARDYN_BEARING_GEOMETRY_H
#include "geardyn/error.h"
#include "geardyn/export.h"

typedef enum gd_bearing_kind { GD_BEARING_BALL = 0, GD_BEARING_ROLLER = 1 } gd_bearing_kind;

typedef struct gd_bearing_geometry {
    gd_bearing_kind kind;
    int elements;             /* Z, 3 .. 1000 */
    double element_diameter;  /* d, m */
    double pitch_diameter;    /* d_m, m (> d) */
    double contact_angle;     /* unloaded alpha0, rad, 0 .. < 90 deg */
    double clearance;         /* radial clearance c_r, m; negative: interference preload */
    double roller_length;     /* effective length l of a roller, m (rollers) */
    double inner_curvature;   /* f_i = groove radius / d (balls, > 0.5; default 0.52) */
    double outer_curvature;   /* f_o (balls, > 0.5; default 0.52) */
    double modulus, poisson;  /* of both bodies (default steel: 206 GPa, 0.3) */
    double contact_stiffness; /* K_n, N/m^n; 0 (default): from the geometry */
    double phase;             /* angle of element 0 from +x, rad */
} gd_bearing_geometry;

/* Defaults: a ball bearing, f_i = f_o = 0.52, steel, the rest 0. */
GD_API void gd_bearing_geometry_init(gd_bearing_geometry *g);
/* GD_EINPUT naming the field (e.g. "element_diameter") and the fix. */
GD_API gd_status gd_bearing_geometry_check(const gd_bearing_geometry *g, gd_error *err);
/* The contact constant K_n (N/m^n, the inner and outer contacts in series) and the
 * exponent n (3/2 balls, 10/9 rollers). */
GD_API gd_status gd_bearing_contact_constant(const gd_bearing_geometry *g, double *kn, double *n,
                                             gd_error *err);
/* F(d) (5, N and N m) and K = dF/dd (25, column-major, may be NULL) at the displacement
 * d; loaded (may be NULL): the elements in contact. */
GD_API gd_status gd_bearing_forces(const gd_bearing_geometry *g, const double d[5], double F[5],
                                   double K[25], int *loaded, gd_error *err);
/* The displacement d (5) at which the bearing carries the load L (5: Fx, Fy, Fz in N, Mx,
 * My in N m) and the stiffness K (25, column-major) there: Newton's method with a line
 * search on the potential from d = 0 (across the clearance). A roller bearing's tilt is
 * held at 0 (its point contacts at the pitch radius tie its moment to its forces, Mx = R
 * tan(alpha) Fy, My = -R tan(alpha) Fx: L's moments must be 0), and at contact angle 0
 * its axial motion too (Fz must be 0). GD_EINPUT when the bearing cannot carry L
 * (named). */
GD_API gd_status gd_bearing_at_load(const gd_bearing_geometry *g, const double L[5], double d[5],
                                    double K[25], gd_error *err);

#endif
