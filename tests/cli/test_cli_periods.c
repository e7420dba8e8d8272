/* geardyn transient --periods N: per-period statistics and the Poincare verdict from the
 * command line (text, JSON, periods.csv, poincare.csv), on the Mathieu pair (periodic off
 * its tongue, period-2 with a backlash in it), the Chen SFD pair's torus (quasi-periodic);
 * `--poincare` and `--sweep-speeds` add the verdict; the errors exit 2 naming the option;
 * `periodic` points to the command where its orbit is unstable. */
#include <math.h>

#include "cli_support.h"
#include "harness.h"

#define MATHIEU "tests/plot/mathieu_pair.yaml"
#define CHEN "examples/chen1998_gear_pair.yaml"

static const cJSON *record0(const cJSON *o)
{
    return cJSON_GetArrayItem(cJSON_GetObjectItem(cJSON_GetObjectItem(o, "periods"), "records"), 0);
}

static double band(const cJSON *rec, const char *q, const char *k)
{
    return jnum(cJSON_GetObjectItem(rec, q), k);
}

/* Off the tongue: the run is 40 revolutions of gear a (rounded up to whole mesh periods)
 * plus 32 mesh periods; mean force = 20 N m / 50 mm; every period alike. */
TEST(mathieu_periodic_json_text_csv)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "transient " MATHIEU " --speed 537 --periods 32 --settle 40rev");
    REQUIRE(o);
    const cJSON *p = cJSON_GetObjectItem(o, "periods");
    REQUIRE(p);
    double T = 2 * M_PI / (20 * 537.0);
    CHECK_REL(jnum(p, "period_s"), T, 1e-12);
    CHECK_REL(jnum(p, "fundamental_rad_s"), 20 * 537.0, 1e-12);
    CHECK(jnum(p, "count") == 32 && jnum(p, "samples_per_period") == 256);
    /* 40 revolutions = 800 mesh periods exactly */
    CHECK_REL(jnum(p, "settle_s"), 800 * T, 1e-9);
    CHECK_REL(jnum(o, "t_end_s"), 832 * T, 1e-9);
    CHECK_STR(jstr(p, "band"), "p05-p95");
    const cJSON *r = record0(o);
    CHECK_STR(jstr(r, "name"), "mesh:m:force");
    CHECK_REL(band(r, "mean", "median"), 400.0, 1e-4);
    CHECK_REL(band(r, "peak_to_peak", "median"), 70.58, 1e-3); /* the library test's */
    CHECK(band(r, "peak_to_peak", "max") - band(r, "peak_to_peak", "min") <
          1e-3 * band(r, "peak_to_peak", "median"));
    const cJSON *v = cJSON_GetObjectItem(p, "verdict");
    CHECK_STR(jstr(v, "class"), "periodic");
    CHECK(jnum(v, "period") == 1 && jnum(v, "points") == 33 && jnum(v, "distinct_points") == 1);
    CHECK(jnum(v, "tolerance") == 1e-3 && jnum(v, "torus_tolerance") == 0.2);
    cJSON_Delete(o);

    run_result t;
    char out[256];
    snprintf(out, sizeof out, "%s/out", s.dir);
    run(&s, &t, "transient " MATHIEU " --speed 537 --periods 32 --settle 40rev --out '%s'", out);
    CHECK(t.code == 0);
    CHECK(contains(t.out, "per-period statistics: 32 periods of"));
    CHECK(contains(t.out, "256 samples per period"));
    CHECK(contains(t.out, "median [5 %, 95 %] over the periods"));
    CHECK(contains(t.out, "Poincare verdict (once per period, 33 points): periodic; 1 distinct"));
    run_free(&t);
    char path[300];
    snprintf(path, sizeof path, "%s/periods.csv", out);
    char *csv = read_file(path);
    REQUIRE(csv);
    CHECK(contains(csv, "record,unit,quantity,median,p05,p95,min,max\n"));
    CHECK(contains(csv, "mesh:m:force,N,peak_to_peak,70.5"));
    CHECK(count_lines(csv) == 1 + 3); /* the force (a linear mesh has no contact state) */
    free(csv);
    snprintf(path, sizeof path, "%s/poincare.csv", out);
    csv = read_file(path);
    REQUIRE(csv);
    CHECK(count_lines(csv) == 1 + 33);
    free(csv);
    scratch_close(&s);
}

/* In the tongue (707 rad/s) with a 20 um backlash: the parametric resonance saturates on
 * contact losses into a period-2 orbit. */
TEST(mathieu_backlash_period_2)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "transient " MATHIEU " --speed 707 --periods 16 --settle 80rev "
                                 "--set 'meshes.m.backlash={gap: 20 um}'");
    REQUIRE(o);
    const cJSON *v = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "periods"), "verdict");
    CHECK_STR(jstr(v, "class"), "period-2");
    CHECK(jnum(v, "period") == 2 && jnum(v, "distinct_points") == 2);
    /* the mean force alternates between two periods' shapes, 345 and 455 N */
    const cJSON *r = record0(o);
    CHECK(band(r, "mean", "min") < 360 && band(r, "mean", "max") > 440);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* The torus of the Chen SFD pair at e_u/C = 1/2 (eccentricity 3 x 12.7 um). */
TEST(chen_torus_quasi_periodic)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o =
        run_json_args(&s, "transient " CHEN " --speed 5650 --unbalance-scale 3 --periods 100 "
                          "--settle 200rev --record gear_a.y,gear_a.x");
    REQUIRE(o);
    const cJSON *v = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "periods"), "verdict");
    CHECK_STR(jstr(v, "class"), "quasi-periodic");
    CHECK(jnum(v, "return_shift") == 15);
    CHECK(jnum(v, "return_distance") < 0.06 && jnum(v, "halves_distance") < 0.15);
    CHECK(jnum(v, "points") == 101 && jnum(v, "distinct_points") > 80);
    cJSON_Delete(o);
    /* --poincare gives the same verdict beside its class ("many") */
    o = run_json_args(&s, "transient " CHEN " --speed 5650 --unbalance-scale 3 --revolutions 300 "
                          "--poincare shaft_a --settle 200rev --record gear_a.y,gear_a.x");
    REQUIRE(o);
    const cJSON *pc = cJSON_GetObjectItem(o, "poincare");
    CHECK_STR(jstr(pc, "class"), "many");
    CHECK_STR(jstr(pc, "verdict"), "quasi-periodic");
    CHECK(jnum(pc, "points") == 101);
    cJSON_Delete(o);
    /* and a sweep, per speed: before the Neimark-Sacker bifurcation (5583 rad/s) and on
     * the torus */
    o = run_json_args(&s, "transient " CHEN " --sweep-speeds 5560:5650:2 --poincare shaft_a "
                          "--settle 200rev --points 48 --unbalance-scale 3 "
                          "--record gear_a.y,gear_a.x");
    REQUIRE(o);
    const cJSON *sp = cJSON_GetObjectItem(o, "speeds");
    CHECK_STR(jstr(cJSON_GetArrayItem(sp, 0), "verdict"), "periodic");
    CHECK_STR(jstr(cJSON_GetArrayItem(sp, 1), "class"), "many");
    CHECK_STR(jstr(cJSON_GetArrayItem(sp, 1), "verdict"), "quasi-periodic");
    cJSON_Delete(o);
    scratch_close(&s);
}

TEST(periods_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --periods 0", "--periods: '0'",
                            "whole number from 1"));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --periods x", "--periods: 'x'", NULL));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --periods 2.5", "--periods: '2.5'", NULL));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --speed 537 --periods 4 --duration 1",
                            "--duration does not apply to --periods", NULL));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --speed 537 --periods 4 --poincare a",
                            "--poincare does not apply to --periods", NULL));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --speed 537 --periods 4 --from 1ms",
                            "--from does not apply to --periods", NULL));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --periods 4", "reference speed > 0",
                            NULL)); /* the model has no speed */
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --speed 537 --periods 4 --settle xrev",
                            "--settle", "revolutions"));
    CHECK(run_fails_cleanly(&s, "transient " MATHIEU " --speed 537 --periods 4 --output-interval 1",
                            "--output-interval", "fewer than 2 samples per period"));
    /* no periodic excitation: no period */
    char path[300], args[400];
    snprintf(path, sizeof path, "%s/steady.yaml", s.dir);
    write_file(path, "dofs: [rz]\n"
                     "shafts:\n"
                     "  - {name: a, nodes: [{name: gear_a}]}\n"
                     "  - {name: b, nodes: [{name: gear_b}]}\n"
                     "disks:\n"
                     "  - {node: gear_a, polar_inertia: 1e-2}\n"
                     "  - {node: gear_b, polar_inertia: 5e-3}\n"
                     "meshes:\n"
                     "  - {name: m, driver: gear_a, driven: gear_b, base_radius: [25 mm, 50 mm],\n"
                     "     teeth: [20, 40], pressure_angle: 20 deg, stiffness: 1e8,\n"
                     "     damping: 140, backlash: {gap: 20 um}}\n"
                     "prescribed:\n"
                     "  - {node: gear_a, motion: nominal}\n"
                     "excitations:\n"
                     "  loads: [{node: gear_b, value: 20}]\n");
    snprintf(args, sizeof args, "transient '%s' --speed 537 --periods 4", path);
    CHECK(run_fails_cleanly(&s, args, "--periods:", "no periodic excitation"));
    scratch_close(&s);
}

/* `periodic` on the torus: the orbit is unstable, and the text ends by naming the
 * transient command. */
TEST(periodic_points_to_transient)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r,
        "periodic " CHEN " --speeds 5650:5650:1 "
        "--set unbalances.gear_a_unbalance.eccentricity=38.1um");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "1 of 1 points have no stable periodic orbit"));
    CHECK(contains(r.out, "geardyn transient " CHEN " --speed 5650 --periods 100 --settle 200rev"));
    run_free(&r);
    /* a stable point: no hint */
    run(&s, &r,
        "periodic " CHEN " --speeds 1500:1500:1 "
        "--set unbalances.gear_a_unbalance.eccentricity=38.1um");
    CHECK(r.code == 0);
    CHECK(!contains(r.out, "geardyn transient"));
    run_free(&r);
    scratch_close(&s);
}

/* The three-stage reducer's excitations (its stages' mesh frequencies, two unbalances)
 * have no common period: `periodic` says so and names a transient run of a given time,
 * not `--periods 100` (which fails for the same reason), and the library's hint says the
 * response is quasi-periodic instead of asking for a periodic excitation it has. The
 * suggested command's options run (here over 2 ms). */
TEST(no_common_period_points_to_duration)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "periodic examples/reducer_three_stage.yaml --speeds 1500rpm:1500rpm:1");
    CHECK(r.code == 1);
    CHECK(contains(r.out, "no common period"));
    CHECK(contains(r.out, "geardyn transient examples/reducer_three_stage.yaml --speed 157.08 "
                          "--duration 12 --from 8\n"));
    CHECK(!contains(r.out, "--periods 100"));
    run_free(&r);
    run(&s, &r, "transient examples/reducer_three_stage.yaml --periods 100");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "quasi-periodic") && contains(r.err, "--duration T"));
    CHECK(!contains(r.err, "give the model a periodic excitation"));
    run_free(&r);
    run(&s, &r,
        "transient examples/reducer_three_stage.yaml --speed 157.08 --duration 2ms "
        "--from 1ms");
    CHECK(r.code == 0);
    if (r.code) show(&r);
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(mathieu_periodic_json_text_csv), T(mathieu_backlash_period_2),
          T(chen_torus_quasi_periodic), T(periods_errors), T(periodic_points_to_transient),
          T(no_common_period_points_to_duration))
