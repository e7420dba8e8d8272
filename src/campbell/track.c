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
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double v = 0;
            if (i < a && j < b) {
                int pi = prev_elastic[i], cj = elastic[j];
                v = gd_mac(prev->shape_re + (size_t)pi * n, prev->shape_im + (size_t)pi * n,
                           cur->shape_re + (size_t)cj * n, cur->shape_im + (size_t)cj * n, n);
            }
            mac[i + (size_t)j * N] = v;
        }
    /* Repeated eigenvalues (e.g. the x/y pairs of an isotropic rotor at rest) have no
     * preferred vectors: compare with their whole eigenspace (sum of the MACs over
     * the group) and let ties keep the frequency order, so the tracks do not depend
     * on which basis the eigensolver returned. */
    for (int i = 0; i < a; i++) {
        const gd_mode *mi = &prev->modes[prev_elastic[i]];
        for (int j = 0; j < N; j++) {
            double v = mac[i + (size_t)j * N];
            if (j < b)
                for (int k = 0; k < a; k++) {
                    const gd_mode *mk = &prev->modes[prev_elastic[k]];
                    if (k != i && hypot(mk->lambda_re - mi->lambda_re,
                                        mk->lambda_im - mi->lambda_im) <= 1e-7 * mi->omega_n)
                        v += mac[k + (size_t)j * N];
                }
            cost[i + (size_t)j * N] = 1.0 - (v > 1 ? 1 : v) + 1e-9 * abs(i - j);
        }
    }
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
