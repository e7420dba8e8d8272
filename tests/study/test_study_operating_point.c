/* `analysis: {operating_point: static|zero}` of a study (docs/studies.md): the state the
 * model's laws are linearised about, with the words and meaning of the CLI's
 * `--operating-point`. Before it a study always linearised at the static equilibrium, so
 * `geardyn modal --operating-point zero` had no study equivalent (the key was refused as
 * unknown). A case equals what `geardyn modal ... --operating-point static|zero` computes
 * bit for bit both ways (and its JSON to its printing); a wrong
 * value, and the key on an analysis that linearises nothing, are located errors. */
#include <unistd.h>

#include "cli_support.h"
#include "geardyn/blas.h"
#include "geardyn/modal.h"
#include "geardyn/model_file.h"
#include "geardyn/static.h"
#include "geardyn/study.h"
#include "harness.h"

/* Loads a study text (written into the scratch folder; the model path is absolute). */
static gd_status load_text(const scratch *sc, const char *text, gd_study **s, gd_error *err)
{
    char path[256];
    snprintf(path, sizeof path, "%s/study.yaml", sc->dir);
    write_file(path, text);
    return gd_study_load(path, s, err);
}

/* Case 0 of a one-case modal study of model at speed (rpm) with op ("" for no key) into
 * v[0..n-1] = frequency_hz[1..n]. 0 when it ran. */
static int study_case(gd_test_state *gd_ts_, const scratch *sc, const char *model, double rpm,
                      const char *op, double *v, int n)
{
    char text[2048];
    snprintf(text, sizeof text,
             "model: %s/examples/%s\nanalysis: {type: modal, speed: %.17g rpm, modes: %d%s%s}\n"
             "parameters:\n  - {path: gravity.g, values: [9.81]}\n"
             "outputs: [\"frequency_hz[1:%d]\"]\n",
             GD_SOURCE_DIR, model, rpm, n, op[0] ? ", operating_point: " : "", op, n);
    gd_study *s = NULL;
    gd_error err;
    if (load_text(sc, text, &s, &err)) {
        char buf[2048];
        gd_error_format(&err, buf, sizeof buf);
        fprintf(stderr, "  %s\n", buf);
        gd_ts_->checks_failed++;
        return 1;
    }
    gd_study_row row;
    gd_study_row_init(s, &row, &err);
    gd_study_run_case(s, 0, &row);
    if (row.status) fprintf(stderr, "  case failed: %s\n", row.message);
    CHECK(row.status == GD_OK && gd_study_noutputs(s) == n);
    for (int i = 0; i < n; i++)
        v[i] = row.outputs[i];
    gd_study_row_free(&row);
    gd_study_free(s);
    return 0;
}

/* `geardyn modal MODEL --speed RPMrpm --modes n [--operating-point op] --json`'s
 * frequency_hz of modes 1..n into v (cJSON prints the shortest text that reads back the
 * same double). 0 when it ran. */
static int cli_modes(gd_test_state *gd_ts_, scratch *sc, const char *model, double rpm,
                     const char *op, double *v, int n)
{
    char args[512];
    snprintf(args, sizeof args, "modal examples/%s --speed %.17grpm --modes %d%s%s", model, rpm, n,
             op[0] ? " --operating-point " : "", op);
    cJSON *o = run_json_args(sc, args);
    if (!o) {
        gd_ts_->checks_failed++;
        return 1;
    }
    const cJSON *modes = cJSON_GetObjectItemCaseSensitive(o, "modes");
    CHECK(cJSON_GetArraySize(modes) == n);
    for (int i = 0; i < n; i++)
        v[i] = jnum(cJSON_GetArrayItem(modes, i), "frequency_hz");
    cJSON_Delete(o);
    return 0;
}

/* What `geardyn modal` does (cli/cmd_modal.c with cli/operating_point.c), in this
 * process: the operating point op set on the loaded system, then gd_modal_solve with the
 * CLI's options (no left vectors). */
static int direct_modes(gd_test_state *gd_ts_, const char *model, double rpm, const char *op,
                        double *v, int n)
{
    char path[512];
    snprintf(path, sizeof path, "%s/examples/%s", GD_SOURCE_DIR, model);
    gd_model *m = NULL;
    gd_system *sys = NULL;
    gd_error err;
    int bad = gd_model_load(path, &m, &err) || gd_system_build(m, &sys, &err);
    double speed = rpm * M_PI / 30;
    if (!bad && !strcmp(op, "zero"))
        bad = gd_system_set_operating_point(sys, GD_OPERATING_ZERO, NULL, NULL, &err);
    else if (!bad) {
        gd_static_options so;
        gd_static_options_init(&so);
        so.speed = speed;
        bad = gd_static_operating_point(sys, &so, 1, &err);
    }
    gd_modal_result *r = NULL;
    if (!bad) {
        gd_modal_options o;
        gd_modal_options_init(&o);
        o.speed = speed;
        o.nmodes = n;
        o.want_left = 0;
        bad = gd_modal_solve(sys, &o, &r, &err);
    }
    CHECK(!bad);
    for (int i = 0; !bad && i < n; i++)
        v[i] = i < r->nmodes ? r->modes[i].frequency_hz : NAN;
    gd_modal_free(r);
    gd_system_free(sys);
    gd_model_free(m);
    return bad;
}

/* rig2018_geometry (ball bearings from geometry, 2 um clearance) at 1000 rpm: about the
 * static equilibrium the bearings carry the gears' weight (123 Hz and up); about q = 0
 * they sit in their clearance and hold nothing (the lowest modes at 0 Hz). The study
 * equals the CLI bit for bit in both, and the two differ. */
TEST(study_operating_point_equals_cli_both_ways)
{
    /* `geardyn modal` is not independent of OpenBLAS's thread count in its last bits
       (OMP_NUM_THREADS=2: 519.379649856754 Hz for rig2018_geometry's mode 6 at 1000 rpm,
       1: ...733): one thread here and in the CLI, as a study's cases run */
    gd_blas_set_threads(1);
    setenv("OMP_NUM_THREADS", "1", 1);
    setenv("OPENBLAS_NUM_THREADS", "1", 1);
    scratch sc;
    REQUIRE(scratch_open(&sc));
    enum { N = 6 };
    static const char *const ops[3] = {"", "static", "zero"};
    double st[3][N], cli[3][N], dir[3][N];
    for (int k = 0; k < 3; k++) {
        if (study_case(gd_ts_, &sc, "rig2018_geometry.yaml", 1000, ops[k], st[k], N) ||
            cli_modes(gd_ts_, &sc, "rig2018_geometry.yaml", 1000, ops[k], cli[k], N) ||
            direct_modes(gd_ts_, "rig2018_geometry.yaml", 1000, ops[k], dir[k], N))
            continue;
        for (int i = 0; i < N; i++) {
            if (st[k][i] != dir[k][i])
                fprintf(stderr, "  op '%s' mode %d: study %.17g, cli path %.17g\n", ops[k], i + 1,
                        st[k][i], dir[k][i]);
            CHECK(st[k][i] == dir[k][i]);
            /* the CLI's JSON: cJSON prints 15 digits where they read back within its
               epsilon, so the last bit or two is the printing's */
            CHECK_REL(cli[k][i], st[k][i], 1e-15);
        }
    }
    /* no key = static; zero is another state */
    for (int i = 0; i < N; i++)
        CHECK(st[0][i] == st[1][i]);
    int differ = 0;
    for (int i = 0; i < N; i++)
        differ += fabs(st[2][i] - st[1][i]) > 1e-3 * fabs(st[1][i]) + 1e-6;
    CHECK(differ >= 2);
    CHECK_REL(st[1][1], 123.02, 1e-3); /* docs/studies.md's static numbers at rest: 123.02 */
    scratch_close(&sc);
}

/* A wrong value names the file, line, field and the words it takes; the key on an analysis
 * that linearises nothing is refused there too, before any case runs. */
TEST(study_operating_point_errors_are_located)
{
    scratch sc;
    REQUIRE(scratch_open(&sc));
    char text[1024];
    gd_study *s = NULL;
    gd_error err;
    snprintf(text, sizeof text,
             "model: %s/examples/rig2018_geometry.yaml\n"
             "analysis: {type: modal, operating_point: rest}\n"
             "parameters:\n  - {path: gravity.g, values: [9.81]}\noutputs: [\"frequency_hz[1]\"]\n",
             GD_SOURCE_DIR);
    CHECK(load_text(&sc, text, &s, &err) == GD_EINPUT && !s);
    CHECK(err.line == 2 && err.column > 0);
    CHECK(strstr(err.file, "study.yaml") != NULL);
    CHECK_STR(err.field, "analysis.operating_point");
    CHECK(strstr(err.message, "'rest'") && strstr(err.hint, "static, zero"));
    snprintf(text, sizeof text,
             "model: %s/examples/ducati_timing_geartrain.yaml\n"
             "analysis: {type: transient, revolutions: 0.1,\n"
             "           operating_point: zero}\n"
             "parameters:\n  - {path: meshes.m01.backlash.gap, values: [15 um]}\n"
             "outputs: [contact_losses]\n",
             GD_SOURCE_DIR);
    CHECK(load_text(&sc, text, &s, &err) == GD_EINPUT && !s);
    CHECK(err.line == 3);
    CHECK_STR(err.field, "analysis.operating_point");
    CHECK(strstr(err.message, "transient") != NULL);
    /* the CLI's own refusal of a wrong word, for the same words */
    CHECK(run_refused(&sc, "'rest' is not static or zero", NULL,
                      "modal examples/rig2018_geometry.yaml --operating-point rest"));
    scratch_close(&sc);
}

RUN_TESTS(T(study_operating_point_equals_cli_both_ways),
          T(study_operating_point_errors_are_located))
