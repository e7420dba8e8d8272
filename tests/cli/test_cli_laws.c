/* Laws of the registry through the CLI (docs/laws.md): check lists them, transient and
 * periodic record them by name, and every wrong record or law in a file exits 2 with a
 * located message and nothing written. */
#include "cli_support.h"
#include "harness.h"

#define DUFFING "examples/duffing.yaml"

TEST(check_lists_the_laws)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "check " DUFFING);
    REQUIRE(o);
    const cJSON *L = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "laws"), 0);
    REQUIRE(L);
    CHECK_STR(jstr(L, "name"), "cubic");
    CHECK_STR(jstr(L, "type"), "polynomial_spring");
    CHECK_STR(jstr(L, "dof"), "x");
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(L, "parameters");
    CHECK(jnum(p, "k3") == 0.1 && jnum(p, "damping") == 0.05 && jnum(p, "k1") == 0);
    cJSON_Delete(o);
    scratch_close(&s);
}

TEST(law_records_in_transient_and_periodic)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* the default records are each law's first */
    cJSON *o = run_json_args(&s, "transient " DUFFING " --duration 20");
    REQUIRE(o);
    const cJSON *r = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "records"), 0);
    CHECK_STR(jstr(r, "name"), "law:cubic:force");
    CHECK_STR(jstr(r, "unit"), "N");
    cJSON_Delete(o);
    /* harmonic balance: the cubic force k3 q^3 of the orbit (harmonics 1 and 3 only:
     * the odd law of a symmetric orbit) */
    o = run_json_args(&s, "periodic " DUFFING " --speeds 1:1:1 --harmonics 15 --record "
                          "m.x,law:cubic:deflection");
    REQUIRE(o);
    const cJSON *pt = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "points"), 0);
    const cJSON *recs = cJSON_GetObjectItemCaseSensitive(pt, "records");
    const cJSON *x = cJSON_GetObjectItemCaseSensitive(recs, "m.x:disp");
    const cJSON *d = cJSON_GetObjectItemCaseSensitive(recs, "law:cubic:deflection");
    REQUIRE(x && d);
    /* the spring's deflection is the DOF's displacement (to ground) */
    CHECK_REL(jnum(d, "rms"), jnum(x, "rms"), 1e-14);
    CHECK(jnum(x, "rms") > 0.29 && jnum(x, "rms") < 0.3);
    cJSON_Delete(o);
    scratch_close(&s);
}

TEST(law_errors_exit_2)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    CHECK(run_fails_cleanly(&s, "transient " DUFFING " --duration 1 --record law:nothing",
                            "no law 'nothing'", "laws: cubic"));
    CHECK(run_fails_cleanly(&s, "transient " DUFFING " --duration 1 --record law:cubic:torque",
                            "no record 'torque'", "force, deflection"));
    CHECK(run_fails_cleanly(&s, "periodic " DUFFING " --speeds 1:1:1 --record law:cubic:x",
                            "no record 'x'", NULL));
    CHECK(run_fails_cleanly(&s, "transient examples/rig2018.yaml --duration 1 --record law:a",
                            "has no law", NULL));
    CHECK(run_fails_cleanly(&s, "transient " DUFFING " --duration 1 --set laws.cubic.k3=abc", "k3",
                            NULL));
    char path[600], args[700];
    snprintf(path, sizeof path, "%s/bad.yaml", s.dir);
    write_file(path, "dofs: [x]\nshafts:\n  - {name: s, nodes: [{name: m}]}\n"
                     "disks:\n  - {name: m, node: m, mass: 1}\n"
                     "laws:\n  - {type: friction, node: m, dof: x, force: 1}\n");
    snprintf(args, sizeof args, "transient %s --duration 1", path);
    CHECK(run_fails_cleanly(&s, args, "bad.yaml:7:", "velocity"));
    scratch_close(&s);
}

/* One rule from a model's laws to their instances (issue 35 item 5): a law on a DOF the
 * model does not keep is the same located error in every analysis (modal and static
 * left it out without a word, transient and periodic refused it). */
TEST(law_on_a_missing_dof_is_the_same_error_everywhere)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[600], args[800];
    snprintf(path, sizeof path, "%s/lost.yaml", s.dir);
    write_file(path, "dofs: [x]\nshafts:\n  - {name: s, nodes: [{name: m}]}\n"
                     "disks:\n  - {name: m, node: m, mass: 1}\n"
                     "springs:\n  - {name: k, node: m, dof: x, stiffness: 1}\n"
                     "laws:\n  - {type: polynomial_spring, name: side, node: m, dof: y, k3: 1}\n");
    const char *runs[] = {"modal %s", "static %s", "campbell %s --speeds 0:10:2",
                          "transient %s --duration 1", "periodic %s --speeds 1:1:1"};
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        snprintf(args, sizeof args, runs[i], path);
        CHECK(run_fails_cleanly(&s, args,
                                "lost.yaml:9:5: laws[0]: law 'side' (polynomial_spring) acts on "
                                "m.y, which is not an active DOF of the model",
                                "keep the DOF type in 'dofs:'"));
    }
    scratch_close(&s);
}

/* The linear analyses linearise the laws (docs/laws.md, "Laws in the linear analyses"):
 * the Duffing oscillator's damper (0.05 N s/m on 1 kg, 1 N/m) gives zeta = 0.025 in
 * modal, and campbell finds the oil whirl of the journal rotor at the short-bearing
 * stability curve's 1134.895 rad/s (tests/campbell/test_campbell_journal.c). */
TEST(laws_in_modal_and_campbell)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "modal " DUFFING);
    REQUIRE(o);
    const cJSON *m = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "modes"), 0);
    CHECK_REL(jnum(m, "damping_ratio"), 0.025, 1e-12);
    CHECK_REL(jnum(m, "omega_n_rad_s"), 1.0, 1e-12);
    cJSON_Delete(o);
    o = run_json_args(&s, "campbell examples/journal_rotor.yaml --speeds 1000:1300:61");
    REQUIRE(o);
    CHECK_REL(jnum(o, "instability_onset_rpm"), 1134.895 * 30 / M_PI, 1e-3);
    cJSON_Delete(o);
    scratch_close(&s);
}

RUN_TESTS(T(check_lists_the_laws), T(law_records_in_transient_and_periodic), T(law_errors_exit_2),
          T(law_on_a_missing_dof_is_the_same_error_everywhere), T(laws_in_modal_and_campbell))
