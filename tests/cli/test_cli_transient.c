/* geardyn transient, run as a program (GD_CLI_PATH) from the source folder: every
 * option and error path, JSON names, output files, and the examples: the Ducati timing
 * geartrain (speed ratios near the gear ratios with fluctuation, contact losses) and
 * the Chen gear pair with its squeeze film damper (orbits of gear a at 1200 and 5500
 * rad/s, spectrum of the vertical response at 5425 rad/s with e_u = C). Runs are short
 * (a few tenths of a second each). */
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

#define DUCATI "examples/ducati_timing_geartrain.yaml"
#define CHEN "examples/chen1998_gear_pair.yaml"
#define KUMAR "examples/kumar2011_torsional.yaml"

/* ---- running the program ---- */

/* scratch folders, running geardyn, reading output: tests/cli_support.h */

/* ---- helpers for the summary ---- */

static const cJSON *record_named(const cJSON *o, const char *name)
{
    const cJSON *recs = cJSON_GetObjectItemCaseSensitive(o, "records"), *e;
    cJSON_ArrayForEach(e, recs) if (!strcmp(jstr(e, "name"), name)) return e;
    return NULL;
}

/* Runs and parses --json; NULL (and shows the run) unless it exits 0 with JSON. */
static cJSON *run_json(gd_test_state *gd_ts_, scratch *s, const char *fmt, ...)
{
    char args[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    run_result r;
    run(s, &r, "%s --json", args);
    cJSON *o = r.code == 0 ? cJSON_Parse(r.out) : NULL;
    if (!o) {
        show(&r);
        gd_ts_->checks_failed++;
    }
    CHECK(r.err[0] == '\0'); /* no progress bar when stderr is not a terminal */
    run_free(&r);
    return o;
}

/* An error run: exit 2, the words on stderr, nothing on stdout, nothing in --out. */
static void expect_error(gd_test_state *gd_ts_, scratch *s, const char *w1, const char *w2,
                         const char *fmt, ...)
{
    char args[2048], out[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    snprintf(out, sizeof out, "%s/err_out", s->dir);
    run_result r;
    run(s, &r, "%s --out '%s'", args, out);
    int ok = r.code == 2 && contains(r.err, w1) && (!w2 || contains(r.err, w2)) && !r.out[0];
    if (!ok) {
        fprintf(stderr, "  args: %s\n", args);
        show(&r);
        gd_ts_->checks_failed++;
    }
    CHECK(count_entries(out) <= 0); /* not created, or left empty */
    run_free(&r);
}

/* ---- the Ducati timing geartrain ---- */

TEST(ducati_speed_ratios_and_contact_losses)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json(gd_ts_, &s,
                        "transient " DUCATI " --revolutions 2 --from 0 "
                        "--record ratio:gear_wheel/crank_pinion,ratio:cam_ve/crank_pinion "
                        "--record crank_pinion.rz:speed,cam_ve.rz:speed");
    REQUIRE(o);
    CHECK_REL(jnum(o, "speed_rad_s"), 10000 * M_PI / 30, 1e-12);
    CHECK_REL(jnum(o, "t_end_s"), 0.012, 1e-12); /* two crank revolutions */
    CHECK(jnum(o, "record_from_s") == 0);
    CHECK(jnum(o, "dofs") == 12);
    CHECK(jnum(o, "free_dofs") == 11); /* crank pinion prescribed */
    CHECK(jnum(o, "steps") > 1000);
    CHECK(jnum(o, "rhs_evaluations") >= jnum(o, "steps"));
    CHECK(jnum(o, "samples") == 2001);
    const cJSON *g = record_named(o, "ratio:gear_wheel/crank_pinion");
    const cJSON *c = record_named(o, "ratio:cam_ve/crank_pinion");
    const cJSON *w0 = record_named(o, "crank_pinion.rz:speed");
    REQUIRE(g && c && w0);
    /* gear wheel: -30/45 (turns the other way); camshaft: 1/2 */
    CHECK_REL(jnum(g, "mean"), -2.0 / 3.0, 3e-3);
    CHECK_REL(jnum(c, "mean"), 0.5, 5e-3);
    CHECK(jnum(g, "peak_to_peak") > 0.02 && jnum(g, "peak_to_peak") < 0.2);
    CHECK(jnum(c, "peak_to_peak") > 0.05 && jnum(c, "peak_to_peak") < 0.3);
    CHECK(jnum(g, "min") < jnum(g, "mean") && jnum(g, "max") > jnum(g, "mean"));
    CHECK(fabs(jnum(g, "rms") - fabs(jnum(g, "mean"))) < 0.01);
    /* the crank turns exactly at its speed */
    CHECK_REL(jnum(w0, "min"), 10000 * M_PI / 30, 1e-12);
    CHECK(jnum(w0, "peak_to_peak") < 1e-9);
    const cJSON *meshes = cJSON_GetObjectItemCaseSensitive(o, "meshes"), *e;
    CHECK(cJSON_GetArraySize(meshes) == 9);
    int losses = 0, coast = 0, n = 0;
    cJSON_ArrayForEach(e, meshes)
    {
        CHECK(jstr(e, "name")[0] != 0);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(e, "backlash")));
        CHECK(jnum(e, "contact_losses") >= 0);
        CHECK(jnum(e, "separated_time_s") >= 0 && jnum(e, "separated_time_s") < 0.012);
        CHECK_REL(jnum(e, "separated_time_s") + jnum(e, "coast_time_s") + jnum(e, "drive_time_s"),
                  0.012, 1e-9);
        losses += (int)jnum(e, "contact_losses");
        coast += (int)jnum(e, "coast_impacts");
        n++;
    }
    CHECK(n == 9);
    CHECK_STR(jstr(cJSON_GetArrayItem(meshes, 0), "name"), "m01");
    /* the alternating cam torques make the teeth rattle through the backlash */
    CHECK(losses > 50);
    CHECK(coast > 50);
    cJSON_Delete(o);
    scratch_close(&s);
}

TEST(ducati_text_static_start_and_wildcards)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r,
        "transient " DUCATI " --duration 3ms --start static --record 'mesh:*:state' --quiet");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "12 DOFs (11 free)"));
    CHECK(contains(r.out, "static start"));
    CHECK(contains(r.out, "mesh:m34vi:state"));
    CHECK(contains(r.out, "contact_losses"));
    CHECK(r.err[0] == 0);
    run_free(&r);
    /* default records: force and state of every nonlinear mesh */
    cJSON *o = run_json(gd_ts_, &s, "transient " DUCATI " --duration 1ms --method adams");
    REQUIRE(o);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(o, "records")) == 18);
    CHECK(record_named(o, "mesh:m01:force") && record_named(o, "mesh:m01:state"));
    CHECK_STR(jstr(o, "method"), "adams");
    CHECK_STR(jstr(o, "start"), "rest");
    /* default: records from the last half */
    CHECK_REL(jnum(o, "record_from_s"), 0.5e-3, 1e-12);
    const cJSON *st = record_named(o, "mesh:m01:state");
    CHECK(jnum(st, "min") >= -1 && jnum(st, "max") <= 1);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* The default method on a linear model (the rig, 30 DOFs, an unbalance switched on
 * from rest, 20 ms): auto takes the linear time-invariant method, says so with its step
 * and error estimate, and agrees with --method bdf at rtol 1e-10. Measured at rtol 1e-4:
 * step 5e-5 s, estimate 3.3e-5; max, rms and peak-to-peak of both records within 4e-6
 * of the tight run; bound the rtol. */
TEST(auto_takes_the_linear_method_on_a_linear_model)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    const char *c = "transient examples/rig2018.yaml --set 'shafts.*.elements_per_section=1' "
                    "--set 'unbalances=[{node: gear48, amount: 1e-5}]' --speed 3000rpm "
                    "--duration 20ms --from 0 --output-interval 0.1ms --record gear48.x,brg_d1.y";
    cJSON *a = run_json(gd_ts_, &s, "%s --rtol 1e-4", c);
    cJSON *b = run_json(gd_ts_, &s, "%s --rtol 1e-10 --method bdf", c);
    REQUIRE(a && b);
    CHECK(strncmp(jstr(a, "method"), "auto: lti", 9) == 0);
    CHECK_STR(jstr(a, "method_used"), "lti");
    CHECK(jnum(a, "error_estimate") <= 1e-4 && jnum(a, "step_s") > 0);
    CHECK_STR(jstr(b, "method"), "bdf");
    CHECK(cJSON_GetObjectItemCaseSensitive(b, "method_used") == NULL);
    const char *names[2] = {"gear48.x:disp", "brg_d1.y:disp"};
    for (int k = 0; k < 2; k++) {
        const cJSON *ra = record_named(a, names[k]), *rb = record_named(b, names[k]);
        REQUIRE(ra && rb);
        CHECK(jnum(rb, "peak_to_peak") > 0);
        CHECK_REL(jnum(ra, "max"), jnum(rb, "max"), 1e-4);
        CHECK_REL(jnum(ra, "rms"), jnum(rb, "rms"), 1e-4);
        CHECK_REL(jnum(ra, "peak_to_peak"), jnum(rb, "peak_to_peak"), 1e-4);
    }
    cJSON_Delete(a);
    cJSON_Delete(b);
    run_result r;
    run(&s, &r, "%s --rtol 1e-4 --quiet", c);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "rest start, auto: lti"));
    run_free(&r);
    scratch_close(&s);
}

TEST(outputs_and_spectrum_files)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char out[256], path[512];
    snprintf(out, sizeof out, "%s/res", s.dir);
    run_result r;
    run(&s, &r,
        "transient " CHEN " --speed 1200 --duration 50ms --from 20ms --output-interval 0.1ms "
        "--record gear_a.y,sfd:support_a:fy --spectrum --window rect --out '%s' --quiet",
        out);
    CHECK(r.code == 0);
    if (r.code) show(&r);
    CHECK(contains(r.out, "spectrum peaks (rect window"));
    run_free(&r);
    CHECK(count_entries(out) == 3);
    snprintf(path, sizeof path, "%s/records.csv", out);
    CHECK(file_exists(path));
    char *csv = read_file(path);
    REQUIRE(csv);
    const char *h1 = "time_s,gear_a.y:disp,sfd:support_a:fy\n";
    CHECK(!strncmp(csv, h1, strlen(h1)));
    CHECK(count_lines(csv) == 302); /* header + 301 samples */
    free(csv);
    snprintf(path, sizeof path, "%s/spectrum.csv", out);
    csv = read_file(path);
    REQUIRE(csv);
    const char *h2 = "frequency_hz,order,gear_a.y:disp,sfd:support_a:fy\n";
    CHECK(!strncmp(csv, h2, strlen(h2)));
    CHECK(count_lines(csv) == 1 + 301 / 2 + 1);
    free(csv);
    snprintf(path, sizeof path, "%s/summary.json", out);
    char *js = read_file(path);
    cJSON *o = js ? cJSON_Parse(js) : NULL;
    free(js);
    REQUIRE(o);
    const cJSON *y = record_named(o, "gear_a.y:disp");
    REQUIRE(y);
    CHECK_STR(jstr(y, "unit"), "m");
    const cJSON *sp = cJSON_GetObjectItemCaseSensitive(y, "spectrum");
    CHECK_STR(jstr(sp, "window"), "rect");
    CHECK_REL(jnum(sp, "df_hz"), 1.0 / (301 * 1e-4), 1e-9);
    const cJSON *pk = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(sp, "peaks"), 0);
    CHECK_REL(jnum(pk, "order"), 1.0, 0.02);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* ---- the Chen gear pair with its squeeze film damper ---- */

/* [Chen1998] Figs. 10-11: near the torsion-dominated coupled mode, with e_u/C = 1/2
 * (--unbalance-scale 3: 3 x 12.7 um = C/2), the vertical response of gear a has content
 * below 1x. The OCR-read parameters put that mode at 5643 rad/s instead of the paper's
 * 5488, so the paper's 5425 and 5435 rad/s correspond to 5578 and 5589 rad/s here (same
 * ratio to the mode). There a sub-synchronous component at 0.87x and its combination
 * tones (1.13x = 2 - 0.87, 0.75x) appear next to 1x; at 5425 rad/s, below the band, the
 * response stays periodic. */
TEST(chen_sfd_subsynchronous_near_the_mesh_mode)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json(gd_ts_, &s,
                        "transient " CHEN " --speed 5589 --duration 0.6 --from 0.3 "
                        "--unbalance-scale 3 --record gear_a.y --spectrum");
    REQUIRE(o);
    const cJSON *y = record_named(o, "gear_a.y:disp");
    REQUIRE(y);
    const cJSON *sp = cJSON_GetObjectItemCaseSensitive(y, "spectrum");
    double a1 = jnum(sp, "amplitude_1x"), below = jnum(sp, "max_below_1x");
    CHECK(below > 0.04 * a1);
    CHECK_ABS(jnum(sp, "max_below_1x_order"), 0.875, 0.01);
    cJSON_Delete(o);
    o = run_json(gd_ts_, &s,
                 "transient " CHEN " --speed 5425 --duration 0.6 --from 0.3 "
                 "--unbalance-scale 3 --record gear_a.y --spectrum");
    REQUIRE(o);
    y = record_named(o, "gear_a.y:disp");
    sp = cJSON_GetObjectItemCaseSensitive(y, "spectrum");
    CHECK(jnum(sp, "max_below_1x") < 1e-3 * jnum(sp, "amplitude_1x"));
    cJSON_Delete(o);
    scratch_close(&s);
}

/* Steady orbits of gear a (12.7 um eccentricity): elliptical, at 1200 rad/s near the
 * second coupled mode and at 5500 rad/s near the mesh mode. */
TEST(chen_sfd_orbits)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const double W[2] = {1200, 5500};
    static const double X[2] = {6.609e-5, 3.255e-5}, Y[2] = {5.236e-5, 1.463e-5};
    static const double E[2][2] = {{0.2276, 0.5031}, {0.0439, 0.2302}};
    for (int k = 0; k < 2; k++) {
        cJSON *o = run_json(gd_ts_, &s,
                            "transient " CHEN " --speed %g --duration 0.3 --from 0.2 "
                            "--record gear_a.x,gear_a.y,sfd:support_a:ecc",
                            W[k]);
        REQUIRE(o);
        const cJSON *x = record_named(o, "gear_a.x:disp"), *y = record_named(o, "gear_a.y:disp");
        const cJSON *e = record_named(o, "sfd:support_a:ecc");
        REQUIRE(x && y && e);
        CHECK_REL(jnum(x, "peak_to_peak"), X[k], 0.01);
        CHECK_REL(jnum(y, "peak_to_peak"), Y[k], 0.01);
        CHECK(fabs(jnum(x, "mean")) < 0.01 * X[k]); /* centred orbit */
        CHECK_ABS(jnum(e, "min"), E[k][0], 0.005);
        CHECK_ABS(jnum(e, "max"), E[k][1], 0.005);
        CHECK(jnum(o, "samples") >= 2000);
        cJSON_Delete(o);
    }
    /* Adams agrees */
    cJSON *o = run_json(gd_ts_, &s,
                        "transient " CHEN " --speed 1200 --duration 0.3 --from 0.2 --method adams "
                        "--rtol 1e-7 --record gear_a.x");
    REQUIRE(o);
    CHECK_REL(jnum(record_named(o, "gear_a.x:disp"), "peak_to_peak"), X[0], 0.01);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* 5425 rad/s with e_u = C (--unbalance-scale 6): below the sub-synchronous band of this
 * model (see the test above) the steady response is periodic: 1x and the odd
 * super-harmonics 3x, 5x of the damper's nonlinearity; the content below 1x stays at
 * the leakage level. The 6x unbalance gives about 6x the orbit of the normal one. */
TEST(chen_sfd_spectrum_high_unbalance)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json(gd_ts_, &s,
                        "transient " CHEN " --speed 5425 --duration 0.25 --from 0.15 "
                        "--unbalance-scale 6 --record gear_a.y --spectrum");
    REQUIRE(o);
    const cJSON *y = record_named(o, "gear_a.y:disp");
    REQUIRE(y);
    const cJSON *sp = cJSON_GetObjectItemCaseSensitive(y, "spectrum");
    const cJSON *pk = cJSON_GetObjectItemCaseSensitive(sp, "peaks");
    REQUIRE(cJSON_GetArraySize(pk) >= 3);
    CHECK_REL(jnum(cJSON_GetArrayItem(pk, 0), "order"), 1.0, 2e-3);
    CHECK_REL(jnum(cJSON_GetArrayItem(pk, 0), "amplitude"), 5.9e-5, 0.02);
    CHECK_REL(jnum(cJSON_GetArrayItem(pk, 1), "order"), 3.0, 2e-3);
    CHECK_REL(jnum(cJSON_GetArrayItem(pk, 1), "amplitude"), 6.8e-6, 0.03);
    CHECK_REL(jnum(cJSON_GetArrayItem(pk, 2), "order"), 5.0, 2e-3);
    CHECK(jnum(sp, "max_below_1x") < 1e-2 * jnum(sp, "amplitude_1x"));
    CHECK_REL(jnum(y, "peak_to_peak"), 2 * 6.70e-5, 0.01);
    cJSON_Delete(o);
    o = run_json(gd_ts_, &s,
                 "transient " CHEN " --speed 5425 --duration 0.25 --from 0.15 "
                 "--record gear_a.y --spectrum");
    REQUIRE(o);
    y = record_named(o, "gear_a.y:disp");
    CHECK(jnum(y, "peak_to_peak") < 0.2 * 2 * 6.70e-5);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* ---- errors ---- */

TEST(record_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    const char *d = "transient " DUCATI " --duration 1ms";
    expect_error(gd_ts_, &s, "unknown node 'nosuch'", "nodes: crank_pinion",
                 "%s --record nosuch.rz", d);
    expect_error(gd_ts_, &s, "unknown DOF 'q'", NULL, "%s --record cam_ve.q", d);
    expect_error(gd_ts_, &s, "crank_pinion.x is not an active DOF", "has rz",
                 "%s --record crank_pinion.x", d);
    expect_error(gd_ts_, &s, "unknown DOF quantity 'accel'", NULL, "%s --record cam_ve.rz:accel",
                 d);
    expect_error(gd_ts_, &s, "expected NODE.DOF", NULL, "%s --record cam_ve", d);
    expect_error(gd_ts_, &s, "unknown mesh 'm99'", "meshes: m01", "%s --record mesh:m99", d);
    expect_error(gd_ts_, &s, "unknown mesh quantity 'torque'", NULL, "%s --record mesh:m01:torque",
                 d);
    expect_error(gd_ts_, &s, "no squeeze film damper", NULL, "%s --record sfd:x", d);
    expect_error(gd_ts_, &s, "ratio:NODE_A/NODE_B", NULL, "%s --record ratio:cam_ve", d);
    expect_error(gd_ts_, &s, "unknown node 'zz'", NULL, "%s --record ratio:cam_ve/zz", d);
    expect_error(gd_ts_, &s, "empty item", NULL, "%s --record cam_ve.rz,,cam_he.rz", d);
    expect_error(gd_ts_, &s, "no squeeze film damper 'support_b'", NULL,
                 "transient " CHEN " --duration 1ms --record sfd:support_b:fx");
    expect_error(gd_ts_, &s, "unknown damper quantity 'fz'", NULL,
                 "transient " CHEN " --duration 1ms --record sfd:support_a:fz");
    scratch_close(&s);
}

TEST(option_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    expect_error(gd_ts_, &s, "--duration: give a time > 0", NULL,
                 "transient " DUCATI " --duration -1ms");
    expect_error(gd_ts_, &s, "--duration: give a time > 0", NULL,
                 "transient " DUCATI " --duration 0");
    expect_error(gd_ts_, &s, "--duration", NULL, "transient " DUCATI " --duration 3kg");
    expect_error(gd_ts_, &s, "--revolutions needs a reference speed", NULL,
                 "transient " KUMAR " --revolutions 2");
    expect_error(gd_ts_, &s, "--revolutions needs a reference speed", NULL,
                 "transient " DUCATI " --revolutions 2 --speed 0");
    expect_error(gd_ts_, &s, "not a positive number", NULL,
                 "transient " DUCATI " --revolutions -1");
    expect_error(gd_ts_, &s, "exclude each other", NULL,
                 "transient " DUCATI " --revolutions 1 --duration 1ms");
    expect_error(gd_ts_, &s, "give --duration T or --revolutions N", NULL, "transient " DUCATI);
    expect_error(gd_ts_, &s, "--from: give a time in [0", NULL,
                 "transient " DUCATI " --duration 1ms --from 2ms");
    expect_error(gd_ts_, &s, "--from", NULL, "transient " DUCATI " --duration 1ms --from -1ms");
    expect_error(gd_ts_, &s, "--output-interval: give a time > 0", NULL,
                 "transient " DUCATI " --duration 1ms --output-interval 0");
    expect_error(gd_ts_, &s, "more than 1e7 samples", NULL,
                 "transient " DUCATI " --duration 1 --output-interval 1e-9");
    expect_error(gd_ts_, &s, "--rtol", NULL, "transient " DUCATI " --duration 1ms --rtol 0");
    expect_error(gd_ts_, &s, "--rtol: give a value below 0.1", NULL,
                 "transient " DUCATI " --duration 1ms --rtol 0.5");
    expect_error(gd_ts_, &s, "not auto, bdf, adams or galpha", NULL,
                 "transient " DUCATI " --duration 1ms --method rk4");
    expect_error(gd_ts_, &s, "--step: give a time > 0", NULL,
                 "transient " DUCATI " --duration 1ms --method galpha --step 0");
    expect_error(gd_ts_, &s, "--rho-inf: '2' is not a number from 0 to 1", NULL,
                 "transient " DUCATI " --duration 1ms --method galpha --rho-inf 2");
    expect_error(gd_ts_, &s, "does not take the cams' angle-dependent inertia", NULL,
                 "transient " DUCATI " --duration 1ms --method galpha");
    expect_error(gd_ts_, &s, "Poincare sample times need a CVODE method", NULL,
                 "transient examples/chen1998_gear_pair.yaml --speed 1500 --duration 20ms "
                 "--poincare shaft_a --method galpha");
    expect_error(gd_ts_, &s, "--reduce does not apply to --sweep-speeds", NULL,
                 "transient examples/chen1998_gear_pair.yaml --sweep-speeds 1000:2000:2 "
                 "--poincare shaft_a --reduce 5kHz");
    expect_error(gd_ts_, &s, "--reduce: 'fast' is not a frequency > 0", NULL,
                 "transient " DUCATI " --duration 1ms --reduce fast");
    expect_error(gd_ts_, &s, "the modal reduction does not take cam valve trains", NULL,
                 "transient " DUCATI " --duration 1ms --reduce 5kHz");
    expect_error(gd_ts_, &s, "not rest or static", NULL,
                 "transient " DUCATI " --duration 1ms --start hot");
    expect_error(gd_ts_, &s, "not hann or rect", NULL,
                 "transient " DUCATI " --duration 1ms --window x");
    expect_error(gd_ts_, &s, "--unbalance-scale", NULL,
                 "transient " CHEN " --duration 1ms --unbalance-scale -2");
    expect_error(gd_ts_, &s, "--speed", NULL, "transient " DUCATI " --duration 1ms --speed fast");
    expect_error(gd_ts_, &s, "unknown option '--bogus'", NULL,
                 "transient " DUCATI " --duration 1ms --bogus");
    expect_error(gd_ts_, &s, "exactly one model file", NULL, "transient --duration 1ms");
    expect_error(gd_ts_, &s, "cannot open", NULL, "transient examples/none.yaml --duration 1ms");
    expect_error(gd_ts_, &s, "unknown coupling level", NULL,
                 "transient " CHEN " --duration 1ms --coupling x");
    /* --dofs rz drops x, y: the damper has nothing to act on */
    expect_error(gd_ts_, &s, "support_a", "no active x and y",
                 "transient " CHEN " --duration 1ms --dofs rz");
    /* --out naming a file */
    char path[256];
    snprintf(path, sizeof path, "%s/afile", s.dir);
    write_file(path, "x");
    run_result r;
    run(&s, &r, "transient " DUCATI " --duration 1ms --out '%s'", path);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "not a folder"));
    run_free(&r);
    run(&s, &r, "transient " DUCATI " --duration");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "option '--duration' needs a value"));
    run_free(&r);
    run(&s, &r, "transient --help");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "ratio:NODE_A/NODE_B"));
    CHECK(contains(r.out, "--revolutions N"));
    run_free(&r);
    scratch_close(&s);
}

/* Model errors found when the spec is built: a load on an inactive DOF (with the model
 * line), a cam without its lift table. */
TEST(model_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[256];
    snprintf(path, sizeof path, "%s/m.yaml", s.dir);
    const char *base =
        "dofs: [rz]\n"
        "speed: 100\n"
        "shafts:\n"
        "  - {name: a, nodes: [{name: p}]}\n"
        "  - {name: b, nodes: [{name: g}]}\n"
        "disks: [{node: p, polar_inertia: 1e-3}, {node: g, polar_inertia: 2e-3}]\n"
        "meshes:\n"
        "  - {name: m, driver: p, driven: g, teeth: [20, 40], base_radius: [0.02, 0.04],\n"
        "     stiffness: 1e8, coupling: torsional, backlash: {gap: 10 um}}\n";
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "%sexcitations:\n  loads:\n    - {name: push, node: g, dof: x, value: 1 N}\n", base);
    write_file(path, yaml);
    expect_error(gd_ts_, &s, "m.yaml:12", "g.x, which is not an active DOF",
                 "transient '%s' --duration 1ms", path);
    snprintf(yaml, sizeof yaml, "%scam_torques:\n  - {camshaft: g, valves: [{mass: 0.1}]}\n", base);
    write_file(path, yaml);
    expect_error(gd_ts_, &s, "lift", NULL, "transient '%s' --duration 1ms", path);
    snprintf(yaml, sizeof yaml,
             "%scam_torques:\n  - {camshaft: g, lift: {angle: [0, 1], lift: [0]}, valves: [{mass: "
             "0.1}]}\n",
             base);
    write_file(path, yaml);
    expect_error(gd_ts_, &s, "lift", NULL, "transient '%s' --duration 1ms", path);
    /* the good model runs: a free pair from rest stays at rest */
    write_file(path, base);
    cJSON *o =
        run_json(gd_ts_, &s, "transient '%s' --duration 1ms --record p.rz,mesh:m:state", path);
    REQUIRE(o);
    CHECK(jnum(record_named(o, "p.rz:disp"), "peak_to_peak") == 0);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* ---- Poincare sections and the bifurcation sweep ---- */

static const cJSON *jitem(const cJSON *o, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(o, key);
}

/* One run with --poincare: the samples sit at the multiples of the shaft period from
 * --settle on, equal CVODE's fixed-interval output at the same times, and a settled Chen
 * pair at 1500 rad/s is period-1; a mesh source samples once per tooth-mesh cycle. */
TEST(poincare_single_run)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char out[256];
    snprintf(out, sizeof out, "%s/p", s.dir);
    const double W = 1500, P = 2 * M_PI / W;
    cJSON *o = run_json(gd_ts_, &s,
                        "transient " CHEN " --speed 1500 --duration 0.4 --from 0.3 --poincare "
                        "shaft_a --settle 0.3 --record gear_a.x,gear_a.y --out '%s'",
                        out);
    REQUIRE(o);
    const cJSON *pc = jitem(o, "poincare");
    REQUIRE(pc);
    CHECK_STR(jstr(pc, "source"), "shaft:shaft_a");
    CHECK_REL(jnum(pc, "period_s"), P, 1e-12);
    int k0 = (int)ceil(0.3 / P), k1 = (int)floor(0.4 / P), n = k1 - k0 + 1;
    CHECK(jnum(pc, "points") == n);
    CHECK_STR(jstr(pc, "class"), "period-1");
    CHECK(jnum(pc, "distinct_points") == 1);
    const cJSON *ts = jitem(pc, "times_s");
    CHECK(cJSON_GetArraySize(ts) == n);
    CHECK_REL(cJSON_GetArrayItem(ts, 0)->valuedouble, k0 * P, 1e-12);
    CHECK_REL(cJSON_GetArrayItem(ts, n - 1)->valuedouble, k1 * P, 1e-12);
    const cJSON *x = cJSON_GetArrayItem(jitem(pc, "records"), 0);
    CHECK_STR(jstr(x, "name"), "gear_a.x:disp");
    double x0 = cJSON_GetArrayItem(jitem(x, "values"), 0)->valuedouble;
    char *csv = NULL;
    char path[300];
    snprintf(path, sizeof path, "%s/poincare.csv", out);
    csv = read_file(path);
    REQUIRE(csv);
    CHECK(count_lines(csv) == n + 1);
    CHECK(contains(csv, "point,time_s,gear_a.x:disp,gear_a.y:disp"));
    free(csv);
    cJSON_Delete(o);
    /* the same instant as the first fixed-interval record of a run from k0 P: the two runs
     * differ in their first step (CVODE sizes it from the first output time), so they
     * agree to the integration tolerance (10 rtol; the fixed-interval records are
     * stroboscopic here, their peak-to-peak is the drift of the period-1 point) */
    char out2[256];
    snprintf(out2, sizeof out2, "%s/r", s.dir);
    o = run_json(gd_ts_, &s,
                 "transient " CHEN " --speed 1500 --duration 0.4 --from %.17g --output-interval "
                 "%.17g --record gear_a.x --out '%s'",
                 k0 * P, P, out2);
    REQUIRE(o);
    double p2p = jnum(record_named(o, "gear_a.x:disp"), "peak_to_peak");
    snprintf(path, sizeof path, "%s/records.csv", out2);
    csv = read_file(path);
    REQUIRE(csv);
    double t_r = 0, x_r = 0;
    CHECK(sscanf(strchr(csv, '\n') + 1, "%lf,%lf", &t_r, &x_r) == 2);
    CHECK_REL(t_r, k0 * P, 1e-11);
    CHECK_REL(x_r, x0, 1e-5);
    printf("     Poincare sample %.10g vs fixed-interval record %.10g (peak-to-peak %.3g)\n", x0,
           x_r, p2p);
    free(csv);
    cJSON_Delete(o);
    /* a mesh: once per tooth-mesh cycle of the crank pinion (30 teeth, 10000 rpm) */
    o = run_json(gd_ts_, &s, "transient " DUCATI " --revolutions 0.2 --poincare mesh:m01");
    REQUIRE(o);
    pc = jitem(o, "poincare");
    REQUIRE(pc);
    CHECK_REL(jnum(pc, "period_s"), 2 * M_PI / (30 * 10000 * M_PI / 30), 1e-12);
    CHECK(jnum(pc, "points") == 4); /* 0.6 .. 1.2 ms every 0.2 ms */
    cJSON_Delete(o);
    /* text */
    run_result r;
    run(&s, &r,
        "transient " CHEN " --speed 1500 --duration 0.4 --poincare shaft_a --settle 75rev "
        "--record gear_a.x");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "Poincare section (shaft:shaft_a"));
    CHECK(contains(r.out, "period-1"));
    run_free(&r);
    scratch_close(&s);
}

/* The sweep carries the state: run-up then run-down, every run starting where the
 * nominal angles W t of the previous one ended; CSV and JSON agree. */
TEST(poincare_sweep)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char out[256], path[300];
    snprintf(out, sizeof out, "%s/sw", s.dir);
    cJSON *o = run_json(gd_ts_, &s,
                        "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a --settle "
                        "40rev --points 6 --both-directions --record gear_a.x --out '%s'",
                        out);
    REQUIRE(o);
    const cJSON *sp = jitem(o, "speeds");
    REQUIRE(cJSON_GetArraySize(sp) == 6);
    const double W[6] = {1000, 1500, 2000, 2000, 1500, 1000};
    double prev_end = 0, prev_w = 0;
    for (int i = 0; i < 6; i++) {
        const cJSON *e = cJSON_GetArrayItem(sp, i);
        CHECK_REL(jnum(e, "speed_rad_s"), W[i], 1e-12);
        CHECK_STR(jstr(e, "direction"), i < 3 ? "up" : "down");
        if (i) CHECK_REL(jnum(e, "t_start_s") * W[i], prev_end * prev_w, 1e-12);
        /* 40 revolutions of settling to the next sample, then 6 points: 45 to 46 revs */
        double revs = (jnum(e, "t_end_s") - jnum(e, "t_start_s")) * W[i] / (2 * M_PI);
        CHECK(revs > 45 - 1e-9 && revs < 46 + 1e-9);
        const cJSON *rec = cJSON_GetArrayItem(jitem(e, "records"), 0);
        CHECK(cJSON_GetArraySize(jitem(rec, "values")) == 6);
        CHECK_STR(jstr(e, "class"), "period-1");
        prev_end = jnum(e, "t_end_s");
        prev_w = W[i];
    }
    snprintf(path, sizeof path, "%s/sweep.csv", out);
    char *csv = read_file(path);
    REQUIRE(csv);
    CHECK(count_lines(csv) == 7);
    CHECK(contains(csv, "direction,speed_rad_s,speed_rpm,class,period,distinct_points,cpu_s,"
                        "gear_a.x:disp_min,gear_a.x:disp_max"));
    free(csv);
    snprintf(path, sizeof path, "%s/poincare.csv", out);
    csv = read_file(path);
    REQUIRE(csv);
    CHECK(count_lines(csv) == 6 * 6 + 1);
    free(csv);
    cJSON_Delete(o);
    /* run-down only: speeds in decreasing order */
    o = run_json(gd_ts_, &s,
                 "transient " CHEN " --sweep-speeds 1000:2000:2 --poincare shaft_a --settle 5ms "
                 "--points 3 --run-down");
    REQUIRE(o);
    CHECK_REL(jnum(cJSON_GetArrayItem(jitem(o, "speeds"), 0), "speed_rad_s"), 2000, 1e-12);
    CHECK_REL(jnum(o, "settle_s"), 5e-3, 1e-12);
    cJSON_Delete(o);
    run_result r;
    run(&s, &r,
        "transient " CHEN " --sweep-speeds 1000:2000:2 --poincare shaft_a --settle 5ms "
        "--points 3");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "bifurcation sweep, 2 runs"));
    run_free(&r);
    scratch_close(&s);
}

TEST(poincare_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    expect_error(gd_ts_, &s, "'nope' is no shaft (shaft_a, shaft_b) or mesh (mesh)", NULL,
                 "transient " CHEN " --speed 1500 --duration 0.1 --poincare nope");
    expect_error(gd_ts_, &s, "'mesh' has no tooth numbers", NULL,
                 "transient " CHEN " --speed 1500 --duration 0.1 --poincare mesh:mesh");
    expect_error(gd_ts_, &s, "'m99' is no shaft", NULL,
                 "transient " DUCATI " --duration 1ms --poincare mesh:m99");
    expect_error(gd_ts_, &s, "--settle: 0.2 s is not before the end of the run (0.1 s)", NULL,
                 "transient " CHEN " --speed 1500 --duration 0.1 --poincare shaft_a --settle 0.2");
    expect_error(gd_ts_, &s, "--settle", "revolutions",
                 "transient " CHEN " --speed 1500 --duration 0.1 --poincare shaft_a --settle xrev");
    expect_error(gd_ts_, &s, "sample(s) between --settle", "run longer",
                 "transient " CHEN " --speed 1500 --duration 5ms --poincare shaft_a --settle 2ms");
    expect_error(gd_ts_, &s, "reference speed > 0", NULL,
                 "transient " CHEN " --duration 5ms --poincare shaft_a");
    expect_error(gd_ts_, &s, "--settle applies to --poincare and --periods only", NULL,
                 "transient " CHEN " --speed 1500 --duration 5ms --settle 1ms");
    expect_error(gd_ts_, &s, "COUNT is 0", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:0 --poincare shaft_a");
    expect_error(gd_ts_, &s, "FROM must be > 0", NULL,
                 "transient " CHEN " --sweep-speeds 0:2000:3 --poincare shaft_a");
    expect_error(gd_ts_, &s, "--sweep-speeds needs --poincare", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3");
    expect_error(gd_ts_, &s, "--duration does not apply to --sweep-speeds", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a --duration 1");
    expect_error(gd_ts_, &s, "--points applies to --sweep-speeds only", NULL,
                 "transient " CHEN " --speed 1500 --duration 5ms --points 4");
    expect_error(gd_ts_, &s, "--points", "whole number",
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a --points 1");
    expect_error(gd_ts_, &s, "exclude each other", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a --run-down "
                 "--both-directions");
    expect_error(gd_ts_, &s, "'x' is no shaft", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare x");
    /* an --out that cannot be created: exit 2 before computing, nothing written */
    run_result r;
    run(&s, &r,
        "transient " CHEN " --sweep-speeds 1000:2000:2 --poincare shaft_a --out "
        "/proc/no/such/dir");
    CHECK(r.code == 2);
    CHECK(!r.out[0]);
    run_free(&r);
    run(&s, &r,
        "transient " CHEN " --speed 1500 --duration 5ms --poincare shaft_a --out "
        "/proc/no/such/dir");
    CHECK(r.code == 2);
    CHECK(!r.out[0]);
    run_free(&r);
    run(&s, &r, "transient --help");
    CHECK(contains(r.out, "--sweep-speeds R"));
    run_free(&r);
    scratch_close(&s);
}

/* --waterfall: the spectra of the record at every speed and the order cuts in --json,
 * DIR/waterfall.csv (every bin of every speed) and DIR/order_cuts.csv (one row per speed);
 * a 1x order cut equals the spectrum's largest bin within 1.5 bins of the shaft speed;
 * and its errors. */
TEST(waterfall_outputs_and_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char out[256], path[300];
    snprintf(out, sizeof out, "%s/wf", s.dir);
    cJSON *o = run_json(gd_ts_, &s,
                        "transient tests/plot/runup_pair.yaml --sweep-speeds 600:800:3 --poincare "
                        "shaft_a --settle 20rev --points 17 --record gear_a.y --waterfall gear_a.x "
                        "--out '%s'",
                        out);
    REQUIRE(o);
    const cJSON *wf = jitem(o, "waterfall");
    REQUIRE(wf);
    CHECK_STR(jstr(wf, "record"), "gear_a.x:disp");
    const cJSON *sp = jitem(wf, "spectra"), *od = jitem(wf, "orders");
    REQUIRE(cJSON_GetArraySize(sp) == 3 && cJSON_GetArraySize(od) == 3);
    /* 16 settled revolutions of 54 samples (2.5 per period of the 16x mesh order at the
     * top speed 800 rad/s: ceil(2.5 x 16 x 800 / 600) = 54 at 600 rad/s) */
    const cJSON *s0 = cJSON_GetArrayItem(sp, 0);
    CHECK(jnum(s0, "samples") == 16 * 54);
    CHECK_REL(jnum(s0, "df_hz"), 600 / (2 * M_PI) / 16, 1e-9);
    const cJSON *o1 = cJSON_GetArrayItem(od, 0);
    CHECK_STR(jstr(o1, "label"), "1x shaft_a");
    /* 1x falls on bin 16 of the 16-revolution record: the cut is the largest of bins 15-17 */
    const cJSON *amp = jitem(s0, "amplitude");
    double best = 0;
    for (int k = 15; k <= 17; k++)
        best = fmax(best, cJSON_GetArrayItem(amp, k)->valuedouble);
    CHECK_REL(cJSON_GetArrayItem(jitem(o1, "amplitude"), 0)->valuedouble, best, 1e-15);
    CHECK(best > 1e-7); /* the unbalance response, not noise */
    snprintf(path, sizeof path, "%s/waterfall.csv", out);
    char *csv = read_file(path);
    REQUIRE(csv);
    /* per revolution ceil(2.5 x 16 x 800 / W): 54, 46, 40 samples at 600, 700, 800 rad/s */
    CHECK(count_lines(csv) == 1 + (8 * 54 + 1) + (8 * 46 + 1) + (8 * 40 + 1));
    free(csv);
    snprintf(path, sizeof path, "%s/order_cuts.csv", out);
    csv = read_file(path);
    REQUIRE(csv);
    CHECK(count_lines(csv) == 4);
    CHECK(contains(csv, "speed_rad_s,speed_rpm,\"1x shaft_a\",\"1x shaft_b\",\"mesh mesh 16x"));
    free(csv);
    cJSON_Delete(o);
    expect_error(gd_ts_, &s, "--waterfall applies to --sweep-speeds only", NULL,
                 "transient " CHEN " --speed 1500 --duration 5ms --waterfall gear_a.x");
    expect_error(gd_ts_, &s, "--waterfall: give one direction", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a "
                 "--both-directions --waterfall gear_a.x");
    expect_error(gd_ts_, &s, "--plot: give one direction", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a "
                 "--both-directions --plot x.svg");
    expect_error(gd_ts_, &s, "--waterfall: give one record", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a "
                 "--waterfall gear_a.x,gear_a.y");
    expect_error(gd_ts_, &s, "nope", NULL,
                 "transient " CHEN " --sweep-speeds 1000:2000:3 --poincare shaft_a "
                 "--waterfall nope.x");
    scratch_close(&s);
}

/* The rows of transient's option table: each value check names its option and its range
 * (exit 2, nothing written), -q is --quiet, and the help lists every option once with the
 * --record forms after the options. */
TEST(option_table_rows)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    expect_error(gd_ts_, &s, "--max-steps: '1.5'", "whole number from 1 to 1e15",
                 "transient " DUCATI " --duration 1ms --max-steps 1.5");
    expect_error(gd_ts_, &s, "--rho-inf: '2'", "from 0 to 1",
                 "transient " DUCATI " --duration 1ms --method galpha --rho-inf 2");
    expect_error(gd_ts_, &s, "--unbalance-scale: '-1'", ">= 0",
                 "transient " DUCATI " --duration 1ms --unbalance-scale -1");
    expect_error(gd_ts_, &s, "--window: 'flat'", "hann or rect",
                 "transient " DUCATI " --duration 1ms --window flat");
    expect_error(gd_ts_, &s, "--start: 'moving'", "rest or static",
                 "transient " DUCATI " --duration 1ms --start moving");
    expect_error(gd_ts_, &s, "--periods: '0'", "whole number from 1",
                 "transient " DUCATI " --periods 0");
    expect_error(gd_ts_, &s, "--revs-per-block: give 1 to 1e5", NULL,
                 "transient " DUCATI " --speed-ramp 0:6000rpm --duration 1ms --revs-per-block 0.5");
    expect_error(gd_ts_, &s, "--spectrum' takes no value", NULL,
                 "transient " DUCATI " --duration 1ms --spectrum=1");
    expect_error(gd_ts_, &s, "did you mean --duration?", NULL,
                 "transient " DUCATI " --duratoin 1ms");
    run_result r;
    /* -q: the short form of --quiet, on either side of the model file */
    run(&s, &r, "transient -q " DUCATI " --duration 0.2ms --record crank_pinion.rz");
    CHECK(r.code == 0 && contains(r.out, "crank_pinion.rz") && !r.err[0]);
    run_free(&r);
    run(&s, &r, "transient --help");
    CHECK(r.code == 0 && contains(r.out, "-q, --quiet"));
    const char *names[] = {"--duration T",      "--record WHAT",     "--method M",
                           "--run-down",        "--both-directions", "--speed-table FILE",
                           "--revs-per-block N"};
    for (int k = 0; k < 7; k++) {
        const char *at = strstr(r.out, "\n\n  --duration T"); /* the option list */
        CHECK(at && strstr(at, names[k]));
    }
    const char *forms = strstr(r.out, "--record WHAT, comma-separated:");
    CHECK(forms && strstr(forms, "mesh:NAME[:force|state|deflection|stiffness]"));
    run_free(&r);
    scratch_close(&s);
}

/* Issue 35: the default sampling followed the shafts only (32 a revolution): 1.3 samples
 * per tooth-mesh cycle at 5700 rpm on a gearbox put its peak-to-peak mesh force 8 % off
 * without a word. The default now takes 20 samples per cycle of the highest tooth-mesh
 * frequency (rig2018's 48-tooth mesh at 5700 rpm: 4560 Hz), and an interval given
 * coarser than 4 a cycle is said (not with --quiet). */
TEST(default_sampling_resolves_the_tooth_mesh)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "transient examples/rig2018.yaml --speed 5700rpm "
                                 "--duration 0.1 --quiet");
    REQUIRE(o);
    double mesh_period = 2 * M_PI / (5700 * 2 * M_PI / 60 * 48);
    CHECK_REL(jnum(o, "output_interval_s"), mesh_period / 20, 1e-9);
    cJSON_Delete(o);
    run_result r;
    run(&s, &r,
        "transient examples/rig2018.yaml --speed 5700rpm --duration 0.02 "
        "--output-interval 1e-4");
    CHECK(r.code == 0 && contains(r.err, "samples per tooth-mesh cycle of mesh 'mesh'") &&
          contains(r.err, "4560 Hz") && contains(r.err, "--output-interval 1.1e-05 s"));
    run_free(&r);
    run(&s, &r,
        "transient examples/rig2018.yaml --speed 5700rpm --duration 0.02 "
        "--output-interval 1e-4 --quiet");
    CHECK(r.code == 0 && !contains(r.err, "tooth-mesh"));
    run_free(&r);
    scratch_close(&s);
}

/* Issue 35: `--start static` failed on a train free in torsion (every gearbox driven by
 * a torque and braked by one) where `geardyn static` holds it. The start is now the
 * train's state under inertia relief: Kumar's 4-DOF torsional pair (no DOF holds its
 * rotation) driven by 10 N m at the motor. Braked by 10 N m x r_g / r_p the mesh
 * carries T / r_p = 224.719 N from the first instant (no start-up vibration); without a
 * brake the whole train accelerates and the mesh carries the force that accelerates the
 * output side, F = J2 r_p T / (J1 r_g^2 + J2 r_p^2) = 70.3072 N, steady as well. */
TEST(static_start_of_a_train_free_in_torsion)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char *base = read_file(GD_SOURCE_DIR "/examples/kumar2011_torsional.yaml");
    REQUIRE(base);
    const double J1 = 0.0115 + 0.001821, J2 = 0.001016 + 0.00575, rp = 0.0445, rg = 0.047;
    for (int braked = 1; braked >= 0; braked--) {
        char path[256], *text = malloc(strlen(base) + 512);
        REQUIRE(text);
        sprintf(text,
                "%s\nexcitations:\n  loads:\n    - {name: drive, node: motor, value: 10 N*m}\n"
                "    - {name: brake, node: load, value: %.9g N*m}\n",
                base, braked ? 10 * rg / rp : 0.0);
        snprintf(path, sizeof path, "%s/free_train.yaml", s.dir);
        write_file(path, text);
        free(text);
        char args[512];
        snprintf(args, sizeof args,
                 "transient '%s' --duration 0.05 --start static --record mesh:mesh --quiet", path);
        cJSON *o = run_json_args(&s, args);
        REQUIRE(o);
        const cJSON *st = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "records"), 0);
        double want = braked ? 10 / rp : J2 * rp * 10 / (J1 * rg * rg + J2 * rp * rp);
        CHECK_REL(jnum(st, "mean"), want, 1e-6);
        CHECK(jnum(st, "peak_to_peak") < 1e-5 * want);
        cJSON_Delete(o);
    }
    free(base);
    /* a rotor on journal bearings, which carry nothing at rest: the static start is
     * `static`'s equilibrium (docs/transient.md), q = 0 with no load in the run (its gravity
     * is static's only), and under a load the journal cannot carry at speed 0 static's
     * located error naming the bearing and the fix */
    run_result r;
    run(&s, &r,
        "transient examples/journal_rotor.yaml --duration 0.01 --start static --quiet --json");
    CHECK(r.code == 0);
    run_free(&r);
    char *jr = read_file(GD_SOURCE_DIR "/examples/journal_rotor.yaml");
    REQUIRE(jr);
    char *loaded = malloc(strlen(jr) + 256), path[256];
    REQUIRE(loaded);
    sprintf(loaded,
            "%s\nexcitations:\n  loads:\n    - {name: weight, node: left, dof: y, "
            "value: -196 N}\n",
            jr);
    snprintf(path, sizeof path, "%s/journal_loaded.yaml", s.dir);
    write_file(path, loaded);
    free(loaded);
    free(jr);
    run(&s, &r, "transient '%s' --duration 0.01 --start static", path);
    CHECK(r.code == 2 && contains(r.err, "journal bearing 'left_bearing' carries nothing") &&
          contains(r.err, "give a speed"));
    if (r.code != 2) show(&r);
    run_free(&r);
    scratch_close(&s);
}

/* --condense (docs/transient.md, "Condensed transient"): every mode kept on the rattling
 * pair gives the full model's mesh force statistics (rtol 1e-10: 1e-7 apart); auto states its
 * cut-off in the JSON (5 x the 26.7 Hz firing order against 2.5 x the mesh's contact frequency,
 * which wins); errors name the option. */
TEST(condensed_transient)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    const char *pair = "tests/transient/condensed_pair.yaml --duration 0.05 --from 0 --rtol 1e-10";
    cJSON *f = run_json(gd_ts_, &s, "transient %s --method bdf", pair);
    cJSON *c = run_json(gd_ts_, &s, "transient %s --condense all", pair);
    cJSON *a = run_json(gd_ts_, &s, "transient %s --condense auto", pair);
    REQUIRE(f && c && a);
    CHECK(jnum(f, "events") > 5 && jnum(c, "events") > 5); /* (26 and 29: the chatter's
                                                              crossings back differ) */
    const cJSON *rf = record_named(f, "mesh:m12:force"), *rc = record_named(c, "mesh:m12:force");
    REQUIRE(rf && rc);
    CHECK_REL(jnum(rc, "rms"), jnum(rf, "rms"), 1e-3);
    CHECK_REL(jnum(rc, "max"), jnum(rf, "max"), 1e-3);
    const cJSON *cc = cJSON_GetObjectItemCaseSensitive(a, "condensed");
    REQUIRE(cc);
    CHECK_REL(jnum(cc, "excitation_hz"), 800.0 / 60 * 2, 1e-12);
    CHECK(jnum(cc, "contact_hz") > 1000);
    CHECK_REL(jnum(cc, "cutoff_hz"), 2.5 * jnum(cc, "contact_hz"), 1e-12);
    CHECK(jnum(cc, "law_dofs") == 2);
    CHECK(strstr(jstr(a, "method"), "condensed") != NULL);
    cJSON_Delete(f);
    cJSON_Delete(c);
    cJSON_Delete(a);
    expect_error(gd_ts_, &s, "--condense: '0Hz' is not auto, off, all or a frequency", NULL,
                 "transient tests/transient/condensed_pair.yaml --duration 1ms --condense 0Hz");
    /* a prescribed flywheel: clamped in the condensed structure (issue 37), its records
     * and the free count those of the full model */
    cJSON *pf = run_json(gd_ts_, &s,
                         "transient examples/rattle_idle.yaml --duration 20ms "
                         "--condense all");
    REQUIRE(pf);
    CHECK(strstr(jstr(pf, "method"), "condensed") != NULL);
    CHECK(jnum(pf, "free_dofs") == 2);
    cJSON_Delete(pf);
    expect_error(gd_ts_, &s, "--condense and --reduce", NULL,
                 "transient tests/transient/condensed_pair.yaml --duration 1ms --condense all "
                 "--reduce 5kHz");
    /* the default: the 3-DOF pair stays full (no choice stated); the pair with its input
     * gear on an FE shaft (103 DOFs, laws on 2) is condensed and says so (20 ms: 0.07 s
     * CPU, the full model 24 s), --condense off keeps it full */
    cJSON *p = run_json(gd_ts_, &s, "transient tests/transient/condensed_pair.yaml --duration 1ms");
    const char *shaft = "tests/transient/condensed_shaft.yaml --from 0";
    cJSON *d = run_json(gd_ts_, &s, "transient %s --duration 20ms", shaft);
    cJSON *o = run_json(gd_ts_, &s, "transient %s --duration 0.05ms --condense off", shaft);
    REQUIRE(p && d && o);
    CHECK(!cJSON_GetObjectItemCaseSensitive(p, "condense"));
    CHECK(!cJSON_GetObjectItemCaseSensitive(p, "condensed"));
    CHECK(strstr(jstr(p, "method"), "condensed") == NULL);
    CHECK(strstr(jstr(d, "condense"), "condensed by default (103 DOFs, laws on 2") != NULL);
    CHECK(strstr(jstr(d, "method"), "auto: adams") != NULL);
    CHECK(jnum(d, "events") > 5);
    const cJSON *dc = cJSON_GetObjectItemCaseSensitive(d, "condensed");
    REQUIRE(dc);
    CHECK(jnum(dc, "law_dofs") == 2 && jnum(dc, "states") == 8);
    CHECK(!cJSON_GetObjectItemCaseSensitive(o, "condense"));
    CHECK(!cJSON_GetObjectItemCaseSensitive(o, "condensed"));
    CHECK(jnum(o, "dofs") == 103);
    cJSON_Delete(p);
    cJSON_Delete(d);
    cJSON_Delete(o);
}

/* bdf's error estimate (a second run at rtol / 10, docs/transient.md) is on by default and
 * left out by --no-estimate; the records are the same bit for bit either way. */
TEST(no_estimate_skips_the_second_run)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o[2];
    const char *cmd[2] = {"transient " DUCATI " --revolutions 0.5 --record mesh:m01:force",
                          "transient " DUCATI " --revolutions 0.5 --record mesh:m01:force "
                          "--no-estimate"};
    for (int k = 0; k < 2; k++)
        o[k] = run_json(gd_ts_, &s, cmd[k]);
    REQUIRE(o[0] && o[1]);
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(o[0], "error_estimate");
    CHECK(cJSON_IsNumber(e) && e->valuedouble > 0 && e->valuedouble < 1);
    CHECK(!cJSON_GetObjectItemCaseSensitive(o[1], "error_estimate"));
    CHECK(jnum(record_named(o[0], "mesh:m01:force"), "rms") ==
          jnum(record_named(o[1], "mesh:m01:force"), "rms"));
    CHECK(jnum(o[0], "steps") == jnum(o[1], "steps"));
    cJSON_Delete(o[0]);
    cJSON_Delete(o[1]);
    scratch_close(&s);
}

RUN_TESTS(T(ducati_speed_ratios_and_contact_losses), T(ducati_text_static_start_and_wildcards),
          T(outputs_and_spectrum_files), T(chen_sfd_orbits), T(chen_sfd_spectrum_high_unbalance),
          T(chen_sfd_subsynchronous_near_the_mesh_mode), T(record_errors), T(option_errors),
          T(auto_takes_the_linear_method_on_a_linear_model), T(model_errors),
          T(poincare_single_run), T(poincare_sweep), T(poincare_errors),
          T(waterfall_outputs_and_errors), T(option_table_rows),
          T(default_sampling_resolves_the_tooth_mesh), T(static_start_of_a_train_free_in_torsion),
          T(condensed_transient), T(no_estimate_skips_the_second_run))
