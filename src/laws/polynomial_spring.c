/* Polynomial spring with viscous damping between two DOFs of one direction, or from one
 * DOF to ground (the Duffing oscillator's spring: NLvib's example 01, Krack & Gross,
 * Harmonic Balance for Nonlinear Vibration Problems, 2019, Sec. 1.2):
 *
 *   F = k1 d + k2 d^2 + k3 d^3 + c d',   d = q_node - q_node2 (q_node2 = 0: ground)
 *
 * acting as -F on the node and +F on node2. SI values: k1 in N/m (N m/rad for a
 * rotation), k2 in N/m^2, k3 in N/m^3, c in N s/m. Local DOFs [q_node, q_node2]. */
#include <math.h>

#include "geardyn/law_type.h"

enum { PS_K1, PS_K2, PS_K3, PS_C, PS_NPARAMS };

static const gd_law_param ps_params[PS_NPARAMS] = {
    {"k1", GD_QTY_DIMLESS, 0.0, GD_LAW_ANY, "linear coefficient, N/m (N m/rad), SI number"},
    {"k2", GD_QTY_DIMLESS, 0.0, GD_LAW_ANY, "quadratic coefficient, N/m^2, SI number"},
    {"k3", GD_QTY_DIMLESS, 0.0, GD_LAW_ANY, "cubic coefficient, N/m^3, SI number"},
    {"damping", GD_QTY_DIMLESS, 0.0, GD_LAW_ANY, "viscous coefficient, N s/m, SI number"},
};

static void ps_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
    u[1] = w[1] = -1.0;
}

static double ps_law(const gd_law *law, double d, double dd, double *dFd)
{
    const double *c = law->value;
    if (dFd) *dFd = c[PS_K1] + d * (2.0 * c[PS_K2] + 3.0 * c[PS_K3] * d);
    return d * (c[PS_K1] + d * (c[PS_K2] + c[PS_K3] * d)) + c[PS_C] * dd;
}

static void ps_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double d = x->q[0] - x->q[1], dd = x->v[0] - x->v[1], kt;
    double F = ps_law(law, d, dd, &kt);
    f[0] -= F;
    f[1] += F;
    if (jq) jq[0] = -kt;
    if (jv) jv[0] = -law->value[PS_C];
}

static const gd_law_record ps_records[] = {{"force", "N"}, {"deflection", "m"}};

static double ps_record(const gd_law *law, int k, const gd_law_point *x)
{
    double d = x->q[0] - x->q[1];
    return k == 0 ? ps_law(law, d, x->v[0] - x->v[1], NULL) : d;
}

static void ps_linearize(const gd_law *law, const gd_law_point *x, double *K, double *C)
{
    double kt;
    ps_law(law, x->q[0] - x->q[1], 0.0, &kt);
    const double s[4] = {1.0, -1.0, -1.0, 1.0};
    for (int k = 0; k < 4; k++) {
        K[k] += kt * s[k];
        C[k] += law->value[PS_C] * s[k];
    }
}

const gd_law_type gd_law_polynomial_spring = {
    .name = "polynomial_spring",
    .summary = "spring k1 d + k2 d^2 + k3 d^3 with damping c d' (cubic: Duffing)",
    .flags = GD_LAW_SMOOTH | GD_LAW_SUPPORT,
    .params = ps_params,
    .nparams = PS_NPARAMS,
    .two_nodes = 1,
    .nterms = 1,
    .term = ps_term,
    .force = ps_force,
    .records = ps_records,
    .nrecords = 2,
    .record = ps_record,
    .linearize = ps_linearize,
};
