/* Per-period statistics and the Poincare verdict (src/signal/cycle_stats.c, poincare.c)
 * on sequences whose answer is known: sines of known amplitude per period; a fixed point,
 * a 2-cycle, the logistic map's 4-cycle; a rotation on a deformed circle (quasi-periodic);
 * the Henon and logistic chaos, pseudo-random points and a slow spiral (irregular). */
#include <math.h>
#include <stdlib.h>

#include "geardyn/cycles.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* a_j sin(2 pi t / T) in period j, a_j = 1 + 0.01 j: period j's peak-to-peak is 2 a_j
 * (the samples hit the crests), mean 0, RMS a_j / sqrt 2 (trapezoid exact on a period) */
static double *ramp_sine(int np, int m, double T, double t0)
{
    int n = np * m + 1;
    double *x = malloc((size_t)n * sizeof *x), dt = T / m;
    for (int i = 0; i < n; i++) {
        double t = t0 + i * dt;
        int j = i / m < np ? i / m : np - 1;
        x[i] = (1 + 0.01 * j) * sin(2 * M_PI * (t - t0) / T);
    }
    return x;
}

TEST(stats_known_bands)
{
    int np = 101, m = 64;
    double T = 0.012, t0 = 0.3;
    double *x = ramp_sine(np, m, T, t0);
    gd_cycle_stats s;
    gd_error err;
    REQUIRE(gd_cycle_stats_compute(x, np * m + 1, t0, T / m, T, t0, &s, &err) == GD_OK);
    CHECK(s.periods == 101);
    CHECK(s.min_samples == 65);
    /* 2 (1 + 0.01 j), j = 0..100: median j = 50, 5 % at j = 5, 95 % at j = 95; the
     * crest samples are exact to rounding */
    CHECK_REL(s.peak_to_peak.median, 3.0, 1e-12);
    CHECK_REL(s.peak_to_peak.p05, 2.1, 1e-12);
    CHECK_REL(s.peak_to_peak.p95, 3.9, 1e-12);
    CHECK_REL(s.peak_to_peak.min, 2.0, 1e-12);
    CHECK_REL(s.peak_to_peak.max, 4.0, 1e-12);
    CHECK_REL(s.rms.median, 1.5 / sqrt(2), 1e-12);
    CHECK_ABS(s.mean.max, 0.0, 1e-13); /* rounding of 65 terms of size 1 */
    CHECK_ABS(s.mean.min, 0.0, 1e-13);
    /* from half a period in: 100 whole periods, each half of two ramps' periods: the
     * crests of 2 (1 + 0.01 j) and then of the next */
    REQUIRE(gd_cycle_stats_compute(x, np * m + 1, t0, T / m, T, t0 + T / 2, &s, &err) == GD_OK);
    CHECK(s.periods == 100);
    CHECK_REL(s.peak_to_peak.min, 1.0 + 1.01, 1e-12);
    /* from before the first sample: the first whole period starts on the grid ahead */
    REQUIRE(gd_cycle_stats_compute(x, np * m + 1, t0, T / m, T, t0 - 0.3 * T, &s, &err) == GD_OK);
    CHECK(s.periods == 100);
    free(x);
}

/* An unaligned grid: 40.5 samples per period of sin, p-p within the sampling error
 * 1 - cos(pi / 40.5) = 3e-3 of the true 2. */
TEST(stats_unaligned)
{
    double T = 1.0, dt = T / 40.5;
    int n = 4051;
    double *x = malloc((size_t)n * sizeof *x);
    for (int i = 0; i < n; i++)
        x[i] = 2.0 + sin(2 * M_PI * i * dt / T);
    gd_cycle_stats s;
    gd_error err;
    REQUIRE(gd_cycle_stats_compute(x, n, 0.0, dt, T, 0.0, &s, &err) == GD_OK);
    CHECK(s.periods == 100);
    CHECK(s.min_samples == 40 || s.min_samples == 41);
    CHECK(s.peak_to_peak.max <= 2.0 + 1e-12);
    CHECK(s.peak_to_peak.min >= 2.0 * cos(M_PI / 40.5) - 1e-12);
    CHECK_REL(s.mean.median, 2.0, 2e-2); /* trapezoid over the samples inside the period */
    free(x);
}

TEST(stats_errors)
{
    double x[8] = {0, 1, 2, 3, 4, 5, 6, NAN};
    gd_cycle_stats s;
    gd_error err;
    CHECK(gd_cycle_stats_compute(x, 1, 0, 1, 2, 0, &s, &err) == GD_EINPUT);
    CHECK(gd_cycle_stats_compute(x, 7, 0, 0, 2, 0, &s, &err) == GD_EINPUT);
    CHECK(gd_cycle_stats_compute(x, 7, 0, 1, -2, 0, &s, &err) == GD_EINPUT);
    CHECK(gd_cycle_stats_compute(x, 7, 0, 1, 10, 0, &s, &err) == GD_EINPUT);  /* no period */
    CHECK(gd_cycle_stats_compute(x, 7, 0, 1, 1.5, 0, &s, &err) == GD_EINPUT); /* 2 samples */
    CHECK(gd_cycle_stats_compute(x, 8, 0, 1, 2, 0, &s, &err) == GD_EINPUT);   /* NaN */
    CHECK(gd_cycle_stats_compute(x, 7, 0, 1, 2, 0, &s, &err) == GD_OK);
    CHECK(s.periods == 3 && s.peak_to_peak.median == 2.0);
}

static gd_poincare_verdict classify(const double *v, int nrec, int n)
{
    double scale[4] = {1, 1, 1, 1};
    gd_poincare_verdict r;
    gd_error err;
    if (gd_poincare_classify(v, nrec, n, scale, NULL, &r, &err)) r.cls = -1;
    return r;
}

TEST(verdict_periodic)
{
    enum { N = 64 };
    double v[2 * N];
    for (int k = 0; k < N; k++) {
        v[k] = 0.3 + 4e-4 * ((k * 37) % 11) / 11.0; /* scatter below 1e-3 */
        v[N + k] = k % 2 ? 0.7 : -0.2;
    }
    gd_poincare_verdict r = classify(v, 1, N);
    char name[32];
    CHECK(r.cls == GD_POINCARE_PERIODIC && r.period == 1 && r.distinct == 1);
    gd_poincare_verdict_name(&r, name, sizeof name);
    CHECK_STR(name, "periodic");
    r = classify(v, 2, N); /* with the 2-cycle record */
    CHECK(r.cls == GD_POINCARE_PERIODIC && r.period == 2 && r.distinct == 2);
    gd_poincare_verdict_name(&r, name, sizeof name);
    CHECK_STR(name, "period-2");
    /* the logistic map x' = 3.5 x (1 - x) settles on its 4-cycle */
    double x = 0.2;
    for (int k = 0; k < 2000; k++)
        x = 3.5 * x * (1 - x);
    for (int k = 0; k < N; k++)
        v[k] = x = 3.5 * x * (1 - x);
    r = classify(v, 1, N);
    CHECK(r.cls == GD_POINCARE_PERIODIC && r.period == 4 && r.distinct == 4);
    CHECK(r.return_shift == 0); /* the torus test is not run */
}

/* A rotation by the golden mean on a deformed circle, with a non-uniform parametrisation:
 * the close returns are at Fibonacci shifts. */
TEST(verdict_quasi_periodic)
{
    enum { N = 200 };
    double v[2 * N], rho = (sqrt(5.0) - 1) / 2;
    for (int k = 0; k < N; k++) {
        double u = fmod(k * rho, 1.0), th = 2 * M_PI * (u + 0.08 * sin(2 * M_PI * u));
        v[k] = cos(th) + 0.3 * cos(2 * th);
        v[N + k] = 0.5 * sin(th);
    }
    gd_poincare_verdict r = classify(v, 2, N);
    CHECK(r.cls == GD_POINCARE_QUASI_PERIODIC);
    CHECK(r.period == 0 && r.distinct == N);
    CHECK(r.return_shift == 89); /* |89 rho - 55| = 5.6e-3, the best q <= 100 */
    CHECK(r.return_distance < 0.05);
    CHECK(r.halves_distance < 0.05);
    char name[32];
    gd_poincare_verdict_name(&r, name, sizeof name);
    CHECK_STR(name, "quasi-periodic");
    /* too few points for the test: irregular, the test not run */
    r = classify(v, 2, 20);
    CHECK(r.cls == GD_POINCARE_IRREGULAR && r.return_shift == 0);
}

TEST(verdict_irregular)
{
    enum { N = 200 };
    double v[2 * N];
    /* Henon map (a 1.4, b 0.3): chaotic on a fractal attractor */
    double x = 0.1, y = 0.1;
    for (int k = 0; k < 1000 + N; k++) {
        double xn = 1 - 1.4 * x * x + y;
        y = 0.3 * x;
        x = xn;
        if (k >= 1000) {
            v[k - 1000] = x;
            v[N + k - 1000] = y;
        }
    }
    gd_poincare_verdict r = classify(v, 2, N);
    CHECK(r.cls == GD_POINCARE_IRREGULAR);
    CHECK(r.return_distance > 0.5); /* close returns only at some points */
    /* logistic map at 4 */
    x = 0.123;
    for (int k = 0; k < N; k++)
        v[k] = x = 4 * x * (1 - x);
    r = classify(v, 1, N);
    CHECK(r.cls == GD_POINCARE_IRREGULAR && r.return_distance > 0.5);
    /* pseudo-random points */
    unsigned s = 12345;
    for (int k = 0; k < 2 * N; k++) {
        s = s * 1103515245u + 12345u;
        v[k] = (s >> 8) / 16777216.0;
    }
    r = classify(v, 2, N);
    CHECK(r.cls == GD_POINCARE_IRREGULAR && r.return_distance > 0.5);
    /* a slow spiral onto a fixed point (multipliers 0.98 e^{+-0.5i}): every point returns
     * near, but the halves do not cover each other: not settled */
    for (int k = 0; k < N; k++) {
        v[k] = pow(0.985, k) * cos(0.5 * k);
        v[N + k] = pow(0.985, k) * sin(0.5 * k);
    }
    r = classify(v, 2, N);
    CHECK(r.cls == GD_POINCARE_IRREGULAR);
    CHECK(r.halves_distance > 0.2);
}

TEST(verdict_errors)
{
    double v[4] = {1, 2, NAN, 4}, scale[2] = {1, 1};
    gd_poincare_verdict r;
    gd_error err;
    gd_poincare_options o;
    gd_poincare_options_init(&o);
    CHECK(o.tol == 1e-3 && o.torus_tol == 0.2 && o.min_points == 32);
    CHECK(gd_poincare_classify(v, 1, 0, scale, &o, &r, &err) == GD_EINPUT);
    CHECK(gd_poincare_classify(v, 0, 2, scale, &o, &r, &err) == GD_EINPUT);
    CHECK(gd_poincare_classify(v, 2, 2, scale, &o, &r, &err) == GD_EINPUT); /* NaN */
    o.tol = 0;
    CHECK(gd_poincare_classify(v, 1, 2, scale, &o, &r, &err) == GD_EINPUT);
    CHECK(gd_poincare_classify(v, 1, 2, scale, NULL, &r, &err) == GD_OK);
    CHECK(r.cls == GD_POINCARE_IRREGULAR && r.distinct == 2); /* 1 != 2, too few to test */
}

RUN_TESTS(T(stats_known_bands), T(stats_unaligned), T(stats_errors), T(verdict_periodic),
          T(verdict_quasi_periodic), T(verdict_irregular), T(verdict_errors))
