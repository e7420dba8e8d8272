/* Two-node Timoshenko shaft element: bending in two planes with shear deformation and
 * rotary inertia, gyroscopic coupling, torsion and axial rod (Friswell, Penny, Garvey &
 * Lees, "Dynamics of Rotating Machines", 2010, Sec. 5.4; Nelson 1980).
 *
 * Bending in plane xz uses the local DOFs (x1, ry1, x2, ry2); plane yz uses
 * (y1, -rx1, y2, -rx2), since a positive rx tilts the axis towards -y. With
 * phi = 12 E I / (kappa G A L^2) (kappa: Cowper's shear coefficient) the bending
 * stiffness in either plane is
 *     E I / (L^3 (1 + phi)) [12, 6L, -12, 6L; 6L, (4+phi)L^2, -6L, (2-phi)L^2; ...],
 * the mass is the translational part rho A L / (1+phi)^2 [m1 .. m6] plus the rotary
 * part rho I / (L (1+phi)^2) [r1 .. r4] (coefficients below), and the gyroscopic
 * matrix (per unit spin) is twice the rotary inertia part, coupling the two planes
 * skew-symmetrically. Torsion (rz1, rz2) and axial motion (z1, z2) are rods:
 *     K = (G J / L) [1 -1; -1 1],  M = (rho J L / 6) [2 1; 1 2]   (J = 2 I),
 *     K = (E A / L) [1 -1; -1 1],  M = (rho A L / 6) [2 1; 1 2].
 * Strain energy: bending and tilt count as lateral, z as axial, rz as torsional, each
 * element to its shaft's component. */
#include <math.h>
#include <string.h>

#include "elements/elements_impl.h"

#define PI 3.14159265358979323846

double gd_shear_coefficient(double nu, double outer_diameter, double inner_diameter)
{
    /* Cowper (1966), "The shear coefficient in Timoshenko's beam theory", J. Appl.
     * Mech. 33, Table 1, hollow circle with m = d_i / d_o; solid: 6(1+nu)/(7+6nu). */
    double m = inner_diameter / outer_diameter, m2 = m * m, q = (1 + m2) * (1 + m2);
    return 6.0 * (1 + nu) * q / ((7 + 6 * nu) * q + (20 + 12 * nu) * m2);
}

/* Local bending DOFs (w1, phi1, w2, phi2), phi = dw/dz, mapped into the 12 DOFs:
 * plane xz uses (x, ry), plane yz uses (y, -rx) since a positive rx tilts the axis
 * towards -y. */
static const int XZ_IDX[4] = {0, 4, 6, 10};
static const int YZ_IDX[4] = {1, 3, 7, 9};
static const double YZ_SIGN[4] = {1, -1, 1, -1};

void gd_shaft_element_matrices(const gd_element *e, const gd_material *mat, double M[144],
                               double K[144], double G[144])
{
    memset(M, 0, 144 * sizeof *M);
    memset(K, 0, 144 * sizeof *K);
    memset(G, 0, 144 * sizeof *G);
    double L = e->length, ro = 0.5 * e->outer_diameter, ri = 0.5 * e->inner_diameter;
    double A = PI * (ro * ro - ri * ri);
    double I = PI * (ro * ro * ro * ro - ri * ri * ri * ri) / 4.0;
    double J = 2.0 * I;
    double E = mat->E, Gs = mat->G, rho = mat->density;
    double kappa = gd_shear_coefficient(mat->poisson, e->outer_diameter, e->inner_diameter);
    double phi = 12.0 * E * I / (kappa * Gs * A * L * L);
    double p1 = 1.0 + phi, p2 = p1 * p1, L2 = L * L;

    /* bending stiffness */
    double kb = E * I / (L * L2 * p1);
    double Kb[4][4] = {{12, 6 * L, -12, 6 * L},
                       {6 * L, (4 + phi) * L2, -6 * L, (2 - phi) * L2},
                       {-12, -6 * L, 12, -6 * L},
                       {6 * L, (2 - phi) * L2, -6 * L, (4 + phi) * L2}};
    /* translational inertia */
    double mt = rho * A * L / p2;
    double m1 = 13.0 / 35 + 7.0 * phi / 10 + phi * phi / 3;
    double m2 = (11.0 / 210 + 11.0 * phi / 120 + phi * phi / 24) * L;
    double m3 = 9.0 / 70 + 3.0 * phi / 10 + phi * phi / 6;
    double m4 = (13.0 / 420 + 3.0 * phi / 40 + phi * phi / 24) * L;
    double m5 = (1.0 / 105 + phi / 60 + phi * phi / 120) * L2;
    double m6 = (1.0 / 140 + phi / 60 + phi * phi / 120) * L2;
    double Mt[4][4] = {
        {m1, m2, m3, -m4}, {m2, m5, m4, -m6}, {m3, m4, m1, -m2}, {-m4, -m6, -m2, m5}};
    /* rotary inertia */
    double mr = rho * I / (L * p2);
    double r1 = 6.0 / 5, r2 = (1.0 / 10 - phi / 2) * L;
    double r3 = (2.0 / 15 + phi / 6 + phi * phi / 3) * L2;
    double r4 = (1.0 / 30 + phi / 6 - phi * phi / 6) * L2;
    double Mr[4][4] = {
        {r1, r2, -r1, r2}, {r2, r3, -r2, -r4}, {-r1, -r2, r1, -r2}, {r2, -r4, -r2, r3}};

    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            double kab = kb * Kb[a][b], mab = mt * Mt[a][b] + mr * Mr[a][b];
            int xa = XZ_IDX[a], xb = XZ_IDX[b], ya = YZ_IDX[a], yb = YZ_IDX[b];
            double sy = YZ_SIGN[a] * YZ_SIGN[b];
            K[xa * 12 + xb] += kab;
            K[ya * 12 + yb] += sy * kab;
            M[xa * 12 + xb] += mab;
            M[ya * 12 + yb] += sy * mab;
            /* gyroscopic: polar inertia per length rho*J = 2 rho I, so G = 2 Mr in the
             * (q_x, q_y) coupling, skew-symmetric */
            double g = 2.0 * mr * Mr[a][b];
            G[xa * 12 + yb] += g * YZ_SIGN[b];
            G[ya * 12 + xb] -= g * YZ_SIGN[a];
        }
    /* torsion (rz) and axial rod (z) with consistent mass */
    double kt = Gs * J / L, mtor = rho * J * L / 6.0;
    double ka = E * A / L, max = rho * A * L / 6.0;
    const int tz[2] = {5, 11}, az[2] = {2, 8};
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            double s = a == b ? 1.0 : -1.0, w = a == b ? 2.0 : 1.0;
            K[tz[a] * 12 + tz[b]] += s * kt;
            M[tz[a] * 12 + tz[b]] += w * mtor;
            K[az[a] * 12 + az[b]] += s * ka;
            M[az[a] * 12 + az[b]] += w * max;
        }
}

static int shaft_count(const gd_model *m)
{
    return m->nelements;
}

static int shaft_nodes(const gd_model *m, int i, int node[2])
{
    node[0] = m->elements[i].node1;
    node[1] = m->elements[i].node2;
    return 2;
}

static unsigned shaft_terms(const gd_model *m, int i)
{
    (void)m;
    (void)i;
    return GD_TERM_M | GD_TERM_K | GD_TERM_G;
}

static void shaft_matrices(const gd_model *m, int i, double speed, double *M, double *K, double *C,
                           double *G)
{
    (void)speed;
    const gd_element *e = &m->elements[i];
    double Me[144], Ke[144], Ge[144];
    gd_shaft_element_matrices(e, &m->materials[e->material], Me, Ke, Ge);
    double ratio = m->shafts[e->shaft].speed_ratio;
    if (M) memcpy(M, Me, sizeof Me);
    if (K) memcpy(K, Ke, sizeof Ke);
    if (G)
        for (int k = 0; k < 144; k++)
            G[k] = ratio * Ge[k];
    if (C) memset(C, 0, sizeof Me);
}

static const gd_motion SHAFT_MOTION[6] = {GD_MOTION_LATERAL, GD_MOTION_LATERAL,
                                          GD_MOTION_AXIAL,   GD_MOTION_LATERAL,
                                          GD_MOTION_LATERAL, GD_MOTION_TORSIONAL};

static int shaft_ncomponents(const gd_model *m)
{
    return m->nshafts;
}

static int shaft_component(const gd_model *m, int i)
{
    return m->elements[i].shaft;
}

static const char *shaft_name(const gd_model *m, int c)
{
    return m->shafts[c].name;
}

const gd_element_type gd_element_shaft = {
    .name = "shaft",
    .count = shaft_count,
    .nodes = shaft_nodes,
    .terms = shaft_terms,
    .matrices = shaft_matrices,
    .motion = SHAFT_MOTION,
    .ncomponents = shaft_ncomponents,
    .component = shaft_component,
    .component_name = shaft_name,
};
