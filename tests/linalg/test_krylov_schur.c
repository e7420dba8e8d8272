/* The Krylov-Schur eigensolver on an operator with a known spectrum: a block-diagonal
 * matrix (2 x 2 rotation-scaling blocks for conjugate pairs, real entries between)
 * whose magnitudes decay like shift-inverted structural modes. Checked: the
 * largest-magnitude eigenvalues, both members of each pair, the eigenvector
 * residuals, and the same answer whether the first pass converges alone or restarts
 * are needed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "system/system_impl.h"

#define N 240

/* y = A x for A block diagonal: blocks of size 2 [a -b; b a] (eigenvalues a +- ib) for
 * even block index, then real diagonal entries */
typedef struct blocks {
    double a[N], b[N]; /* per row pair: a, b (b = 0 marks two real entries a, b2) */
    double r2[N];
} blocks;

static void apply(void *ctx, const double *x, double *y)
{
    const blocks *B = ctx;
    for (int i = 0; i < N; i += 2) {
        if (B->b[i] != 0) {
            y[i] = B->a[i] * x[i] - B->b[i] * x[i + 1];
            y[i + 1] = B->b[i] * x[i] + B->a[i] * x[i + 1];
        } else {
            y[i] = B->a[i] * x[i];
            y[i + 1] = B->r2[i] * x[i + 1];
        }
    }
}

/* magnitudes decay geometrically like shift-inverted structural modes; every third
 * block is a pair of reals */
static void make(blocks *B)
{
    memset(B, 0, sizeof *B);
    for (int i = 0, k = 0; i < N; i += 2, k++) {
        double mag = pow(0.93, k);
        if (k % 3 == 2) {
            B->a[i] = mag;
            B->r2[i] = -0.97 * mag;
        } else {
            B->a[i] = -0.01 * mag;
            B->b[i] = mag;
        }
    }
}

static double smallest_magnitude(const gd_ks_result *r)
{
    /* every returned value must be one of the largest in magnitude */
    double mn = INFINITY;
    for (int i = 0; i < r->nconv; i++) {
        double m = hypot(r->mu_re[i], r->mu_im[i]);
        if (m < mn) mn = m;
    }
    return mn;
}

static void check_result(gd_test_state *gd_ts_, const blocks *B, const gd_ks_result *r, int nev)
{
    CHECK(r->nconv >= nev);
    /* the wanted ones are the first nev/2-odd blocks: magnitude >= 0.93^(blocks-1) */
    int nblocks = 0, cnt = 0;
    while (cnt < nev) {
        cnt += 2;
        nblocks++;
    }
    CHECK(smallest_magnitude(r) >= pow(0.93, nblocks - 1) * (1 - 1e-12));
    for (int c = 0; c < r->nconv; c++) {
        /* residual |A v - mu v| with v = vr + i vi */
        double vr[N], vi[N], ar[N], ai[N];
        memcpy(vr, r->vec_re + (size_t)c * N, sizeof vr);
        memcpy(vi, r->vec_im + (size_t)c * N, sizeof vi);
        apply((void *)B, vr, ar);
        apply((void *)B, vi, ai);
        double res = 0, mr = r->mu_re[c], mi = r->mu_im[c];
        for (int i = 0; i < N; i++) {
            double er = ar[i] - (mr * vr[i] - mi * vi[i]), ei = ai[i] - (mr * vi[i] + mi * vr[i]);
            res += er * er + ei * ei;
        }
        CHECK_ABS(sqrt(res), 0, 1e-9);
        /* the eigenvalue is exactly one of the blocks' */
        double best = INFINITY;
        for (int i = 0; i < N; i += 2) {
            double d1, d2;
            if (B->b[i] != 0) {
                d1 = hypot(mr - B->a[i], mi - B->b[i]);
                d2 = hypot(mr - B->a[i], mi + B->b[i]);
            } else {
                d1 = hypot(mr - B->a[i], mi);
                d2 = hypot(mr - B->r2[i], mi);
            }
            best = fmin(best, fmin(d1, d2));
        }
        CHECK_ABS(best, 0, 1e-10);
    }
    /* conjugate pairs come together: the imaginary parts sum to zero */
    double sum = 0;
    for (int c = 0; c < r->nconv; c++)
        sum += r->mu_im[c];
    CHECK_ABS(sum, 0, 1e-12);
}

/* A generous basis converges in the first pass (no restart). */
TEST(first_pass_converges)
{
    blocks B;
    make(&B);
    gd_ks_result r;
    REQUIRE(gd_krylov_schur(apply, &B, N, N, 20, 2 * 20 + 30, 1e-11, 50, NULL, &r) == GD_OK);
    CHECK(r.iterations == 0);
    check_result(gd_ts_, &B, &r, 20);
    gd_ks_result_free(&r);
}

/* A tight basis needs restarts (Schur form, reordering, thick restart) and still gives
 * the same eigenvalues; only the first nout rows of the vectors come back when asked. */
TEST(restarts_give_the_same_answer)
{
    blocks B;
    make(&B);
    gd_ks_result r, f;
    REQUIRE(gd_krylov_schur(apply, &B, N, N, 20, 28, 1e-11, 200, NULL, &r) == GD_OK);
    CHECK(r.iterations > 0);
    check_result(gd_ts_, &B, &r, 20);
    REQUIRE(gd_krylov_schur(apply, &B, N, N / 2, 20, 2 * 20 + 30, 1e-11, 50, NULL, &f) == GD_OK);
    CHECK(f.nconv == r.nconv);
    for (int c = 0; c < f.nconv && c < r.nconv; c++) {
        double best = INFINITY;
        for (int k = 0; k < r.nconv; k++)
            best = fmin(best, hypot(f.mu_re[c] - r.mu_re[k], f.mu_im[c] - r.mu_im[k]));
        CHECK_ABS(best, 0, 1e-12);
    }
    gd_ks_result_free(&r);
    gd_ks_result_free(&f);
}

/* Too few restarts allowed: a numerical failure, nothing returned. */
TEST(no_convergence_is_reported)
{
    blocks B;
    make(&B);
    gd_ks_result r;
    CHECK(gd_krylov_schur(apply, &B, N, N, 20, 24, 1e-14, 0, NULL, &r) == GD_ENUMERIC);
    CHECK(r.nconv == 0 && r.mu_re == NULL && r.vec_re == NULL);
}

/* Exactly repeated eigenvalues among the wanted ones: blocks 0 and 1 the same pair
 * (a double conjugate pair of magnitude 1), block 2 two equal reals 0.9 and block 5 a
 * third 0.9 (a triple). A single start vector meets each repeated eigenspace in one
 * direction only, so before the deflated checks one copy of each was returned and the
 * next values took their places. Every copy must come back, with independent vectors
 * (Gram determinant of the unit vectors of each value > 0.5; 1 when orthogonal). */
TEST(repeated_eigenvalues_are_all_found)
{
    blocks B;
    make(&B);
    B.a[2] = B.a[0];
    B.b[2] = B.b[0];
    B.a[4] = 0.9;
    B.r2[4] = 0.9;
    B.a[10] = 0.9;
    gd_ks_result r;
    /* 4 (double pair) + 3 (triple) + 2 + 2 (the pairs of blocks 3 and 4) */
    REQUIRE(gd_krylov_schur(apply, &B, N, N, 11, 2 * 11 + 12, 1e-11, 200, NULL, &r) == GD_OK);
    CHECK(r.nconv == 11);
    int npair = 0, ntriple = 0, ipair[4], itriple[3];
    for (int c = 0; c < r.nconv; c++) {
        if (hypot(r.mu_re[c] - B.a[0], r.mu_im[c] - B.b[0]) < 1e-10 && npair < 4)
            ipair[npair++] = c;
        if (hypot(r.mu_re[c] - 0.9, r.mu_im[c]) < 1e-10 && ntriple < 3) itriple[ntriple++] = c;
    }
    CHECK(npair == 2); /* + i b: twice (and - i b twice, not counted) */
    CHECK(ntriple == 3);
    CHECK(smallest_magnitude(&r) >= pow(0.93, 4) * (1 - 1e-12));
    if (ntriple == 3) { /* the 3 x 3 Gram matrix of real unit vectors */
        double g[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double *x = r.vec_re + (size_t)itriple[i] * N,
                             *y = r.vec_re + (size_t)itriple[j] * N;
                double s = 0;
                for (int k = 0; k < N; k++)
                    s += x[k] * y[k];
                g[i][j] = s;
            }
        double det = g[0][0] * (g[1][1] * g[2][2] - g[1][2] * g[2][1]) -
                     g[0][1] * (g[1][0] * g[2][2] - g[1][2] * g[2][0]) +
                     g[0][2] * (g[1][0] * g[2][1] - g[1][1] * g[2][0]);
        CHECK(det > 0.5);
    }
    if (npair == 2) { /* |<x, y>|^2 of the two complex unit vectors */
        const double *xr = r.vec_re + (size_t)ipair[0] * N, *xi = r.vec_im + (size_t)ipair[0] * N;
        const double *yr = r.vec_re + (size_t)ipair[1] * N, *yi = r.vec_im + (size_t)ipair[1] * N;
        double sr = 0, si = 0;
        for (int k = 0; k < N; k++) {
            sr += xr[k] * yr[k] + xi[k] * yi[k];
            si += xr[k] * yi[k] - xi[k] * yr[k];
        }
        CHECK(1 - (sr * sr + si * si) > 0.5);
    }
    /* residuals |A v - mu v| of every returned pair */
    for (int c = 0; c < r.nconv; c++) {
        double vr[N], vi[N], ar[N], ai[N], res = 0, mr = r.mu_re[c], mi = r.mu_im[c];
        memcpy(vr, r.vec_re + (size_t)c * N, sizeof vr);
        memcpy(vi, r.vec_im + (size_t)c * N, sizeof vi);
        apply(&B, vr, ar);
        apply(&B, vi, ai);
        for (int i = 0; i < N; i++) {
            double er = ar[i] - (mr * vr[i] - mi * vi[i]), ei = ai[i] - (mr * vi[i] + mi * vr[i]);
            res += er * er + ei * ei;
        }
        CHECK_ABS(sqrt(res), 0, 1e-9);
    }
    gd_ks_result_free(&r);
}

RUN_TESTS(T(first_pass_converges), T(restarts_give_the_same_answer), T(no_convergence_is_reported),
          T(repeated_eigenvalues_are_all_found))
