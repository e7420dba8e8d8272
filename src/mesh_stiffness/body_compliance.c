/* Gear-body (rim/web) torsional compliance in series with the teeth ([Benini2004] Eq. 6):
 * 1/K* = 1/K + 1/K_T1 + 1/K_T2, each body's torsional stiffness K_T (N m/rad) seen at
 * the contact as K_T / (rb cos(beta_b))^2 along the normal line of action. Without a
 * given K_T, a web of thickness t between radii r_i and r_o in in-plane shear gives
 * K_T = 4 pi G t / (1/r_i^2 - 1/r_o^2) (shear stress T / (2 pi r^2 t)); a body with
 * neither is rigid. */
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

double gd_ms_body_torsional_stiffness(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d,
                                      int i)
{
    const gd_gear_geometry *w = &g->gear[i];
    if (w->body_torsional_stiffness > 0) return w->body_torsional_stiffness;
    if (!(w->web_thickness > 0)) return 0;
    double ri = w->web_inner_radius > 0 ? w->web_inner_radius : d->bore_radius[i];
    double ro =
        w->web_outer_radius > 0 ? w->web_outer_radius : d->root_radius[i] - 2 * g->normal_module;
    if (!(ro > ri)) return 0;
    double G = w->E / (2 * (1 + w->poisson));
    return 4 * GD_MS_PI * G * w->web_thickness / (1 / (ri * ri) - 1 / (ro * ro));
}

double gd_ms_body_stiffness(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d)
{
    double c = 0, cb = cos(d->base_helix_angle);
    for (int i = 0; i < 2; i++) {
        double kt = gd_ms_body_torsional_stiffness(g, d, i);
        if (kt > 0) {
            double r = d->base_radius[i] * cb;
            c += r * r / kt;
        }
    }
    return c > 0 ? 1 / c : 0;
}
