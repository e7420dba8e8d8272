/* gd_gear_pair_load: a gear pair's geometry and mesh-stiffness options read from a mesh
 * entry of a file, picked by name or as the first with a geometry, with overrides, and
 * its errors located in the file or at the override. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geardyn/model_file.h"
#include "harness.h"

#define PAIR1 "examples/helical_pair1.yaml"

/* A model file with a plain mesh first and an unnamed mesh with a geometry second. */
static const char TWO_MESHES[] = "materials:\n"
                                 "  steel: {density: 7800, E: 2.06e11, poisson: 0.3}\n"
                                 "meshes:\n"
                                 "  - {name: plain, stiffness: 2e8}\n"
                                 "  - geometry:\n"
                                 "      normal_module: 3 mm\n"
                                 "      face_width: 25 mm\n"
                                 "      driver: {teeth: 25, material: steel}\n"
                                 "      driven: {teeth: 40, material: steel}\n";

static void show_error(const gd_error *e)
{
    fprintf(stderr, "    got: status %d, '%s':%d:%d, field '%s'\n    message: %s\n    hint: %s\n",
            (int)e->status, e->file, e->line, e->column, e->field, e->message, e->hint);
}

TEST(first_mesh_with_a_geometry_and_its_options)
{
    gd_gear_pair_geometry g;
    gd_tvms_options t;
    char name[80];
    gd_error e;
    gd_status st = gd_gear_pair_load(PAIR1, NULL, NULL, &g, &t, name, sizeof name, &e);
    if (st) show_error(&e);
    REQUIRE(st == GD_OK);
    CHECK_STR(name, "pair1");
    CHECK(g.gear[0].teeth == 52 && g.gear[1].teeth == 72);
    CHECK_REL(g.helix_angle, 20 * M_PI / 180, 1e-15);
    CHECK_REL(g.normal_module, 1.75e-3, 1e-15);
    CHECK(g.hand == -1);
    CHECK(t.method == GD_TVMS_ENERGY && t.points == 360 && t.slices == 50 && t.cycles == 1);
    /* tvms and the name may be left out */
    CHECK(gd_gear_pair_load(PAIR1, "pair1", NULL, &g, NULL, NULL, 0, &e) == GD_OK);
}

TEST(overrides_change_the_geometry)
{
    static const char *const set[] = {"meshes.pair1.geometry.helix_angle=15deg",
                                      "meshes.pair1.stiffness.points=90"};
    gd_load_options opt = {2, set};
    gd_gear_pair_geometry g;
    gd_tvms_options t;
    gd_error e;
    REQUIRE(gd_gear_pair_load(PAIR1, NULL, &opt, &g, &t, NULL, 0, &e) == GD_OK);
    CHECK_REL(g.helix_angle, 0.2617993877991494, 1e-15);
    CHECK(t.points == 90);
}

TEST(unnamed_mesh_is_named_by_its_path)
{
    char dir[] = "/tmp/gd_gear_pair_XXXXXX", path[64];
    REQUIRE(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/two.yaml", dir);
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs(TWO_MESHES, f);
    fclose(f);
    gd_gear_pair_geometry g;
    char name[80];
    gd_error e;
    CHECK(gd_gear_pair_load(path, NULL, NULL, &g, NULL, name, sizeof name, &e) == GD_OK);
    CHECK_STR(name, "meshes[1]");
    CHECK(g.gear[0].teeth == 25);
    /* the plain mesh, by name: no geometry */
    CHECK(gd_gear_pair_load(path, "plain", NULL, &g, NULL, name, sizeof name, &e) == GD_EINPUT);
    CHECK_STR(e.field, "meshes[0].geometry");
    CHECK(strstr(e.message, "no geometry") != NULL);
    CHECK(e.line == 4);
    CHECK_STR(name, "");
    unlink(path);
    rmdir(dir);
}

TEST(errors)
{
    gd_gear_pair_geometry g;
    gd_error e;
    CHECK(gd_gear_pair_load(PAIR1, "nope", NULL, &g, NULL, NULL, 0, &e) == GD_EINPUT);
    CHECK_STR(e.field, "--mesh");
    CHECK_STR(e.message, "no mesh named 'nope'");
    CHECK_STR(e.hint, "known meshes: 'pair1'");
    CHECK_STR(e.file, PAIR1);
    CHECK(gd_gear_pair_load("no/such.yaml", NULL, NULL, &g, NULL, NULL, 0, &e) == GD_EIO);
    /* a value an override wrote: the error names it */
    static const char *const neg[] = {"meshes.0.geometry.face_width=-20mm"};
    gd_load_options opt = {1, neg};
    CHECK(gd_gear_pair_load(PAIR1, NULL, &opt, &g, NULL, NULL, 0, &e) == GD_EINPUT);
    CHECK_STR(e.file, "--set meshes.0.geometry.face_width=-20mm");
    CHECK_STR(e.field, "meshes[0].geometry.face_width");
    CHECK(e.line == 0);
    /* found when deriving the geometry, still at the override */
    static const char *const tip[] = {"meshes.pair1.geometry.driver.tip_radius=40mm"};
    opt.set = tip;
    CHECK(gd_gear_pair_load(PAIR1, NULL, &opt, &g, NULL, NULL, 0, &e) == GD_EINPUT);
    CHECK_STR(e.file, "--set meshes.pair1.geometry.driver.tip_radius=40mm");
    CHECK_STR(e.field, "meshes[0].geometry.driver.tip_radius");
    static const char *const none[] = {"meshes.pear1.geometry.helix_angle=0"};
    opt.set = none;
    CHECK(gd_gear_pair_load(PAIR1, NULL, &opt, &g, NULL, NULL, 0, &e) == GD_EINPUT);
    CHECK_STR(e.message, "no mesh named 'pear1' in 'meshes'");
    CHECK_STR(e.hint, "have: pair1 (or an index from 0 to 0)");
}

RUN_TESTS(T(first_mesh_with_a_geometry_and_its_options), T(overrides_change_the_geometry),
          T(unnamed_mesh_is_named_by_its_path), T(errors))
