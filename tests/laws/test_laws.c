/* Element laws for time integration: backlash, squeeze film damper (against quadrature
 * of the short-bearing Reynolds pressure and the classical closed forms), cam torque,
 * tables, load and prescribed-motion laws. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/laws.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ------------------------------------------------------------------ backlash */

TEST(backlash_branches)
{
    gd_backlash_params p = {
        .b = 1e-5, .k_drive = 1e8, .k_coast = 2e8, .c_drive = 100, .c_coast = 150, .c_free = 1};
    gd_contact s;
    CHECK_REL(gd_backlash_force_auto(&p, 3e-5, 0.2, &s), 1e8 * 2e-5 + 100 * 0.2, 1e-14);
    CHECK(s == GD_CONTACT_DRIVE);
    CHECK_REL(gd_backlash_force_auto(&p, 4e-6, 0.2, &s), 1 * 0.2, 1e-14);
    CHECK(s == GD_CONTACT_SEPARATED);
    CHECK_REL(gd_backlash_force_auto(&p, -4e-5, -0.3, &s), 2e8 * (-3e-5) + 150 * (-0.3), 1e-14);
    CHECK(s == GD_CONTACT_COAST);
    /* boundaries belong to the separated state */
    CHECK(gd_backlash_state(1e-5, 1e-5) == GD_CONTACT_SEPARATED);
    CHECK(gd_backlash_state(-1e-5, 1e-5) == GD_CONTACT_SEPARATED);
    CHECK(gd_backlash_state(1.0000001e-5, 1e-5) == GD_CONTACT_DRIVE);
    /* frozen state: the drive branch continued below b pulls (negative) */
    CHECK_REL(gd_backlash_force(&p, GD_CONTACT_DRIVE, 0.0, 0.0), -1e8 * 1e-5, 1e-14);
}

TEST(backlash_elastic_force_continuous)
{
    gd_backlash_params p = {
        .b = 2e-5, .k_drive = 3e8, .k_coast = 1e8, .c_drive = 0, .c_coast = 0, .c_free = 0};
    /* the elastic force goes to zero at both flanks from either side */
    for (int side = -1; side <= 1; side += 2) {
        for (double h = 1e-7; h > 1e-13; h /= 10) {
            double in = gd_backlash_force_auto(&p, side * (p.b - h), 0.0, NULL);
            double out = gd_backlash_force_auto(&p, side * (p.b + h), 0.0, NULL);
            CHECK_ABS(in, 0.0, 0.0);
            double k = side > 0 ? p.k_drive : p.k_coast;
            CHECK_REL(out, side * k * h, 1e-6);
        }
    }
    /* without backlash and equal flanks it is the linear spring */
    gd_backlash_params l = {
        .b = 0, .k_drive = 2e8, .k_coast = 2e8, .c_drive = 50, .c_coast = 50, .c_free = 0};
    for (double d = -3e-5; d <= 3e-5; d += 1e-5)
        CHECK_REL(gd_backlash_force_auto(&l, d, 0.01, NULL), 2e8 * d + 0.5, 1e-12);
}

TEST(mesh_damping_laws)
{
    CHECK_REL(gd_mesh_damping(200, 0, 3e8), 200, 0);
    CHECK_REL(gd_mesh_damping(0, 1e-6, 3e8), 300, 1e-15);
    CHECK_REL(gd_mesh_damping(20, 1e-6, 2e8), 220, 1e-15);
}

/* ------------------------------------------------------------------ SFD */

/* Forces by direct quadrature of the short-bearing pressure
 * p = 6 mu h_t (z^2 - L^2/4) / h^3 over the land, pressure set to zero where negative
 * for the pi film; h = c - x cos a - y sin a at the housing angle a. */
static void sfd_quadrature(const gd_sfd_params *P, double x, double y, double vx, double vy,
                           double *fx, double *fy)
{
    const int N = 200000;
    const double gz[3] = {-sqrt(0.6), 0.0, sqrt(0.6)}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    double sx = 0, sy = 0, L = P->length, mu = P->viscosity, c = P->clearance;
    for (int k = 0; k < N; k++) {
        double a = (k + 0.5) * 2.0 * M_PI / N, ca = cos(a), sa = sin(a);
        double h = c - x * ca - y * sa, ht = -(vx * ca + vy * sa);
        double pz = 0;
        for (int g = 0; g < 3; g++) {
            double z = 0.5 * L * gz[g];
            double p = 6.0 * mu * ht * (z * z - 0.25 * L * L) / (h * h * h);
            if (P->film == GD_SFD_PI_FILM && p < 0) p = 0;
            pz += 0.5 * L * gw[g] * p;
        }
        sx -= pz * ca;
        sy -= pz * sa;
    }
    *fx = sx * P->radius * 2.0 * M_PI / N;
    *fy = sy * P->radius * 2.0 * M_PI / N;
}

static gd_sfd_params chen_sfd(gd_sfd_film film)
{
    /* [Chen1998] Appendix II (DESIGN.md): mu 6.895e-3 Pa s, D 35.56 mm, L 17.145 mm, C 76.2 um */
    gd_sfd_params p = {.viscosity = 6.895e-3,
                       .radius = 0.5 * 35.56e-3,
                       .length = 17.145e-3,
                       .clearance = 76.2e-6,
                       .film = film,
                       .correction = -1,
                       .max_eccentricity = 0.999};
    return p;
}

TEST(sfd_against_quadrature)
{
    const double eps[] = {0.05, 0.3, 0.6, 0.85, 0.95};
    const double phi[] = {0.3, 2.2, -1.9, 4.0, 0.0};
    /* (e', e phi') in m/s: pure squeeze, pure whirl, mixed of both signs */
    const double vel[][2] = {{0.01, 0.0}, {0.0, 0.02}, {-0.013, 0.007}, {0.004, -0.03}};
    double worst = 0;
    for (int film = 0; film < 2; film++) {
        gd_sfd_params P = chen_sfd(film ? GD_SFD_2PI_FILM : GD_SFD_PI_FILM);
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 4; j++) {
                double e = eps[i] * P.clearance, cp = cos(phi[i]), sp = sin(phi[i]);
                double x = e * cp, y = e * sp;
                double vx = vel[j][0] * cp - vel[j][1] * sp, vy = vel[j][0] * sp + vel[j][1] * cp;
                double fx, fy, qx, qy;
                gd_sfd_force(&P, x, y, vx, vy, &fx, &fy);
                sfd_quadrature(&P, x, y, vx, vy, &qx, &qy);
                double scale = hypot(qx, qy);
                double rel = hypot(fx - qx, fy - qy) / scale;
                if (rel > worst) worst = rel;
                CHECK(rel < 1e-6);
            }
    }
    printf("     SFD closed form vs quadrature: worst relative error %.2e\n", worst);
}

TEST(sfd_classical_circular_orbit)
{
    /* circular centred orbit (e' = 0, phi' = w): textbook short-damper forces */
    for (int i = 0; i < 4; i++) {
        double ep = 0.2 + 0.2 * i, w = 300.0;
        gd_sfd_params P = chen_sfd(GD_SFD_2PI_FILM);
        double k = P.viscosity * P.radius * pow(P.length, 3) / (P.clearance * P.clearance);
        double s2 = 1 - ep * ep;
        double fr, ft;
        gd_sfd_force_polar(&P, ep * P.clearance, 0.0, w, &fr, &ft);
        CHECK_ABS(fr, 0.0, 1e-12 * fabs(ft));
        CHECK_REL(ft, -M_PI * k * ep * w / pow(s2, 1.5), 1e-12);
        P.film = GD_SFD_PI_FILM;
        gd_sfd_force_polar(&P, ep * P.clearance, 0.0, w, &fr, &ft);
        CHECK_REL(fr, -2.0 * k * ep * ep * w / (s2 * s2), 1e-12);
        CHECK_REL(ft, -0.5 * M_PI * k * ep * w / pow(s2, 1.5), 1e-12);
        /* pure radial squeeze, full film: F_r = -k e'/c pi (1 + 2 eps^2) / s^5 */
        P.film = GD_SFD_2PI_FILM;
        double ed = 0.01;
        gd_sfd_force_polar(&P, ep * P.clearance, ed, 0.0, &fr, &ft);
        CHECK_REL(fr, -k * ed / P.clearance * M_PI * (1 + 2 * ep * ep) / pow(s2, 2.5), 1e-12);
        CHECK_ABS(ft, 0.0, 1e-12 * fabs(fr));
    }
    /* centred journal: linear damping pi mu R L^3 / c^3 (2pi) and half of it (pi) */
    gd_sfd_params P = chen_sfd(GD_SFD_2PI_FILM);
    double c0 = M_PI * P.viscosity * P.radius * pow(P.length, 3) / pow(P.clearance, 3);
    double fx, fy;
    gd_sfd_force(&P, 0, 0, 0.01, -0.02, &fx, &fy);
    CHECK_REL(fx, -c0 * 0.01, 1e-6);
    CHECK_REL(fy, c0 * 0.02, 1e-6);
    P.film = GD_SFD_PI_FILM;
    gd_sfd_force(&P, 0, 0, 0.01, -0.02, &fx, &fy);
    CHECK_REL(fx, -0.5 * c0 * 0.01, 1e-6);
    CHECK_REL(fy, 0.5 * c0 * 0.02, 1e-6);
}

TEST(sfd_integrals_any_interval)
{
    /* closed forms against Simpson's rule on intervals crossing pi and 2 pi */
    const double iv[][2] = {{0.3, 2.9}, {2.0, 5.5}, {-1.0, 4.0}, {4.0, 11.0}, {-7.0, -0.5}};
    for (int e = 0; e < 3; e++) {
        double eps = 0.1 + 0.4 * e;
        for (int k = 0; k < 5; k++) {
            double j[3], q[3] = {0, 0, 0};
            gd_sfd_integrals(eps, iv[k][0], iv[k][1], j);
            const int N = 20000;
            double h = (iv[k][1] - iv[k][0]) / N;
            for (int i = 0; i <= N; i++) {
                double t = iv[k][0] + i * h, w = (i == 0 || i == N) ? 1 : (i % 2 ? 4 : 2);
                double u = 1 + eps * cos(t), u3 = u * u * u;
                q[0] += w * cos(t) * cos(t) / u3;
                q[1] += w * sin(t) * cos(t) / u3;
                q[2] += w * sin(t) * sin(t) / u3;
            }
            for (int m = 0; m < 3; m++)
                CHECK_ABS(j[m], q[m] * h / 3, 1e-9 * (1 + fabs(q[m] * h / 3)));
        }
    }
}

TEST(sfd_finite_length_correction)
{
    /* eta = finite/short force at small eccentricity: the axial profile
     * 1 - cosh(z/R)/cosh(L/2R) of P'' - P/R^2 = S integrated, against the parabola */
    const double ld[] = {0.1, 0.25, 0.482, 1.0};
    for (int i = 0; i < 4; i++) {
        double R = 1.0, L = 2.0 * R * ld[i];
        const int N = 100000;
        double fin = 0, sh = 0, h = L / N;
        for (int k = 0; k < N; k++) {
            double z = -0.5 * L + (k + 0.5) * h;
            fin += -R * R * (1.0 - cosh(z / R) / cosh(0.5 * L / R)) * h; /* S = 1 */
            sh += 0.5 * (z * z - 0.25 * L * L) * h;
        }
        CHECK_REL(gd_sfd_correction_factor(ld[i]), fin / sh, 1e-8);
    }
    CHECK_REL(gd_sfd_correction_factor(1e-4), 1.0, 1e-8);
    CHECK(gd_sfd_correction_factor(0.482) < 0.92 && gd_sfd_correction_factor(0.482) > 0.90);
    /* applied as a factor */
    gd_sfd_params P = chen_sfd(GD_SFD_PI_FILM), Q = P;
    Q.correction = 0;
    double f1, f2, g1, g2;
    gd_sfd_force(&P, 2e-5, 1e-5, 0.01, 0.02, &f1, &f2);
    gd_sfd_force(&Q, 2e-5, 1e-5, 0.01, 0.02, &g1, &g2);
    double eta = gd_sfd_correction_factor(P.length / (2 * P.radius));
    CHECK_REL(g1, eta * f1, 1e-14);
    CHECK_REL(g2, eta * f2, 1e-14);
}

/* ------------------------------------------------------------------ tables */

TEST(table_linear_periodic)
{
    double x[4] = {0.0, 1.0, 2.5, 3.0}, y[4] = {1.0, 3.0, 0.0, 2.0};
    gd_table *t;
    gd_error err;
    REQUIRE(gd_table_new(4, x, y, 4.0, GD_INTERP_LINEAR, &t, &err) == GD_OK);
    double d;
    CHECK_REL(gd_table_eval(t, 0.5, &d, NULL), 2.0, 1e-15);
    CHECK_REL(d, 2.0, 1e-15);
    CHECK_REL(gd_table_eval(t, 2.0, NULL, NULL), 1.0, 1e-15);
    /* closing interval 3 -> 4 (= 0): 2 -> 1 */
    CHECK_REL(gd_table_eval(t, 3.5, &d, NULL), 1.5, 1e-15);
    CHECK_REL(d, -1.0, 1e-15);
    /* wrap-around in both directions */
    CHECK_REL(gd_table_eval(t, 0.5 + 4.0 * 7, NULL, NULL), 2.0, 1e-12);
    CHECK_REL(gd_table_eval(t, 3.5 - 4.0 * 3, NULL, NULL), 1.5, 1e-12);
    gd_table_free(t);
    /* errors */
    double bad[3] = {0, 2, 1};
    CHECK(gd_table_new(3, bad, y, 0, GD_INTERP_LINEAR, &t, &err) == GD_EINPUT);
    CHECK(gd_table_new(4, x, y, 3.0, GD_INTERP_LINEAR, &t, &err) == GD_EINPUT);
    CHECK(gd_table_new(2, x, y, 0, GD_INTERP_SPLINE, &t, &err) == GD_EINPUT);
}

/* A non-finite argument (an angle t / w at a speed of 5.3e-312 rad/s) has no interval:
 * NaN out, never a NaN or inf converted to an index (undefined behaviour, caught by the
 * sanitizer build's -fsanitize=float-cast-overflow). Issue 23. */
TEST(table_non_finite_argument)
{
    double x[4] = {0.0, 1.0, 2.0, 3.0}, y[4] = {1.0, 3.0, 0.0, 2.0};
    const double period[2] = {4.0, 0.0}, arg[3] = {NAN, INFINITY, -INFINITY};
    for (int p = 0; p < 2; p++)
        for (int it = 0; it < 2; it++) {
            gd_table *t;
            gd_error err;
            REQUIRE(gd_table_new(4, x, y, period[p], it ? GD_INTERP_SPLINE : GD_INTERP_LINEAR, &t,
                                 &err) == GD_OK);
            for (int a = 0; a < 3; a++) {
                double d = 0.0, d2 = 0.0;
                double v = gd_table_eval(t, arg[a], &d, &d2);
                /* periodic: no value at all; a table continued linearly by its end
                 * slopes keeps the sign of inf */
                if (p == 0 || a == 0)
                    CHECK(isnan(v) && isnan(d));
                else
                    CHECK(isinf(v) || isnan(v));
            }
            CHECK_REL(gd_table_eval(t, 1.0, NULL, NULL), 3.0, 1e-15);
            gd_table_free(t);
        }
}

TEST(table_periodic_spline)
{
    enum { N = 64 };
    double x[N], y[N], xn[N];
    for (int i = 0; i < N; i++) {
        x[i] = i * 2 * M_PI / N;
        y[i] = sin(x[i]) + 0.3 * cos(2 * x[i]);
        /* a non-uniform grid of the same function */
        xn[i] = x[i] + 0.02 * sin(3 * x[i]);
    }
    gd_table *t, *tn;
    gd_error err;
    REQUIRE(gd_table_new(N, x, y, 2 * M_PI, GD_INTERP_SPLINE, &t, &err) == GD_OK);
    CHECK(t->uniform > 0);
    double yn[N];
    for (int i = 0; i < N; i++)
        yn[i] = sin(xn[i]) + 0.3 * cos(2 * xn[i]);
    REQUIRE(gd_table_new(N, xn, yn, 2 * M_PI, GD_INTERP_SPLINE, &tn, &err) == GD_OK);
    CHECK(tn->uniform == 0);
    double e0 = 0, e1 = 0, e2 = 0;
    for (int k = 0; k < 997; k++) {
        double s = -3 + k * 0.0191, d1, d2;
        double v = gd_table_eval(t, s, &d1, &d2);
        e0 = fmax(e0, fabs(v - (sin(s) + 0.3 * cos(2 * s))));
        e1 = fmax(e1, fabs(d1 - (cos(s) - 0.6 * sin(2 * s))));
        e2 = fmax(e2, fabs(d2 - (-sin(s) - 1.2 * cos(2 * s))));
        double vn = gd_table_eval(tn, s, NULL, NULL);
        CHECK_ABS(vn, sin(s) + 0.3 * cos(2 * s), 2e-5);
    }
    CHECK(e0 < 5e-6);
    CHECK(e1 < 2e-4);
    CHECK(e2 < 2e-2);
    /* smooth across the wrap point: value, slope and curvature continuous */
    double a1, a2, b1, b2;
    double a0 = gd_table_eval(t, 2 * M_PI - 1e-9, &a1, &a2);
    double b0 = gd_table_eval(t, 2 * M_PI + 1e-9, &b1, &b2);
    CHECK_ABS(a0, b0, 1e-8);
    CHECK_ABS(a1, b1, 1e-7);
    CHECK_ABS(a2, b2, 1e-6);
    gd_table_free(t);
    gd_table_free(tn);
}

TEST(table_not_periodic)
{
    /* an angle-vs-time table: natural spline inside, linear continuation outside */
    double x[5] = {0, 0.1, 0.2, 0.3, 0.4}, y[5];
    for (int i = 0; i < 5; i++)
        y[i] = 100 * x[i];
    gd_table *t;
    gd_error err;
    REQUIRE(gd_table_new(5, x, y, 0, GD_INTERP_SPLINE, &t, &err) == GD_OK);
    double d1, d2;
    CHECK_REL(gd_table_eval(t, 0.25, &d1, &d2), 25.0, 1e-13);
    CHECK_REL(d1, 100.0, 1e-13);
    CHECK_ABS(d2, 0.0, 1e-9);
    CHECK_REL(gd_table_eval(t, 0.5, &d1, &d2), 50.0, 1e-13);
    CHECK_REL(gd_table_eval(t, -0.1, &d1, &d2), -10.0, 1e-13);
    CHECK_REL(d1, 100.0, 1e-13);
    gd_table_free(t);
}

TEST(table_from_tvms_result)
{
    /* a hand-made result: two cycles, the first one is used */
    double ang[8], k[8];
    for (int i = 0; i < 8; i++) {
        ang[i] = i * 0.25;
        k[i] = 3e8 + 1e8 * (i % 4 == 1);
    }
    gd_tvms_result r = {0};
    r.points = 4;
    r.n = 8;
    r.angle_rad = ang;
    r.stiffness = k;
    r.mesh_period_rad = 1.0;
    gd_table *t;
    gd_error err;
    REQUIRE(gd_table_from_tvms(&r, GD_INTERP_LINEAR, &t, &err) == GD_OK);
    CHECK_REL(gd_table_eval(t, 0.25, NULL, NULL), 4e8, 1e-15);
    CHECK_REL(gd_table_eval(t, 1.125, NULL, NULL), 3.5e8, 1e-15);
    CHECK_REL(gd_table_eval(t, 0.875, NULL, NULL), 3e8, 1e-15);
    gd_table_free(t);
}

/* ------------------------------------------------------------------ cams */

TEST(cam_torque_harmonic_law)
{
    /* s = 4 mm - 3 mm cos(th) + 1 mm sin(2 th) by hand */
    gd_lift_law law = {.kind = GD_LIFT_HARMONIC};
    law.harmonic.mean = 4e-3;
    law.harmonic.order = 1;
    law.harmonic.n = 2;
    law.harmonic.cos_amp[0] = -3e-3;
    law.harmonic.sin_amp[1] = 1e-3;
    double m = 0.12, ph = 0.7, W = 523.6, Wd = 1500.0;
    for (int i = 0; i < 12; i++) {
        double th = -2 + 0.61 * i, u = th - ph;
        double s1 = 3e-3 * sin(u) + 2e-3 * cos(2 * u);
        double s2 = 3e-3 * cos(u) - 4e-3 * sin(2 * u);
        double T = m * s1 * (s2 * W * W + s1 * Wd);
        CHECK_REL(gd_cam_torque(&law, m, ph, th, W, Wd), T, 1e-12);
        double s, d1, d2;
        s = gd_lift_eval(&law, u, &d1, &d2);
        CHECK_REL(s, 4e-3 - 3e-3 * cos(u) + 1e-3 * sin(2 * u), 1e-13);
    }
    /* the same lift as a periodic spline table of 720 samples */
    enum { N = 720 };
    double x[N], y[N];
    for (int i = 0; i < N; i++) {
        x[i] = i * 2 * M_PI / N;
        y[i] = gd_lift_eval(&law, x[i], NULL, NULL);
    }
    gd_table *t;
    gd_error err;
    REQUIRE(gd_table_new(N, x, y, 2 * M_PI, GD_INTERP_SPLINE, &t, &err) == GD_OK);
    gd_lift_law tab = {.kind = GD_LIFT_TABLE, .table = t};
    double tmax = m * 7e-3 * 11e-3 * W * W;
    for (int i = 0; i < 50; i++) {
        double th = 0.1257 * i;
        CHECK_ABS(gd_cam_torque(&tab, m, ph, th, W, 0), gd_cam_torque(&law, m, ph, th, W, 0),
                  1e-4 * tmax);
    }
    gd_table_free(t);
}

/* ------------------------------------------------------------------ loads, motion */

TEST(load_and_prescribed_laws)
{
    gd_load_law c = {.kind = GD_LOAD_CONSTANT, .mean = 12};
    CHECK_REL(gd_load_eval(&c, 3, 4), 12, 0);
    gd_load_law h = {
        .kind = GD_LOAD_HARMONIC_TIME, .mean = 1, .amplitude = 2, .frequency = 10, .phase = 0.5};
    CHECK_REL(gd_load_eval(&h, 0.3, 99), 1 + 2 * cos(3.5), 1e-15);
    gd_load_law a = {.kind = GD_LOAD_HARMONIC_ANGLE, .amplitude = 2, .frequency = 3};
    CHECK_REL(gd_load_eval(&a, 99, 0.4), 2 * cos(1.2), 1e-15);
    double x[3] = {0, 1, 2}, y[3] = {5, 7, 6};
    gd_table *t;
    gd_error err;
    REQUIRE(gd_table_new(3, x, y, 3, GD_INTERP_LINEAR, &t, &err) == GD_OK);
    gd_load_law tl = {.kind = GD_LOAD_TABLE_ANGLE, .mean = 1, .table = t, .phase = 0.5};
    CHECK_REL(gd_load_eval(&tl, 0, 3.0), 1 + 6.0, 1e-15); /* angle 3.5 -> 0.5 */
    gd_table_free(t);

    double q, qd, qdd;
    gd_prescribed_law p0 = {.kind = GD_PRESCRIBED_NOMINAL};
    gd_prescribed_eval(&p0, 2, 100, &q, &qd, &qdd);
    CHECK(q == 0 && qd == 0 && qdd == 0);
    gd_prescribed_law ps = {.kind = GD_PRESCRIBED_SPEED, .speed = 110};
    gd_prescribed_eval(&ps, 2, 100, &q, &qd, &qdd);
    CHECK_REL(q, 20, 1e-15);
    CHECK_REL(qd, 10, 1e-15);
    gd_prescribed_law ph = {
        .kind = GD_PRESCRIBED_HARMONIC, .amplitude = 1e-3, .frequency = 50, .phase = 0.2};
    gd_prescribed_eval(&ph, 0.01, 0, &q, &qd, &qdd);
    CHECK_REL(q, 1e-3 * cos(0.7), 1e-14);
    CHECK_REL(qd, -0.05 * sin(0.7), 1e-14);
    CHECK_REL(qdd, -2.5 * cos(0.7), 1e-14);
    double tt[4] = {0, 0.01, 0.02, 0.03}, an[4] = {0, 1.0, 2.0, 3.0};
    REQUIRE(gd_table_new(4, tt, an, 0, GD_INTERP_LINEAR, &t, &err) == GD_OK);
    gd_prescribed_law pt = {.kind = GD_PRESCRIBED_TABLE, .table = t};
    gd_prescribed_eval(&pt, 0.015, 90, &q, &qd, &qdd);
    CHECK_REL(q, 1.5 - 90 * 0.015, 1e-13);
    CHECK_REL(qd, 100 - 90, 1e-12);
    gd_table_free(t);
}

RUN_TESTS(T(backlash_branches), T(backlash_elastic_force_continuous), T(mesh_damping_laws),
          T(sfd_against_quadrature), T(sfd_classical_circular_orbit), T(sfd_integrals_any_interval),
          T(sfd_finite_length_correction), T(table_linear_periodic), T(table_non_finite_argument),
          T(table_periodic_spline), T(table_not_periodic), T(table_from_tvms_result),
          T(cam_torque_harmonic_law), T(load_and_prescribed_laws))
