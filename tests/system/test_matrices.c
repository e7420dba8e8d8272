/* gd_system_matrices: the sparse M, K(W), C(W) and G against the dense matrices of
 * gd_system_dense (D = C(W) + W G), their form (sorted rows, no stored zeros, symmetry
 * of M, K and C, skew-symmetry of G), speed-table bearings at two speeds, NULL outputs
 * and a non-finite speed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "model_support.h"

#define RIG "examples/rig2018.yaml"

/* The oil-film bearing of docs/model-format.md ("Speed tables"). */
static const char OIL_FILM[] = "shafts:\n"
                               "  - name: rotor\n"
                               "    nodes: [{name: journal}, {name: housing}]\n"
                               "disks:\n"
                               "  - {node: journal, mass: 20, polar_inertia: 0.1}\n"
                               "  - {node: housing, mass: 50}\n"
                               "bearings:\n"
                               "  - name: oil_film\n"
                               "    node: journal\n"
                               "    to: housing\n"
                               "    table:\n"
                               "      - {speed: 0, k: 1e8, c: 2e3}\n"
                               "      - {speed: 3000 rpm, kxx: 8e7, kyy: 1.2e8, kxy: 3e7, "
                               "kyx: -3e7, c: 1.5e3}\n"
                               "      - {speed: 6000 rpm, kxx: 6e7, kyy: 1.1e8, kxy: 5e7, "
                               "kyx: -5e7, c: 1.2e3}\n"
                               "  - {name: pedestal, node: housing, k: 5e8, c: 1e4}\n";

/* Dense column-major copy of a. */
static double *dense(const gd_csc *a)
{
    double *d = calloc((size_t)a->n * (size_t)a->n, sizeof *d);
    for (int j = 0; d && j < a->n; j++)
        for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++)
            d[a->rowind[k] + (size_t)j * a->n] = a->values[k];
    return d;
}

static double max_abs(const double *a, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(a[i]));
    return m;
}

/* Entry by entry: |a - b| <= tol |b|, with a floor of 1e-15 of the largest entry. */
static int close_to(const double *a, const double *b, size_t n, double tol)
{
    double floor_ = 1e-15 * max_abs(b, n);
    for (size_t i = 0; i < n; i++)
        if (fabs(a[i] - b[i]) > tol * fabs(b[i]) + floor_) {
            fprintf(stderr, "    entry %zu: %.17g vs %.17g\n", i, a[i], b[i]);
            return 0;
        }
    return 1;
}

/* sign +1: A = A^T; -1: A = -A^T (relative to the largest entry). */
static int symmetric(const double *a, int n, double sign, double tol)
{
    double s = tol * max_abs(a, (size_t)n * n);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (fabs(a[i + (size_t)j * n] - sign * a[j + (size_t)i * n]) > s) return 0;
    return 1;
}

/* Square n x n, rows strictly increasing within each column, no stored zero. */
static int well_formed(const gd_csc *a, int n)
{
    if (a->n != n || a->colptr[0] != 0) return 0;
    for (int j = 0; j < n; j++) {
        if (a->colptr[j + 1] < a->colptr[j]) return 0;
        for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++) {
            if (a->values[k] == 0.0 || a->rowind[k] < 0 || a->rowind[k] >= n) return 0;
            if (k > a->colptr[j] && a->rowind[k] <= a->rowind[k - 1]) return 0;
        }
    }
    return 1;
}

static void free4(gd_csc *m)
{
    for (int i = 0; i < 4; i++)
        gd_csc_free(&m[i]);
}

TEST(rig_equals_dense_at_speed)
{
    fx f;
    REQUIRE(load(&f, RIG, NULL));
    int n = f.s->ndof;
    size_t nn = (size_t)n * n;
    double W = 3000 * M_PI / 30;
    gd_csc m[4];
    gd_error e;
    REQUIRE(gd_system_matrices(f.s, W, &m[0], &m[1], &m[2], &m[3], &e) == GD_OK);
    for (int i = 0; i < 4; i++)
        CHECK(well_formed(&m[i], n));
    double *Md = malloc(nn * sizeof *Md), *Dd = malloc(nn * sizeof *Dd),
           *Kd = malloc(nn * sizeof *Kd);
    gd_system_dense(f.s, W, Md, Dd, Kd);
    double *M = dense(&m[0]), *K = dense(&m[1]), *C = dense(&m[2]), *G = dense(&m[3]);
    REQUIRE(M && K && C && G && Md && Dd && Kd);
    double *D = malloc(nn * sizeof *D);
    for (size_t i = 0; i < nn; i++)
        D[i] = C[i] + W * G[i];
    CHECK(close_to(M, Md, nn, 1e-12));
    CHECK(close_to(K, Kd, nn, 1e-12));
    CHECK(close_to(D, Dd, nn, 1e-12));
    CHECK(symmetric(M, n, 1, 1e-14));
    CHECK(symmetric(K, n, 1, 1e-14));
    CHECK(symmetric(C, n, 1, 1e-14)); /* no gyroscopic term in C */
    CHECK(symmetric(G, n, -1, 1e-14));
    CHECK(m[3].colptr[n] > 0); /* the rig spins: G is not zero */
    CHECK(m[0].colptr[n] > n); /* consistent mass of the shaft elements */
    /* the mesh stiffness 3.9e8 couples the two gears */
    int a = dof(&f, "gear48", GD_X), b = dof(&f, "gear32", GD_X);
    CHECK(K[a + (size_t)b * n] != 0.0);
    free(M), free(K), free(C), free(G), free(D), free(Md), free(Dd), free(Kd);
    free4(m);
    fx_free(&f);
}

TEST(speed_table_gives_k_at_the_speed)
{
    fx f;
    REQUIRE(load(&f, NULL, OIL_FILM));
    int n = f.s->ndof;
    int jx = dof(&f, "journal", GD_X), jy = dof(&f, "journal", GD_Y);
    REQUIRE(jx >= 0 && jy >= 0);
    gd_csc k0, k1, c1, m1[4];
    gd_error e;
    double W = 3000 * M_PI / 30;
    REQUIRE(gd_system_matrices(f.s, 0, NULL, &k0, NULL, NULL, &e) == GD_OK);
    REQUIRE(gd_system_matrices(f.s, W, NULL, &k1, &c1, NULL, &e) == GD_OK);
    double *K0 = dense(&k0), *K1 = dense(&k1), *C1 = dense(&c1);
    REQUIRE(K0 && K1 && C1);
    CHECK_REL(K0[jx + (size_t)jx * n], 1e8, 1e-12);
    CHECK(K0[jx + (size_t)jy * n] == 0.0);
    CHECK_REL(K1[jx + (size_t)jx * n], 8e7, 1e-9);
    CHECK_REL(K1[jy + (size_t)jy * n], 1.2e8, 1e-9);
    CHECK_REL(K1[jx + (size_t)jy * n], 3e7, 1e-9); /* kxy: row x, column y */
    CHECK_REL(K1[jy + (size_t)jx * n], -3e7, 1e-9);
    CHECK_REL(C1[jx + (size_t)jx * n], 1.5e3, 1e-9);
    /* and equal to the dense matrices at that speed */
    size_t nn = (size_t)n * n;
    double *Kd = malloc(nn * sizeof *Kd), *Dd = malloc(nn * sizeof *Dd);
    REQUIRE(Kd && Dd);
    gd_system_dense(f.s, W, NULL, Dd, Kd);
    REQUIRE(gd_system_matrices(f.s, W, &m1[0], &m1[1], &m1[2], &m1[3], &e) == GD_OK);
    double *G1 = dense(&m1[3]);
    REQUIRE(G1);
    for (size_t i = 0; i < nn; i++)
        G1[i] = C1[i] + W * G1[i];
    CHECK(close_to(K1, Kd, nn, 1e-12));
    CHECK(close_to(G1, Dd, nn, 1e-12));
    free(K0), free(K1), free(C1), free(G1), free(Kd), free(Dd);
    gd_csc_free(&k0), gd_csc_free(&k1), gd_csc_free(&c1);
    free4(m1);
    fx_free(&f);
}

TEST(non_finite_speed)
{
    fx f;
    REQUIRE(load(&f, RIG, NULL));
    gd_csc k = {0};
    gd_error e;
    gd_error_clear(&e);
    CHECK(gd_system_matrices(f.s, NAN, NULL, &k, NULL, NULL, &e) == GD_EINPUT);
    CHECK(strstr(e.message, "not finite") != NULL);
    CHECK_STR(e.field, "speed");
    CHECK(k.colptr == NULL && k.n == 0);
    CHECK(gd_system_matrices(f.s, INFINITY, NULL, &k, NULL, NULL, NULL) == GD_EINPUT);
    fx_free(&f);
}

RUN_TESTS(T(rig_equals_dense_at_speed), T(speed_table_gives_k_at_the_speed), T(non_finite_speed))
