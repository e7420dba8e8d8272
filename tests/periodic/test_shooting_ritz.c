/* The residuals of Ritz values (src/linalg/ritz.c) and the stability verdict they allow
 * (gd_ritz_verdict, used by the matrix-free shooting's multipliers): on a small monodromy-like
 * matrix with the wind-turbine gearbox's spectrum in miniature (docs/planetary.md: six
 * lightly damped pairs within 1e-3 of the unit circle, the rest well inside), block upper
 * triangular so its eigenvalues are known. Checked: each residual |h_{m+1,m}| |e_m^T s_j|
 * equals |A x - theta x| of its Ritz vector, m = N steps give the dense eigenvalues with
 * residuals at rounding, and 8 steps, whose values near 1 are not converged, give no verdict
 * where the full space says stable (one pair at 1.5 is a converged "unstable"). */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "linalg/linalg_impl.h"

#define N 24

typedef struct mono {
    double A[N * N]; /* column-major */
} mono;

static int apply(void *data, const double *x, double *y)
{
    const mono *m = data;
    for (int i = 0; i < N; i++) {
        double s = 0.0;
        for (int j = 0; j < N; j++)
            s += m->A[j * N + i] * x[j];
        y[i] = s;
    }
    return 0;
}

/* pairs r_k exp(+-i phi_k): k < 6 within 1e-3 of 1 (r = 0.9990 + 1e-4 k), the rest 0.3-0.8;
 * with outside, pair 0 at 1.5. Coupling above the 2 x 2 blocks. */
static void build(mono *m, int outside)
{
    memset(m->A, 0, sizeof m->A);
    for (int k = 0; k < N / 2; k++) {
        double r = k < 6 ? 0.9990 + 1e-4 * k : 0.3 + 0.5 * (k - 6) / 6.0;
        if (outside && k == 0) r = 1.5;
        const double ph = 0.04 + 0.3 * k, c = r * cos(ph), s = r * sin(ph);
        const int i = 2 * k;
        m->A[i * N + i] = c;
        m->A[(i + 1) * N + i + 1] = c;
        m->A[(i + 1) * N + i] = s;
        m->A[i * N + i + 1] = -s;
        for (int j = i + 2; j < N; j++) {
            m->A[j * N + i] = 0.02 * sin(1.0 + i + 2.0 * j);
            m->A[j * N + i + 1] = 0.02 * cos(2.0 + i + j);
        }
    }
}

/* Arnoldi m steps from the shooting's start vector: V, H allocated here */
static int arnoldi(mono *a, int m, double **V, double **H)
{
    double v0[N];
    for (int i = 0; i < N; i++)
        v0[i] = 1.0 + 0.5 * sin(1.0 + i);
    *V = malloc(sizeof **V * N * (m + 1));
    *H = malloc(sizeof **H * (m + 1) * m);
    int steps = 0;
    if (gd_arnoldi(apply, a, N, v0, m, *V, *H, &steps, 0.0, NULL)) return -1;
    return steps;
}

TEST(ritz_residual_is_the_true_residual)
{
    static mono a;
    build(&a, 0);
    const int m = 8;
    double *V, *H, re[N], im[N], res[N], Hs[N * N], S[N * N], wre[N], wim[N], dummy[1];
    CHECK(arnoldi(&a, m, &V, &H) == m);
    CHECK(gd_ritz(H, m + 1, m, re, im, res) == 0);
    for (int c = 0; c < m; c++)
        for (int r = 0; r < m; r++)
            Hs[c * m + r] = H[c * (m + 1) + r];
    CHECK(LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', m, Hs, m, wre, wim, dummy, 1, S, m) == 0);
    double worst = 0.0, rmin = INFINITY;
    for (int j = 0; j < m; j++) {
        CHECK(wre[j] == re[j] && wim[j] == im[j]);
        /* x = V s_j (complex for a pair), |A x - theta x| by products */
        const int pair = im[j] != 0.0, c0 = pair && im[j] < 0 ? j - 1 : j;
        const double sg = pair && im[j] < 0 ? -1.0 : 1.0;
        double xr[N], xi[N], ar[N], ai[N];
        for (int i = 0; i < N; i++) {
            xr[i] = xi[i] = 0.0;
            for (int l = 0; l < m; l++) {
                xr[i] += V[l * N + i] * S[c0 * m + l];
                if (pair) xi[i] += sg * V[l * N + i] * S[(c0 + 1) * m + l];
            }
        }
        apply(&a, xr, ar);
        apply(&a, xi, ai);
        double r2 = 0.0;
        for (int i = 0; i < N; i++) {
            const double complex d =
                (ar[i] + I * ai[i]) - (re[j] + I * im[j]) * (xr[i] + I * xi[i]);
            r2 += creal(d) * creal(d) + cimag(d) * cimag(d);
        }
        worst = fmax(worst, fabs(sqrt(r2) - res[j]) / fmax(res[j], 1e-12));
        rmin = fmin(rmin, res[j]);
    }
    printf("  8 steps: residuals %.2g and up, formula against products within %.2g relative\n",
           rmin, worst);
    CHECK(rmin > 1e-6); /* not converged: the test means something */
    CHECK(worst <= 1e-8);
    free(V);
    free(H);
}

TEST(full_space_ritz_values_are_the_dense_eigenvalues)
{
    static mono a;
    build(&a, 0);
    double *V, *H, re[N], im[N], res[N], A[N * N], dre[N], dim[N], dummy[1];
    CHECK(arnoldi(&a, N, &V, &H) == N);
    CHECK(gd_ritz(H, N + 1, N, re, im, res) == 0);
    memcpy(A, a.A, sizeof A);
    CHECK(LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', N, A, N, dre, dim, dummy, 1, dummy, 1) == 0);
    double worst = 0.0, rmax = 0.0;
    for (int i = 0; i < N; i++) {
        double best = INFINITY;
        for (int j = 0; j < N; j++)
            best = fmin(best, hypot(re[j] - dre[i], im[j] - dim[i]));
        worst = fmax(worst, best);
        rmax = fmax(rmax, res[i]);
    }
    printf("  %d steps: Ritz values within %.2g of dense dgeev, residuals up to %.2g\n", N, worst,
           rmax);
    CHECK(worst <= 1e-9);
    CHECK(rmax <= 1e-12);
    CHECK(gd_ritz_verdict(re, im, res, N, 1.0 + 1e-6) == 1);
    free(V);
    free(H);
}

TEST(an_unconverged_value_near_one_is_not_a_verdict)
{
    static mono a;
    build(&a, 0);
    double *V, *H, re[N], im[N], res[N];
    CHECK(arnoldi(&a, 8, &V, &H) == 8);
    CHECK(gd_ritz(H, 9, 8, re, im, res) == 0);
    double mu = 0.0;
    for (int j = 0; j < 8; j++)
        mu = fmax(mu, hypot(re[j], im[j]));
    printf("  8 steps on the stable cluster: largest Ritz |mu| %.6f, verdict %d\n", mu,
           gd_ritz_verdict(re, im, res, 8, 1.0 + 1e-6));
    CHECK(gd_ritz_verdict(re, im, res, 8, 1.0 + 1e-6) == -1);
    free(V);
    free(H);
    /* a pair well outside converges first: a verdict (unstable) from 8 steps */
    build(&a, 1);
    CHECK(arnoldi(&a, 8, &V, &H) == 8);
    CHECK(gd_ritz(H, 9, 8, re, im, res) == 0);
    printf("  8 steps with a pair at 1.5: Ritz |mu| %.6f, residual %.2g\n", hypot(re[0], im[0]),
           res[0]);
    CHECK(gd_ritz_verdict(re, im, res, 8, 1.0 + 1e-6) == 0);
    free(V);
    free(H);
    /* the rule itself: outside by more than the residual, inside by more, or neither */
    const double r1[] = {1.0068, 0.5}, i1[] = {0.0399, 0.0};
    const double big[] = {0.05, 0.3}, small[] = {1e-4, 0.3}, in[] = {0.9996, 0.5},
                 e0[] = {0.0, 0.0}, rin[] = {1e-5, 0.4}, rwide[] = {1e-3, 0.4};
    CHECK(gd_ritz_verdict(r1, i1, big, 2, 1.0 + 1e-6) == -1);
    CHECK(gd_ritz_verdict(r1, i1, small, 2, 1.0 + 1e-6) == 0);
    CHECK(gd_ritz_verdict(in, e0, rin, 2, 1.0 + 1e-6) == 1);
    CHECK(gd_ritz_verdict(in, e0, rwide, 2, 1.0 + 1e-6) == -1);
}

RUN_TESTS(T(ritz_residual_is_the_true_residual),
          T(full_space_ritz_values_are_the_dense_eigenvalues),
          T(an_unconverged_value_near_one_is_not_a_verdict))
