/* The mean loads of the static analysis (docs/static.md):
 * - each excitation load at its mean: a harmonic (in time or in angle) averages to its
 *   `mean`, a table in angle to mean + its average over one period;
 * - the input torque of the options, about the input node's shaft in its sense of
 *   rotation (the sign of the shaft's speed ratio);
 * - gravity: f = M t with t the rigid translation g on the x, y, z DOFs. For the
 *   consistent shaft mass this is the consistent load of the distributed weight (the
 *   rotary inertia part gives nothing: a translation does not rotate the sections), and
 *   the weight m g of every disk at its node.
 * Unbalances and cam torques have zero mean over a revolution (a rotating force; the
 * cam torque m s' s'' W^2 = d/dtheta (m s'^2 W^2 / 2) of 003 Eq. 10 is a derivative of a
 * periodic function), so they add nothing. */
#include <math.h>
#include <string.h>

#include "static/static_impl.h"

/* Average of a periodic table over its period, by the midpoint rule on 4096 points
 * (exact to ~1e-7 relative for the linear and spline tables of a load). */
static double table_mean(const gd_table *t)
{
    if (!t || t->n < 1) return 0;
    double x0 = t->x[0], per = t->period > 0 ? t->period : t->x[t->n - 1] - t->x[0];
    if (!(per > 0)) return t->y[0];
    const int n = 4096;
    double s = 0;
    for (int i = 0; i < n; i++)
        s += gd_table_eval(t, x0 + per * (i + 0.5) / n, NULL, NULL);
    return s / n;
}

static double load_mean(const gd_load_law *law)
{
    double v = law->mean;
    if (law->kind == GD_LOAD_TABLE_ANGLE) v += table_mean(law->table);
    return v;
}

int gd_st_input_node(const gd_model *m, const gd_static_options *opt)
{
    if (opt->input_node >= 0) return opt->input_node;
    int s = m->reference_shaft >= 0 && m->reference_shaft < m->nshafts ? m->reference_shaft : 0;
    return m->nshafts > 0 ? m->shafts[s].first_node : -1;
}

gd_status gd_st_loads(const gd_system *sys, const gd_static_options *opt, double *f, gd_error *err)
{
    const gd_model *m = sys->model;
    const int n = sys->ndof;
    memset(f, 0, (size_t)n * sizeof *f);
    if (opt->loads)
        for (int k = 0; k < m->nexcitations; k++) {
            const gd_excitation *e = &m->excitations[k];
            int i = gd_system_dof(sys, e->node, e->dof);
            if (i >= 0) f[i] += load_mean(&e->law);
        }
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
    const double *g = m->gravity;
    if (opt->gravity && (g[0] != 0 || g[1] != 0 || g[2] != 0)) {
        /* f += M t, column by column over the translation DOFs */
        for (int j = 0; j < n; j++) {
            gd_dof d = sys->dof_type[j];
            if (d > GD_Z || g[d] == 0) continue;
            for (int p = sys->M.colptr[j]; p < sys->M.colptr[j + 1]; p++)
                f[sys->M.rowind[p]] += sys->M.values[p] * g[d];
        }
    }
    return GD_OK;
}
