/* A new user's gearbox through every command (examples/reducer_three_stage*.yaml, written
 * from the docs alone) and what that round found: `report` linearises the model's laws
 * (rolling bearings from geometry) about the static equilibrium, as `modal` does, and
 * never silently at q = 0, where a bearing with clearance holds nothing. */
#include <math.h>

#include "cli_support.h"
#include "harness.h"

#define GEOMETRIC "examples/rig2018_geometry.yaml"

TEST(report_modes_are_those_of_modal_at_the_static_state)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* modal's first elastic mode on the rig on ball bearings from geometry (default
       --operating-point static): 123.02 Hz; at q = 0 the 2 um clearance holds nothing and
       the lowest elastic mode is 18.77 Hz with five rigid-body modes before it */
    run_result r;
    run(&s, &r, "modal " GEOMETRIC " --modes 2");
    CHECK(r.code == 0 && contains(r.out, "123.02"));
    run_free(&r);
    char html[300], cmd[600];
    snprintf(html, sizeof html, "%s/r.html", s.dir);
    snprintf(cmd, sizeof cmd,
             "report " GEOMETRIC " --out '%s' --speeds 0:0:1 --freq-points 2 --modes 2", html);
    run(&s, &r, "%s", cmd);
    CHECK(r.code == 0);
    run_free(&r);
    char *text = read_file(html);
    REQUIRE(text);
    CHECK(contains(text, "mode 2: 123.02 Hz"));
    CHECK(!contains(text, "18.7739 Hz"));
    free(text);
    /* asked for, q = 0 is still there (the same options as modal's) */
    snprintf(cmd, sizeof cmd,
             "report " GEOMETRIC " --out '%s' --speeds 0:0:1 --freq-points 2 --modes 2 "
             "--operating-point zero",
             html);
    run(&s, &r, "%s", cmd);
    CHECK(r.code == 0);
    run_free(&r);
    text = read_file(html);
    REQUIRE(text);
    CHECK(contains(text, "18.7739 Hz"));
    free(text);
    scratch_close(&s);
}

TEST(report_without_an_equilibrium_is_the_located_error)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* a journal rotor at rest: no equilibrium; the report says so as modal does (exit 2,
       located at the law) and writes nothing */
    char html[300];
    snprintf(html, sizeof html, "%s/j.html", s.dir);
    run_result r;
    run(&s, &r, "report examples/journal_rotor.yaml --out '%s' --speeds 0:0:1 --freq-points 2",
        html);
    CHECK(r.code == 2 && contains(r.err, "journal_rotor.yaml:24:5: laws[0]") &&
          contains(r.err, "--operating-point zero"));
    CHECK(!file_exists(html));
    run_free(&r);
    scratch_close(&s);
}

TEST(rounding_noise_of_zeta_is_shown_as_zero)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* Cooley & Parker's undamped set at 3000 rpm: the state-space eigenvalues carry
       zeta -1.578e-15 (rounding); the tables showed it, read as a negative damping */
    run_result r;
    run(&s, &r, "modal examples/planetary_cooley_parker.yaml --speed 3000rpm --modes 3");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "   1      229.286      1440.64      1440.64         0         0  "));
    run_free(&r);
    /* the JSON keeps the value */
    cJSON *o = run_json_args(&s, "modal examples/planetary_cooley_parker.yaml --speed 3000rpm "
                                 "--modes 3");
    REQUIRE(o);
    double z =
        jnum(cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "modes"), 0), "damping_ratio");
    CHECK(z != 0 && fabs(z) < 1e-12);
    cJSON_Delete(o);
    /* campbell's smallest log decrement per mode: the same rule */
    run(&s, &r, "campbell examples/planetary_cooley_parker.yaml --speeds 0:3000rpm:2 --modes 3");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "   1  forward   lateral         265.678      229.286          0\n"));
    CHECK(!contains(r.out, "e-15"));
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(report_modes_are_those_of_modal_at_the_static_state),
          T(report_without_an_equilibrium_is_the_located_error),
          T(rounding_noise_of_zeta_is_shown_as_zero))
