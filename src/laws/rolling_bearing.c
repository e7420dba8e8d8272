/* Rolling-element bearing: Hertzian contacts of Z balls or rollers with radial
 * clearance, the cage turning at its kinematic speed, so that the bearing's stiffness
 * varies at the ball-pass frequency (the "varying compliance" vibration of Sunnersjo
 * 1978, Fukata et al. 1985, Tiwari, Gupta & Prakash, J. Sound Vib. 238 (2000) 723).
 *
 * The inner race (node) moves by (x, y) relative to the outer race (node2, or ground).
 * Element j sits at theta_j = theta_c + 2 pi j / Z, theta_c = w_c t + phase, and is
 * compressed by delta_j = x cos theta_j + y sin theta_j - gamma (gamma: radial clearance);
 * it carries Q_j = K delta_j^n when delta_j > 0 (Hertz: n = 3/2 for point contact, 10/9
 * for line contact; Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., 2006, ch. 6-7).
 * The force on the inner race is -sum Q_j (cos theta_j, sin theta_j), plus a viscous
 * damping c (x', y'), and the opposite on the outer race.
 *
 * Cage speed (pure rolling, Harris & Kotzalas ch. 8): with inner and outer races spinning
 * at w_i, w_o, w_c = [w_i (1 - g) + w_o (1 + g)] / 2, g = (d / D) cos(alpha), d the ball
 * diameter, D the pitch diameter, alpha the contact angle; the elements pass a point of
 * the outer race at Z |w_c - w_o|, the frequency of the varying compliance.
 *
 * Local DOFs [x, y] of node, then [x, y] of node2. The force is C1 for n > 1. */
#include <math.h>
#include <stdio.h>

#include "geardyn/law_type.h"
#include "laws/laws_impl.h"

enum { RB_Z, RB_K, RB_N, RB_GAP, RB_D, RB_DB, RB_ALPHA, RB_C, RB_PHASE, RB_NPARAMS };

static const gd_law_param rb_params[RB_NPARAMS] = {
    {"elements", GD_QTY_DIMLESS, NAN, GD_LAW_POSITIVE, "number of balls or rollers Z (3 or more)"},
    {"contact_stiffness", GD_QTY_DIMLESS, NAN, GD_LAW_POSITIVE,
     "load-deflection constant K of one element, N/m^n (SI number)"},
    {"exponent", GD_QTY_DIMLESS, 1.5, GD_LAW_POSITIVE, "Hertz exponent n: 1.5 balls, 10/9 rollers"},
    {"clearance", GD_QTY_LENGTH, 0.0, GD_LAW_NONNEG, "radial internal clearance gamma"},
    {"pitch_diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "pitch diameter D of the elements"},
    {"element_diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "ball or roller diameter d"},
    {"contact_angle", GD_QTY_ANGLE, 0.0, GD_LAW_NONNEG, "contact angle alpha"},
    {"damping", GD_QTY_DAMPING, 0.0, GD_LAW_NONNEG, "viscous damping c of the bearing, N s/m"},
    {"phase", GD_QTY_ANGLE, 0.0, GD_LAW_ANY, "cage angle of element 0 at t = 0"},
};

static int rb_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    const double *p = law->value;
    if (p[RB_Z] < 3 || p[RB_Z] != floor(p[RB_Z]) || p[RB_Z] > 1000) {
        *field = "elements";
        snprintf(msg, cap, "the number of elements is a whole number from 3 to 1000 (got %g)",
                 p[RB_Z]);
        return 1;
    }
    if (p[RB_N] < 1.0 || p[RB_N] > 2.0) {
        *field = "exponent";
        snprintf(msg, cap, "the Hertz exponent is between 1 and 2 (got %g)", p[RB_N]);
        return 1;
    }
    if (!(p[RB_DB] < p[RB_D])) {
        *field = "element_diameter";
        snprintf(msg, cap, "the element diameter %g m must be below the pitch diameter %g m",
                 p[RB_DB], p[RB_D]);
        return 1;
    }
    if (!(p[RB_ALPHA] < 1.5707963267948966)) {
        *field = "contact_angle";
        snprintf(msg, cap, "the contact angle must be below 90 deg");
        return 1;
    }
    return 0;
}

/* cage speed, rad/s */
static double cage_speed(const gd_law *law)
{
    double g = law->value[RB_DB] / law->value[RB_D] * cos(law->value[RB_ALPHA]);
    return 0.5 * (law->spin[0] * (1.0 - g) + law->spin[1] * (1.0 + g));
}

/* Contact force on the inner race (fx, fy) at relative (x, y) and time t, its stiffness
 * J = d(fx, fy)/d(x, y) (row-major 2 x 2, may be NULL), the number of loaded elements
 * and the largest element load. */
static void rb_contacts(const gd_law *law, double t, double x, double y, double *fx, double *fy,
                        double J[4], int *nloaded, double *qmax)
{
    const double *p = law->value;
    int Z = (int)p[RB_Z];
    double th0 = cage_speed(law) * t + p[RB_PHASE], n = p[RB_N];
    double sx = 0, sy = 0, kxx = 0, kxy = 0, kyy = 0, qm = 0;
    int nl = 0;
    for (int j = 0; j < Z; j++) {
        double th = th0 + 6.283185307179586 * j / Z, c = cos(th), s = sin(th);
        double d = x * c + y * s - p[RB_GAP];
        if (d <= 0) continue;
        double dn1 = pow(d, n - 1.0), q = p[RB_K] * dn1 * d, kq = n * p[RB_K] * dn1;
        sx += q * c;
        sy += q * s;
        kxx += kq * c * c;
        kxy += kq * c * s;
        kyy += kq * s * s;
        qm = q > qm ? q : qm;
        nl++;
    }
    *fx = -sx;
    *fy = -sy;
    if (J) {
        J[0] = -kxx;
        J[1] = -kxy;
        J[2] = -kxy;
        J[3] = -kyy;
    }
    if (nloaded) *nloaded = nl;
    if (qmax) *qmax = qm;
}

static void rb_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double rx = x->q[0] - x->q[2], ry = x->q[1] - x->q[3], fx, fy, J[4];
    double c = law->value[RB_C];
    rb_contacts(law, x->t, rx, ry, &fx, &fy, jq ? J : NULL, NULL, NULL);
    fx -= c * (x->v[0] - x->v[2]);
    fy -= c * (x->v[1] - x->v[3]);
    f[0] += fx;
    f[1] += fy;
    f[2] -= fx;
    f[3] -= fy;
    for (int k = 0; k < 4; k++) {
        if (jq) jq[k] = J[k];
        if (jv) jv[k] = k == 0 || k == 3 ? -c : 0.0;
    }
}

static int rb_frequencies(const gd_law *law, double *w, int cap, char *msg, size_t cap_msg)
{
    (void)msg, (void)cap_msg;
    double f = law->value[RB_Z] * fabs(cage_speed(law) - law->spin[1]);
    if (!(f > 0) || cap < 1) return 0;
    w[0] = f;
    return 1;
}

static const gd_law_record rb_records[] = {
    {"fx", "N"}, {"fy", "N"}, {"loaded", "-"}, {"max_element_load", "N"}};

static double rb_record(const gd_law *law, int k, const gd_law_point *x)
{
    double fx, fy, qm;
    int nl;
    rb_contacts(law, x->t, x->q[0] - x->q[2], x->q[1] - x->q[3], &fx, &fy, NULL, &nl, &qm);
    double c = law->value[RB_C];
    if (k == 0) return fx - c * (x->v[0] - x->v[2]);
    if (k == 1) return fy - c * (x->v[1] - x->v[3]);
    return k == 2 ? (double)nl : qm;
}

const gd_law_type gd_law_rolling_bearing = {
    .name = "rolling_bearing",
    .summary = "ball or roller bearing: Hertzian contacts with clearance, cage at its "
               "kinematic speed (varying compliance)",
    .flags = GD_LAW_SMOOTH | GD_LAW_SUPPORT | GD_LAW_CONSTANT_SPEED,
    .params = rb_params,
    .nparams = RB_NPARAMS,
    .dirs = gd_law_xy_dirs,
    .ndirs = 2,
    .two_nodes = 1,
    .check = rb_check,
    .nterms = 4,
    .term = gd_law_xy_term,
    .force = rb_force,
    .frequencies = rb_frequencies,
    .records = rb_records,
    .nrecords = 4,
    .record = rb_record,
    .linearize = gd_law_linearize_terms,
};
