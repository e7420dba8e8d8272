/* The forced periodic orbit of a linear time-periodic model by shooting in the reduced
 * basis (gd_hb_orbit_reduced, src/periodic/floquet/floquet_reduced.c; docs/periodic.md,
 * "Reduced shooting") against harmonic balance where harmonic balance is converged:
 * [JMSTHelical] (examples/helical_two_stage.yaml, spur pairs, full coupling) at 2500 rpm,
 * H = 591 (the H `--harmonics auto` takes near there, within 0.3 % of a transient). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model_file.h"
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "periodic/periodic_impl.h"

/* Measured: means 235.206 / 538.827 N against 235.202 / 538.824 (2e-5, 6e-6), peak-to-peaks
 * 536.6 / 467.0 N against 536.9 / 464.7 (0.06 %, 0.5 %); the orbit linearised at rest
 * instead of at the static state (the TVMS read at the nominal angles, not the wound-up
 * ones) gives 353 N for mesh 2, 24 % low. */
TEST(seed002_reduced_orbit_equals_hb_at_2500rpm)
{
    const char *set[4] = {"meshes.pair1.geometry.helix_angle=0deg",
                          "meshes.pair2.geometry.helix_angle=0deg", "meshes.pair1.coupling=full",
                          "meshes.pair2.coupling=full"};
    gd_load_options lo = {4, set};
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_error err;
    const double W = 2500.0 * M_PI / 30.0;
    REQUIRE(!gd_model_load_opts(GD_SOURCE_DIR "/examples/helical_two_stage.yaml", &lo, &m, &err) &&
            !gd_system_build(m, &s, &err) && !gd_transient_model_build(s, &tm, &err) &&
            !gd_transient_new(s, &tm->spec, W, &tr, &err));
    double w0 = 0.0;
    int order = 0;
    REQUIRE(!gd_periodic_fundamental(s, &tm->spec, W, &w0, &order, &err));
    const gd_tr_record rec[2] = {{GD_REC_MESH_FORCE, 0, 0}, {GD_REC_MESH_FORCE, 1, 0}};
    hb h;
    REQUIRE(!gd_hb_init(&h, gd_transient_nstates(tr) / 2, 1, 4));
    double mean[2], p2p[2], mumax = 0.0;
    int nb = 0;
    char msg[160];
    CHECK(!gd_hb_orbit_reduced(&h, tr, w0, 8192, 0, 2e4 * 2.0 * M_PI, rec, 2, mean, p2p, &nb,
                               &mumax, msg));
    CHECK(nb == 74);
    CHECK(mumax > 0.99 && mumax < 1.0);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 591;
    o.estimate = 0;
    o.stability = 0;
    gd_periodic_result *r = NULL;
    REQUIRE(!gd_periodic_run(s, &tm->spec, NULL, &W, 1, &o, rec, 2, &r, &err));
    const gd_periodic_point *p = &r->points[0];
    CHECK(p->converged);
    for (int k = 0; k < 2; k++) {
        CHECK_REL(mean[k], p->records[k].mean, 1e-4);
        CHECK_REL(p2p[k], p->records[k].peak_to_peak, 0.015);
    }
    gd_periodic_result_free(r);
    gd_hb_free(&h);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

RUN_TESTS(T(seed002_reduced_orbit_equals_hb_at_2500rpm))
