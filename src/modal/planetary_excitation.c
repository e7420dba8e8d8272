/* The mesh excitation of a planetary set at one harmonic of the mesh frequency, with each
 * planet's mesh phase ([Parker2000], [ParkerLin2004]): a static transmission error
 * e_n = E cos(l w_m t - 2 pi l gamma_n) on mesh n, gamma_n the planet's phase in mesh
 * periods (gd_planetary_mesh_phase: frac(Z_s psi_n / 2 pi) for the sun meshes when the sun
 * turns counterclockwise relative to the carrier, the same for the ring meshes plus the
 * sun-ring phase), loads the system with k e_n a_n, a_n the mesh's deformation vector:
 * complex amplitude F = sum_n k a_n exp(-2 pi i l gamma_n) per unit E. The same phases the
 * meshes' laws take in transient and periodic runs; docs/planetary.md. */
#include <math.h>
#include <string.h>

#include "elements/elements_impl.h"
#include "geardyn/modal.h"

gd_status gd_planetary_mesh_excitation(const gd_system *sys, int set, int harmonic, int ring,
                                       double *re, double *im, gd_error *err)
{
    const gd_model *m = sys->model;
    if (set < 0 || set >= m->nplanetary)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "set", "name a set of the model",
                            "no planetary set %d", set);
    const gd_planetary *g = &m->planetary[set];
    int z = g->teeth[ring ? 1 : 0];
    if (z <= 0)
        return gd_error_set(err, GD_EINPUT, m->file, g->loc.line, g->loc.column, "teeth",
                            "give the set's teeth (`teeth: {sun, ring, planet}`)",
                            "the mesh phases of set '%s' need its teeth", g->name);
    memset(re, 0, (size_t)sys->ndof * sizeof *re);
    memset(im, 0, (size_t)sys->ndof * sizeof *im);
    int member = ring ? GD_PLANETARY_RING : GD_PLANETARY_SUN;
    double rel = m->shafts[m->nodes[g->member[GD_PLANETARY_SUN].node].shaft].speed_ratio -
                 m->shafts[m->nodes[g->member[GD_PLANETARY_CARRIER].node].shaft].speed_ratio;
    for (int n = 0; n < g->nplanets; n++) {
        double a[12],
            ph = -2 * M_PI * harmonic * gd_planetary_mesh_phase(g, ring, n, rel < 0 ? -1 : 1);
        gd_planetary_mesh_vector(g, ring, n, a);
        for (int k = 0; k < 12; k++) {
            int i = gd_system_dof(sys, k < 6 ? g->member[member].node : g->first_planet + n,
                                  (gd_dof)(k % 6));
            if (i < 0) continue;
            re[i] += g->mesh_stiffness[ring ? 1 : 0] * a[k] * cos(ph);
            im[i] += g->mesh_stiffness[ring ? 1 : 0] * a[k] * sin(ph);
        }
    }
    return GD_OK;
}
