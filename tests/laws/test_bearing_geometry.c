/* Rolling bearings from geometry (src/laws/bearing_geometry.c, [LimSingh1990]): the 5 x 5
 * stiffness at load against its invariants and independent references: the radial block
 * equals the rolling_bearing law's; the ball bearing's radial stiffness grows as F^(1/3)
 * (and a roller's as F^(1/10)) with zero clearance; Harris's radial load integral J_r(1/2);
 * a preloaded angular-contact bearing under axial load against the one-dimensional
 * balance of its equally loaded balls; the tangent against central differences. */
#include <math.h>
#include <string.h>

#include "geardyn/bearing_geometry.h"
#include "geardyn/law_type.h"
#include "harness.h"

static gd_bearing_geometry ball(double alpha, double clearance)
{
    gd_bearing_geometry g;
    gd_bearing_geometry_init(&g);
    g.elements = 9; /* 6205-like: balls 7.94 mm on a 39.04 mm pitch circle */
    g.element_diameter = 7.94e-3;
    g.pitch_diameter = 39.04e-3;
    g.contact_angle = alpha;
    g.clearance = clearance;
    return g;
}

static gd_bearing_geometry roller(double alpha)
{
    gd_bearing_geometry g;
    gd_bearing_geometry_init(&g);
    g.kind = GD_BEARING_ROLLER;
    g.elements = 14;
    g.element_diameter = 7.5e-3;
    g.pitch_diameter = 46e-3;
    g.roller_length = 10e-3;
    g.contact_angle = alpha;
    return g;
}

/* With alpha0 = 0 and no axial motion the ball's contact stays radial: the radial forces
 * and the 2 x 2 radial block are the rolling_bearing law's (opposite sign: the law gives
 * the force on the inner race), to rounding. */
TEST(radial_block_is_the_rolling_bearing_law)
{
    gd_bearing_geometry g = ball(0, 3e-6);
    g.contact_stiffness = 8e9;
    g.phase = 0.3;
    gd_law L;
    gd_law_init(&L, &gd_law_rolling_bearing, "b");
    double v[] = {9, 8e9, 1.5, 3e-6, 0.03904, 0.00794, 0, 0, 0.3};
    memcpy(L.value, v, sizeof v);
    double d[5] = {11e-6, -4e-6, 0, 0, 0}, F[5], K[25];
    gd_error err;
    REQUIRE(gd_bearing_forces(&g, d, F, K, NULL, &err) == GD_OK);
    double q[4] = {d[0], d[1], 0, 0}, vel[4] = {0}, f[4] = {0}, Kl[16] = {0}, Cl[16] = {0};
    gd_law_point x = {0, q, vel};
    L.type->force(&L, &x, f, NULL, NULL);
    L.type->linearize(&L, &x, Kl, Cl);
    CHECK_REL(F[0], -f[0], 1e-12);
    CHECK_REL(F[1], -f[1], 1e-12);
    for (int b = 0; b < 2; b++)
        for (int a = 0; a < 2; a++)
            CHECK_REL(K[a + 5 * b], Kl[a + 4 * b], 1e-12);
}

/* Zero clearance, radial load: the load zone keeps its shape, delta ~ F^(1/n), so the
 * radial stiffness n F / delta grows as F^(1 - 1/n): F^(1/3) for balls, F^(1/10) for
 * rollers. Exact but for the solve (1e-11 of the load): 1e-8. */
TEST(radial_stiffness_power_laws)
{
    gd_error err;
    for (int kind = 0; kind < 2; kind++) {
        gd_bearing_geometry g = kind ? roller(0) : ball(0, 0);
        double n = kind ? 10.0 / 9.0 : 1.5, k1[25], k8[25], d[5];
        double L1[5] = {0, 1000, 0, 0, 0}, L8[5] = {0, 8000, 0, 0, 0};
        REQUIRE(gd_bearing_at_load(&g, L1, d, k1, &err) == GD_OK);
        REQUIRE(gd_bearing_at_load(&g, L8, d, k8, &err) == GD_OK);
        double ratio = k8[1 + 5 * 1] / k1[1 + 5 * 1], want = pow(8.0, 1 - 1 / n);
        printf("  %s: k_yy %.5g -> %.5g N/m for 1 -> 8 kN: x %.10f (F^%.4f: %.10f)\n",
               kind ? "roller" : "ball", k1[6], k8[6], ratio, 1 - 1 / n, want);
        CHECK_REL(ratio, want, 1e-8);
        CHECK_REL(k8[0] / k1[0], want, 1e-8); /* the x stiffness alike */
    }
}

/* Harris's radial integral: with zero clearance F_r = Z Q_max J_r(1/2), J_r(1/2) = (1/pi)
 * int_0^(pi/2) cos^(n+1) psi dpsi = 0.2288 (balls, n = 3/2), 0.2453 (line
 * contact as n = 1.1) in Harris & Kotzalas Table 7.1 (four digits: 1e-4 absolute); the
 * closed form Gamma((n+2)/2) / (2 sqrt(pi)
 * Gamma((n+3)/2)) to 1e-6 with Z = 360 elements (the discrete sum's error is far
 * below). */
TEST(harris_radial_load_integral)
{
    gd_error err;
    for (int kind = 0; kind < 2; kind++) {
        gd_bearing_geometry g = kind ? roller(0) : ball(0, 0);
        g.elements = 360;
        g.phase = M_PI / 2; /* element 0 under the load */
        double n = kind ? 10.0 / 9.0 : 1.5, kn, nn, d[5], K[25];
        REQUIRE(gd_bearing_contact_constant(&g, &kn, &nn, &err) == GD_OK);
        CHECK(nn == n);
        double L[5] = {0, 5000, 0, 0, 0};
        REQUIRE(gd_bearing_at_load(&g, L, d, K, &err) == GD_OK);
        double qmax = kn * pow(d[1], n), J = L[1] / (g.elements * qmax);
        double closed = tgamma((n + 2) / 2) / (2 * sqrt(M_PI) * tgamma((n + 3) / 2));
        printf("  %s: J_r(1/2) %.6f, closed form %.6f, Harris %.4f\n", kind ? "roller" : "ball", J,
               closed, kind ? 0.2453 : 0.2288);
        CHECK_REL(J, closed, 1e-6);
        /* Harris's table: n = 1.5 and n = 1.1 (his line contact) */
        double nh = kind ? 1.1 : 1.5;
        double table = tgamma((nh + 2) / 2) / (2 * sqrt(M_PI) * tgamma((nh + 3) / 2));
        CHECK_ABS(table, kind ? 0.2453 : 0.2288, 1e-4);
    }
}

/* An angular-contact ball bearing (25 deg) preloaded by 2 um of interference under a pure
 * axial load: every ball carries Q = K_n (A - A0)^(3/2) at the same angle, Z Q sin(alpha)
 * = F_a; the axial approach by bisection of that balance, to 1e-9. */
TEST(axial_load_on_angular_contact)
{
    gd_error err;
    gd_bearing_geometry g = ball(25 * M_PI / 180, -2e-6);
    double kn, n, d[5], K[25], L[5] = {0, 0, 1500, 0, 0};
    REQUIRE(gd_bearing_contact_constant(&g, &kn, &n, &err) == GD_OK);
    REQUIRE(gd_bearing_at_load(&g, L, d, K, &err) == GD_OK);
    const double A0 = 0.04 * g.element_diameter, a0 = g.contact_angle;
    double lo = -1e-4, hi = 1e-4;
    for (int i = 0; i < 200; i++) {
        double z = 0.5 * (lo + hi), u = A0 * sin(a0) + z, v = A0 * cos(a0) + 2e-6;
        double A = hypot(u, v), F = A > A0 ? 9 * kn * pow(A - A0, 1.5) * u / A : 0;
        (F > 1500 ? (hi = z) : (lo = z));
    }
    printf("  K_n %.5g N/m^1.5; axial approach %.6g um (bisection %.6g um), k_zz %.5g N/m\n", kn,
           d[2] * 1e6, 0.5e6 * (lo + hi), K[2 + 5 * 2]);
    CHECK_REL(d[2], 0.5 * (lo + hi), 1e-9);
    CHECK_ABS(d[0], 0.0, 1e-12 * fabs(d[2]));
    CHECK_ABS(d[3], 0.0, 1e-9 * fabs(d[2]) / 0.02);
}

/* Combined load (radial, axial and moments) on the angular-contact ball bearing and a
 * tapered roller bearing (15 deg): the load is carried (1e-9), K is symmetric (1e-12 of
 * its largest entry) and equals Richardson-extrapolated central differences of F (steps
 * 1e-7 of the displacement's size) to 1e-6 of its largest entry. */
TEST(tangent_against_central_differences)
{
    gd_error err;
    for (int kind = 0; kind < 2; kind++) {
        gd_bearing_geometry g = kind ? roller(15 * M_PI / 180) : ball(25 * M_PI / 180, -2e-6);
        double L[5] = {700, -1200, 2500, 15, -8}, d[5], K[25], F[5];
        double rt = 0.5 * g.pitch_diameter * tan(g.contact_angle);
        if (kind) L[3] = L[4] = 0; /* a roller's tilt is held: its moments follow */
        REQUIRE(gd_bearing_at_load(&g, L, d, K, &err) == GD_OK);
        REQUIRE(gd_bearing_forces(&g, d, F, NULL, NULL, &err) == GD_OK);
        if (kind) {
            CHECK(d[3] == 0 && d[4] == 0);
            L[3] = rt * L[1]; /* Mx = R tan(alpha) Fy, My = -R tan(alpha) Fx */
            L[4] = -rt * L[0];
        }
        for (int a = 0; a < 5; a++)
            CHECK_ABS(F[a], L[a], 1e-9 * 2500);
        double big = 0, asym = 0, worst = 0, size = 0;
        for (int a = 0; a < 25; a++)
            big = fmax(big, fabs(K[a]));
        for (int a = 0; a < 5; a++) {
            size = fmax(size, fabs(a < 3 ? d[a] : d[a] * 0.023));
            for (int b = 0; b < 5; b++)
                asym = fmax(asym, fabs(K[a + 5 * b] - K[b + 5 * a]));
        }
        for (int b = 0; b < 5; b++) {
            double h = 1e-7 * (b < 3 ? size : size / 0.023), col[2][5];
            for (int pass = 0; pass < 2; pass++) {
                double hh = pass ? 2 * h : h, dp[5], dm[5], Fp[5], Fm[5];
                memcpy(dp, d, sizeof dp);
                memcpy(dm, d, sizeof dm);
                dp[b] += hh;
                dm[b] -= hh;
                gd_bearing_forces(&g, dp, Fp, NULL, NULL, &err);
                gd_bearing_forces(&g, dm, Fm, NULL, NULL, &err);
                for (int a = 0; a < 5; a++)
                    col[pass][a] = (Fp[a] - Fm[a]) / (2 * hh);
            }
            /* the entries of the tilt columns and rows carry R and R^2: compare each in
               the scaled coordinates (tilt x R) */
            for (int a = 0; a < 5; a++) {
                double s = (a < 3 ? 1 : 1 / 0.023) * (b < 3 ? 1 : 1 / 0.023);
                double fd = (4 * col[0][a] - col[1][a]) / 3;
                worst = fmax(worst, fabs(K[a + 5 * b] - fd) * s);
            }
        }
        double bigs = 0;
        for (int b = 0; b < 5; b++)
            for (int a = 0; a < 5; a++)
                bigs = fmax(bigs,
                            fabs(K[a + 5 * b]) * (a < 3 ? 1 : 1 / 0.023) * (b < 3 ? 1 : 1 / 0.023));
        printf("  %s: d = (%.4g, %.4g, %.4g um, %.4g, %.4g mrad); |K - K_fd| %.2g, asymmetry "
               "%.2g of the largest entry\n",
               kind ? "tapered roller" : "angular ball", d[0] * 1e6, d[1] * 1e6, d[2] * 1e6,
               d[3] * 1e3, d[4] * 1e3, worst / bigs, asym / big);
        printf("    K_xx %.4g K_yy %.4g K_zz %.4g N/m, K_xz %.4g N/m, K_z,bx %.4g N/rad, K_bxbx "
               "%.4g N m/rad\n",
               K[0], K[6], K[12], K[2], K[2 + 15], K[18]);
        CHECK(asym <= 1e-12 * big);
        CHECK(worst <= 1e-6 * bigs);
    }
}

TEST(bad_input_is_named)
{
    gd_error err;
    gd_bearing_geometry g = ball(0, 0);
    g.element_diameter = 0.05;
    double kn, n, d[5], K[25];
    CHECK(gd_bearing_contact_constant(&g, &kn, &n, &err) == GD_EINPUT);
    CHECK_STR(err.field, "pitch_diameter");
    g = ball(0, 0);
    g.elements = 2;
    CHECK(gd_bearing_contact_constant(&g, &kn, &n, &err) == GD_EINPUT);
    CHECK_STR(err.field, "elements");
    g = roller(0);
    double axial[5] = {0, 100, 50, 0, 0};
    CHECK(gd_bearing_at_load(&g, axial, d, K, &err) == GD_EINPUT);
    CHECK_STR(err.field, "load");
    CHECK(strstr(err.message, "axial") != NULL);
    CHECK(strstr(err.hint, "contact angle") != NULL);
    g = roller(0.2);
    double moment[5] = {0, 100, 50, 1, 0};
    CHECK(gd_bearing_at_load(&g, moment, d, K, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "moments") != NULL);
    g = roller(0);
    double nan_load[5] = {NAN, 0, 0, 0, 0};
    CHECK(gd_bearing_at_load(&g, nan_load, d, K, &err) == GD_EINPUT);
    g = roller(0);
    g.roller_length = 0;
    CHECK(gd_bearing_contact_constant(&g, &kn, &n, &err) == GD_EINPUT);
    CHECK_STR(err.field, "roller_length");
}

RUN_TESTS(T(radial_block_is_the_rolling_bearing_law), T(radial_stiffness_power_laws),
          T(harris_radial_load_integral), T(axial_load_on_angular_contact),
          T(tangent_against_central_differences), T(bad_input_is_named))
