/* Backlash mesh force with contact on the drive and the coast flank, [Benini2004] Eqs. 2-4
 * (as cleaned up in DESIGN.md), and mesh damping laws. */
#include "geardyn/laws.h"

gd_contact gd_backlash_state(double d, double b)
{
    if (d > b) return GD_CONTACT_DRIVE;
    if (d < -b) return GD_CONTACT_COAST;
    return GD_CONTACT_SEPARATED;
}

/* One-sided contact (coast_stiffness_ratio 0, k_coast = 0): there is no coast flank, so
 * beyond the gap on that side the teeth stay separated (only c_free acts, not the
 * contact damping). */
static gd_contact flank(const gd_backlash_params *p, gd_contact state)
{
    return state == GD_CONTACT_COAST && p->k_coast == 0.0 ? GD_CONTACT_SEPARATED : state;
}

double gd_backlash_force(const gd_backlash_params *p, gd_contact state, double d, double dd)
{
    switch (flank(p, state)) {
    case GD_CONTACT_DRIVE:
        return p->k_drive * (d - p->b) + p->c_drive * dd;
    case GD_CONTACT_COAST:
        return p->k_coast * (d + p->b) + p->c_coast * dd;
    default:
        return p->c_free * dd;
    }
}

void gd_backlash_force_grad(const gd_backlash_params *p, gd_contact state, double d, double dd,
                            double g[4])
{
    switch (flank(p, state)) {
    case GD_CONTACT_DRIVE:
        g[0] = p->k_drive, g[1] = p->c_drive, g[2] = d - p->b, g[3] = dd;
        break;
    case GD_CONTACT_COAST:
        g[0] = p->k_coast, g[1] = p->c_coast, g[2] = d + p->b, g[3] = dd;
        break;
    default:
        g[0] = 0.0, g[1] = p->c_free, g[2] = 0.0, g[3] = dd;
        break;
    }
}

double gd_backlash_force_auto(const gd_backlash_params *p, double d, double dd, gd_contact *state)
{
    gd_contact s = gd_backlash_state(d, p->b);
    if (state) *state = s;
    return gd_backlash_force(p, s, d, dd);
}

double gd_mesh_damping(double c_const, double c_per_k, double k)
{
    return c_const + c_per_k * k;
}
