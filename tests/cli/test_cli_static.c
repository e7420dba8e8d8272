/* geardyn static: the rig's mesh force and reactions from the torque balance, the
 * two-stage helical example's motor torque, --out and --plot files, and the errors. */
#include "cli_support.h"
#include "harness.h"

#define RIG "examples/rig2018.yaml"
#define HELICAL "examples/helical_two_stage.yaml"

static const cJSON *item(const cJSON *o, const char *key, int i)
{
    return cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, key), i);
}

TEST(rig_torque_balance)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "static " RIG " --torque 20N*m --no-gravity");
    REQUIRE(o);
    /* F = T / rb1 (the output held), its reaction T rb2 / rb1, each bearing F / 2 */
    const cJSON *m = item(o, "meshes", 0);
    CHECK_REL(jnum(m, "force_N"), 20 / 0.048, 1e-9);
    CHECK_REL(jnum(m, "face_width_m"), 0.02, 1e-12);
    /* gears at mid-span of symmetric shafts: no tilt, no misalignment */
    CHECK(fabs(jnum(m, "f_sh_m")) < 1e-15);
    const cJSON *h = item(o, "holds", 0);
    CHECK_STR(jstr(h, "node"), "brg_n2");
    CHECK_STR(jstr(h, "kind"), "torque");
    CHECK_REL(fabs(jnum(h, "reaction")), 20 * 32.0 / 48, 1e-9);
    for (int b = 0; b < 4; b++) {
        const cJSON *f = cJSON_GetObjectItemCaseSensitive(item(o, "bearings", b), "force_N");
        double fx = cJSON_GetArrayItem(f, 0)->valuedouble,
               fy = cJSON_GetArrayItem(f, 1)->valuedouble;
        CHECK_REL(hypot(fx, fy), 10 / 0.048, 1e-9);
    }
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(o, "nodes")) == 34);
    /* the rig's gravity (9.81 down -y): the driving shaft's bearings carry its weight
       more, shaft (steel, 25.4 mm, 0.5 m) and 1.15 kg gear */
    cJSON *g = run_json_args(&s, "static " RIG " --torque 20N*m");
    REQUIRE(g);
    double dy = 0;
    for (int b = 0; b < 2; b++) {
        const cJSON *f0 = cJSON_GetObjectItemCaseSensitive(item(o, "bearings", b), "force_N");
        const cJSON *f1 = cJSON_GetObjectItemCaseSensitive(item(g, "bearings", b), "force_N");
        dy += cJSON_GetArrayItem(f1, 1)->valuedouble - cJSON_GetArrayItem(f0, 1)->valuedouble;
    }
    CHECK_REL(dy, 9.81 * (7800 * M_PI / 4 * 0.0254 * 0.0254 * 0.5 + 1.15), 1e-9);
    cJSON_Delete(g);
    cJSON_Delete(o);
    scratch_close(&s);
}

TEST(helical_motor_torque_and_misalignment)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "static " HELICAL);
    REQUIRE(o);
    /* the prescribed input reacts the 50 N m load through both ratios */
    const cJSON *h = item(o, "holds", 0);
    CHECK_STR(jstr(h, "kind"), "prescribed");
    CHECK_REL(fabs(jnum(h, "reaction")), 50.0 * 52 * 22 / (72.0 * 79), 1e-9);
    /* off-centre gears: a misalignment of microns, f_sh = b x tilt in the plane */
    for (int k = 0; k < 2; k++) {
        const cJSON *m = item(o, "meshes", k);
        CHECK_REL(jnum(m, "f_sh_m"), 0.02 * jnum(m, "tilt_in_plane_rad"), 1e-9);
        CHECK(fabs(jnum(m, "f_sh_m")) > 1e-7 && fabs(jnum(m, "f_sh_m")) < 1e-4);
        CHECK(jnum(m, "axial_N") > 0);
    }
    cJSON_Delete(o);
    scratch_close(&s);
}

TEST(out_and_plot)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "static " RIG " --torque 20 --out '%s/o' --plot '%s/p.svg'", s.dir, s.dir);
    CHECK(r.code == 0);
    if (r.code) show(&r);
    CHECK(contains(r.out, "bearing reactions"));
    run_free(&r);
    char p[300];
    const char *files[] = {"static_nodes.csv", "static_bearings.csv", "static_meshes.csv",
                           "static_holds.csv"};
    for (int i = 0; i < 4; i++) {
        snprintf(p, sizeof p, "%s/o/%s", s.dir, files[i]);
        CHECK(file_exists(p));
    }
    snprintf(p, sizeof p, "%s/o/static_nodes.csv", s.dir);
    char *t = read_file(p);
    CHECK(count_lines(t) == 35);
    free(t);
    snprintf(p, sizeof p, "%s/o", s.dir);
    CHECK(count_entries(p) == 4);
    snprintf(p, sizeof p, "%s/p.svg", s.dir);
    t = read_file(p);
    CHECK(contains(t, "<svg") && contains(t, "deflection x") && contains(t, "bearing reactions"));
    free(t);
    scratch_close(&s);
}

TEST(errors_exit_2)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[256], args[512];
    /* a shaft nothing holds axially */
    snprintf(path, sizeof path, "%s/free.yaml", s.dir);
    write_file(path, "dofs: [x, y, z, rx, ry, rz]\n"
                     "materials: {steel: {density: 7800, E: 2.1e11, poisson: 0.3}}\n"
                     "shafts:\n"
                     "  - name: s\n"
                     "    material: steel\n"
                     "    sections: [{length: 0.4, outer_diameter: 30 mm, elements: 4}]\n"
                     "    nodes: [{name: a, at: 0}, {name: b, at: 0.4}]\n"
                     "bearings:\n"
                     "  - {name: A, node: a, k: 1e8}\n"
                     "  - {name: B, node: b, k: 1e8}\n");
    snprintf(args, sizeof args, "static '%s'", path);
    CHECK(run_fails_cleanly(&s, args, "free.yaml:4:5: shafts[0]", "axial translation z"));
    snprintf(path, sizeof path, "%s/grav.yaml", s.dir);
    write_file(path, "shafts: [{name: s, nodes: [{name: a}]}]\n"
                     "disks: [{node: a, mass: 1}]\n"
                     "gravity: {direction: [0, -1, 0], g: -9.81}\n");
    snprintf(args, sizeof args, "static '%s'", path);
    CHECK(run_fails_cleanly(&s, args, "grav.yaml:3:", "gravity"));
    CHECK(run_fails_cleanly(&s, "static " RIG " --hold nosuch", "--hold", "nosuch"));
    CHECK(run_fails_cleanly(&s, "static " RIG " --torque 3kg", "--torque", NULL));
    scratch_close(&s);
}

/* A rotor held by its journal bearings alone: the laws' records in the JSON and in
 * static_laws.csv, the vertical forces adding up to the weight (40 kg), and at rest
 * (no speed) an input error naming the laws. */
TEST(journal_rotor_on_its_laws)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "static examples/journal_rotor.yaml --speed 1000");
    REQUIRE(o);
    double fy = 0;
    for (int l = 0; l < 2; l++) {
        const cJSON *law = item(o, "laws", l);
        REQUIRE(law);
        CHECK_STR(jstr(law, "type"), "journal_bearing");
        const cJSON *rec = cJSON_GetObjectItemCaseSensitive(law, "records");
        fy += jnum(rec, "fy");
        /* Ocvirk's short bearing at this load and speed: eccentricity 0.5526 (the
           library test compares the state with the linear analyses' one to 1e-9) */
        CHECK(fabs(jnum(rec, "ecc") - 0.5526) < 1e-4);
    }
    CHECK_REL(fy, 40 * 9.81, 1e-9);
    cJSON_Delete(o);
    char path[600];
    run_result r;
    CHECK(run(&s, &r, "static examples/journal_rotor.yaml --speed 1000 --out '%s/o'", s.dir) == 0);
    run_free(&r);
    snprintf(path, sizeof path, "%s/o/static_laws.csv", s.dir);
    char *csv = read_file(path);
    REQUIRE(csv);
    CHECK(strstr(csv, "law,type,record,value,unit\nleft_bearing,journal_bearing,fx,") == csv);
    CHECK(strstr(csv, "right_bearing,journal_bearing,ecc,0.5525") != NULL);
    free(csv);
    CHECK(run_fails_cleanly(&s, "static examples/journal_rotor.yaml",
                            "journal_rotor.yaml:24:", "carries nothing at 0 rad/s"));
    scratch_close(&s);
}

RUN_TESTS(T(rig_torque_balance), T(helical_motor_torque_and_misalignment), T(out_and_plot),
          T(errors_exit_2), T(journal_rotor_on_its_laws))
