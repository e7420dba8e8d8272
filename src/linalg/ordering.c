/* The fill-reducing ordering of each block KLU factors: AMD's, or an exact minimum-degree
 * one when the symbolic count of its elimination predicts fewer flops. Decided once per
 * sparsity pattern (gd_splu_analyze), by counts, never clocks: deterministic.
 *
 * Why a second candidate: AMD ranks a supervariable (variables with the same neighbours)
 * by its external degree, the neighbours outside it. In a planetary set, once one planet
 * is eliminated, the sun, ring and carrier share all their neighbours, AMD merges them and
 * eliminates them before the other planets, which fills the planets in with each other;
 * the exact degree eliminates the planets first. On K_{3,3} (three hubs, three planets,
 * one DOF each) AMD's order costs 91 flops, minimum degree's 76; on the 5-planet set of
 * bench/bench_planetary.sh 23,746 against 16,456. AMD stays where it is as good (the
 * parallel train: 12,040 against minimum degree's 12,192).
 *
 * Flops of the elimination of C + C^T with diagonal pivots in a given order (as AMD's
 * Info): sum over the columns of L of 2 d^2 + d, d the column's entries below the
 * diagonal. AMD's own figure is an upper bound (approximate degrees); the comparison
 * uses the exact count of AMD's order (elimination tree and row subtrees, O(nnz(L))),
 * and minimum degree stops as soon as it costs as much. So the trial costs at most
 * about one symbolic elimination of the block, paid once per pattern. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"

/* The symmetric graph of C + C^T without the diagonal: adjacency lists in a pool where a
 * list that grows moves to the pool's end (the elimination graph adds fill). */
typedef struct graph {
    int n;
    int *start, *len, *cap; /* n each: list v is pool[start[v] .. start[v] + len[v]) */
    int *pool;
    size_t used, size;
} graph;

static void graph_free(graph *g)
{
    free(g->start);
    free(g->len);
    free(g->cap);
    free(g->pool);
}

/* 0 ok, 1 out of memory. mark: n ints of workspace. */
static int graph_build(graph *g, int n, const int *cp, const int *ci, int *mark)
{
    memset(g, 0, sizeof *g);
    g->n = n;
    g->start = malloc((size_t)n * sizeof *g->start);
    g->len = calloc((size_t)n, sizeof *g->len);
    g->cap = malloc((size_t)n * sizeof *g->cap);
    size_t nz = (size_t)cp[n];
    g->size = 2 * nz + 1;
    g->pool = malloc(g->size * sizeof *g->pool);
    if (!g->start || !g->len || !g->cap || !g->pool) return 1;
    /* upper bound of each list: entries of column v plus those of row v */
    for (int j = 0; j < n; j++)
        for (int p = cp[j]; p < cp[j + 1]; p++) {
            g->len[j]++;
            g->len[ci[p]]++;
        }
    size_t s = 0;
    for (int v = 0; v < n; v++) {
        g->start[v] = (int)s;
        s += (size_t)g->len[v];
        g->len[v] = 0;
        mark[v] = -1;
    }
    g->used = s;
    for (int j = 0; j < n; j++)
        for (int p = cp[j]; p < cp[j + 1]; p++) {
            int i = ci[p];
            if (i == j) continue;
            g->pool[g->start[j] + g->len[j]++] = i;
            g->pool[g->start[i] + g->len[i]++] = j;
        }
    /* duplicates ((i, j) and (j, i) both present) out */
    for (int v = 0; v < n; v++) {
        int *a = g->pool + g->start[v], w = 0;
        for (int q = 0; q < g->len[v]; q++)
            if (mark[a[q]] != v) {
                mark[a[q]] = v;
                a[w++] = a[q];
            }
        g->len[v] = w;
    }
    for (int v = 0; v < n; v++) /* the room up to the next list's start */
        g->cap[v] = (v + 1 < n ? g->start[v + 1] : (int)g->used) - g->start[v];
    return 0;
}

/* Appends w to list v, moving the list to the pool's end when it is full. 0 ok, 1 out of
 * memory. */
static int graph_append(graph *g, int v, int w)
{
    if (g->len[v] == g->cap[v]) {
        size_t cap = 2 * (size_t)g->cap[v] + 4;
        if (g->used + cap > g->size) {
            size_t size = 2 * g->size + cap;
            if (size > INT32_MAX) return 1;
            int *pool = realloc(g->pool, size * sizeof *pool);
            if (!pool) return 1;
            g->pool = pool;
            g->size = size;
        }
        memcpy(g->pool + g->used, g->pool + g->start[v], (size_t)g->len[v] * sizeof *g->pool);
        g->start[v] = (int)g->used;
        g->cap[v] = (int)cap;
        g->used += cap;
    }
    g->pool[g->start[v] + g->len[v]++] = w;
    return 0;
}

/* Exact symbolic count of eliminating the graph in the order perm (Liu's elimination
 * tree, then each row's subtree marks the entries of L in that row): flops as AMD's Info.
 * work: 4 n ints. */
static double count_order(const graph *g, const int *perm, int *work)
{
    int n = g->n, *pinv = work, *parent = work + n, *anc = work + 2 * n, *flag = work + 3 * n;
    for (int k = 0; k < n; k++)
        pinv[perm[k]] = k;
    for (int k = 0; k < n; k++) {
        parent[k] = anc[k] = -1;
        const int *a = g->pool + g->start[perm[k]];
        for (int q = 0; q < g->len[perm[k]]; q++)
            for (int j = pinv[a[q]], next; j != -1 && j < k; j = next) {
                next = anc[j];
                anc[j] = k;
                if (next == -1) parent[j] = k;
            }
    }
    int *cnt = anc; /* below-diagonal entries of each column of L */
    for (int k = 0; k < n; k++) {
        cnt[k] = 0;
        flag[k] = -1;
    }
    for (int k = 0; k < n; k++) {
        flag[k] = k;
        const int *a = g->pool + g->start[perm[k]];
        for (int q = 0; q < g->len[perm[k]]; q++)
            for (int j = pinv[a[q]]; j < k && flag[j] != k; j = parent[j]) {
                cnt[j]++; /* L(k, j) */
                flag[j] = k;
            }
    }
    double flops = 0;
    for (int k = 0; k < n; k++)
        flops += 2.0 * cnt[k] * cnt[k] + cnt[k];
    return flops;
}

/* A binary heap of (degree, vertex) keys, the smallest first; stale keys are skipped by
 * the caller (lazy deletion). */
typedef struct heap {
    int64_t *k;
    size_t n, cap;
} heap;

static int heap_push(heap *h, int deg, int v)
{
    if (h->n == h->cap) {
        size_t cap = 2 * h->cap + 64;
        int64_t *k = realloc(h->k, cap * sizeof *k);
        if (!k) return 1;
        h->k = k;
        h->cap = cap;
    }
    int64_t key = ((int64_t)deg << 32) | (int64_t)v;
    size_t i = h->n++;
    while (i > 0 && h->k[(i - 1) / 2] > key) {
        h->k[i] = h->k[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h->k[i] = key;
    return 0;
}

static int64_t heap_pop(heap *h)
{
    int64_t top = h->k[0], last = h->k[--h->n];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= h->n) break;
        if (c + 1 < h->n && h->k[c + 1] < h->k[c]) c++;
        if (h->k[c] >= last) break;
        h->k[i] = h->k[c];
        i = c;
    }
    if (h->n) h->k[i] = last;
    return top;
}

/* Exact minimum degree on the elimination graph (ties: the lower index), into perm. Stops
 * once its flops reach bound. Returns its flops (*lnz: entries of L with the diagonal), or
 * -1 when it stopped or ran out of memory. Destroys g. work: 2 n ints. */
static double min_degree(graph *g, double bound, int *perm, double *lnz, int *work)
{
    int n = g->n, *done = work, *seen = work + n, *nb = NULL;
    heap h = {0};
    double flops = 0;
    *lnz = 0;
    if (!(nb = malloc((size_t)n * sizeof *nb))) return -1;
    for (int v = 0; v < n; v++) {
        done[v] = 0;
        seen[v] = -1;
        if (heap_push(&h, g->len[v], v)) goto fail;
    }
    for (int k = 0, tick = 0; k < n; k++) {
        int v;
        for (;;) {
            int64_t key = heap_pop(&h);
            v = (int)(key & 0xffffffff);
            if (!done[v] && (int)(key >> 32) == g->len[v]) break;
        }
        int d = g->len[v];
        flops += 2.0 * d * d + d;
        *lnz += d + 1;
        if (flops >= bound) goto fail;
        memcpy(nb, g->pool + g->start[v], (size_t)d * sizeof *nb);
        done[v] = 1;
        perm[k] = v;
        /* v's neighbours become a clique; v leaves their lists */
        for (int a = 0; a < d; a++) {
            int u = nb[a], *l = g->pool + g->start[u], w = 0;
            tick++;
            for (int q = 0; q < g->len[u]; q++)
                if (l[q] != v) {
                    seen[l[q]] = tick;
                    l[w++] = l[q];
                }
            g->len[u] = w;
            for (int b = 0; b < d; b++)
                if (nb[b] != u && seen[nb[b]] != tick && graph_append(g, u, nb[b])) goto fail;
            if (heap_push(&h, g->len[u], u)) goto fail;
        }
        g->len[v] = 0;
    }
    free(nb);
    free(h.k);
    return flops;
fail:
    free(nb);
    free(h.k);
    return -1;
}

int gd_order_block(int n, int *cp, int *ci, int *perm, klu_common *common)
{
    gd_order_choice *ch = common->user_data;
    double info[AMD_INFO];
    /* as klu_analyze's own AMD call, so a block AMD wins is analysed as before */
    int r = amd_order(n, cp, ci, perm, NULL, info);
    if (r < AMD_OK) {
        if (r == AMD_OUT_OF_MEMORY) ch->out_of_memory = 1;
        return 0;
    }
    double lnz_amd = info[AMD_LNZ] + n, flops_amd = 2 * info[AMD_NMULTSUBS_LU] + info[AMD_NDIV];
    int *work = NULL, *mdperm = NULL;
    graph g = {0};
    if ((work = malloc(4 * (size_t)n * sizeof *work)) &&
        (mdperm = malloc((size_t)n * sizeof *mdperm)) && !graph_build(&g, n, cp, ci, work)) {
        double exact = count_order(&g, perm, work), lnz_md;
        double md = min_degree(&g, exact, mdperm, &lnz_md, work);
        if (md >= 0) { /* below AMD's exact count (min_degree stops at it) */
            memcpy(perm, mdperm, (size_t)n * sizeof *perm);
            lnz_amd = lnz_md;
            flops_amd = md;
            ch->nmd++;
        }
    }
    /* memory that the trial could not get leaves AMD's order */
    graph_free(&g);
    free(work);
    free(mdperm);
    ch->flops += flops_amd;
    return (int)lnz_amd;
}
