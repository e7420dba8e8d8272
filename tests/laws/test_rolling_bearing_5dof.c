/* The rolling bearing from its geometry as a 5-DOF law (src/laws/rolling_bearing_5dof.c):
 * its force is gd_bearing_forces of the relative motion (inner race minus outer race,
 * opposite on the two), its 25 Jacobian terms give K = -df/dq, checked against
 * Richardson central differences of the force (issue 34's 1e-6) for a deep-groove ball
 * bearing with clearance under combined load, a preloaded angular-contact bearing and a
 * tapered roller, also with the cage turned and the outer race moving; bad geometry is
 * named. */
#include <math.h>
#include <string.h>

#include "geardyn/bearing_geometry.h"
#include "geardyn/law_type.h"
#include "harness.h"

static void set(gd_law *L, const char *name, double v)
{
    int k = gd_law_param_index(L->type, name);
    if (k >= 0) L->value[k] = v;
}

/* a 6205-like ball bearing with 2 um clearance; an angular-contact one preloaded; a
   tapered roller */
static void make(gd_law *L, int which)
{
    gd_law_init(L, &gd_law_rolling_bearing_5dof, "b");
    for (int j = 0; j < 10; j++)
        L->dof[j] = j;
    if (which == 0) {
        set(L, "elements", 9);
        set(L, "element_diameter", 7.94e-3);
        set(L, "pitch_diameter", 39.04e-3);
        set(L, "clearance", 2e-6);
        set(L, "phase", 0.1);
    } else if (which == 1) {
        set(L, "elements", 13);
        set(L, "element_diameter", 7.5e-3);
        set(L, "pitch_diameter", 40e-3);
        set(L, "contact_angle", 25 * M_PI / 180);
        set(L, "clearance", -2e-6);
    } else {
        set(L, "elements", 15);
        set(L, "roller", 1);
        set(L, "element_diameter", 7e-3);
        set(L, "pitch_diameter", 38e-3);
        set(L, "roller_length", 10e-3);
        set(L, "contact_angle", 15 * M_PI / 180);
    }
    set(L, "damping", 150);
}

static void geometry_of(int which, double phase, gd_bearing_geometry *g)
{
    gd_bearing_geometry_init(g);
    if (which == 0) {
        g->elements = 9;
        g->element_diameter = 7.94e-3;
        g->pitch_diameter = 39.04e-3;
        g->clearance = 2e-6;
    } else if (which == 1) {
        g->elements = 13;
        g->element_diameter = 7.5e-3;
        g->pitch_diameter = 40e-3;
        g->contact_angle = 25 * M_PI / 180;
        g->clearance = -2e-6;
    } else {
        g->kind = GD_BEARING_ROLLER;
        g->elements = 15;
        g->element_diameter = 7e-3;
        g->pitch_diameter = 38e-3;
        g->roller_length = 10e-3;
        g->contact_angle = 15 * M_PI / 180;
    }
    g->phase = phase;
}

/* relative motions: inner race (q[0..4]) and outer race (q[5..9]), each element away from
 * its first touch (there the 3/2 contact's second derivative is unbounded and differences
 * lose their order: 4e-4 with dy 9.5 um below, whose element 1 barely touches) */
static const double STATES[3][10] = {
    {1.2e-6, 9.0e-6, 1.5e-6, 2e-4, -1.5e-4, 0.3e-6, -1.1e-6, 0.2e-6, 0.5e-4, 0},
    {0.8e-6, -2.5e-6, 6e-6, -1e-4, 0.6e-4, 0, 0, -1e-6, 0, 0.2e-4},
    {0.5e-6, 7e-6, 4e-6, 0, 0, -0.2e-6, 0, 0, 0, 0}};

TEST(force_is_the_geometrys_relative_load)
{
    for (int which = 0; which < 3; which++) {
        gd_law L;
        make(&L, which);
        gd_error err;
        REQUIRE(gd_law_check(&L, &err) == GD_OK);
        double v[10] = {0}, f[10] = {0}, F[5], d[5];
        for (int a = 0; a < 5; a++)
            d[a] = STATES[which][a] - STATES[which][5 + a];
        gd_bearing_geometry g;
        geometry_of(which, which == 0 ? 0.1 : 0.0, &g);
        int loaded = 0;
        REQUIRE(gd_bearing_forces(&g, d, F, NULL, &loaded, &err) == GD_OK);
        gd_law_point x = {0.0, STATES[which], v};
        L.type->force(&L, &x, f, NULL, NULL);
        double big = 0, worst = 0;
        for (int a = 0; a < 5; a++) {
            big = fmax(big, fabs(F[a]));
            worst = fmax(worst, fmax(fabs(f[a] + F[a]), fabs(f[5 + a] - F[a])));
        }
        printf("  case %d: %d elements loaded, |F| max %.5g, |f - (-F, F)| %.2g\n", which, loaded,
               big, worst);
        CHECK(loaded > 0 && big > 10);
        CHECK(worst <= 1e-12 * big);
        /* the records are the force on the inner race and the elements in contact */
        CHECK_REL(L.type->record(&L, 2, &x), f[2], 1e-12);
        CHECK(L.type->record(&L, 5, &x) == loaded);
    }
}

/* K = -df/dq from the law's terms against Richardson central differences of its force
 * (steps 1e-8 m and 1e-6 rad, and twice those), every state with the cage at t = 0 and
 * turned (t = 1e-3 s at 300 rad/s spin); tolerance 1e-6 of the largest entry. The damping
 * terms against differences in the velocities. */
TEST(tangent_against_central_differences)
{
    for (int which = 0; which < 3; which++)
        for (int turned = 0; turned < 2; turned++) {
            gd_law L;
            make(&L, which);
            L.spin[0] = 300.0;
            double q[10], v[10] = {0}, K[100] = {0}, C[100] = {0};
            memcpy(q, STATES[which], sizeof q);
            gd_law_point x = {turned ? 1e-3 : 0.0, q, v};
            L.type->linearize(&L, &x, K, C);
            double big = 0, worst = 0, worst_c = 0;
            for (int j = 0; j < 100; j++)
                big = fmax(big, fabs(K[j]));
            for (int b = 0; b < 10; b++) {
                double h = b % 5 < 3 ? 1e-8 : 1e-6, d1[10], d2[10], keep = q[b];
                for (int pass = 0; pass < 2; pass++) {
                    double hh = pass ? 2 * h : h, fp[10] = {0}, fm[10] = {0};
                    q[b] = keep + hh;
                    L.type->force(&L, &x, fp, NULL, NULL);
                    q[b] = keep - hh;
                    L.type->force(&L, &x, fm, NULL, NULL);
                    q[b] = keep;
                    for (int a = 0; a < 10; a++)
                        (pass ? d2 : d1)[a] = -(fp[a] - fm[a]) / (2 * hh);
                }
                double fp[10] = {0}, fm[10] = {0};
                v[b] = 1e-3;
                L.type->force(&L, &x, fp, NULL, NULL);
                v[b] = -1e-3;
                L.type->force(&L, &x, fm, NULL, NULL);
                v[b] = 0;
                for (int a = 0; a < 10; a++) {
                    /* moments and forces weigh alike by the lever (about 0.02 m) */
                    worst = fmax(worst, fabs(K[a + 10 * b] - (4 * d1[a] - d2[a]) / 3));
                    worst_c = fmax(worst_c, fabs(C[a + 10 * b] + (fp[a] - fm[a]) / 2e-3));
                }
            }
            printf("  case %d, cage %s: |K - K_fd| %.2g of the largest entry %.4g; |C - C_fd| "
                   "%.2g N s/m\n",
                   which, turned ? "turned" : "at t = 0", worst / big, big, worst_c);
            CHECK(big > 1e6);
            CHECK(worst <= 1e-6 * big);
            CHECK(worst_c <= 1e-9 * 150);
            /* symmetric (a potential) and each race's block the opposite of the coupling */
            double asym = 0;
            for (int a = 0; a < 10; a++)
                for (int b = 0; b < 10; b++)
                    asym = fmax(asym, fabs(K[a + 10 * b] - K[b + 10 * a]));
            CHECK(asym <= 1e-12 * big);
            CHECK_REL(K[0], -K[5], 1e-15);
        }
}

TEST(bad_geometry_is_named)
{
    gd_law L;
    gd_error err;
    make(&L, 0);
    set(&L, "pitch_diameter", 5e-3);
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "pitch_diameter");
    printf("  %s\n", err.message);
    make(&L, 0);
    set(&L, "roller", 2);
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "roller");
    make(&L, 2);
    set(&L, "roller_length", 0);
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "roller_length");
    make(&L, 0);
    set(&L, "elements", 2.5);
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "elements");
    make(&L, 0);
    set(&L, "clearance", 1e-3);
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "clearance");
}

RUN_TESTS(T(force_is_the_geometrys_relative_load), T(tangent_against_central_differences),
          T(bad_geometry_is_named))
