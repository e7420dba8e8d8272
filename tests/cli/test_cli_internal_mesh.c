/* geardyn mesh-stiffness on an internal (ring-planet) pair: text and JSON against the
 * library, the helix override, the contact analysis, the key's errors located in the
 * file with exit 2 and nothing written, and a model mesh refusing `internal`. */
#include "cli_support.h"
#include "geardyn/mesh_stiffness.h"
#include "harness.h"

static const char *const EXAMPLE = "examples/ring_planet_pair.yaml";

/* The example's pair, built in C. */
static void example_pair(gd_gear_pair_geometry *g)
{
    gd_gear_pair_geometry_init(g);
    g->internal = 1;
    g->normal_module = 2e-3;
    g->face_width = 0.02;
    g->gear[0].teeth = 30;
    g->gear[0].bore_radius = 0.01;
    g->gear[1].teeth = 84;
}

TEST(json_matches_library)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char args[300];
    snprintf(args, sizeof args, "mesh-stiffness %s --points 90", EXAMPLE);
    cJSON *o = run_json_args(&s, args);
    REQUIRE(o);
    gd_gear_pair_geometry g;
    example_pair(&g);
    gd_tvms_options opt;
    gd_tvms_options_init(&opt);
    opt.points = 90;
    gd_tvms_result *r = NULL;
    gd_error err;
    REQUIRE(gd_tvms_compute(&g, &opt, &r, &err) == GD_OK);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(o, "internal")));
    /* printed with cJSON's 17 digits: equal to 1e-14 */
    CHECK_REL(jnum(o, "contact_ratio_transverse"), r->geom.contact_ratio_transverse, 1e-14);
    CHECK_REL(jnum(o, "center_distance_m"), 0.054, 1e-14); /* (84 - 30) 2 mm / 2 */
    CHECK_REL(jnum(o, "stiffness_mean"), r->mean, 1e-14);
    CHECK_REL(jnum(o, "trochoid_margin_rad"), r->geom.trochoid_margin, 1e-14);
    CHECK_REL(jnum(o, "path_of_contact_m"), r->geom.contact_length, 1e-14);
    const cJSON *tip = cJSON_GetObjectItemCaseSensitive(o, "tip_radius_m");
    const cJSON *root = cJSON_GetObjectItemCaseSensitive(o, "root_radius_m");
    /* the ring's tip circle inside its reference circle (84 mm), the root outside */
    CHECK_REL(cJSON_GetArrayItem(tip, 1)->valuedouble, 0.082, 1e-14);
    CHECK_REL(cJSON_GetArrayItem(root, 1)->valuedouble, 0.0865, 1e-14);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(o, "stiffness")) == 90);
    gd_tvms_free(r);
    cJSON_Delete(o);
    /* the text form names the pair internal */
    run_result t;
    CHECK(run(&s, &t, "mesh-stiffness %s --points 30", EXAMPLE) == 0);
    CHECK(contains(t.out, "(internal: the driven gear is a ring)"));
    CHECK(contains(t.out, "trochoid margin"));
    CHECK(contains(t.out, "contact ratio    transverse 1.9306"));
    run_free(&t);
    scratch_close(&s);
}

TEST(helix_and_contact_analysis)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char args[300];
    snprintf(args, sizeof args, "mesh-stiffness %s --points 60 --helix-angle '15 deg' --slices 20",
             EXAMPLE);
    cJSON *o = run_json_args(&s, args);
    REQUIRE(o);
    /* face contact ratio b sin(beta) / (pi m_n) */
    CHECK_REL(jnum(o, "contact_ratio_face"), 0.02 * sin(15 * M_PI / 180) / (M_PI * 2e-3), 1e-12);
    cJSON_Delete(o);
    /* loaded contact analysis without modifications: the approach is F / k(theta) */
    snprintf(args, sizeof args, "mesh-stiffness %s --points 40 --load '200 N m'", EXAMPLE);
    o = run_json_args(&s, args);
    REQUIRE(o);
    const cJSON *ste = cJSON_GetObjectItemCaseSensitive(o, "ste");
    const cJSON *k = cJSON_GetObjectItemCaseSensitive(o, "stiffness");
    double F = jnum(o, "normal_force_N");
    REQUIRE(cJSON_GetArraySize(ste) == 40 && cJSON_GetArraySize(k) == 40 && F > 0);
    CHECK_REL(F, 200 / (0.084 * cos(20 * M_PI / 180) * 30 / 84), 1e-12); /* T / r_b1 */
    for (int i = 0; i < 40; i++)
        CHECK_REL(cJSON_GetArrayItem(ste, i)->valuedouble,
                  F / cJSON_GetArrayItem(k, i)->valuedouble, 1e-9);
    cJSON_Delete(o);
    scratch_close(&s);
}

TEST(errors_located_nothing_written)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char *base = read_file(GD_SOURCE_DIR "/examples/ring_planet_pair.yaml");
    REQUIRE(base);
    static const struct {
        const char *from, *to, *w1, *w2;
    } cases[] = {
        /* a 33-tooth ring: its tips have no involute */
        {"driven: {teeth: 84,", "driven: {teeth: 33,", "involute interference",
         "meshes[0].geometry.driven"},
        /* 8 teeth difference: trochoid interference */
        {"driven: {teeth: 84,", "driven: {teeth: 38,", "trochoid interference",
         "meshes[0].geometry.driven.teeth"},
        {"driven: {teeth: 84,", "driven: {teeth: 28,", "not more than the 30",
         "meshes[0].geometry.driven.teeth"},
        {"      internal: true", "      internal: maybe", "not true or false", "geometry.internal"},
        {"face_width: 20 mm", "face_width: 20 mm\n      center_distance: 54.1 mm", "jam",
         "meshes[0].geometry.center_distance"},
        {"driven: {teeth: 84, material: steel}",
         "driven: {teeth: 84, material: steel, modifications: {tip_relief: {amount: 5 um, "
         "start_diameter: 160 mm}}}",
         "not outside its tip", "driven.modifications.tip_relief.start_diameter"},
        {"driven: {teeth: 84, material: steel}",
         "driven: {teeth: 84, material: steel, bore_radius: 87 mm}", "rim", "driven.bore_radius"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *at = strstr(base, cases[i].from);
        REQUIRE(at);
        char text[4096];
        snprintf(text, sizeof text, "%.*s%s%s", (int)(at - base), base, cases[i].to,
                 at + strlen(cases[i].from));
        char path[300], args[400];
        snprintf(path, sizeof path, "%s/bad.yaml", s.dir);
        write_file(path, text);
        snprintf(args, sizeof args, "mesh-stiffness '%s'", path);
        if (!run_fails_cleanly(&s, args, cases[i].w1, cases[i].w2)) {
            fprintf(stderr, "  case %zu\n", i);
            CHECK(0);
        }
        run_result r;
        run(&s, &r, "mesh-stiffness '%s'", path);
        CHECK(contains(r.err, "bad.yaml:")); /* file and line */
        run_free(&r);
    }
    free(base);
    scratch_close(&s);
}

/* A model's meshes couple external gears: `internal: true` there is refused, located. */
TEST(model_mesh_refuses_internal)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char *base = read_file(GD_SOURCE_DIR "/examples/helical_two_stage.yaml");
    REQUIRE(base);
    const char *at = strstr(base, "normal_module:");
    if (!at) {
        fprintf(stderr, "  examples/helical_two_stage.yaml has no geometry\n");
        free(base);
        scratch_close(&s);
        return;
    }
    /* the indentation of the geometry keys */
    const char *line = at;
    while (line > base && line[-1] != '\n')
        line--;
    char text[1 << 16];
    snprintf(text, sizeof text, "%.*sinternal: true\n%s", (int)(at - base), base, line);
    char path[300];
    snprintf(path, sizeof path, "%s/model.yaml", s.dir);
    write_file(path, text);
    run_result r;
    CHECK(run(&s, &r, "modal '%s'", path) == 2);
    CHECK(contains(r.err, "internal pairs are not supported here"));
    CHECK(contains(r.err, "model.yaml:"));
    run_free(&r);
    free(base);
    scratch_close(&s);
}

RUN_TESTS(T(json_matches_library), T(helix_and_contact_analysis), T(errors_located_nothing_written),
          T(model_mesh_refuses_internal))
