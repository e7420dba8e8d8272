/* Parameter studies (geardyn/study.h): the study file, the cases of each design, one
 * case against the same model loaded with --set, failed cases as rows, the table's
 * lines, and every error of the study file located before any case runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geardyn/modal.h"
#include "geardyn/model_file.h"
#include "geardyn/static.h"
#include "geardyn/study.h"
#include "harness.h"

#define EX GD_SOURCE_DIR "/examples/"

static char *read_text_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = calloc(1, 1 << 16);
    if (buf) buf[fread(buf, 1, (1 << 16) - 1, f)] = '\0';
    fclose(f);
    return buf;
}

/* Writes a study next to the examples (its model path is relative to it). */
static const char *study_file(const char *text)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/examples/studies/.test_study_%d.yaml", GD_SOURCE_DIR,
             (int)getpid());
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return path;
}

static gd_status load_text(const char *text, gd_study **s, gd_error *err)
{
    const char *path = study_file(text);
    gd_status st = gd_study_load(path, s, err);
    remove(path);
    return st;
}

TEST(chen_fig4_cases_and_one_case_equal_a_direct_load)
{
    gd_study *s;
    gd_error err;
    REQUIRE(gd_study_load(EX "studies/chen1998_mesh_stiffness.yaml", &s, &err) == GD_OK);
    CHECK(gd_study_ncases(s) == 200);
    CHECK(gd_study_nparams(s) == 1 && gd_study_noutputs(s) == 6);
    CHECK_STR(gd_study_param_name(s, 0), "km_over_ka");
    CHECK_STR(gd_study_output_name(s, 5), "omega_n[6]");
    /* the ends exactly as written, log spacing in between: ratio of neighbours 10^(4/199) */
    CHECK(gd_study_case_value(s, 0, 0) == 0.1 && gd_study_case_value(s, 199, 0) == 1000);
    CHECK_REL(gd_study_case_value(s, 100, 0) / gd_study_case_value(s, 99, 0), pow(10, 4.0 / 199),
              1e-12);
    /* case 150 against the model loaded with the same override: bitwise equal (same text,
     * same solver) */
    gd_study_row row;
    REQUIRE(gd_study_row_init(s, &row, &err) == GD_OK);
    gd_study_run_case(s, 150, &row);
    CHECK(row.status == GD_OK && row.message[0] == '\0');
    char set[128];
    snprintf(set, sizeof set, "meshes.mesh.stiffness=%.17g N/m",
             gd_study_case_value(s, 150, 0) * 5.683e6);
    const char *sets[] = {set};
    gd_load_options opt = {1, sets};
    gd_model *m;
    gd_system *sys;
    gd_modal_result *res;
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.kind = GD_MODAL_UNDAMPED;
    REQUIRE(gd_model_load_opts(EX "chen1998_gear_pair.yaml", &opt, &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &sys, &err) == GD_OK);
    REQUIRE(gd_modal_solve(sys, &mo, &res, &err) == GD_OK);
    for (int k = 0; k < 6; k++)
        CHECK(row.outputs[k] == res->modes[k].omega_n);
    gd_modal_free(res);
    gd_system_free(sys);
    gd_model_free(m);
    /* the paper's Fig. 3 point k_m/k_a = 6 lies between cases; at the far ends the mesh
     * mode goes to the bearing-only frequencies: with k_m -> 0 the lowest lateral mode
     * of gear a is sqrt(k_a/m_a) = sqrt(5.683e6/8.975) = 795.7 rad/s (within 0.1%, the
     * mesh adds 1e-4 k_a at the left end) */
    gd_study_run_case(s, 0, &row);
    CHECK_REL(row.outputs[1], sqrt(5.683e6 / 8.975), 1e-3);
    gd_study_row_free(&row);
    gd_study_free(s);
}

TEST(factorial_zip_random_and_latin_hypercube)
{
    gd_study *s;
    gd_error err;
    const char *head = "model: ../chen1998_gear_pair.yaml\nanalysis: modal\n"
                       "outputs: [\"omega_n[1]\"]\n";
    char text[1024];
    snprintf(text, sizeof text,
             "%sparameters:\n  - {path: meshes.mesh.stiffness, values: [1e7, 2e7]}\n"
             "  - {path: bearings.support_a.k, range: {from: 1e6, to: 3e6, count: 3}}\n",
             head);
    REQUIRE(load_text(text, &s, &err) == GD_OK);
    CHECK(gd_study_ncases(s) == 6);
    /* the first parameter varies slowest */
    CHECK(gd_study_case_value(s, 0, 0) == 1e7 && gd_study_case_value(s, 2, 0) == 1e7);
    CHECK(gd_study_case_value(s, 3, 0) == 2e7);
    CHECK(gd_study_case_value(s, 1, 1) == 2e6 && gd_study_case_value(s, 5, 1) == 3e6);
    gd_study_free(s);

    snprintf(text, sizeof text,
             "%sdesign: zip\nparameters:\n  - {path: meshes.mesh.stiffness, values: [1e7, 2e7]}\n"
             "  - {path: bearings.support_a.k, values: [1e6, 3e6]}\n",
             head);
    REQUIRE(load_text(text, &s, &err) == GD_OK);
    CHECK(gd_study_ncases(s) == 2 && gd_study_case_value(s, 1, 1) == 3e6);
    gd_study_free(s);

    /* Latin hypercube: each of the 50 strata of each parameter holds exactly one sample;
     * the same seed gives the same samples, another seed others */
    const char *lhs =
        "%sdesign: latin-hypercube\nsamples: 50\nseed: %d\nparameters:\n"
        "  - {path: meshes.mesh.stiffness, range: {from: 1e7, to: 1e9, spacing: log}}\n"
        "  - {path: bearings.support_a.k, range: {from: 1e6, to: 2e6}}\n";
    snprintf(text, sizeof text, lhs, head, 7);
    REQUIRE(load_text(text, &s, &err) == GD_OK);
    CHECK(gd_study_ncases(s) == 50);
    int hit0[50] = {0}, hit1[50] = {0};
    for (size_t c = 0; c < 50; c++) {
        double u0 = (log10(gd_study_case_value(s, c, 0)) - 7) / 2;
        double u1 = (gd_study_case_value(s, c, 1) - 1e6) / 1e6;
        CHECK(u0 >= 0 && u0 < 1 && u1 >= 0 && u1 < 1);
        hit0[(int)(u0 * 50)]++;
        hit1[(int)(u1 * 50)]++;
    }
    for (int k = 0; k < 50; k++)
        CHECK(hit0[k] == 1 && hit1[k] == 1);
    double first = gd_study_case_value(s, 0, 0);
    gd_study_free(s);
    REQUIRE(load_text(text, &s, &err) == GD_OK);
    CHECK(gd_study_case_value(s, 0, 0) == first);
    gd_study_free(s);
    snprintf(text, sizeof text, lhs, head, 8);
    REQUIRE(load_text(text, &s, &err) == GD_OK);
    CHECK(gd_study_case_value(s, 0, 0) != first);
    gd_study_free(s);

    /* random: uniform samples in the range, mean near the middle (n = 2000: the standard
     * error of the mean of U(0,1) is 0.0065, so 0.03 is over 4 sigma) */
    snprintf(text, sizeof text,
             "%sdesign: random\nsamples: 2000\nparameters:\n"
             "  - {path: bearings.support_a.k, range: {from: 1e6, to: 2e6}}\n",
             head);
    REQUIRE(load_text(text, &s, &err) == GD_OK);
    double mean = 0;
    for (size_t c = 0; c < 2000; c++)
        mean += (gd_study_case_value(s, c, 0) - 1e6) / 1e6 / 2000;
    CHECK_ABS(mean, 0.5, 0.03);
    gd_study_free(s);
}

TEST(failed_case_is_a_row_and_rows_round_trip)
{
    gd_study *s;
    gd_error err;
    REQUIRE(load_text("model: ../chen1998_gear_pair.yaml\nanalysis: modal\n"
                      "parameters:\n  - {path: meshes.mesh.stiffness, values: [3e7, -1, 4e7]}\n"
                      "outputs: [\"omega_n[1:2]\", nmodes]\n",
                      &s, &err) == GD_OK);
    gd_study_row row, back;
    REQUIRE(gd_study_row_init(s, &row, &err) == GD_OK &&
            gd_study_row_init(s, &back, &err) == GD_OK);
    gd_study_run_case(s, 1, &row);
    CHECK(row.status == GD_EINPUT);
    CHECK(strstr(row.message, "--set meshes.mesh.stiffness=-1") != NULL);
    CHECK(isnan(row.outputs[0]) && !strchr(row.message, '\n'));
    char line[4096];
    gd_study_format_row(s, &row, line, sizeof line);
    CHECK(strstr(line, ",input error,") != NULL);
    REQUIRE(gd_study_parse_row(s, line, &back, &err) == GD_OK);
    CHECK(back.index == 1 && back.status == GD_EINPUT && !strcmp(back.message, row.message));
    /* a message with commas and quotes survives the CSV quoting */
    snprintf(row.message, sizeof row.message, "a \"quoted\", comma");
    gd_study_run_case(s, 2, &row);
    snprintf(row.message, sizeof row.message, "a \"quoted\", comma");
    gd_study_format_row(s, &row, line, sizeof line);
    REQUIRE(gd_study_parse_row(s, line, &back, &err) == GD_OK);
    CHECK_STR(back.message, "a \"quoted\", comma");
    CHECK(back.outputs[0] == row.outputs[0] && back.outputs[2] == 6);
    /* a cut line is not a row */
    line[strlen(line) / 2] = '\0';
    CHECK(gd_study_parse_row(s, line, &back, &err) == GD_EINPUT);
    gd_study_row_free(&row);
    gd_study_row_free(&back);
    gd_study_free(s);

    /* an error in the model file itself, found in every case, keeps its place in the
     * file: the parsed document's clone keeps lines and columns */
    char *model = read_text_file(EX "chen1998_gear_pair.yaml");
    REQUIRE(model);
    char *at = strstr(model, "k: 25.5735 MN/m");
    REQUIRE(at);
    memcpy(at, "k: -5.5735 MN/m", 15);
    char mpath[256];
    snprintf(mpath, sizeof mpath, "%s/examples/studies/.test_model_%d.yaml", GD_SOURCE_DIR,
             (int)getpid());
    FILE *f = fopen(mpath, "w");
    REQUIRE(f);
    fputs(model, f);
    fclose(f);
    free(model);
    char text[512];
    snprintf(text, sizeof text,
             "model: .test_model_%d.yaml\nanalysis: modal\nparameters:\n"
             "  - {path: meshes.mesh.stiffness, values: [3e7]}\noutputs: [nmodes]\n",
             (int)getpid());
    gd_status st = load_text(text, &s, &err);
    CHECK(st == GD_OK);
    if (!st) {
        gd_study_row_init(s, &row, &err);
        gd_study_run_case(s, 0, &row);
        CHECK(row.status == GD_EINPUT);
        CHECK(strstr(row.message, ".test_model_") && strstr(row.message, ".yaml:24:"));
        if (!strstr(row.message, ".yaml:24:")) fprintf(stderr, "  %s\n", row.message);
        gd_study_row_free(&row);
        gd_study_free(s);
    }
    remove(mpath);
}

/* Runs case c of the study text into out (n outputs); the case must succeed. */
static int run_one(gd_test_state *gd_ts_, const char *text, size_t c, double *out, int n)
{
    gd_study *s;
    gd_error err;
    if (load_text(text, &s, &err)) {
        char buf[2048];
        gd_error_format(&err, buf, sizeof buf);
        fprintf(stderr, "  %s\n", buf);
        gd_ts_->checks_failed++;
        return 1;
    }
    gd_study_row row;
    gd_study_row_init(s, &row, &err);
    gd_study_run_case(s, c, &row);
    if (row.status) fprintf(stderr, "  case failed: %s\n", row.message);
    CHECK(row.status == GD_OK && gd_study_noutputs(s) == n);
    for (int i = 0; i < n; i++)
        out[i] = row.outputs[i];
    gd_study_row_free(&row);
    gd_study_free(s);
    return 0;
}

TEST(every_analysis_gives_the_papers_numbers)
{
    double v[4];
    /* Campbell of the MMT 2018 rig: the first critical speed is the 48x tooth-mesh order
     * crossing the first elastic mode, 126.5 Hz (Table 4): 48 rpm/60 = 126.5 Hz within
     * the sweep's interpolation (1%); two elements per section (126.54 Hz, see
     * rig2018_convergence.yaml) keep the test fast */
    if (!run_one(
            gd_ts_,
            "model: ../rig2018.yaml\nanalysis: {type: campbell, speeds: {from: 0, to: "
            "1200 rpm, count: 13}, modes: 4}\nparameters:\n  - {path: "
            "\"shafts.*.elements_per_section\", values: [2]}\noutputs: [\"critical_speed_rpm[1]\", "
            "\"critical_frequency_hz[1]\", ncritical]\n",
            0, v, 3)) {
        CHECK_REL(v[0] * 48 / 60, 126.5, 0.01);
        CHECK_REL(v[1], 126.5, 0.01);
        CHECK(v[2] >= 1);
    }
    /* FRF of Kumar & Rao 2011 (coupled): the mesh force per motor torque peaks at the
     * lateral-torsional mesh mode, 23288.5 rad/s = 3706.5 Hz, within the grid spacing
     * (25000/399 rad/s = 10 Hz) */
    if (!run_one(gd_ts_,
                 "model: ../kumar2011_coupled.yaml\nanalysis: {type: frf, input: \"torque:motor\", "
                 "output: \"mesh:mesh\", frequencies: {from: 1000, to: 26000, count: 400}}\n"
                 "parameters:\n  - {path: meshes.mesh.damping, values: [0]}\n"
                 "outputs: [peak_magnitude, peak_frequency_hz]\n",
                 0, v, 2)) {
        CHECK_ABS(v[1], 3706.47, 10.1);
        CHECK(v[0] > 0);
    }
    /* Unbalance of Chen 1998 (gear a): the response of gear a across the line of action
     * peaks at the 1071.6 rad/s mode (Fig. 3 list), within the grid spacing 19.7 rad/s
     * and the damped shift */
    if (!run_one(gd_ts_,
                 "model: ../chen1998_gear_pair.yaml\nanalysis: {type: unbalance, output: gear_a.y, "
                 "speeds: {from: 100, to: 6000, count: 300}}\nparameters:\n  - {path: "
                 "meshes.mesh.stiffness, values: [34.098e6]}\noutputs: [peak_amplitude, "
                 "peak_speed_rpm]\n",
                 0, v, 2)) {
        CHECK_ABS(v[1] * M_PI / 30, 1071.6, 25);
    }
    /* Transient of the Ducati timing train with m01's backlash 15 um (the example's own
     * value): the numbers `geardyn transient --revolutions 0.2` prints for m01 (2 contact
     * losses, 1.74443e-4 s separated, to its 6 digits) */
    if (!run_one(gd_ts_,
                 "model: ../ducati_timing_geartrain.yaml\nanalysis: {type: transient, revolutions: "
                 "0.2, mesh: m01}\nparameters:\n  - {path: meshes.m01.backlash.gap, values: "
                 "[15 um]}\noutputs: [contact_losses, separated_time, mesh_force_max]\n",
                 0, v, 3)) {
        CHECK(v[0] == 2);
        CHECK_REL(v[1], 1.74443e-4, 1e-5);
        CHECK(v[2] > 0);
    }
    /* Mesh stiffness of [JMSTHelical]'s pair 1 at 20 deg: the contact ratios of Table 1 */
    if (!run_one(gd_ts_,
                 "model: ../helical_pair1.yaml\nanalysis: {type: mesh-stiffness, points: 60, "
                 "slices: 20}\nparameters:\n  - {path: meshes.pair1.geometry.helix_angle, unit: "
                 "deg, values: [20]}\noutputs: [contact_ratio_transverse, contact_ratio_face]\n",
                 0, v, 2)) {
        CHECK_ABS(v[0], 1.6268, 5e-5);
        CHECK_ABS(v[1], 1.2442, 5e-5);
    }
}

/* The analyses that linearise the model's laws do it about the static equilibrium, as
 * `geardyn modal` does (gd_static_operating_point): the rig on 5-DOF ball bearings with
 * 2 um clearance had every bearing at q = 0 in a study (frequency_hz[1:3] 0, 0, 0) where
 * `geardyn modal examples/rig2018_geometry.yaml` gives 0, 123.02, 128.85 Hz. The case
 * equals the direct run bit for bit. */
TEST(linearising_analyses_use_the_static_operating_point)
{
    double v[3];
    if (run_one(gd_ts_,
                "model: ../rig2018_geometry.yaml\nanalysis: {type: modal}\nparameters:\n"
                "  - {path: gravity.g, values: [9.81]}\noutputs: [\"frequency_hz[1:3]\"]\n",
                0, v, 3))
        return;
    CHECK_ABS(v[0], 0, 1e-3); /* the train's rotation */
    CHECK_REL(v[1], 123.02, 5e-5);
    CHECK_REL(v[2], 128.85, 5e-5);
    gd_model *m = NULL;
    gd_system *sys = NULL;
    gd_error err;
    REQUIRE(gd_model_load(EX "rig2018_geometry.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &sys, &err) == GD_OK);
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    gd_static_options so;
    gd_static_options_init(&so);
    so.speed = mo.speed;
    REQUIRE(gd_static_operating_point(sys, &so, 1, &err) == GD_OK);
    gd_modal_result *res = NULL;
    REQUIRE(gd_modal_solve(sys, &mo, &res, &err) == GD_OK);
    for (int k = 0; k < 3; k++)
        CHECK(v[k] == res->modes[k].frequency_hz);
    gd_modal_free(res);
    gd_system_free(sys);
    gd_model_free(m);
    /* a sweep (campbell) solves the equilibrium at each speed: its first critical speed
       is above 0 only with the bearings holding the shafts */
    if (!run_one(gd_ts_,
                 "model: ../rig2018_geometry.yaml\nanalysis: {type: campbell, speeds: {from: 0, "
                 "to: 300 rpm, count: 4}, modes: 4}\nparameters:\n"
                 "  - {path: gravity.g, values: [9.81]}\noutputs: [\"critical_frequency_hz[1]\"]\n",
                 0, v, 1))
        CHECK(v[0] > 100 && v[0] < 140);
}

/* Periodic steady state of the damped-Mathieu pair (tests/plot/mathieu_pair.yaml) across
 * its primary tongue, 680..730 rad/s: period doubling at both boundaries, 698.97 and
 * 715.17 rad/s (first-order transition curves, Nayfeh & Mook 1979 Sec. 5.4, as
 * test_periodic: within 0.05 rad/s), the four points inside unstable, and the numbers
 * `geardyn periodic ... --speeds 680:730:11 --harmonics 4 --record mesh:m:force` prints
 * (its 6 digits: p2p 54.7927 N at 680 rad/s, |mu| max 1.022790 at 705 rad/s). */
TEST(periodic_summarises_the_branch)
{
    double v[12];
    if (run_one(gd_ts_,
                "model: ../../tests/plot/mathieu_pair.yaml\nanalysis: {type: periodic, speeds: "
                "{from: 680, to: 730, count: 11}, harmonics: 4, output: \"mesh:m\"}\n"
                "parameters:\n  - {path: meshes.m.damping, values: [141.42135623730951]}\n"
                "outputs: [p2p_max, p2p_max_speed_rpm, floquet_max, unstable_points, "
                "converged_points, nbifurcations, nperiod_doublings, nfolds, nneimark_sacker, "
                "first_bifurcation_rpm, \"harmonic_amplitude_max[1:2]\"]\n",
                0, v, 12))
        return;
    CHECK_REL(v[0], 54.7927, 1e-5);
    CHECK_REL(v[1] * M_PI / 30, 680, 1e-12);
    CHECK_REL(v[2], 1.022790, 1e-6);
    CHECK(v[3] == 4 && v[4] == 11 && v[5] == 2 && v[6] == 2 && v[7] == 0 && v[8] == 0);
    CHECK_ABS(v[9] * M_PI / 30, 698.97, 0.05);
    /* harmonic 1 carries most of the fluctuation: 2 A_1 close to the peak-to-peak */
    CHECK(v[10] > 0.4 * v[0] && v[10] < 0.5 * v[0] * 1.01 && v[11] < 0.1 * v[10]);
    /* an output this analysis does not have is refused before any case runs */
    gd_study *s = NULL;
    gd_error err;
    CHECK(load_text("model: ../../tests/plot/mathieu_pair.yaml\nanalysis: {type: periodic, "
                    "speeds: {from: 680, to: 730, count: 3}, output: \"mesh:nope\"}\n"
                    "parameters:\n  - {path: meshes.m.damping, values: [100]}\n"
                    "outputs: [p2p_max]\n",
                    &s, &err) == GD_EINPUT);
    CHECK(s == NULL && strstr(err.message, "no mesh named 'nope'"));
    gd_study_free(s);
}

/* Sink of periodic_cases_on_threads: the first output of case c into out[c]. */
static int keep_first_output(void *user, const gd_study_row *row)
{
    double *out = user;
    out[row->index] = row->status == GD_OK ? row->outputs[0] : NAN;
    return 0;
}

/* Eight periodic cases (the Mathieu pair at eight dampings) over two threads give the
 * bits the same cases give one at a time: each case plans its FFTs while another runs
 * (the planner is made thread-safe once, src/signal/fft_planner.c). */
TEST(periodic_cases_on_threads)
{
    gd_study *s = NULL;
    gd_error err;
    REQUIRE(load_text("model: ../../tests/plot/mathieu_pair.yaml\nanalysis: {type: periodic, "
                      "speeds: {from: 690, to: 720, count: 4}, harmonics: 4, output: "
                      "\"mesh:m\"}\nparameters:\n  - {path: meshes.m.damping, values: [100, "
                      "110, 120, 130, 140, 150, 160, 170]}\noutputs: [p2p_max]\n",
                      &s, &err) == GD_OK);
    size_t cases[8];
    double one[8], two[8];
    for (int c = 0; c < 8; c++)
        cases[c] = (size_t)c;
    REQUIRE(gd_study_run(s, cases, 8, 1, keep_first_output, one, &err) == GD_OK);
    REQUIRE(gd_study_run(s, cases, 8, 2, keep_first_output, two, &err) == GD_OK);
    int same = 0;
    for (int c = 0; c < 8; c++)
        same += one[c] > 0 && memcmp(&one[c], &two[c], sizeof one[c]) == 0;
    CHECK(same == 8);
    /* more damping, less response inside the tongue */
    CHECK(one[7] < one[0]);
    gd_study_free(s);
}

/* Each bad study: GD_EINPUT at the line and field given, with the words expected. */
static void bad(gd_test_state *gd_ts_, const char *text, int line, const char *field,
                const char *words)
{
    gd_study *s = NULL;
    gd_error err;
    gd_error_clear(&err);
    CHECK(load_text(text, &s, &err) == GD_EINPUT);
    CHECK(s == NULL);
    if (err.line != line || strcmp(err.field, field) || !strstr(err.message, words)) {
        char buf[2048];
        gd_error_format(&err, buf, sizeof buf);
        fprintf(stderr, "  expected line %d field %s '%s', got: %s\n", line, field, words, buf);
        gd_ts_->checks_failed++;
    }
    gd_study_free(s);
}

TEST(errors_are_located_in_the_study_file)
{
    const char *h = "model: ../chen1998_gear_pair.yaml\nanalysis: modal\n";
    char t[1024];
    snprintf(t, sizeof t,
             "%sparameters:\n  - {path: meshes.nope.stiffness, values: [1]}\n"
             "outputs: [\"omega_n[1]\"]\n",
             h);
    bad(gd_ts_, t, 4, "parameters[0].path", "reaches nothing");
    snprintf(t, sizeof t,
             "%sparameters:\n  - {path: meshes.mesh.stifness, values: [1]}\n"
             "outputs: [\"omega_n[1]\"]\n",
             h);
    bad(gd_ts_, t, 4, "parameters[0].path", "does not accept");
    snprintf(t, sizeof t,
             "%sparameters:\n  - path: meshes.mesh.stiffness\n"
             "    range: {from: 1, to: 2, count: 0}\noutputs: [\"omega_n[1]\"]\n",
             h);
    bad(gd_ts_, t, 5, "parameters[0].range.count", "empty range");
    snprintf(t, sizeof t,
             "%sparameters:\n  - {path: meshes.mesh.stiffness, values: []}\n"
             "outputs: [\"omega_n[1]\"]\n",
             h);
    bad(gd_ts_, t, 4, "parameters[0].values", "empty list");
    snprintf(t, sizeof t,
             "%sparameters:\n  - {path: meshes.mesh.stiffness, values: [1e7]}\n"
             "outputs: [\"omega_n[1]\", peak_force]\n",
             h);
    bad(gd_ts_, t, 5, "outputs[1]", "unknown output 'peak_force'");
    snprintf(t, sizeof t,
             "%sparameters:\n  - {path: meshes.mesh.stiffness, values: [1e7]}\n"
             "outputs: [omega_n]\n",
             h);
    bad(gd_ts_, t, 5, "outputs[0]", "needs an index");
    snprintf(t, sizeof t,
             "model: ../chen1998_gear_pair.yaml\nanalysis: {type: modes}\n"
             "parameters:\n  - {path: meshes.mesh.stiffness, values: [1e7]}\n"
             "outputs: [nmodes]\n");
    bad(gd_ts_, t, 2, "analysis.type", "unknown analysis 'modes'");
    snprintf(t, sizeof t,
             "%sdesign: zip\nparameters:\n  - {path: meshes.mesh.stiffness, values: [1, 2]}\n"
             "  - {path: bearings.support_a.k, values: [1]}\noutputs: [nmodes]\n",
             h);
    bad(gd_ts_, t, 6, "parameters[1]", "1 values where parameters[0] has 2");
    snprintf(t, sizeof t,
             "%sdesign: random\nparameters:\n  - {path: meshes.mesh.stiffness, range: {from: 1, "
             "to: 2}}\n"
             "outputs: [nmodes]\n",
             h);
    bad(gd_ts_, t, 3, "samples", "needs the number of samples");
    snprintf(t, sizeof t,
             "%sparameters:\n  - {path: meshes.mesh.stiffness, values: [1e7]}\n"
             "outputs: [nmodes]\nsampels: 3\n",
             h);
    bad(gd_ts_, t, 6, "sampels", "unknown key");
    snprintf(t, sizeof t,
             "model: ../chen1998_gear_pair.yaml\nanalysis: {type: frf, input: \"torque:gear_a\",\n"
             "  output: \"mesh:nope\", frequencies: {from: 1, to: 2, count: 2}}\n"
             "parameters:\n  - {path: meshes.mesh.stiffness, values: [1e7]}\noutputs: "
             "[peak_magnitude]\n");
    bad(gd_ts_, t, 2, "analysis", "no mesh named 'nope'");
    snprintf(t, sizeof t,
             "%sparameters:\n  - {name: status, path: meshes.mesh.stiffness, values: [1e7]}\n"
             "outputs: [nmodes]\n",
             h);
    bad(gd_ts_, t, 4, "parameters[0]", "a column of the table itself");
    snprintf(t, sizeof t, "model: ../missing.yaml\nanalysis: modal\nparameters: []\noutputs: []\n");
    bad(gd_ts_, t, 1, "model", "cannot read model");
}

RUN_TESTS(T(chen_fig4_cases_and_one_case_equal_a_direct_load), T(periodic_summarises_the_branch),
          T(periodic_cases_on_threads), T(every_analysis_gives_the_papers_numbers),
          T(factorial_zip_random_and_latin_hypercube), T(failed_case_is_a_row_and_rows_round_trip),
          T(errors_are_located_in_the_study_file),
          T(linearising_analyses_use_the_static_operating_point))
