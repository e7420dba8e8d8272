/* The element registry: each kind's local matrix against hand values, through its
 * gd_element_type (disk, bearing with a speed table between two nodes, spring, mesh at
 * the torsional level), the registry's order and lookup, and the strain energy and
 * force rows the kinds give. The shaft element's matrices have their own closed-form
 * tests (test_shaft_element.c), the mesh vector its invariants (test_gear_mesh.c). */
#include <math.h>
#include <stdlib.h>

#include "elements/elements_impl.h"
#include "harness.h"
#include "model_support.h"

static const char *MODEL =
    "dofs: [x, y, z, rx, ry, rz]\n"
    "shafts:\n"
    "  - name: a\n"
    "    speed_ratio: 1\n"
    "    nodes: [{name: journal}, {name: housing}]\n"
    "  - name: b\n"
    "    speed_ratio: -2\n"
    "    nodes: [{name: wheel}]\n"
    "disks:\n"
    "  - {node: journal, mass: 20, polar_inertia: 0.1, diametral_inertia: 0.06}\n"
    "  - {node: housing, mass: 50}\n"
    "  - {node: wheel, mass: 3, polar_inertia: 0.02, diametral_inertia: 0.01}\n"
    "bearings:\n"
    "  - name: oil_film\n"
    "    node: journal\n"
    "    to: housing\n"
    "    table:\n"
    "      - {speed: 0, k: 1e8, c: 2e3}\n"
    "      - {speed: 100, kxx: 8e7, kyy: 1.2e8, kxy: 3e7, kyx: -3e7, c: 1e3}\n"
    "  - {name: pedestal, node: housing, k: 5e8, c: 1e4, kzz: 1e8, "
    "k_tilt: 1e6, k_torsion: 1e5}\n"
    "  - {name: wheel_support, node: wheel, k: 2e8, kzz: 1e8, k_tilt: 1e6}\n"
    "springs:\n"
    "  - {name: coupling, node: journal, to: wheel, dof: rz, "
    "stiffness: 2000, damping: 0.5}\n";

TEST(registry_order_and_lookup)
{
    REQUIRE(gd_nelement_types == 6);
    const char *names[6] = {"shaft", "disk", "bearing", "spring", "mesh", "planetary"};
    for (int k = 0; k < 6; k++) {
        CHECK_STR(gd_element_types[k]->name, names[k]);
        CHECK(gd_element_type_find(names[k]) == gd_element_types[k]);
    }
    CHECK(gd_element_type_find("gearbox") == NULL);
}

/* Disk on a shaft turning at -2 x the reference speed: M = diag(m, m, m, Id, Id, Ip),
 * G[rx][ry] = ratio Ip = -0.04, G[ry][rx] = +0.04. */
TEST(disk_matrices_by_hand)
{
    fx f;
    REQUIRE(load(&f, NULL, MODEL));
    int node[2];
    REQUIRE(gd_element_disk.count(f.m) == 3);
    CHECK(gd_element_disk.nodes(f.m, 2, node) == 1 && node[0] == gd_model_find_node(f.m, "wheel"));
    double M[36], G[36], K[36];
    gd_element_disk.matrices(f.m, 2, 50.0, M, K, NULL, G);
    double want_m[6] = {3, 3, 3, 0.01, 0.01, 0.02};
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            CHECK_ABS(M[i * 6 + j], i == j ? want_m[i] : 0.0, 0);
            CHECK_ABS(K[i * 6 + j], 0.0, 0);
        }
    CHECK_ABS(G[GD_RX * 6 + GD_RY], -0.04, 1e-17);
    CHECK_ABS(G[GD_RY * 6 + GD_RX], 0.04, 1e-17);
    CHECK(gd_element_disk.terms(f.m, 1) == GD_TERM_M); /* no polar inertia: no G */
    fx_free(&f);
}

/* Oil film between journal and housing, halfway between its two rows at 50 rad/s:
 * kxx = 9e7, kyy = 1.1e8, kxy = 1.5e7, kyx = -1.5e7, c = 1.5e3, and the 12 x 12 is
 * [A -A; -A A]. */
TEST(bearing_speed_table_between_nodes_by_hand)
{
    fx f;
    REQUIRE(load(&f, NULL, MODEL));
    int node[2];
    CHECK(gd_element_bearing.nodes(f.m, 0, node) == 2);
    CHECK(gd_element_bearing.terms(f.m, 0) == (GD_TERM_K | GD_TERM_C | GD_TERM_SPEED));
    CHECK(gd_element_bearing.terms(f.m, 1) == (GD_TERM_K | GD_TERM_C));
    double K[144], C[144];
    gd_element_bearing.matrices(f.m, 0, 50.0, NULL, K, C, NULL);
    double A[4] = {9e7, 1.5e7, -1.5e7, 1.1e8}; /* xx, xy, yx, yy */
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double a = A[i * 2 + j];
            CHECK_REL(K[i * 12 + j], a, 1e-15);
            CHECK_REL(K[(i + 6) * 12 + j + 6], a, 1e-15);
            CHECK_REL(K[i * 12 + j + 6], -a, 1e-15);
            CHECK_REL(K[(i + 6) * 12 + j], -a, 1e-15);
            CHECK_REL(C[i * 12 + j], i == j ? 1.5e3 : 0.0, 1e-15);
        }
    CHECK_ABS(K[GD_Z * 12 + GD_Z], 0, 0);
    int acts[12];
    gd_element_bearing.speed_pattern(f.m, 0, acts);
    for (int a = 0; a < 12; a++)
        CHECK(acts[a] == (a % 6 == GD_X || a % 6 == GD_Y));
    /* the force it transmits in y: row y of [A -A] for both K and C */
    double kr[12], cr[12];
    gd_element_bearing.force_row(f.m, 0, 50.0, GD_Y, kr, cr);
    CHECK_REL(kr[GD_X], -1.5e7, 1e-15);
    CHECK_REL(kr[GD_Y], 1.1e8, 1e-15);
    CHECK_REL(kr[6 + GD_Y], -1.1e8, 1e-15);
    CHECK_REL(cr[6 + GD_Y], -1.5e3, 1e-15);
    fx_free(&f);
}

/* Pedestal to ground (6 x 6): diag(5e8, 5e8, 1e8, 1e6, 1e6, 1e5); C diag(1e4, 1e4). */
TEST(bearing_to_ground_by_hand)
{
    fx f;
    REQUIRE(load(&f, NULL, MODEL));
    int node[2];
    CHECK(gd_element_bearing.nodes(f.m, 1, node) == 1 && node[1] == -1);
    double K[36], C[36];
    gd_element_bearing.matrices(f.m, 1, 0.0, NULL, K, C, NULL);
    double k[6] = {5e8, 5e8, 1e8, 1e6, 1e6, 1e5}, c[6] = {1e4, 1e4, 0, 0, 0, 0};
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            CHECK_ABS(K[i * 6 + j], i == j ? k[i] : 0.0, 0);
            CHECK_ABS(C[i * 6 + j], i == j ? c[i] : 0.0, 0);
        }
    fx_free(&f);
}

/* Torsional coupling between two shafts: k and c at (rz, rz) in [A -A; -A A]; its
 * strain energy for rz1 = 0.01, rz2 = -0.02 is k (0.03)^2 / 2 = 0.9 J, all torsional. */
TEST(spring_matrix_energy_and_force_by_hand)
{
    fx f;
    REQUIRE(load(&f, NULL, MODEL));
    double K[144], C[144];
    gd_element_spring.matrices(f.m, 0, 0.0, NULL, K, C, NULL);
    for (int i = 0; i < 12; i++)
        for (int j = 0; j < 12; j++) {
            double s = (i % 6 == GD_RZ && j % 6 == GD_RZ) ? ((i < 6) == (j < 6) ? 1.0 : -1.0) : 0;
            CHECK_ABS(K[i * 12 + j], 2000 * s, 0);
            CHECK_ABS(C[i * 12 + j], 0.5 * s, 0);
        }
    double u[12] = {0}, by[GD_NMOTIONS] = {0};
    u[GD_RZ] = 0.01;
    u[6 + GD_RZ] = -0.02;
    /* the generic split (the spring has no strain_energy override) via the system */
    int j = gd_system_dof(f.s, gd_model_find_node(f.m, "journal"), GD_RZ);
    int w = gd_system_dof(f.s, gd_model_find_node(f.m, "wheel"), GD_RZ);
    REQUIRE(j >= 0 && w >= 0);
    double *re = calloc((size_t)f.s->ndof, sizeof *re),
           *comp = calloc((size_t)f.s->ncomponents, sizeof(double));
    re[j] = u[GD_RZ];
    re[w] = u[6 + GD_RZ];
    double total = gd_system_strain_energy(f.s, 0.0, re, NULL, by, comp);
    CHECK_REL(total, 0.9, 1e-14);
    CHECK_REL(by[GD_MOTION_TORSIONAL], 0.9, 1e-14);
    CHECK_ABS(by[GD_MOTION_LATERAL] + by[GD_MOTION_AXIAL] + by[GD_MOTION_TILT], 0, 0);
    /* components: shafts a, b, bearings oil_film, pedestal, wheel_support, spring */
    REQUIRE(f.s->ncomponents == 6);
    CHECK_REL(comp[5], 0.9, 1e-14);
    int idx;
    const char *name;
    CHECK(gd_system_component(f.s, 5, &idx, &name) == &gd_element_spring);
    CHECK_STR(name, "coupling");
    CHECK(gd_system_component(f.s, 3, &idx, &name) == &gd_element_bearing && idx == 1);
    CHECK_STR(name, "pedestal");
    double kr[12], cr[12];
    gd_element_spring.force_row(f.m, 0, 0.0, GD_RZ, kr, cr);
    CHECK_ABS(kr[GD_RZ], 2000, 0);
    CHECK_ABS(kr[6 + GD_RZ], -2000, 0);
    CHECK_ABS(cr[6 + GD_RZ], -0.5, 0);
    free(re);
    free(comp);
    fx_free(&f);
}

/* At the torsional level the mesh is k [rb1^2, s rb1 rb2; s rb1 rb2, rb2^2] on the two
 * rz DOFs (DESIGN.md), here for Kumar's gear pair (rb 0.0445, 0.047, k 2e8). */
TEST(mesh_torsional_matrix_by_hand)
{
    fx f;
    REQUIRE(load(&f, "examples/kumar2011_torsional.yaml", NULL));
    REQUIRE(gd_element_mesh.count(f.m) == 1);
    double K[144], C[144];
    gd_element_mesh.matrices(f.m, 0, 0.0, NULL, K, C, NULL);
    double r1 = 0.0445, r2 = 0.047, k = 2e8;
    int p = GD_RZ, g = 6 + GD_RZ;
    CHECK_REL(K[p * 12 + p], k * r1 * r1, 1e-14);
    CHECK_REL(K[g * 12 + g], k * r2 * r2, 1e-14);
    CHECK_REL(fabs(K[p * 12 + g]), k * r1 * r2, 1e-14);
    CHECK_ABS(K[p * 12 + g] - K[g * 12 + p], 0, 0);
    double off = 0;
    for (int i = 0; i < 144; i++)
        if (i != p * 13 && i != g * 13 && i != p * 12 + g && i != g * 12 + p) off += fabs(K[i]);
    CHECK_ABS(off, 0, 0);
    fx_free(&f);
}

RUN_TESTS(T(registry_order_and_lookup), T(disk_matrices_by_hand),
          T(bearing_speed_table_between_nodes_by_hand), T(bearing_to_ground_by_hand),
          T(spring_matrix_energy_and_force_by_hand), T(mesh_torsional_matrix_by_hand))
