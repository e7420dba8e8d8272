/* Floquet multipliers in a reduced basis (periodic.h, floquet = GD_FLOQUET_REDUCED;
 * src/periodic/floquet/floquet_reduced.c) against the dense Magnus monodromy over the same steps:
 * the Mathieu pair (one DOF: the basis is the whole model, so only the Strang splitting
 * differs from the fourth-order Magnus steps), the Chen SFD pair (six DOFs, four local
 * terms) with every mode and with a cut-off that leaves modes out (their multipliers then
 * estimated one by one), a free rotation (Kumar 2011: no usable eigenvector basis, the
 * dense monodromy instead) and the option checks. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model_file.h"
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "floquet_support.h"
#include "model_support.h"

/* The Chen SFD pair at the eccentricity e_u/C = 1/2 (38.1 um), gear b's torsional support
 * made rigid (k_torsion 1e12) when stiff. 1 ok. */
static int load_chen(fx *f, int stiff)
{
    const char *set[2] = {"unbalances.gear_a_unbalance.eccentricity=38.1um",
                          "bearings.support_b.k_torsion=1e12"};
    gd_load_options lo;
    memset(&lo, 0, sizeof lo);
    lo.nset = stiff ? 2 : 1;
    lo.set = set;
    gd_error err;
    memset(f, 0, sizeof *f);
    return gd_model_load_opts(GD_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", &lo, &f->m,
                              &err) == GD_OK &&
           gd_system_build(f->m, &f->s, &err) == GD_OK;
}

/* The largest distance from each of a's first n multipliers to the nearest of b's. */
static double worst_distance(const gd_periodic_point *a, int n, const gd_periodic_point *b)
{
    double worst = 0.0;
    for (int i = 0; i < n && i < a->nmult; i++) {
        double best = INFINITY;
        for (int j = 0; j < b->nmult; j++)
            best = fmin(best, hypot(a->mu_re[i] - b->mu_re[j], a->mu_im[i] - b->mu_im[j]));
        worst = fmax(worst, best);
    }
    return worst;
}

/* Mathieu pair outside and inside its tongue (698.97 .. 715.17 rad/s), both multipliers
 * against the dense monodromy's, two ways:
 *  - H = 8, 2048 steps each: within 1e-10 (measured 9e-14 and 2.1e-13: two fourth-order
 *    schemes, the interaction picture's and the plain Magnus steps, in balanced states);
 *  - H = 64, every step count default: dense takes 4 x samples (2048), the reduced method
 *    its own count, from 256 (8 per period of the top excitation order, at least 256)
 *    doubled until two counts' moduli agree (each within 1 % of its distance from the
 *    circle, at least 1e-7): it stops far below 2048 (measured 512) within 1e-7 of dense
 *    (measured 8e-14 and 4e-14: its constant part is exact, the steps only follow the
 *    stiffness). */
TEST(mathieu_reduced_equals_dense)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double W[2] = {690.0, 707.0};
    for (int own = 0; own < 2; own++)
        for (int c = 0; c < 2; c++) {
            const int H = own ? 64 : 8, steps = own ? 0 : 2048;
            gd_periodic_result *d =
                floquet_point(&f, &tm->spec, W[c], H, steps, GD_FLOQUET_DENSE, 0, 0);
            gd_periodic_result *r =
                floquet_point(&f, &tm->spec, W[c], H, steps, GD_FLOQUET_REDUCED, 0, 0);
            REQUIRE(d && r);
            const gd_periodic_point *pd = &d->points[0], *pr = &r->points[0];
            CHECK(pr->floquet_basis == 1 && pd->floquet_basis == 0 && pr->floquet_krylov == 0);
            CHECK(pr->nmult == 2);
            double w = worst_distance(pr, 2, pd);
            printf("  H = %d, W = %.0f: dense %d steps |mu|max %.12f, reduced %d steps %.12f, "
                   "distance %.2g\n",
                   H, W[c], pd->floquet_steps, pd->mu_max, pr->floquet_steps, pr->mu_max, w);
            CHECK(pd->floquet_steps == 2048);
            if (own)
                CHECK(pr->floquet_steps >= 512 && pr->floquet_steps <= 1024);
            else
                CHECK(pr->floquet_steps == 2048);
            CHECK(w <= (own ? 1e-7 : 1e-10));
            CHECK(pr->stable == pd->stable);
            CHECK(pd->stable == (c == 0)); /* 707 rad/s lies inside the tongue */
            gd_periodic_result_free(d);
            gd_periodic_result_free(r);
        }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The Mathieu tongue traced with the reduced multipliers (11 speeds, 256 steps): the same
 * two period doublings as the dense monodromy gives in the same run (measured with
 * floquet = GD_FLOQUET_DENSE: 698.969804 and 715.170885 rad/s; the two methods'
 * multipliers differ by about 2e-12, so the located speeds agree to the 1e-6 printed). */
TEST(mathieu_bifurcations_by_reduced)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    double at[2] = {0, 0};
    int nb = 0, basis = 0;
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 8;
    o.estimate = 0;
    o.monodromy_steps = 256;
    o.floquet = GD_FLOQUET_REDUCED;
    double v[11];
    for (int i = 0; i < 11; i++)
        v[i] = 690.0 + 3.0 * i;
    gd_periodic_result *r = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, v, 11, &o, NULL, 0, &r, &err) == GD_OK);
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        if (b->type == GD_BIF_PERIOD_DOUBLING && nb < 2) at[nb++] = b->speed;
    }
    for (int i = 0; i < r->npoints; i++)
        basis += r->points[i].floquet_basis == 1;
    CHECK(basis == r->npoints);
    printf("  reduced: %d period doublings, at %.6f and %.6f rad/s\n", nb, at[0], at[1]);
    CHECK(nb == 2);
    CHECK(fabs(at[0] - 698.969804) < 2e-6 && fabs(at[1] - 715.170885) < 2e-6);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Chen SFD pair (unbalance 38.1 um, as in test_floquet_krylov) at 5350 and 5650 rad/s
 * (inside the Neimark-Sacker region: |mu|max 1.178), H = 12, 512 steps. Every mode kept
 * (the default cut-off keeps all six): all twelve multipliers within 1e-6 of the dense
 * ones (measured 1.5e-7 at 5650; both schemes are fourth order: at 128 steps each is
 * 2e-5 from the 2048-step value 1.17840059, at 512 steps 9e-8 and 7e-8). At 5350 a
 * cut-off of 0.3 x the mesh frequency keeps 3 modes and a residual vector, the others'
 * multipliers estimated one by one: |mu|max within 1e-5 (measured 7e-7). */
TEST(chen_sfd_reduced_equals_dense)
{
    fx f;
    gd_error err;
    REQUIRE(load_chen(&f, 0));
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double W[2] = {5350.0, 5650.0};
    for (int c = 0; c < 2; c++) {
        gd_periodic_result *d = floquet_point(&f, &tm->spec, W[c], 12, 512, GD_FLOQUET_DENSE, 0, 0);
        gd_periodic_result *r =
            floquet_point(&f, &tm->spec, W[c], 12, 512, GD_FLOQUET_REDUCED, 0, 0);
        REQUIRE(d && r);
        const gd_periodic_point *pd = &d->points[0], *pr = &r->points[0];
        double w = worst_distance(pr, pr->nmult, pd);
        printf("  W = %.0f: every mode (%d): |mu|max dense %.10f, reduced %.10f, distance %.2g\n",
               W[c], pr->floquet_basis, pd->mu_max, pr->mu_max, w);
        CHECK(pr->floquet_basis == 6 && pr->nmult == 12);
        CHECK(w <= 1e-6);
        CHECK(fabs(pr->mu_max - pd->mu_max) <= 1e-6);
        CHECK(pr->stable == pd->stable);
        CHECK(pd->stable == (c == 0));
        if (c == 0) {
            gd_periodic_result *s =
                floquet_point(&f, &tm->spec, W[c], 12, 512, GD_FLOQUET_REDUCED, 0, 0.3);
            REQUIRE(s);
            const gd_periodic_point *ps = &s->points[0];
            printf("  cut-off 0.3 (%d vectors): |mu|max %.10f\n", ps->floquet_basis, ps->mu_max);
            CHECK(ps->floquet_basis > 0 && ps->floquet_basis < 6);
            CHECK(ps->nmult == 12);
            CHECK(fabs(ps->mu_max - pd->mu_max) <= 1e-5);
            CHECK(ps->stable == pd->stable);
            gd_periodic_result_free(s);
        }
        gd_periodic_result_free(d);
        gd_periodic_result_free(r);
    }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* A stiff DOF does not bias the dense monodromy: the Chen pair with gear b's torsional
 * support made rigid (k_torsion 1e12 N m/rad: 1.4e7 rad/s, against 5350 rad/s) at 512
 * steps. Unbalanced ([x; x']), the state matrix's 1-norm is 2e14 1/s^2 and the scaling and
 * squaring of each step's exponential (about 30 squarings) put the dense |mu|max 5.8e-6
 * above the reduced basis's (every mode kept: its exponential of the constant part is
 * exact) whatever the step count; in the balanced state [c x; x'] the two agree to 1e-10
 * (measured: |mu|max 2e-11, every multiplier 1e-10). The [JMSTHelical] model cut to 178
 * states showed the same 5.6e-6 (docs/periodic.md, "Stability at scale"). */
TEST(stiff_dof_dense_equals_reduced)
{
    fx f;
    gd_error err;
    REQUIRE(load_chen(&f, 1));
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_result *d = floquet_point(&f, &tm->spec, 5350.0, 12, 512, GD_FLOQUET_DENSE, 0, 0);
    gd_periodic_result *r =
        floquet_point(&f, &tm->spec, 5350.0, 12, 512, GD_FLOQUET_REDUCED, 0, 1e6);
    REQUIRE(d && r);
    const gd_periodic_point *pd = &d->points[0], *pr = &r->points[0];
    double w = worst_distance(pr, pr->nmult, pd);
    printf("  |mu|max dense %.12f, reduced (%d modes) %.12f, distance %.2g\n", pd->mu_max,
           pr->floquet_basis, pr->mu_max, w);
    CHECK(pr->floquet_basis == 6 && pr->nmult == 12);
    CHECK(fabs(pr->mu_max - pd->mu_max) <= 1e-8);
    CHECK(w <= 1e-8);
    gd_periodic_result_free(d);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* A free rotation (examples/kumar2011_coupled.yaml: a zero eigenvalue of K, a Jordan block
 * of the state matrix) has no eigenvector basis: the reduced method hands over to the
 * dense monodromy (16 states, under floquet_dmax), whose multipliers come out unchanged. */
TEST(free_rotation_falls_back_to_dense)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/examples/kumar2011_coupled.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_result *d = floquet_point(&f, &tm->spec, 300.0, 94, 256, GD_FLOQUET_DENSE, 0, 0);
    gd_periodic_result *r = floquet_point(&f, &tm->spec, 300.0, 94, 256, GD_FLOQUET_REDUCED, 0, 0);
    REQUIRE(d && r);
    const gd_periodic_point *pd = &d->points[0], *pr = &r->points[0];
    printf("  |mu|max dense %.12f, reduced request %.12f (basis %d)\n", pd->mu_max, pr->mu_max,
           pr->floquet_basis);
    CHECK(pr->floquet_basis == 0 && pr->floquet_krylov == 0);
    CHECK(pr->nmult == 16);
    CHECK(pr->mu_max == pd->mu_max);
    gd_periodic_result_free(d);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Option checks, and the CPU budget: over it (1e-9 s, passed by the estimate of the modes
 * alone) the point keeps its orbit with stability unknown and the reason. */
TEST(reduced_options_checked)
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
        if (c == 1) o.floquet_cutoff = -1.0;
        double W = 690.0;
        gd_periodic_result *r = NULL;
        CHECK(gd_periodic_run(f.s, &tm->spec, NULL, &W, 1, &o, NULL, 0, &r, &err) == GD_EINPUT);
        CHECK_STR(err.field, c ? "floquet_cutoff" : "floquet");
        CHECK(r == NULL);
    }
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.floquet = GD_FLOQUET_REDUCED;
    o.floquet_budget = 1e-9;
    o.estimate = 0;
    double W = 690.0;
    gd_periodic_result *r = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, &W, 1, &o, NULL, 0, &r, &err) == GD_OK);
    REQUIRE(r->npoints == 1);
    CHECK(r->points[0].converged == 1 && r->points[0].stable == -1);
    CHECK(strstr(r->points[0].reason, "reduced basis") != NULL);
    CHECK(strstr(r->points[0].reason, "budget") != NULL);
    printf("  %s\n", r->points[0].reason);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

RUN_TESTS(T(mathieu_reduced_equals_dense), T(stiff_dof_dense_equals_reduced),
          T(mathieu_bifurcations_by_reduced), T(chen_sfd_reduced_equals_dense),
          T(free_rotation_falls_back_to_dense), T(reduced_options_checked))
