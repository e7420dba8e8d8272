/* Connectors: elements that act on the relative motion of two nodes, or of one node
 * against ground, through a 6 x 6 matrix A: K_local = [A -A; -A A] (bearings with a
 * second node, springs and couplings between shafts), or A alone to ground. */
#include <math.h>
#include <string.h>

#include "elements/elements_impl.h"

const gd_motion gd_support_motion[6] = {GD_MOTION_LATERAL, GD_MOTION_LATERAL, GD_MOTION_AXIAL,
                                        GD_MOTION_TILT,    GD_MOTION_TILT,    GD_MOTION_TORSIONAL};

int gd_connector_nodes(int node1, int node2, int node[2])
{
    node[0] = node1;
    node[1] = node2;
    return node2 >= 0 ? 2 : 1;
}

void gd_connector_expand(const double a6[36], int nnodes, double *out)
{
    if (nnodes == 1) {
        memcpy(out, a6, 36 * sizeof *out);
        return;
    }
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            double v = a6[i * 6 + j];
            out[i * 12 + j] = v;
            out[(i + 6) * 12 + j + 6] = v;
            out[i * 12 + j + 6] = -v;
            out[(i + 6) * 12 + j] = -v;
        }
}

void gd_connector_row(const double K6[36], const double C6[36], int nnodes, gd_dof dir, double *k,
                      double *c)
{
    for (int side = 0; side < nnodes; side++) {
        double sg = side ? -1.0 : 1.0;
        for (int e = 0; e < 6; e++) {
            k[6 * side + e] = sg * K6[dir * 6 + e];
            c[6 * side + e] = sg * C6[dir * 6 + e];
        }
    }
}

double gd_node_shaft_speed(const gd_model *m, int node, double speed)
{
    return fabs(m->shafts[m->nodes[node].shaft].speed_ratio * speed);
}
