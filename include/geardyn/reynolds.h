/* Finite-length fluid film by the Reynolds equation (docs/bearings.md, "Finite-length
 * film"): the force of a plain cylindrical film (a squeeze film damper, or a journal
 * bearing through the turning frame of src/laws/journal_bearing.c) by finite differences
 * on the unwrapped film, instead of the short-bearing (Ocvirk) closed forms.
 *
 * With theta from the point of maximum film (opposite the eccentricity e at angle phi),
 * h = c (1 + eps cos theta) and dh/dt = c (eps' cos theta + eps phi' sin theta), the
 * Reynolds equation
 *   (1 / R^2) d/dtheta (h^3 dp/dtheta) + d/dz (h^3 dp/dz) = 12 mu dh/dt
 * with p = 0 at both ends z = +-L/2 and periodic in theta is discretised by the
 * conservative five-point scheme (h^3 at the cell faces) on ntheta x nz points and
 * solved by successive over-relaxation. Cavitation: GD_FILM_GUMBEL solves the full film
 * and drops the negative pressures from the force (half-Sommerfeld; the short bearing's
 * pi film in the limit L/D -> 0); GD_FILM_REYNOLDS keeps p >= 0 at every sweep
 * (Christopherson's projected SOR: p = dp/dn = 0 at the film's rupture, the Reynolds
 * condition). The force on the journal is -int p n R dtheta dz.
 *
 * Ownership and threads: pure functions; work arrays allocated per call. */
#ifndef GEARDYN_REYNOLDS_H
#define GEARDYN_REYNOLDS_H
#include "geardyn/error.h"
#include "geardyn/export.h"
#include "geardyn/laws.h"

typedef enum gd_film_cavitation { GD_FILM_GUMBEL = 0, GD_FILM_REYNOLDS = 1 } gd_film_cavitation;

typedef struct gd_reynolds_grid {
    int ntheta; /* points around, >= 16 (default 96) */
    int nz;     /* interior points along the length, >= 3 (default 21) */
    gd_film_cavitation cavitation;
    double tol; /* SOR stop: largest update below tol x largest pressure
                   (default 1e-10) */
} gd_reynolds_grid;

GD_API void gd_reynolds_grid_init(gd_reynolds_grid *g);
/* The film's force (fx, fy) on the journal at relative position (x, y) and velocity
 * (vx, vy) (p's viscosity, radius, length, clearance and max_eccentricity are used; its
 * film and correction are not). GD_EINPUT for a bad grid or parameters, GD_ENUMERIC
 * when SOR does not converge in 20000 sweeps, GD_ENOMEM. */
GD_API gd_status gd_reynolds_force(const gd_sfd_params *p, const gd_reynolds_grid *grid, double x,
                                   double y, double vx, double vy, double *fx, double *fy,
                                   gd_error *err);

/* A plain journal bearing of the finite-length film under the static load W (N, along
 * -y: the journal is pushed down) at spin w (rad/s > 0, about +z): the film force is the
 * squeeze film's in the frame turning at w / 2 (src/laws/journal_bearing.c). Solves the
 * journal's equilibrium (Newton on the film force, its Jacobian by central differences)
 * and gives the eccentricity ratio eps, the attitude angle (rad, between the load line
 * and the line of centres) and the eight coefficients K = -dF/dq, C = -dF/dq' (row-major
 * [xx xy yx yy], N/m and N s/m) by central differences (steps 1e-5 of the clearance and
 * of c w). GD_EINPUT when the film cannot carry W below the eccentricity cap or for bad
 * parameters; the errors of gd_reynolds_force. */
GD_API gd_status gd_reynolds_journal(const gd_sfd_params *p, const gd_reynolds_grid *grid,
                                     double load, double speed, double *eps, double *attitude,
                                     double K[4], double C[4], gd_error *err);

#endif
