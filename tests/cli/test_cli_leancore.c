/* Small CLI fixes of issue 35 item 6: `static --torque` says the total torque at its node
 * when it adds to the model's own loads, and that the model's other loads act too;
 * `frf --output` takes a comma list as `--record` does (an empty item refused); `./setup
 * help` lists the setup verbs and the Makefile's targets without installing anything. */
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "harness.h"

TEST(static_torque_says_the_total)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    run_result r;
    /* helical_two_stage: a -50 N m load at gear4 (the model's own) */
    run(&d, &r, "static examples/helical_two_stage.yaml --torque 10N*m --input gear4");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "input torque at gear4: -40 N m = --torque 10 N m + the model's own "
                          "loads there -50 N m"));
    if (r.code) show(&r);
    run_free(&r);
    /* at the default input: the total is the torque given, and the load elsewhere is said */
    run(&d, &r, "static examples/helical_two_stage.yaml --torque 10N*m");
    CHECK(r.code == 0 && contains(r.out, "input torque at b11: 10 N m (--torque)"));
    CHECK(contains(r.out, "the model's own mean loads and gravity act too, on 1 more DOF"));
    run_free(&r);
    run(&d, &r, "static examples/helical_two_stage.yaml --torque 10N*m --no-loads --json");
    CHECK(r.code == 0);
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(cJSON_GetObjectItem(o, "input_torque_total_n_m") &&
          cJSON_GetObjectItem(o, "input_torque_total_n_m")->valuedouble == 10);
    CHECK(cJSON_IsString(cJSON_GetObjectItem(o, "input_node")));
    cJSON_Delete(o);
    run_free(&r);
    /* without --torque: no such line */
    run(&d, &r, "static examples/helical_two_stage.yaml");
    CHECK(r.code == 0 && !contains(r.out, "input torque at"));
    run_free(&r);
    scratch_close(&d);
}

static int noutputs(const char *json)
{
    cJSON *o = cJSON_Parse(json);
    int n = o ? cJSON_GetArraySize(cJSON_GetObjectItem(o, "outputs")) : -1;
    cJSON_Delete(o);
    return n;
}

TEST(frf_output_takes_a_comma_list)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    run_result a, b;
    run(&d, &a,
        "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh,pinion.y "
        "--output gear.y --freq 100:2000:5 --json");
    run(&d, &b,
        "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh --output "
        "pinion.y --output gear.y --freq 100:2000:5 --json");
    CHECK(a.code == 0 && b.code == 0);
    CHECK(noutputs(a.out) == 3);
    CHECK(!strcmp(a.out, b.out)); /* the same run */
    run_free(&a);
    run_free(&b);
    const char *bad[] = {"mesh:mesh,,pinion.y", "mesh:mesh,", ",gear.y"};
    for (int k = 0; k < 3; k++) {
        run(&d, &a,
            "frf examples/kumar2011_coupled.yaml --input torque:motor --output '%s' --freq "
            "100:2000:5",
            bad[k]);
        CHECK(a.code == 2 && contains(a.err, "--output: an empty item"));
        CHECK(a.out[0] == '\0');
        run_free(&a);
    }
    scratch_close(&d);
}

TEST(setup_help_lists_the_verbs)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "cd '%s' && ./setup help 2>&1", GD_SOURCE_DIR);
    FILE *p = popen(cmd, "r");
    REQUIRE(p);
    char buf[8192];
    size_t n = fread(buf, 1, sizeof buf - 1, p);
    buf[n] = '\0';
    int st = pclose(p);
    CHECK(st == 0);
    CHECK(strstr(buf, "./setup demo") && strstr(buf, "./setup test") &&
          strstr(buf, "./setup help"));
    CHECK(strstr(buf, "Makefile targets") && strstr(buf, "  install ") &&
          strstr(buf, "  test-unit "));
    CHECK(!strstr(buf, "apt-get install")); /* nothing installed */
}

RUN_TESTS(T(static_torque_says_the_total), T(frf_output_takes_a_comma_list),
          T(setup_help_lists_the_verbs))
