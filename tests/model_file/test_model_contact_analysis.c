/* Model meshes with `stiffness: {from: contact_analysis}` and tooth `modifications:`:
 * the loaded stiffness and the transmission error the dynamics subtract, and located
 * errors of bad micro-geometry (docs/mesh-stiffness.md, "Micro-geometry"). */
#include <math.h>
#include <string.h>

#include "geardyn/laws.h"
#include "geardyn/mesh_stiffness.h"
#include "geardyn/model.h"
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
    "    coupling: torsional\n"                                                                    \
    "    geometry:\n"                                                                              \
    "      normal_module: 2 mm\n"                                                                  \
    "      face_width: 20 mm\n"                                                                    \
    "      driver: {teeth: 48, material: steel, bore_radius: 12.7 mm}\n"

/* line 18: the driven gear, 19: the stiffness */
#define DRIVEN "      driven: {teeth: 32, material: steel, bore_radius: 12.7 mm}\n"
#define RELIEVED                                                                                   \
    "      driven:\n"                                                                              \
    "        teeth: 32\n"                                                                          \
    "        material: steel\n"                                                                    \
    "        bore_radius: 12.7 mm\n"                                                               \
    "        modifications:\n"                                                                     \
    "          tip_relief: {amount: 8 um, start_diameter: 67 mm, shape: linear}\n"                 \
    "          crowning: 2 um\n"
#define LTCA "    stiffness: {from: contact_analysis, load: 100 N m, points: 64, slices: 20}\n"

static gd_model *load(const char *yaml)
{
    gd_error err;
    gd_model *m = NULL;
    if (gd_model_load_string(yaml, "ca.yaml", &m, &err)) {
        fprintf(stderr, "  %s: %s (%s)\n", err.field, err.message, err.hint);
        return NULL;
    }
    return m;
}

/* Unmodified: the loaded stiffness is the TVMS and the error the dynamics subtract is
 * zero (delta = F0 / k), so the model is that of `from: geometry`. */
TEST(unmodified_is_the_tvms)
{
    gd_model *a = load(PAIR DRIVEN LTCA);
    gd_model *b = load(PAIR DRIVEN "    stiffness: {from: geometry, points: 64}\n");
    REQUIRE(a && b);
    const gd_mesh *ga = &a->meshes[0], *gb = &b->meshes[0];
    REQUIRE(ga->tvms && gb->tvms && ga->dyn.ste);
    CHECK_REL(ga->stiffness, gb->stiffness, 1e-9);
    for (size_t i = 0; i < ga->tvms->points; i++) {
        CHECK_REL(ga->tvms->stiffness[i], gb->tvms->stiffness[i], 1e-9);
        CHECK_ABS(gd_table_eval(ga->dyn.ste, ga->tvms->angle_rad[i], NULL, NULL), 0, 1e-18);
    }
    gd_model_free(a);
    gd_model_free(b);
}

/* Relieved and crowned: the stiffness table is the contact analysis's tangent
 * stiffness, and the mesh law k_L (d - e) carries the mean load F0 exactly at the
 * loaded transmission error d = delta (1e-12). */
TEST(relieved_mesh_carries_its_load_at_the_loaded_te)
{
    gd_model *m = load(PAIR RELIEVED LTCA);
    REQUIRE(m);
    const gd_mesh *g = &m->meshes[0];
    REQUIRE(g->tvms && g->dyn.ste && g->dyn.tvms == NULL);
    gd_gear_pair_geometry geo;
    gd_gear_pair_geometry_init(&geo);
    geo.normal_module = 2e-3, geo.face_width = 0.02;
    geo.gear[0].teeth = 48, geo.gear[1].teeth = 32;
    for (int i = 0; i < 2; i++)
        geo.gear[i].E = 2.0e11, geo.gear[i].bore_radius = 12.7e-3;
    geo.gear[1].mod.tip_relief = (gd_profile_relief){8e-6, 67e-3, 0, GD_RELIEF_LINEAR};
    geo.gear[1].mod.crowning = 2e-6;
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 64, o.slices = 20, o.load_torque = 100;
    gd_ltca_result *r = NULL;
    gd_error err;
    REQUIRE(gd_ltca_compute(&geo, &o, &r, &err) == GD_OK);
    CHECK(r->ste_peak_to_peak > 0);
    CHECK_REL(g->stiffness, r->stiffness_mean, 1e-12);
    for (size_t i = 0; i < r->points; i++) {
        double th = r->angle_rad[i], k = g->tvms->stiffness[i];
        double e = gd_table_eval(g->dyn.ste, th, NULL, NULL);
        CHECK_REL(k, r->stiffness[i], 1e-12);
        CHECK_REL(k * (r->ste[i] - e), r->force, 1e-12);
    }
    gd_ltca_free(r);
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
    if (err.line != line || strcmp(err.field, field) ||
        !(strstr(err.message, word) || strstr(err.hint, word)))
        fprintf(stderr, "    got %d %s: %s (%s)\n", err.line, err.field, err.message, err.hint);
}

#define MODS(text)                                                                                 \
    PAIR "      driven:\n"                                                                         \
         "        teeth: 32\n"                                                                     \
         "        material: steel\n"                                                               \
         "        modifications:\n" text LTCA

TEST(located_errors)
{
    const char *D = "meshes[0].geometry.driven.modifications.";
    char f[200];
    /* line 22: the first line of the modifications */
    snprintf(f, sizeof f, "%scrowning", D);
    expect_error(gd_ts_, MODS("          crowning: -2 um\n"), 22, f, "negative crowning");
    snprintf(f, sizeof f, "%stip_relief.start_diameter", D);
    expect_error(gd_ts_, MODS("          tip_relief: {amount: 8 um, start_diameter: 63 mm}\n"), 22,
                 f, "longer than the addendum");
    snprintf(f, sizeof f, "%stip_relief.amount", D);
    expect_error(gd_ts_, MODS("          tip_relief: {amount: 8, start_diameter: 66 mm}\n"), 22, f,
                 "um");
    snprintf(f, sizeof f, "%sroot_relief.start_diameter", D);
    expect_error(gd_ts_, MODS("          root_relief: {amount: 5 um, start_diameter: 65 mm}\n"), 22,
                 f, "longer than the dedendum");
    snprintf(f, sizeof f, "%scrowing", D);
    expect_error(gd_ts_, MODS("          crowing: 2 um\n"), 22, f, "crowning");
    snprintf(f, sizeof f, "%stip_relief.shape", D);
    expect_error(
        gd_ts_, MODS("          tip_relief: {amount: 8 um, start_diameter: 66 mm, shape: round}\n"),
        22, f, "parabolic");
    /* the stiffness map (line 19) */
    expect_error(gd_ts_, PAIR DRIVEN "    stiffness: {from: contact_analysis}\n", 19,
                 "meshes[0].stiffness", "load");
    expect_error(gd_ts_, PAIR DRIVEN "    stiffness: {from: geometry, load: 5 N m}\n", 19,
                 "meshes[0].stiffness", "contact_analysis");
    expect_error(gd_ts_,
                 PAIR DRIVEN
                 "    stiffness: {from: contact_analysis, load: 5 N m, method: iso6336}\n",
                 19, "meshes[0].stiffness", "stiffness law");
    /* the contact analysis gives the transmission error: no table besides */
    expect_error(gd_ts_,
                 PAIR DRIVEN LTCA "    transmission_error: {angle: [0, 0.1], error: [0, 1e-6]}\n",
                 20, "meshes[0].transmission_error", "contact analysis");
}

RUN_TESTS(T(unmodified_is_the_tvms), T(relieved_mesh_carries_its_load_at_the_loaded_te),
          T(located_errors))
