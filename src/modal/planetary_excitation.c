/* The mesh excitation of a planetary set at one harmonic of the mesh frequency, with each
 * planet's mesh phase ([Parker2000]): a static transmission error e_n = E cos(l w_m t -
 * l Z_s psi_n) on sun-planet mesh n (planet n meets its tooth l Z_s psi_n / 2 pi of a mesh
 * period after planet 1, psi_n in the sun's teeth) loads the system with k_sp e_n a_n, a_n
 * the mesh's deformation vector: complex amplitude F = sum_n k_sp a_n exp(-i l Z_s psi_n)
 * per unit E. The ring-planet meshes' phases l Z_r psi_n (plus the sun-ring phase) follow
 * the same way; docs/planetary.md. */
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
    for (int n = 0; n < g->nplanets; n++) {
        double a[12], ph = -harmonic * z * g->planet_angle[n];
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
