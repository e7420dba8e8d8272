/* geardyn transient --speed-ramp / --speed-table and geardyn report --run-up, run as a
 * program (GD_CLI_PATH) from the source folder: the acceptance of issue 21 through the
 * command line (the run-up waterfall's 1x peak of the rig's driving shaft,
 * tests/transient/runup_rotor.yaml, at the critical speed `campbell` gives), a table
 * giving the ramp's numbers, the output files, and every refusal located (exit 2). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "harness.h"

#define ROTOR "tests/transient/runup_rotor.yaml"
/* 5500 -> 7800 rpm at 625 rpm/s, 8 turns per block, generalized-alpha at 1e-4 s */
#define RAMP                                                                                       \
    "transient " ROTOR " --speed-ramp 5500:7800rpm --duration 3.68s --record gear48.x "            \
    "--waterfall gear48.x --revs-per-block 8 --method galpha --step 1e-4 --output-interval 1e-4"

/* the speed (rpm) of the largest 1x amplitude of the waterfall, and the spacing of the
 * blocks there */
static double peak_rpm(const cJSON *o, double *spacing)
{
    const cJSON *wf = cJSON_GetObjectItemCaseSensitive(o, "waterfall");
    const cJSON *sp = cJSON_GetObjectItemCaseSensitive(wf, "spectra");
    const cJSON *o1 = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(wf, "orders"), 0);
    const cJSON *amp = cJSON_GetObjectItemCaseSensitive(o1, "amplitude");
    int n = cJSON_GetArraySize(amp), best = 0;
    for (int k = 1; k < n; k++)
        if (cJSON_GetArrayItem(amp, k)->valuedouble > cJSON_GetArrayItem(amp, best)->valuedouble)
            best = k;
    double at = jnum(cJSON_GetArrayItem(sp, best), "speed_rpm");
    *spacing = fabs(jnum(cJSON_GetArrayItem(sp, best > 0 ? best - 1 : 1), "speed_rpm") - at);
    return at;
}

/* Acceptance: campbell's 1x crossing of the first forward mode (6649.8 rpm) against the
 * run-up's 1x peak at 625 rpm/s: measured +77 rpm (the peak swept through at a finite
 * rate comes late; tests/transient/test_runup.c shows it shrinking with the rate);
 * bounds: one block spacing below, 2 % above. The table with the ramp's two corners
 * (in rpm, from a header) gives the same numbers to 1e-9. */
TEST(run_up_peak_at_the_campbell_critical_speed)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *c = run_json_args(&s, "campbell " ROTOR " --speeds 6000:7200rpm:121 --modes 2");
    REQUIRE(c);
    double crit = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, cJSON_GetObjectItemCaseSensitive(c, "critical_speeds"))
    {
        if (!strcmp(jstr(e, "order"), "1x driving")) crit = fmax(crit, jnum(e, "speed_rpm"));
    }
    cJSON_Delete(c);
    CHECK_REL(crit, 6649.8, 1e-3);
    char out[256], path[320], args[1024];
    snprintf(out, sizeof out, "%s/ramp", s.dir);
    snprintf(args, sizeof args, RAMP " --out '%s'", out);
    cJSON *o = run_json_args(&s, args);
    REQUIRE(o);
    double spacing = 0, pk = peak_rpm(o, &spacing);
    fprintf(stderr, "  critical %.1f rpm, run-up peak %.1f rpm (blocks %.1f rpm apart)\n", crit, pk,
            spacing);
    CHECK(pk >= crit - spacing);
    CHECK(pk <= 1.02 * crit);
    const cJSON *prof = cJSON_GetObjectItemCaseSensitive(o, "speed_profile");
    CHECK_STR(jstr(prof, "kind"), "ramp");
    CHECK_REL(jnum(prof, "acceleration_rad_s2"), 2300 * M_PI / 30 / 3.68, 1e-12);
    CHECK(contains(jstr(o, "method"), "galpha"));
    const cJSON *wf = cJSON_GetObjectItemCaseSensitive(o, "waterfall");
    CHECK(jnum(wf, "revs_per_block") == 8);
    CHECK(jnum(wf, "samples_per_rev") == 32);
    const char *files[] = {"records.csv", "summary.json", "waterfall.csv", "order_cuts.csv"};
    for (int k = 0; k < 4; k++) {
        snprintf(path, sizeof path, "%s/%s", out, files[k]);
        CHECK(file_exists(path));
    }
    /* the same ramp as a table in rpm */
    snprintf(path, sizeof path, "%s/table.csv", s.dir);
    write_file(path, "# the ramp of RAMP\ntime_s, speed_rpm\n0, 5500\n3.68, 7800\n");
    snprintf(args, sizeof args,
             "transient " ROTOR " --speed-table '%s' --record gear48.x --waterfall gear48.x "
             "--revs-per-block 8 --method galpha --step 1e-4 --output-interval 1e-4",
             path);
    cJSON *t = run_json_args(&s, args);
    REQUIRE(t);
    double sp2, pk2 = peak_rpm(t, &sp2);
    CHECK_REL(pk2, pk, 1e-9);
    CHECK_STR(jstr(cJSON_GetObjectItemCaseSensitive(t, "speed_profile"), "kind"), "table");
    cJSON_Delete(t);
    cJSON_Delete(o);
    /* the text table: the profile line and the tracked waterfall's heading */
    run_result r;
    run(&s, &r,
        "transient " ROTOR " --speed-ramp 5000:8000rpm --duration 1s --waterfall "
        "gear48.x --method galpha --step 1e-4");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "speed ramp 5000 -> 8000 rpm over 0 .. 1 s (3000 rpm/s)"));
    CHECK(contains(r.out, "run-up waterfall of gear48.x:disp (order tracking"));
    run_free(&r);
    scratch_close(&s);
}

/* Refusals: exit 2, located, nothing written. */
TEST(run_up_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[320], args[1024];
    CHECK(run_fails_cleanly(&s, "transient " ROTOR " --speed-ramp 0:6000rpm",
                            "--speed-ramp needs --duration", NULL));
    CHECK(run_fails_cleanly(&s, "transient " ROTOR " --speed-ramp 6000rpm --duration 1s",
                            "is not FROM:TO", NULL));
    CHECK(run_fails_cleanly(&s, "transient " ROTOR " --speed-ramp -100:100 --duration 1s",
                            "--speed-ramp: give speeds of zero or more", NULL));
    CHECK(run_fails_cleanly(&s,
                            "transient " ROTOR " --speed-ramp 0:6000rpm --duration 1s --reduce "
                            "1kHz",
                            "--reduce does not apply to a speed profile", NULL));
    CHECK(run_fails_cleanly(&s,
                            "transient " ROTOR " --speed-ramp 0:6000rpm --duration 1s "
                            "--sweep-speeds 1:2:2 --poincare driving",
                            "does not apply to a speed profile", NULL));
    CHECK(run_fails_cleanly(&s,
                            "transient " ROTOR " --speed-ramp 0:6000rpm --duration 1s --spectrum",
                            "--spectrum (use --waterfall) does not apply", NULL));
    CHECK(run_fails_cleanly(&s,
                            "transient " ROTOR " --speed 3000rpm --duration 1s "
                            "--revs-per-block 4",
                            "--revs-per-block applies to --speed-ramp", NULL));
    CHECK(run_fails_cleanly(&s,
                            "transient " ROTOR " --speed-ramp 0:6000rpm --duration 0.5s "
                            "--waterfall gear48.x --revs-per-block 100 --method galpha",
                            "fewer than one block", NULL));
    snprintf(path, sizeof path, "%s/bad.csv", s.dir);
    write_file(path, "time, rpm\n0, 1000\n1, 2000\n1, 3000\n");
    snprintf(args, sizeof args, "transient " ROTOR " --speed-table '%s'", path);
    CHECK(run_fails_cleanly(&s, args, "bad.csv:4", "does not increase"));
    write_file(path, "0, 1000\n1, x\n");
    CHECK(run_fails_cleanly(&s, args, "bad.csv:2", "time, speed"));
    write_file(path, "0, 100\n1, -100\n");
    CHECK(run_fails_cleanly(&s, args, "changes the sense of rotation", NULL));
    CHECK(run_fails_cleanly(&s, "transient " ROTOR " --speed-table /nonexistent.csv",
                            "cannot read '/nonexistent.csv'", NULL));
    CHECK(
        run_fails_cleanly(&s, "report " ROTOR " --run-up 6000:1000rpm", "--run-up", "below FROM"));
    scratch_close(&s);
}

/* report --run-up: the waterfall section and its note; without it, a note saying how. */
TEST(report_run_up)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char out[256], args[600];
    snprintf(out, sizeof out, "%s/r.html", s.dir);
    snprintf(args, sizeof args,
             "report " ROTOR " --speeds 0:9000rpm:5 --freq-points 20 --run-up 4000:9000rpm "
             "--run-up-revolutions 100 --out '%s.svg'",
             out);
    run_result r;
    run(&s, &r, "%s", args);
    CHECK(r.code == 0);
    run_free(&r);
    snprintf(args, sizeof args, "%s.svg", out);
    char *svg = read_file(args);
    REQUIRE(svg);
    CHECK(contains(svg, "Run-up waterfall"));
    CHECK(contains(svg, "order cuts"));
    CHECK(contains(svg, "A run-up from 4000 to 9000 rpm"));
    CHECK(contains(svg, "forced by the model&apos;s unbalances") ||
          contains(svg, "forced by the model's unbalances"));
    free(svg);
    snprintf(args, sizeof args,
             "report " ROTOR " --speeds 0:9000rpm:5 --freq-points 20 --out '%s.svg'", out);
    run(&s, &r, "%s", args);
    CHECK(r.code == 0);
    run_free(&r);
    snprintf(args, sizeof args, "%s.svg", out);
    svg = read_file(args);
    REQUIRE(svg);
    CHECK(contains(svg, "Not asked for"));
    free(svg);
    scratch_close(&s);
}

/* The rows of report's option table: --out is required, each count and the run-up's
 * length name their range (exit 2, nothing written), and the help lists every option. */
TEST(report_option_rows)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "report " ROTOR);
    CHECK(r.code == 2 && contains(r.err, "--out FILE.html is required") && !r.out[0]);
    run_free(&r);
    CHECK(run_fails_cleanly(&s, "report " ROTOR " --modes 0", "--modes: '0'",
                            "whole number from 1 to 1000"));
    CHECK(run_fails_cleanly(&s, "report " ROTOR " --freq-points 1", "--freq-points: '1'",
                            "whole number from 2 to 100000"));
    CHECK(run_fails_cleanly(&s, "report " ROTOR " --threads 0", "--threads: '0'",
                            "whole number from 1"));
    CHECK(run_fails_cleanly(&s, "report " ROTOR " --run-up 0:6000rpm --run-up-revolutions 10",
                            "--run-up-revolutions: '10'", "from 16"));
    CHECK(run_fails_cleanly(&s, "report " ROTOR " --speeds 0:9000rpm:5 --run-up-revol=x",
                            "--run-up-revolutions: 'x'", NULL));
    run(&s, &r, "report --help");
    const char *names[] = {"--out FILE.html",  "--speeds FROM:TO:COUNT", "--speed VALUE",
                           "--modes N",        "--freq-points N",        "--threads N",
                           "--run-up FROM:TO", "--run-up-revolutions N", "--coupling LEVEL",
                           "--set PATH=VALUE"};
    CHECK(r.code == 0);
    for (int k = 0; k < 10; k++)
        CHECK(strstr(r.out, names[k]) != NULL);
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(run_up_peak_at_the_campbell_critical_speed), T(run_up_errors), T(report_run_up),
          T(report_option_rows))
