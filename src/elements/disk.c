/* Rigid disk or gear body at a node (Friswell et al., "Dynamics of Rotating Machines",
 * 2010, Sec. 5.3): mass m, diametral inertia Id and polar inertia Ip, and the gyroscopic
 * moment of its spin, Id rx'' + Ip W ry' = Mx, Id ry'' - Ip W rx' = My. Over
 * (x, y, z, rx, ry, rz):
 *     M = diag(m, m, m, Id, Id, Ip),   G[rx][ry] = Ip, G[ry][rx] = -Ip (per unit spin),
 * the spin being the disk's shaft speed (signed speed ratio x reference speed). No
 * stiffness, so no strain energy and no force probe. */
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

static int disk_count(const gd_model *m)
{
    return m->ndisks;
}

static int disk_nodes(const gd_model *m, int i, int node[2])
{
    node[0] = m->disks[i].node;
    node[1] = -1;
    return 1;
}

static unsigned disk_terms(const gd_model *m, int i)
{
    return GD_TERM_M | (m->disks[i].polar_inertia != 0 ? GD_TERM_G : 0);
}

static void disk_matrices(const gd_model *m, int i, double speed, double *M, double *K, double *C,
                          double *G)
{
    (void)speed;
    const gd_disk *d = &m->disks[i];
    double M6[36], G6[36];
    gd_disk_matrices(d, M6, G6);
    double ratio = m->shafts[m->nodes[d->node].shaft].speed_ratio;
    if (M) memcpy(M, M6, sizeof M6);
    if (G)
        for (int k = 0; k < 36; k++)
            G[k] = ratio * G6[k];
    if (K) memset(K, 0, sizeof M6);
    if (C) memset(C, 0, sizeof M6);
}

static const gd_motion DISK_MOTION[6] = {GD_MOTION_LATERAL, GD_MOTION_LATERAL, GD_MOTION_AXIAL,
                                         GD_MOTION_TILT,    GD_MOTION_TILT,    GD_MOTION_TORSIONAL};

const gd_element_type gd_element_disk = {
    .name = "disk",
    .count = disk_count,
    .nodes = disk_nodes,
    .terms = disk_terms,
    .matrices = disk_matrices,
    .motion = DISK_MOTION,
};
