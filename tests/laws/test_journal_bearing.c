/* The journal bearing law (src/laws/journal_bearing.c) against Ocvirk's short-bearing
 * closed forms for a cavitated (pi) film: the radial and tangential film forces of a
 * journal held at eccentricity ratio eps, the load capacity (Sommerfeld number) and the
 * attitude angle; a bush spinning with the journal carries nothing; the eight linearised
 * stiffness and damping coefficients about a static state against the short-bearing
 * closed forms. */
#include <math.h>

#include "geardyn/laws.h"
#include "geardyn/reynolds.h"
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

/* The law linearises its own force in closed form (gd_sfd_force_jacobian): agreement with the
 * closed forms (short_bearing_reference.h) to 1e-6 of the largest coefficient. */
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

/* Richardson-extrapolated central difference of gd_sfd_force along coordinate j of
 * u = (x, y, vx, vy), step h: d[i] = d f_i / d u_j. */
static void film_difference(const gd_sfd_params *p, const double u[4], int j, double h, double d[2])
{
    double D[2][2];
    for (int r = 0; r < 2; r++) {
        double hs = r ? 0.5 * h : h, up[4], um[4], fp[2], fm[2];
        for (int k = 0; k < 4; k++)
            up[k] = um[k] = u[k];
        up[j] += hs;
        um[j] -= hs;
        gd_sfd_force(p, up[0], up[1], up[2], up[3], &fp[0], &fp[1]);
        gd_sfd_force(p, um[0], um[1], um[2], um[3], &fm[0], &fm[1]);
        for (int i = 0; i < 2; i++)
            D[r][i] = (fp[i] - fm[i]) / (2.0 * hs);
    }
    for (int i = 0; i < 2; i++)
        d[i] = (4.0 * D[1][i] - D[0][i]) / 3.0;
}

/* The closed-form Jacobian of the short-bearing film (issue 34: every linearised law's
 * tangent against central differences to 1e-6) over eccentricities 0.05 to 0.95, whirl
 * and squeeze velocities of both signs, both films, the finite-length correction and the
 * eccentricity cap: each 2 x 2 block within 1e-6 of its largest entry of Richardson
 * central differences (steps 1e-4 of c and of the velocity scale: truncation O(h^4)). */
TEST(ocvirk_jacobian_against_central_differences)
{
    const double c = 50e-6;
    double worst = 0;
    for (int film = 0; film < 2; film++)
        for (int corr = 0; corr < 2; corr++)
            for (int cap = 0; cap < 2; cap++)
                for (int ke = 0; ke < 7; ke++)
                    for (int kv = 0; kv < 6; kv++) {
                        gd_sfd_params p = {.viscosity = 0.02,
                                           .radius = 0.025,
                                           .length = 0.02,
                                           .clearance = c,
                                           .film = film ? GD_SFD_2PI_FILM : GD_SFD_PI_FILM,
                                           .correction = corr ? 0.0 : -1.0,
                                           .max_eccentricity = cap ? 0.6 : 0.0};
                        double eps = 0.05 + 0.15 * ke, ang = 0.7 + 1.1 * ke;
                        /* with the cap at 0.6 the larger eccentricities sit beyond it */
                        double x = eps * c * cos(ang), y = eps * c * sin(ang);
                        double vang = 0.3 + 1.05 * kv, vs = 0.004 * (1 + kv);
                        double u[4] = {x, y, vs * cos(vang), vs * sin(vang)};
                        double fx, fy, jq[4], jv[4];
                        gd_sfd_force_jacobian(&p, u[0], u[1], u[2], u[3], &fx, &fy, jq, jv);
                        double f0[2];
                        gd_sfd_force(&p, u[0], u[1], u[2], u[3], &f0[0], &f0[1]);
                        CHECK_REL(fx, f0[0], 1e-12);
                        CHECK_REL(fy, f0[1], 1e-12);
                        double nq = 0, nv = 0, dq[4], dv[4];
                        for (int j = 0; j < 2; j++) {
                            double d[2];
                            film_difference(&p, u, j, 1e-4 * c, d);
                            dq[j] = d[0], dq[2 + j] = d[1];
                            film_difference(&p, u, 2 + j, 1e-4 * vs, d);
                            dv[j] = d[0], dv[2 + j] = d[1];
                        }
                        for (int m = 0; m < 4; m++) {
                            nq = fmax(nq, fabs(dq[m]));
                            nv = fmax(nv, fabs(dv[m]));
                        }
                        for (int m = 0; m < 4; m++) {
                            CHECK_ABS(jq[m], dq[m], 1e-6 * nq);
                            CHECK_ABS(jv[m], dv[m], 1e-6 * nv);
                            worst = fmax(worst,
                                         fmax(fabs(jq[m] - dq[m]) / nq, fabs(jv[m] - dv[m]) / nv));
                        }
                    }
    printf("  336 states: worst difference %.2g of the block's largest entry\n", worst);
}

/* The law's finite-length model (model: 1, the Reynolds equation by finite differences,
 * Gumbel cavitation) in the short-bearing limit: at L/D = 0.05 its force equals Ocvirk's
 * (model: 0) within 1 % of the load (the O((L/D)^2) finite-length effect and the grid:
 * 0.4 to 0.7 % for the damper in test_reynolds.c) and its eight coefficients equal the
 * short bearing's within 2 % of the largest, at eps 0.2 to 0.6 (at 0.8 the 96 points
 * around resolve the narrow film's peak to 1.7 % and 2.3 %). */
TEST(finite_model_short_bearing_limit)
{
    gd_law S, F;
    bearing(&S);
    S.value[2] = 0.0025; /* L/D 0.05 */
    F = S;
    F.value[6] = 1.0; /* model: finite */
    gd_error err;
    REQUIRE(gd_law_check(&F, &err) == GD_OK);
    const double c = 50e-6;
    for (int k = 0; k < 3; k++) {
        double e = 0.2 + 0.2 * k, ang = 0.4 + k;
        double q[4] = {e * c * cos(ang), e * c * sin(ang), 0, 0}, v[4] = {0};
        double fs[4] = {0}, ff[4] = {0}, Ks[16] = {0}, Cs[16] = {0}, Kf[16] = {0}, Cf[16] = {0};
        gd_law_point x = {0.0, q, v};
        gd_law_journal_bearing.force(&S, &x, fs, NULL, NULL);
        gd_law_journal_bearing.force(&F, &x, ff, NULL, NULL);
        double W = hypot(fs[0], fs[1]);
        CHECK_ABS(ff[0], fs[0], 0.01 * W);
        CHECK_ABS(ff[1], fs[1], 0.01 * W);
        gd_law_journal_bearing.linearize(&S, &x, Ks, Cs);
        gd_law_journal_bearing.linearize(&F, &x, Kf, Cf);
        double km = 0, cm = 0, dk = 0, dc = 0;
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                km = fmax(km, fabs(Ks[i + 4 * j]));
                cm = fmax(cm, fabs(Cs[i + 4 * j]));
                dk = fmax(dk, fabs(Kf[i + 4 * j] - Ks[i + 4 * j]));
                dc = fmax(dc, fabs(Cf[i + 4 * j] - Cs[i + 4 * j]));
            }
        CHECK(dk <= 0.02 * km);
        CHECK(dc <= 0.02 * cm);
        printf("  eps %.1f: force %.3f %%, K %.3f %%, C %.3f %% of the short bearing's largest\n",
               e, 100 * hypot(ff[0] - fs[0], ff[1] - fs[1]) / W, 100 * dk / km, 100 * dc / cm);
    }
}

/* The long-bearing end: the finite film's force at L/D = 4 and 8, extrapolated in D/L
 * (the side leakage's first-order effect: r(inf) = 2 r(8) - r(4)), equals the infinitely
 * long half-Sommerfeld bearing, F_r = -12 mu w R^3 L eps^2 / (c^2 (2 + eps^2) (1 - eps^2)),
 * F_t = 6 pi mu w R^3 L eps / (c^2 (2 + eps^2) sqrt(1 - eps^2)) (Hamrock, Fundamentals of
 * Fluid Film Lubrication, 1994, ch. 12; the full Sommerfeld film with its negative half
 * dropped, as Gumbel's model drops it), within 3 % (measured 1.2 to 2.2 %: the
 * extrapolation's second-order remainder and the 96-point grid around). */
TEST(finite_model_long_bearing_limit)
{
    const double R = 0.025, c = 50e-6, mu = 0.02, w = 500.0;
    for (int k = 0; k < 2; k++) {
        double e = 0.3 + 0.4 * k, r[2][2];
        for (int m = 0; m < 2; m++) {
            gd_law F;
            bearing(&F);
            double L = (m ? 8.0 : 4.0) * 2 * R;
            F.value[2] = L;
            F.value[6] = 1.0;
            double q[4] = {e * c, 0, 0, 0}, v[4] = {0}, f[4] = {0};
            gd_law_point x = {0.0, q, v};
            gd_law_journal_bearing.force(&F, &x, f, NULL, NULL);
            double s2 = 1 - e * e, a = mu * w * R * R * R * L / (c * c * (2 + e * e));
            r[m][0] = f[0] / (-12 * a * e * e / s2);
            r[m][1] = f[1] / (6 * M_PI * a * e / sqrt(s2));
        }
        for (int i = 0; i < 2; i++) {
            double rinf = 2 * r[1][i] - r[0][i];
            CHECK(r[0][i] < r[1][i] && r[1][i] < 1); /* the side leakage shrinks */
            CHECK_ABS(rinf, 1.0, 0.03);
            printf("  eps %.1f, %s: L/D 4 %.4f, L/D 8 %.4f of the long bearing, extrapolated "
                   "%.4f\n",
                   e, i ? "tangential" : "radial", r[0][i], r[1][i], rinf);
        }
    }
}

/* The law with a groove (model 1, land_arc > 0): its force is the land's film
 * (gd_reynolds_land_force) at the journal's position and velocity relative to the bush,
 * spinning at the journal's spin less the bush's; its Jacobians agree with central
 * differences of its force at ten times the law's step (within 1e-4 of the block's
 * largest entry: the film's own finite-difference noise); a groove without the finite
 * model, or a land of 360 deg, is refused by name. */
TEST(grooved_law_force_and_jacobian)
{
    gd_law L;
    bearing(&L);
    L.value[6] = 1.0;                /* model: finite */
    L.value[7] = 1.0;                /* cavitation: Reynolds */
    L.value[8] = 90.05 * M_PI / 180; /* land_start */
    L.value[9] = 359.9 * M_PI / 180; /* land_arc */
    L.value[10] = 0.0;               /* supply_pressure */
    L.spin[1] = 50.0;                /* the bush turning too: relative spin 450 rad/s */
    gd_error err;
    REQUIRE(gd_law_check(&L, &err) == GD_OK);
    const double c = 50e-6;
    double q[4] = {0.3 * c, -0.2 * c, 0.05 * c, 0.02 * c}, v[4] = {0.002, -0.001, 0.0005, 0};
    double f[4] = {0}, jq[4], jv[4];
    gd_law_point x = {0.0, q, v};
    gd_law_journal_bearing.force(&L, &x, f, NULL, NULL);
    gd_sfd_params p = {0.02, 0.025, 0.02, c, GD_SFD_PI_FILM, -1.0, 0};
    gd_reynolds_grid g;
    gd_reynolds_grid_init(&g);
    g.cavitation = GD_FILM_REYNOLDS;
    gd_journal_land land = {L.value[8], L.value[9], 0};
    double fx, fy;
    REQUIRE(gd_reynolds_land_force(&p, &g, &land, 450.0, q[0] - q[2], q[1] - q[3], v[0] - v[2],
                                   v[1] - v[3], &fx, &fy, &err) == GD_OK);
    CHECK_REL(f[0], fx, 1e-12);
    CHECK_REL(f[1], fy, 1e-12);
    CHECK_REL(f[2], -fx, 1e-12);
    CHECK_REL(f[3], -fy, 1e-12);
    double f0[4] = {0};
    gd_law_journal_bearing.force(&L, &x, f0, jq, jv);
    double nq = 0, nv = 0, worst = 0, dq[4], dv[4];
    /* the terms: dF/d(relative position, velocity) of the journal, 2 x 2 row-major */
    for (int j = 0; j < 2; j++) {
        for (int kind = 0; kind < 2; kind++) {
            double *u = kind ? v : q, h = kind ? 1e-4 * c * 450 : 1e-4 * c, fp[4] = {0},
                   fm[4] = {0};
            double keep = u[j];
            u[j] = keep + h;
            gd_law_journal_bearing.force(&L, &x, fp, NULL, NULL);
            u[j] = keep - h;
            gd_law_journal_bearing.force(&L, &x, fm, NULL, NULL);
            u[j] = keep;
            for (int i = 0; i < 2; i++)
                (kind ? dv : dq)[2 * i + j] = (fp[i] - fm[i]) / (2 * h);
        }
    }
    for (int m = 0; m < 4; m++) {
        nq = fmax(nq, fabs(dq[m]));
        nv = fmax(nv, fabs(dv[m]));
    }
    for (int m = 0; m < 4; m++) {
        CHECK_ABS(jq[m], dq[m], 1e-4 * nq);
        CHECK_ABS(jv[m], dv[m], 1e-4 * nv);
        worst = fmax(worst, fmax(fabs(jq[m] - dq[m]) / nq, fabs(jv[m] - dv[m]) / nv));
    }
    printf("  grooved law: Jacobians within %.2g of the block's largest entry\n", worst);
    gd_law B;
    bearing(&B);
    B.value[9] = 1.0; /* a groove on the short bearing */
    CHECK(gd_law_check(&B, &err) != GD_OK);
    B.value[6] = 1.0, B.value[9] = 2 * M_PI;
    CHECK(gd_law_check(&B, &err) != GD_OK);
}

RUN_TESTS(T(ocvirk_static_forces_and_attitude), T(no_relative_spin_no_wedge),
          T(linearised_coefficients_against_short_bearing),
          T(ocvirk_jacobian_against_central_differences), T(finite_model_short_bearing_limit),
          T(finite_model_long_bearing_limit), T(grooved_law_force_and_jacobian))
