/* Laws of the registry in whole problems: a model file's `laws:` list read with its
 * located errors, a user-defined type equal to the built-in one it copies, and harmonic
 * balance of a Duffing oscillator (a polynomial spring) against a long time
 * integration, the independent check of the law's Jacobian terms in Newton. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_error_support.h"
#include "model_support.h"

/* mu q'' + zeta q' + kappa q + gamma q^3 = P cos(W t) with NLvib's first example's
 * numbers (Krack & Gross 2019, 01_Duffing: mu 1, zeta 0.05, kappa 1, gamma 0.1, P 0.18)
 * in SI, at W = 1.2 rad/s */
#define DUFFING_HEAD                                                                               \
    "dofs: [x]\n"                                                                                  \
    "shafts:\n  - {name: s, nodes: [{name: m}]}\n"                                                 \
    "disks:\n  - {name: m, node: m, mass: 1}\n"                                                    \
    "springs:\n  - {name: k, node: m, dof: x, stiffness: 1}\n"                                     \
    "excitations:\n  loads:\n    - {node: m, dof: x, amplitude: 0.18, frequency: 1.2 rad/s}\n"
#define DUFFING                                                                                    \
    DUFFING_HEAD "laws:\n  - {type: polynomial_spring, name: cubic, node: m, dof: x, k3: 0.1, "    \
                 "damping: 0.05}\n"

TEST(model_file_laws_are_read)
{
    fx f;
    REQUIRE(load(&f, NULL, DUFFING));
    REQUIRE(f.m->nlaws == 1);
    const gd_model_law *L = &f.m->laws[0];
    CHECK_STR(L->name, "cubic");
    CHECK(L->type == &gd_law_polynomial_spring);
    CHECK(L->node == 0 && L->node2 == -1 && L->dof == GD_X);
    CHECK(L->value[2] == 0.1 && L->value[3] == 0.05 && L->value[0] == 0.0);
    gd_transient_model *tm;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    CHECK(tm->spec.nlaws == 1);
    CHECK(tm->spec.laws[0].dof[0] == 0 && tm->spec.laws[0].dof[1] == -1);
    gd_transient_model_free(tm);
    fx_free(&f);
}

TEST(model_file_law_errors_are_located)
{
    EXPECT_LOAD_ERROR(DUFFING_HEAD "laws:\n  - {type: journal, node: m, dof: x}\n", 12,
                      "laws[0].type", "unknown law type 'journal'", "polynomial_spring");
    EXPECT_LOAD_ERROR(DUFFING_HEAD "laws:\n  - {type: polynomial_spring, node: m, dof: x, k4: 1}\n",
                      12, NULL, "k4", "k3");
    EXPECT_LOAD_ERROR(DUFFING_HEAD "laws:\n  - {type: friction, node: m, dof: x, velocity: 0.01}\n",
                      12, NULL, "force", NULL);
    EXPECT_LOAD_ERROR(DUFFING_HEAD
                      "laws:\n  - {type: friction, node: m, dof: x, force: 1, velocity: 0}\n",
                      12, "laws[0].velocity", "positive", NULL);
    EXPECT_LOAD_ERROR(DUFFING_HEAD "laws:\n  - {type: polynomial_spring, node: nowhere, dof: x}\n",
                      12, NULL, "nowhere", NULL);
    EXPECT_LOAD_ERROR(DUFFING_HEAD "laws:\n  - {type: polynomial_spring, node: m, to: m, dof: x}\n",
                      12, "laws[0].to", "itself", NULL);
    EXPECT_LOAD_ERROR(DUFFING_HEAD "laws:\n  - {type: polynomial_spring, node: m, dof: q}\n", 12,
                      NULL, "q", NULL);
    EXPECT_LOAD_ERROR(DUFFING_HEAD "laws:\n  - {type: sfd, node: m, viscosity: 0.01, diameter: "
                                   "0.03, length: 0.01, clearance: 0.1 mm, film: 2}\n",
                      12, "laws[0].film", "film", NULL);
    /* a law on a DOF the model does not keep: one rule for every analysis (issue 35
     * item 5), the system refuses it with its line and field (the linear analyses
     * dropped it silently, the transient spec refused it) */
    gd_model *m = NULL;
    gd_error err;
    REQUIRE(gd_model_load_string(DUFFING_HEAD
                                 "laws:\n  - {type: polynomial_spring, node: m, dof: y, k1: 1}\n",
                                 "m.yaml", &m, &err) == GD_OK);
    gd_system *sys = NULL;
    CHECK(gd_system_build(m, &sys, &err) == GD_EINPUT);
    CHECK(sys == NULL);
    CHECK_STR(err.file, "m.yaml");
    CHECK(err.line == 12);
    CHECK_STR(err.field, "laws[0]");
    CHECK(strstr(err.message, "law 'polynomial_spring1' (polynomial_spring) acts on m.y, which "
                              "is not an active DOF") != NULL);
    CHECK(strstr(err.hint, "'dofs:'") != NULL);
    gd_model_free(m);
}

/* The cubic spring with damping written as a user would write their own law. */
static void user_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law, (void)k;
    u[0] = w[0] = 1.0;
}
static void user_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    const double *c = law->user; /* k3, damping */
    double d = x->q[0];
    f[0] -= c[0] * d * d * d + c[1] * x->v[0];
    if (jq) jq[0] = -3.0 * c[0] * d * d;
    if (jv) jv[0] = -c[1];
}
static const gd_law_record user_records[] = {{"force", "N"}};
static double user_record(const gd_law *law, int k, const gd_law_point *x)
{
    (void)k;
    const double *c = law->user;
    return c[0] * x->q[0] * x->q[0] * x->q[0] + c[1] * x->v[0];
}
static const gd_law_type user_cubic = {.name = "user_cubic",
                                       .flags = GD_LAW_SMOOTH,
                                       .nterms = 1,
                                       .term = user_term,
                                       .force = user_force,
                                       .records = user_records,
                                       .nrecords = 1,
                                       .record = user_record};

static gd_transient_result *run_duffing(const gd_system *sys, const gd_transient_spec *spec)
{
    gd_transient *tr;
    gd_error err;
    if (gd_transient_new(sys, spec, 0.0, &tr, &err)) return NULL;
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 60.0;
    o.record_from = 30.0;
    o.rtol = 1e-9;
    gd_tr_record rec[2] = {{GD_REC_DISP, 0, 0}, {GD_REC_LAW, 0, 0}};
    gd_transient_result *r = NULL;
    gd_transient_run(tr, &o, rec, 2, &r, &err);
    gd_transient_free(tr);
    return r;
}

TEST(user_law_equals_the_builtin_one)
{
    fx f;
    REQUIRE(load(&f, NULL, DUFFING));
    gd_transient_model *tm;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_transient_result *a = run_duffing(f.s, &tm->spec);
    /* the same problem with the user's law in place of the model's */
    double coef[2] = {0.1, 0.05};
    gd_law mine;
    gd_law_init(&mine, &user_cubic, "mine");
    mine.dof[0] = 0;
    mine.user = coef;
    gd_transient_spec spec = tm->spec;
    spec.laws = &mine;
    spec.nlaws = 1;
    gd_transient_result *b = run_duffing(f.s, &spec);
    REQUIRE(a && b);
    REQUIRE(a->nout == b->nout);
    double big = 0, diff = 0, fbig = 0, fdiff = 0;
    for (int k = 0; k < a->nout; k++) {
        big = fmax(big, fabs(a->values[k]));
        diff = fmax(diff, fabs(a->values[k] - b->values[k]));
        fbig = fmax(fbig, fabs(a->values[a->nout + k]));
        fdiff = fmax(fdiff, fabs(a->values[a->nout + k] - b->values[b->nout + k]));
    }
    /* the same arithmetic in another order: equal to rounding */
    CHECK(diff <= 1e-12 * big);
    CHECK(fdiff <= 1e-12 * fbig);
    CHECK(big > 0.3 && big < 0.7); /* still settling at 60 s: the orbit is 0.42 */
    gd_transient_result_free(a);
    gd_transient_result_free(b);
    /* a user type with a broken table is refused when the problem is made */
    gd_law_type broken = user_cubic;
    broken.force = NULL;
    mine.type = &broken;
    gd_transient *tr = NULL;
    CHECK(gd_transient_new(f.s, &spec, 0.0, &tr, &err) == GD_EINPUT);
    CHECK(tr == NULL);
    CHECK(strstr(err.message, "force") != NULL);
    gd_transient_model_free(tm);
    fx_free(&f);
}

TEST(duffing_harmonic_balance_against_time_integration)
{
    fx f;
    REQUIRE(load(&f, NULL, DUFFING));
    gd_transient_model *tm;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    /* the period is the load's: 2 pi / 1.2 s */
    double w0;
    REQUIRE(gd_periodic_fundamental(f.s, &tm->spec, 0.0, &w0, NULL, &err) == GD_OK);
    CHECK_REL(w0, 1.2, 1e-12);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 15;
    double speed = 1.0;
    gd_tr_record rec[2] = {{GD_REC_DISP, 0, 0}, {GD_REC_LAW, 0, 0}};
    gd_periodic_result *hb = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, &speed, 1, &o, rec, 2, &hb, &err) == GD_OK);
    REQUIRE(hb->npoints == 1 && hb->points[0].converged);
    /* the integrated orbit, sampled densely over whole periods after the transient
     * (free motion decays as e^(-zeta t / 2): 4e-14 of its start after 236 periods) */
    gd_transient *tr;
    REQUIRE(gd_transient_new(f.s, &tm->spec, 0.0, &tr, &err) == GD_OK);
    gd_transient_options to;
    gd_transient_options_init(&to);
    double T = 2 * M_PI / 1.2;
    to.t_end = 240 * T;
    to.record_from = 236 * T;
    to.output_interval = T / 4000;
    to.rtol = 1e-11;
    to.atol_q = to.atol_v = 1e-14;
    gd_transient_result *r = NULL;
    REQUIRE(gd_transient_run(tr, &to, rec, 2, &r, &err) == GD_OK);
    /* harmonics 1 and 3 of the integrated orbit (a DFT over its four whole periods, the
     * repeated end sample left out) against harmonic balance's: the integrator's error
     * (rtol 1e-11) bounds the difference; H = 15 is converged to 1e-15 here */
    const double *x = r->values;
    int N = r->nout - 1;
    double rms = 0;
    for (int k = 0; k < N; k++)
        rms += x[k] * x[k];
    rms = sqrt(rms / N);
    for (int h = 1; h <= 3; h += 2) {
        double c = 0, s2 = 0;
        for (int k = 0; k < N; k++) {
            double ph = 2 * M_PI * 4 * h * k / N;
            c += x[k] * cos(ph);
            s2 += x[k] * sin(ph);
        }
        double amp = 2 * hypot(c, s2) / N;
        CHECK_REL(hb->points[0].records[0].amplitude[h], amp, h == 1 ? 1e-8 : 1e-5);
    }
    CHECK_REL(hb->points[0].records[0].rms, rms, 1e-8);
    CHECK(hb->points[0].records[0].amplitude[1] > 0.4);
    /* a stable orbit (the period-1 response below the fold) */
    CHECK(hb->points[0].stable == 1);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    gd_periodic_result_free(hb);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* A rigid rotor (2 kg) on a 6205-like ball bearing with 5 um clearance under a 200 N
 * radial load at 3000 rpm: the response repeats at the ball-pass frequency Z w_c, not at
 * the shaft's (varying compliance, Sunnersjo 1978; Tiwari, Gupta & Prakash 2000) */
#define ROTOR_ON_BALLS                                                                             \
    "dofs: [x, y]\nshafts:\n  - {name: rotor, nodes: [{name: j}]}\n"                               \
    "disks:\n  - {name: j, node: j, mass: 2}\nspeed: 3000 rpm\n"                                   \
    "laws:\n  - {type: rolling_bearing, name: b, node: j, elements: 9, contact_stiffness: 8e9, "   \
    "clearance: 5 um, pitch_diameter: 39.04 mm, element_diameter: 7.94 mm, damping: 200 "          \
    "N*s/m}\n"                                                                                     \
    "excitations:\n  loads:\n    - {node: j, dof: y, value: -200 N}\n"

TEST(rolling_bearing_varying_compliance_at_ball_pass_frequency)
{
    fx f;
    REQUIRE(load(&f, NULL, ROTOR_ON_BALLS));
    gd_transient_model *tm;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    double W = 3000 * M_PI / 30, w0;
    REQUIRE(gd_periodic_fundamental(f.s, &tm->spec, W, &w0, NULL, &err) == GD_OK);
    double bpfo = 4.5 * (1 - 7.94 / 39.04) * W; /* Z / 2 (1 - d / D) W */
    CHECK_REL(w0, bpfo, 1e-9);
    gd_transient *tr;
    REQUIRE(gd_transient_new(f.s, &tm->spec, W, &tr, &err) == GD_OK);
    gd_transient_options o;
    gd_transient_options_init(&o);
    double Tb = 2 * M_PI / bpfo;
    o.t_end = 1.0 + 4 * Tb; /* settled: the free motion decays by e every ~0.1 s */
    o.record_from = 1.0;
    o.output_interval = Tb / 200;
    o.rtol = 1e-10;
    o.atol_q = 1e-16;
    o.atol_v = 1e-12;
    gd_tr_record rec[2] = {{GD_REC_DISP, dof(&f, "j", GD_Y), 0}, {GD_REC_LAW, 0, 2}};
    gd_transient_result *r = NULL;
    REQUIRE(gd_transient_run(tr, &o, rec, 2, &r, &err) == GD_OK);
    REQUIRE(r->nout == 801);
    double p2p = r->stats[0].peak_to_peak, dT = 0, dhalf = 0, dshaft = 0;
    int ks = (int)lround(2 * M_PI / W / o.output_interval); /* one shaft turn, in samples */
    for (int k = 0; k + 200 < r->nout; k++) {
        dT = fmax(dT, fabs(r->values[k + 200] - r->values[k]));
        dhalf = fmax(dhalf, fabs(r->values[k + 100] - r->values[k]));
        if (k + ks < r->nout) dshaft = fmax(dshaft, fabs(r->values[k + ks] - r->values[k]));
    }
    CHECK(p2p > 1e-8 && p2p < 1e-6); /* a ripple on the 11 um static deflection */
    /* periodic at the ball-pass period to the integrator's error (the ripple is 1e-2 of
     * the deflection), and neither at half of it nor at the shaft's turn */
    CHECK(dT < 1e-3 * p2p);
    CHECK(dhalf > 0.5 * p2p);
    CHECK(dshaft > 0.5 * p2p);
    /* three or four balls carry the load as the cage turns */
    CHECK(r->stats[1].min == 3 && r->stats[1].max == 4);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

RUN_TESTS(T(model_file_laws_are_read), T(model_file_law_errors_are_located),
          T(user_law_equals_the_builtin_one), T(duffing_harmonic_balance_against_time_integration),
          T(rolling_bearing_varying_compliance_at_ball_pass_frequency))
