/* Bearings at the operating point through the CLI (docs/bearings.md): `static` finds the
 * roller bearing's equilibrium inside its clearance (issue 38 M2), modal, campbell, frf
 * and unbalance linearise the laws there and say so (`--operating-point static|zero`,
 * `--torque`), and where the laws have no equilibrium the run exits 2 with a located
 * error or flags the speeds, never a silent linearisation at q = 0. */
#include "cli_support.h"
#include "harness.h"

#define ROLLER "examples/roller_bearing.yaml"
#define JOURNAL "examples/journal_rotor.yaml"

TEST(roller_static_and_modal_at_its_load)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "static " ROLLER);
    REQUIRE(o);
    const cJSON *L = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "laws"), 0);
    REQUIRE(L);
    const cJSON *rec = cJSON_GetObjectItemCaseSensitive(L, "records");
    CHECK_REL(jnum(rec, "fy"), 200.0, 1e-9); /* the bearing carries the load */
    cJSON_Delete(o);
    /* modal at the static state: 474.795 and 1127.87 Hz (closed forms in
       tests/static/test_static_bearings.c), and the statement of the state */
    o = run_json_args(&s, "modal " ROLLER);
    REQUIRE(o);
    const cJSON *md = cJSON_GetObjectItemCaseSensitive(o, "modes");
    CHECK_REL(jnum(cJSON_GetArrayItem(md, 0), "frequency_hz"), 474.795, 1e-5);
    CHECK_REL(jnum(cJSON_GetArrayItem(md, 1), "frequency_hz"), 1127.87, 1e-5);
    const cJSON *op = cJSON_GetObjectItemCaseSensitive(o, "operating_point");
    CHECK_STR(jstr(op, "state"), "static");
    CHECK(jnum(op, "laws") == 1);
    cJSON_Delete(o);
    run_result r;
    run(&s, &r, "modal " ROLLER);
    CHECK(r.code == 0 && contains(r.out, "operating point: 1 law(s) linearised about the static "
                                         "equilibrium"));
    run_free(&r);
    /* at q = 0 the contacts are inside their clearance: rigid-body modes, said so */
    run(&s, &r, "modal " ROLLER " --operating-point zero");
    CHECK(r.code == 0 && contains(r.out, "(rigid body)") &&
          contains(r.out, "linearised about q = 0 (--operating-point zero)"));
    run_free(&r);
    scratch_close(&s);
}

TEST(journal_at_rest_is_an_error_or_a_flagged_speed)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* modal and frf at the model's speed (0): no equilibrium, a located error */
    CHECK(run_fails_cleanly(&s, "modal " JOURNAL, "journal_rotor.yaml:24:5: laws[0]",
                            "--operating-point zero"));
    CHECK(run_fails_cleanly(&s, "frf " JOURNAL " --input left.x --output left.y --freq 1:100:5",
                            "journal bearing 'left_bearing' carries nothing at 0 rad/s", NULL));
    /* campbell through 0: that speed is flagged (stderr and JSON), the others solved */
    run_result r;
    run(&s, &r, "campbell " JOURNAL " --speeds 0:1300:3 --json");
    CHECK(r.code == 0 && contains(r.err, "no static equilibrium at 1 of 3 speeds"));
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    const cJSON *op = cJSON_GetObjectItemCaseSensitive(o, "operating_point");
    const cJSON *bad = cJSON_GetObjectItemCaseSensitive(op, "no_equilibrium_speeds_rpm");
    CHECK(cJSON_GetArraySize(bad) == 1 && cJSON_GetArrayItem(bad, 0)->valuedouble == 0);
    cJSON_Delete(o);
    run_free(&r);
    /* a journal bearing with zero clearance: the law's located bound */
    char *text = read_file(GD_SOURCE_DIR "/examples/jeffcott_journal.yaml"), path[256];
    REQUIRE(text);
    char *at = strstr(text, "clearance: 50 um");
    REQUIRE(at);
    memcpy(at, "clearance:  0 um", 16);
    snprintf(path, sizeof path, "%s/zero.yaml", s.dir);
    write_file(path, text);
    free(text);
    run(&s, &r, "modal '%s' --speed 1000", path);
    CHECK(r.code == 2 && contains(r.err, "zero.yaml:22:") &&
          contains(r.err, "laws[0].clearance: must be positive"));
    run_free(&r);
    /* modal at a speed: the film's equilibrium, no error */
    run(&s, &r, "modal " JOURNAL " --speed 1000");
    CHECK(r.code == 0 && contains(r.out, "2 law(s) linearised about the static equilibrium"));
    run_free(&r);
    scratch_close(&s);
}

TEST(operating_point_options)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "modal " ROLLER " --operating-point mean");
    CHECK(r.code == 2 && contains(r.err, "--operating-point"));
    run_free(&r);
    run(&s, &r, "modal " ROLLER " --torque abc");
    CHECK(r.code == 2 && contains(r.err, "--torque"));
    run_free(&r);
    /* a torque with no torsion DOF to take it: the static analysis's located error */
    run(&s, &r, "modal " ROLLER " --torque 5");
    CHECK(r.code == 2 && contains(r.err, "torsion"));
    run_free(&r);
    /* unbalance: the statement after the tables */
    char *text = read_file(GD_SOURCE_DIR "/" JOURNAL), path[256];
    REQUIRE(text);
    size_t len = strlen(text);
    char *with = malloc(len + 200);
    REQUIRE(with);
    snprintf(with, len + 200,
             "%sunbalances:\n  - {name: u, node: left, mass: 20, eccentricity: "
             "1 um}\n",
             text);
    snprintf(path, sizeof path, "%s/unbalanced.yaml", s.dir);
    write_file(path, with);
    run(&s, &r, "unbalance '%s' --speeds 1000:1100:2 --output left.x", path);
    CHECK(r.code == 0 && contains(r.out, "solved at each speed"));
    run_free(&r);
    free(text);
    free(with);
    scratch_close(&s);
}

/* bearing-stiffness: the table's ball bearing at a radial load (its stiffness from the
 * library, tests/laws/test_bearing_geometry.c), and its located errors */
TEST(bearing_stiffness_from_a_table)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "bearing-stiffness examples/bearings.yaml --bearing 6205 --load "
                                 "0,1kN");
    REQUIRE(o);
    CHECK_STR(jstr(o, "bearing"), "6205");
    CHECK_STR(jstr(o, "type"), "ball");
    CHECK_REL(jnum(o, "contact_constant"), 9.31923e9, 1e-5);
    const cJSON *K = cJSON_GetObjectItemCaseSensitive(o, "stiffness");
    CHECK_REL(cJSON_GetArrayItem(cJSON_GetArrayItem(K, 1), 1)->valuedouble, 1.07051e8, 1e-5);
    CHECK(jnum(o, "loaded") == 4);
    cJSON_Delete(o);
    run_result r;
    run(&s, &r, "bearing-stiffness examples/bearings.yaml --bearing X");
    CHECK(r.code == 2 && contains(r.err, "bearings.yaml:6:3: --bearing: no bearing named 'X'") &&
          contains(r.err, "'NU205'"));
    run_free(&r);
    run(&s, &r, "bearing-stiffness examples/bearings.yaml --bearing NU205 --load 0,1kN,100");
    CHECK(r.code == 2 && contains(r.err, "cannot carry an axial load") && !r.out[0]);
    run_free(&r);
    run(&s, &r, "bearing-stiffness examples/bearings.yaml --load 1,2,3,4,5,6");
    CHECK(r.code == 2 && contains(r.err, "at most five"));
    run_free(&r);
    run(&s, &r, "bearing-stiffness examples/bearings.yaml --load 1kg");
    CHECK(r.code == 2 && contains(r.err, "--load"));
    run_free(&r);
    char path[256];
    snprintf(path, sizeof path, "%s/t.yaml", s.dir);
    write_file(path, "bearings:\n  - {name: a, type: ball, elements: 9, element_diameter: 40 "
                     "mm,\n     pitch_diameter: 39 mm}\n");
    run(&s, &r, "bearing-stiffness '%s'", path);
    CHECK(r.code == 2 && contains(r.err, "t.yaml:3:22: bearings[0].pitch_diameter"));
    run_free(&r);
    write_file(path, "bearings:\n  - {name: a, type: ball, elements: 9, element_diam: 4 mm}\n");
    run(&s, &r, "bearing-stiffness '%s'", path);
    CHECK(r.code == 2 && contains(r.err, "element_diam"));
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(bearing_stiffness_from_a_table), T(roller_static_and_modal_at_its_load),
          T(journal_at_rest_is_an_error_or_a_flagged_speed), T(operating_point_options))
