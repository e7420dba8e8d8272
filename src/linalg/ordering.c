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
 * diagonal; minimum degree counts them exactly as it eliminates, and stops as soon as it
 * costs GD_ORDER_GAIN of AMD's figure (an upper bound of its order's, from approximate
 * degrees, within 1 % on the models measured). So the trial costs at most
 * one symbolic elimination of the block, paid once per pattern. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"

/* Minimum degree replaces AMD when it predicts at most this fraction of AMD's flops: a new
 * pivot order changes every result's rounding, and the prediction assumes diagonal pivots.
 * Measured (callgrind): the 5-planet set of bench/bench_planetary.sh 0.69 (its Campbell
 * sweep 401.3 -> 384.9 M instructions); rig366 0.86, where `modal` took one inverse
 * iteration more under callgrind (rounding: natively two fewer), +3.2 %; rig2018 0.89
 * (`campbell`, 21 speeds, 4315 -> 3957 M). */
#define GD_ORDER_GAIN 0.75

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

/* A binary heap of the vertices not yet eliminated, the smallest (degree, index) first,
 * with each vertex's position (an indexed heap: one entry per vertex). */
typedef struct heap {
    int64_t *k; /* degree << 32 | vertex */
    int *pos;   /* n: position of each vertex in k, -1 when out */
    int n;
} heap;

static void heap_place(heap *h, int i, int64_t key)
{
    for (;;) { /* up */
        int up = (i - 1) / 2;
        if (i == 0 || h->k[up] <= key) break;
        h->k[i] = h->k[up];
        h->pos[h->k[i] & 0xffffffff] = i;
        i = up;
    }
    for (;;) { /* down */
        int c = 2 * i + 1;
        if (c >= h->n) break;
        if (c + 1 < h->n && h->k[c + 1] < h->k[c]) c++;
        if (h->k[c] >= key) break;
        h->k[i] = h->k[c];
        h->pos[h->k[i] & 0xffffffff] = i;
        i = c;
    }
    h->k[i] = key;
    h->pos[key & 0xffffffff] = i;
}

static void heap_set(heap *h, int v, int deg)
{
    heap_place(h, h->pos[v], ((int64_t)deg << 32) | v);
}

static int heap_pop(heap *h)
{
    int v = (int)(h->k[0] & 0xffffffff);
    h->pos[v] = -1;
    if (--h->n > 0) heap_place(h, 0, h->k[h->n]);
    return v;
}

/* Exact minimum degree on the elimination graph (ties: the lower index), into perm. Stops
 * once its flops reach bound. Returns its flops (*lnz: entries of L with the diagonal), or
 * -1 when it stopped or ran out of memory. Destroys g. work: 2 n ints. */
static double min_degree(graph *g, double bound, int *perm, double *lnz, int *work)
{
    int n = g->n, *seen = work, *nb = NULL;
    heap h = {.pos = work + n, .n = 0};
    double flops = 0;
    *lnz = 0;
    if (!(nb = malloc((size_t)n * sizeof *nb)) || !(h.k = malloc((size_t)n * sizeof *h.k))) {
        free(nb);
        return -1;
    }
    for (int v = 0; v < n; v++) {
        seen[v] = -1;
        heap_place(&h, h.n++, ((int64_t)g->len[v] << 32) | v);
    }
    for (int k = 0, tick = 0; k < n; k++) {
        int v = heap_pop(&h), d = g->len[v];
        flops += 2.0 * d * d + d;
        *lnz += d + 1;
        if (flops >= bound) goto fail;
        memcpy(nb, g->pool + g->start[v], (size_t)d * sizeof *nb);
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
            heap_set(&h, u, g->len[u]);
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
    if ((work = malloc(2 * (size_t)n * sizeof *work)) &&
        (mdperm = malloc((size_t)n * sizeof *mdperm)) && !graph_build(&g, n, cp, ci, work)) {
        double lnz_md, md = min_degree(&g, GD_ORDER_GAIN * flops_amd, mdperm, &lnz_md, work);
        if (md >= 0) { /* below the bound (min_degree stops at it) */
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
