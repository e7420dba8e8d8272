/* Valve lift laws and the cam inertial torque of a desmodromic valve train,
 * [Benini2004] Eqs. 7-10: T = m_eq s'(theta) [s''(theta) W^2 + s'(theta) dW/dt]; and the
 * law type of one valve train on its camshaft's torsional DOF (gd_law_cam_torque), which
 * the model's `cam_torques:` make (one instance per valve).
 *
 * The cam angle is the camshaft's rotation in its own sense s (+1 turning about +z, -1
 * about -z): theta = s (rate t + q), W = s (spin + q'), dW/dt = s a (a the absolute
 * angular acceleration). The generalised force on q is -s T:
 *   f = -s m s' s'' W^2 - m s'^2 a
 * whose last term, with `acceleration` set, is the configuration-dependent inertia
 * m s'^2 (gd_law_type.inertia: the integrator applies it to q'' and a run-up's nominal
 * acceleration); without it the s'^2 dW/dt term is left out whole. */
#include <math.h>
#include <stdio.h>

#include "geardyn/law_type.h"
#include "geardyn/laws.h"

static inline double lift_at(const gd_lift_law *law, double theta, double *ds, double *d2s)
{
    if (law->kind == GD_LIFT_TABLE) return gd_table_eval(law->table, theta, ds, d2s);
    return gd_harmonic_eval(&law->harmonic, theta, ds, d2s);
}

double gd_lift_eval(const gd_lift_law *law, double theta, double *ds, double *d2s)
{
    return lift_at(law, theta, ds, d2s);
}

double gd_cam_torque(const gd_lift_law *law, double m_eq, double phase, double theta, double w,
                     double wdot)
{
    double s1, s2;
    gd_lift_eval(law, theta - phase, &s1, &s2);
    return m_eq * s1 * (s2 * w * w + s1 * wdot);
}

enum { CAM_MASS, CAM_PHASE, CAM_ACC, CAM_NPARAMS };

static const gd_law_param cam_params[CAM_NPARAMS] = {
    {"mass", GD_QTY_MASS, NAN, GD_LAW_NONNEG, "equivalent mass of the valve train, kg"},
    {"phase", GD_QTY_ANGLE, 0.0, GD_LAW_ANY, "cam angle of the valve's lift law, rad"},
    {"acceleration", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "1: keep the m s'^2 dW/dt term (include_acceleration), 0: leave it out"},
};

static const int cam_dirs[1] = {5}; /* rz */

static int cam_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    if (law->data) return 0;
    *field = "cams";
    snprintf(msg, cap, "cam on no DOF, or lift law missing");
    return 1;
}

static unsigned cam_flags(const gd_law *law)
{
    return GD_LAW_SMOOTH | (law->value[CAM_ACC] != 0.0 ? GD_LAW_INERTIA : 0u);
}

static void cam_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
}

/* The camshaft's sense: that of its spin, ratio W (at W = 0, the sign of the zero: the
 * ratio's, so a run-up from rest reads its lift in the sense it will turn in). */
static int cam_sense(const gd_law *law)
{
    return signbit(law->spin[0]) ? -1 : 1;
}

/* The force into f, with jq, jv when not NULL. */
static void cam_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    const gd_lift_law *lift = law->data;
    const int sense = cam_sense(law);
    const double m = law->value[CAM_MASS], phase = law->value[CAM_PHASE];
    double th = sense * (law->rate[0] * x->t + x->q[0]);
    double w = sense * (law->spin[0] + x->v[0]);
    double s1, s2;
    lift_at(lift, th - phase, &s1, &s2);
    f[0] -= sense * m * s1 * s2 * w * w;
    if (jq) {
        /* d(s' s'')/d theta by central differences (a table's third derivative jumps) */
        double s1p, s2p, s1m, s2m, h = 1e-6;
        lift_at(lift, th - phase + h, &s1p, &s2p);
        lift_at(lift, th - phase - h, &s1m, &s2m);
        double dss = (s1p * s2p - s1m * s2m) / (2.0 * h);
        jq[0] = -m * dss * w * w;
    }
    if (jv) jv[0] = -2.0 * m * s1 * s2 * w;
}

/* The inertia op (an instance with the acceleration term): the force, as cam_force
 * without the Jacobian, and m s'^2; on the right-hand side's path of every evaluation,
 * so written without cam_force's branches. */
static void cam_inertia(const gd_law *law, const gd_law_point *x, double *f, double *mass)
{
    const double s = cam_sense(law), m = law->value[CAM_MASS];
    const double w = s * (law->spin[0] + x->v[0]);
    double s1, s2;
    lift_at(law->data, s * (law->rate[0] * x->t + x->q[0]) - law->value[CAM_PHASE], &s1, &s2);
    f[0] -= s * m * s1 * s2 * w * w;
    mass[0] += m * s1 * s1;
}

/* The lift is periodic over one cam revolution: the camshaft's speed. */
static int cam_frequencies(const gd_law *law, double *w, int cap, char *msg, size_t cap_msg)
{
    (void)msg;
    (void)cap_msg;
    if (cap < 1) return 0;
    w[0] = fabs(law->rate[0]);
    return 1;
}

const gd_law_type gd_law_cam_torque = {
    .name = "cam_torque",
    .summary = "inertial torque of a desmodromic valve train on its camshaft ([Benini2004] "
               "Eq. 10)",
    .flags = GD_LAW_SMOOTH,
    .instance_flags = cam_flags,
    .params = cam_params,
    .nparams = CAM_NPARAMS,
    .dirs = cam_dirs,
    .ndirs = 1,
    .check = cam_check,
    .nterms = 1,
    .term = cam_term,
    .force = cam_force,
    .frequencies = cam_frequencies,
    .inertia = cam_inertia,
};
