/* The drag laws (src/laws/churning_drag.c, src/laws/bearing_drag.c): their torques
 * against the published formulas written out by hand here, in the units the papers use,
 * their speed exponents, their sign and regularisation, and the located errors of bad
 * parameters. (Their Jacobians against differences: tests/laws/test_law_registry.c.) */
#include <math.h>
#include <string.h>

#include "geardyn/laws.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The torque on the node (the `torque` record) of law L at absolute speed w of node,
 * node2 at rest. */
static double torque_at_(gd_test_state *gd_ts_, gd_law *L, double w)
{
    double q[2] = {0, 0}, v[2] = {0, 0};
    L->rate[0] = w;
    L->rate[1] = 0.0;
    gd_law_point x = {0, q, v};
    double f[2] = {0, 0};
    L->type->force(L, &x, f, NULL, NULL);
    /* the record and the force agree, and the force is equal and opposite */
    CHECK_REL(L->type->record(L, 0, &x), f[0], 1e-15);
    CHECK_REL(f[1], -f[0], 1e-15);
    return f[0];
}
#define torque_at(L, w) torque_at_(gd_ts_, L, w)

static void churning_idler(gd_law *L)
{
    gd_law_init(L, &gd_law_churning_drag, "idler3");
    L->value[gd_law_param_index(L->type, "viscosity")] = 0.04;
    L->value[gd_law_param_index(L->type, "radius")] = 0.04;
    L->value[gd_law_param_index(L->type, "face_width")] = 0.015;
    L->value[gd_law_param_index(L->type, "immersion")] = 0.02;
    L->value[gd_law_param_index(L->type, "oil_volume")] = 1.5e-3;
}

TEST(churning_torque_equals_changenet_velex)
{
    gd_law L;
    churning_idler(&L);
    gd_error err;
    REQUIRE(gd_law_check(&L, &err) == GD_OK);
    /* Changenet & Velex (2007), first regime, written out: R 40 mm, b 15 mm, h 20 mm
     * (half the radius: wetted half-angle 60 deg), V0 1.5 l, mu 0.04 Pa s, rho 870, at
     * 200 rad/s. */
    double R = 0.04, b = 0.015, h = 0.02, rho = 870, nu = 0.04 / 870, w = 200, D = 0.08;
    double a = M_PI / 3; /* acos(1 - h / R) */
    double Sm = R * R * (2 * a - sin(2 * a)) + 2 * a * R * b;
    double Fr = w * w * R / 9.81, Re = w * R * b / nu;
    double Cm =
        1.366 * pow(h / D, 0.45) * pow(1.5e-3 / (D * D * D), 0.1) * pow(Fr, -0.6) * pow(Re, -0.21);
    double C = 0.5 * rho * w * w * Sm * R * R * R * Cm;
    /* the regularisation s = sqrt(w^2 + 1) changes it by 0.5 (1/200)^2 (1 - 0.59) ~ 5e-6 */
    CHECK_REL(-torque_at(&L, w), C, 1e-5);
    CHECK(Re < 6000); /* the first regime's range: the law's reynolds record */
    double q[2] = {0, 0}, v[2] = {0, 0};
    gd_law_point x = {0, q, v};
    CHECK_REL(L.type->record(&L, 2, &x), Re, 1e-12);
    /* the size of an idler's drag at idle: tens of mN m (C = 0.0260 N m here) */
    CHECK(C > 0.02 && C < 0.03);
    /* speed exponent 2 - 1.2 - 0.21 = 0.59, well above the regularisation */
    double r = torque_at(&L, 400) / torque_at(&L, 100);
    CHECK_REL(log(r) / log(4.0), 0.59, 1e-4);
    /* opposes the speed, odd, and linear through zero below w_r = 1 rad/s */
    CHECK(torque_at(&L, 50) < 0 && torque_at(&L, -50) > 0);
    CHECK_REL(torque_at(&L, -50), -torque_at(&L, 50), 1e-15);
    CHECK_REL(torque_at(&L, 1e-4) / torque_at(&L, 2e-4), 0.5, 1e-6);
    /* thicker oil (colder) churns less in this regime: Re^-0.21 */
    double t1 = torque_at(&L, 200);
    L.value[0] = 0.16;
    CHECK_REL(torque_at(&L, 200) / t1, pow(4.0, 0.21), 1e-12);
}

TEST(viscous_face_drag_equals_couette)
{
    gd_law L;
    churning_idler(&L);
    L.value[gd_law_param_index(L.type, "immersion")] = 0.0; /* no churning: faces only */
    L.value[gd_law_param_index(L.type, "wall_gap")] = 1e-3;
    /* both faces: 2 x integral_0^R (mu w r / s) 2 pi r^2 dr = pi mu w R^4 / s */
    double expect = M_PI * 0.04 * 150 * pow(0.04, 4) / 1e-3;
    CHECK_REL(-torque_at(&L, 150), expect, 1e-14);
}

TEST(bearing_moment_equals_palmgren)
{
    gd_law L;
    gd_law_init(&L, &gd_law_bearing_drag, "needle");
    gd_error err;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT); /* f0, pitch diameter, viscosity required */
    CHECK_STR(err.field, "f0");
    L.value[0] = 3.0;    /* f0 */
    L.value[1] = 0.035;  /* dm 35 mm */
    L.value[2] = 0.0435; /* mu: nu = 50 cSt at rho 870 */
    L.value[4] = 5e-4;   /* f1 */
    L.value[5] = 1000.0; /* P1 N */
    L.value[6] = 0.01;   /* w_r: the sign's regularisation far below the speeds checked */
    REQUIRE(gd_law_check(&L, &err) == GD_OK);
    /* at 1000 rpm: nu n = 5e4 >= 2000, M = 1e-7 f0 (nu n)^(2/3) dm^3 + f1 P1 dm (N mm) */
    double w = 1000 * M_PI / 30;
    double M_nmm = 1e-7 * 3.0 * pow(50.0 * 1000, 2.0 / 3.0) * pow(35.0, 3) + 5e-4 * 1000 * 35.0;
    CHECK_REL(-torque_at(&L, w), M_nmm * 1e-3, 1e-6);
    /* at 20 rpm: nu n = 1000 < 2000, the constant 160e-7 f0 dm^3 */
    w = 20 * M_PI / 30;
    M_nmm = 160e-7 * 3.0 * pow(35.0, 3) + 5e-4 * 1000 * 35.0;
    CHECK_REL(-torque_at(&L, w), M_nmm * 1e-3, 1e-4); /* 0.5 (w_r / w)^2 = 1e-5 */
    /* relative speed: the moment depends on node minus node2 */
    double q[2] = {0, 0}, v[2] = {3.0, 0}, f[2] = {0, 0};
    L.rate[0] = 200, L.rate[1] = 203;
    gd_law_point x = {0, q, v};
    L.type->force(&L, &x, f, NULL, NULL);
    CHECK_ABS(f[0], 0.0, 1e-15); /* no slip, no moment */
    /* negative viscosity: located at the field, with the fix */
    L.value[2] = -0.01;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "viscosity");
    CHECK(strstr(err.message, ">= 0") != NULL);
    /* none at all: the oil is needed, by viscosity or by nu40, nu100 and a temperature */
    L.value[2] = 0.0;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "viscosity");
    CHECK(strstr(err.message, "nu40") != NULL);
}

/* Temperature through Walther's equation (ASTM D341): an ISO VG 68 oil (68 and 8.7 mm^2/s
 * at 40 and 100 C) gives back its two points and thins in between; the laws then equal
 * the same laws given that viscosity. */
TEST(temperature_through_walther)
{
    gd_law T, V;
    churning_idler(&T);
    const gd_law_type *t = T.type;
    T.value[gd_law_param_index(t, "viscosity")] = 0.0;
    T.value[gd_law_param_index(t, "nu40")] = 68.0;
    T.value[gd_law_param_index(t, "nu100")] = 8.7;
    gd_error err;
    REQUIRE(gd_law_check(&T, &err) == GD_OK);
    double prev = 1e300;
    for (double c = 40; c <= 100; c += 10) {
        T.value[gd_law_param_index(t, "temperature")] = c;
        /* the viscosity the law uses, from its Reynolds number record: Re = w R b rho / mu */
        double q[2] = {0, 0}, v[2] = {0, 0};
        T.rate[0] = 200.0;
        gd_law_point x = {0, q, v};
        double mu = 200.0 * 0.04 * 0.015 * 870.0 / t->record(&T, 2, &x);
        if (c == 40) CHECK_REL(mu, 870 * 68e-6, 1e-12);
        if (c == 100) CHECK_REL(mu, 870 * 8.7e-6, 1e-12);
        CHECK(mu < prev);
        prev = mu;
        /* the same law given that viscosity */
        churning_idler(&V);
        V.value[0] = mu;
        CHECK_REL(torque_at(&T, 200.0), torque_at(&V, 200.0), 1e-12);
    }
    /* an oil that thickens when warmer is refused, naming the field */
    T.value[gd_law_param_index(t, "nu100")] = 80.0;
    CHECK(gd_law_check(&T, &err) == GD_EINPUT);
    CHECK_STR(err.field, "nu40");
}

TEST(churning_bad_parameters_are_located)
{
    gd_law L;
    churning_idler(&L);
    gd_error err;
    L.value[0] = -0.04;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "viscosity");
    L.value[0] = 0.04;
    L.value[gd_law_param_index(L.type, "immersion")] = 0.09; /* beyond 2 R = 0.08 */
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "immersion");
    CHECK(strstr(err.message, "pitch diameter") != NULL);
}

RUN_TESTS(T(churning_torque_equals_changenet_velex), T(viscous_face_drag_equals_couette),
          T(temperature_through_walther), T(bearing_moment_equals_palmgren),
          T(churning_bad_parameters_are_located))
