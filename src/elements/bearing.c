/* Bearing / support element: linear stiffness and damping on the six DOFs of a node,
 * to ground or to a second node (a bearing housing, another shaft), with cross-coupled
 * lateral terms and coefficients that may depend on the shaft speed (a table,
 * interpolated linearly). With A the 6 x 6 coefficient matrix over (x, y, z, rx, ry, rz)
 *
 *         | kxx kxy  .    .     .     .      |
 *         | kyx kyy  .    .     .     .      |
 *     A = |  .   .  kzz   .     .     .      |      (C likewise with the c's)
 *         |  .   .   .  ktilt   .     .      |
 *         |  .   .   .    .   ktilt   .      |
 *         |  .   .   .    .     .  ktorsion  |
 *
 * the local stiffness is A to ground, or [A -A; -A A] between two nodes (connector.c):
 * the usual 8-coefficient linearised bearing (Friswell et al., "Dynamics of Rotating
 * Machines", 2010, Sec. 5.5), extended by axial, tilt and torsional terms. Strain energy
 * goes to lateral (x, y), axial (z), tilt (rx, ry) and torsional (rz) motion; the force
 * probe is the force the bearing transmits in one direction, the row of K dq + C dq'. */
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

static int bearing_count(const gd_model *m)
{
    return m->nbearings;
}

static int bearing_nodes(const gd_model *m, int i, int node[2])
{
    return gd_connector_nodes(m->bearings[i].node, m->bearings[i].node2, node);
}

static int coeffs_damp(const gd_bearing_coeffs *c)
{
    return c->cxx || c->cxy || c->cyx || c->cyy || c->czz || c->ctilt || c->ctorsion;
}

static unsigned bearing_terms(const gd_model *m, int i)
{
    const gd_bearing *b = &m->bearings[i];
    if (!b->ntable) return GD_TERM_K | GD_TERM_C;
    unsigned t = GD_TERM_K | GD_TERM_SPEED;
    for (int r = 0; r < b->ntable; r++)
        if (coeffs_damp(&b->table[r])) t |= GD_TERM_C;
    return t;
}

static void coefficient_matrices(const gd_model *m, int i, double speed, double K6[36],
                                 double C6[36])
{
    const gd_bearing *b = &m->bearings[i];
    gd_bearing_coeffs c;
    gd_bearing_coeffs_at(b, gd_node_shaft_speed(m, b->node, speed), &c);
    gd_bearing_matrices(&c, K6, C6);
}

static void bearing_matrices(const gd_model *m, int i, double speed, double *M, double *K,
                             double *C, double *G)
{
    int nn = m->bearings[i].node2 >= 0 ? 2 : 1, n = 6 * nn;
    double K6[36], C6[36];
    coefficient_matrices(m, i, speed, K6, C6);
    if (M) memset(M, 0, (size_t)(n * n) * sizeof *M);
    if (G) memset(G, 0, (size_t)(n * n) * sizeof *G);
    if (K) gd_connector_expand(K6, nn, K);
    if (C) gd_connector_expand(C6, nn, C);
}

/* The DOFs a speed table acts on at any speed: the union over its rows. */
static void bearing_speed_pattern(const gd_model *m, int i, int *acts)
{
    const gd_bearing *b = &m->bearings[i];
    int nn = b->node2 >= 0 ? 2 : 1;
    memset(acts, 0, (size_t)(6 * nn) * sizeof *acts);
    for (int r = 0; r < b->ntable; r++) {
        double K6[36], C6[36];
        gd_bearing_matrices(&b->table[r], K6, C6);
        for (int d = 0; d < 6; d++)
            for (int e = 0; e < 6; e++)
                if (K6[d * 6 + e] != 0 || C6[d * 6 + e] != 0)
                    for (int s = 0; s < nn; s++)
                        acts[6 * s + d] = 1;
    }
}

static int bearing_ncomponents(const gd_model *m)
{
    return m->nbearings;
}

static int bearing_component(const gd_model *m, int i)
{
    (void)m;
    return i;
}

static const char *bearing_name(const gd_model *m, int c)
{
    return m->bearings[c].name;
}

static void bearing_force_row(const gd_model *m, int i, double speed, gd_dof dir, double *k,
                              double *c)
{
    double K6[36], C6[36];
    coefficient_matrices(m, i, speed, K6, C6);
    gd_connector_row(K6, C6, m->bearings[i].node2 >= 0 ? 2 : 1, dir, k, c);
}

const gd_element_type gd_element_bearing = {
    .name = "bearing",
    .count = bearing_count,
    .nodes = bearing_nodes,
    .terms = bearing_terms,
    .matrices = bearing_matrices,
    .speed_pattern = bearing_speed_pattern,
    .motion = gd_support_motion,
    .ncomponents = bearing_ncomponents,
    .component = bearing_component,
    .component_name = bearing_name,
    .force_row = bearing_force_row,
    .probe = "bearing",
    .probe_dirs = 1,
    .probe_help = "force the bearing transmits in DIR (x, y, z, rx, ry, rz)",
};
