/* Floquet multipliers without the dense monodromy (periodic.h, floquet = GD_FLOQUET_KRYLOV;
 * src/periodic/floquet/floquet_krylov.c): the multipliers from monodromy-vector products equal
 * the dense Magnus monodromy's over the same steps, on the Mathieu pair (two states: the
 * monodromy's columns from the products) and the Chen SFD pair (twelve states, the four
 * and the eight largest by Krylov-Schur), and the Mathieu tongue's stability and period
 * doubling come out the same by both. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model_file.h"
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "floquet_support.h"
#include "model_support.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The largest distance from each Krylov multiplier to the nearest dense one, and whether
 * the Krylov ones are the largest (none of the dense ones left out is larger than the
 * smallest Krylov one, within tol). */
static double worst_distance(const gd_periodic_point *d, const gd_periodic_point *k, int *largest)
{
    double worst = 0.0, kmin = INFINITY;
    for (int a = 0; a < k->nmult; a++) {
        double best = INFINITY;
        for (int b = 0; b < d->nmult; b++) {
            double e = hypot(k->mu_re[a] - d->mu_re[b], k->mu_im[a] - d->mu_im[b]);
            best = e < best ? e : best;
        }
        worst = best > worst ? best : worst;
        kmin = fmin(kmin, hypot(k->mu_re[a], k->mu_im[a]));
    }
    int above = 0;
    for (int b = 0; b < d->nmult; b++)
        above += hypot(d->mu_re[b], d->mu_im[b]) > kmin + 1e-8;
    *largest = above <= k->nmult;
    return worst;
}

/* Mathieu pair inside and outside its tongue (tests/plot/mathieu_pair.yaml: 698.97 ..
 * 715.17 rad/s), 2048 Magnus steps: both multipliers (two states: every column of the
 * monodromy from a product) to 1e-8 of the dense ones. Measured 2e-12: the Taylor sums
 * and the Pade exponential differ by rounding per step. */
TEST(mathieu_products_equal_dense)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double W[2] = {690.0, 707.0};
    for (int c = 0; c < 2; c++) {
        gd_periodic_result *d = floquet_point(&f, &tm->spec, W[c], 8, 2048, GD_FLOQUET_DENSE, 0, 0);
        gd_periodic_result *k =
            floquet_point(&f, &tm->spec, W[c], 8, 2048, GD_FLOQUET_KRYLOV, 0, 0);
        REQUIRE(d && k);
        const gd_periodic_point *pd = &d->points[0], *pk = &k->points[0];
        CHECK(pd->floquet_krylov == 0 && pk->floquet_krylov == 1);
        CHECK(pk->nmult == 2 && pd->nmult == 2);
        int largest;
        double w = worst_distance(pd, pk, &largest);
        printf("  W = %.0f: |mu|max dense %.12f, Krylov %.12f, distance %.2g\n", W[c], pd->mu_max,
               pk->mu_max, w);
        CHECK(w <= 1e-8);
        CHECK(pk->stable == pd->stable);
        CHECK(pd->stable == (c == 0)); /* 707 rad/s lies inside the tongue */
        gd_periodic_result_free(d);
        gd_periodic_result_free(k);
    }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Chen SFD pair (examples/chen1998_gear_pair.yaml, 12 states, unbalance raised to 38.1 um
 * as in test_periodic) near its Neimark-Sacker region, 128 Magnus steps: the 4 and the 8
 * largest multipliers by Krylov-Schur (tolerance 1e-10) are the dense monodromy's largest,
 * to 1e-8 (measured 8e-10: the Ritz values' residual and the per-step rounding). */
TEST(chen_sfd_krylov_schur_equals_dense)
{
    fx f;
    gd_load_options lo;
    const char *set[1] = {"unbalances.gear_a_unbalance.eccentricity=38.1um"};
    memset(&lo, 0, sizeof lo);
    lo.nset = 1;
    lo.set = set;
    gd_error err;
    memset(&f, 0, sizeof f);
    REQUIRE(gd_model_load_opts(GD_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", &lo, &f.m,
                               &err) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double W[2] = {5350.0, 5650.0};
    for (int c = 0; c < 2; c++) {
        gd_periodic_result *d = floquet_point(&f, &tm->spec, W[c], 12, 128, GD_FLOQUET_DENSE, 0, 0);
        REQUIRE(d);
        for (int q = 0; q < 2; q++) {
            const int want = q ? 8 : 4;
            gd_periodic_result *k =
                floquet_point(&f, &tm->spec, W[c], 12, 128, GD_FLOQUET_KRYLOV, want, 0);
            REQUIRE(k);
            const gd_periodic_point *pd = &d->points[0], *pk = &k->points[0];
            int largest;
            double w = worst_distance(pd, pk, &largest);
            printf("  W = %.0f, %d wanted: %d found, |mu|max dense %.12f, Krylov %.12f, "
                   "distance %.2g\n",
                   W[c], want, pk->nmult, pd->mu_max, pk->mu_max, w);
            CHECK(pk->floquet_krylov == 1);
            CHECK(pk->nmult >= want && pk->nmult <= want + 1);
            CHECK(w <= 1e-8);
            CHECK(largest);
            CHECK(fabs(pk->mu_max - pd->mu_max) <= 1e-8);
            CHECK(pk->stable == pd->stable);
            gd_periodic_result_free(k);
        }
        gd_periodic_result_free(d);
    }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The Mathieu tongue traced with Krylov multipliers: the same period doublings as with the
 * dense monodromy (located to 1e-10 on |mu| - 1; the two methods' multipliers differ by
 * about 1e-12, so the located speeds agree to 1e-6 rad/s). */
TEST(mathieu_bifurcations_unchanged)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    double at[2][2] = {{0, 0}, {0, 0}};
    int nb[2] = {0, 0};
    for (int m = 0; m < 2; m++) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = 8;
        o.estimate = 0;
        o.monodromy_steps = 1024;
        o.floquet = m ? GD_FLOQUET_KRYLOV : GD_FLOQUET_DENSE;
        double v[11];
        for (int i = 0; i < 11; i++)
            v[i] = 690.0 + 3.0 * i;
        gd_periodic_result *r = NULL;
        REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, v, 11, &o, NULL, 0, &r, &err) == GD_OK);
        for (int i = 0; i < r->nbifurcations; i++) {
            const gd_bifurcation *b = &r->bifurcations[i];
            if (b->type == GD_BIF_PERIOD_DOUBLING && nb[m] < 2) at[m][nb[m]++] = b->speed;
        }
        printf("  %s: %d period doublings, at %.6f and %.6f rad/s\n", m ? "Krylov" : "dense", nb[m],
               at[m][0], at[m][1]);
        gd_periodic_result_free(r);
    }
    CHECK(nb[0] == 2 && nb[1] == 2);
    CHECK(fabs(at[0][0] - 698.97) < 0.05 && fabs(at[0][1] - 715.17) < 0.05);
    CHECK(fabs(at[0][0] - at[1][0]) < 1e-6 && fabs(at[0][1] - at[1][1]) < 1e-6);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The Chen SFD pair's Neimark-Sacker pair (test_periodic:
 * chen_sfd_neimark_sacker_matches_transient, the same run) with the 4 largest multipliers
 * by Krylov-Schur: the same two located speeds and critical angle as the dense monodromy
 * gives there (5583 +- 2 rad/s, 5740..5760 rad/s, 44.5 +- 1 deg). Measured: all eight
 * events of the run (four Neimark-Sacker, two folds, a branch point) at the dense run's
 * speeds to the printed 1e-3 rad/s, the same critical multipliers to 1e-6. */
TEST(chen_sfd_neimark_sacker_by_krylov)
{
    fx f;
    gd_load_options lo;
    const char *set[1] = {"unbalances.gear_a_unbalance.eccentricity=38.1um"};
    memset(&lo, 0, sizeof lo);
    lo.nset = 1;
    lo.set = set;
    gd_error err;
    memset(&f, 0, sizeof f);
    REQUIRE(gd_model_load_opts(GD_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", &lo, &f.m,
                               &err) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 12;
    o.monodromy_steps = 128;
    o.floquet = GD_FLOQUET_KRYLOV;
    o.floquet_count = 4;
    double v[46];
    for (int i = 0; i < 46; i++)
        v[i] = 5350.0 + 10.0 * i;
    gd_periodic_result *r = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, v, 46, &o, NULL, 0, &r, &err) == GD_OK);
    int ns = 0, krylov = 0;
    double at[2] = {0, 0}, ang = 0;
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        printf("  %s at %.3f rad/s, multiplier %.6f%+.6fi\n", gd_bifurcation_name(b->type),
               b->speed, b->mu_re, b->mu_im);
        if (b->type == GD_BIF_NEIMARK_SACKER && b->speed > 5560 && ns < 2) {
            if (!ns) ang = atan2(b->mu_im, b->mu_re) * 180 / M_PI;
            at[ns++] = b->speed;
        }
    }
    for (int i = 0; i < r->npoints; i++)
        krylov += r->points[i].floquet_krylov;
    CHECK(krylov == r->npoints);
    REQUIRE(ns == 2);
    CHECK(fabs(at[0] - 5583) < 2.0);
    CHECK(at[1] > 5740 && at[1] < 5760);
    CHECK(fabs(ang - 44.5) < 1.0);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Option bounds: an unknown method and a count above 256 are refused, naming the field. */
TEST(floquet_options_checked)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    for (int c = 0; c < 2; c++) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        if (c == 0) o.floquet = GD_FLOQUET_REDUCED + 1;
        if (c == 1) o.floquet_count = 1000;
        const double v[1] = {700.0};
        gd_periodic_result *r = NULL;
        CHECK(gd_periodic_run(f.s, &tm->spec, NULL, v, 1, &o, NULL, 0, &r, &err) == GD_EINPUT);
        CHECK(r == NULL);
        CHECK_STR(err.field, "floquet");
    }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The CPU budget of one point's multipliers (floquet_budget): over it (1e-9 s, passed by
 * any real cost) the point keeps its orbit, converged, with stability not computed and a
 * reason naming the budget, by either method; within it (1000 s) the multipliers are the
 * unbudgeted ones bit for bit (the budget only reads the clock); a negative one is refused. */
TEST(floquet_budget_leaves_stability_out_and_says_why)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double v[1] = {700.0};
    for (int m = GD_FLOQUET_DENSE; m <= GD_FLOQUET_KRYLOV; m++) {
        gd_periodic_result *r[3] = {NULL, NULL, NULL};
        const double budget[3] = {0.0, 1e-9, 1e3};
        for (int c = 0; c < 3; c++) {
            gd_periodic_options o;
            gd_periodic_options_init(&o);
            o.harmonics = 8;
            o.estimate = 0;
            o.floquet = m;
            o.floquet_budget = budget[c];
            CHECK(gd_periodic_run(f.s, &tm->spec, NULL, v, 1, &o, NULL, 0, &r[c], &err) == GD_OK);
        }
        if (r[0] && r[1] && r[2]) {
            const gd_periodic_point *p0 = &r[0]->points[0], *p1 = &r[1]->points[0],
                                    *p2 = &r[2]->points[0];
            CHECK(p0->converged && p1->converged && p2->converged);
            CHECK(p0->stable >= 0 && p0->nmult == 2);
            CHECK(p1->stable == -1 && p1->nmult == 0 && isnan(p1->mu_max));
            CHECK(strstr(p1->reason, "stability not computed") != NULL);
            CHECK(strstr(p1->reason, "budget") != NULL);
            CHECK(p2->stable == p0->stable && p2->nmult == p0->nmult);
            CHECK(p2->mu_max == p0->mu_max);
            CHECK(p1->coef[0] == p0->coef[0]); /* the orbit itself is the same */
        }
        for (int c = 0; c < 3; c++)
            gd_periodic_result_free(r[c]);
    }
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.floquet_budget = -1.0;
    gd_periodic_result *r = NULL;
    CHECK(gd_periodic_run(f.s, &tm->spec, NULL, v, 1, &o, NULL, 0, &r, &err) == GD_EINPUT);
    CHECK(r == NULL);
    CHECK_STR(err.field, "floquet_budget");
    gd_transient_model_free(tm);
    fx_free(&f);
}

RUN_TESTS(T(mathieu_products_equal_dense), T(chen_sfd_krylov_schur_equals_dense),
          T(mathieu_bifurcations_unchanged), T(chen_sfd_neimark_sacker_by_krylov),
          T(floquet_options_checked), T(floquet_budget_leaves_stability_out_and_says_why))
