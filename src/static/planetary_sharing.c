/* Planet load sharing in the static analysis (docs/planetary.md): the loads of the planets'
 * pin position errors, and each planet's mesh and bearing forces from the static state.
 * A pin displaced by e along the carrier's tangent (or rho radially) moves the bearing's
 * unloaded position: its energy k_p (t . q - e)^2 / 2 (k_p (r . q - rho)^2 / 2) ([LinParker1999]
 * Eq. 4 with an offset) gives the load k_p e t (k_p rho r) on K q = f. The load-sharing factor is
 * the mesh load factor K_gamma of ISO 6336-1 / AGMA 6123: N max F_n / sum F_n over the sun-planet
 * mesh forces F_n, signed in the sense of their sum (a planet whose force changes sign would lose
 * contact: the linear model does not follow that). */
#include <math.h>
#include <string.h>

#include "elements/elements_impl.h"
#include "static/static_impl.h"

/* The system's DOF of local DOF a of instance nodes (carrier or member, planet). */
static int local_dof(const gd_system *sys, int node1, int node2, int a)
{
    return gd_system_dof(sys, a < 6 ? node1 : node2, (gd_dof)(a % 6));
}

void gd_st_planetary_loads(const gd_system *sys, double *f)
{
    const gd_model *m = sys->model;
    for (int k = 0; k < m->nplanetary; k++) {
        const gd_planetary *g = &m->planetary[k];
        if (!g->pin_error && !g->pin_error_radial) continue;
        for (int n = 0; n < g->nplanets; n++) {
            double r[12], t[12];
            double et = g->pin_error ? g->pin_error[n] : 0,
                   er = g->pin_error_radial ? g->pin_error_radial[n] : 0;
            gd_planetary_bearing_vectors(g, n, r, t);
            for (int a = 0; a < 12; a++) {
                int i =
                    local_dof(sys, g->member[GD_PLANETARY_CARRIER].node, g->first_planet + n, a);
                if (i >= 0) f[i] += g->bearing_stiffness * (et * t[a] + er * r[a]);
            }
        }
    }
}

static double project(const gd_system *sys, const double *q, int node1, int node2,
                      const double v[12])
{
    double d = 0;
    for (int a = 0; a < 12; a++) {
        int i = local_dof(sys, node1, node2, a);
        if (i >= 0) d += v[a] * q[i];
    }
    return d;
}

gd_status gd_static_planetary(const gd_system *sys, const gd_static_result *res, int set,
                              gd_static_planetary_loads *out, gd_error *err)
{
    const gd_model *m = sys->model;
    memset(out, 0, sizeof *out);
    if (set < 0 || set >= m->nplanetary)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "set", "name a set of the model",
                            "no planetary set %d", set);
    const gd_planetary *g = &m->planetary[set];
    out->nplanets = g->nplanets;
    double sum = 0, mx = 0;
    for (int n = 0; n < g->nplanets; n++) {
        int p = g->first_planet + n;
        double a[12], r[12], t[12];
        gd_planetary_mesh_vector(g, 0, n, a);
        out->sun_force[n] =
            g->mesh_stiffness[0] * project(sys, res->q, g->member[GD_PLANETARY_SUN].node, p, a);
        gd_planetary_mesh_vector(g, 1, n, a);
        out->ring_force[n] =
            g->mesh_stiffness[1] * project(sys, res->q, g->member[GD_PLANETARY_RING].node, p, a);
        gd_planetary_bearing_vectors(g, n, r, t);
        int c = g->member[GD_PLANETARY_CARRIER].node;
        double e = g->pin_error ? g->pin_error[n] : 0,
               er = g->pin_error_radial ? g->pin_error_radial[n] : 0;
        out->bearing_force[n] = g->bearing_stiffness * hypot(project(sys, res->q, c, p, r) - er,
                                                             project(sys, res->q, c, p, t) - e);
        sum += out->sun_force[n];
    }
    /* signed, in the sense of the total (a negative share: the teeth would separate) */
    double sg = sum < 0 ? -1 : 1;
    for (int n = 0; n < g->nplanets; n++)
        mx = fmax(mx, sg * out->sun_force[n]);
    out->load_sharing = sum != 0 ? g->nplanets * mx / (sg * sum) : NAN;
    return GD_OK;
}
