/* The linear time-invariant method (src/transient/linear.c) and GD_TR_AUTO: exactness
 * on a free oscillator, an unbalance run-up against CVODE at rtol 1e-10 within the rtol
 * asked, and auto on a nonlinear model (Chen's gear pair with squeeze film dampers)
 * taking CVODE BDF with the same numbers as an explicit bdf run. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/model_file.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static gd_transient_result *run(gd_transient *tr, gd_tr_method method, double rtol, double t_end,
                                double dt, const gd_tr_record *rec, int nrec)
{
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.method = method;
    o.t_end = t_end;
    o.output_interval = dt;
    o.rtol = rtol;
    if (rtol < 1e-8) {
        o.atol_q = 1e-16;
        o.atol_v = 1e-13;
    }
    gd_transient_result *r = NULL;
    gd_error err;
    if (gd_transient_run(tr, &o, rec, nrec, &r, &err)) fprintf(stderr, "  %s\n", err.message);
    return r;
}

/* Largest difference of every record over the samples, relative to the record's peak in
 * the reference (the measure of bench/bench_transient_linear). */
static double rel_error(const gd_transient_result *a, const gd_transient_result *ref)
{
    double e = 0;
    for (int k = 0; k < ref->nrecords; k++) {
        double pk = 0, d = 0;
        for (int i = 0; i < ref->nout; i++) {
            pk = fmax(pk, fabs(ref->values[(size_t)k * ref->nout + i]));
            d = fmax(d, fabs(a->values[(size_t)k * ref->nout + i] -
                             ref->values[(size_t)k * ref->nout + i]));
        }
        e = fmax(e, d / pk);
    }
    return e;
}

/* m = 1 kg on k = 1e6 N/m (omega = 1000 rad/s) released from q0 = 1e-3 m: q0 cos(w t)
 * over 0.1 s (16 periods) sampled every 1e-3 s (w dt = 1). Measured with the (8,8)
 * approximant (issue 35): the h^16 regime is seen at the first level, the run at 1e-3 s is
 * returned, its samples agree with the cosine to 3.0e-12 of q0 (round-off), estimate
 * 7.8e-12 (Richardson's d / 65535 plus the round-off floor; without the floor 2e-17);
 * bounds: the rtol, and the estimate within 10x of the error. */
TEST(free_oscillator_is_exact)
{
    static const char *sdof = "dofs: [x]\n"
                              "shafts: [{name: s, nodes: [{name: n}]}]\n"
                              "disks: [{node: n, mass: 1}]\n"
                              "bearings: [{name: b, node: n, kxx: 1e6}]\n";
    gd_error err;
    gd_model *m = NULL;
    gd_system *s = NULL;
    REQUIRE(gd_model_load_string(sdof, "sdof.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    gd_transient_spec spec;
    memset(&spec, 0, sizeof spec);
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(s, &spec, 0, &tr, &err) == GD_OK);
    double q0 = 1e-3, v0 = 0;
    gd_tr_record rec = {GD_REC_DISP, 0, 0};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.method = GD_TR_AUTO;
    o.rtol = 1e-10;
    o.t_end = 0.1;
    o.output_interval = 1e-3;
    o.init = GD_TR_INIT_GIVEN;
    o.q0 = &q0;
    o.v0 = &v0;
    gd_transient_result *r = NULL;
    REQUIRE(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_OK);
    CHECK(r->method_used == GD_TR_LTI);
    double e = 0;
    for (int i = 0; i < r->nout; i++)
        e = fmax(e, fabs(r->values[i] - q0 * cos(1000.0 * r->t[i])));
    printf("  free oscillator: step %g s, estimate %.3g, error %.3g of q0\n", r->step,
           r->error_estimate, e / q0);
    CHECK(r->error_estimate <= 1e-10);
    CHECK_ABS(e / q0, 0.0, 1e-10);
    CHECK(e / q0 <= r->error_estimate && r->error_estimate <= 10 * e / q0);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    gd_system_free(s);
    gd_model_free(m);
}

/* Unbalances on both gears of the MMT rig (one element per section: 30 DOFs; the
 * shafts turn at 3000 and 4500 rpm: two harmonic responses) switched on from rest,
 * 0.02 s sampled every 1e-4 s, records at the two gears and a bearing: auto against CVODE
 * BDF at rtol 1e-10 (an independent method; its own error is about 2.4e-8 here) and
 * against the linear method at rtol 1e-12 (the truth to about 1e-12). Measured: at rtol
 * 1e-4 and 1e-6 the step is halved twice to 2.5e-5 s; the difference from the run at
 * 5e-5 s is 9.3e-7, 1/280 of the one before (the h^8 regime), so the estimate is
 * Richardson's 9.3e-7 / 255 = 3.6e-9 against a true error of 4.2e-9 (issue 35: the
 * estimate was the bound 9.3e-7, 250 times the error). Bounds: the error within the rtol
 * asked, CVODE within its own error, the estimate within 10x of the true error. */
TEST(unbalance_run_up_within_rtol_of_tight_cvode)
{
    const char *set[] = {"shafts.*.elements_per_section=1",
                         "unbalances=[{node: gear48, amount: 1e-5}, "
                         "{node: gear32, amount: 5e-6, phase: 90 deg}]"};
    gd_error err;
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_load_options lo = {2, set};
    REQUIRE(gd_model_load_opts("examples/rig2018.yaml", &lo, &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    gd_transient_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.unbalances = 1;
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(s, &spec, 314.159265, &tr, &err) == GD_OK);
    gd_tr_record rec[3] = {
        {GD_REC_DISP, gd_system_dof(s, gd_model_find_node(m, "gear48"), GD_X), 0},
        {GD_REC_DISP, gd_system_dof(s, gd_model_find_node(m, "gear32"), GD_Y), 0},
        {GD_REC_DISP, gd_system_dof(s, gd_model_find_node(m, "brg_d1"), GD_Y), 0}};
    gd_transient_result *ref = run(tr, GD_TR_BDF, 1e-10, 0.02, 1e-4, rec, 3);
    REQUIRE(ref);
    gd_transient_result *truth = run(tr, GD_TR_LTI, 1e-12, 0.02, 1e-4, rec, 3);
    REQUIRE(truth);
    CHECK(truth->error_estimate <= 1e-12);
    const double rtols[2] = {1e-4, 1e-6};
    for (int k = 0; k < 2; k++) {
        gd_transient_result *r = run(tr, GD_TR_AUTO, rtols[k], 0.02, 1e-4, rec, 3);
        REQUIRE(r);
        double e = rel_error(r, ref), et = rel_error(r, truth);
        printf("  rtol %g: %s; error against CVODE 1e-10: %.3g, against lti 1e-12: %.3g\n",
               rtols[k], r->method_note, e, et);
        CHECK(r->method_used == GD_TR_LTI);
        CHECK(r->error_estimate <= rtols[k]);
        CHECK(et <= rtols[k]);
        CHECK(e <= fmax(rtols[k], 1e-7));
        CHECK(et <= 10 * r->error_estimate && r->error_estimate <= 10 * et);
        gd_transient_result_free(r);
    }
    gd_transient_result_free(truth);
    gd_transient_result_free(ref);
    gd_transient_free(tr);
    gd_system_free(s);
    gd_model_free(m);
}

/* ROSS's rotor_example (bench/models/ross_example42.yaml, 42 DOFs) with its unbalance at
 * 3000 rpm from rest, 0.1 s every 1e-4 s, disk0.x (bench/bench_ross.sh), at the default
 * rtol 1e-6 against the method at rtol 1e-10. The difference of the first level (steps
 * of 1e-4 s against 2e-4 s) is 7.7e-7 and under rtol; the error of the run at 1e-4 s is
 * 3.0e-8, so returning it with 7.7e-7 said 25 times its error (issue 35). Measured: the
 * run at 2e-4 s is returned, error 7.8e-7, estimate 7.7e-7 (ratio 0.99); at rtol 1e-8
 * the run at 5e-5 s, error 2.9e-9, estimate 2.9e-9. With the (8,8) approximant (issue 35;
 * truth: the method at rtol 1e-13): the run at 2e-4 s, error 2.4e-8, estimate 2.4e-8; at
 * rtol 1e-8 the run at 1e-4 s, error 1.85e-12, estimate 1.85e-12. Bounds: within 10x
 * either way. */
TEST(estimate_within_10x_on_the_42_dof_ross_rotor)
{
    gd_error err;
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    REQUIRE(gd_model_load("bench/models/ross_example42.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    REQUIRE(gd_transient_new(s, &tm->spec, 3000 * M_PI / 30, &tr, &err) == GD_OK);
    gd_tr_record rec = {GD_REC_DISP, gd_system_dof(s, gd_model_find_node(m, "disk0"), GD_X), 0};
    gd_transient_result *truth = run(tr, GD_TR_LTI, 1e-13, 0.1, 1e-4, &rec, 1);
    REQUIRE(truth);
    const double rtols[2] = {1e-6, 1e-8};
    for (int k = 0; k < 2; k++) {
        gd_transient_result *r = run(tr, GD_TR_AUTO, rtols[k], 0.1, 1e-4, &rec, 1);
        REQUIRE(r);
        double e = rel_error(r, truth), est = r->error_estimate;
        printf("  rtol %g: step %g s, estimate %.3g, error %.3g (ratio %.2f)\n", rtols[k], r->step,
               est, e, est / e);
        CHECK(r->method_used == GD_TR_LTI);
        CHECK(est <= rtols[k] && e <= rtols[k]);
        CHECK(e > 0 && est >= e / 10 && est <= 10 * e);
        gd_transient_result_free(r);
    }
    gd_transient_result_free(truth);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

/* Chen's gear pair (squeeze film dampers: nonlinear) at 1500 rpm, 20 ms: auto takes
 * CVODE BDF, bit-identical to an explicit bdf run, and its note names the reason.
 * Against BDF at rtol 1e-10, measured error 7.5e-5 of the peak at the default rtol
 * 1e-6 (CVODE controls the local error; the global one is larger); bound 2e-4. */
TEST(auto_on_a_nonlinear_model_is_bdf)
{
    gd_error err;
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_model_load("examples/chen1998_gear_pair.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(s, &tm->spec, 1500 * M_PI / 30, &tr, &err) == GD_OK);
    gd_tr_record rec[2] = {{GD_REC_MESH_FORCE, 0, 0}, {GD_REC_SFD_FX, 0, 0}};
    gd_transient_result *ra = run(tr, GD_TR_AUTO, 1e-6, 0.02, 1e-5, rec, 2);
    gd_transient_result *rb = run(tr, GD_TR_BDF, 1e-6, 0.02, 1e-5, rec, 2);
    gd_transient_result *ref = run(tr, GD_TR_BDF, 1e-10, 0.02, 1e-5, rec, 2);
    REQUIRE(ra && rb && ref);
    CHECK(ra->method_used == GD_TR_BDF);
    CHECK(strstr(ra->method_note, "auto: bdf") != NULL);
    CHECK(strstr(ra->method_note, "sfd") != NULL);
    int same = ra->nout == rb->nout && ra->steps == rb->steps;
    for (int i = 0; same && i < 2 * ra->nout; i++)
        same = ra->values[i] == rb->values[i];
    CHECK(same);
    double e = rel_error(ra, ref);
    printf("  %s; error against CVODE 1e-10: %.3g\n", ra->method_note, e);
    CHECK_ABS(e, 0.0, 2e-4);
    gd_transient_result_free(ra);
    gd_transient_result_free(rb);
    gd_transient_result_free(ref);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

/* Explicit GD_TR_LTI on a nonlinear model: an input error naming the cause. */
TEST(lti_refuses_a_nonlinear_model)
{
    gd_error err;
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_model_load("examples/chen1998_gear_pair.yaml", &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    REQUIRE(gd_transient_model_build(s, &tm, &err) == GD_OK);
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(s, &tm->spec, 100, &tr, &err) == GD_OK);
    gd_tr_record rec = {GD_REC_MESH_FORCE, 0, 0};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.method = GD_TR_LTI;
    o.t_end = 1e-3;
    gd_transient_result *r = NULL;
    CHECK(gd_transient_run(tr, &o, &rec, 1, &r, &err) == GD_EINPUT);
    CHECK(r == NULL);
    CHECK(strstr(err.message, "sfd") != NULL);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
}

RUN_TESTS(T(free_oscillator_is_exact), T(unbalance_run_up_within_rtol_of_tight_cvode),
          T(estimate_within_10x_on_the_42_dof_ross_rotor), T(auto_on_a_nonlinear_model_is_bdf),
          T(lti_refuses_a_nonlinear_model))
