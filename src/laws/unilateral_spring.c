/* Unilateral spring with a gap between two DOFs of one direction, or from one DOF to
 * ground: a one-sided elastic stop (NLvib's "unilateralSpring", Krack & Gross, Harmonic
 * Balance for Nonlinear Vibration Problems, 2019, its example 03):
 *
 *   F = k (s d - g) + c s d'   when s d >= g,   else 0,   d = q_node - q_node2
 *
 * with side s = +1 (contact when d reaches +g) or -1 (when d reaches -g); acting as
 * -s F on the node and +s F on node2. SI values: k in N/m (N m/rad), g in m (rad),
 * c in N s/m (damping while in contact only). Local DOFs [q_node, q_node2]. */
#include <math.h>
#include <stdio.h>

#include "geardyn/law_type.h"

enum { US_K, US_GAP, US_C, US_SIDE, US_NPARAMS };

static const gd_law_param us_params[US_NPARAMS] = {
    {"stiffness", GD_QTY_DIMLESS, NAN, GD_LAW_NONNEG,
     "contact stiffness, N/m (N m/rad), SI number"},
    {"gap", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "free travel before contact, m (rad), SI number"},
    {"damping", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "viscous coefficient while in contact, N s/m, SI number"},
    {"side", GD_QTY_DIMLESS, 1.0, GD_LAW_ANY,
     "+1: contact when q_node - q_to reaches +gap; -1: when it reaches -gap"},
};

static int us_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    double s = law->value[US_SIDE];
    if (s == 1.0 || s == -1.0) return 0;
    *field = "side";
    snprintf(msg, cap, "side is %g: give 1 (contact at d = +gap) or -1 (at d = -gap)", s);
    return 1;
}

static void us_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
    u[1] = w[1] = -1.0;
}

/* The contact force F >= 0 along s, and its derivatives in d and d' (times s^2 = 1). */
static double us_law(const gd_law *law, double d, double dd, double *kt, double *ct)
{
    const double *c = law->value;
    const double s = c[US_SIDE], pen = s * d - c[US_GAP];
    const int on = pen >= 0.0;
    if (kt) *kt = on ? c[US_K] : 0.0;
    if (ct) *ct = on ? c[US_C] : 0.0;
    return on ? c[US_K] * pen + c[US_C] * s * dd : 0.0;
}

static void us_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double kt, ct, s = law->value[US_SIDE];
    double F = us_law(law, x->q[0] - x->q[1], x->v[0] - x->v[1], &kt, &ct);
    f[0] -= s * F;
    f[1] += s * F;
    if (jq) jq[0] = -kt;
    if (jv) jv[0] = -ct;
}

static const gd_law_record us_records[] = {{"force", "N"}, {"penetration", "m"}};

static double us_record(const gd_law *law, int k, const gd_law_point *x)
{
    double d = x->q[0] - x->q[1];
    if (k == 0) return us_law(law, d, x->v[0] - x->v[1], NULL, NULL);
    return law->value[US_SIDE] * d - law->value[US_GAP];
}

static void us_linearize(const gd_law *law, const gd_law_point *x, double *K, double *C)
{
    double kt, ct;
    us_law(law, x->q[0] - x->q[1], 0.0, &kt, &ct);
    const double sg[4] = {1.0, -1.0, -1.0, 1.0};
    for (int k = 0; k < 4; k++) {
        K[k] += kt * sg[k];
        C[k] += ct * sg[k];
    }
}

const gd_law_type gd_law_unilateral_spring = {
    .name = "unilateral_spring",
    .summary = "one-sided spring k (s d - gap) with damping, acting only in contact",
    .flags = 0,
    .params = us_params,
    .nparams = US_NPARAMS,
    .two_nodes = 1,
    .check = us_check,
    .nterms = 1,
    .term = us_term,
    .force = us_force,
    .records = us_records,
    .nrecords = 2,
    .record = us_record,
    .linearize = us_linearize,
};
