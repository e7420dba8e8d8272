/* The laws of the registry in the linear analyses (src/system/law_state.c): the static
 * equilibrium of a rigid rotor on two short journal bearings follows Ocvirk's load
 * capacity and attitude angle at every speed; the system's K and D at the journal are
 * the short-bearing closed forms at that equilibrium; a mass on a rolling-element
 * bearing under its weight has the modal frequencies of Harris & Kotzalas's
 * load-deflection relation; a model without laws is untouched. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/modal.h"
#include "harness.h"
#include "model_support.h"
#include "short_bearing_reference.h"

/* examples/journal_rotor.yaml: 20 kg on each bearing, mu 0.02 Pa s, R 25 mm, L 10 mm,
 * c 50 um, springs 1e11 N/m between the two halves. */
static const double MU = 0.02, RAD = 0.025, LEN = 0.01, CL = 50e-6, WLOAD = 20 * 9.81;

/* Ocvirk's load capacity of a pi film at eccentricity ratio e and speed w. */
static double ocvirk_load(double e, double w)
{
    double s2 = 1 - e * e;
    return MU * w * RAD * pow(LEN, 3) / (4 * CL * CL) * e * sqrt(M_PI * M_PI * s2 + 16 * e * e) /
           (s2 * s2);
}

TEST(journal_equilibrium_follows_sommerfeld)
{
    fx f;
    REQUIRE(load(&f, "examples/journal_rotor.yaml", NULL));
    REQUIRE(f.s->nlaws == 2);
    int n = f.s->ndof, ix = dof(&f, "left", GD_X), iy = dof(&f, "left", GD_Y);
    double *q = malloc((size_t)n * sizeof *q);
    const double speeds[4] = {300, 600, 1200, 2400};
    for (int k = 0; k < 4; k++) {
        REQUIRE(gd_system_law_state(f.s, speeds[k], q) == 1);
        double e = hypot(q[ix], q[iy]) / CL;
        /* the film carries the weight (the springs carry nothing: both halves alike) */
        CHECK_REL(ocvirk_load(e, speeds[k]), WLOAD, 1e-8);
        /* attitude: angle from the load line (-y) to the displacement */
        double phi = acos(-q[iy] / (e * CL));
        CHECK_REL(phi, atan(M_PI * sqrt(1 - e * e) / (4 * e)), 1e-8);
        printf("  %6.0f rad/s: eps %.6f, attitude %.4f deg\n", speeds[k], e, phi * 180 / M_PI);
    }
    /* at rest the film carries nothing: no equilibrium, linearised about the centre */
    CHECK(gd_system_law_state(f.s, 0.0, q) == 0);
    CHECK(q[ix] == 0 && q[iy] == 0);
    free(q);
    fx_free(&f);
}

TEST(journal_coefficients_in_the_system_matrices)
{
    fx f;
    REQUIRE(load(&f, "examples/journal_rotor.yaml", NULL));
    int n = f.s->ndof, id[2] = {dof(&f, "left", GD_X), dof(&f, "left", GD_Y)};
    double *K = malloc((size_t)n * n * sizeof *K), *D = malloc((size_t)n * n * sizeof *D);
    double *q = malloc((size_t)n * sizeof *q);
    const double w = 1200.0;
    gd_system_dense(f.s, w, NULL, D, K);
    REQUIRE(gd_system_law_state(f.s, w, q) == 1);
    double e = hypot(q[id[0]], q[id[1]]) / CL, a[4], b[4];
    short_bearing_coefficients(e, a, b);
    /* load along -y: the closed forms' y is -y, their x is -x; the sign flips cancel */
    double amax = 0, bmax = 0, ka = 0, kb = 0;
    for (int m = 0; m < 4; m++) {
        amax = fmax(amax, fabs(a[m]));
        bmax = fmax(bmax, fabs(b[m]));
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double kij = K[id[i] + (size_t)id[j] * n] - (i == j ? 1e11 : 0.0); /* the spring */
            double cij = D[id[i] + (size_t)id[j] * n];
            double an = kij * CL / WLOAD, bn = cij * CL * w / WLOAD;
            CHECK_ABS(an, a[2 * i + j], 1e-6 * amax);
            CHECK_ABS(bn, b[2 * i + j], 1e-6 * bmax);
            ka = fmax(ka, fabs(an - a[2 * i + j]) / amax);
            kb = fmax(kb, fabs(bn - b[2 * i + j]) / bmax);
        }
    printf("  eps %.4f at %.0f rad/s: stiffness off by %.2g, damping by %.2g (of the largest)\n", e,
           w, ka, kb);
    free(K);
    free(D);
    free(q);
    fx_free(&f);
}

/* A 10 kg mass on a deep-groove ball bearing (6205 geometry, Z = 9, K = 8e9 N/m^1.5, no
 * clearance) under its weight along -y, element 0 at the bottom. Harris & Kotzalas
 * (Rolling Bearing Analysis, 5th ed., 2006, ch. 7): with zero clearance element j at
 * psi_j from the load line deflects delta cos(psi_j), so F = K delta^n S_(n+1) with
 * S_p = sum over the loaded elements of cos^p(psi_j), and the stiffness is
 * k_y = n K delta^(n-1) S_(n+1) = n F / delta, k_x = n K delta^(n-1) sum cos^(n-1) sin^2.
 * The modal frequencies are sqrt(k / m) (no damping). Against Harris's integral
 * J_r(1/2) = 0.2288 (F = Z K delta^n J_r): the 9 discrete balls differ by a few per cent. */
static const char *ROLLING = "title: mass on a ball bearing\n"
                             "dofs: [x, y]\n"
                             "gravity: {direction: [0, -1, 0], g: 9.81}\n"
                             "shafts:\n"
                             "  - name: s\n"
                             "    nodes: [{name: m}]\n"
                             "disks:\n"
                             "  - {name: m, node: m, mass: 10}\n"
                             "laws:\n"
                             "  - {type: rolling_bearing, name: b, node: m, elements: 9,\n"
                             "     contact_stiffness: 8e9, pitch_diameter: 39.04 mm,\n"
                             "     element_diameter: 7.94 mm, phase: -90 deg}\n";

TEST(rolling_bearing_stiffness_in_modal)
{
    fx f;
    REQUIRE(load(&f, NULL, ROLLING));
    const double m = 10, F = m * 9.81, Kc = 8e9, nh = 1.5;
    double S = 0, Sx = 0;
    for (int j = 0; j < 9; j++) {
        double psi = 2 * M_PI * j / 9, c = cos(psi), s = sin(psi);
        if (c <= 0) continue;
        S += pow(c, nh + 1);
        Sx += pow(c, nh - 1) * s * s;
    }
    double delta = pow(F / (Kc * S), 1 / nh);
    double ky = nh * F / delta, kx = nh * Kc * pow(delta, nh - 1) * Sx;
    double *q = malloc(2 * sizeof *q);
    REQUIRE(gd_system_law_state(f.s, 100.0, q) == 1);
    CHECK_REL(-q[dof(&f, "m", GD_Y)], delta, 1e-8);
    CHECK_ABS(q[dof(&f, "m", GD_X)], 0.0, 1e-12 * delta);
    gd_modal_options opt;
    gd_modal_options_init(&opt);
    opt.speed = 100.0;
    gd_modal_result *r = NULL;
    gd_error err;
    REQUIRE(gd_modal_solve(f.s, &opt, &r, &err) == GD_OK);
    REQUIRE(r->nmodes == 2);
    double wx = sqrt(kx / m), wy = sqrt(ky / m);
    CHECK_REL(r->modes[0].omega_n, fmin(wx, wy), 1e-7);
    CHECK_REL(r->modes[1].omega_n, fmax(wx, wy), 1e-7);
    /* Harris's continuous load zone: delta = (F / (Z K J_r))^(1/n) */
    double dh = pow(F / (9 * Kc * 0.2288), 1 / nh), kh = nh * F / dh;
    printf("  delta %.4g m (J_r: %.4g), k_y %.4g N/m (J_r: %.4g), k_x %.4g N/m: %.2f, %.2f Hz\n",
           delta, dh, ky, kh, kx, r->modes[0].frequency_hz, r->modes[1].frequency_hz);
    CHECK_REL(ky, kh, 0.05);
    gd_modal_free(r);
    free(q);
    fx_free(&f);
}

/* No laws: the dense matrices are the linear ones (the same as gd_system_matrices). */
TEST(no_laws_nothing_added)
{
    fx f;
    REQUIRE(load(&f, "examples/kumar2011_coupled.yaml", NULL));
    REQUIRE(f.s->nlaws == 0);
    int n = f.s->ndof;
    double *K = calloc((size_t)n * n, sizeof *K), *q = malloc((size_t)n * sizeof *q);
    gd_system_dense(f.s, 300.0, NULL, NULL, K);
    gd_csc Ks = {0};
    gd_error err;
    REQUIRE(gd_system_matrices(f.s, 300.0, NULL, &Ks, NULL, NULL, &err) == GD_OK);
    for (int j = 0; j < n; j++)
        for (int p = Ks.colptr[j]; p < Ks.colptr[j + 1]; p++)
            K[Ks.rowind[p] + (size_t)j * n] -= Ks.values[p];
    double worst = 0;
    for (size_t i = 0; i < (size_t)n * n; i++)
        worst = fmax(worst, fabs(K[i]));
    CHECK(worst == 0.0);
    CHECK(gd_system_law_state(f.s, 300.0, q) == 1);
    gd_csc_free(&Ks);
    free(K);
    free(q);
    fx_free(&f);
}

RUN_TESTS(T(journal_equilibrium_follows_sommerfeld), T(journal_coefficients_in_the_system_matrices),
          T(rolling_bearing_stiffness_in_modal), T(no_laws_nothing_added))
