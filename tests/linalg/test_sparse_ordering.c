/* The ordering KLU factors with (src/linalg/ordering.c): on a planetary set's pattern
 * (three hubs, sun, ring and carrier, each coupled to every planet), AMD's order is not
 * minimal and the analysis takes the exact minimum-degree one; where AMD is as good
 * (a chain) or minimum degree saves less than a quarter, the analysis is AMD's exactly. Flops
 * counted by KLU itself (klu_flops) after the numeric factorisation, so the prediction is checked
 * against what the factorisation did. */
#include <klu.h>

#include "harness.h"
#include "linalg/linalg_impl.h"

#define NMAX 32

typedef struct pat {
    gd_pattern p;
    int colptr[NMAX + 1], rowind[NMAX * NMAX], diag[NMAX];
    double x[NMAX * NMAX];
} pat;

/* The pattern of the symmetric adjacency adj (n x n, 1 = coupled) with its diagonal;
 * values diagonally dominant, so KLU pivots on the diagonal as the count assumes. */
static void make(pat *a, int n, const char adj[NMAX][NMAX])
{
    int q = 0;
    for (int j = 0; j < n; j++) {
        a->colptr[j] = q;
        for (int i = 0; i < n; i++)
            if (i == j || adj[i][j]) {
                if (i == j) a->diag[j] = q;
                a->x[q] = i == j ? 20.0 + j : 1.0 / (1.0 + i + j);
                a->rowind[q++] = i;
            }
    }
    a->colptr[n] = q;
    a->p =
        (gd_pattern){.n = n, .nnz = q, .colptr = a->colptr, .rowind = a->rowind, .diag = a->diag};
}

/* nh hubs coupled to each of np planets (scalar DOFs), copies times along the diagonal */
static void planetary(pat *a, int nh, int np, int copies)
{
    static char adj[NMAX][NMAX];
    memset(adj, 0, sizeof adj);
    int m = nh + np;
    for (int c = 0; c < copies; c++)
        for (int h = 0; h < nh; h++)
            for (int p = nh; p < m; p++)
                adj[c * m + h][c * m + p] = adj[c * m + p][c * m + h] = 1;
    make(a, copies * m, (const char(*)[NMAX])adj);
}

/* KLU's flop count of factoring a with the analysis sym (real values) */
static double factor_flops(const pat *a, klu_symbolic *sym)
{
    klu_common c;
    klu_defaults(&c);
    klu_numeric *num = klu_factor(a->p.colptr, a->p.rowind, (double *)a->x, sym, &c);
    if (!num) return -1;
    klu_flops(sym, num, &c);
    klu_free_numeric(&num, &c);
    return c.flops;
}

TEST(minimum_degree_where_amd_merges_the_hubs)
{
    /* sun, ring, carrier and 5 planets (K_{3,5}): after the first planet the three hubs
     * have the same neighbours, AMD merges them and ranks them by their external degree
     * (the 4 other planets), below a planet's 3 hubs: 167 flops. The planets first
     * (exact degree 3, 2 9 + 3 flops each), then the hubs' clique (2 4 + 2, 2 1 + 1):
     * 5 21 + 13 = 118 */
    pat a;
    planetary(&a, 3, 5, 1);
    klu_common c;
    klu_defaults(&c);
    klu_symbolic *amd = klu_analyze(a.p.n, a.p.colptr, a.p.rowind, &c);
    REQUIRE(amd);
    CHECK_ABS(amd->est_flops, 167, 0);
    CHECK_ABS(factor_flops(&a, amd), 167, 0);
    gd_splu_symbolic s;
    REQUIRE(gd_splu_analyze(&a.p, &s, NULL) == GD_OK);
    CHECK(s.nmd == 1);
    CHECK_ABS(s.sym->est_flops, 118, 0);
    CHECK_ABS(factor_flops(&a, s.sym), 118, 0);
    CHECK(s.sym->lnz < amd->lnz); /* 5 4 + 3 + 2 + 1 against AMD's 29 */
    CHECK_ABS(s.sym->lnz, 26, 0);
    /* the factors solve: A x = A 1 gives x = 1 */
    gd_splu lu;
    REQUIRE(gd_splu_factor(&lu, &a.p, &s, a.x, 0, 1) == 0);
    double b[NMAX] = {0};
    for (int j = 0; j < a.p.n; j++)
        for (int q = a.p.colptr[j]; q < a.p.colptr[j + 1]; q++)
            b[a.p.rowind[q]] += a.x[q];
    gd_splu_solve(&lu, &s, a.p.n, 1, b);
    for (int i = 0; i < a.p.n; i++)
        CHECK_REL(b[i], 1.0, 1e-14);
    gd_splu_free(&lu);
    gd_splu_symbolic_free(&s);
    klu_free_symbolic(&amd, &c);
}

TEST(each_block_chosen_on_its_own)
{
    /* two sets side by side: BTF finds two blocks, each ordered by minimum degree, and the
     * prediction is the sum (2 x 118) */
    pat a;
    planetary(&a, 3, 5, 2);
    gd_splu_symbolic s;
    REQUIRE(gd_splu_analyze(&a.p, &s, NULL) == GD_OK);
    CHECK(s.sym->nblocks == 2);
    CHECK(s.nmd == 2);
    CHECK_ABS(s.sym->est_flops, 236, 0);
    CHECK_ABS(factor_flops(&a, s.sym), 236, 0);
    gd_splu_symbolic_free(&s);
}

TEST(amd_kept_for_a_small_gain)
{
    /* 3 planets (K_{3,3}): minimum degree 76 flops against AMD's 91, 16 % fewer, less
     * than the quarter a new pivot order must save (GD_ORDER_GAIN): AMD's analysis */
    pat a;
    planetary(&a, 3, 3, 1);
    klu_common c;
    klu_defaults(&c);
    klu_symbolic *amd = klu_analyze(a.p.n, a.p.colptr, a.p.rowind, &c);
    gd_splu_symbolic s;
    REQUIRE(amd && gd_splu_analyze(&a.p, &s, NULL) == GD_OK);
    CHECK(s.nmd == 0);
    CHECK_ABS(s.sym->est_flops, 91, 0);
    CHECK_ABS(factor_flops(&a, s.sym), 91, 0);
    CHECK(!memcmp(s.sym->Q, amd->Q, (size_t)a.p.n * sizeof *amd->Q));
    gd_splu_symbolic_free(&s);
    klu_free_symbolic(&amd, &c);
}

TEST(amd_kept_where_it_is_as_good)
{
    /* a chain with two branches (no fill in either order): minimum degree does no better,
     * so the analysis is AMD's, permutation and estimates, as klu_analyze's own */
    static char adj[NMAX][NMAX];
    memset(adj, 0, sizeof adj);
    int n = 12;
    for (int i = 0; i + 1 < n; i++)
        if (i != 5) adj[i][i + 1] = adj[i + 1][i] = 1;
    adj[2][6] = adj[6][2] = 1;
    pat a;
    make(&a, n, (const char(*)[NMAX])adj);
    klu_common c;
    klu_defaults(&c);
    klu_symbolic *amd = klu_analyze(n, a.p.colptr, a.p.rowind, &c);
    gd_splu_symbolic s;
    REQUIRE(amd && gd_splu_analyze(&a.p, &s, NULL) == GD_OK);
    CHECK(s.nmd == 0);
    CHECK(s.sym->nblocks == amd->nblocks);
    CHECK(!memcmp(s.sym->P, amd->P, (size_t)n * sizeof *amd->P));
    CHECK(!memcmp(s.sym->Q, amd->Q, (size_t)n * sizeof *amd->Q));
    CHECK_ABS(s.sym->est_flops, amd->est_flops, 0);
    CHECK_ABS(s.sym->lnz, amd->lnz, 0);
    CHECK_ABS(factor_flops(&a, s.sym), 3.0 * (n - 1), 0); /* one entry per column of L */
    gd_splu_symbolic_free(&s);
    klu_free_symbolic(&amd, &c);
}

RUN_TESTS(T(minimum_degree_where_amd_merges_the_hubs), T(each_block_chosen_on_its_own),
          T(amd_kept_for_a_small_gain), T(amd_kept_where_it_is_as_good))
