/* One-sided contact (a backlash mesh with coast_stiffness_ratio: 0): no coast flank, so
 * beyond the gap on that side the teeth stay apart. The law gives the separated force
 * there; harmonic balance equals shooting (transient's integrator) on a rattling pair. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/laws.h"
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_support.h"

/* A torsional pair with backlash and a sinusoidal STE, light load: it separates over
 * part of each mesh period at 500 .. 600 rad/s. */
static const char *PAIR =
    "dofs: [rz]\n"
    "shafts:\n"
    "  - {name: input, nodes: [{name: pinion}]}\n"
    "  - {name: output, nodes: [{name: gear}]}\n"
    "disks:\n"
    "  - {node: pinion, polar_inertia: 1e-3}\n"
    "  - {node: gear, polar_inertia: 4e-3}\n"
    "meshes:\n"
    "  - name: mesh\n"
    "    driver: pinion\n"
    "    driven: gear\n"
    "    teeth: [20, 40]\n"
    "    base_radius: [0.03, 0.06]\n"
    "    pressure_angle: 20 deg\n"
    "    coupling: torsional\n"
    "    stiffness: 2e8\n"
    "    damping: {constant: 600, separated: 600}\n"
    "    transmission_error: {interpolation: spline, angle: [0, 0.07853981633974483, "
    "0.15707963267948966, 0.23561944901923448], error: [0, 4e-6, 0, -4e-6]}\n"
    "    backlash: {gap: 20 um, coast_stiffness_ratio: 0}\n"
    "prescribed:\n"
    "  - {node: pinion, motion: nominal}\n"
    "excitations:\n"
    "  loads: [{node: gear, value: 20}]\n";

TEST(coast_state_without_coast_flank_is_separated)
{
    gd_backlash_params p = {
        .b = 1e-5, .k_drive = 2e8, .k_coast = 0.0, .c_drive = 600, .c_coast = 600, .c_free = 35};
    double g[4];
    /* d = -3e-5 lies 2e-5 beyond the coast-side gap: with no coast flank only c_free acts */
    CHECK_REL(gd_backlash_force(&p, GD_CONTACT_COAST, -3e-5, 0.2), 35 * 0.2, 1e-15);
    gd_backlash_force_grad(&p, GD_CONTACT_COAST, -3e-5, 0.2, g);
    CHECK(g[0] == 0.0 && g[1] == 35.0 && g[2] == 0.0);
    p.k_coast = 1e8; /* a coast flank: its contact force */
    CHECK_REL(gd_backlash_force(&p, GD_CONTACT_COAST, -3e-5, 0.2), 1e8 * -2e-5 + 600 * 0.2, 1e-15);
}

TEST(one_sided_pair_hb_equals_shooting)
{
    fx f;
    REQUIRE(load(&f, NULL, PAIR));
    CHECK(f.m->meshes[0].dyn.coast_stiffness_ratio == 0.0);
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    CHECK(tm->spec.meshes[0].coast_scale == 0.0);
    const double w[3] = {500, 550, 600};
    gd_tr_record rec[2] = {{GD_REC_MESH_DEFLECTION, 0, 0}, {GD_REC_MESH_STATE, 0, 0}};
    gd_periodic_result *r[2] = {NULL, NULL};
    for (int m = 0; m < 2; m++) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = 20;
        o.estimate = 0;
        o.stability = 0;
        o.kind = m ? GD_PER_SHOOTING : GD_PER_HB;
        REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, w, 3, &o, rec, 2, &r[m], &err) == GD_OK);
        REQUIRE(r[m]->npoints == 3);
    }
    for (int i = 0; i < 3; i++) {
        const gd_periodic_point *a = &r[0]->points[i], *b = &r[1]->points[i];
        REQUIRE(a->converged && b->converged);
        /* the pair separates (state 1 and 0) and never reaches a coast flank (-1) */
        CHECK(a->records[1].peak_to_peak == 1.0 && b->records[1].peak_to_peak == 1.0);
        double pa = a->records[0].peak_to_peak, pb = b->records[0].peak_to_peak;
        printf("  %.0f rad/s: deflection p2p HB %.6e, shooting %.6e (%.1e)\n", a->speed, pa, pb,
               fabs(pa - pb) / pb);
        /* HB's truncation at H = 20 (the change to H = 40 is 7e-5): within 1e-3 */
        CHECK_REL(pa, pb, 1e-3);
        CHECK_REL(a->records[0].mean, b->records[0].mean, 1e-4);
    }
    gd_periodic_result_free(r[0]);
    gd_periodic_result_free(r[1]);
    gd_transient_model_free(tm);
    fx_free(&f);
}

RUN_TESTS(T(coast_state_without_coast_flank_is_separated), T(one_sided_pair_hb_equals_shooting))
