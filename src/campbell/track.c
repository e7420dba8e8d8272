/* Mode tracking across speeds: the complex MAC between the modes of consecutive speeds,
 * and an optimal one-to-one assignment (Hungarian algorithm on 1 - MAC), so crossing
 * modes (different shapes, equal frequencies) keep their identity and veering modes
 * follow their shapes. A pair whose MAC is below mac_min is not the same mode: the
 * new one starts a track (e.g. a mode entering the lowest-k window). */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "campbell/campbell_impl.h"

/* sum |z|^2 of a complex vector given as parts (im may be NULL) */
static double norm2(const double *re, const double *im, int n)
{
    double s = 0;
    if (im) {
#pragma omp simd reduction(+ : s)
        for (int i = 0; i < n; i++)
            s += re[i] * re[i] + im[i] * im[i];
    } else {
#pragma omp simd reduction(+ : s)
        for (int i = 0; i < n; i++)
            s += re[i] * re[i];
    }
    return s;
}

/* |a^H b|^2 / (aa bb) for precomputed aa = |a|^2, bb = |b|^2, in real arithmetic:
 * a^H b = sum (ar br + ai bi) + i (ar bi - ai br). */
static double mac_with_norms(const double *are, const double *aim, double aa, const double *bre,
                             const double *bim, double bb, int n)
{
    if (!(aa > 0 && bb > 0)) return 0;
    double abr = 0, abi = 0;
    if (aim && bim) {
#pragma omp simd reduction(+ : abr, abi)
        for (int i = 0; i < n; i++) {
            abr += are[i] * bre[i] + aim[i] * bim[i];
            abi += are[i] * bim[i] - aim[i] * bre[i];
        }
    } else {
        for (int i = 0; i < n; i++) {
            double ai = aim ? aim[i] : 0, bi = bim ? bim[i] : 0;
            abr += are[i] * bre[i] + ai * bi;
            abi += are[i] * bi - ai * bre[i];
        }
    }
    double m = (abr * abr + abi * abi) / (aa * bb);
    return m > 1 ? 1 : m;
}

double gd_mac(const double *are, const double *aim, const double *bre, const double *bim, int n)
{
    return mac_with_norms(are, aim, norm2(are, aim, n), bre, bim, norm2(bre, bim, n), n);
}

int gd_hungarian(const double *cost, int n, int *col_of_row)
{
    /* 1-based potentials formulation (e-maxx); p[j] = row matched to column j */
    double *u = calloc((size_t)n + 1, sizeof *u), *v = calloc((size_t)n + 1, sizeof *v);
    double *minv = malloc(((size_t)n + 1) * sizeof *minv);
    int *p = calloc((size_t)n + 1, sizeof *p), *way = calloc((size_t)n + 1, sizeof *way);
    int *used = malloc(((size_t)n + 1) * sizeof *used);
    if (!u || !v || !minv || !p || !way || !used) {
        free(u);
        free(v);
        free(minv);
        free(p);
        free(way);
        free(used);
        return -1;
    }
    for (int i = 1; i <= n; i++) {
        p[0] = i;
        int j0 = 0;
        for (int j = 0; j <= n; j++) {
            minv[j] = INFINITY;
            used[j] = 0;
        }
        do {
            used[j0] = 1;
            int i0 = p[j0], j1 = 0;
            double delta = INFINITY;
            for (int j = 1; j <= n; j++)
                if (!used[j]) {
                    double cur = cost[(i0 - 1) + (size_t)(j - 1) * n] - u[i0] - v[j];
                    if (cur < minv[j]) {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if (minv[j] < delta) {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            for (int j = 0; j <= n; j++) {
                if (used[j]) {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
        } while (p[j0] != 0);
        do {
            int j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
        } while (j0);
    }
    for (int j = 1; j <= n; j++)
        if (p[j]) col_of_row[p[j] - 1] = j - 1;
    free(u);
    free(v);
    free(minv);
    free(p);
    free(way);
    free(used);
    return 0;
}

/* a^H b of complex vectors given as parts */
static double complex dot(const double *are, const double *aim, const double *bre,
                          const double *bim, int n)
{
    double r = 0, i = 0;
#pragma omp simd reduction(+ : r, i)
    for (int k = 0; k < n; k++) {
        r += are[k] * bre[k] + aim[k] * bim[k];
        i += are[k] * bim[k] - aim[k] * bre[k];
    }
    return r + I * i;
}

enum { SPAN_MAX = 8 }; /* the largest repeated group compared as a subspace */

/* The MAC of c with the span of the g vectors P (a repeated eigenvalue's eigenspace):
 * c^H P (P^H P)^-1 P^H c / c^H c, the share of c in that subspace. The eigensolver may
 * return any basis of the eigenspace, even two nearly parallel vectors, so the sum of
 * the separate MACs is not that share (it can be near 0 for a vector of the space). */
static double span_mac(const double *const *pre, const double *const *pim, int g, const double *cre,
                       const double *cim, int n)
{
    double complex G[SPAN_MAX][SPAN_MAX + 1];
    double cc = creal(dot(cre, cim, cre, cim, n));
    if (!(cc > 0)) return 0;
    double gmax = 0;
    for (int r = 0; r < g; r++) {
        for (int c = 0; c < g; c++)
            G[r][c] = dot(pre[r], pim[r], pre[c], pim[c], n);
        G[r][g] = dot(pre[r], pim[r], cre, cim, n); /* P^H c */
        gmax = fmax(gmax, creal(G[r][r]));
    }
    double complex b[SPAN_MAX], x[SPAN_MAX];
    for (int r = 0; r < g; r++)
        b[r] = G[r][g];
    /* Gaussian elimination with partial pivoting; a direction the basis does not span
     * (a pivot at rounding level) is dropped */
    int keep[SPAN_MAX];
    for (int k = 0; k < g; k++) {
        int piv = k;
        for (int r = k + 1; r < g; r++)
            if (cabs(G[r][k]) > cabs(G[piv][k])) piv = r;
        for (int c = 0; c <= g; c++) {
            double complex t = G[k][c];
            G[k][c] = G[piv][c];
            G[piv][c] = t;
        }
        keep[k] = cabs(G[k][k]) > 1e-12 * gmax;
        if (!keep[k]) continue;
        for (int r = k + 1; r < g; r++) {
            double complex f = G[r][k] / G[k][k];
            for (int c = k; c <= g; c++)
                G[r][c] -= f * G[k][c];
        }
    }
    for (int k = g - 1; k >= 0; k--) {
        x[k] = 0;
        if (!keep[k]) continue;
        double complex v = G[k][g];
        for (int c = k + 1; c < g; c++)
            v -= G[k][c] * x[c];
        x[k] = v / G[k][k];
    }
    double complex bx = 0;
    for (int r = 0; r < g; r++)
        bx += conj(b[r]) * x[r];
    double m = creal(bx) / cc;
    return m < 0 ? 0 : m > 1 ? 1 : m;
}

int gd_campbell_track_step(const gd_modal_result *prev, const int *prev_elastic, int prev_nel,
                           const int *prev_track, const gd_modal_result *cur, const int *elastic,
                           int nel_cur, double mac_min, int *track, int *ntracks)
{
    if (!prev) {
        for (int j = 0; j < nel_cur; j++)
            track[j] = (*ntracks)++;
        return 0;
    }
    int a = prev_nel, b = nel_cur, N = a > b ? a : b, n = cur->ndof;
    double *cost = malloc((size_t)(N > 0 ? N : 1) * (size_t)(N > 0 ? N : 1) * sizeof *cost);
    double *mac = malloc((size_t)(N > 0 ? N : 1) * (size_t)(N > 0 ? N : 1) * sizeof *mac);
    int *col = malloc((size_t)(N > 0 ? N : 1) * sizeof *col);
    double *nrm = malloc((size_t)(N > 0 ? 2 * N : 1) * sizeof *nrm);
    if (!cost || !mac || !col || !nrm) {
        free(nrm);
        free(cost);
        free(mac);
        free(col);
        return -1;
    }
    /* each shape's norm once (gd_mac's own numbers: its norms are these) */
    for (int i = 0; i < a; i++)
        nrm[i] = norm2(prev->shape_re + (size_t)prev_elastic[i] * n,
                       prev->shape_im + (size_t)prev_elastic[i] * n, n);
    for (int j = 0; j < b; j++)
        nrm[N + j] = norm2(cur->shape_re + (size_t)elastic[j] * n,
                           cur->shape_im + (size_t)elastic[j] * n, n);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double v = 0;
            if (i < a && j < b) {
                int pi = prev_elastic[i], cj = elastic[j];
                v = mac_with_norms(prev->shape_re + (size_t)pi * n, prev->shape_im + (size_t)pi * n,
                                   nrm[i], cur->shape_re + (size_t)cj * n,
                                   cur->shape_im + (size_t)cj * n, nrm[N + j], n);
            }
            mac[i + (size_t)j * N] = v;
        }
    /* Repeated eigenvalues (e.g. the x/y pairs of an isotropic rotor, at rest or on a
     * lumped motor's bearings) have no preferred vectors: compare with their whole
     * eigenspace (span_mac) and let ties keep the frequency order, so the tracks do
     * not depend on which basis the eigensolver returned. */
    double *zeros =
        (!prev->shape_im || !cur->shape_im) ? calloc((size_t)n + 1, sizeof *zeros) : NULL;
    if (!prev->shape_im || !cur->shape_im) {
        if (!zeros) {
            free(nrm);
            free(cost);
            free(mac);
            free(col);
            return -1;
        }
    }
    for (int i = 0; i < a; i++) {
        const gd_mode *mi = &prev->modes[prev_elastic[i]];
        const double *pre[SPAN_MAX], *pim[SPAN_MAX];
        int g = 0;
        for (int k = 0; k < a; k++) {
            const gd_mode *mk = &prev->modes[prev_elastic[k]];
            if (hypot(mk->lambda_re - mi->lambda_re, mk->lambda_im - mi->lambda_im) <=
                    1e-7 * mi->omega_n &&
                g < SPAN_MAX) {
                pre[g] = prev->shape_re + (size_t)prev_elastic[k] * n;
                pim[g] = prev->shape_im ? prev->shape_im + (size_t)prev_elastic[k] * n : zeros;
                g++;
            }
        }
        for (int j = 0; j < N; j++) {
            double v = mac[i + (size_t)j * N];
            if (j < b && g > 1)
                v = span_mac(pre, pim, g, cur->shape_re + (size_t)elastic[j] * n,
                             cur->shape_im ? cur->shape_im + (size_t)elastic[j] * n : zeros, n);
            cost[i + (size_t)j * N] = 1.0 - (v > 1 ? 1 : v) + 1e-9 * abs(i - j);
        }
    }
    free(zeros);
    for (int i = a; i < N; i++)
        for (int j = 0; j < N; j++)
            cost[i + (size_t)j * N] = 1.0 + 1e-9 * abs(i - j);
    for (int j = 0; j < b; j++)
        for (int i = 0; i < a; i++)
            mac[i + (size_t)j * N] = 1.0 - cost[i + (size_t)j * N] + 1e-9 * abs(i - j);
    for (int j = 0; j < b; j++)
        track[j] = -1;
    if (N > 0 && gd_hungarian(cost, N, col)) {
        free(nrm);
        free(cost);
        free(mac);
        free(col);
        return -1;
    }
    for (int i = 0; i < a; i++) {
        int j = col[i];
        if (j < b && mac[i + (size_t)j * N] >= mac_min) track[j] = prev_track[i];
    }
    for (int j = 0; j < b; j++)
        if (track[j] < 0) track[j] = (*ntracks)++;
    free(nrm);
    free(cost);
    free(mac);
    free(col);
    return 0;
}
