/* The tooth-pair stiffness law of a method, ready for slicing: the energy method's
 * tabulated law, the Cai-Hayashi law or the square wave (both from the ISO single
 * stiffness c'); iso6336 slices with the square law (its constant replaces the sum).
 * Shared by the TVMS and the loaded contact analysis. */
#include "mesh_stiffness/mesh_stiffness_impl.h"

int gd_ms_pair_law_init(gd_ms_pair_law *p, const gd_gear_pair_geometry *g,
                        const gd_gear_pair_derived *d, gd_tvms_method method, double rtol)
{
    gd_ms_iso6336(g, d, &p->iso);
    p->cai = (gd_ms_cai_law){d->contact_start, d->contact_length, p->iso.c_single};
    p->have_energy = 0;
    p->fn = gd_ms_square_law_eval;
    p->ctx = &p->iso.c_single;
    if (method == GD_TVMS_ENERGY) {
        if (gd_ms_energy_law_init(&p->energy, g, d, rtol)) return -1;
        p->have_energy = 1;
        p->fn = gd_ms_energy_law_eval;
        p->ctx = &p->energy;
    } else if (method == GD_TVMS_SINGLE_PAIR) {
        p->fn = gd_ms_cai_law_eval;
        p->ctx = &p->cai;
    }
    return 0;
}

void gd_ms_pair_law_free(gd_ms_pair_law *p)
{
    if (p->have_energy) gd_ms_energy_law_free(&p->energy);
    p->have_energy = 0;
}
