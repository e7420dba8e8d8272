/* Friction moment of a rolling bearing (a needle bearing between an idler and its shaft,
 * or a shaft's support to the housing), Palmgren's two-term form [Palmgren1959]
 * [HarrisKotzalas2006]:
 *
 *   M = M0 + M1,
 *   M0 = 1e-7 f0 (nu n)^(2/3) dm^3   for nu n >= 2000,   160e-7 f0 dm^3 below,
 *   M1 = f1 P1 dm,
 *
 * in N mm with nu the oil's kinematic viscosity in mm^2/s (cSt), n the relative speed in
 * rpm and dm the pitch diameter in mm: M0 is the load-independent viscous moment (f0 by
 * bearing type and lubrication: tables of the references), M1 the load-dependent one
 * (f1, P1 the equivalent load). Local DOFs [rz of node, rz of node2 (or ground)]; the
 * relative speed w = (rate + q') at node minus at node2, its sign regularised below
 * `velocity` (drag_speed.c). The oil as for churning_drag: its viscosity, or nu40, nu100
 * and a temperature (Walther's equation, drag_speed.c). M0 has a kink at nu n = 2000 (continuous,
 * 158.7 against 160), so the law is not flagged smooth. */
#include <math.h>
#include <stdio.h>

#include "laws/laws_impl.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

enum {
    BD_F0,
    BD_DM,
    BD_VISCOSITY,
    BD_DENSITY,
    BD_F1,
    BD_LOAD,
    BD_VREG,
    BD_NU40,
    BD_NU100,
    BD_TEMP,
    BD_NPARAMS
};

static const gd_law_param bd_params[BD_NPARAMS] = {
    {"f0", GD_QTY_DIMLESS, NAN, GD_LAW_NONNEG,
     "Palmgren's factor f0 of the bearing type and lubrication (e.g. 2 .. 12 for needle "
     "bearings in an oil bath)"},
    {"pitch_diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "pitch diameter dm of the bearing"},
    {"viscosity", GD_QTY_VISCOSITY, 0.0, GD_LAW_NONNEG,
     "dynamic viscosity mu of the oil at its temperature (Pa s), or 0 and nu40, nu100, "
     "temperature"},
    {"density", GD_QTY_DENSITY, 870.0, GD_LAW_POSITIVE, "oil density rho (kg/m^3): nu = mu / rho"},
    {"f1", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "Palmgren's load factor f1 (0: no load term)"},
    {"load", GD_QTY_FORCE, 0.0, GD_LAW_NONNEG, "equivalent load P1 of the load term"},
    {"velocity", GD_QTY_ANGULAR_SPEED, 1.0, GD_LAW_POSITIVE,
     "speed w_r below which the moment's sign is regularised (rad/s)"},
    {"nu40", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "without viscosity: kinematic viscosity at 40 C, mm^2/s (the ISO VG grade)"},
    {"nu100", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "without viscosity: at 100 C, mm^2/s"},
    {"temperature", GD_QTY_DIMLESS, 40.0, GD_LAW_ANY,
     "without viscosity: the oil's temperature, C (Walther's equation, ASTM D341)"},
};

static const int bd_dirs[1] = {5};

static void bd_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
    u[1] = w[1] = -1.0;
}

/* The moment opposing relative speed w, and dM/dw. */
static double bd_torque(const gd_law *law, double w, double *dT)
{
    const double *p = law->value;
    double s = gd_law_drag_s(w, p[BD_VREG]);
    double mu = gd_law_drag_mu(p[BD_VISCOSITY], p[BD_DENSITY], p[BD_NU40], p[BD_NU100], p[BD_TEMP]);
    double nu_cst = mu / p[BD_DENSITY] * 1e6, n = s * 30.0 / M_PI;
    double dm_mm = p[BD_DM] * 1e3, g, dg;
    if (nu_cst * n >= 2000.0) {
        g = 1e-7 * p[BD_F0] * pow(nu_cst * n, 2.0 / 3.0) * dm_mm * dm_mm * dm_mm * 1e-3;
        dg = 2.0 / 3.0 * g / s;
    } else {
        g = 160e-7 * p[BD_F0] * dm_mm * dm_mm * dm_mm * 1e-3;
        dg = 0.0;
    }
    g += p[BD_F1] * p[BD_LOAD] * p[BD_DM]; /* N m with dm in m */
    return gd_law_drag_odd(g, dg, w, s, dT);
}

static void bd_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double dT, T = bd_torque(law, gd_law_drag_speed(law, x), &dT);
    f[0] -= T;
    f[1] += T;
    if (jq) jq[0] = 0.0;
    if (jv) jv[0] = -dT;
}

static int bd_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    const double *p = law->value;
    return gd_law_drag_check_oil(p[BD_VISCOSITY], p[BD_NU40], p[BD_NU100], p[BD_TEMP], field, msg,
                                 cap);
}

static const gd_law_record bd_records[] = {{"torque", "N m"}, {"speed", "rad/s"}};

static double bd_record(const gd_law *law, int k, const gd_law_point *x)
{
    double w = gd_law_drag_speed(law, x);
    return k == 0 ? -bd_torque(law, w, NULL) : w;
}

const gd_law_type gd_law_bearing_drag = {
    .name = "bearing_drag",
    .summary = "rolling-bearing friction moment M0 + M1 (Palmgren) between two torsional DOFs",
    .params = bd_params,
    .nparams = BD_NPARAMS,
    .dirs = bd_dirs,
    .ndirs = 1,
    .two_nodes = 1,
    .check = bd_check,
    .nterms = 1,
    .term = bd_term,
    .force = bd_force,
    .records = bd_records,
    .nrecords = 2,
    .record = bd_record,
    .linearize = gd_law_linearize_terms,
};
