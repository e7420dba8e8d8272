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

/* An axial groove and the land it bounds (ROSS's FixedGeometryBearing with one pad: a
 * land of angular extent `arc` from `start`, the groove filling the rest of the bore).
 * Angles from the bush's +x axis towards +y (the journal's spin direction, about +z);
 * the film runs from the land's leading edge `start` to its trailing edge start + arc,
 * where it meets the groove again. The groove holds the oil at `supply_pressure` (Pa,
 * gauge: p at both land edges and over the groove's own arc; the bearing's axial ends
 * are at 0). arc = 0 means no groove: the 360 deg film periodic around the bore. */
typedef struct gd_journal_land {
    double start;           /* rad */
    double arc;             /* rad, 0 (no groove) or in (0, 2 pi) */
    double supply_pressure; /* Pa, >= 0 */
} gd_journal_land;

/* The film's force (fx, fy) on a journal spinning at w (rad/s, about +z, relative to the
 * bush) at relative position (x, y) and velocity (vx, vy) in the bush's frame, on the land
 * of `land` (NULL or arc 0: the groove-less film, = gd_reynolds_force in the frame turning
 * at w / 2). With a groove the Reynolds equation is solved in the bush's frame,
 *   (1 / R^2) d/dtheta (h^3 dp/dtheta) + d/dz (h^3 dp/dz) = 6 mu w dh/dtheta + 12 mu dh/dt,
 * h = c - x cos theta - y sin theta, on grid->ntheta intervals along the land (its two
 * edges at the supply pressure) x grid->nz interior points along the length. With
 * GD_FILM_REYNOLDS the film, once ruptured, stays ruptured to the trailing edge: p = 0
 * where the film converges again downstream of its thinnest point (the oil that the
 * cavitated zone carries cannot refill a gap thicker than the rupture's before the
 * groove supplies it: Jakobsson-Floberg-Olsson mass conservation; ROSS's rule too).
 * Errors as gd_reynolds_force, and GD_EINPUT for a bad land. */
GD_API gd_status gd_reynolds_land_force(const gd_sfd_params *p, const gd_reynolds_grid *grid,
                                        const gd_journal_land *land, double w, double x, double y,
                                        double vx, double vy, double *fx, double *fy,
                                        gd_error *err);

/* gd_reynolds_journal on the land of `land` (NULL: groove-less, = gd_reynolds_journal). */
GD_API gd_status gd_reynolds_journal_land(const gd_sfd_params *p, const gd_reynolds_grid *grid,
                                          const gd_journal_land *land, double load, double speed,
                                          double *eps, double *attitude, double K[4], double C[4],
                                          gd_error *err);

#endif
