/* The cam torque law (gd_law_cam_torque, src/laws/cam_torque.c): its force is minus
 * [Benini2004] Eq. 10's torque (gd_cam_torque) in the camshaft's own sense, its
 * inertia is m s'^2 (only with the acceleration term), its Jacobian terms match
 * central differences of its force, its frequency is the camshaft's speed. */
#include <math.h>
#include <string.h>

#include "geardyn/laws.h"
#include "harness.h"

/* a lift of once and twice per revolution, 8 mm peak */
static gd_lift_law lift(void)
{
    gd_lift_law l;
    memset(&l, 0, sizeof l);
    l.kind = GD_LIFT_HARMONIC;
    l.harmonic.mean = 4e-3;
    l.harmonic.order = 1.0;
    l.harmonic.n = 2;
    l.harmonic.cos_amp[0] = -4e-3;
    l.harmonic.cos_amp[1] = 5e-4;
    l.harmonic.sin_amp[1] = 2e-4;
    return l;
}

/* a valve of 0.12 kg at phase 0.4 rad on a camshaft at W = rate (sense of its sign) */
static void cam(gd_law *L, const gd_lift_law *l, double rate, double acc)
{
    gd_law_init(L, &gd_law_cam_torque, "c");
    L->data = l;
    L->dof[0] = 0;
    L->value[gd_law_param_index(&gd_law_cam_torque, "mass")] = 0.12;
    L->value[gd_law_param_index(&gd_law_cam_torque, "phase")] = 0.4;
    L->value[gd_law_param_index(&gd_law_cam_torque, "acceleration")] = acc;
    L->rate[0] = L->spin[0] = rate;
}

TEST(cam_force_is_minus_eq10_torque_in_the_camshafts_sense)
{
    gd_lift_law l = lift();
    for (int s = -1; s <= 1; s += 2)
        for (int acc = 0; acc < 2; acc++) {
            gd_law L;
            cam(&L, &l, s * 500.0, acc);
            gd_error err;
            REQUIRE(gd_law_check(&L, &err) == GD_OK);
            CHECK(((gd_law_flags(&L) & GD_LAW_INERTIA) != 0) == acc);
            const double t = 3.1e-3, q = 0.02, v = -7.0, qdd = 4e3;
            gd_law_point x = {t, &q, &v};
            double f = 0.0, m = 0.0, f2 = 0.0;
            gd_law_cam_torque.force(&L, &x, &f, NULL, NULL);
            /* the inertia op (asked only with the flag): the same force, and the mass */
            if (acc) {
                gd_law_cam_torque.inertia(&L, &x, &f2, &m);
                CHECK(f2 == f);
            }
            /* theta, W, W' in the camshaft's sense; generalised force -s T - m q'' */
            double th = s * (s * 500.0 * t + q), w = s * (s * 500.0 + v);
            double wdot = acc ? s * qdd : 0.0;
            double T = gd_cam_torque(&l, 0.12, 0.4, th, w, wdot);
            CHECK_REL(f - m * qdd, -s * T, 1e-13);
            /* the inertia is m s'^2 */
            double s1, s2;
            gd_lift_eval(&l, th - 0.4, &s1, &s2);
            CHECK_REL(m, acc ? 0.12 * s1 * s1 : 0.0, 1e-15);
            CHECK(s1 != 0.0); /* the point is on the lift's flank */
        }
}

TEST(cam_jacobian_terms_match_differences)
{
    gd_lift_law l = lift();
    gd_law L;
    cam(&L, &l, -450.0, 0);
    double q = 0.3, v = 12.0, f = 0.0, jq, jv;
    gd_law_point x = {1e-3, &q, &v};
    gd_law_cam_torque.force(&L, &x, &f, &jq, &jv);
    double u = 0, w = 0;
    gd_law_cam_torque.term(&L, 0, &u, &w);
    CHECK(u == 1.0 && w == 1.0);
    for (int pass = 0; pass < 2; pass++) {
        double *z = pass ? &v : &q, keep = *z, h = 1e-5 * (fabs(keep) + 1e-3);
        double fp = 0.0, fm = 0.0;
        *z = keep + h;
        gd_law_cam_torque.force(&L, &x, &fp, NULL, NULL);
        *z = keep - h;
        gd_law_cam_torque.force(&L, &x, &fm, NULL, NULL);
        *z = keep;
        /* the law's d(s' s'')/d theta is itself a difference of step 1e-6: 1e-7 */
        CHECK_REL(pass ? jv : jq, (fp - fm) / (2 * h), 1e-7);
    }
}

TEST(cam_frequency_and_checks)
{
    gd_lift_law l = lift();
    gd_law L;
    cam(&L, &l, -450.0, 1);
    double w[2];
    char msg[80];
    CHECK(gd_law_cam_torque.frequencies(&L, w, 2, msg, sizeof msg) == 1);
    CHECK(w[0] == 450.0); /* the lift repeats once per cam revolution */
    gd_error err;
    L.data = NULL;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "lift law missing") != NULL);
    L.data = &l;
    L.value[gd_law_param_index(&gd_law_cam_torque, "mass")] = -1.0;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "mass");
    CHECK(gd_law_type_validate(&gd_law_cam_torque, &err) == GD_OK);
}

RUN_TESTS(T(cam_force_is_minus_eq10_torque_in_the_camshafts_sense),
          T(cam_jacobian_terms_match_differences), T(cam_frequency_and_checks))
