/* geardyn testmodal and correlate: synthetic measurements with a known truth (the tests'
 * UFF writer, tests/uff_support.h), the seed 004 table, a test setup, and every error
 * path: located message, exit 2, nothing on stdout, no figure written. */
#include "cli_support.h"
#include "harness.h"
#include "uff_support.h"

static scratch S;
static synth SY;
static char UFF[256], UFFB[256];

static int setup_once(void)
{
    if (UFF[0]) return 1;
    if (!scratch_open(&S)) return 0;
    if (!synth_make(&SY, 1.2, 0.02, 12, 4097, 0.25, 36)) return 0;
    snprintf(UFF, sizeof UFF, "%s/rig.uff", S.dir);
    snprintf(UFFB, sizeof UFFB, "%s/rig_b.uff", S.dir);
    return synth_write_uff(&SY, UFF, 0, 6) && synth_write_uff(&SY, UFFB, 1, 5);
}

/* an error run: exit 2, the words on stderr, nothing on stdout, no figure */
static int fails_cleanly(const char *args, const char *w1, const char *w2)
{
    char plot[300];
    snprintf(plot, sizeof plot, "%s/fig.svg", S.dir);
    remove(plot);
    run_result r;
    run(&S, &r, "%s --plot '%s'", args, plot);
    int ok = r.code == 2 && contains(r.err, w1) && (!w2 || contains(r.err, w2)) && !r.out[0] &&
             !file_exists(plot);
    if (!ok) {
        fprintf(stderr, "  args: %s\n", args);
        show(&r);
    }
    run_free(&r);
    return ok;
}

TEST(testmodal_finds_the_true_modes)
{
    REQUIRE(setup_once());
    char args[600], plot[300];
    snprintf(plot, sizeof plot, "%s/stab.svg", S.dir);
    snprintf(args, sizeof args, "testmodal '%s' --plot '%s'", UFFB, plot);
    cJSON *o = run_json_args(&S, args);
    REQUIRE(o);
    const cJSON *modes = cJSON_GetObjectItem(o, "modes");
    int nvis = 0;
    for (int t = 0; t < SY.nmodes; t++) {
        if (!SY.visible[t]) continue;
        nvis++;
        int found = 0;
        const cJSON *m;
        cJSON_ArrayForEach(m, modes)
        {
            /* issue 36: 0.3 % in frequency, 15 % in damping */
            if (fabs(jnum(m, "frequency_hz") / SY.hz[t] - 1) < 0.003 &&
                fabs(jnum(m, "damping_ratio") / SY.zeta[t] - 1) < 0.15)
                found = 1;
        }
        CHECK(found);
    }
    CHECK(nvis >= 3 && cJSON_GetArraySize(modes) <= nvis + 1);
    const cJSON *shape = cJSON_GetObjectItem(cJSON_GetArrayItem(modes, 0), "shape");
    CHECK(cJSON_GetArraySize(shape) == 12);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(o, "stabilisation")) > 100);
    CHECK(file_exists(plot));
    char *svg = read_file(plot);
    CHECK(svg && contains(svg, "<svg") && contains(svg, "stable frequency and damping"));
    free(svg);
    cJSON_Delete(o);
    /* peak picking, text */
    run_result r;
    CHECK(run(&S, &r, "testmodal '%s' --method peaks --band 100:900", UFF) == 0);
    CHECK(contains(r.out, "peaks:") && contains(r.out, "mode"));
    run_free(&r);
}

TEST(correlate_updates_the_bearings)
{
    REQUIRE(setup_once());
    char args[700];
    snprintf(args, sizeof args,
             "correlate examples/rig2018.yaml '%s' --set 'dofs=[y, rx, rz]' --update "
             "'bearings.*.k=3e7:5e8' --fd-check",
             UFF);
    cJSON *o = run_json_args(&S, args);
    REQUIRE(o);
    const cJSON *u = cJSON_GetObjectItem(o, "update");
    const cJSON *p = cJSON_GetArrayItem(cJSON_GetObjectItem(u, "parameters"), 0);
    CHECK_REL(jnum(p, "updated"), 1.2e8, 0.02);
    CHECK(jnum(p, "std_dev") > 0);
    const cJSON *pairs = cJSON_GetObjectItem(cJSON_GetObjectItem(o, "correlation"), "pairs");
    const cJSON *q;
    cJSON_ArrayForEach(q, pairs) CHECK(jnum(q, "mac") > 0.99);
    /* the overlay: the model's FRF at the measured points, 12 of them */
    const cJSON *frfs = cJSON_GetObjectItem(o, "frfs");
    CHECK(cJSON_GetArraySize(frfs) == 12);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(cJSON_GetArrayItem(frfs, 0), "model_re")) == 4097);
    cJSON_Delete(o);
}

TEST(correlate_seed004_table_and_setup)
{
    REQUIRE(setup_once());
    run_result r;
    CHECK(run(&S, &r, "correlate examples/rig2018.yaml examples/mmt2018_coupled_modes.csv") == 0);
    CHECK(contains(r.out, "121.90       126.53") && contains(r.out, "rms difference 3.503 %"));
    run_free(&r);
    /* a setup file naming the model's nodes: the same result as the default numbering */
    gd_model *m;
    gd_error err;
    const char *sets[1] = {"dofs=[y, rx, rz]"};
    gd_load_options lo = {1, sets};
    REQUIRE(gd_model_load_opts("examples/rig2018.yaml", &lo, &m, &err) == GD_OK);
    char path[300], text[4096];
    size_t n = (size_t)snprintf(text, sizeof text, "points:\n");
    for (int j = 0; j < SY.nresp; j++)
        n += (size_t)snprintf(text + n, sizeof text - n, "  %d: '%s'\n", SY.resp_node[j] + 1,
                              m->nodes[SY.resp_node[j]].name);
    snprintf(path, sizeof path, "%s/setup.yaml", S.dir);
    write_file(path, text);
    gd_model_free(m);
    CHECK(run(&S, &r, "correlate examples/rig2018.yaml '%s' --set 'dofs=[y, rx, rz]' --setup '%s'",
              UFF, path) == 0);
    CHECK(contains(r.out, "0.999"));
    run_free(&r);
    /* a node that is not in the model */
    text[strlen("points:\n  ") + snprintf(NULL, 0, "%d: ", SY.resp_node[0] + 1)] = 0;
    strcat(text, "nowhere\n");
    write_file(path, text); /* the first point's node is not in the model */
    char args[800];
    snprintf(args, sizeof args,
             "correlate examples/rig2018.yaml '%s' --set 'dofs=[y, rx, rz]' --setup '%s'", UFF,
             path);
    CHECK(fails_cleanly(args, "node 'nowhere' of test point", "is not in the model"));
    /* a point missing from the setup */
    snprintf(text, sizeof text, "points:\n  %d: gear48\n", SY.resp_node[1] + 1);
    write_file(path, text);
    CHECK(fails_cleanly(args, "is not in the test setup", NULL));
}

TEST(bad_input_is_refused_cleanly)
{
    REQUIRE(setup_once());
    char *text = read_file(UFF);
    REQUIRE(text);
    char bad[300], args[800];
    snprintf(bad, sizeof bad, "%s/bad.uff", S.dir);
    /* cut in the middle */
    text[strlen(text) / 3 + 777] = 0; /* inside the 5th dataset's values */
    write_file(bad, text);
    snprintf(args, sizeof args, "testmodal '%s'", bad);
    CHECK(fails_cleanly(args, "bad.uff:", "cut short"));
    free(text);
    text = read_file(UFF);
    /* unknown dataset type */
    memcpy(strchr(text, '\n') + 1, "   151", 6);
    write_file(bad, text);
    CHECK(fails_cleanly(args, "bad.uff:2:", "dataset type 151 is not read"));
    memcpy(strchr(text, '\n') + 1, "    58", 6);
    /* units that do not convert */
    char *u = strstr(text, "m/s^2");
    memcpy(u, "degC ", 5);
    write_file(bad, text);
    CHECK(fails_cleanly(args, "bad.uff:11:", "cannot convert"));
    memcpy(u, "m/s^2", 5);
    /* a frequency axis that does not increase */
    char *r7 = strstr(text, " 2.50000E-01");
    REQUIRE(r7);
    memcpy(r7, " 0.00000E+00", 12);
    write_file(bad, text);
    CHECK(fails_cleanly(args, "bad.uff:9:", "does not increase"));
    free(text);
    /* too few lines; then a node not in the model: point 99 of a 34-node model, no setup */
    snprintf(bad, sizeof bad, "%s/far.csv", S.dir);
    write_file(bad, "# geardyn frf\n# response: 99 +y\n# reference: 2 +y\n# units: m/N\n"
                    "frequency_hz,re,im\n10,1e-6,0\n20,2e-6,0\n");
    snprintf(args, sizeof args, "testmodal '%s'", bad); /* two lines: too few to fit */
    CHECK(fails_cleanly(args, "lines in the band", NULL));
    {
        /* enough lines for a fit: 200 of a single-mode FRF */
        char *t2 = malloc(20000);
        size_t n = (size_t)sprintf(t2, "# geardyn frf\n# response: 99 +y\n# reference: 2 +y\n"
                                       "# units: m/N\nfrequency_hz,re,im\n");
        for (int k = 1; k <= 200; k++) {
            double w = 2 * M_PI * k, wn = 2 * M_PI * 100, d = wn * wn - w * w, c = 0.04 * wn * w;
            n += (size_t)sprintf(t2 + n, "%d,%.10g,%.10g\n", k, d / (d * d + c * c),
                                 -c / (d * d + c * c));
        }
        write_file(bad, t2);
        free(t2);
    }
    snprintf(args, sizeof args, "correlate examples/rig2018.yaml '%s'", bad);
    CHECK(fails_cleanly(args, "far.csv:", "test point 99 is not a node of the model"));
    /* an updating parameter that changes no target */
    CHECK(fails_cleanly("correlate examples/rig2018.yaml examples/mmt2018_coupled_modes.csv "
                        "--update 'bearings.*.c=1:1000'",
                        "bearings.*.c", "changes no target frequency"));
    CHECK(fails_cleanly("correlate examples/rig2018.yaml examples/mmt2018_coupled_modes.csv "
                        "--update 'bearings.*.k=5e8:1e7'",
                        "bounds", "0 < LO < HI"));
    CHECK(fails_cleanly("correlate examples/rig2018.yaml examples/mmt2018_coupled_modes.csv "
                        "--update 'bearings.nope.k=1e7:5e8'",
                        "nope", NULL));
    CHECK(fails_cleanly("correlate examples/rig2018.yaml examples/mmt2018_coupled_modes.csv "
                        "--update 'bearings.*.k'",
                        "KEY=LO:HI", NULL));
    snprintf(args, sizeof args, "testmodal '%s' --band 900:100", UFF);
    CHECK(fails_cleanly(args, "--band", NULL));
    CHECK(fails_cleanly("testmodal examples/rig2018.yaml", "not a test-data file", NULL));
    CHECK(fails_cleanly("testmodal", "give at least one test-data file", NULL));
    CHECK(
        fails_cleanly("testmodal examples/mmt2018_coupled_modes.csv", "no FRF in the files", NULL));
    CHECK(fails_cleanly("correlate examples/rig2018.yaml",
                        "give a model file and at least one test-data file", NULL));
    snprintf(args, sizeof args, "testmodal '%s' --method peaks", UFF);
    CHECK(fails_cleanly(args, "--plot draws LSCF's stabilisation diagram", NULL));
    snprintf(args, sizeof args, "testmodal '%s' --order 1", UFF);
    CHECK(fails_cleanly(args, "--order", NULL));
}

static void done(void)
{
    if (UFF[0]) {
        scratch_close(&S);
        synth_free(&SY);
    }
}

int main(int argc, char **argv)
{
    static const gd_test_case cases[] = {
        T(testmodal_finds_the_true_modes), T(correlate_updates_the_bearings),
        T(correlate_seed004_table_and_setup), T(bad_input_is_refused_cleanly)};
    int rc = gd_test_run(cases, 4, argc, argv);
    done();
    return rc;
}
