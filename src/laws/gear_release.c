/* The old gear released at a shift (docs/rattle.md, "Shifting"): the engaged gear's lock
 * is a torsional spring of the system (k, c between the idler and its synchroniser's
 * node, assembled in K and C); from the shift time t_s on this law adds its opposite,
 *
 *   T = +k (q_idler - q_node) + c (q'_idler - q'_node)   for t >= t_s, else 0,
 *
 * so that the idler turns free. Exact: the spring acts on the same perturbation
 * coordinates q the law sees. One switch, t - t_s. Local DOFs [rz of the idler, rz of the
 * synchroniser's node]. */
#include <math.h>
#include <stdio.h>

#include "geardyn/law_type.h"

enum { GR_TIME, GR_K, GR_C, GR_NPARAMS };
enum { GR_LOCKED, GR_RELEASED };

static const gd_law_param gr_params[GR_NPARAMS] = {
    {"time", GD_QTY_TIME, NAN, GD_LAW_NONNEG, "the shift's start t_s, s"},
    {"stiffness", GD_QTY_ROT_STIFFNESS, NAN, GD_LAW_NONNEG, "the lock's stiffness, N m/rad"},
    {"damping", GD_QTY_ROT_DAMPING, 0.0, GD_LAW_NONNEG, "the lock's damping, N m s/rad"},
};

static const int gr_dirs[1] = {5}; /* rz */

static void gr_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
    u[1] = w[1] = -1.0;
}

static double gr_torque(const gd_law *law, const gd_law_point *x)
{
    if (law->mode != GR_RELEASED) return 0;
    return law->value[GR_K] * (x->q[0] - x->q[1]) + law->value[GR_C] * (x->v[0] - x->v[1]);
}

static void gr_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double T = gr_torque(law, x);
    f[0] += T;
    f[1] -= T;
    int on = law->mode == GR_RELEASED;
    if (jq) jq[0] = on ? law->value[GR_K] : 0;
    if (jv) jv[0] = on ? law->value[GR_C] : 0;
}

static const gd_law_record gr_records[] = {{"torque", "N m"}};

static double gr_record(const gd_law *law, int k, const gd_law_point *x)
{
    (void)k;
    return gr_torque(law, x);
}

static void gr_switches(const gd_law *law, const gd_law_point *x, double *g)
{
    g[0] = x->t - law->value[GR_TIME];
}

static int gr_mode_at(const gd_law *law, const gd_law_point *x)
{
    return x->t < law->value[GR_TIME] ? GR_LOCKED : GR_RELEASED;
}

static int gr_mode_after(const gd_law *law, int mode, const int *dir)
{
    (void)law;
    return dir[0] > 0 ? GR_RELEASED : mode;
}

static int gr_switch_of(const gd_law *law, int from, int to)
{
    (void)law;
    (void)from;
    (void)to;
    return 0;
}

const gd_law_type gd_law_gear_release = {
    .name = "gear_release",
    .summary = "a shift releases the engaged gear: cancels its lock spring from t_s on",
    .flags = 0,
    .params = gr_params,
    .nparams = GR_NPARAMS,
    .dirs = gr_dirs,
    .ndirs = 1,
    .two_nodes = 1,
    .nterms = 1,
    .term = gr_term,
    .force = gr_force,
    .records = gr_records,
    .nrecords = 1,
    .record = gr_record,
    .nswitches = 1,
    .switches = gr_switches,
    .mode_at = gr_mode_at,
    .mode_after = gr_mode_after,
    .switch_of = gr_switch_of,
    .hold_mode = GR_LOCKED,
};
