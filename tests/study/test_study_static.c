/* Study analysis `static`: a bearing-stiffness study on the MMT 2018 rig, each case
 * equal to gd_static_run on the model loaded with the same --set, and the rig's torque
 * balance (F = T / rb1) in every case. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geardyn/model_file.h"
#include "geardyn/static.h"
#include "geardyn/study.h"
#include "harness.h"

static const char STUDY[] =
    "model: ../rig2018.yaml\n"
    "analysis: {type: static, torque: 20 N*m, gravity: false}\n"
    "parameters:\n"
    "  - {path: bearings.A2.k, values: [1e8, 2e7]}\n"
    "outputs: [\"mesh_force[1]\", \"f_sh[1]\", \"tilt_in_plane[1]\", \"bearing_force[1:2]\",\n"
    "          max_deflection, hold_reaction]\n";

TEST(static_cases_equal_direct_runs)
{
    char path[256];
    snprintf(path, sizeof path, "%s/examples/studies/.test_study_static_%d.yaml", GD_SOURCE_DIR,
             (int)getpid());
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs(STUDY, f);
    fclose(f);
    gd_study *s;
    gd_error err;
    gd_status st = gd_study_load(path, &s, &err);
    remove(path);
    if (st) fprintf(stderr, "  %s\n", err.message);
    REQUIRE(!st);
    REQUIRE(gd_study_noutputs(s) == 7 && gd_study_ncases(s) == 2);
    const char *sets[2] = {"bearings.A2.k=1e8", "bearings.A2.k=2e7"};
    for (size_t c = 0; c < 2; c++) {
        gd_study_row row;
        REQUIRE(!gd_study_row_init(s, &row, &err));
        gd_study_run_case(s, c, &row);
        CHECK(row.status == GD_OK);
        /* the same run directly */
        gd_load_options lo;
        gd_load_options_init(&lo);
        lo.nset = 1;
        lo.set = &sets[c];
        gd_model *m;
        gd_system *sys;
        gd_static_result *r;
        REQUIRE(!gd_model_load_opts(GD_SOURCE_DIR "/examples/rig2018.yaml", &lo, &m, &err));
        REQUIRE(!gd_system_build(m, &sys, &err));
        gd_static_options o;
        gd_static_options_init(&o);
        o.input_torque = 20;
        o.gravity = 0;
        REQUIRE(!gd_static_run(sys, &o, &r, &err));
        CHECK(row.outputs[0] == r->meshes[0].force);
        CHECK(row.outputs[1] == r->meshes[0].f_sh);
        CHECK(row.outputs[2] == r->meshes[0].tilt_in_plane);
        CHECK(row.outputs[3] == hypot(r->bearings[0].force[0], r->bearings[0].force[1]));
        CHECK(row.outputs[6] == r->holds[0].reaction);
        /* F = T / rb1; each of the driver's bearings F / 2 (statically determinate) */
        CHECK_REL(row.outputs[0], 20 / 0.048, 1e-12);
        CHECK_REL(row.outputs[3], 10 / 0.048, 1e-9);
        CHECK_REL(row.outputs[4], 10 / 0.048, 1e-9);
        CHECK(row.outputs[5] > 1e-4 && row.outputs[5] < 1e-3); /* 0.28 mm */
        /* the soft bearing tilts the driving shaft: a misalignment of 0.36 um */
        if (c == 0)
            CHECK(fabs(row.outputs[1]) < 1e-15);
        else
            CHECK(fabs(row.outputs[1]) > 1e-7);
        gd_static_free(r);
        gd_system_free(sys);
        gd_model_free(m);
        gd_study_row_free(&row);
    }
    gd_study_free(s);
}

RUN_TESTS(T(static_cases_equal_direct_runs))
