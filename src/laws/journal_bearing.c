/* Plain hydrodynamic journal bearing, short-bearing (Ocvirk) theory with a cavitated
 * (pi) film: the squeeze film damper's Reynolds solution (src/laws/sfd.c) with the
 * journal spinning. With the journal turning at w relative to the bush, the film sees
 * the squeeze velocity plus the wedge term (w / 2) dh/dtheta, which is the squeeze film
 * of a journal whirling at phi' - w / 2 (Childs, Turbomachinery Rotordynamics, 1993,
 * ch. 3; San Andres's notes on short bearings): the force at (x, y, x', y') is the
 * damper's at the velocity relative to a frame turning at w / 2,
 *
 *   F(x, y, x', y') = F_sfd(x, y, x' + (w / 2) y, y' - (w / 2) x).
 *
 * Static check: a journal held at eccentricity ratio eps carries the Ocvirk load
 * W = mu w R L^3 / (4 c^2) eps sqrt(pi^2 (1 - eps^2) + 16 eps^2) / (1 - eps^2)^2 at the
 * attitude angle tan(phi) = pi sqrt(1 - eps^2) / (4 eps) from the line of centres
 * (tests/laws/test_journal_bearing.c). The spin w is the spin of the journal node's
 * shaft minus that of the bush node's (law->spin). Local DOFs [x, y] of the journal,
 * then [x, y] of the bush (absent: ground).
 *
 * model: 1 takes the film's force from the finite-length Reynolds equation instead
 * (geardyn/reynolds.h: finite differences on a 96 x 21 grid, SOR), at the same relative
 * velocity in the frame turning at w / 2; cavitation 0 drops the negative pressures of
 * the full film (Gumbel, half-Sommerfeld), 1 keeps p >= 0 during the solution
 * (Christopherson: the Reynolds condition at the film's rupture). Its Jacobian is by
 * central differences (steps 1e-5 of c and of c w): eight more film solutions. `film`
 * is the short bearing's and is not used by it.
 *
 * land_arc > 0 (finite model only) gives the bush an axial groove: the film covers the
 * land from land_start over land_arc (angles from the bush's +x towards +y, the spin's
 * direction), its edges at supply_pressure, solved in the bush's frame
 * (gd_reynolds_land_force; ROSS's FixedGeometryBearing with one pad). The position and
 * velocity are then the journal's relative to the bush as they are, and the Jacobian is
 * by central differences in them directly. */
#include <math.h>
#include <stdio.h>

#include "geardyn/laws.h"
#include "geardyn/reynolds.h"
#include "laws/laws_impl.h"

enum {
    JB_MU,
    JB_D,
    JB_L,
    JB_C,
    JB_FILM,
    JB_EMAX,
    JB_MODEL,
    JB_CAV,
    JB_LSTART,
    JB_LARC,
    JB_PSUP,
    JB_NPARAMS
};

static const gd_law_param jb_params[JB_NPARAMS] = {
    {"viscosity", GD_QTY_VISCOSITY, NAN, GD_LAW_POSITIVE, "the oil's dynamic viscosity, Pa s"},
    {"diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the journal diameter D"},
    {"length", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the bearing length L (short: L/D <= 0.5)"},
    {"clearance", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the radial clearance c"},
    {"film", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "0: pi (cavitated) film, 1: 2pi film"},
    {"max_eccentricity", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "cap of the eccentricity ratio, below 1 (0: 0.995)"},
    {"model", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "0: short bearing (Ocvirk), 1: finite length (Reynolds equation by finite differences)"},
    {"cavitation", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "finite model: 0 Gumbel (half-Sommerfeld), 1 Reynolds condition (Christopherson)"},
    {"land_start", GD_QTY_ANGLE, 0.0, GD_LAW_ANY,
     "finite model with a groove: the land's leading edge, from the bush's +x towards +y"},
    {"land_arc", GD_QTY_ANGLE, 0.0, GD_LAW_NONNEG,
     "finite model: the land's extent below 360 deg, an axial groove filling the rest (0: no "
     "groove)"},
    {"supply_pressure", GD_QTY_PRESSURE, 0.0, GD_LAW_NONNEG,
     "finite model with a groove: the oil's gauge pressure in the groove"},
};

static void jb_params_of(const gd_law *law, gd_sfd_params *p)
{
    const double *v = law->value;
    p->viscosity = v[JB_MU];
    p->radius = 0.5 * v[JB_D];
    p->length = v[JB_L];
    p->clearance = v[JB_C];
    p->film = v[JB_FILM] != 0.0 ? GD_SFD_2PI_FILM : GD_SFD_PI_FILM;
    p->correction = -1.0; /* Ocvirk's short bearing as it is */
    p->max_eccentricity = v[JB_EMAX];
}

static int jb_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    const double *v = law->value;
    if (v[JB_MODEL] != 0.0 && v[JB_MODEL] != 1.0) {
        *field = "model";
        snprintf(msg, cap, "model is 0 (short bearing) or 1 (finite length), not %g", v[JB_MODEL]);
        return 1;
    }
    if (v[JB_CAV] != 0.0 && v[JB_CAV] != 1.0) {
        *field = "cavitation";
        snprintf(msg, cap, "cavitation is 0 (Gumbel) or 1 (Reynolds condition), not %g", v[JB_CAV]);
        return 1;
    }
    if (v[JB_LARC] != 0.0 && (v[JB_MODEL] != 1.0 || !(v[JB_LARC] < 6.283185307179586))) {
        *field = "land_arc";
        snprintf(msg, cap,
                 "a groove (land_arc %g rad) needs model: 1 and a land below 360 deg (2 pi rad)",
                 v[JB_LARC]);
        return 1;
    }
    return gd_law_check_film(v[JB_FILM], v[JB_EMAX], field, msg, cap);
}

static int jb_grooved(const gd_law *law)
{
    return law->value[JB_MODEL] != 0.0 && law->value[JB_LARC] > 0.0;
}

/* The grooved film's force at relative (x, y, vx, vy) in the bush's frame, spinning at w;
 * as finite_force, its last iterate's force if SOR does not converge. */
static void land_force(const gd_law *law, const gd_sfd_params *p, double w, const double *u,
                       double *f)
{
    gd_reynolds_grid g;
    gd_reynolds_grid_init(&g);
    g.cavitation = law->value[JB_CAV] != 0.0 ? GD_FILM_REYNOLDS : GD_FILM_GUMBEL;
    gd_journal_land land = {law->value[JB_LSTART], law->value[JB_LARC], law->value[JB_PSUP]};
    gd_error err;
    gd_reynolds_land_force(p, &g, &land, w, u[0], u[1], u[2], u[3], &f[0], &f[1], &err);
}

/* the grooved film's force and, if jq or jv, its Jacobians by central differences */
static void land_eval(const gd_law *law, const gd_sfd_params *p, double w, const double *u,
                      double *fx, double *fy, double *jq, double *jv)
{
    double f[2];
    land_force(law, p, w, u, f);
    *fx = f[0];
    *fy = f[1];
    if (!jq && !jv) return;
    double c = p->clearance, hv = 1e-5 * c * fmax(fabs(w), 1.0);
    double hs[4] = {1e-5 * c, 1e-5 * c, hv, hv};
    for (int j = 0; j < 4; j++) {
        double *J = j < 2 ? jq : jv;
        if (!J) continue;
        double up[4] = {u[0], u[1], u[2], u[3]}, um[4] = {u[0], u[1], u[2], u[3]}, fp[2], fm[2];
        up[j] += hs[j];
        um[j] -= hs[j];
        land_force(law, p, w, up, fp);
        land_force(law, p, w, um, fm);
        for (int i = 0; i < 2; i++)
            J[2 * i + (j & 1)] = (fp[i] - fm[i]) / (2 * hs[j]);
    }
}

/* The finite-length film's force at relative (x, y) and frame velocity (vx, vy). A grid
 * that does not converge in SOR's sweep limit still gives its last (finite) iterate's
 * force: the force law has no error channel, and the iterate is the best estimate. */
static void finite_force(const gd_law *law, const gd_sfd_params *p, double x, double y, double vx,
                         double vy, double *fx, double *fy)
{
    gd_reynolds_grid g;
    gd_reynolds_grid_init(&g);
    g.cavitation = law->value[JB_CAV] != 0.0 ? GD_FILM_REYNOLDS : GD_FILM_GUMBEL;
    gd_error err;
    gd_reynolds_force(p, &g, x, y, vx, vy, fx, fy, &err);
}

/* Its Jacobian by central differences, in the frame velocities (a, b as
 * gd_sfd_force_jacobian's jq, jv). */
static void finite_jacobian(const gd_law *law, const gd_sfd_params *p, double w, double x, double y,
                            double vx, double vy, double *fx, double *fy, double a[4], double b[4])
{
    double u[4] = {x, y, vx, vy}, c = p->clearance;
    double hs[4] = {1e-5 * c, 1e-5 * c, 1e-5 * c * fmax(fabs(w), 1.0),
                    1e-5 * c * fmax(fabs(w), 1.0)};
    finite_force(law, p, x, y, vx, vy, fx, fy);
    for (int j = 0; j < 4; j++) {
        double up[4] = {u[0], u[1], u[2], u[3]}, um[4] = {u[0], u[1], u[2], u[3]}, fp[2], fm[2];
        up[j] += hs[j];
        um[j] -= hs[j];
        finite_force(law, p, up[0], up[1], up[2], up[3], &fp[0], &fp[1]);
        finite_force(law, p, um[0], um[1], um[2], um[3], &fm[0], &fm[1]);
        double *J = j < 2 ? a : b;
        for (int i = 0; i < 2; i++)
            J[2 * i + (j & 1)] = (fp[i] - fm[i]) / (2 * hs[j]);
    }
}

/* force on the journal and, if J, its Jacobians (row-major 2 x 2: jq, jv) */
static void jb_eval(const gd_law *law, const gd_law_point *x, double *fx, double *fy, double *jq,
                    double *jv)
{
    gd_sfd_params p;
    jb_params_of(law, &p);
    double h = 0.5 * (law->spin[0] - law->spin[1]);
    double rx = x->q[0] - x->q[2], ry = x->q[1] - x->q[3];
    if (jb_grooved(law)) {
        double u[4] = {rx, ry, x->v[0] - x->v[2], x->v[1] - x->v[3]};
        land_eval(law, &p, 2.0 * h, u, fx, fy, jq, jv);
        return;
    }
    double vx = x->v[0] - x->v[2] + h * ry, vy = x->v[1] - x->v[3] - h * rx;
    int finite = law->value[JB_MODEL] != 0.0;
    if (!jq && !jv) {
        if (finite)
            finite_force(law, &p, rx, ry, vx, vy, fx, fy);
        else
            gd_sfd_force(&p, rx, ry, vx, vy, fx, fy);
        return;
    }
    double a[4], b[4];
    if (finite)
        finite_jacobian(law, &p, 2.0 * h, rx, ry, vx, vy, fx, fy, a, b);
    else
        gd_sfd_force_jacobian(&p, rx, ry, vx, vy, fx, fy, a, b);
    /* chain rule through the turning frame: d(vx)/dy = h, d(vy)/dx = -h */
    if (jq) {
        jq[0] = a[0] - h * b[1];
        jq[1] = a[1] + h * b[0];
        jq[2] = a[2] - h * b[3];
        jq[3] = a[3] + h * b[2];
    }
    if (jv)
        for (int k = 0; k < 4; k++)
            jv[k] = b[k];
}

static void jb_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double fx, fy;
    jb_eval(law, x, &fx, &fy, jq, jv);
    f[0] += fx;
    f[1] += fy;
    f[2] -= fx;
    f[3] -= fy;
}

static const gd_law_record jb_records[] = {{"fx", "N"}, {"fy", "N"}, {"ecc", "-"}};

static double jb_record(const gd_law *law, int k, const gd_law_point *x)
{
    if (k == 2) return hypot(x->q[0] - x->q[2], x->q[1] - x->q[3]) / law->value[JB_C];
    double fx, fy;
    jb_eval(law, x, &fx, &fy, NULL, NULL);
    return k == 0 ? fx : fy;
}

const gd_law_type gd_law_journal_bearing = {
    .name = "journal_bearing",
    .summary = "plain journal bearing: short-bearing (Ocvirk) theory with film rupture, or the "
               "finite-length Reynolds equation",
    .flags = GD_LAW_SMOOTH | GD_LAW_SUPPORT,
    .params = jb_params,
    .nparams = JB_NPARAMS,
    .dirs = gd_law_xy_dirs,
    .ndirs = 2,
    .two_nodes = 1,
    .check = jb_check,
    .nterms = 4,
    .term = gd_law_xy_term,
    .force = jb_force,
    .records = jb_records,
    .nrecords = 3,
    .record = jb_record,
    .linearize = gd_law_linearize_terms,
};
