/* Run-up through a speed profile (gd_transient_options.profile, src/transient/
 * speed_profile.c) and computed order tracking (gd_waterfall_order_track,
 * src/campbell/order_track.c): the profile's angle and speed, order amplitudes of a
 * synthetic chirp, a flat profile against the constant-speed path, the refusals, and a
 * run-up of the rig's driving shaft (tests/transient/runup_rotor.yaml) through its first
 * critical speed against the Campbell diagram's 1x crossing. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/campbell.h"
#include "geardyn/model_file.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "geardyn/waterfall.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#define RPM (M_PI / 30)

static const char *MODEL = "tests/transient/runup_rotor.yaml";

/* A ramp's angle is the integral of its speed (exact for the piecewise-linear speed),
 * a table with the same corners gives the same numbers. */
TEST(profile_angle_is_the_speed_integral)
{
    gd_speed_profile p = {GD_SPEED_RAMP, 100, 300, 1, 3, 0, NULL, NULL};
    gd_error err;
    REQUIRE(gd_speed_profile_check(&p, &err) == GD_OK);
    double a, w, dw;
    gd_speed_profile_eval(&p, 0.5, &a, &w, &dw);
    CHECK_REL(a, 50, 1e-14);
    CHECK_REL(w, 100, 1e-14);
    CHECK_ABS(dw, 0, 0);
    gd_speed_profile_eval(&p, 2, &a, &w, &dw); /* 100 + 100 * 1 + 50 * 1^2 */
    CHECK_REL(a, 250, 1e-14);
    CHECK_REL(w, 200, 1e-14);
    CHECK_REL(dw, 100, 1e-14);
    gd_speed_profile_eval(&p, 4, &a, &w, &dw); /* 100 + 400 + 300 */
    CHECK_REL(a, 800, 1e-14);
    CHECK_ABS(dw, 0, 0);
    double tt[] = {0, 1, 3}, ww[] = {100, 100, 300};
    gd_speed_profile q = {GD_SPEED_TABLE, 0, 0, 0, 0, 3, tt, ww};
    REQUIRE(gd_speed_profile_check(&q, &err) == GD_OK);
    for (double t = -0.5; t < 5; t += 0.37) {
        double b, v, dv;
        gd_speed_profile_eval(&p, t, &a, &w, &dw);
        gd_speed_profile_eval(&q, t, &b, &v, &dv);
        CHECK_REL(b, a, 1e-13);
        CHECK_REL(v, w, 1e-14);
        CHECK_REL(dv, dw, 1e-14);
    }
    double bad_w[] = {100, -1, 300};
    gd_speed_profile r = {GD_SPEED_TABLE, 0, 0, 0, 0, 3, tt, bad_w};
    CHECK(gd_speed_profile_check(&r, &err) == GD_EINPUT);
}

static int load(gd_model **m, gd_system **s)
{
    gd_error err;
    if (gd_model_load(MODEL, m, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        return 1;
    }
    return gd_system_build(*m, s, &err) != GD_OK;
}

/* x = 2 cos(phi) + 0.5 cos(3 phi + 0.3) + 0.2 cos(2 pi 170 t) under a ramp 100 -> 300
 * rad/s: order 1 and 3 read 2 and 0.5 in every block (exact bins, Hann window: the
 * linear resampling costs (k pi / S)^2 / 6 ~ 0.4 % at order 3 of 64 samples per turn,
 * bound 1 %); the 170 Hz tone, not an order, is smeared and reads below 0.2 at order 3;
 * each block's speed is the ramp's at the block's middle time (a linear ramp's mean
 * speed) to 1e-6. */
TEST(order_tracking_of_a_chirp)
{
    gd_model *m = NULL;
    gd_system *s = NULL;
    REQUIRE(!load(&m, &s));
    gd_speed_profile p = {GD_SPEED_RAMP, 100, 300, 0, 4, 0, NULL, NULL};
    const int n = 4 * 300 * 2 * 64 / 6 * 2; /* 2 x 64 samples per turn at 300 rad/s */
    double *t = malloc((size_t)n * sizeof *t), *x = malloc((size_t)n * sizeof *x),
           *ang = malloc((size_t)n * sizeof *ang);
    REQUIRE(t && x && ang);
    for (int k = 0; k < n; k++) {
        t[k] = 4.0 * k / (n - 1);
        gd_speed_profile_eval(&p, t[k], &ang[k], NULL, NULL);
        x[k] = 2 * cos(ang[k]) + 0.5 * cos(3 * ang[k] + 0.3) + 0.2 * cos(2 * M_PI * 170 * t[k]);
    }
    gd_order_track_options o;
    gd_order_track_options_init(&o);
    gd_waterfall *w = NULL;
    gd_error err;
    REQUIRE(gd_waterfall_order_track(s, t, x, ang, n, &o, &w, &err) == GD_OK);
    CHECK(w->tracked == 1);
    CHECK(w->nspeeds > 10);
    CHECK(w->norders == 1); /* 1x driving */
    for (int b = 0; b < w->nspeeds; b++) {
        const gd_spectrum *sp = w->spectra[b];
        CHECK_REL(w->order_amplitude[b], 2.0, 1e-2);
        int k3 = (int)(3 * o.revs_per_block + 0.5);
        CHECK_REL(sp->amplitude[k3], 0.5, 1e-2);
        CHECK_REL(sp->freq[k3], 3 * w->speeds[b] / (2 * M_PI), 1e-12);
        /* the block's middle time from its angles: phi(t) = 100 t + 25 t^2 */
        double a0 = 2 * M_PI * b * o.revs_per_block * (1 - o.overlap);
        double a1 = a0 + 2 * M_PI * o.revs_per_block;
        double t0 = (-100 + sqrt(1e4 + 100 * a0)) / 50, t1 = (-100 + sqrt(1e4 + 100 * a1)) / 50;
        CHECK_REL(w->speeds[b], 100 + 50 * 0.5 * (t0 + t1), 1e-6);
    }
    gd_waterfall_free(w);
    /* too coarse a record: refused, naming the samples per revolution */
    for (int k = 0; k < n / 4; k++) {
        t[k] = t[4 * k];
        x[k] = x[4 * k];
        ang[k] = ang[4 * k];
    }
    CHECK(gd_waterfall_order_track(s, t, x, ang, n / 4, &o, &w, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "samples per revolution") != NULL);
    free(t);
    free(x);
    free(ang);
    gd_system_free(s);
    gd_model_free(m);
}

static gd_transient_result *run(gd_transient *tr, const gd_speed_profile *p, double t_end,
                                double step, const gd_tr_record *rec)
{
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.method = GD_TR_GEN_ALPHA;
    o.step = step;
    o.t_end = t_end;
    o.output_interval = step;
    o.profile = p;
    gd_transient_result *r = NULL;
    gd_error err;
    if (gd_transient_run(tr, &o, rec, 1, &r, &err)) fprintf(stderr, "  %s\n", err.message);
    return r;
}

/* A flat profile at the reference speed runs the run-up code (time-varying gyroscopic
 * term, unbalance with W' = 0) and gives the constant-speed numbers: the same forces
 * in other arithmetic, to 1e-9 of the peak (measured 2e-13). */
TEST(flat_profile_equals_constant_speed)
{
    gd_model *m = NULL;
    gd_system *s = NULL;
    REQUIRE(!load(&m, &s));
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    double W = 6000 * RPM;
    REQUIRE(gd_transient_new(s, &tm->spec, W, &tr, &err) == GD_OK);
    gd_tr_record rec = {GD_REC_DISP, gd_system_dof(s, 1, GD_X), 0};
    gd_speed_profile flat = {GD_SPEED_RAMP, W, W, 0, 1, 0, NULL, NULL};
    gd_transient_result *a = run(tr, NULL, 0.05, 1e-4, &rec), *b = run(tr, &flat, 0.05, 1e-4, &rec);
    REQUIRE(a && b && a->nout == b->nout);
    double pk = 0, d = 0;
    for (int k = 0; k < a->nout; k++) {
        pk = fmax(pk, fabs(a->values[k]));
        d = fmax(d, fabs(a->values[k] - b->values[k]));
    }
    CHECK(pk > 1e-6);
    CHECK(d <= 1e-9 * pk);
    /* and the constant path again after the run-up: the same numbers exactly */
    gd_transient_result *c = run(tr, NULL, 0.05, 1e-4, &rec);
    REQUIRE(c);
    CHECK(memcmp(a->values, c->values, (size_t)a->nout * sizeof *a->values) == 0);
    /* the LTI method and a monodromy refuse a profile */
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.01;
    o.method = GD_TR_LTI;
    o.profile = &flat;
    gd_transient_result *r = NULL;
    CHECK(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "constant speed") != NULL);
    o.method = GD_TR_AUTO;
    o.output_interval = 1e-4;
    REQUIRE(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_OK);
    CHECK(r->method_used == GD_TR_BDF);
    CHECK(strstr(r->method_note, "speed profile") != NULL);
    gd_transient_result_free(r);
    gd_transient_result_free(a);
    gd_transient_result_free(b);
    gd_transient_result_free(c);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

/* A problem built at 5000 rpm running a flat profile at 7000 rpm gives the numbers of
 * one built at 7000 rpm: the gyroscopic term's change (W(t) - W) G, the speed-table
 * bearings re-evaluated at W(t) (their stiffness 2e6 -> 1e6 N/m, cross-coupling from
 * 3000 rpm) and the unbalance at the profile's speed. Both by generalized-alpha at one
 * step, whose Newton iteration stops at 1e-10 of the displacements (the run-up's terms
 * at W(t) are outside its tangent): to 1e-8 of the peak (measured 3.3e-10). */
TEST(profile_re_evaluates_gyroscopics_and_bearing_tables)
{
    static const char *yaml =
        "dofs: [x, y, rx, ry]\n"
        "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"
        "shafts: [{name: s, material: steel, elements_per_section: 2,\n"
        "  sections: [{length: 0.5, outer_diameter: 25.4 mm}],\n"
        "  nodes: [{name: a, at: 0}, {name: g, at: 0.25}, {name: b, at: 0.5}]}]\n"
        "disks: [{name: g, node: g, mass: 1.15, polar_inertia: 0.05}]\n"
        "bearings:\n"
        "  - {name: A, node: a, table: [{speed: 0, k: 2e6, c: 300},\n"
        "      {speed: 3000 rpm, kxx: 2e6, kyy: 2e6, kxy: 2e5, kyx: -2e5, c: 300},\n"
        "      {speed: 9000 rpm, kxx: 1e6, kyy: 1.5e6, kxy: 5e5, kyx: -5e5, c: 200}]}\n"
        "  - {name: B, node: b, k: 2e6, c: 300}\n"
        "unbalances: [{name: u, node: g, amount: 1e-5 kg*m}]\n";
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_error err;
    REQUIRE(gd_model_load_string(yaml, "tables.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    REQUIRE(s->has_speed_dependent);
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    gd_transient *t5 = NULL, *t7 = NULL;
    REQUIRE(gd_transient_new(s, &tm->spec, 5000 * RPM, &t5, &err) == GD_OK);
    REQUIRE(gd_transient_new(s, &tm->spec, 7000 * RPM, &t7, &err) == GD_OK);
    gd_tr_record rec = {GD_REC_DISP, gd_system_dof(s, 1, GD_Y), 0};
    gd_speed_profile flat = {GD_SPEED_RAMP, 7000 * RPM, 7000 * RPM, 0, 1, 0, NULL, NULL};
    gd_transient_result *a = run(t7, NULL, 0.05, 1e-4, &rec), *b = run(t5, &flat, 0.05, 1e-4, &rec);
    REQUIRE(a && b && a->nout == b->nout);
    double pk = 0, d = 0;
    for (int k = 0; k < a->nout; k++) {
        pk = fmax(pk, fabs(a->values[k]));
        d = fmax(d, fabs(a->values[k] - b->values[k]));
    }
    fprintf(stderr, "  peak %.4g m, largest difference %.3g of it\n", pk, d / pk);
    CHECK(pk > 1e-6);
    CHECK(d <= 1e-8 * pk);
    CHECK(strstr(b->method_note, "speed-table bearings at W(t)") != NULL);
    gd_transient_result_free(a);
    gd_transient_result_free(b);
    gd_transient_free(t5);
    gd_transient_free(t7);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

/* What a run-up cannot do is refused naming it (GD_EINPUT): a rolling-bearing law (its
 * cage angle is its spin times t), a prescribed speed (an absolute motion), a reduced
 * model; and the problem still runs at constant speed afterwards. */
TEST(run_up_refusals)
{
    static const char *yaml =
        "dofs: [x, y]\nshafts:\n  - {name: rotor, nodes: [{name: j}]}\n"
        "disks:\n  - {name: j, node: j, mass: 2}\nspeed: 3000 rpm\n"
        "laws:\n  - {type: rolling_bearing, name: b, node: j, elements: 9, contact_stiffness: "
        "8e9, clearance: 5 um, pitch_diameter: 39.04 mm, element_diameter: 7.94 mm, damping: "
        "200 N*s/m}\n";
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_error err;
    REQUIRE(gd_model_load_string(yaml, "balls.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    REQUIRE(gd_transient_new(s, &tm->spec, 300, &tr, &err) == GD_OK);
    gd_speed_profile ramp = {GD_SPEED_RAMP, 100, 300, 0, 0.01, 0, NULL, NULL};
    gd_tr_record rec = {GD_REC_DISP, 0, 0};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.01;
    o.method = GD_TR_GEN_ALPHA;
    o.profile = &ramp;
    gd_transient_result *r = NULL;
    CHECK(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "rolling_bearing") != NULL);
    o.profile = NULL;
    REQUIRE(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_OK);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    /* a prescribed speed, and a reduced model (of the run-up rotor) */
    gd_tr_prescribed pr = {1, {GD_PRESCRIBED_SPEED, 10, 0, 0, 0, NULL}};
    gd_transient_spec sp = tm->spec;
    sp.laws = NULL;
    sp.nlaws = 0;
    sp.prescribed = &pr;
    sp.nprescribed = 1;
    REQUIRE(gd_transient_new(s, &sp, 300, &tr, &err) == GD_OK);
    o.profile = &ramp;
    r = NULL;
    CHECK(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "prescribed speed") != NULL);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
    REQUIRE(!load(&m, &s));
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    REQUIRE(gd_transient_new_reduced(s, &tm->spec, 300, 2000, &tr, &err) == GD_OK);
    CHECK(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "reduced model") != NULL);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

/* The peak of the 1x order cut of gear48.x over a ramp 5500 -> 7800 rpm at `rate` rpm/s
 * (8 revolutions per block); *spacing: the speed between its neighbouring blocks. */
static double peak_speed(gd_transient *tr, const gd_system *s, double rate, double *spacing)
{
    gd_speed_profile p = {GD_SPEED_RAMP, 5500 * RPM, 7800 * RPM, 0, 2300 / rate, 0, NULL, NULL};
    gd_tr_record rec = {GD_REC_DISP, gd_system_dof(s, 1, GD_X), 0};
    gd_transient_result *r = run(tr, &p, p.t1, 1e-4, &rec);
    if (!r) return NAN;
    double *ang = malloc((size_t)r->nout * sizeof *ang);
    for (int k = 0; ang && k < r->nout; k++)
        gd_speed_profile_eval(&p, r->t[k], &ang[k], NULL, NULL);
    gd_order_track_options o;
    gd_order_track_options_init(&o);
    o.revs_per_block = 8;
    o.samples_per_rev = 32;
    gd_waterfall *w = NULL;
    gd_error err;
    double at = NAN;
    if (ang && !gd_waterfall_order_track(s, r->t, r->values, ang, r->nout, &o, &w, &err)) {
        int best = 0;
        for (int b = 1; b < w->nspeeds; b++)
            if (w->order_amplitude[b] > w->order_amplitude[best]) best = b;
        at = w->speeds[best];
        *spacing = best + 1 < w->nspeeds ? w->speeds[best + 1] - at : at - w->speeds[best - 1];
        gd_waterfall_free(w);
    }
    free(ang);
    gd_transient_result_free(r);
    return at;
}

/* Acceptance (issue 21): the run-up's 1x peak lies at the Campbell diagram's 1x crossing
 * of the first forward mode (6649.8 rpm) within the ramp's resolution: the speed step
 * between blocks (8 revolutions: 41 rpm at 1250 rpm/s, 21 rpm at 625 rpm/s) plus the
 * delay of a peak swept through at a finite rate, which vanishes as the rate does
 * (about as its square root). Measured: +121 rpm at 1250 rpm/s, +77 rpm at 625 rpm/s
 * (1.2 %); bounds: within one block spacing below and 2 % above at 625 rpm/s, and the
 * shift smaller at the slower rate (0.64 of the faster one's; bound 0.85). The mode alone
 * as a one-DOF whirl swept and tracked the same way in numpy/scipy
 * (runup_sdof_check.py) peaks in the same blocks: the shift is the sweep's. */
TEST(run_up_peak_at_the_critical_speed)
{
    gd_model *m = NULL;
    gd_system *s = NULL;
    REQUIRE(!load(&m, &s));
    /* the critical speed from campbell: 1x crossings between 6000 and 7200 rpm */
    double speeds[121];
    for (int i = 0; i < 121; i++)
        speeds[i] = (6000 + 10 * i) * RPM;
    gd_campbell_options co;
    gd_campbell_options_init(&co);
    co.nspeeds = 121;
    co.speeds = speeds;
    co.nmodes = 2;
    gd_campbell_result *cr = NULL;
    gd_error err;
    REQUIRE(gd_campbell(s, &co, &cr, &err) == GD_OK);
    double crit = 0;
    for (int i = 0; i < cr->ncritical; i++)
        crit = fmax(crit, cr->critical[i].speed); /* the forward mode's (the higher) */
    gd_campbell_free(cr);
    CHECK_REL(crit, 6649.8 * RPM, 1e-3);
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    REQUIRE(gd_transient_new(s, &tm->spec, 6650 * RPM, &tr, &err) == GD_OK);
    double sp1 = 0, sp2 = 0;
    double p1 = peak_speed(tr, s, 1250, &sp1), p2 = peak_speed(tr, s, 625, &sp2);
    fprintf(stderr, "  critical %.1f rpm; peaks %.1f rpm (1250 rpm/s), %.1f rpm (625 rpm/s)\n",
            crit / RPM, p1 / RPM, p2 / RPM);
    CHECK(p2 >= crit - fabs(sp2));
    CHECK(p2 <= 1.02 * crit);
    CHECK(p2 - crit < 0.85 * (p1 - crit));
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

RUN_TESTS(T(profile_angle_is_the_speed_integral), T(order_tracking_of_a_chirp),
          T(flat_profile_equals_constant_speed),
          T(profile_re_evaluates_gyroscopics_and_bearing_tables), T(run_up_refusals),
          T(run_up_peak_at_the_critical_speed))
