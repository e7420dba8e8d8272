/* geardyn periodic --method auto (the default) per value and with a given H (issue 33 item
 * 3; src/periodic/auto_values.c, choose.c, refuse.c): on seed 002 (examples/
 * helical_two_stage.yaml, spur pairs, full coupling) each speed by harmonic balance where
 * its truncation estimate is within 1 % by H = 591 against 1183, else by reduced shooting,
 * decided from the points before, in both directions; a given --harmonics H on the
 * co-prime gearbox read as the torus' order, or refused where the torus does not fit.
 * Run as a program from the source folder; a few minutes of CPU (seed 002's points). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "harness.h"

#define SEED002                                                                                    \
    "periodic examples/helical_two_stage.yaml --set meshes.pair1.geometry.helix_angle=0deg "       \
    "--set meshes.pair2.geometry.helix_angle=0deg --coupling full --record mesh:pair1:force "      \
    "--record mesh:pair2:force --quiet --no-stability"
#define COPRIME                                                                                    \
    "periodic examples/gearbox_coprime.yaml --speeds 900rpm:900rpm:1 --record mesh:stage1:force "  \
    "--record mesh:stage2:force --no-stability --quiet"

static const cJSON *point(const cJSON *o, int i)
{
    return cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "points"), i);
}

static double p2p(const cJSON *p, const char *name)
{
    return jnum(
        cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(p, "records"), name),
        "peak_to_peak");
}

/* `--harmonics 72 --no-estimate` on the co-prime gearbox (23/67, 19/71 teeth: a common
 * period of 67 mesh-1 periods) is the torus' order: the same orbit as `--method multifreq`
 * at that order, not ordinary harmonic balance of the common period (one harmonic of mesh
 * 1: mesh 1's standard deviation +115 % off the transient's, docs/periodic.md). Mutation
 * caught: the old rule (a given H always ordinary harmonic balance). */
TEST(coprime_given_h_is_the_torus_order)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *a = run_json_args(&s, COPRIME " --harmonics 72 --no-estimate");
    cJSON *m = run_json_args(&s, COPRIME " --harmonics 72 --no-estimate --method multifreq");
    cJSON *h = run_json_args(&s, COPRIME " --harmonics 72 --no-estimate --method hb");
    REQUIRE(a && m && h);
    CHECK(!strcmp(jstr(a, "method"), "multi_frequency_hb"));
    CHECK(contains(jstr(a, "method_choice"), "--harmonics 72 read as the torus' order"));
    CHECK(contains(jstr(a, "method_choice"), "H >= 1608"));
    const char *names[2] = {"mesh:stage1:force", "mesh:stage2:force"};
    for (int k = 0; k < 2; k++) {
        CHECK_REL(p2p(point(a, 0), names[k]), p2p(point(m, 0), names[k]), 1e-12);
        printf("  %s: auto %.6g, multifreq %.6g, ordinary hb %.6g N\n", names[k],
               p2p(point(a, 0), names[k]), p2p(point(m, 0), names[k]), p2p(point(h, 0), names[k]));
    }
    /* the ordinary harmonic balance the old rule ran is another orbit */
    CHECK(fabs(p2p(point(h, 0), names[0]) / p2p(point(a, 0), names[0]) - 1) > 0.05);
    cJSON_Delete(a);
    cJSON_Delete(m);
    cJSON_Delete(h);
    scratch_close(&s);
}

/* Where the torus does not take the model (two more loads at 101 and 103 times the common
 * fundamental: four base frequencies), a given H below 24 a period of the highest
 * excitation is refused before any point, naming the common period (67 / 23 input
 * revolutions), the H it needs (103 x 24) and the options that work, exit 2, nothing
 * written. Mutation caught: no refusal (ordinary harmonic balance at H = 120 ran). */
TEST(coprime_given_h_refused_where_the_torus_does_not_fit)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char *text = read_file("examples/gearbox_coprime.yaml");
    REQUIRE(text);
    const double W = 900 * 6.28318530717958647692 / 60, w0 = 23 * W / 67;
    char loads[400];
    snprintf(loads, sizeof loads,
             "    - {name: load_torque, node: load, value: -60 N*m}\n"
             "    - {node: gear2, amplitude: 1, frequency: %.17g Hz}\n"
             "    - {node: gear4, amplitude: 1, frequency: %.17g Hz}\n",
             101 * w0 / 6.28318530717958647692, 103 * w0 / 6.28318530717958647692);
    char *at = strstr(text, "    - {name: load_torque");
    REQUIRE(at != NULL);
    char *eol = strchr(at, '\n');
    REQUIRE(eol != NULL);
    static char model[9000];
    snprintf(model, sizeof model, "%.*s%s%s", (int)(at - text), text, loads, eol + 1);
    free(text);
    char path[256], args[600];
    snprintf(path, sizeof path, "%s/four_bases.yaml", s.dir);
    write_file(path, model);
    snprintf(args, sizeof args,
             "periodic '%s' --speeds 900rpm:900rpm:1 --harmonics 120 --no-stability", path);
    CHECK(run_fails_cleanly(&s, args, "H >= 2472", "--method shooting"));
    CHECK(run_fails_cleanly(&s, args, "2.91304 input revolutions", "harmonics"));
    scratch_close(&s);
}

/* Seed 002 upward 300 -> 2500 rpm: at 300 rpm (the first value, no trend) harmonic
 * balance's estimate at H = 591 against 1183 is 0.56 and reduced shooting solves the point;
 * at 2500 rpm the estimate extrapolated from it as v^-2 (0.008) is within 0.01, harmonic
 * balance runs there and confirms it (0.0071), its mesh forces within 1 % of the docs'
 * H = 591 point (536.911 / 464.686 N). Mutation caught: the old rule (the first value
 * decides the whole curve: reduced shooting at 2500 rpm too). */
TEST(seed002_the_method_per_value)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, SEED002 " --speeds 300rpm:2500rpm:2");
    REQUIRE(o);
    const cJSON *a = point(o, 0), *b = point(o, 1);
    REQUIRE(a && b);
    CHECK(!strcmp(jstr(a, "method"), "reduced_shooting"));
    CHECK(contains(jstr(a, "reason"), "the first value"));
    CHECK(!strcmp(jstr(b, "method"), "harmonic_balance"));
    CHECK(contains(jstr(b, "reason"), "within 0.01 (trend: 0.008 extrapolated from 0.56"));
    CHECK(jnum(b, "harmonics") == 1183);
    CHECK_REL(p2p(b, "mesh:pair1:force"), 536.911, 0.01);
    CHECK_REL(p2p(b, "mesh:pair2:force"), 464.686, 0.01);
    CHECK(contains(jstr(o, "method_choice"),
                   "1 points by harmonic balance (4 solves), 1 by reduced shooting (0 by the "
                   "trend, 1 after harmonic balance's estimate)"));
    printf("  %s\n  %s\n", jstr(a, "reason"), jstr(b, "reason"));
    cJSON_Delete(o);
    scratch_close(&s);
}

RUN_TESTS(T(seed002_the_method_per_value), T(coprime_given_h_is_the_torus_order),
          T(coprime_given_h_refused_where_the_torus_does_not_fit))
