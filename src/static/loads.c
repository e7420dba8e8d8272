/* The mean loads of the static analysis (docs/static.md):
 * - each excitation load at its mean: a harmonic (in time or in angle) averages to its
 *   `mean`, a table in angle to mean + its average over one period;
 * - the input torque of the options, about the input node's shaft in its sense of
 *   rotation (the sign of the shaft's speed ratio);
 * - gravity: f = M t with t the rigid translation g on the x, y, z DOFs. For the
 *   consistent shaft mass this is the consistent load of the distributed weight (the
 *   rotary inertia part gives nothing: a translation does not rotate the sections), and
 *   the weight m g of every disk at its node.
 * - the planets' pin position errors of planetary sets (planetary_sharing.c).
 * Unbalances and cam torques have zero mean over a revolution (a rotating force; the
 * cam torque m s' s'' W^2 = d/dtheta (m s'^2 W^2 / 2) of [Benini2004] Eq. 10 is a derivative of a
 * periodic function), so they add nothing. */
#include <math.h>
#include <string.h>

#include "static/static_impl.h"
#include "system/system_impl.h"

int gd_st_input_node(const gd_model *m, const gd_static_options *opt)
{
    if (opt->input_node >= 0) return opt->input_node;
    int s = m->reference_shaft >= 0 && m->reference_shaft < m->nshafts ? m->reference_shaft : 0;
    return m->nshafts > 0 ? m->shafts[s].first_node : -1;
}

gd_status gd_st_loads(const gd_system *sys, const gd_static_options *opt, double *f, gd_error *err)
{
    const gd_model *m = sys->model;
    /* the mean excitation loads and gravity: the static load the laws' equilibrium of
       the linear analyses also uses (src/system/law_state.c) */
    gd_system_mean_loads(sys, opt->loads, opt->gravity, f);
    gd_st_planetary_loads(sys, f); /* pin position errors (docs/planetary.md) */
    if (opt->input_torque != 0) {
        int node = gd_st_input_node(m, opt);
        int i = node >= 0 ? gd_system_dof(sys, node, GD_RZ) : -1;
        if (i < 0)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "input_node",
                                "apply the input torque at a node whose torsion (rz) is active",
                                "the input torque's node has no active torsion DOF");
        double ratio = m->shafts[m->nodes[node].shaft].speed_ratio;
        f[i] += (ratio < 0 ? -1.0 : 1.0) * opt->input_torque;
    }
    return GD_OK;
}
