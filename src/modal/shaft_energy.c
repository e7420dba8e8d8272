/* Modal strain energy per shaft and motion type ([JMSTHelical] Tables 4-7): each component's
 * energy split by motion type, grouped with its shaft (gd_system_component_shafts: a
 * bearing, spring or mesh between two shafts half to each), as fractions of the mode's
 * total. */
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

gd_status gd_modal_energy_by_shaft(const gd_system *sys, const gd_modal_result *r, int mode,
                                   double *table, gd_error *err)
{
    int ns = sys->model->nshafts, nc = sys->ncomponents;
    if (mode < 0 || mode >= r->nmodes || r->ndof != sys->ndof)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "mode", "give a mode of this result",
                            "mode %d is not one of the %d modes", mode, r->nmodes);
    memset(table, 0, (size_t)ns * GD_NMOTIONS * sizeof *table);
    double *ct = malloc(((size_t)nc * GD_NMOTIONS + 1) * sizeof *ct);
    if (!ct) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    const double *re = r->shape_re + (size_t)mode * r->ndof,
                 *im = r->shape_im + (size_t)mode * r->ndof;
    /* the laws about the static state at r's speed, as the modes (gd_modal_energies_laws) */
    double total = gd_system_strain_energy_table(sys, r->speed, re, im, ct);
    if (total != 0 && !r->modes[mode].rigid_body)
        for (int c = 0; c < nc; c++) {
            int sh[2];
            double w[2];
            int n = gd_system_component_shafts(sys, c, sh, w);
            for (int j = 0; j < n; j++)
                for (int k = 0; k < GD_NMOTIONS; k++)
                    table[(size_t)sh[j] * GD_NMOTIONS + k] +=
                        w[j] * ct[(size_t)c * GD_NMOTIONS + k] / total + 0.0;
        }
    free(ct);
    return GD_OK;
}
