/* The sweep commands (campbell, frf, unbalance) run as a program (GD_CLI_PATH) from the
 * source folder: the JSON names other tools rely on, options, output files and every
 * error path (exit 2, nothing written).
 * Temporary files live in a mkdtemp folder under /tmp that each test removes. */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cli_support.h"
#include "harness.h"

#define KUMAR_COUPLED "examples/kumar2011_coupled.yaml"
#define KUMAR_TORSIONAL "examples/kumar2011_torsional.yaml"
#define CHEN "examples/chen1998_gear_pair.yaml"
#define RIG "examples/rig2018.yaml"

/* ---- running the program ---- */

/* scratch folders, running geardyn, reading output: tests/cli_support.h */

static const cJSON *jget(const cJSON *o, const char *k)
{
    return cJSON_GetObjectItemCaseSensitive(o, k);
}

/* ---- campbell ---- */

TEST(campbell_json_names_and_values)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "campbell %s --speeds 0:6000rpm:13 --modes 4 --orders 2 --json", RIG);
    if (r.code) show(&r);
    REQUIRE(r.code == 0);
    cJSON *j = cJSON_Parse(r.out);
    REQUIRE(j);
    const cJSON *sp = jget(j, "speeds_rad_s"), *modes = jget(j, "modes"),
                *cs = jget(j, "critical_speeds");
    REQUIRE(cJSON_GetArraySize(sp) == 13);
    CHECK_REL(cJSON_GetArrayItem(sp, 12)->valuedouble, 6000 * M_PI / 30, 1e-12);
    REQUIRE(cJSON_GetArraySize(modes) == 4);
    const cJSON *m0 = cJSON_GetArrayItem(modes, 0);
    CHECK(jnum(m0, "id") == 1);
    CHECK_STR(jstr(m0, "dominant_motion"), "lateral");
    CHECK(jstr(m0, "whirl")[0]);
    CHECK(cJSON_GetArraySize(jget(m0, "frequency_hz")) == 13);
    CHECK(cJSON_GetArraySize(jget(m0, "damping_ratio")) == 13);
    CHECK(cJSON_GetArraySize(jget(m0, "log_decrement")) == 13);
    CHECK_REL(cJSON_GetArrayItem(jget(m0, "frequency_hz"), 0)->valuedouble, 126.53,
              1e-3); /* MMT Table 5 */
    REQUIRE(cJSON_GetArraySize(cs) > 0);
    const cJSON *c0 = cJSON_GetArrayItem(cs, 0);
    CHECK(jnum(c0, "mode") >= 1);
    CHECK(jstr(c0, "order")[0]);
    CHECK(jnum(c0, "speed_rpm") > 0 && jnum(c0, "frequency_hz") > 0);
    CHECK(cJSON_IsNull(jget(j, "instability_onset_rpm")));
    cJSON_Delete(j);
    run_free(&r);
    /* the table */
    run(&s, &r, "campbell %s --speeds 0:3000rpm:4 --modes 2", RIG);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "critical speeds"));
    CHECK(contains(r.out, "stable over the whole speed range"));
    CHECK(contains(r.out, "mode1"));
    run_free(&r);
    scratch_close(&s);
}

TEST(campbell_out_csv_long_form)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "campbell %s --speeds 0:1000:5 --modes 3 --method sparse --threads 2 --out '%s/o'",
        RIG, s.dir);
    if (r.code) show(&r);
    REQUIRE(r.code == 0);
    char p[300];
    snprintf(p, sizeof p, "%s/o/campbell.csv", s.dir);
    char *csv = read_file(p);
    REQUIRE(csv);
    CHECK(!strncmp(csv,
                   "speed_rad_s,speed_rpm,mode,frequency_hz,natural_frequency_hz,damping_ratio,"
                   "log_decrement,whirl,dominant_motion\n",
                   100));
    CHECK(count_lines(csv) == 1 + 5 * 3);
    free(csv);
    snprintf(p, sizeof p, "%s/o/critical_speeds.csv", s.dir);
    CHECK(file_exists(p));
    run_free(&r);
    scratch_close(&s);
}

TEST(campbell_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    struct {
        const char *args, *msg;
    } cases[] = {
        {"--speeds 0:100:0", "COUNT is 0"},
        {"--speeds 100:0:5", "below FROM"},
        {"--speeds 0:100", "FROM:TO:COUNT"},
        {"--speeds 0:100furlongs:5", "--speeds"},
        {"--speeds -5:100:5", "zero or more"},
        {"--speeds 0:100:x", "COUNT"},
        {"--speeds 5:5:3", "FROM equals TO"},
        {"--speeds 0:100:3 --modes 0", "--modes"},
        {"--speeds 0:100:3 --orders 2,x", "--orders"},
        {"--speeds 0:100:3 --method fast", "--method"},
        {"--speeds 0:100:3 --threads 0", "--threads"},
        {"--speeds 0:100:3 --shift -3", "--shift"},
        {"--speeds 0:100:3 --modes all --method sparse", "lowest modes"},
        {"--speeds 0:100:3 --coupling weird", "coupling"},
        {"--speeds 0:100:3 --bogus", "unknown option"},
        {"", "--speeds"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        run(&s, &r, "campbell %s %s --out '%s/o'", RIG, cases[k].args, s.dir);
        CHECK(r.code == 2);
        if (!contains(r.err, cases[k].msg)) {
            fprintf(stderr, "  case '%s'\n", cases[k].args);
            show(&r);
        }
        CHECK(contains(r.err, cases[k].msg));
        CHECK(r.out[0] == '\0');
        char p[300];
        snprintf(p, sizeof p, "%s/o", s.dir);
        CHECK(count_entries(p) <= 0); /* nothing written */
        run_free(&r);
    }
    run(&s, &r, "campbell examples/missing.yaml --speeds 0:1:2");
    CHECK(r.code == 2);
    run_free(&r);
    scratch_close(&s);
}

/* ---- frf ---- */

TEST(frf_json_and_methods)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r,
        "frf %s --input gear48.x --output gear48.x --output mesh:mesh --output bearing:A1.y "
        "--freq 100:20000:40 --speed 3000rpm --json",
        RIG);
    if (r.code) show(&r);
    REQUIRE(r.code == 0);
    cJSON *a = cJSON_Parse(r.out);
    run_free(&r);
    run(&s, &r,
        "frf %s --input node:gear48.x --output gear48.x --output mesh:mesh --output bearing:A1.y "
        "--freq 100:20000:40 --speed 3000rpm --method modal --json",
        RIG);
    REQUIRE(r.code == 0);
    cJSON *b = cJSON_Parse(r.out);
    REQUIRE(a && b);
    const cJSON *oa = jget(a, "outputs"), *ob = jget(b, "outputs");
    REQUIRE(cJSON_GetArraySize(oa) == 3 && cJSON_GetArraySize(ob) == 3);
    CHECK_STR(jstr(cJSON_GetArrayItem(oa, 1), "name"), "mesh:mesh");
    CHECK_STR(jstr(b, "method"), "modal");
    CHECK(jnum(b, "rigid_body_modes") == 1);
    for (int o = 0; o < 3; o++) {
        const char *keys[5] = {"frequency_rad_s", "magnitude", "phase_deg", "real", "imag"};
        for (int k = 0; k < 5; k++)
            CHECK(cJSON_GetArraySize(jget(cJSON_GetArrayItem(oa, o), keys[k])) == 40);
        const cJSON *ma = jget(cJSON_GetArrayItem(oa, o), "real"),
                    *mb = jget(cJSON_GetArrayItem(ob, o), "real");
        for (int i = 0; i < 40; i += 13)
            CHECK_REL(cJSON_GetArrayItem(mb, i)->valuedouble,
                      cJSON_GetArrayItem(ma, i)->valuedouble, 1e-4);
    }
    cJSON_Delete(a);
    cJSON_Delete(b);
    run_free(&r);
    /* directional, table, csv, and the rigid-body note at 0 */
    run(&s, &r, "frf %s --input gear48.xy --output gear48.xy --freq 0:5000:11 --out '%s/o'", RIG,
        s.dir);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "gear48.xy forward") && contains(r.out, "gear48.xy backward"));
    CHECK(contains(r.err, "singular"));
    char p[300];
    snprintf(p, sizeof p, "%s/o/frf.csv", s.dir);
    char *csv = read_file(p);
    CHECK(csv && count_lines(csv) == 1 + 2 * 11);
    free(csv);
    run_free(&r);
    run(&s, &r,
        "frf %s --input torque:motor --output pinion.rz --type accelerance --freq 1000:2000:3 "
        "--json",
        KUMAR_COUPLED);
    CHECK(r.code == 0);
    cJSON *c = cJSON_Parse(r.out);
    REQUIRE(c);
    CHECK_STR(jstr(cJSON_GetArrayItem(jget(c, "outputs"), 0), "quantity"), "accelerance");
    cJSON_Delete(c);
    run_free(&r);
    scratch_close(&s);
}

TEST(frf_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    struct {
        const char *args, *msg;
    } cases[] = {
        {"--input nowhere.x --output gear48.x --freq 0:10:2", "unknown node 'nowhere'"},
        {"--input gear48.q --output gear48.x --freq 0:10:2", "unknown DOF"},
        {"--input gear48.z --output gear48.x --freq 0:10:2", "not active"},
        {"--input gear48 --output gear48.x --freq 0:10:2", "NODE.DOF"},
        {"--input gear48.x --output mesh:nomesh --freq 0:10:2", "unknown mesh 'nomesh'"},
        {"--input gear48.x --output bearing:Z9.x --freq 0:10:2", "unknown bearing 'Z9'"},
        {"--input gear48.x --output bearing:A1.w --freq 0:10:2", "unknown direction"},
        {"--input gear48.x --output gear48.x --freq 0:10:0", "COUNT is 0"},
        {"--input gear48.x --output gear48.x --freq 10:0:3", "below FROM"},
        {"--input gear48.x --output gear48.x", "--freq"},
        {"--output gear48.x --freq 0:10:2", "--input"},
        {"--input gear48.x --freq 0:10:2", "--output"},
        {"--input gear48.x --output gear48.x --freq 0:10:2 --method exact", "--method"},
        {"--input gear48.x --output gear48.x --freq 0:10:2 --type speed", "--type"},
        {"--input gear48.x --output mesh:mesh --freq 0:10:2 --type mobility", "is a force"},
        {"--input gear48.xy --output gear48.x --freq 0:10:2", "NODE.xy"},
        {"--input gear48.x --output gear48.xy --freq 0:10:2", "directional"},
        {"--input gear48.x --output gear48.x --freq 0:10:2 --speed fast", "--speed"},
        {"--input gear48.x --output gear48.x --freq 0:10:2 --modes -1", "--modes"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        run(&s, &r, "frf %s %s --out '%s/o'", RIG, cases[k].args, s.dir);
        CHECK(r.code == 2);
        if (!contains(r.err, cases[k].msg)) {
            fprintf(stderr, "  case '%s'\n", cases[k].args);
            show(&r);
        }
        CHECK(contains(r.err, cases[k].msg));
        char p[300];
        snprintf(p, sizeof p, "%s/o", s.dir);
        CHECK(count_entries(p) <= 0);
        run_free(&r);
    }
    scratch_close(&s);
}

/* ---- unbalance ---- */

TEST(unbalance_json_and_defaults)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "unbalance %s --speeds 0:60000rpm:21 --json", CHEN);
    if (r.code) show(&r);
    REQUIRE(r.code == 0);
    cJSON *j = cJSON_Parse(r.out);
    REQUIRE(j);
    REQUIRE(cJSON_GetArraySize(jget(j, "harmonics")) == 1);
    const cJSON *outs = jget(j, "outputs");
    /* gear_a x, y, rz; the mesh; x, y of two supports */
    REQUIRE(cJSON_GetArraySize(outs) == 8);
    const cJSON *o0 = cJSON_GetArrayItem(outs, 0);
    CHECK_STR(jstr(o0, "name"), "gear_a.x");
    CHECK(jnum(o0, "harmonic_order") == 1);
    const char *keys[5] = {"speed_rad_s", "magnitude", "phase_deg", "real", "imag"};
    for (int k = 0; k < 5; k++)
        CHECK(cJSON_GetArraySize(jget(o0, keys[k])) == 21);
    CHECK_STR(jstr(cJSON_GetArrayItem(outs, 3), "name"), "mesh:mesh");
    const cJSON *orb = cJSON_GetArrayItem(jget(j, "orbits"), 0);
    CHECK_STR(jstr(orb, "node"), "gear_a");
    CHECK(cJSON_GetArraySize(jget(orb, "major")) == 21);
    CHECK_STR(cJSON_GetArrayItem(jget(orb, "whirl"), 1)->valuestring, "forward");
    cJSON_Delete(j);
    run_free(&r);
    run(&s, &r,
        "unbalance %s --speeds 100:3000:3 --output gear.rz --output orbit:gear --out '%s/o'",
        KUMAR_COUPLED, s.dir);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "harmonic 0.94"));
    CHECK(contains(r.out, "orbit of gear"));
    char p[300];
    snprintf(p, sizeof p, "%s/o/unbalance.csv", s.dir);
    char *csv = read_file(p);
    CHECK(csv && count_lines(csv) == 1 + 2 * 3);
    free(csv);
    snprintf(p, sizeof p, "%s/o/orbits.csv", s.dir);
    CHECK(file_exists(p));
    run_free(&r);
    scratch_close(&s);
}

TEST(unbalance_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    struct {
        const char *model, *args, *msg;
    } cases[] = {
        {RIG, "--speeds 0:100:3", "no unbalances"},
        {KUMAR_COUPLED, "--speeds 0:100:3 --dofs rz", "not active"},
        {KUMAR_COUPLED, "--speeds 0:100:0", "COUNT is 0"},
        {KUMAR_COUPLED, "--speeds 0:100:3 --output orbit:nobody", "unknown node"},
        {KUMAR_COUPLED, "--speeds 0:100:3 --output mesh:none", "unknown mesh"},
        {KUMAR_COUPLED, "--speeds 0:100:3 --output motor.q", "unknown DOF"},
        {KUMAR_COUPLED, "--speeds 0:100:3 --output orbit:motor", "no active x and y"},
        {KUMAR_COUPLED, "--output pinion.x", "--speeds"},
        {KUMAR_COUPLED, "--speeds 0:100:3 --threads x", "--threads"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        run(&s, &r, "unbalance %s %s --out '%s/o'", cases[k].model, cases[k].args, s.dir);
        CHECK(r.code == 2);
        if (!contains(r.err, cases[k].msg)) {
            fprintf(stderr, "  case '%s'\n", cases[k].args);
            show(&r);
        }
        CHECK(contains(r.err, cases[k].msg));
        char p[300];
        snprintf(p, sizeof p, "%s/o", s.dir);
        CHECK(count_entries(p) <= 0);
        run_free(&r);
    }
    scratch_close(&s);
}

TEST(help_lists_sweeps)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "--help");
    CHECK(contains(r.out, "campbell") && contains(r.out, "frf") && contains(r.out, "unbalance"));
    run_free(&r);
    const char *cmds[3] = {"campbell", "frf", "unbalance"};
    for (int k = 0; k < 3; k++) {
        run(&s, &r, "%s --help", cmds[k]);
        CHECK(r.code == 0 && contains(r.out, "usage: geardyn"));
        run_free(&r);
    }
    scratch_close(&s);
}

/* Issue 35: a fixed 12 tracked modes stopped a gearbox's Campbell diagram far below its
 * tooth-mesh crossings. Without --modes, every elastic mode up to 1.25 x the highest order
 * at the top speed is tracked (rig2018: its 48-tooth mesh at 6000 rpm is 4800 Hz, so
 * 6000 Hz), checked against the undamped modes of `geardyn modal --modes all`. */
TEST(campbell_default_modes_reach_the_mesh_orders)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *m = run_json_args(&s, "modal examples/rig2018.yaml --undamped --modes all");
    REQUIRE(m);
    int below = 0;
    const cJSON *md;
    cJSON_ArrayForEach(md, cJSON_GetObjectItem(m, "modes"))
    {
        below += !cJSON_IsTrue(cJSON_GetObjectItem(md, "rigid_body")) &&
                 jnum(md, "frequency_hz") <= 6000.0;
    }
    cJSON_Delete(m);
    CHECK(below > 12);
    cJSON *c = run_json_args(&s, "campbell examples/rig2018.yaml --speeds 0:6000rpm:3");
    REQUIRE(c);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(c, "modes")) == below + 2);
    cJSON_Delete(c);
    run_result r;
    run(&s, &r, "campbell examples/rig2018.yaml --speeds 0:6000rpm:3");
    CHECK(r.code == 0 && contains(r.out, "every mode up to 6000 Hz"));
    run_free(&r);
    /* --modes keeps its meaning */
    c = run_json_args(&s, "campbell examples/rig2018.yaml --speeds 0:6000rpm:3 --modes 5");
    REQUIRE(c);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(c, "modes")) == 5);
    cJSON_Delete(c);
    scratch_close(&s);
}

RUN_TESTS(T(campbell_default_modes_reach_the_mesh_orders), T(campbell_json_names_and_values),
          T(campbell_out_csv_long_form), T(campbell_errors), T(frf_json_and_methods), T(frf_errors),
          T(unbalance_json_and_defaults), T(unbalance_errors), T(help_lists_sweeps))
