/* Coulomb friction between two DOFs of one direction (or one DOF and ground),
 * regularised by a hyperbolic tangent so that the force is smooth (a common choice in
 * harmonic balance; NLvib's regularised friction element, Krack & Gross 2019, Sec. 2.3):
 *
 *   F = F_c tanh(s / v_reg),   s = q'_node - q'_node2 (the slip velocity)
 *
 * acting as -F on the node and +F on node2: a friction force of level F_c (mu N, N or
 * N m) that opposes the slip, linear with slope F_c / v_reg below the regularisation
 * velocity v_reg (m/s or rad/s). Local DOFs [q_node, q_node2]. */
#include <math.h>
#include <stdio.h>

#include "geardyn/law_type.h"

enum { FR_FORCE, FR_VREG, FR_NPARAMS };

static const gd_law_param fr_params[FR_NPARAMS] = {
    {"force", GD_QTY_DIMLESS, NAN, GD_LAW_NONNEG,
     "Coulomb force level mu N (N, or N m for a rotation), SI number"},
    {"velocity", GD_QTY_DIMLESS, NAN, GD_LAW_POSITIVE,
     "regularisation velocity v_reg (m/s or rad/s), small against the slip velocities"},
};

static void fr_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
    u[1] = w[1] = -1.0;
}

static double fr_law(const gd_law *law, double s, double *dFds)
{
    double th = tanh(s / law->value[FR_VREG]);
    if (dFds) *dFds = law->value[FR_FORCE] / law->value[FR_VREG] * (1.0 - th * th);
    return law->value[FR_FORCE] * th;
}

static void fr_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double ds, F = fr_law(law, x->v[0] - x->v[1], &ds);
    f[0] -= F;
    f[1] += F;
    if (jq) jq[0] = 0.0;
    if (jv) jv[0] = -ds;
}

static const gd_law_record fr_records[] = {{"force", "N"}, {"slip", "m/s"}};

static double fr_record(const gd_law *law, int k, const gd_law_point *x)
{
    double s = x->v[0] - x->v[1];
    return k == 0 ? fr_law(law, s, NULL) : s;
}

static void fr_linearize(const gd_law *law, const gd_law_point *x, double *K, double *C)
{
    (void)K;
    double ds;
    fr_law(law, x->v[0] - x->v[1], &ds);
    const double s[4] = {1.0, -1.0, -1.0, 1.0};
    for (int k = 0; k < 4; k++)
        C[k] += ds * s[k];
}

const gd_law_type gd_law_friction = {
    .name = "friction",
    .summary = "Coulomb friction F_c tanh(slip / v_reg) between two DOFs",
    .flags = GD_LAW_SMOOTH,
    .params = fr_params,
    .nparams = FR_NPARAMS,
    .two_nodes = 1,
    .nterms = 1,
    .term = fr_term,
    .force = fr_force,
    .records = fr_records,
    .nrecords = 2,
    .record = fr_record,
    .linearize = fr_linearize,
};
