/* Reading test data: UFF 58 (ASCII) and 58b (binary) written by the tests' own writer
 * from the dataset description (tests/uff_support.h), the CSV forms, unit conversions,
 * and located errors for bad files. */
#include "harness.h"
#include "uff_support.h"

#include <unistd.h>

static const char *tmp_path(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "/tmp/gd_uff_%d_%s", (int)getpid(), name);
    return buf;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static gd_status read1(const char *path, gd_testdata **td, gd_error *err)
{
    const char *p[1] = {path};
    return gd_testdata_read(1, p, 0, td, err);
}

/* ASCII double, ASCII single, 58b little and big endian: the same values back, to
 * the precision the format keeps (E20.12: 1e-11 relative; single: 6e-8 of the
 * largest value, E13.5: 5e-6 relative) */
TEST(uff58_ascii_and_binary_read_field_by_field)
{
    synth sy;
    REQUIRE(synth_make(&sy, 1.0, 0.0, 4, 801, 1.25, 7));
    const int modes[4][2] = {{0, 6}, {0, 5}, {1, 6}, {2, 5}};
    const double tol[4] = {1e-11, 5e-6, 1e-15, 6e-8};
    for (int c = 0; c < 4; c++) {
        char path[256];
        tmp_path(path, sizeof path, "a.uff");
        REQUIRE(synth_write_uff(&sy, path, modes[c][0], modes[c][1]));
        gd_testdata *td;
        gd_error err;
        gd_status st = read1(path, &td, &err);
        if (st) fprintf(stderr, "  %s:%d: %s\n", err.file, err.line, err.message);
        REQUIRE(st == GD_OK);
        CHECK(td->nfunctions == 4);
        for (int j = 0; j < td->nfunctions && j < 4; j++) {
            const gd_td_function *f = &td->functions[j];
            CHECK(f->function_type == 4);
            CHECK(f->response_node == sy.resp_node[j] + 1 && f->response_dir == 2);
            CHECK(f->reference_node == sy.resp_node[1] + 1 && f->reference_dir == 2);
            CHECK(f->quantity == GD_TD_ACCELERANCE);
            CHECK(f->n == 801);
            CHECK_ABS(f->freq_hz[800], 1000.0, 1e-9);
            double amax = 0, emax = 0;
            for (int k = 0; k < f->n; k++) {
                double tr = sy.re[(size_t)j * sy.n + k], ti = sy.im[(size_t)j * sy.n + k];
                amax = fmax(amax, hypot(tr, ti));
                emax = fmax(emax, hypot(f->re[k] - tr, f->im[k] - ti));
            }
            CHECK(emax <= tol[c] * amax);
        }
        char id[64];
        snprintf(id, sizeof id, "H y%dy%d", sy.resp_node[0] + 1, sy.resp_node[1] + 1);
        CHECK_STR(td->functions[0].name, id);
        gd_testdata_free(td);
        unlink(path);
    }
    synth_free(&sy);
}

/* accelerance -> receptance -> mobility: H_x = -H_a / w^2 and H_v = i w H_x, exact;
 * units in g and mm */
TEST(frf_conversions_and_units)
{
    gd_td_quantity q;
    double f;
    CHECK(gd_td_units("g/N", &q, &f, NULL) == GD_OK && q == GD_TD_ACCELERANCE);
    CHECK_REL(f, 9.80665, 1e-15);
    CHECK(gd_td_units("mm/s/N", &q, &f, NULL) == GD_OK && q == GD_TD_MOBILITY);
    CHECK_REL(f, 1e-3, 1e-15);
    CHECK(gd_td_units("in/lbf", &q, &f, NULL) == GD_OK && q == GD_TD_RECEPTANCE);
    CHECK_REL(f, 0.0254 / 4.4482216152605, 1e-15);
    gd_error err;
    CHECK(gd_td_units("Pa/N", &q, &f, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "numerator") != NULL);
    CHECK(gd_td_units("m/s^2/kg", &q, &f, &err) == GD_EINPUT);
    double fr[2] = {0, 10}, re[2] = {1, 2}, im[2] = {0, 3};
    gd_td_function fn = {0};
    fn.n = 2;
    fn.freq_hz = fr;
    fn.re = re;
    fn.im = im;
    fn.quantity = GD_TD_ACCELERANCE;
    REQUIRE(gd_td_convert(&fn, GD_TD_RECEPTANCE, NULL) == GD_OK);
    double w = 2 * M_PI * 10;
    CHECK(isnan(re[0]));
    CHECK_REL(re[1], -2 / (w * w), 1e-14);
    CHECK_REL(im[1], -3 / (w * w), 1e-14);
    REQUIRE(gd_td_convert(&fn, GD_TD_MOBILITY, NULL) == GD_OK);
    CHECK_REL(re[1], 3 / w, 1e-14); /* i w (-2 - 3i)/w^2 = (3 - 2i)/w */
    CHECK_REL(im[1], -2 / w, 1e-14);
    fn.quantity = GD_TD_RATIO;
    CHECK(gd_td_convert(&fn, GD_TD_RECEPTANCE, NULL) == GD_EINPUT);
}

TEST(csv_forms)
{
    char p[256];
    tmp_path(p, sizeof p, "h.csv");
    write_text(p, "# geardyn frf\n# response: 2 +y\n# reference: 3 -y\n# units: g/N\n"
                  "frequency_hz,re,im\n10,1,0\n20,0.5,-0.5\n");
    gd_testdata *td;
    gd_error err;
    REQUIRE(read1(p, &td, &err) == GD_OK);
    CHECK(td->nfunctions == 1);
    CHECK(td->functions[0].reference_dir == -2 && td->functions[0].response_node == 2);
    CHECK_REL(td->functions[0].re[1], 0.5 * 9.80665, 1e-15);
    CHECK_STR(td->functions[0].name, "H +y2 -y3");
    gd_testdata_free(td);
    write_text(p, "# geardyn modes\nfrequency_hz,damping_ratio,label\n134.4,,H y9y10\n"
                  "156.9,0.012,\n");
    REQUIRE(read1(p, &td, &err) == GD_OK);
    CHECK(td->nmodes == 2);
    CHECK(isnan(td->mode_zeta[0]) && td->mode_zeta[1] == 0.012);
    CHECK_STR(td->mode_label[0], "H y9y10");
    gd_testdata_free(td);
    unlink(p);
}

/* Bad files: every error names the file, the line and the record */
TEST(bad_files_are_located)
{
    synth sy;
    REQUIRE(synth_make(&sy, 1.0, 0.0, 2, 101, 2.0, 7));
    char p[256], q[256];
    tmp_path(p, sizeof p, "good.uff");
    tmp_path(q, sizeof q, "bad.uff");
    REQUIRE(synth_write_uff(&sy, p, 0, 6));
    char *text = NULL;
    {
        FILE *f = fopen(p, "rb");
        REQUIRE(f);
        text = calloc(1, 1 << 20);
        size_t n = fread(text, 1, (1 << 20) - 1, f);
        fclose(f);
        text[n] = 0;
    }
    gd_testdata *td = NULL;
    gd_error err;
    /* cut in the middle of the first dataset's values (line 30) */
    {
        char *cut = text;
        for (int l = 0; l < 30; l++)
            cut = strchr(cut, '\n') + 1;
        char c = *cut;
        *cut = 0;
        write_text(q, text);
        *cut = c;
        CHECK(read1(q, &td, &err) == GD_EINPUT && td == NULL);
        CHECK(strstr(err.message, "cut short") != NULL);
        CHECK(strstr(err.file, "bad.uff") != NULL && err.line == 30); /* its last line */
    }
    /* a dataset type not read: 55 */
    {
        char *t2 = malloc(strlen(text) + 16);
        strcpy(t2, text);
        memcpy(strchr(t2, '\n') + 1, "    55", 6);
        write_text(q, t2);
        CHECK(read1(q, &td, &err) == GD_EINPUT);
        CHECK(strstr(err.message, "dataset type 55") != NULL && err.line == 2);
        /* skipped when asked: the second dataset is read */
        const char *pp[1] = {q};
        CHECK(gd_testdata_read(1, pp, 1, &td, &err) == GD_OK && td->nfunctions == 1);
        gd_testdata_free(td);
        td = NULL;
        free(t2);
    }
    /* units that do not convert: Pa in record 9 */
    {
        char *t2 = malloc(strlen(text) + 16);
        strcpy(t2, text);
        char *u = strstr(t2, "m/s^2");
        memcpy(u, "Pa   ", 5);
        write_text(q, t2);
        CHECK(read1(q, &td, &err) == GD_EINPUT);
        CHECK(strstr(err.message, "cannot convert") != NULL && err.line == 11);
        free(t2);
    }
    /* a frequency axis that does not increase: increment -2 */
    {
        char *t2 = malloc(strlen(text) + 16);
        strcpy(t2, text);
        char *r7 = strstr(t2, " 2.00000E+00");
        REQUIRE(r7);
        memcpy(r7, "-2.00000E+00", 12);
        write_text(q, t2);
        CHECK(read1(q, &td, &err) == GD_EINPUT);
        CHECK(strstr(err.message, "does not increase") != NULL && err.line == 9);
        free(t2);
    }
    /* an uneven axis that goes back, in CSV */
    write_text(q, "# geardyn frf\n# units: m/N\nfrequency_hz,re,im\n10,1,0\n9,1,0\n");
    CHECK(read1(q, &td, &err) == GD_EINPUT && strstr(err.message, "does not increase"));
    free(text);
    unlink(p);
    unlink(q);
    synth_free(&sy);
}

/* a coherence (record 6 function type 6) is kept as a ratio, and an FRF fit refuses it */
TEST(coherence_is_a_ratio)
{
    synth sy;
    REQUIRE(synth_make(&sy, 1.0, 0.0, 2, 101, 2.0, 7));
    char p[256];
    tmp_path(p, sizeof p, "coh.uff");
    REQUIRE(synth_write_uff(&sy, p, 0, 6));
    FILE *f = fopen(p, "rb");
    REQUIRE(f);
    char *text = calloc(1, 1 << 20);
    size_t n = fread(text, 1, (1 << 20) - 1, f);
    fclose(f);
    text[n] = 0;
    /* the first dataset's record 6 starts "    4": make it "    6" */
    char *r6 = text;
    for (int l = 0; l < 7; l++)
        r6 = strchr(r6, '\n') + 1;
    REQUIRE(strncmp(r6, "    4", 5) == 0);
    r6[4] = '6';
    write_text(p, text);
    free(text);
    gd_testdata *td;
    gd_error err;
    REQUIRE(read1(p, &td, &err) == GD_OK);
    CHECK(td->functions[0].function_type == GD_UFF_COHERENCE);
    CHECK(td->functions[0].quantity == GD_TD_RATIO);
    CHECK(td->functions[1].quantity == GD_TD_ACCELERANCE);
    const gd_td_function *fs[2] = {&td->functions[0], &td->functions[1]};
    gd_ema_result *r;
    CHECK(gd_ema_lscf(2, fs, NULL, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "is not an FRF") != NULL);
    gd_testdata_free(td);
    unlink(p);
    synth_free(&sy);
}

RUN_TESTS(T(coherence_is_a_ratio), T(uff58_ascii_and_binary_read_field_by_field),
          T(frf_conversions_and_units), T(csv_forms), T(bad_files_are_located))
