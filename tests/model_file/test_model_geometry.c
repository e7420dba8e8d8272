/* Meshes described by gear geometry: sizes and mean stiffness from the mesh stiffness
 * module (docs/mesh-stiffness.md), used by the linear analyses. */
#include "geardyn/mesh_stiffness.h"
#include "geardyn/modal.h"
#include "harness.h"

#define PAIR                                                                                       \
    "dofs: [rz]\n"                                                                                 \
    "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"                               \
    "shafts:\n"                                                                                    \
    "  - {name: a, nodes: [{name: p}]}\n"                                                          \
    "  - {name: b, nodes: [{name: g}]}\n"                                                          \
    "disks:\n"                                                                                     \
    "  - {node: p, polar_inertia: 1.3e-3}\n"                                                       \
    "  - {node: g, polar_inertia: 2.5e-4}\n"                                                       \
    "meshes:\n"                                                                                    \
    "  - name: m\n"                                                                                \
    "    driver: p\n"                                                                              \
    "    driven: g\n"                                                                              \
    "    coupling: torsional\n"

#define GEOMETRY                                                                                   \
    "    geometry:\n"                                                                              \
    "      normal_module: 2 mm\n"                                                                  \
    "      normal_pressure_angle: 20 deg\n"                                                        \
    "      face_width: 20 mm\n"                                                                    \
    "      driver: {teeth: 48, material: steel, bore_radius: 12.7 mm}\n"                           \
    "      driven: {teeth: 32, material: steel, bore_radius: 12.7 mm}\n"

TEST(mesh_sizes_and_stiffness_from_geometry)
{
    gd_error err;
    gd_model *m;
    REQUIRE(gd_model_load_string(PAIR GEOMETRY "    stiffness: {from: geometry}\n", "g.yaml", &m,
                                 &err) == GD_OK);
    const gd_mesh *g = &m->meshes[0];
    CHECK(g->teeth[0] == 48 && g->teeth[1] == 32);
    double c20 = cos(20 * M_PI / 180);
    CHECK_REL(g->base_radius[0], 0.048 * c20, 1e-12);
    CHECK_REL(g->base_radius[1], 0.032 * c20, 1e-12);
    CHECK_REL(g->pressure_angle, 20 * M_PI / 180, 1e-12);
    REQUIRE(g->tvms != NULL);
    CHECK_REL(g->stiffness, g->tvms->mean, 1e-15);
    /* [MMT2018] Sec. 5.1: mean about 3.3e8 N/m (within 15%) */
    CHECK_REL(g->stiffness, 3.3e8, 0.15);
    CHECK_REL(g->tvms->mesh_period_rad, 2 * M_PI / 48, 1e-14);
    /* the gear ratio drives the shaft speeds */
    CHECK_REL(m->shafts[1].speed_ratio, -1.5, 1e-12);

    gd_system *s;
    gd_modal_result *r;
    gd_modal_options o;
    gd_modal_options_init(&o);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    REQUIRE(gd_modal_solve(s, &o, &r, &err) == GD_OK);
    REQUIRE(r->nmodes == 2);
    double rb1 = g->base_radius[0], rb2 = g->base_radius[1];
    double w = sqrt(g->stiffness * (rb1 * rb1 / 1.3e-3 + rb2 * rb2 / 2.5e-4));
    CHECK(r->modes[0].rigid_body);
    CHECK_REL(r->modes[1].omega_n, w, 1e-10);
    gd_modal_free(r);
    gd_system_free(s);
    gd_model_free(m);
}

/* A constant stiffness may sit beside the geometry: the geometry still gives the sizes. */
TEST(constant_stiffness_with_geometry)
{
    gd_error err;
    gd_model *m;
    REQUIRE(gd_model_load_string(PAIR GEOMETRY "    stiffness: 3.9e8\n", "g.yaml", &m, &err) ==
            GD_OK);
    CHECK(m->meshes[0].tvms == NULL);
    CHECK_REL(m->meshes[0].stiffness, 3.9e8, 1e-15);
    CHECK_REL(m->meshes[0].base_radius[0], 0.048 * cos(20 * M_PI / 180), 1e-12);
    gd_model_free(m);
}

static void expect_error(gd_test_state *gd_ts_, const char *yaml, int line, const char *field,
                         const char *word)
{
    gd_error err;
    gd_model *m = NULL;
    gd_error_clear(&err);
    CHECK(gd_model_load_string(yaml, "bad.yaml", &m, &err) == GD_EINPUT);
    CHECK(m == NULL);
    if (line) CHECK(err.line == line);
    CHECK_STR(err.field, field);
    CHECK(strstr(err.message, word) || strstr(err.hint, word));
    CHECK(err.hint[0] != '\0');
    if (err.line != line || strcmp(err.field, field))
        fprintf(stderr, "    got %d %s: %s\n", err.line, err.field, err.message);
}

TEST(geometry_errors)
{
    /* stiffness from geometry without geometry (line 14) */
    expect_error(gd_ts_, PAIR "    base_radius: [0.045, 0.03]\n    stiffness: {from: geometry}\n",
                 15, "meshes[0].stiffness", "geometry");
    /* sizes twice */
    expect_error(gd_ts_, PAIR GEOMETRY "    base_radius: [0.045, 0.03]\n    stiffness: 1e8\n", 10,
                 "meshes[0]", "more than once");
    /* teeth beside the geometry */
    expect_error(gd_ts_, PAIR GEOMETRY "    teeth: [48, 32]\n    stiffness: 1e8\n", 20,
                 "meshes[0].teeth", "geometry");
    /* non-physical geometry is caught when the model is loaded (6 teeth undercut) */
    expect_error(gd_ts_,
                 PAIR "    geometry:\n"
                      "      normal_module: 2 mm\n"
                      "      normal_pressure_angle: 20 deg\n"
                      "      face_width: 20 mm\n"
                      "      driver: {teeth: 6, material: steel}\n"
                      "      driven: {teeth: 32, material: steel}\n"
                      "    stiffness: 1e8\n",
                 18, "meshes[0].geometry.driver.profile_shift", "undercut");
}

/* A stand-alone mesh-stiffness file given where a model is expected says so. */
TEST(mesh_only_file_points_to_mesh_stiffness)
{
    gd_error err;
    gd_model *m = NULL;
    CHECK(gd_model_load("examples/rig2018_pair.yaml", &m, &err) == GD_EINPUT);
    CHECK(m == NULL);
    CHECK_STR(err.field, "shafts");
    CHECK(strstr(err.hint, "geardyn mesh-stiffness") != NULL);
}

RUN_TESTS(T(mesh_only_file_points_to_mesh_stiffness), T(mesh_sizes_and_stiffness_from_geometry),
          T(constant_stiffness_with_geometry), T(geometry_errors))
