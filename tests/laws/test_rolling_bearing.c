/* The rolling-element bearing law (src/laws/rolling_bearing.c) against Harris &
 * Kotzalas (Rolling Bearing Analysis, 5th ed., 2006): the radial load integral J_r of a
 * bearing with zero clearance, Stribeck's maximum element load, and the ball-pass
 * frequency of the cage's kinematic speed. */
#include <math.h>

#include "geardyn/law_type.h"
#include "harness.h"

static void bearing(gd_law *L, int Z, double n, double gap)
{
    gd_law_init(L, &gd_law_rolling_bearing, "b");
    L->value[0] = Z;
    L->value[1] = 8e9; /* N/m^n */
    L->value[2] = n;
    L->value[3] = gap;
    L->value[4] = 0.03904; /* 6205: pitch diameter 39.04 mm, balls 7.94 mm */
    L->value[5] = 0.00794;
}

/* F_r = Z K delta^n J_r(1/2) with zero clearance: J_r(1/2) = (1/pi) int_0^pi/2
 * cos^(n+1) = Gamma((n+2)/2) / (2 sqrt(pi) Gamma((n+3)/2)) (0.2288 for balls, Harris &
 * Kotzalas Table 7.1; 0.2453 for n = 1.1) */
TEST(radial_load_integral_zero_clearance)
{
    const double ns[2] = {1.5, 10.0 / 9.0};
    for (int k = 0; k < 2; k++) {
        double n = ns[k];
        gd_law L;
        bearing(&L, 720, n, 0.0);
        gd_error err;
        REQUIRE(gd_law_check(&L, &err) == GD_OK);
        double delta = 2e-5, q[4] = {0, delta, 0, 0}, v[4] = {0}, f[4] = {0};
        gd_law_point x = {0.0, q, v};
        gd_law_rolling_bearing.force(&L, &x, f, NULL, NULL);
        double Jr = -f[1] / (720 * 8e9 * pow(delta, n));
        double exact = tgamma((n + 2) / 2) / (2 * sqrt(M_PI) * tgamma((n + 3) / 2));
        /* 720 elements: the sum is the integral to ~(2 pi / 720)^(n+2) */
        CHECK_REL(Jr, exact, 1e-6);
        CHECK(fabs(f[0]) < 1e-9 * fabs(f[1])); /* symmetric about the load */
        if (k == 0) CHECK_REL(exact, 0.2288, 2e-4);
        /* Stribeck: Q_max = F_r / (Z J_r), 4.37 F_r / Z for balls */
        double qmax = gd_law_rolling_bearing.record(&L, 3, &x);
        CHECK_REL(qmax * 720 / -f[1], 1.0 / exact, 1e-6);
        if (k == 0) CHECK_REL(qmax * 720 / -f[1], 4.37, 1e-3);
    }
}

TEST(clearance_and_loaded_elements)
{
    gd_law L;
    bearing(&L, 9, 1.5, 1e-5);
    double q[4] = {0, 0.5e-5, 0, 0}, v[4] = {0}, f[4] = {0};
    gd_law_point x = {0.0, q, v};
    gd_law_rolling_bearing.force(&L, &x, f, NULL, NULL);
    CHECK(f[0] == 0 && f[1] == 0); /* inside the clearance: no contact */
    CHECK(gd_law_rolling_bearing.record(&L, 2, &x) == 0);
    q[1] = 3e-5;           /* the elements near +y carry the load */
    L.value[8] = M_PI / 2; /* phase: element 0 on the load line, its neighbours at 40 deg */
    gd_law_rolling_bearing.force(&L, &x, f, NULL, NULL);
    double side = 3e-5 * cos(2 * M_PI / 9) - 1e-5; /* 1.30e-5: loaded too */
    double Fy = 8e9 * (pow(2e-5, 1.5) + 2 * pow(side, 1.5) * cos(2 * M_PI / 9));
    CHECK(gd_law_rolling_bearing.record(&L, 2, &x) == 3);
    CHECK_REL(-f[1], Fy, 1e-12);
    CHECK(fabs(f[0]) < 1e-12 * Fy);
    /* the force pushes the inner race back and the outer race along */
    CHECK(f[3] == -f[1]);
}

/* 6205 (9 balls, d/D = 7.94/39.04, alpha 0): BPFO = Z/2 (1 - d/D) f_shaft = 3.585 f_shaft */
TEST(ball_pass_frequency_of_the_cage)
{
    gd_law L;
    bearing(&L, 9, 1.5, 0.0);
    L.spin[0] = 100.0; /* inner race, rad/s; outer fixed */
    double w[2];
    char msg[64];
    REQUIRE(gd_law_rolling_bearing.frequencies(&L, w, 2, msg, sizeof msg) == 1);
    CHECK_REL(w[0] / 100.0, 4.5 * (1 - 0.00794 / 0.03904), 1e-14);
    CHECK_REL(w[0] / 100.0, 3.585, 2e-4);
    /* the cage angle advances at w_c: the contact pattern repeats after 2 pi / (Z w_c) */
    double wc = w[0] / 9;
    double q[4] = {1e-6, 2e-5, 0, 0}, v[4] = {0}, f0[4] = {0}, f1[4] = {0};
    gd_law_point x0 = {0.0, q, v}, x1 = {2 * M_PI / (9 * wc), q, v};
    gd_law_rolling_bearing.force(&L, &x0, f0, NULL, NULL);
    gd_law_rolling_bearing.force(&L, &x1, f1, NULL, NULL);
    CHECK_REL(f1[1], f0[1], 1e-9);
    /* a rotating outer race (housing spinning with the shaft): no relative motion */
    L.spin[1] = 100.0;
    CHECK(gd_law_rolling_bearing.frequencies(&L, w, 2, msg, sizeof msg) == 0);
}

TEST(bad_parameters_are_named)
{
    gd_law L;
    gd_error err;
    bearing(&L, 9, 1.5, 0.0);
    L.value[0] = 2.5;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "elements");
    bearing(&L, 9, 1.5, 0.0);
    L.value[5] = 0.05; /* ball larger than the pitch circle */
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "element_diameter");
    bearing(&L, 9, 3.0, 0.0);
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "exponent");
}

RUN_TESTS(T(radial_load_integral_zero_clearance), T(clearance_and_loaded_elements),
          T(ball_pass_frequency_of_the_cage), T(bad_parameters_are_named))
