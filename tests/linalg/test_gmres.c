/* Matrix-free GMRES and Arnoldi (src/linalg/gmres.c) on a tridiagonal operator with a known
 * solution and spectrum: A = tridiag(-1, 3, -1.5) (non-symmetric, eigenvalues
 * 3 - 2 sqrt(1.5) cos(k pi / (n + 1)), all real). Checked: GMRES reaches its tolerance in
 * the true residual, one full cycle solves to rounding, restarts reach what one cycle
 * cannot, a failing product is reported, and m = n Arnoldi steps' Hessenberg matrix has
 * A's eigenvalues. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "linalg/linalg_impl.h"

#define N 30

typedef struct tri {
    int products, fail_at;
} tri;

static int apply(void *data, const double *x, double *y)
{
    tri *t = data;
    if (++t->products == t->fail_at) return 1;
    for (int i = 0; i < N; i++)
        y[i] = 3.0 * x[i] - (i > 0 ? x[i - 1] : 0.0) - 1.5 * (i + 1 < N ? x[i + 1] : 0.0);
    return 0;
}

/* |b - A x| / |b| */
static double residual(const double *b, const double *x)
{
    tri t = {0, 0};
    double y[N], r = 0.0, nb = 0.0;
    apply(&t, x, y);
    for (int i = 0; i < N; i++) {
        r += (b[i] - y[i]) * (b[i] - y[i]);
        nb += b[i] * b[i];
    }
    return sqrt(r / nb);
}

TEST(one_cycle_to_tolerance_and_to_rounding)
{
    double b[N], x[N];
    for (int i = 0; i < N; i++)
        b[i] = sin(1.0 + i);
    tri t = {0, 0};
    CHECK(gd_gmres(apply, &t, N, N, b, x, 1e-6, 1e-12, 1) == 0);
    const double r = residual(b, x);
    CHECK(r <= 1e-6);
    CHECK(r > 1e-12); /* stopped at the tolerance, not beyond */
    CHECK(t.products < N);
    tri t2 = {0, 0};
    CHECK(gd_gmres(apply, &t2, N, N, b, x, 0.0, 0.0, 1) == 0);
    CHECK(residual(b, x) <= 1e-13);
}

TEST(restarts_reach_what_one_short_cycle_cannot)
{
    double b[N], x[N];
    for (int i = 0; i < N; i++)
        b[i] = cos(0.3 * i);
    tri t = {0, 0};
    CHECK(gd_gmres(apply, &t, N, 5, b, x, 1e-10, 1e-20, 1) == 0);
    const double one = residual(b, x);
    tri t2 = {0, 0};
    CHECK(gd_gmres(apply, &t2, N, 5, b, x, 1e-10, 1e-16, 40) == 0);
    const double many = residual(b, x);
    CHECK(one > 1e-3);
    CHECK(many <= 1e-8);
}

TEST(a_failing_product_is_reported)
{
    double b[N], x[N];
    for (int i = 0; i < N; i++)
        b[i] = 1.0;
    tri t = {0, 3};
    CHECK(gd_gmres(apply, &t, N, N, b, x, 1e-12, 1e-24, 2) == 1);
}

TEST(arnoldi_hessenberg_has_the_spectrum)
{
    const int m = N;
    double v0[N], *V = malloc(sizeof *V * N * (m + 1)), *H = malloc(sizeof *H * (m + 1) * m),
                  Hs[N * N], re[N], im[N], dummy[1];
    for (int i = 0; i < N; i++)
        v0[i] = 1.0 + 0.5 * sin(1.0 + i);
    tri t = {0, 0};
    int steps = 0;
    CHECK(gd_arnoldi(apply, &t, N, v0, m, V, H, &steps, 0.0, NULL) == 0);
    CHECK(steps == N);
    for (int c = 0; c < steps; c++)
        for (int r = 0; r < steps; r++)
            Hs[c * steps + r] = H[c * (m + 1) + r];
    CHECK(LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', steps, Hs, steps, re, im, dummy, 1, dummy, 1) ==
          0);
    /* every exact eigenvalue has a computed one close by */
    double worst = 0.0;
    for (int k = 1; k <= N; k++) {
        const double lam = 3.0 - 2.0 * sqrt(1.5) * cos(k * M_PI / (N + 1));
        double best = INFINITY;
        for (int i = 0; i < steps; i++)
            best = fmin(best, hypot(re[i] - lam, im[i]));
        worst = fmax(worst, best);
    }
    printf("  Arnoldi, %d steps: eigenvalues within %.2g of the exact ones\n", steps, worst);
    /* measured 5e-8: the non-normal matrix (eigenvector condition about 1.5^15) and plain
     * modified Gram-Schmidt over all N steps */
    CHECK(worst <= 1e-6);
    free(V);
    free(H);
}

RUN_TESTS(T(one_cycle_to_tolerance_and_to_rounding), T(restarts_reach_what_one_short_cycle_cannot),
          T(a_failing_product_is_reported), T(arnoldi_hessenberg_has_the_spectrum))
