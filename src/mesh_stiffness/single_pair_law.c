/* Single-tooth-pair stiffness law of Cai & Hayashi (J. Mech. Des. 116, 1994), used in
 * [Benini2004] Eq. 5: over the contact arc of length eps p, with x the position on it,
 *   K_s(x) = K_m [ -1.8 x^2 / (eps p)^2 + 1.8 x / (eps p) + 0.55 ],
 * 0.55 K_m where a pair enters and leaves, K_m at mid-arc. K_m is the ISO 6336-1
 * single stiffness c' ([Benini2004]: "K_m is evaluated according to ISO"). Pairs in contact
 * add in parallel; helical pairs go through the same slicing as the energy method. */
#include "mesh_stiffness/mesh_stiffness_impl.h"

double gd_ms_cai_factor(double xi)
{
    return -1.8 * xi * xi + 1.8 * xi + 0.55;
}

double gd_ms_cai_law_eval(double s, const void *ctx)
{
    const gd_ms_cai_law *c = ctx;
    return c->k_single * gd_ms_cai_factor((s - c->s_A) / c->g_alpha);
}
