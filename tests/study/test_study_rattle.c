/* The rattle metrics of the study analysis `transient` (docs/rattle.md, docs/studies.md)
 * on examples/rattle_idle.yaml: a 2nd-order torque on the gearbox input behind the clutch
 * damper drives an idler held by its churning drag. The classic rattle threshold, the
 * idler's inertia torque J2 (r1/r2) A (2W)^2 against its drag T_d with the input's
 * amplitude A = T / |k - J_eff (2W)^2 + i c 2W| (J_eff = J1 + J2 (r1/r2)^2, the pair in
 * contact), gives T* = 0.357 N m at 1000 rpm and 0.854 N m at 600 rpm (T_d from the
 * churning law at the idler's speed); the cases on each side of it must not rattle and
 * rattle. The full 20-point map is examples/studies/rattle_map.yaml. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geardyn/laws.h"
#include "geardyn/study.h"
#include "harness.h"

static const char STUDY[] =
    "model: ../rattle_idle.yaml\n"
    "analysis: {type: transient, duration: 1, from: 0.5}\n"
    "design: zip\n"
    "parameters:\n"
    "  - {path: speed, unit: rpm, values: [600, 600, 1000, 1000]}\n"
    "  - {path: excitations.loads.firing.amplitude, unit: N*m, values: [0.5, 1, 0.25, 0.5]}\n"
    "outputs: [contact_losses, separated_fraction, separated_fraction_hw, "
    "drive_impacts_per_s, rattle_intensity, impact_speed_rms]\n";

/* T* at speed W (rad/s): the drag from the registry law as the example sets it. */
static double threshold(double W)
{
    gd_law L;
    gd_law_init(&L, &gd_law_churning_drag, "drag2");
    L.value[gd_law_param_index(L.type, "viscosity")] = 0.04;
    L.value[gd_law_param_index(L.type, "radius")] = 0.0425;
    L.value[gd_law_param_index(L.type, "face_width")] = 0.015;
    L.value[gd_law_param_index(L.type, "immersion")] = 0.02;
    L.value[gd_law_param_index(L.type, "oil_volume")] = 1.5e-3;
    double q[2] = {0, 0}, v[2] = {0, 0};
    L.rate[0] = 0.75 * W;
    gd_law_point x = {0, q, v};
    double Td = fabs(L.type->record(&L, 0, &x));
    double W2 = 2 * W, J2 = 5.8e-4, Je = 2e-3 + J2 * 0.75 * 0.75;
    double A = Td / (J2 * 0.75 * W2 * W2);
    return A * hypot(500 - Je * W2 * W2, 0.05 * W2);
}

TEST(onset_over_torque_agrees_with_the_threshold)
{
    double T600 = threshold(600 * M_PI / 30), T1000 = threshold(1000 * M_PI / 30);
    CHECK(T600 > 0.5 && T600 < 1.0);    /* 0.854 */
    CHECK(T1000 > 0.25 && T1000 < 0.5); /* 0.357 */
    char path[256];
    snprintf(path, sizeof path, "%s/examples/studies/.test_study_rattle_%d.yaml", GD_SOURCE_DIR,
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
    REQUIRE(gd_study_ncases(s) == 4 && gd_study_noutputs(s) == 6);
    const int rattles[4] = {0, 1, 0, 1};
    for (size_t c = 0; c < 4; c++) {
        gd_study_row row;
        REQUIRE(!gd_study_row_init(s, &row, &err));
        gd_study_run_case(s, c, &row);
        CHECK(row.status == GD_OK);
        if (rattles[c]) {
            CHECK(row.outputs[0] > 10);                        /* contact losses */
            CHECK(row.outputs[1] > 0.5 && row.outputs[1] < 1); /* separated */
            CHECK(row.outputs[2] > 0 && row.outputs[2] < 0.2); /* its half-width */
            CHECK(row.outputs[3] > 10 && row.outputs[4] > 0 && row.outputs[5] > 0);
        } else {
            for (int k = 0; k < 6; k++)
                CHECK(row.outputs[k] == 0.0);
        }
        gd_study_row_free(&row);
    }
    gd_study_free(s);
}

RUN_TESTS(T(onset_over_torque_agrees_with_the_threshold))
