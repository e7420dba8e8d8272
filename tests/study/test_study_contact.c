/* Study analysis `contact`: a tip-relief x load study on examples/rig2018_pair_relief.yaml
 * (3 driver relief amounts x 2 driver torques), each row equal to gd_ltca_compute on the
 * gear pair loaded with the same --set, the design relief's Harris-map minimum, and a
 * relief past the reader's limit failing its case only. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geardyn/mesh_stiffness.h"
#include "geardyn/model_file.h"
#include "geardyn/study.h"
#include "harness.h"

#define RELIEF "meshes.mesh.geometry.driver.modifications.tip_relief.amount"
#define LOAD "meshes.mesh.stiffness.load"

static const char STUDY[] =
    "model: ../rig2018_pair_relief.yaml\n"
    "analysis: {type: contact}\n"
    "parameters:\n"
    "  - {name: relief, path: " RELIEF ", unit: um, values: [0, 10.2, 20]}\n"
    "  - {name: load, path: " LOAD ", unit: N m, values: [50, 100]}\n"
    "outputs: [te_p2p, te_mean, te_unloaded_p2p, k_mean, k_min, k_max, face_load_factor, force,\n"
    "          torque, flagged]\n";

static gd_status load_study(const char *text, gd_study **s, gd_error *err)
{
    char path[256];
    snprintf(path, sizeof path, "%s/examples/studies/.test_study_contact_%d.yaml", GD_SOURCE_DIR,
             (int)getpid());
    FILE *f = fopen(path, "w");
    if (!f) return GD_EIO;
    fputs(text, f);
    fclose(f);
    gd_status st = gd_study_load(path, s, err);
    remove(path);
    if (st) fprintf(stderr, "  %s\n", err->message);
    return st;
}

TEST(contact_cases_equal_direct_runs)
{
    gd_study *s;
    gd_error err;
    REQUIRE(!load_study(STUDY, &s, &err));
    REQUIRE(gd_study_noutputs(s) == 10 && gd_study_ncases(s) == 6);
    CHECK_STR(gd_study_analysis(s), "contact");
    static const double reliefs[3] = {0, 10.2, 20}, loads[2] = {50, 100};
    double p2p[3][2];
    for (size_t c = 0; c < 6; c++) {
        int i = (int)c / 2, j = (int)c % 2; /* the first parameter varies slowest */
        gd_study_row row;
        REQUIRE(!gd_study_row_init(s, &row, &err));
        gd_study_run_case(s, c, &row);
        CHECK(row.status == GD_OK);
        /* the same analysis directly: the pair as the file gives it with both --set */
        char a[128], b[128];
        snprintf(a, sizeof a, RELIEF "=%.17g um", reliefs[i]);
        snprintf(b, sizeof b, LOAD "=%.17g N m", loads[j]);
        const char *sets[2] = {a, b};
        gd_load_options lo;
        gd_load_options_init(&lo);
        lo.nset = 2;
        lo.set = sets;
        gd_gear_pair_geometry g;
        gd_tvms_options t;
        gd_ltca_result *r;
        REQUIRE(!gd_gear_pair_load(GD_SOURCE_DIR "/examples/rig2018_pair_relief.yaml", NULL, &lo,
                                   &g, &t, NULL, 0, &err));
        CHECK(t.contact_analysis == 1 && t.load_torque == loads[j]);
        CHECK_REL(g.gear[0].mod.tip_relief.amount, reliefs[i] * 1e-6, 1e-15);
        REQUIRE(!gd_ltca_compute(&g, &t, &r, &err));
        double umin = INFINITY, umax = -INFINITY;
        for (size_t k = 0; k < r->points; k++) {
            umin = fmin(umin, r->ste_unloaded[k]);
            umax = fmax(umax, r->ste_unloaded[k]);
        }
        /* the same computation: bit-identical */
        CHECK(row.outputs[0] == r->ste_peak_to_peak);
        CHECK(row.outputs[1] == r->ste_mean);
        CHECK(row.outputs[2] == umax - umin);
        CHECK(row.outputs[3] == r->stiffness_mean);
        CHECK(row.outputs[4] == r->stiffness_min);
        CHECK(row.outputs[5] == r->stiffness_max);
        CHECK(row.outputs[6] == r->face_load_factor_cycle);
        CHECK(row.outputs[7] == r->force);
        CHECK(row.outputs[8] == loads[j]);
        CHECK(row.outputs[9] == 0);
        /* F = T / r_b1 (spur): r_b1 = 48 mm cos 20 deg */
        CHECK_REL(row.outputs[7], loads[j] / (0.048 * cos(20 * M_PI / 180)), 1e-12);
        /* a spur pair aligned: uniform load across the face (K_Hbeta = 1 to rounding) */
        CHECK_ABS(row.outputs[6], 1, 1e-12);
        p2p[i][j] = row.outputs[0];
        gd_ltca_free(r);
        gd_study_row_free(&row);
    }
    /* Harris map (Tavakoli & Houser 1986): the relief sized for 100 N m gives, at 100
     * N m, a peak-to-peak TE well below the driver without relief (0.71 um against
     * 4.25 um) and below the same relief at half the load (2.90 um); the double relief
     * overshoots (3.81 um). The bounds leave room for a change of the slice law but not
     * for losing the effect. */
    CHECK(p2p[1][1] < 0.25 * p2p[0][1]);
    CHECK(p2p[1][1] < 0.5 * p2p[1][0]);
    CHECK(p2p[1][1] < 0.5 * p2p[2][1]);
    /* without relief TE grows with the load */
    CHECK(p2p[0][1] > p2p[0][0]);
    gd_study_free(s);
}

/* A relief past the reader's limit (a tenth of the module) fails its case with the
 * reader's message; the other case runs. The analysis's own load wins over the file's. */
TEST(contact_bad_relief_fails_its_case)
{
    static const char BAD[] = "model: ../rig2018_pair_relief.yaml\n"
                              "analysis: {type: contact, load: 80 N m, points: 64}\n"
                              "parameters:\n"
                              "  - {path: " RELIEF ", unit: um, values: [300, 10.2]}\n"
                              "outputs: [te_p2p, torque]\n";
    gd_study *s;
    gd_error err;
    REQUIRE(!load_study(BAD, &s, &err));
    gd_study_row row;
    REQUIRE(!gd_study_row_init(s, &row, &err));
    gd_study_run_case(s, 0, &row);
    CHECK(row.status == GD_EINPUT);
    CHECK(strstr(row.message, "tip_relief.amount") != NULL);
    CHECK(strstr(row.message, "a tenth of the normal module") != NULL);
    CHECK(isnan(row.outputs[0]));
    gd_study_run_case(s, 1, &row);
    CHECK(row.status == GD_OK);
    CHECK(row.outputs[0] > 0 && row.outputs[0] < 1e-5);
    CHECK(row.outputs[1] == 80); /* not the file's 100 N m */
    gd_study_row_free(&row);
    gd_study_free(s);
    /* iso6336 has no slice law: refused when the study is read */
    static const char ISO[] = "model: ../rig2018_pair_relief.yaml\n"
                              "analysis: {type: contact, method: iso6336}\n"
                              "parameters:\n"
                              "  - {path: " LOAD ", values: [100]}\n"
                              "outputs: [te_p2p]\n";
    CHECK(load_study(ISO, &s, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "stiffness law") != NULL);
}

RUN_TESTS(T(contact_cases_equal_direct_runs), T(contact_bad_relief_fails_its_case))
