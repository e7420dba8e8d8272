/* Speed-dependent drag torque of a gear turning in oil (an idler's drag at idle): oil
 * churning of the immersed part [ChangenetVelex2007] plus, optionally, the viscous shear
 * of its two faces against a near wall [DailyNece1960]. Local DOFs [rz of node, rz of
 * node2 (or ground: the housing)]; w = (rate + q') at node minus at node2.
 *
 * Churning ([ChangenetVelex2007], their Eqs. for the first regime, Re < 6000):
 *   C_ch = 1/2 rho w^2 S_m R^3 C_m,
 *   C_m  = 1.366 (h / D)^0.45 (V0 / D^3)^0.1 Fr^-0.6 Re^-0.21,
 *   Fr = w^2 R / g,  Re = w R b / nu,  nu = mu / rho,  D = 2 R,
 * with R the pitch radius, b the face width, h the immersion depth (oil level above the
 * lowest point of the pitch circle), V0 the oil volume and S_m the immersed surface. The
 * torque grows as |w|^0.59. S_m is taken as a smooth disc's: both faces' wetted circular
 * segment R^2 (2 a - sin 2a) and the wetted rim 2 a R b, cos a = 1 - h / R (the tooth
 * flanks' extra area is left out: a lower bound, the `surface` parameter overrides it).
 *
 * Viscous face drag, with `wall_gap` s > 0: laminar Couette flow between each face and a
 * wall at s (Daily & Nece's regime I, torque coefficient C_M = 2 pi / ((s/R) Re_R)):
 *   C_v = pi mu w R^4 / s   (both faces).
 *
 * The oil: its dynamic viscosity, or (viscosity 0) its kinematic viscosities at 40 and 100 C
 * and its temperature, through Walther's equation (ASTM D341; drag_speed.c).
 *
 * The sign is regularised below `velocity` (drag_speed.c). Records: the torque on node
 * (N m, opposing w), w, and Re (the first regime's validity). */
#include <math.h>
#include <stdio.h>

#include "laws/laws_impl.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

enum {
    CD_VISCOSITY,
    CD_DENSITY,
    CD_RADIUS,
    CD_WIDTH,
    CD_IMMERSION,
    CD_VOLUME,
    CD_SURFACE,
    CD_GAP,
    CD_VREG,
    CD_NU40,
    CD_NU100,
    CD_TEMP,
    CD_NPARAMS
};

static const gd_law_param cd_params[CD_NPARAMS] = {
    {"viscosity", GD_QTY_VISCOSITY, 0.0, GD_LAW_NONNEG,
     "dynamic viscosity mu of the oil at its temperature (Pa s, e.g. 0.04 Pa*s), or 0 and "
     "nu40, nu100, temperature"},
    {"density", GD_QTY_DENSITY, 870.0, GD_LAW_POSITIVE, "oil density rho (kg/m^3)"},
    {"radius", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "pitch radius R of the gear"},
    {"face_width", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "face width b of the gear"},
    {"immersion", GD_QTY_LENGTH, 0.0, GD_LAW_NONNEG,
     "immersion depth h of the pitch circle's lowest point, 0 .. 2 R (0: no churning)"},
    {"oil_volume", GD_QTY_DIMLESS, 1e-3, GD_LAW_POSITIVE, "oil volume V0 of the sump (m^3)"},
    {"surface", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "immersed surface S_m (m^2); 0: the smooth disc's from the immersion"},
    {"wall_gap", GD_QTY_LENGTH, 0.0, GD_LAW_NONNEG,
     "gap s between each face and a wall for the viscous face drag (0: none)"},
    {"velocity", GD_QTY_ANGULAR_SPEED, 1.0, GD_LAW_POSITIVE,
     "speed w_r below which the torque's sign is regularised (rad/s)"},
    {"nu40", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "without viscosity: kinematic viscosity at 40 C, mm^2/s (the ISO VG grade)"},
    {"nu100", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "without viscosity: at 100 C, mm^2/s"},
    {"temperature", GD_QTY_DIMLESS, 40.0, GD_LAW_ANY,
     "without viscosity: the oil's temperature, C (Walther's equation, ASTM D341)"},
};

static const int cd_dirs[1] = {5};

static void cd_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
    u[1] = w[1] = -1.0;
}

/* The immersed surface S_m (smooth disc, or the user's). */
static double cd_surface(const gd_law *law)
{
    const double *p = law->value;
    if (p[CD_SURFACE] > 0) return p[CD_SURFACE];
    double R = p[CD_RADIUS], b = p[CD_WIDTH], h = p[CD_IMMERSION];
    double a = acos(1.0 - h / R); /* half-angle of the wetted arc */
    return R * R * (2.0 * a - sin(2.0 * a)) + 2.0 * a * R * b;
}

/* The drag torque at relative speed w (opposing it) and dT/dw. */
static double cd_torque(const gd_law *law, double w, double *dT)
{
    const double *p = law->value;
    const double g0 = 9.81;
    double rho = p[CD_DENSITY], R = p[CD_RADIUS], b = p[CD_WIDTH];
    double mu = gd_law_drag_mu(p[CD_VISCOSITY], rho, p[CD_NU40], p[CD_NU100], p[CD_TEMP]);
    double h = p[CD_IMMERSION], D = 2.0 * R, nu = mu / rho;
    double s = gd_law_drag_s(w, p[CD_VREG]), g = 0.0, dg = 0.0;
    if (h > 0) {
        /* C_ch = A s^0.59: 2 - 2 (0.6) - 0.21 */
        double A = 0.5 * rho * cd_surface(law) * R * R * R * 1.366 * pow(h / D, 0.45) *
                   pow(p[CD_VOLUME] / (D * D * D), 0.1) * pow(R / g0, -0.6) *
                   pow(R * b / nu, -0.21);
        g = A * pow(s, 0.59);
        dg = 0.59 * g / s;
    }
    double T = gd_law_drag_odd(g, dg, w, s, dT);
    if (p[CD_GAP] > 0) { /* linear in w: no regularisation needed */
        double cv = M_PI * mu * R * R * R * R / p[CD_GAP];
        T += cv * w;
        if (dT) *dT += cv;
    }
    return T;
}

static void cd_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double dT, T = cd_torque(law, gd_law_drag_speed(law, x), &dT);
    f[0] -= T;
    f[1] += T;
    if (jq) jq[0] = 0.0;
    if (jv) jv[0] = -dT;
}

static const gd_law_record cd_records[] = {
    {"torque", "N m"}, {"speed", "rad/s"}, {"reynolds", "-"}};

static double cd_record(const gd_law *law, int k, const gd_law_point *x)
{
    double w = gd_law_drag_speed(law, x);
    if (k == 0) return -cd_torque(law, w, NULL);
    if (k == 1) return w;
    const double *p = law->value;
    double mu = gd_law_drag_mu(p[CD_VISCOSITY], p[CD_DENSITY], p[CD_NU40], p[CD_NU100], p[CD_TEMP]);
    return fabs(w) * p[CD_RADIUS] * p[CD_WIDTH] * p[CD_DENSITY] / mu;
}

static int cd_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    const double *p = law->value;
    if (gd_law_drag_check_oil(p[CD_VISCOSITY], p[CD_NU40], p[CD_NU100], p[CD_TEMP], field, msg,
                              cap))
        return 1;
    if (p[CD_IMMERSION] > 2.0 * p[CD_RADIUS]) {
        *field = "immersion";
        snprintf(msg, cap,
                 "the immersion depth %g m exceeds the pitch diameter %g m (the model's range "
                 "is 0 .. 2 R)",
                 p[CD_IMMERSION], 2.0 * p[CD_RADIUS]);
        return 1;
    }
    return 0;
}

const gd_law_type gd_law_churning_drag = {
    .name = "churning_drag",
    .summary = "drag torque of a gear in oil: churning (Changenet & Velex) + viscous face drag",
    .flags = GD_LAW_SMOOTH,
    .params = cd_params,
    .nparams = CD_NPARAMS,
    .dirs = cd_dirs,
    .ndirs = 1,
    .two_nodes = 1,
    .check = cd_check,
    .nterms = 1,
    .term = cd_term,
    .force = cd_force,
    .records = cd_records,
    .nrecords = 3,
    .record = cd_record,
    .linearize = gd_law_linearize_terms,
};
