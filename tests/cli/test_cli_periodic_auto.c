/* geardyn periodic with default options (issue 33 items 1-3, issue 38 L6, L7): the same
 * command gives the same output bit for bit; `--method auto` is the default, takes
 * shooting where a law is not smooth, hands a failed point to the other method and says
 * so per point; messages name the continued quantity; --dofs. Run as a program from the
 * source folder; each run well under a second but the NLvib branch (about 4 s). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "harness.h"

#define CHEN "examples/chen1998_gear_pair.yaml"
#define DUFFING "examples/duffing.yaml"
#define NLVIB3 "examples/nlvib_ex03.yaml"

static const cJSON *point(const cJSON *o, int i)
{
    return cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "points"), i);
}

static int npoints(const cJSON *o)
{
    return cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(o, "points"));
}

/* Five identical runs give identical stdout, byte for byte (L7: no clock decides a budget
 * or a method, and no timing is printed there). The Duffing sweep upward hands a point
 * to shooting; the Chen pair's multipliers are over a tiny budget, whose message quotes
 * the counted cost (it quoted the measured CPU time of the first Magnus step before). */
TEST(five_runs_identical)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const char *cmd[2] = {"periodic " DUFFING " --frequency 0.5:1.6:12 --json",
                                 "periodic " CHEN " --speeds 900:1100:3 --harmonics 7 "
                                 "--floquet-budget 1e-6 --floquet dense"};
    for (int c = 0; c < 2; c++) {
        char *first = NULL;
        for (int k = 0; k < 5; k++) {
            run_result r;
            run(&s, &r, "%s", cmd[c]);
            CHECK(r.code == 0);
            if (r.code) show(&r);
            if (!k)
                first = strdup(r.out ? r.out : "");
            else
                CHECK(first && r.out && !strcmp(first, r.out));
            if (!c && !k) CHECK(!contains(r.out, "cpu_seconds"));
            if (c && !k)
                CHECK(contains(r.out, "stability not computed: the dense monodromy of 12 states") &&
                      contains(r.out, "counted work"));
            run_free(&r);
        }
        free(first);
    }
    scratch_close(&s);
}

/* NLvib's example 03 (a unilateral spring) from 0.8 down to 0.6 rad/s with default
 * options: auto takes shooting (the law has a kink), every point says its stability came
 * from a shooting orbit, and the bifurcations are shooting's: a fold at 0.755627 and at
 * 0.653439, period doublings at 0.755586 and 0.738783, a Neimark-Sacker point at 0.618607
 * (--method shooting's, located to 1e-8 relative; the scipy oracle of issue 33 agrees on
 * every multiplier to 1e-4). Harmonic balance along its truncated orbit (--method hb, the
 * old default) finds only the lower fold: no period doubling, the Neimark-Sacker point
 * missing, and calls points of the middle branch stable (|mu| 0.88 against 2.24 at 0.7).
 * Tolerance 1e-6 on the locations: shooting's own location tolerance (1e-8) and the
 * integrator's (rtol 1e-9) are far inside it. */
TEST(unilateral_spring_default_is_shooting)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "periodic " NLVIB3 " --frequency 0.8:0.6:3");
    REQUIRE(o);
    CHECK(!strcmp(jstr(o, "method"), "shooting"));
    CHECK(strstr(jstr(o, "method_choice"), "non-smooth") != NULL);
    REQUIRE(npoints(o) == 5);
    for (int i = 0; i < 5; i++) {
        const cJSON *p = point(o, i);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p, "converged")));
        CHECK(!strcmp(jstr(p, "method"), "shooting"));
        CHECK(!strcmp(jstr(p, "stability_method"), "shooting"));
    }
    static const struct {
        const char *type;
        double at;
    } want[5] = {{"fold", 0.6534390782},
                 {"fold", 0.7556273420},
                 {"period_doubling", 0.7555861537},
                 {"period_doubling", 0.7387830275},
                 {"neimark_sacker", 0.6186068701}};
    const cJSON *bs = cJSON_GetObjectItemCaseSensitive(o, "bifurcations");
    REQUIRE(cJSON_GetArraySize(bs) == 5);
    for (int k = 0; k < 5; k++) {
        int found = 0;
        for (const cJSON *b = bs->child; b; b = b->next)
            found += !strcmp(jstr(b, "type"), want[k].type) &&
                     fabs(jnum(b, "parameter") - want[k].at) < 1e-6;
        CHECK(found == 1);
    }
    cJSON_Delete(o);
    scratch_close(&s);
}

/* Harmonic balance's multipliers where a law is not smooth come from the orbit corrected
 * by shooting (--stability-orbit auto, the default, also with --method hb): on NLvib's
 * example 03 at H = 10 over 0.8-0.64 rad/s the five points (0.72 rad/s three times: the
 * lower, the middle and the resonant branch) have shooting's verdicts and |mu|max
 * (--method shooting: 0.956, 0.95123, 1.73092, 0.84009, 0.88579; tolerance 1e-4, the
 * issue's oracle agreement) and the period doubling at 0.7387830 (shooting's 0.7387830275,
 * located to 1e-6). Along the truncated Fourier orbit (--stability-orbit fourier) the
 * middle and the resonant branch trade verdicts (0.8397 stable and 1.97304 unstable, in
 * the wrong order) and the period doubling sits at 0.678 rad/s, where shooting has none. */
TEST(hb_stability_from_corrected_orbit)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "periodic " NLVIB3 " --frequency 0.8:0.64:3 --method hb "
                                 "--harmonics 10 --no-estimate");
    REQUIRE(o);
    REQUIRE(npoints(o) == 5);
    static const double mu[5] = {0.956, 0.95123, 1.73092, 0.84009, 0.88579};
    for (int i = 0; i < 5; i++) {
        const cJSON *p = point(o, i);
        CHECK(!strcmp(jstr(p, "method"), "harmonic_balance"));
        CHECK(!strcmp(jstr(p, "stability_method"), "shooting"));
        CHECK(fabs(jnum(p, "floquet_multiplier_max_abs") - mu[i]) < 1e-4);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p, "stable")) == (i != 2));
    }
    int pd = 0;
    const cJSON *bs = cJSON_GetObjectItemCaseSensitive(o, "bifurcations");
    for (const cJSON *b = bs ? bs->child : NULL; b; b = b->next)
        if (!strcmp(jstr(b, "type"), "period_doubling")) {
            CHECK(fabs(jnum(b, "parameter") - 0.7387830275) < 1e-6);
            pd++;
        }
    CHECK(pd == 1);
    cJSON_Delete(o);
    CHECK(run_fails_cleanly(&s, "periodic " NLVIB3 " --frequency 0.8:0.7:2 --stability-orbit x",
                            "--stability-orbit", "fourier"));
    scratch_close(&s);
}

/* A truncation not within the tolerance: the Fourier orbit is not the time-domain one to
 * that accuracy, so a small model's multipliers come from the orbit corrected by shooting
 * (smooth law or not). The Duffing oscillator at H = 1 (--method hb) from 1.6 down to 1.1
 * rad/s: the points within the tolerance keep the Magnus multipliers, the three beyond it
 * (1.2 twice, 1.1) take shooting's: |mu|max 1.31491 and 0.87731 at 1.2 rad/s, 0.86693 at
 * 1.1 (--method shooting; tolerance 1e-4, the Newton tolerances of both). */
TEST(truncated_points_take_the_corrected_orbit)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "periodic " DUFFING " --frequency 1.6:1.1:6 --harmonics 1 "
                                 "--method hb");
    REQUIRE(o);
    REQUIRE(npoints(o) == 8);
    static const double mu[3] = {1.31491, 0.87731, 0.86693};
    int k = 0;
    for (int i = 0; i < 8; i++) {
        const cJSON *p = point(o, i),
                    *t = cJSON_GetObjectItemCaseSensitive(
                        cJSON_GetObjectItemCaseSensitive(p, "truncation"), "within_tolerance");
        const int ok = cJSON_IsTrue(t);
        CHECK(!strcmp(jstr(p, "stability_method"), ok ? "harmonic_balance" : "shooting"));
        if (!ok && k < 3) CHECK(fabs(jnum(p, "floquet_multiplier_max_abs") - mu[k++]) < 1e-4);
    }
    CHECK(k == 3);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* A point the chosen method fails goes to the other: shooting with a budget too small for
 * one monodromy fails every point of NLvib's example 03, and harmonic balance solves each
 * alone; each point says so (method, stability_method, reason) and the text's summary
 * counts them. */
TEST(failed_points_handed_over)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "periodic " NLVIB3 " --frequency 0.8:0.7:3 --shoot-budget 1e-9");
    REQUIRE(o);
    REQUIRE(npoints(o) == 3);
    CHECK(strstr(jstr(o, "method_choice"), "3 failed point(s) handed to harmonic balance, 3 "
                                           "solved there") != NULL);
    for (int i = 0; i < 3; i++) {
        const cJSON *p = point(o, i);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p, "converged")));
        CHECK(!strcmp(jstr(p, "method"), "harmonic_balance"));
        /* its multipliers from the harmonic balance orbit: the budget now reaches inside
         * the correction's first monodromy too (counted right-hand sides, issue 33) */
        CHECK(!strcmp(jstr(p, "stability_method"), "harmonic_balance"));
        CHECK(strstr(jstr(p, "reason"), "solved by harmonic balance (shooting failed") != NULL);
    }
    cJSON_Delete(o);
    run_result r;
    run(&s, &r, "periodic " NLVIB3 " --frequency 0.8:0.7:3 --shoot-budget 1e-9");
    CHECK(r.code == 0 && contains(r.out, "points: 3 by harmonic balance, 0 by shooting"));
    run_free(&r);
    scratch_close(&s);
}

/* L6: the Duffing oscillator swept upward in the load frequency with --method hb fails
 * its point at 1 rad/s (the fixed-value Newton from the arc); the message names the load
 * frequency, and the hint names a transient run that works (exit 0), not a speed of 0.
 * By default the point goes to shooting and converges (exit 0). */
TEST(frequency_messages_name_the_quantity)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "periodic " DUFFING " --frequency 0.5:1.6:12 --method hb");
    CHECK(r.code == 1);
    CHECK(contains(r.err, "load frequency 1 rad/s: Newton did not converge"));
    CHECK(!contains(r.err, " 0 rad/s") && !contains(r.out, "--speed 0"));
    CHECK(contains(r.out, "geardyn transient " DUFFING " --set excitations.loads.0.frequency="));
    run_free(&r);
    /* the suggested transient runs */
    run(&s, &r,
        "transient " DUFFING " --set excitations.loads.0.frequency=1rad/s --duration 1884.96 "
        "--from 1256.64");
    CHECK(r.code == 0);
    if (r.code) show(&r);
    run_free(&r);
    run(&s, &r, "periodic " DUFFING " --frequency 0.5:1.6:12");
    CHECK(r.code == 0 && contains(r.out, "1 failed point(s) handed to shooting, 1 solved there"));
    run_free(&r);
    scratch_close(&s);
}

/* --dofs, as the other commands take it: the Chen pair kept to its torsional DOF only has
 * fewer multipliers; an unknown DOF names the option; --parameter with --dofs is refused. */
TEST(dofs_option)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *a = run_json_args(&s, "periodic " CHEN " --speeds 1000:1000:1 --harmonics 7");
    cJSON *b = run_json_args(&s, "periodic " CHEN " --speeds 1000:1000:1 --harmonics 7 "
                                 "--dofs x,y");
    REQUIRE(a && b);
    const int na = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(point(a, 0), "floquet_re")),
              nb = cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(point(b, 0), "floquet_re"));
    CHECK(na == 12);
    CHECK(nb > 0 && nb < na);
    cJSON_Delete(a);
    cJSON_Delete(b);
    CHECK(run_fails_cleanly(&s, "periodic " CHEN " --speeds 1:2:3 --dofs q", "--dofs", NULL));
    CHECK(run_fails_cleanly(&s,
                            "periodic " CHEN " --speeds 1:1:1 --dofs x,y --parameter "
                            "disks.0.mass=1:2:2",
                            "--dofs", NULL));
    scratch_close(&s);
}

/* A run that takes long says so without a terminal (issue 33: "progress on stderr whenever
 * a point takes more than a second, terminal or not, unless --quiet"): the Ducati train's
 * point at 10000 rpm by shooting within a counted budget of 6 s (2.6 s CPU measured: more
 * than a second on any machine) ends, not converged, with a line on stderr naming the
 * point by its continued quantity and unit; --quiet leaves stderr without it. stdout is
 * the same either way (no clock reaches it). */
TEST(progress_without_terminal)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const char *cmd = "periodic examples/ducati_timing_geartrain.yaml "
                             "--speeds 10000rpm:10000rpm:1 --shoot-budget 6";
    run_result a, b;
    run(&s, &a, "%s", cmd);
    run(&s, &b, "%s --quiet", cmd);
    CHECK(a.code == 1 && b.code == 1);
    CHECK(contains(a.err, "geardyn periodic: point 1 (speed 1047.2 rad/s) failed by shooting in "));
    CHECK(!contains(b.err, "geardyn periodic: point 1"));
    CHECK(a.out && b.out && !strcmp(a.out, b.out));
    if (!contains(a.err, "geardyn periodic: point 1")) show(&a);
    run_free(&a);
    run_free(&b);
    scratch_close(&s);
}

/* A rattling idler (examples/rattle_pair.yaml, backlash) with default options: shooting,
 * whose estimate (0.175 s per point, counted) is over 20 times harmonic balance's but
 * under a second, follows an unstable orbit at every speed, as --method shooting does
 * (largest multipliers 3.81, 3.33, 3.01). Harmonic balance, taken before by the 20x
 * ratio alone, failed two of the three and shooting alone from rest found no orbit. */
TEST(rattling_pair_default_is_shooting)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "periodic examples/rattle_pair.yaml --speeds 600rpm:1000rpm:3");
    REQUIRE(o);
    CHECK(npoints(o) == 3);
    static const double mu[3] = {3.813367, 3.331904, 3.010756};
    for (int i = 0; i < npoints(o) && i < 3; i++) {
        const cJSON *p = point(o, i);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p, "converged")));
        CHECK(!strcmp(cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(p, "method")),
                      "shooting"));
        const double m =
            cJSON_GetNumberValue(cJSON_GetObjectItemCaseSensitive(p, "floquet_multiplier_max_abs"));
        CHECK(fabs(m - mu[i]) < 1e-4 * mu[i]);
    }
    cJSON_Delete(o);
    scratch_close(&s);
}

/* The matrix-free verdict (shooting above --shoot-dense-max states: Arnoldi on
 * monodromy-vector products) within a counted budget: on the Chen pair (12 states, forced
 * matrix-free) at 1000 rad/s its 12 Arnoldi steps cost about 0.018 s of counted work, so
 * under --floquet-budget 1e-4 they are not started and the point says "not determined",
 * naming the budget (the verdict ignored every budget before and spent them); with the
 * default budget the verdict is stable, |mu|max 0.884956 (the dense monodromy's 0.88496). */
TEST(krylov_verdict_within_counted_budget)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const char *fb[2] = {"1e-4", "30"};
    for (int c = 0; c < 2; c++) {
        char args[200];
        snprintf(args, sizeof args,
                 "periodic " CHEN " --speeds 1000:1000:1 --method shooting "
                 "--shoot-dense-max 1 --sequential --floquet-budget %s",
                 fb[c]);
        cJSON *o = run_json_args(&s, args);
        REQUIRE(o);
        const cJSON *p = point(o, 0);
        CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p, "converged")));
        const char *why = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(p, "reason"));
        const double m =
            cJSON_GetNumberValue(cJSON_GetObjectItemCaseSensitive(p, "floquet_multiplier_max_abs"));
        if (!c) {
            CHECK(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(p, "stable")));
            CHECK(why && strstr(why, "stability not determined: 12 Arnoldi steps") &&
                  strstr(why, "--floquet-budget"));
        } else {
            CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p, "stable")));
            CHECK(fabs(m - 0.884956) < 1e-5);
        }
        cJSON_Delete(o);
    }
    scratch_close(&s);
}

/* A branch that stops: the rattling idler (examples/rattle_idle.yaml, backlash) at
 * --shoot-rtol 1e-7 from 62.8 rad/s (stable, |mu|max 0.7194) to 66 rad/s. Its stable
 * branch ends near 65 rad/s, where shooting's corrector fails at every step length (30
 * iterations at residual 2e-3, about 1.3 s CPU a try at the default rtol's tenth); the
 * arclength stops after 6 failed steps in a row (it halved on to 1e-6 of the range before,
 * minutes at the default rtol) and names --sequential; `auto` solves the value past the
 * stop by shooting alone, from its own transient. About 8 s CPU. */
TEST(branch_stop_handed_to_shooting_alone)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(
        &s, "periodic examples/rattle_idle.yaml --speeds 62.8:66:2 --shoot-rtol 1e-7");
    REQUIRE(o);
    CHECK(npoints(o) == 2);
    const cJSON *p0 = point(o, 0), *p1 = point(o, 1);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p0, "stable")));
    CHECK(fabs(cJSON_GetNumberValue(
                   cJSON_GetObjectItemCaseSensitive(p0, "floquet_multiplier_max_abs")) -
               0.719426) < 1e-4);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(p1, "converged")));
    const char *why = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(p1, "reason"));
    CHECK(why && strstr(why, "solved by shooting alone at this value (the branch stops at "
                             "64.9759 rad/s after 6 failed steps in a row; --sequential"));
    CHECK(strstr(jstr(o, "method_choice"), "1 failed, handed to shooting alone") != NULL);
    cJSON_Delete(o);
    scratch_close(&s);
}

RUN_TESTS(T(five_runs_identical), T(unilateral_spring_default_is_shooting),
          T(hb_stability_from_corrected_orbit), T(truncated_points_take_the_corrected_orbit),
          T(failed_points_handed_over), T(frequency_messages_name_the_quantity), T(dofs_option),
          T(progress_without_terminal), T(rattling_pair_default_is_shooting),
          T(krylov_verdict_within_counted_budget), T(branch_stop_handed_to_shooting_alone))
