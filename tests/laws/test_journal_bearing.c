/* The journal bearing law (src/laws/journal_bearing.c) against Ocvirk's short-bearing
 * closed forms for a cavitated (pi) film: the radial and tangential film forces of a
 * journal held at eccentricity ratio eps, the load capacity (Sommerfeld number) and the
 * attitude angle; a bush spinning with the journal carries nothing; the eight linearised
 * stiffness and damping coefficients about a static state against the short-bearing
 * closed forms. */
#include <math.h>

#include "geardyn/laws.h"
#include "harness.h"
#include "short_bearing_reference.h"

static void bearing(gd_law *L)
{
    gd_law_init(L, &gd_law_journal_bearing, "jb");
    L->value[0] = 0.02;  /* Pa s */
    L->value[1] = 0.05;  /* D */
    L->value[2] = 0.02;  /* L: L/D 0.4 */
    L->value[3] = 50e-6; /* c */
    L->spin[0] = 500.0;  /* rad/s */
}

TEST(ocvirk_static_forces_and_attitude)
{
    gd_law L;
    bearing(&L);
    gd_error err;
    REQUIRE(gd_law_check(&L, &err) == GD_OK);
    const double mu = 0.02, R = 0.025, len = 0.02, c = 50e-6, w = 500.0;
    const double eps[4] = {0.1, 0.3, 0.6, 0.9};
    for (int k = 0; k < 4; k++) {
        double e = eps[k];
        /* the journal along +x: radial = x, tangential = +y */
        double q[4] = {e * c, 0, 0, 0}, v[4] = {0}, f[4] = {0};
        gd_law_point x = {0.0, q, v};
        gd_law_journal_bearing.force(&L, &x, f, NULL, NULL);
        double s2 = 1 - e * e;
        double Fr = -mu * w * R * pow(len, 3) * e * e / (c * c * s2 * s2);
        double Ft = M_PI * mu * w * R * pow(len, 3) * e / (4 * c * c * pow(s2, 1.5));
        CHECK_REL(f[0], Fr, 1e-10);
        CHECK_REL(f[1], Ft, 1e-10);
        /* load capacity and attitude angle (Ocvirk) */
        double W = mu * w * R * pow(len, 3) / (4 * c * c) * e *
                   sqrt(M_PI * M_PI * s2 + 16 * e * e) / (s2 * s2);
        CHECK_REL(hypot(f[0], f[1]), W, 1e-10);
        CHECK_REL(atan2(f[1], -f[0]), atan(M_PI * sqrt(s2) / (4 * e)), 1e-10);
        /* the bush carries the opposite force */
        CHECK(f[2] == -f[0] && f[3] == -f[1]);
        CHECK_REL(gd_law_journal_bearing.record(&L, 2, &x), e, 1e-14);
    }
}

TEST(no_relative_spin_no_wedge)
{
    gd_law L;
    bearing(&L);
    L.spin[1] = L.spin[0]; /* the bush turns with the journal: no wedge action */
    double q[4] = {20e-6, 5e-6, 0, 0}, v[4] = {0}, f[4] = {0};
    gd_law_point x = {0.0, q, v};
    gd_law_journal_bearing.force(&L, &x, f, NULL, NULL);
    CHECK(fabs(f[0]) < 1e-12 && fabs(f[1]) < 1e-12);
    /* and the journal bearing without spin is the squeeze film damper */
    gd_law S;
    gd_sfd_params p = {.viscosity = 0.02,
                       .radius = 0.025,
                       .length = 0.02,
                       .clearance = 50e-6,
                       .film = GD_SFD_PI_FILM,
                       .correction = -1};
    gd_law_init(&S, &gd_law_sfd, "d");
    gd_sfd_law_values(&p, &S);
    double vv[4] = {0.01, -0.02, 0, 0}, fj[4] = {0}, fs[4] = {0};
    gd_law_point xs = {0.0, q, vv};
    L.spin[0] = L.spin[1] = 0;
    gd_law_journal_bearing.force(&L, &xs, fj, NULL, NULL);
    gd_law_sfd.force(&S, &xs, fs, NULL, NULL);
    CHECK_REL(fj[0], fs[0], 1e-14);
    CHECK_REL(fj[1], fs[1], 1e-14);
}

/* The law linearises its own force by central differences (relative step 1e-6):
 * agreement with the closed forms (short_bearing_reference.h) to 1e-6 of the largest
 * coefficient. */
TEST(linearised_coefficients_against_short_bearing)
{
    gd_law L;
    bearing(&L);
    const double c = 50e-6, w = 500.0;
    double worst_k = 0, worst_c = 0;
    for (int k = 1; k <= 9; k++) {
        double e = 0.1 * k;
        /* held at eps along +x at zero velocity: the static state of the load -f */
        double q[4] = {e * c, 0, 0, 0}, v[4] = {0}, f[4] = {0}, K[16] = {0}, C[16] = {0};
        gd_law_point x = {0.0, q, v};
        gd_law_journal_bearing.force(&L, &x, f, NULL, NULL);
        gd_law_journal_bearing.linearize(&L, &x, K, C);
        double W = hypot(f[0], f[1]);
        double ly[2] = {-f[0] / W, -f[1] / W}; /* y: along the load */
        double lx[2] = {ly[1], -ly[0]};        /* x: y turned by -90 deg */
        const double *ax[2] = {lx, ly};
        double a[4], b[4], Kd[4], Cd[4];
        short_bearing_coefficients(e, a, b);
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                double sk = 0, sc = 0;
                for (int r = 0; r < 2; r++)
                    for (int t = 0; t < 2; t++) {
                        sk += ax[i][r] * K[r + 4 * t] * ax[j][t];
                        sc += ax[i][r] * C[r + 4 * t] * ax[j][t];
                    }
                Kd[2 * i + j] = sk * c / W;
                Cd[2 * i + j] = sc * c * w / W;
            }
        double amax = 0, bmax = 0;
        for (int m = 0; m < 4; m++) {
            amax = fmax(amax, fabs(a[m]));
            bmax = fmax(bmax, fabs(b[m]));
        }
        for (int m = 0; m < 4; m++) {
            CHECK_ABS(Kd[m], a[m], 1e-6 * amax);
            CHECK_ABS(Cd[m], b[m], 1e-6 * bmax);
            worst_k = fmax(worst_k, fabs(Kd[m] - a[m]) / amax);
            worst_c = fmax(worst_c, fabs(Cd[m] - b[m]) / bmax);
        }
        if (k == 5)
            printf("  eps 0.5: a = %.6f %.6f %.6f %.6f (closed form %.6f %.6f %.6f %.6f)\n"
                   "           b = %.6f %.6f %.6f %.6f (closed form %.6f %.6f %.6f %.6f)\n",
                   Kd[0], Kd[1], Kd[2], Kd[3], a[0], a[1], a[2], a[3], Cd[0], Cd[1], Cd[2], Cd[3],
                   b[0], b[1], b[2], b[3]);
        /* the journal's block enters the bush's with the opposite sign */
        CHECK(K[2 + 4 * 2] == K[0] && K[0 + 4 * 2] == -K[0]);
    }
    printf("  eps 0.1..0.9: worst stiffness %.2g, damping %.2g of the largest coefficient\n",
           worst_k, worst_c);
}

RUN_TESTS(T(ocvirk_static_forces_and_attitude), T(no_relative_spin_no_wedge),
          T(linearised_coefficients_against_short_bearing))
