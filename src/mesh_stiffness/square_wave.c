/* Rectangular-wave mesh stiffness: every tooth pair in contact has the same stiffness
 * per unit face width (the ISO 6336-1 single stiffness c'), so a spur mesh switches
 * between n and n+1 times c' b with the duty set by the contact ratio, and a helical
 * mesh follows the total length of the contact lines. */
#include "mesh_stiffness/mesh_stiffness_impl.h"

double gd_ms_square_law_eval(double s, const void *ctx)
{
    (void)s;
    return *(const double *)ctx;
}
