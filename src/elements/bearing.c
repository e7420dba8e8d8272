/* Linear bearing/support: stiffness and damping on the six DOFs of a node, with
 * optional cross-coupled lateral terms and speed tables. */
#include <string.h>

#include "elements/elements_impl.h"

void gd_bearing_coeffs_at(const gd_bearing *b, double shaft_speed, gd_bearing_coeffs *out)
{
    if (b->ntable == 0) {
        *out = b->coeffs;
        return;
    }
    int n = b->ntable;
    if (shaft_speed <= b->table_speed[0]) {
        *out = b->table[0];
        return;
    }
    if (shaft_speed >= b->table_speed[n - 1]) {
        *out = b->table[n - 1];
        return;
    }
    int j = 1;
    while (b->table_speed[j] < shaft_speed)
        j++;
    double t = (shaft_speed - b->table_speed[j - 1]) / (b->table_speed[j] - b->table_speed[j - 1]);
    const double *lo = (const double *)&b->table[j - 1], *hi = (const double *)&b->table[j];
    double *o = (double *)out;
    for (size_t k = 0; k < sizeof *out / sizeof(double); k++)
        o[k] = lo[k] + t * (hi[k] - lo[k]);
}

void gd_bearing_matrices(const gd_bearing_coeffs *c, double K[36], double C[36])
{
    memset(K, 0, 36 * sizeof *K);
    memset(C, 0, 36 * sizeof *C);
    K[GD_X * 6 + GD_X] = c->kxx;
    K[GD_X * 6 + GD_Y] = c->kxy;
    K[GD_Y * 6 + GD_X] = c->kyx;
    K[GD_Y * 6 + GD_Y] = c->kyy;
    K[GD_Z * 6 + GD_Z] = c->kzz;
    K[GD_RX * 6 + GD_RX] = K[GD_RY * 6 + GD_RY] = c->ktilt;
    K[GD_RZ * 6 + GD_RZ] = c->ktorsion;
    C[GD_X * 6 + GD_X] = c->cxx;
    C[GD_X * 6 + GD_Y] = c->cxy;
    C[GD_Y * 6 + GD_X] = c->cyx;
    C[GD_Y * 6 + GD_Y] = c->cyy;
    C[GD_Z * 6 + GD_Z] = c->czz;
    C[GD_RX * 6 + GD_RX] = C[GD_RY * 6 + GD_RY] = c->ctilt;
    C[GD_RZ * 6 + GD_RZ] = c->ctorsion;
}
