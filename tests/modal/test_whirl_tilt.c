/* The whirl of a gyroscopic tilt pair (src/modal/mode_properties.c): the motor rotor of
 * examples/reducer_three_stage.yaml (a lumped disk on stiff bearings, 1500 rpm) tilts at
 * 221.36 Hz (backward, softened by the gyroscopic moment) and 228.86 Hz (forward,
 * stiffened) while its centre stays still. Its whirl was read from the centre's orbit
 * alone: "none" by the dense solver (an exact zero) and "mixed" by the sparse one
 * (rounding that turns either way). Both solvers must now say backward, then forward,
 * and the issue 35 rules keep: a mode under 5 % lateral and tilt energy has no whirl,
 * the dominant component holds strain energy. */
#include <math.h>

#include "geardyn/modal.h"
#include "geardyn/model_file.h"
#include "geardyn/static.h"
#include "harness.h"

static void tilt_pair(gd_test_state *gd_ts_, gd_eig_method method)
{
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_error err;
    REQUIRE(gd_model_load("examples/reducer_three_stage.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    /* the laws linearised about the static equilibrium, as `geardyn modal` does */
    gd_static_options so;
    gd_static_options_init(&so);
    so.speed = 1500 * 2 * M_PI / 60;
    REQUIRE(gd_static_operating_point(s, &so, 1, &err) == GD_OK);
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = 1500 * 2 * M_PI / 60;
    o.nmodes = 12;
    o.want_left = 0;
    o.method = method;
    gd_modal_result *r = NULL;
    REQUIRE(gd_modal_solve(s, &o, &r, &err) == GD_OK);
    int found = 0;
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (md->rigid_body) continue;
        if (fabs(md->frequency_hz - 221.36) < 0.05) {
            CHECK(md->dominant_motion == GD_MOTION_TILT);
            CHECK(md->whirl == GD_WHIRL_BACKWARD);
            found |= 1;
        }
        if (fabs(md->frequency_hz - 228.86) < 0.05) {
            CHECK(md->dominant_motion == GD_MOTION_TILT);
            CHECK(md->whirl == GD_WHIRL_FORWARD);
            found |= 2;
        }
        double lat = md->energy_share[GD_MOTION_LATERAL] + md->energy_share[GD_MOTION_TILT];
        if (lat < GD_WHIRL_MIN_LATERAL) CHECK(md->whirl == GD_WHIRL_NONE);
        if (md->dominant_component >= 0)
            CHECK(r->energy_by_component[md->dominant_component + (size_t)j * s->ncomponents] >
                  1e-9);
    }
    if (found != 3)
        for (int j = 0; j < r->nmodes; j++)
            printf("  mode %d %.4f Hz whirl %d\n", j + 1, r->modes[j].frequency_hz,
                   r->modes[j].whirl);
    CHECK(found == 3);
    gd_modal_free(r);
    gd_system_free(s);
    gd_model_free(m);
}

TEST(tilt_pair_dense)
{
    tilt_pair(gd_ts_, GD_EIG_DENSE);
}

TEST(tilt_pair_sparse)
{
    tilt_pair(gd_ts_, GD_EIG_SPARSE);
}

RUN_TESTS(T(tilt_pair_dense), T(tilt_pair_sparse))
