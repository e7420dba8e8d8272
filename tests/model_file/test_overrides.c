/* Overrides (`--set PATH=VALUE`) applied to a model file before validation, through
 * gd_model_load_opts / gd_model_load_string_opts: paths by key, index, name and `*`,
 * units, added keys, flow values, the order of several overrides, and every error:
 * nothing matched (message, field and hint), malformed assignments, and values the
 * model rejects, which name the override instead of a line of the file. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/model_file.h"
#include "harness.h"

#define CHEN "examples/chen1998_gear_pair.yaml"
#define RIG "examples/rig2018.yaml"

/* Three bearings given by kxx/kyy, two shafts of which one has sections, one mesh
 * without damping. Lines are numbered in the comments. */
static const char MODEL[] = "dofs: [x, y, rz]\n"                                     /* 1 */
                            "materials:\n"                                           /* 2 */
                            "  steel: {density: 7800, E: 2e11, poisson: 0.3}\n"      /* 3 */
                            "shafts:\n"                                              /* 4 */
                            "  - name: a\n"                                          /* 5 */
                            "    material: steel\n"                                  /* 6 */
                            "    sections: [{length: 0.2, outer_diameter: 20 mm},\n" /* 7 */
                            "               {length: 0.1, outer_diameter: 20 mm}]\n" /* 8 */
                            "    nodes: [{name: p, at: 0.1}, {name: a0, at: 0},\n"   /* 9 */
                            "            {name: a1, at: 0.3}]\n"                     /* 10 */
                            "  - name: b\n"                                          /* 11 */
                            "    nodes: [{name: g}]\n"                               /* 12 */
                            "disks:\n"                                               /* 13 */
                            "  - {node: p, mass: 1, polar_inertia: 1e-3}\n"          /* 14 */
                            "  - {node: g, mass: 2, polar_inertia: 4e-3}\n"          /* 15 */
                            "bearings:\n"                                            /* 16 */
                            "  - {name: b1, node: a0, kxx: 1e8, kyy: 1e8}\n"         /* 17 */
                            "  - {name: b2, node: a1, kxx: 1e8, kyy: 3e8}\n"         /* 18 */
                            "  - {name: b3, node: g, kxx: 5e7, kyy: 5e7, k_torsion: 1e4}\n"
                            "meshes:\n"                         /* 20 */
                            "  - name: m\n"                     /* 21 */
                            "    driver: p\n"                   /* 22 */
                            "    driven: g\n"                   /* 23 */
                            "    base_radius: [20 mm, 40 mm]\n" /* 24 */
                            "    pressure_angle: 20 deg\n"      /* 25 */
                            "    stiffness: 2e8\n";             /* 26 */

static void show_error(const gd_error *e)
{
    fprintf(stderr, "    got: status %d, '%s':%d:%d, field '%s'\n    message: %s\n    hint: %s\n",
            (int)e->status, e->file, e->line, e->column, e->field, e->message, e->hint);
}

/* MODEL (or the file at path) with n overrides; NULL (and the error shown) on failure. */
static gd_model *load_set(const char *path, int n, const char *const *set, gd_error *e)
{
    gd_load_options opt;
    gd_load_options_init(&opt);
    opt.nset = n;
    opt.set = set;
    gd_model *m = NULL;
    gd_error_clear(e);
    gd_status st = path ? gd_model_load_opts(path, &opt, &m, e)
                        : gd_model_load_string_opts(MODEL, "model.yaml", &opt, &m, e);
    if (st) show_error(e);
    return m;
}

/* An override that must fail with GD_EINPUT located at it: file "--set SET", line 0,
 * the field, and words of the message and hint. */
static void expect_fail(gd_test_state *gd_ts_, int at, const char *set, const char *field,
                        const char *msg, const char *hint)
{
    gd_load_options opt = {1, &set};
    gd_model *m = NULL;
    gd_error e;
    gd_error_clear(&e);
    gd_status st = gd_model_load_string_opts(MODEL, "model.yaml", &opt, &m, &e);
    char file[300];
    snprintf(file, sizeof file, "--set %s", set);
    int ok = st == GD_EINPUT && e.status == GD_EINPUT && !m && !strcmp(e.file, file) &&
             e.line == 0 && (!field || !strcmp(e.field, field)) && strstr(e.message, msg) &&
             (!hint || strstr(e.hint, hint));
    if (!ok) {
        fprintf(stderr, "  %s:%d: override '%s' did not fail as expected\n", __FILE__, at, set);
        show_error(&e);
        gd_ts_->checks_failed++;
    }
    gd_model_free(m);
}
#define EXPECT_FAIL(set, field, msg, hint) expect_fail(gd_ts_, __LINE__, set, field, msg, hint)

TEST(no_overrides_is_the_plain_load)
{
    gd_error e;
    gd_model *m = load_set(NULL, 0, NULL, &e);
    REQUIRE(m);
    CHECK(m->meshes[0].stiffness == 2e8);
    gd_model_free(m);
    gd_model *n = NULL;
    REQUIRE(gd_model_load_opts(CHEN, NULL, &n, &e) == GD_OK); /* opt NULL */
    CHECK(n->meshes[0].stiffness == 34.098e6);
    gd_model_free(n);
}

TEST(by_name_with_units)
{
    static const char *const set[] = {"meshes.m.stiffness=3e8N/m"};
    gd_error e;
    gd_model *m = load_set(NULL, 1, set, &e);
    REQUIRE(m);
    CHECK(m->meshes[0].stiffness == 3e8);
    gd_model_free(m);
    static const char *const spaced[] = {"meshes.mesh.stiffness = 3.5e8 N/m",
                                         "bearings.support_b.c=2 kN*s/m"};
    m = load_set(CHEN, 2, spaced, &e);
    REQUIRE(m);
    CHECK(m->meshes[0].stiffness == 3.5e8);
    CHECK(m->bearings[1].coeffs.cxx == 2000 && m->bearings[1].coeffs.cyy == 2000);
    CHECK(m->bearings[0].coeffs.cxx == 714.18); /* the other bearing untouched */
    gd_model_free(m);
}

TEST(helix_angle_in_degrees)
{
    static const char *const set[] = {"meshes.m.helix_angle=15deg"};
    gd_error e;
    gd_model *m = load_set(NULL, 1, set, &e);
    REQUIRE(m);
    CHECK_REL(m->meshes[0].helix_angle, 0.2617993877991494, 1e-15);
    gd_model_free(m);
}

TEST(by_index)
{
    static const char *const set[] = {"shafts.0.sections.1.length=0.3"};
    gd_error e;
    gd_model *m = load_set(RIG, 1, set, &e);
    REQUIRE(m);
    CHECK(m->shafts[0].sections[1].length == 0.3);
    CHECK(m->shafts[0].sections[0].length == 0.25);
    CHECK(m->shafts[1].sections[1].length == 0.25);
    gd_shaft_summary ss;
    gd_model_shaft_summary(m, 0, &ss);
    CHECK_REL(ss.length, 0.55, 1e-15);
    gd_model_free(m);
    /* names and indices mix: shaft by name, section by index */
    static const char *const mixed[] = {"shafts.driven.sections.0.outer_diameter=30mm"};
    m = load_set(RIG, 1, mixed, &e);
    REQUIRE(m);
    CHECK_REL(m->shafts[1].sections[0].outer_diameter, 0.03, 1e-15);
    CHECK(m->shafts[0].sections[0].outer_diameter == 0.0254);
    gd_model_free(m);
}

TEST(wildcard_over_every_bearing)
{
    static const char *const set[] = {"bearings.*.kxx=2e8"};
    gd_error e;
    gd_model *m = load_set(NULL, 1, set, &e);
    REQUIRE(m);
    REQUIRE(m->nbearings == 3);
    for (int i = 0; i < 3; i++)
        CHECK(m->bearings[i].coeffs.kxx == 2e8);
    CHECK(m->bearings[0].coeffs.kyy == 1e8);
    CHECK(m->bearings[1].coeffs.kyy == 3e8);
    CHECK(m->bearings[2].coeffs.kyy == 5e7);
    gd_model_free(m);
}

TEST(wildcard_skips_items_without_the_rest_of_the_path)
{
    /* shaft b has no sections: only a's change */
    static const char *const set[] = {"shafts.*.sections.*.outer_diameter=25mm"};
    gd_error e;
    gd_model *m = load_set(NULL, 1, set, &e);
    REQUIRE(m);
    CHECK_REL(m->shafts[0].sections[0].outer_diameter, 0.025, 1e-15);
    CHECK_REL(m->shafts[0].sections[1].outer_diameter, 0.025, 1e-15);
    CHECK(m->shafts[1].nsections == 0);
    gd_model_free(m);
}

TEST(a_missing_last_key_is_added)
{
    static const char *const set[] = {"meshes.m.damping=500", "speed=3000rpm"};
    gd_error e;
    gd_model *m = load_set(NULL, 2, set, &e);
    REQUIRE(m);
    CHECK(m->meshes[0].damping == 500);
    CHECK_REL(m->speed, 3000 * M_PI / 30, 1e-15);
    gd_model_free(m);
}

TEST(later_overrides_see_earlier_ones)
{
    static const char *const set[] = {"meshes.m.damping=500", "meshes.m.damping=700",
                                      "meshes.m.name=gears", "meshes.gears.stiffness=1e8"};
    gd_error e;
    gd_model *m = load_set(NULL, 4, set, &e);
    REQUIRE(m);
    CHECK(m->meshes[0].damping == 700);
    CHECK_STR(m->meshes[0].name, "gears");
    CHECK(m->meshes[0].stiffness == 1e8);
    gd_model_free(m);
}

TEST(flow_and_quoted_values)
{
    static const char *const set[] = {"meshes.m.base_radius=[25 mm, 50mm]",
                                      "meshes.m.name='gear mesh'",
                                      "bearings.b3={node: g, k: 7e7, k_torsion: 2e4}"};
    gd_error e;
    gd_model *m = load_set(NULL, 3, set, &e);
    REQUIRE(m);
    CHECK_REL(m->meshes[0].base_radius[0], 0.025, 1e-15);
    CHECK_REL(m->meshes[0].base_radius[1], 0.05, 1e-15);
    CHECK_STR(m->meshes[0].name, "gear mesh");
    CHECK(m->bearings[2].coeffs.kxx == 7e7 && m->bearings[2].coeffs.kyy == 7e7);
    CHECK(m->bearings[2].coeffs.ktorsion == 2e4);
    CHECK_STR(m->bearings[2].name, "bearing3"); /* the map replaced: the default name */
    gd_model_free(m);
}

TEST(nothing_matched)
{
    EXPECT_FAIL("meshes.msh.stiffness=3e8", "meshes.msh", "no mesh named 'msh' in 'meshes'",
                "have: m (or an index from 0 to 0)");
    EXPECT_FAIL("bearings.b9.kxx=1", "bearings.b9", "no bearing named 'b9' in 'bearings'",
                "have: b1, b2, b3 (or an index from 0 to 2)");
    EXPECT_FAIL("bearings.3.kxx=1", "bearings.3", "no bearing at index 3 in 'bearings' (it has 3)",
                "have: b1, b2, b3");
    EXPECT_FAIL("meshes.m.geometry.helix_angle=0", "meshes.m.geometry",
                "no key 'geometry' in 'meshes.m'",
                "have: name, driver, driven, base_radius, pressure_angle, stiffness");
    EXPECT_FAIL("mesh.m.stiffness=1", "mesh", "no key 'mesh' at the top level",
                "have: dofs, materials, shafts, disks, bearings, meshes");
    EXPECT_FAIL("shafts.a.sections.0.length.x=1", "shafts.a.sections.0.length.x",
                "'shafts.a.sections.0.length' is a single value (0.2), not a map or list",
                "end the path at 'shafts.a.sections.0.length'");
    EXPECT_FAIL("shafts.*.sections.*.length.x=1", "shafts.a.sections.0.length.x",
                "is a single value", NULL);
    EXPECT_FAIL("shafts.b.sections.0.length=1", "shafts.b.sections", "no key 'sections' in",
                "have: name, nodes");
    EXPECT_FAIL("shafts.a.nodes.q.at=0", "shafts.a.nodes.q", "no node named 'q'",
                "have: p, a0, a1");
    EXPECT_FAIL("materials.*.x.y=1", "materials.steel.x", "no key 'x' in 'materials.steel'",
                "have: density, E, poisson");
}

TEST(malformed_assignments)
{
    EXPECT_FAIL("meshes.m.stiffness", "", "no '=' between the path and the value",
                "write PATH=VALUE");
    EXPECT_FAIL("=3e8", "", "empty path", "separated by single dots");
    EXPECT_FAIL("  = 1", "", "empty path", NULL);
    EXPECT_FAIL("meshes..stiffness=1", "meshes..stiffness", "empty segment 2 in the path", NULL);
    EXPECT_FAIL(".meshes=1", ".meshes", "empty segment 1 in the path", NULL);
    EXPECT_FAIL("meshes.=1", "meshes.", "empty segment 2 in the path", NULL);
    EXPECT_FAIL("meshes.m.base_radius=[1 mm, 2 mm", "",
                "in the value: YAML syntax error: did not find expected ',' or ']'", NULL);
}

TEST(rejected_values_name_the_override)
{
    EXPECT_FAIL("disks.0.mass=-2", "disks[0].mass", "must be positive (got -2)",
                "greater than zero");
    EXPECT_FAIL("meshes.m.stiffness=-1", "meshes[0].stiffness", "must be positive (got -1)", NULL);
    EXPECT_FAIL("meshes.m.stiffness=3e8 kg", "meshes[0].stiffness", "is not a matching quantity",
                NULL);
    EXPECT_FAIL("meshes.m.dampng=5", "meshes[0].dampng", "unknown key 'dampng'",
                "did you mean 'damping'?");
    EXPECT_FAIL("meshes.*.driver=nowhere", "meshes[0].driver", "unknown node 'nowhere'", NULL);
    EXPECT_FAIL("meshes.m.base_radius=[25 mm]", "meshes[0].base_radius", "", NULL);
    EXPECT_FAIL("shafts.a.sections.1={length: 0.1}", "shafts[0].sections[1].outer_diameter",
                "required key 'outer_diameter' is missing", NULL);
}

TEST(errors_elsewhere_keep_their_line)
{
    /* the override is fine; the mistake is in the file, and the error says where */
    static const char BAD[] = "shafts: [{name: a, nodes: [{name: n}]}]\n"
                              "disks: [{node: n, mass: -1}]\n";
    static const char *const set[] = {"shafts.a.name=b"};
    gd_load_options opt = {1, set};
    gd_model *m = NULL;
    gd_error e;
    gd_error_clear(&e);
    CHECK(gd_model_load_string_opts(BAD, "bad.yaml", &opt, &m, &e) == GD_EINPUT);
    CHECK_STR(e.file, "bad.yaml");
    CHECK(e.line == 2 && e.column > 0);
    CHECK_STR(e.field, "disks[0].mass");
    CHECK(m == NULL);
    /* a conflict with a key of the file is located where the model locates it: here at
     * the file's kxx, which the added k contradicts */
    static const char *const k[] = {"bearings.*.k=1e8"};
    opt.set = k;
    CHECK(gd_model_load_string_opts(MODEL, "model.yaml", &opt, &m, &e) == GD_EINPUT);
    CHECK_STR(e.file, "model.yaml");
    CHECK(e.line == 17);
    CHECK_STR(e.message, "'kxx' given together with 'k'");
}

TEST(bad_options)
{
    gd_load_options opt = {-1, NULL};
    gd_model *m = NULL;
    gd_error e;
    CHECK(gd_model_load_string_opts(MODEL, "model.yaml", &opt, &m, &e) == GD_EINPUT);
    CHECK(strstr(e.message, "bad load options") != NULL);
    const char *holes[] = {"meshes.m.damping=1", NULL};
    opt.nset = 2;
    opt.set = holes;
    CHECK(gd_model_load_string_opts(MODEL, "model.yaml", &opt, &m, &e) == GD_EINPUT);
    CHECK(strstr(e.message, "override 1 is NULL") != NULL);
    CHECK(m == NULL);
    /* a file that does not load is reported before any override */
    static const char *const set[] = {"meshes.m.damping=1"};
    opt.nset = 1;
    opt.set = set;
    CHECK(gd_model_load_opts("no/such/model.yaml", &opt, &m, &e) == GD_EIO);
    CHECK_STR(e.file, "no/such/model.yaml");
}

RUN_TESTS(T(no_overrides_is_the_plain_load), T(by_name_with_units), T(helix_angle_in_degrees),
          T(by_index), T(wildcard_over_every_bearing),
          T(wildcard_skips_items_without_the_rest_of_the_path), T(a_missing_last_key_is_added),
          T(later_overrides_see_earlier_ones), T(flow_and_quoted_values), T(nothing_matched),
          T(malformed_assignments), T(rejected_values_name_the_override),
          T(errors_elsewhere_keep_their_line), T(bad_options))
