/* A mesh's stiffness table at its mean load (stiffness: {from: contact_analysis}): the
 * TVMS result with its k(theta) replaced by the contact analysis's tangent stiffness
 * k_L(theta), and the transmission error the dynamics subtract from the mesh
 * deformation. The mesh force of the dynamics is k(theta) (d - e(theta)); linearised
 * about the loaded contact at the normal load F0 it is F0 + k_L (d - delta(theta)), so
 *   e(theta) = delta(theta) - F0 / k_L(theta),
 * which makes the static deflection under F0 the loaded transmission error delta and
 * vanishes for unmodified, aligned teeth (delta = F0 / k). */
#include <math.h>
#include <stdlib.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

gd_status gd_ms_loaded_tvms(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                            gd_tvms_result **tvms, double **ste, gd_error *err)
{
    *tvms = NULL;
    *ste = NULL;
    gd_ltca_result *l = NULL;
    gd_tvms_result *r = NULL;
    gd_status st = gd_ltca_compute(g, opt, &l, err);
    if (st || (st = gd_tvms_compute(g, opt, &r, err))) {
        gd_ltca_free(l);
        return st;
    }
    double *e = malloc(l->points * sizeof *e);
    if (!e || r->n != l->n || r->max_pairs != l->max_pairs) {
        free(e);
        gd_ltca_free(l);
        gd_tvms_free(r);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    const size_t P = (size_t)r->max_pairs;
    for (size_t i = 0; i < r->n; i++) {
        r->stiffness[i] = l->stiffness[i];
        r->pairs_in_contact[i] = l->pairs_in_contact[i];
        for (size_t j = 0; j < P; j++)
            r->load_share[i * P + j] = l->pair_load[i * P + j] / l->force;
    }
    for (size_t i = 0; i < r->points; i++)
        e[i] = l->ste[i] - l->force / l->stiffness[i];
    gd_ms_tvms_summarise(r);
    gd_ltca_free(l);
    *tvms = r;
    *ste = e;
    return GD_OK;
}
