/* Finite-length film by finite differences of the Reynolds equation
 * (geardyn/reynolds.h). Unknowns p[i][k], theta_i = 2 pi i / nt (periodic), z_k = -L/2 +
 * (k + 1) dz, dz = L / (nz + 1) (p = 0 at both ends). Five-point scheme with h^3 at the
 * faces:
 *   [a_e (p_{i+1} - p_i) - a_w (p_i - p_{i-1})] / (R dth)^2
 *     + h_i^3 (p_{k+1} - 2 p_k + p_{k-1}) / dz^2 = 12 mu dh/dt_i,
 * a_e = h^3 at theta_{i+1/2}; solved by SOR (omega 1.8), projected on p >= 0 for the
 * Reynolds condition. The force integrates p over the film by the trapezoidal rule in z
 * (zero ends) and the periodic rectangle rule in theta. */
#include "geardyn/reynolds.h"

#include <math.h>
#include <stdlib.h>

#define TWO_PI 6.283185307179586

void gd_reynolds_grid_init(gd_reynolds_grid *g)
{
    g->ntheta = 96;
    g->nz = 21;
    g->cavitation = GD_FILM_GUMBEL;
    g->tol = 1e-10;
}

/* the grid, the film's parameters and the state, shared by the plain and grooved films */
static gd_status check_inputs(const gd_sfd_params *p, const gd_reynolds_grid *grid, double x,
                              double y, double vx, double vy, gd_error *err)
{
    const int nt = grid->ntheta, nz = grid->nz;
    if (nt < 16 || nt > 100000 || nz < 3 || nz > 100000 || !(grid->tol > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "grid",
                            "at least 16 points around and 3 along, a tolerance > 0",
                            "bad Reynolds grid %d x %d", nt, nz);
    if (!(p->viscosity > 0) || !(p->radius > 0) || !(p->length > 0) || !(p->clearance > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "clearance",
                            "viscosity, radius, length and clearance must be positive",
                            "bad film parameters");
    if (!isfinite(x) || !isfinite(y) || !isfinite(vx) || !isfinite(vy))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "", "give finite values",
                            "position or velocity not finite");
    return GD_OK;
}

/* Successive over-relaxation of the Reynolds equation's five-point scheme: rows i (theta)
 * of nz points along z (pressure zero beyond both ends), rows i0 .. i1 - 1 swept, a row's
 * east and west neighbours (i +- 1) mod nrow (the plain film is periodic; a land's edge
 * rows 0 and nrow - 1 are never swept, so they hold the supply pressure), rows with fix[i]
 * kept (the Reynolds condition's cavitated gap); proj clamps p >= 0. Until the largest
 * change is tol of the largest pressure: 1 converged, 0 not within maxsweeps. */
static int sor(double *P, int nrow, int i0, int i1, int nz, const double *h3, const double *he,
               const double *rhs, double ct, double cz, double om, int proj, const char *fix,
               double tol, int maxsweeps)
{
    for (int sweep = 0; sweep < maxsweeps; sweep++) {
        double du = 0, pm = 0;
        for (int i = i0; i < i1; i++) {
            if (fix && fix[i]) continue;
            const int ie = (i + 1) % nrow, iw = (i + nrow - 1) % nrow;
            double ae = he[i] * ct, aw = he[iw] * ct, az = h3[i] * cz;
            double diag = ae + aw + 2 * az;
            double *Pi = P + (size_t)i * nz;
            const double *Pe = P + (size_t)ie * nz, *Pw = P + (size_t)iw * nz;
            for (int k = 0; k < nz; k++) {
                double pn = k + 1 < nz ? Pi[k + 1] : 0, pz = k > 0 ? Pi[k - 1] : 0;
                double gs = (ae * Pe[k] + aw * Pw[k] + az * (pn + pz) - rhs[i]) / diag;
                double old = Pi[k], v = old + om * (gs - old);
                if (proj && v < 0) v = 0;
                Pi[k] = v;
                du = fmax(du, fabs(v - old));
                pm = fmax(pm, fabs(v));
            }
        }
        if (du <= tol * pm || pm == 0) return 1;
    }
    return 0;
}

gd_status gd_reynolds_force(const gd_sfd_params *p, const gd_reynolds_grid *grid, double x,
                            double y, double vx, double vy, double *fx, double *fy, gd_error *err)
{
    *fx = *fy = 0;
    gd_reynolds_grid def;
    if (!grid) {
        gd_reynolds_grid_init(&def);
        grid = &def;
    }
    gd_status st = check_inputs(p, grid, x, y, vx, vy, err);
    if (st) return st;
    const int nt = grid->ntheta, nz = grid->nz;
    const double c = p->clearance, R = p->radius, L = p->length, mu = p->viscosity;
    const double emax = p->max_eccentricity > 0 ? p->max_eccentricity : 0.995;
    double e = hypot(x, y), cphi = 1, sphi = 0;
    if (e > 1e-12 * c) cphi = x / e, sphi = y / e;
    double eps = fmin(e / c, emax);
    double edot = vx * cphi + vy * sphi, ephid = -vx * sphi + vy * cphi; /* e', e phi' */
    double *P = calloc((size_t)nt * nz, sizeof *P), *h3 = malloc((size_t)nt * 3 * sizeof *h3);
    if (!P || !h3) {
        free(P);
        free(h3);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    double *he = h3 + nt, *rhs = he + nt;
    const double dth = TWO_PI / nt, dz = L / (nz + 1);
    const double ct = 1.0 / (R * dth * R * dth), cz = 1.0 / (dz * dz);
    for (int i = 0; i < nt; i++) {
        double th = i * dth, h = c * (1 + eps * cos(th));
        double hf = c * (1 + eps * cos(th + 0.5 * dth));
        h3[i] = h * h * h;
        he[i] = hf * hf * hf;
        rhs[i] = 12 * mu * (edot * cos(th) + ephid * sin(th)); /* 12 mu dh/dt */
    }
    int proj = grid->cavitation == GD_FILM_REYNOLDS;
    st = GD_OK;
    int done = sor(P, nt, 0, nt, nz, h3, he, rhs, ct, cz, 1.8, proj, NULL, grid->tol, 20000);
    if (!done) {
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "grid", "use a coarser grid",
                          "the Reynolds equation's SOR did not converge");
    } else {
        /* theta from the maximum film, opposite e: the surface point at phi + pi + theta */
        double sx = 0, sy = 0;
        for (int i = 0; i < nt; i++) {
            double b = i * dth, cb = -cos(b), sb = -sin(b); /* rotate by pi */
            double q = 0;
            for (int k = 0; k < nz; k++) {
                double v = P[i * nz + k];
                if (v > 0) q += v; /* Gumbel: the negative pressures carry nothing */
            }
            q *= dz * R * dth;
            double gx = cb * cphi - sb * sphi, gy = cb * sphi + sb * cphi;
            sx -= q * gx;
            sy -= q * gy;
        }
        *fx = sx;
        *fy = sy;
    }
    free(P);
    free(h3);
    return st;
}

/* A land between two edges of an axial groove (geardyn/reynolds.h): the film in the
 * bush's frame, nodes theta_i = start + i dth, i = 0..nt (dth = arc / nt; the edges i = 0
 * and nt held at the supply pressure), z as above. The wedge term 6 mu w dh/dtheta is
 * the Couette flux's difference between the cell faces, 6 mu w (h_{i+1/2} - h_{i-1/2}) /
 * dth, so the scheme stays conservative. SOR's factor is the optimum of the model
 * problem (h constant: Young's omega from the Jacobi spectral radius), since the land's
 * Dirichlet edges make the plain 1.8 slow on fine grids. */
static gd_status land_solve(const gd_sfd_params *p, const gd_reynolds_grid *grid,
                            const gd_journal_land *land, double w, double x, double y, double vx,
                            double vy, double *fx, double *fy, gd_error *err)
{
    const int nt = grid->ntheta, nz = grid->nz;
    const double c = p->clearance, R = p->radius, L = p->length, mu = p->viscosity;
    const double emax = p->max_eccentricity > 0 ? p->max_eccentricity : 0.995;
    const double ps = land->supply_pressure;
    double e = hypot(x, y);
    if (e > emax * c) x *= emax * c / e, y *= emax * c / e; /* the cap, as the plain film */
    const size_t np = (size_t)(nt + 1) * nz;
    double *P = malloc(np * sizeof *P), *h = malloc((size_t)(nt + 1) * 4 * sizeof *h);
    char *fix = calloc((size_t)nt + 1, 1);
    if (!P || !h || !fix) {
        free(P);
        free(h);
        free(fix);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    double *h3 = h + nt + 1, *he = h3 + nt + 1, *rhs = he + nt + 1;
    const double dth = land->arc / nt, dz = L / (nz + 1);
    const double ct = 1.0 / (R * dth * R * dth), cz = 1.0 / (dz * dz);
    int imin = 0;
    for (int i = 0; i <= nt; i++) {
        double th = land->start + i * dth, thf = th + 0.5 * dth;
        h[i] = c - x * cos(th) - y * sin(th);
        double hf = c - x * cos(thf) - y * sin(thf);
        h3[i] = h[i] * h[i] * h[i];
        he[i] = hf * hf * hf;                              /* face i + 1/2 */
        rhs[i] = -12 * mu * (vx * cos(th) + vy * sin(th)); /* 12 mu dh/dt */
        if (i > 0)
            rhs[i] +=
                6 * mu * w * (hf - (c - x * cos(th - 0.5 * dth) - y * sin(th - 0.5 * dth))) / dth;
        if (h[i] < h[imin]) imin = i;
    }
    int proj = grid->cavitation == GD_FILM_REYNOLDS;
    /* Reynolds condition: no reformation downstream of the thinnest film before the
       trailing edge (the converging gap there stays cavitated, p = 0) */
    if (proj)
        for (int i = imin + 1; i < nt; i++)
            fix[i] = h[i] > h[i + 1];
    for (int i = 0; i <= nt; i++)
        for (int k = 0; k < nz; k++)
            P[(size_t)i * nz + k] = (i == 0 || i == nt) ? ps : 0;
    double rho = (ct * cos(M_PI / nt) + cz * cos(M_PI / (nz + 1))) / (ct + cz);
    double om = 2.0 / (1.0 + sqrt(fmax(1 - rho * rho, 0)));
    gd_status st = GD_OK;
    int done = sor(P, nt + 1, 1, nt, nz, h3, he, rhs, ct, cz, om, proj, fix, grid->tol, 100000);
    if (!done) {
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "grid", "use a coarser grid",
                          "the Reynolds equation's SOR did not converge on the land");
    } else {
        /* trapezoidal in theta over the land (edges half weight) and in z (zero ends) */
        double sx = 0, sy = 0;
        for (int i = 0; i <= nt; i++) {
            double q = 0, th = land->start + i * dth;
            for (int k = 0; k < nz; k++) {
                double v = P[(size_t)i * nz + k];
                if (v > 0) q += v; /* Gumbel: the negative pressures carry nothing */
            }
            q *= dz * R * dth * (i == 0 || i == nt ? 0.5 : 1.0);
            sx -= q * cos(th);
            sy -= q * sin(th);
        }
        /* the groove's own arc at the supply pressure over the full length */
        double a = land->start + land->arc, b = land->start + TWO_PI;
        sx -= ps * L * R * (sin(b) - sin(a));
        sy -= ps * L * R * (cos(a) - cos(b));
        *fx = sx;
        *fy = sy;
    }
    free(P);
    free(h);
    free(fix);
    return st;
}

gd_status gd_reynolds_land_force(const gd_sfd_params *p, const gd_reynolds_grid *grid,
                                 const gd_journal_land *land, double w, double x, double y,
                                 double vx, double vy, double *fx, double *fy, gd_error *err)
{
    *fx = *fy = 0;
    if (land && (!isfinite(land->start) || !(land->arc >= 0) || !(land->arc < TWO_PI) ||
                 !(land->supply_pressure >= 0) || !isfinite(land->supply_pressure)))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "land_arc",
                            "a land arc in [0, 360) deg (0: no groove) and a supply pressure >= 0",
                            "bad groove: land arc %g rad, supply pressure %g Pa", land->arc,
                            land->supply_pressure);
    if (!isfinite(w))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "", "give a finite speed",
                            "journal speed not finite");
    /* groove-less: the squeeze film in the frame turning at w / 2 */
    if (!land || land->arc == 0)
        return gd_reynolds_force(p, grid, x, y, vx + 0.5 * w * y, vy - 0.5 * w * x, fx, fy, err);
    gd_reynolds_grid def;
    if (!grid) {
        gd_reynolds_grid_init(&def);
        grid = &def;
    }
    gd_status st = check_inputs(p, grid, x, y, vx, vy, err);
    if (st) return st;
    return land_solve(p, grid, land, w, x, y, vx, vy, fx, fy, err);
}

/* the journal's film force at (x, y, vx, vy) spinning at w */
static gd_status journal_force(const gd_sfd_params *p, const gd_reynolds_grid *g,
                               const gd_journal_land *land, double w, const double *u, double *f,
                               gd_error *err)
{
    return gd_reynolds_land_force(p, g, land, w, u[0], u[1], u[2], u[3], &f[0], &f[1], err);
}

/* J[2 x 4] row-major = dF/d(x, y, vx, vy) by central differences */
static gd_status jacobian(const gd_sfd_params *p, const gd_reynolds_grid *g,
                          const gd_journal_land *land, double w, const double *u, double *J,
                          gd_error *err)
{
    double hs[4] = {1e-5 * p->clearance, 1e-5 * p->clearance, 1e-5 * p->clearance * w,
                    1e-5 * p->clearance * w};
    for (int j = 0; j < 4; j++) {
        double up[4] = {u[0], u[1], u[2], u[3]}, um[4] = {u[0], u[1], u[2], u[3]}, fp[2], fm[2];
        up[j] += hs[j];
        um[j] -= hs[j];
        gd_status st;
        if ((st = journal_force(p, g, land, w, up, fp, err)) ||
            (st = journal_force(p, g, land, w, um, fm, err)))
            return st;
        for (int i = 0; i < 2; i++)
            J[4 * i + j] = (fp[i] - fm[i]) / (2 * hs[j]);
    }
    return GD_OK;
}

gd_status gd_reynolds_journal(const gd_sfd_params *p, const gd_reynolds_grid *grid, double load,
                              double speed, double *eps, double *attitude, double K[4], double C[4],
                              gd_error *err)
{
    return gd_reynolds_journal_land(p, grid, NULL, load, speed, eps, attitude, K, C, err);
}

gd_status gd_reynolds_journal_land(const gd_sfd_params *p, const gd_reynolds_grid *grid,
                                   const gd_journal_land *land, double load, double speed,
                                   double *eps, double *attitude, double K[4], double C[4],
                                   gd_error *err)
{
    if (!(load > 0) || !isfinite(load) || !(speed > 0) || !isfinite(speed))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "load", "give a load and a speed > 0",
                            "a journal bearing's equilibrium needs a load and a speed");
    const double c = p->clearance;
    const double emax = p->max_eccentricity > 0 ? p->max_eccentricity : 0.995;
    /* start below the centre, where the load pushes */
    double u[4] = {0, -0.3 * c, 0, 0}, f[2], J[8];
    gd_status st;
    int found = 0;
    for (int it = 0; it < 60 && !found; it++) {
        if ((st = journal_force(p, grid, land, speed, u, f, err))) return st;
        double r0 = f[0], r1 = f[1] - load; /* film force + load (0, -W) */
        if (hypot(r0, r1) <= 1e-8 * load) {
            found = 1;
            break;
        }
        if ((st = jacobian(p, grid, land, speed, u, J, err))) return st;
        double a = J[0], b = J[1], cc = J[4], d = J[5], det = a * d - b * cc;
        if (!(fabs(det) > 0)) break;
        double dx = -(d * r0 - b * r1) / det, dy = -(-cc * r0 + a * r1) / det;
        /* keep the journal inside the cap: halve the step until it is */
        double t = 1;
        while (hypot(u[0] + t * dx, u[1] + t * dy) > emax * c && t > 1e-6)
            t *= 0.5;
        u[0] += t * dx;
        u[1] += t * dy;
    }
    if (!found)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "load",
                            "raise the speed, the viscosity or the bearing length, or lower the "
                            "load",
                            "the finite-length film carries no equilibrium for %g N at %g rad/s "
                            "below eccentricity %g",
                            load, speed, emax);
    *eps = hypot(u[0], u[1]) / c;
    *attitude = atan2(fabs(u[0]), -u[1]);
    if ((st = jacobian(p, grid, land, speed, u, J, err))) return st;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            K[2 * i + j] = -J[4 * i + j];
            C[2 * i + j] = -J[4 * i + j + 2];
        }
    return GD_OK;
}
