/* Rigid disk or gear body at a node: mass, diametral and polar inertia, and the
 * gyroscopic moment of its spin: Id rx'' + Ip W ry' = Mx, Id ry'' - Ip W rx' = My. */
#include <string.h>

#include "elements/elements_impl.h"

void gd_disk_matrices(const gd_disk *d, double M[36], double G[36])
{
    memset(M, 0, 36 * sizeof *M);
    memset(G, 0, 36 * sizeof *G);
    M[GD_X * 6 + GD_X] = M[GD_Y * 6 + GD_Y] = M[GD_Z * 6 + GD_Z] = d->mass;
    M[GD_RX * 6 + GD_RX] = M[GD_RY * 6 + GD_RY] = d->diametral_inertia;
    M[GD_RZ * 6 + GD_RZ] = d->polar_inertia;
    G[GD_RX * 6 + GD_RY] = d->polar_inertia;
    G[GD_RY * 6 + GD_RX] = -d->polar_inertia;
}
