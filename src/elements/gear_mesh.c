/* Gear mesh element: the tooth contact deformation d = a . q along the contact
 * normal, so the mesh adds k a a^T to K and c a a^T to C (DESIGN.md; Kahraman 1994,
 * and the 12-DOF helical element of [JMSTHelical] Eqs. 14-16).
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
 * bb = 0 the tilt terms vanish (spur); the rz entries are s rb1 cos(bb), s rb2 cos(bb).
 *
 * Local matrices over (driver x..rz, driven x..rz): K = k a a^T, C = c a a^T with
 * c = damping + per_stiffness x mean k (gd_mesh_linear_damping), no mass. The strain
 * energy k |d|^2 / 2 is shared among motion types in proportion to |d_motion|^2, the
 * part of d from the DOFs of that motion, so the shares are non-negative. The force
 * probe is the dynamic mesh force F = k d + c d' ([Kumar2011] Fig. 3 plots K_m (r_p theta_p +
 * r_g theta_g), the torsional case). */
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

static int mesh_count(const gd_model *m)
{
    return m->nmeshes;
}

static int mesh_nodes(const gd_model *m, int i, int node[2])
{
    node[0] = m->meshes[i].driver;
    node[1] = m->meshes[i].driven;
    return 2;
}

static unsigned mesh_terms(const gd_model *m, int i)
{
    (void)m;
    (void)i;
    return GD_TERM_K | GD_TERM_C;
}

static void mesh_matrices(const gd_model *m, int i, double speed, double *M, double *K, double *C,
                          double *G)
{
    (void)speed;
    const gd_mesh *g = &m->meshes[i];
    double a[12], k = g->stiffness, c = gd_mesh_linear_damping(g);
    gd_mesh_vector_local(g, a);
    for (int r = 0; r < 12; r++)
        for (int s = 0; s < 12; s++) {
            if (K) K[r * 12 + s] = k * a[r] * a[s];
            if (C) C[r * 12 + s] = c * a[r] * a[s];
            if (M) M[r * 12 + s] = 0;
            if (G) G[r * 12 + s] = 0;
        }
}

static double mesh_strain_energy(const gd_model *m, int i, const double *K, const double *re,
                                 const double *im, double *by_motion)
{
    (void)K;
    double a[12];
    gd_mesh_vector_local(&m->meshes[i], a);
    double dm_re[GD_NMOTIONS] = {0}, dm_im[GD_NMOTIONS] = {0}, d_re = 0, d_im = 0;
    for (int j = 0; j < 12; j++) {
        if (a[j] == 0.0) continue;
        gd_motion mo = gd_support_motion[j % 6];
        double ur = re[j], ui = im ? im[j] : 0;
        dm_re[mo] += a[j] * ur;
        dm_im[mo] += a[j] * ui;
        d_re += a[j] * ur;
        d_im += a[j] * ui;
    }
    double en = 0.5 * m->meshes[i].stiffness * (d_re * d_re + d_im * d_im);
    double wsum = 0;
    for (int k = 0; k < GD_NMOTIONS; k++)
        wsum += dm_re[k] * dm_re[k] + dm_im[k] * dm_im[k];
    if (wsum > 0)
        for (int k = 0; k < GD_NMOTIONS; k++)
            by_motion[k] += en * (dm_re[k] * dm_re[k] + dm_im[k] * dm_im[k]) / wsum;
    return en;
}

static int mesh_ncomponents(const gd_model *m)
{
    return m->nmeshes;
}

static int mesh_component(const gd_model *m, int i)
{
    (void)m;
    return i;
}

static const char *mesh_name(const gd_model *m, int c)
{
    return m->meshes[c].name;
}

/* F = k d + c d' along the contact normal (dir is not used: a mesh has one force). */
static void mesh_force_row(const gd_model *m, int i, double speed, gd_dof dir, double *k, double *c)
{
    (void)speed;
    (void)dir;
    const gd_mesh *g = &m->meshes[i];
    double a[12], kk = g->stiffness, cc = gd_mesh_linear_damping(g);
    gd_mesh_vector_local(g, a);
    for (int j = 0; j < 12; j++) {
        k[j] = kk * a[j];
        c[j] = cc * a[j];
    }
}

const gd_element_type gd_element_mesh = {
    .name = "mesh",
    .count = mesh_count,
    .nodes = mesh_nodes,
    .terms = mesh_terms,
    .matrices = mesh_matrices,
    .motion = gd_support_motion,
    .strain_energy = mesh_strain_energy,
    .ncomponents = mesh_ncomponents,
    .component = mesh_component,
    .component_name = mesh_name,
    .force_row = mesh_force_row,
    .probe = "mesh",
    .probe_help = "dynamic mesh force k d + c d' along the contact normal (N)",
};
