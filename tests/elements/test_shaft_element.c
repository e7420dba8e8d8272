/* Shaft element: matrix properties and beam frequencies against closed forms. */
#include <lapacke.h>
#include <stdlib.h>

#include "elements/elements_impl.h"
#include "geardyn/modal.h"
#include "harness.h"

static const gd_material STEEL = {"steel", 7800.0, 2.0e11, 2.0e11 / 2.6, 0.3};

static gd_element element(double L, double d_out, double d_in)
{
    gd_element e = {0, 0, 0, 1, L, d_out, d_in, 0};
    return e;
}

TEST(matrices_symmetric_and_gyroscopic_skew)
{
    gd_element e = element(0.07, 0.05, 0.02);
    double M[144], K[144], G[144];
    gd_shaft_element_matrices(&e, &STEEL, M, K, G);
    double gmax = 0;
    for (int i = 0; i < 12; i++)
        for (int j = 0; j < 12; j++) {
            CHECK_ABS(M[i * 12 + j] - M[j * 12 + i], 0, 1e-15 * fabs(M[0]));
            CHECK_ABS(K[i * 12 + j] - K[j * 12 + i], 0, 1e-12 * fabs(K[0]));
            CHECK_ABS(G[i * 12 + j] + G[j * 12 + i], 0, 1e-18);
            if (fabs(G[i * 12 + j]) > gmax) gmax = fabs(G[i * 12 + j]);
        }
    CHECK(gmax > 0);
}

/* K has exactly six zero eigenvalues (rigid motions of a free element), M none. */
TEST(stiffness_has_six_rigid_modes_mass_positive_definite)
{
    gd_element e = element(0.1, 0.04, 0.0);
    double M[144], K[144], G[144], w[12];
    gd_shaft_element_matrices(&e, &STEEL, M, K, G);
    REQUIRE(LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'U', 12, M, 12, w) == 0);
    CHECK(w[0] > 0);
    REQUIRE(LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'U', 12, K, 12, w) == 0);
    int zeros = 0;
    for (int i = 0; i < 12; i++) {
        CHECK(w[i] > -1e-9 * w[11]);
        if (fabs(w[i]) < 1e-9 * w[11]) zeros++;
    }
    CHECK(zeros == 6);
}

/* Rigid motion of the element stores no energy and a uniform spin has the kinetic
 * energy of a rod: u^T M u for a unit translation equals the element mass. */
TEST(mass_matrix_reproduces_rigid_body_inertia)
{
    gd_element e = element(0.3, 0.06, 0.03);
    double M[144], K[144], G[144];
    gd_shaft_element_matrices(&e, &STEEL, M, K, G);
    double A = M_PI / 4 * (0.06 * 0.06 - 0.03 * 0.03), m = STEEL.density * A * 0.3;
    double Jp = m * (0.03 * 0.03 + 0.015 * 0.015) / 2;
    for (int d = 0; d < 3; d++) {
        double s = 0;
        for (int i = 0; i < 12; i++)
            for (int j = 0; j < 12; j++)
                if (i % 6 == d && j % 6 == d) s += M[i * 12 + j];
        CHECK_REL(s, m, 1e-12);
    }
    double s = 0;
    for (int i = 0; i < 12; i++)
        for (int j = 0; j < 12; j++)
            if (i % 6 == GD_RZ && j % 6 == GD_RZ) s += M[i * 12 + j];
    CHECK_REL(s, Jp, 1e-12);
}

/* The hollow-section shear coefficient reduces to Cowper's solid value. */
TEST(shear_coefficient_solid_and_thin)
{
    CHECK_REL(gd_shear_coefficient(0.3, 1.0, 0.0), 6 * 1.3 / (7 + 1.8), 1e-14);
    /* thin-walled tube tends to 2(1+nu)/(4+3nu) */
    CHECK_REL(gd_shear_coefficient(0.3, 1.0, 0.9999), 2 * 1.3 / (4 + 0.9), 1e-4);
}

static gd_modal_result *solve_yaml(const char *yaml, int nmodes)
{
    gd_error err;
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_modal_result *r = NULL;
    if (gd_model_load_string(yaml, "beam.yaml", &m, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return NULL;
    }
    if (gd_system_build(m, &s, &err) == GD_OK) {
        gd_modal_options o;
        gd_modal_options_init(&o);
        o.nmodes = nmodes;
        if (gd_modal_solve(s, &o, &r, &err)) fprintf(stderr, "%s\n", err.message);
    }
    gd_system_free(s);
    gd_model_free(m);
    return r;
}

/* Simply supported Timoshenko beam: exact frequencies from
 * (rA w^2 - kGA a^2)(rI w^2 - EI a^2 - kGA) = (kGA a)^2, a = n pi / L. */
static double timoshenko_ss(int n, double L, double d)
{
    double A = M_PI * d * d / 4, In = M_PI * pow(d, 4) / 64, E = STEEL.E, G = STEEL.G,
           r = STEEL.density, k = gd_shear_coefficient(0.3, d, 0), a = n * M_PI / L;
    double qa = r * A * r * In,
           qb = -(r * A * (E * In * a * a + k * G * A) + k * G * A * a * a * r * In),
           qc = k * G * A * E * In * pow(a, 4);
    double x = (-qb - sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
    return sqrt(x);
}

TEST(pinned_pinned_thick_beam_matches_timoshenko)
{
    /* L/d = 8: shear and rotary inertia lower the frequencies by several per cent */
    const char *yaml = "dofs: [x, ry]\n"
                       "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"
                       "shafts:\n"
                       "  - name: beam\n"
                       "    material: steel\n"
                       "    elements_per_section: 60\n"
                       "    sections: [{length: 0.8, outer_diameter: 0.1}]\n"
                       "    nodes: [{name: a, at: 0}, {name: b, at: 0.8}]\n"
                       "bearings:\n"
                       "  - {node: a, kxx: 1e14}\n"
                       "  - {node: b, kxx: 1e14}\n";
    gd_modal_result *r = solve_yaml(yaml, 3);
    REQUIRE(r);
    for (int n = 1; n <= 3; n++) {
        double exact = timoshenko_ss(n, 0.8, 0.1);
        double euler = pow(n * M_PI / 0.8, 2) *
                       sqrt(STEEL.E * M_PI * pow(0.1, 4) / 64 / (STEEL.density * M_PI * 0.01 / 4));
        CHECK(exact < euler * 0.99); /* the test is sensitive to shear */
        CHECK_REL(r->modes[n - 1].omega_n, exact, 2e-4);
    }
    gd_modal_free(r);
}

TEST(free_free_slender_beam_matches_euler_bernoulli)
{
    const char *yaml = "dofs: [y, rx]\n"
                       "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"
                       "shafts:\n"
                       "  - {name: beam, material: steel, elements_per_section: 40,\n"
                       "     sections: [{length: 2.0, outer_diameter: 0.02}]}\n";
    gd_modal_result *r = solve_yaml(yaml, 5);
    REQUIRE(r);
    CHECK(r->modes[0].rigid_body && r->modes[1].rigid_body && !r->modes[2].rigid_body);
    const double bl[3] = {4.730040745, 7.853204624, 10.99560784};
    double EI = STEEL.E * M_PI * pow(0.02, 4) / 64, rA = STEEL.density * M_PI * 0.0004 / 4;
    /* Timoshenko lies slightly below Euler-Bernoulli: by about (beta r)^2 (1 + E/kG)/2,
     * 1.5e-3 for the third mode here */
    for (int k = 0; k < 3; k++) {
        double eb = bl[k] * bl[k] * sqrt(EI / (rA * 16.0));
        CHECK_REL(r->modes[k + 2].omega_n, eb, 2e-3);
        CHECK(r->modes[k + 2].omega_n < eb);
    }
    gd_modal_free(r);
}

TEST(torsion_and_axial_rod_frequencies)
{
    const char *yaml =
        "dofs: [z, rz]\n"
        "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"
        "shafts:\n"
        "  - {name: rod, material: steel, elements_per_section: 80,\n"
        "     sections: [{length: 1.0, outer_diameter: 0.05, inner_diameter: 0.03}]}\n";
    gd_modal_result *r = solve_yaml(yaml, 6);
    REQUIRE(r);
    int rigid = 0;
    for (int j = 0; j < 6; j++)
        rigid += r->modes[j].rigid_body;
    CHECK(rigid == 2);
    double wt = M_PI * sqrt(STEEL.G / STEEL.density), wa = M_PI * sqrt(STEEL.E / STEEL.density);
    /* free-free rods: n pi/L sqrt(G/rho) (torsion), n pi/L sqrt(E/rho) (axial) */
    CHECK_REL(r->modes[2].omega_n, wt, 2e-4);
    CHECK(r->modes[2].dominant_motion == GD_MOTION_TORSIONAL);
    CHECK_REL(r->modes[3].omega_n, wa, 2e-4);
    CHECK(r->modes[3].dominant_motion == GD_MOTION_AXIAL);
    CHECK_REL(r->modes[4].omega_n, 2 * wt, 5e-4);
    CHECK(r->modes[4].dominant_motion == GD_MOTION_TORSIONAL);
    gd_modal_free(r);
}

RUN_TESTS(T(matrices_symmetric_and_gyroscopic_skew),
          T(stiffness_has_six_rigid_modes_mass_positive_definite),
          T(mass_matrix_reproduces_rigid_body_inertia), T(shear_coefficient_solid_and_thin),
          T(pinned_pinned_thick_beam_matches_timoshenko),
          T(free_free_slender_beam_matches_euler_bernoulli), T(torsion_and_axial_rod_frequencies))
