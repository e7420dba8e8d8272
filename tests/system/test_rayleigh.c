/* Rayleigh damping (issue 14, [JMSTHelical] "Rayleigh-type damping"): `damping: {rayleigh:
 * {alpha, beta}}` adds C = alpha M + beta K, and `{ratios: [z1, z2], frequencies: [w1,
 * w2]}` chooses alpha and beta so that the modes at w1 and w2 have the damping ratios
 * z1 and z2 (z = alpha / (2 w) + beta w / 2). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/builder.h"
#include "geardyn/modal.h"
#include "geardyn/model_file.h"
#include "harness.h"
#include "model_error_support.h"
#include "model_support.h"

/* Three inertias on torsional springs, with a damper of its own on the first spring. */
#define CHAIN                                                                                      \
    "dofs: [rz]\n"                                                          /* 1 */                \
    "shafts:\n"                                                             /* 2 */                \
    "  - {name: a, nodes: [{name: n1}, {name: n2}, {name: n3}]}\n"          /* 3 */                \
    "disks: [{node: n1, polar_inertia: 1}, {node: n2, polar_inertia: 2},\n" /* 4 */                \
    "        {node: n3, polar_inertia: 1.5}]\n"                             /* 5 */                \
    "springs:\n"                                                            /* 6 */                \
    "  - {node: n1, to: n2, dof: rz, stiffness: 1e4, damping: 3}\n"         /* 7 */                \
    "  - {node: n2, to: n3, dof: rz, stiffness: 2e4}\n"                     /* 8 */                \
    "  - {node: n3, dof: rz, stiffness: 5e3}\n"                             /* 9 */

TEST(alpha_beta_give_c_plus_alpha_m_plus_beta_k)
{
    fx plain, ray;
    REQUIRE(load(&plain, NULL, CHAIN));
    REQUIRE(load(&ray, NULL, CHAIN "damping: {rayleigh: {alpha: 0.7, beta: 2 ms}}\n"));
    int n = plain.s->ndof;
    REQUIRE(n == 3 && ray.s->ndof == 3);
    double M[9], K[9], D0[9], D[9];
    gd_system_dense(plain.s, 0, M, D0, K);
    gd_system_dense(ray.s, 0, NULL, D, NULL);
    /* hand values: M = diag(1, 2, 1.5), K of the chain; C0 = 3 on the first spring */
    CHECK_REL(M[0], 1, 0);
    CHECK_REL(K[0], 1e4, 0);
    CHECK_REL(K[4], 3e4, 0);
    CHECK_REL(K[8], 2.5e4, 0);
    CHECK_REL(K[1], -1e4, 0);
    for (int i = 0; i < 9; i++)
        CHECK_ABS(D[i], D0[i] + 0.7 * M[i] + 2e-3 * K[i], 1e-12 * (1 + fabs(D[i])));
    CHECK_REL(D[0], 3 + 0.7 + 20, 1e-15); /* C0 + alpha + beta 1e4 */
    CHECK_REL(D[4], 3 + 1.4 + 60, 1e-15); /* C0 + alpha 2 + beta 3e4 */
    CHECK_REL(D[1], -3 + 0 - 20, 1e-15);  /* -C0 + beta (-1e4) */
    CHECK(ray.s->has_damping);
    fx_free(&plain);
    fx_free(&ray);
}

TEST(ratio_formula_hand_values)
{
    double a, b;
    gd_error e;
    REQUIRE(gd_rayleigh_from_ratios(0.02, 0.05, 60, 200, &a, &b, &e) == GD_OK);
    /* alpha = 2 w1 w2 (z1 w2 - z2 w1) / (w2^2 - w1^2) = 24000 / 36400,
       beta = 2 (z2 w2 - z1 w1) / (w2^2 - w1^2) = 17.6 / 36400 */
    CHECK_REL(a, 24000.0 / 36400.0, 1e-14);
    CHECK_REL(b, 17.6 / 36400.0, 1e-14);
    CHECK(gd_rayleigh_from_ratios(0.02, 0.05, 60, 60, &a, &b, &e) == GD_EINPUT);
    CHECK(gd_rayleigh_from_ratios(0.5, 0.001, 60, 200, &a, &b, &e) == GD_EINPUT);
    CHECK(strstr(e.message, "negative") != NULL);
}

/* Ratios at two of the chain's own frequencies: the damped solver gives exactly those
 * ratios there (Rayleigh damping keeps the undamped modes), and the third mode
 * alpha / (2 w) + beta w / 2. The spring's own damper is left out here. */
TEST(ratios_reproduce_the_modal_damping_of_two_modes)
{
    fx f;
    static const char *NO_C0 = "springs.0.damping=0";
    gd_load_options lo;
    gd_load_options_init(&lo);
    lo.nset = 1;
    lo.set = &NO_C0;
    gd_error e;
    memset(&f, 0, sizeof f);
    REQUIRE(gd_model_load_string_opts(CHAIN, "chain.yaml", &lo, &f.m, &e) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &e) == GD_OK);
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.kind = GD_MODAL_UNDAMPED;
    gd_modal_result *r = NULL;
    REQUIRE(gd_modal_solve(f.s, &o, &r, &e) == GD_OK);
    REQUIRE(r->nmodes == 3);
    double w[3];
    for (int i = 0; i < 3; i++)
        w[i] = r->modes[i].omega_n;
    gd_modal_free(r);
    fx_free(&f);

    char yaml[2048], set[160];
    snprintf(set, sizeof set,
             "damping={rayleigh: {ratios: [0.02, 0.05], frequencies: [%.17g, %.17g]}}", w[0], w[2]);
    const char *sets[] = {NO_C0, set};
    lo.nset = 2;
    lo.set = sets;
    snprintf(yaml, sizeof yaml, "%s", CHAIN "damping: {}\n");
    REQUIRE(gd_model_load_string_opts(yaml, "chain.yaml", &lo, &f.m, &e) == GD_OK);
    CHECK_REL(f.m->rayleigh_alpha,
              2 * w[0] * w[2] * (0.02 * w[2] - 0.05 * w[0]) / (w[2] * w[2] - w[0] * w[0]), 1e-13);
    REQUIRE(gd_system_build(f.m, &f.s, &e) == GD_OK);
    o.kind = GD_MODAL_DAMPED;
    REQUIRE(gd_modal_solve(f.s, &o, &r, &e) == GD_OK);
    REQUIRE(r->nmodes == 3);
    /* classical damping: each undamped mode keeps its shape, zeta exact to rounding
       of the 6 x 6 state-space eigenproblem */
    CHECK_REL(r->modes[0].damping_ratio, 0.02, 1e-9);
    CHECK_REL(r->modes[2].damping_ratio, 0.05, 1e-9);
    double a = f.m->rayleigh_alpha, b = f.m->rayleigh_beta;
    CHECK_REL(r->modes[1].damping_ratio, a / (2 * w[1]) + b * w[1] / 2, 1e-9);
    CHECK_REL(r->modes[1].omega_n, w[1], 1e-9); /* |lambda| is the undamped w */
    gd_modal_free(r);
    fx_free(&f);
}

TEST(rayleigh_errors_are_located)
{
    EXPECT_LOAD_ERROR(CHAIN "damping: {rayleigh: {alpha: 1, ratios: [0.01, 0.02],\n" /* 10 */
                            "  frequencies: [10, 20]}}\n",
                      10, "damping.rayleigh", "both", "ratios");
    EXPECT_LOAD_ERROR(CHAIN "damping: {rayleigh: {}}\n", 10, "damping.rayleigh", "neither",
                      "alpha");
    EXPECT_LOAD_ERROR(CHAIN "damping: {rayleigh: {ratios: [0.01], frequencies: [1, 2]}}\n", 10,
                      "damping.rayleigh.ratios", "expected 2 values", "two values");
    EXPECT_LOAD_ERROR(CHAIN "damping: {rayleigh: {ratios: [0.5, 0.001],\n" /* 10 */
                            "  frequencies: [60, 200]}}\n",
                      10, "damping.rayleigh.ratios", "negative", "Rayleigh");
    EXPECT_LOAD_ERROR(CHAIN "damping: {rayleigh: {ratios: [0.01, 0.02],\n" /* 10 */
                            "  frequencies: [50 Hz, 50 Hz]}}\n",
                      11, "damping.rayleigh.frequencies", "do not fix", "different");
    EXPECT_LOAD_ERROR(CHAIN "damping: {rayleigh: {alpha: -1}}\n", 10, "damping.rayleigh.alpha",
                      "negative", "zero or more");
    EXPECT_LOAD_ERROR(CHAIN "damping: {viscous: 1}\n", 10, "damping.viscous", "unknown key",
                      "rayleigh");
}

RUN_TESTS(T(alpha_beta_give_c_plus_alpha_m_plus_beta_k), T(ratio_formula_hand_values),
          T(ratios_reproduce_the_modal_damping_of_two_modes), T(rayleigh_errors_are_located))
