/* The base frequencies of a multi-frequency harmonic balance and its truncation set on the
 * torus (qphb_impl.h). A two-stage gearbox with teeth z1/z2 and z3/z4 has the mesh
 * frequencies W z1 and W z1 z3 / z2: with z2 and z3 co-prime their common fundamental is
 * W z1 / z2, so one period holds z2 cycles of the first mesh and ordinary harmonic balance
 * needs z2 times the harmonics of one mesh; on the torus each mesh keeps its own. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/multifreq/qphb_impl.h"
#include "transient/transient_impl.h"

/* a law joins a base of which its fundamental is a whole multiple up to this */
#define MAX_MULTIPLE 64

/* gcd of two positive reals to the absolute tolerance tol */
static double real_gcd(double a, double b, double tol)
{
    if (a < b) {
        double t = a;
        a = b;
        b = t;
    }
    while (b > tol) {
        double r = fmod(a, b);
        if (r > b - tol) r = 0.0;
        a = b;
        b = r;
    }
    return a;
}

/* m when x / base is the whole number m (1..MAX_MULTIPLE, relative 1e-9), else 0 */
static int multiple_of(double x, double base)
{
    double r = x / base;
    long m = lround(r);
    return m >= 1 && m <= MAX_MULTIPLE && fabs(r - m) <= 1e-9 * r ? (int)m : 0;
}

int gd_qp_find_bases(gd_transient *tr, const gd_system *sys, const gd_transient_spec *spec,
                     double speed, gd_qp_bases *b, char *msg, size_t cap)
{
    memset(b, 0, sizeof *b);
    const gd_model *m = sys->model;
    if (spec->unbalances && m->nunbalances && speed != 0.0) {
        snprintf(msg, cap,
                 "unbalance forces turn with the shafts, not with a law's base frequency (the "
                 "multi-frequency harmonic balance takes meshes and loads)");
        return 1;
    }
    for (int i = 0; i < spec->nprescribed; i++) {
        const int dof = spec->prescribed[i].dof;
        double r = sys->dof_type[dof] == GD_RZ
                       ? m->shafts[m->nodes[sys->dof_node[dof]].shaft].speed_ratio * speed
                       : 0.0,
               w[4];
        char why[200] = "";
        if (gd_prescribed_frequencies(&spec->prescribed[i].law, r, w, 4, why, sizeof why) != 0) {
            snprintf(msg, cap,
                     "a prescribed motion has its own frequency (the multi-frequency harmonic "
                     "balance takes meshes and loads)");
            return 1;
        }
    }
    b->nlaw = tr->nlaw;
    b->group = malloc((size_t)(tr->nlaw > 0 ? tr->nlaw : 1) * sizeof *b->group);
    double *lf = malloc((size_t)(tr->nlaw > 0 ? tr->nlaw : 1) * sizeof *lf);
    if (!b->group || !lf) {
        free(lf);
        snprintf(msg, cap, "out of memory");
        return 1;
    }
    /* each law's own fundamental (the gcd of its frequencies) */
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        b->group[i] = -1;
        lf[i] = 0.0;
        if (!L->type->frequencies) continue;
        double w[16];
        char why[200] = "";
        int nw = L->type->frequencies(L, w, 16, why, sizeof why);
        if (nw < 0) {
            snprintf(msg, cap, "%s: %s", L->name, why);
            free(lf);
            return 1;
        }
        double g = 0.0, top = 0.0;
        for (int k = 0; k < nw; k++)
            top = fmax(top, w[k]);
        for (int k = 0; k < nw; k++)
            if (w[k] > 0 && isfinite(w[k])) g = g > 0 ? real_gcd(g, w[k], 1e-9 * top) : w[k];
        lf[i] = g;
    }
    /* bases: the laws' fundamentals in ascending order, each joining a base it is a whole
     * multiple of, else a base of its own */
    for (;;) {
        int lo = -1;
        for (int i = 0; i < tr->nlaw; i++)
            if (lf[i] > 0 && b->group[i] < 0 && (lo < 0 || lf[i] < lf[lo])) lo = i;
        if (lo < 0) break;
        int g = -1;
        for (int k = 0; k < b->d && g < 0; k++)
            if (multiple_of(lf[lo], b->W[k])) g = k;
        if (g < 0) {
            if (b->d == GD_QP_MAXD) {
                snprintf(msg, cap,
                         "more than %d independent base frequencies (%.6g, %.6g, %.6g and "
                         "%.6g rad/s)",
                         GD_QP_MAXD, b->W[0], b->W[1], b->W[2], lf[lo]);
                free(lf);
                return 1;
            }
            g = b->d++;
            b->W[g] = lf[lo];
        }
        b->group[lo] = g;
    }
    free(lf);
    /* the common fundamental, where the bases have one of modest order */
    if (b->d >= 1) {
        double g = b->W[0], top = b->W[b->d - 1];
        for (int k = 1; k < b->d; k++)
            g = real_gcd(g, b->W[k], 1e-9 * top);
        if (g > 0 && top / g <= 100000.5) {
            b->common = g;
            b->order = lround(top / g);
        }
    }
    return 0;
}

void gd_qp_bases_free(gd_qp_bases *b)
{
    free(b->group);
    memset(b, 0, sizeof *b);
}

/* ---------------------------------------------------------------- truncation set */

static long wrap(int k, int N)
{
    return ((k % N) + N) % N;
}

/* 1 when the first non-zero component of k is positive */
static int positive_half(const int *k, int d)
{
    for (int g = 0; g < d; g++)
        if (k[g]) return k[g] > 0;
    return 0;
}

/* The least n' >= n whose prime factors are 2, 3 and 5 (FFTW's fast sizes). */
static int smooth_size(int n)
{
    for (int m = n > 1 ? n : 1;; m++) {
        int r = m;
        while (r % 2 == 0)
            r /= 2;
        while (r % 3 == 0)
            r /= 3;
        while (r % 5 == 0)
            r /= 5;
        if (r == 1) return m;
    }
}

int gd_qp_torus_init(gd_qp_torus *T, const gd_qp_bases *b, int H)
{
    memset(T, 0, sizeof *T);
    const int d = b->d;
    T->d = d;
    T->H = H;
    memcpy(T->W, b->W, sizeof T->W);
    /* the frequency-weighted set sum |k_g| W_g <= H W_top: base g keeps its harmonics up
     * to H_g = H W_top / W_g, so every harmonic of frequency content up to H times the
     * highest base is kept whatever base it comes from (a pinion's mesh mode excited by
     * the slow mesh's stiffness steps lies at a high order of that mesh) */
    const double top = b->W[d - 1], cut = H * top * (1 + 1e-12);
    int Hg[GD_QP_MAXD];
    long span = 1, count = 0;
    for (int g = 0; g < d; g++) {
        Hg[g] = (int)floor(cut / b->W[g]);
        span *= 2L * Hg[g] + 1;
    }
    T->k = malloc((size_t)span * d * sizeof *T->k);
    T->box = malloc((size_t)span * sizeof *T->box);
    if (!T->k || !T->box) return 1;
    memcpy(T->Hg, Hg, sizeof Hg);
    T->span = span;
    for (long c = 0; c < span; c++)
        T->box[c] = -1;
    /* k = 0, then the positive half in lexicographic order: the set of order H is a
     * prefix of that of 2 H only in content, so pad() maps by value (qp_run.c) */
    for (long c = 0; c < span; c++) {
        int k[GD_QP_MAXD];
        double w = 0.0;
        long r = c;
        for (int g = d - 1; g >= 0; g--) {
            k[g] = (int)(r % (2 * Hg[g] + 1)) - Hg[g];
            r /= 2 * Hg[g] + 1;
            w += abs(k[g]) * b->W[g];
        }
        if (w > cut) continue;
        int zero = 1;
        for (int g = 0; g < d; g++)
            zero &= k[g] == 0;
        if (!zero && !positive_half(k, d)) continue;
        long at = zero ? 0 : ++count; /* k = 0 first */
        T->box[c] = (int)at;
        memcpy(T->k + at * d, k, (size_t)d * sizeof *k);
    }
    T->nk = (int)count + 1;
    T->Ntot = 1;
    for (int g = 0; g < d; g++) {
        /* 4 (H_g + 1) samples, as the single-frequency AFT (at 3 (H_g + 1) the
         * commensurate check, tests/periodic/test_multifreq.c, is off by 5e-8 from ordinary
         * harmonic balance; at 4, 2e-9) */
        T->N[g] = smooth_size(4 * (Hg[g] + 1) > 16 ? 4 * (Hg[g] + 1) : 16);
        T->Ntot *= T->N[g];
    }
    T->pos = malloc((size_t)T->nk * sizeof *T->pos);
    T->neg = malloc((size_t)T->nk * sizeof *T->neg);
    if (!T->pos || !T->neg) return 1;
    for (int j = 0; j < T->nk; j++) {
        long p = 0, n = 0;
        for (int g = 0; g < d; g++) { /* row-major: the last base varies fastest */
            p = p * T->N[g] + wrap(T->k[j * d + g], T->N[g]);
            n = n * T->N[g] + wrap(-T->k[j * d + g], T->N[g]);
        }
        T->pos[j] = p;
        T->neg[j] = n;
    }
    return 0;
}

int gd_qp_torus_find(const gd_qp_torus *T, const int *k)
{
    long c = 0;
    for (int g = 0; g < T->d; g++) {
        if (abs(k[g]) > T->Hg[g]) return -1;
        c = c * (2L * T->Hg[g] + 1) + k[g] + T->Hg[g];
    }
    return T->box[c];
}

void gd_qp_torus_free(gd_qp_torus *T)
{
    free(T->k);
    free(T->box);
    free(T->pos);
    free(T->neg);
    memset(T, 0, sizeof *T);
}
