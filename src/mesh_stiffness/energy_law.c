/* Tooth-pair stiffness per unit face width by the potential energy method ([JMSTHelical]
 * Eq. 6): Hertz, and for each tooth bending, shear, axial compression and fillet
 * foundation, all in series. A contact at position s on the line of action (from N1)
 * has roll angle s/rb1 on the driver and (N1N2 - s)/rb2 on the driven gear ((N1N2 + s)/rb2
 * on the ring of an internal pair, whose tooth is ring_tooth.c's). Helical
 * slices use the transverse profile ([JMSTHelical] Sec. 2.2). */
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

double gd_ms_energy_pair_stiffness(const gd_ms_energy_law *e, double s)
{
    double c = e->hertz;
    /* an internal pair's ring rolls on the same side of the contact as the planet */
    double roll[2] = {s, e->tooth[1].internal ? s + e->line_of_action : e->line_of_action - s};
    for (int i = 0; i < 2; i++) {
        const gd_ms_tooth *t = &e->tooth[i];
        double tc = roll[i] / t->rb;
        if (t->internal) {
            double b[3];
            gd_ms_radial_beam_terms(t, tc, e->rtol, b);
            c += b[0] + b[1] + b[2] + gd_ms_ring_fillet_compliance(t, tc);
        } else {
            c += gd_ms_tooth_beam_compliance(t, tc, e->rtol, NULL) + gd_ms_fillet_compliance(t, tc);
        }
    }
    return 1.0 / c;
}

static double direct(double s, void *ctx)
{
    return gd_ms_energy_pair_stiffness(ctx, s);
}

int gd_ms_energy_law_init(gd_ms_energy_law *e, const gd_gear_pair_geometry *g,
                          const gd_gear_pair_derived *d, double rtol)
{
    for (int i = 0; i < 2; i++) {
        gd_ms_tooth *t = &e->tooth[i];
        t->rb = d->base_radius[i];
        t->alpha2 = d->half_angle_base[i];
        t->rf = d->root_radius[i];
        t->rbore = d->bore_radius[i];
        t->E = g->gear[i].E;
        t->nu = g->gear[i].poisson;
        t->internal = i == 1 && d->internal;
    }
    e->line_of_action = d->line_of_action;
    e->hertz =
        gd_ms_hertz_compliance(g->gear[0].E, g->gear[0].poisson, g->gear[1].E, g->gear[1].poisson);
    e->rtol = rtol;
    /* the table need not be finer than the integrals, nor than 1e-9 */
    double ttol = rtol > 1e-9 ? rtol : 1e-9;
    return gd_ms_cheb_build(&e->table, direct, e, d->contact_start, d->contact_end, 9, 257, ttol);
}

double gd_ms_energy_law_eval(double s, const void *ctx)
{
    const gd_ms_energy_law *e = ctx;
    return gd_ms_cheb_eval(&e->table, s);
}

void gd_ms_energy_law_free(gd_ms_energy_law *e)
{
    gd_ms_cheb_free(&e->table);
}
