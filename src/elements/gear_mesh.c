/* Gear mesh element: the tooth contact deformation d = a . q along the contact
 * normal, so the mesh adds k a a^T to K and c a a^T to C (DESIGN.md; Kahraman 1994,
 * and the 12-DOF helical element of 002 Eqs. 14-16).
 *
 * Geometry (all shafts parallel to z): e_c points from the driver's centre to the
 * driven gear's along the line of centres (angle gamma from +x), e_p = z x e_c. For a
 * driver turning with sense s (+1: about +z) the drive-flank line of action in the
 * transverse plane is n = s R(-s alpha) e_p; it touches the driver's base circle at
 * rho1 = s rb1 R(-90deg) n and the driven gear's at rho2 = -s rb2 R(-90deg) n. The
 * helical contact normal is N = cos(bb) n - s h sin(bb) z, h = +1 for a right-hand
 * driver, bb the base helix angle. The contact point displaces u + theta x rho, so
 *   a_driver = [N, rho1 x N],  a_driven = -[N, rho2 x N].
 * Checks (tests): rotation in the gear ratio and common translation give d = 0; at
 * bb = 0 the tilt terms vanish (spur); the rz entries are s rb1 cos(bb), s rb2 cos(bb). */
#include <math.h>
#include <string.h>

#include "elements/elements_impl.h"

void gd_mesh_vector_local(const gd_mesh *g, double a[12])
{
    double s = g->driver_sense >= 0 ? 1.0 : -1.0;
    double gam = g->line_of_centres, al = g->pressure_angle, bb = g->base_helix_angle;
    double ep[2] = {-sin(gam), cos(gam)};
    double th = -s * al, c = cos(th), sn = sin(th);
    double n[2] = {s * (ep[0] * c - ep[1] * sn), s * (ep[0] * sn + ep[1] * c)};
    double rn[2] = {n[1], -n[0]}; /* R(-90deg) n */
    double N[3] = {cos(bb) * n[0], cos(bb) * n[1], -s * g->hand * sin(bb)};
    double rho[2][3] = {{s * g->base_radius[0] * rn[0], s * g->base_radius[0] * rn[1], 0},
                        {-s * g->base_radius[1] * rn[0], -s * g->base_radius[1] * rn[1], 0}};
    for (int k = 0; k < 2; k++) {
        const double *r = rho[k];
        double sign = k == 0 ? 1.0 : -1.0;
        double *ak = a + 6 * k;
        ak[GD_X] = sign * N[0];
        ak[GD_Y] = sign * N[1];
        ak[GD_Z] = sign * N[2];
        ak[GD_RX] = sign * (r[1] * N[2] - r[2] * N[1]);
        ak[GD_RY] = sign * (r[2] * N[0] - r[0] * N[2]);
        ak[GD_RZ] = sign * (r[0] * N[1] - r[1] * N[0]);
    }
    unsigned keep = gd_coupling_dof_mask(g->coupling);
    if (g->coupling == GD_COUPLING_LATERAL_TORSIONAL)
        keep = GD_DOF_BIT(GD_X) | GD_DOF_BIT(GD_Y) | GD_DOF_BIT(GD_RZ);
    for (int k = 0; k < 12; k++)
        if (!(keep & GD_DOF_BIT(k % 6))) a[k] = 0.0;
}
