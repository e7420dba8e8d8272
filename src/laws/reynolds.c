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

gd_status gd_reynolds_force(const gd_sfd_params *p, const gd_reynolds_grid *grid, double x,
                            double y, double vx, double vy, double *fx, double *fy, gd_error *err)
{
    *fx = *fy = 0;
    gd_reynolds_grid def;
    if (!grid) {
        gd_reynolds_grid_init(&def);
        grid = &def;
    }
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
    int proj = grid->cavitation == GD_FILM_REYNOLDS, done = 0;
    gd_status st = GD_OK;
    for (int sweep = 0; sweep < 20000 && !done; sweep++) {
        double du = 0, pm = 0;
        for (int i = 0; i < nt; i++) {
            int ie = (i + 1) % nt, iw = (i + nt - 1) % nt;
            double ae = he[i] * ct, aw = he[iw] * ct, az = h3[i] * cz;
            double diag = ae + aw + 2 * az;
            for (int k = 0; k < nz; k++) {
                double pn = k + 1 < nz ? P[i * nz + k + 1] : 0, ps = k > 0 ? P[i * nz + k - 1] : 0;
                double gs =
                    (ae * P[ie * nz + k] + aw * P[iw * nz + k] + az * (pn + ps) - rhs[i]) / diag;
                double old = P[i * nz + k], v = old + 1.8 * (gs - old);
                if (proj && v < 0) v = 0;
                P[i * nz + k] = v;
                du = fmax(du, fabs(v - old));
                pm = fmax(pm, fabs(v));
            }
        }
        if (du <= grid->tol * pm || pm == 0) done = 1;
    }
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

/* the journal's film force at (x, y, vx, vy) spinning at w: the squeeze film's in the
   frame turning at w / 2 */
static gd_status journal_force(const gd_sfd_params *p, const gd_reynolds_grid *g, double w,
                               const double *u, double *f, gd_error *err)
{
    double h = 0.5 * w;
    return gd_reynolds_force(p, g, u[0], u[1], u[2] + h * u[1], u[3] - h * u[0], &f[0], &f[1], err);
}

/* J[2 x 4] row-major = dF/d(x, y, vx, vy) by central differences */
static gd_status jacobian(const gd_sfd_params *p, const gd_reynolds_grid *g, double w,
                          const double *u, double *J, gd_error *err)
{
    double hs[4] = {1e-5 * p->clearance, 1e-5 * p->clearance, 1e-5 * p->clearance * w,
                    1e-5 * p->clearance * w};
    for (int j = 0; j < 4; j++) {
        double up[4] = {u[0], u[1], u[2], u[3]}, um[4] = {u[0], u[1], u[2], u[3]}, fp[2], fm[2];
        up[j] += hs[j];
        um[j] -= hs[j];
        gd_status st;
        if ((st = journal_force(p, g, w, up, fp, err)) ||
            (st = journal_force(p, g, w, um, fm, err)))
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
        if ((st = journal_force(p, grid, speed, u, f, err))) return st;
        double r0 = f[0], r1 = f[1] - load; /* film force + load (0, -W) */
        if (hypot(r0, r1) <= 1e-8 * load) {
            found = 1;
            break;
        }
        if ((st = jacobian(p, grid, speed, u, J, err))) return st;
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
    if ((st = jacobian(p, grid, speed, u, J, err))) return st;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            K[2 * i + j] = -J[4 * i + j];
            C[2 * i + j] = -J[4 * i + j + 2];
        }
    return GD_OK;
}
