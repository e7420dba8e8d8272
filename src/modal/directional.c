/* Directional modes ([Kumar2011], complex variable approach, Eqs. 2.5-2.8): the lateral
 * DOFs of each node become the complex coordinates p = x + i y and its conjugate
 * pbar = x - i y (forward and backward whirl components), the equation of motion is
 * written for them, M_c c'' + D_c c' + K_c c = 0 with q = T c and X_c = T^H X T, and
 * its eigenvalues are solved as a complex pencil (zggev on the linearisation
 * [0 I; -K_c -D_c] z = lambda [I 0; 0 M_c] z, so massless DOFs give infinite roots that
 * are dropped). Each physical mode appears as a conjugate pair of roots; the one whose
 * vector is carried by p (the forward coordinate, taken about each shaft's own sense
 * of rotation) is its directional eigenvalue: Im > 0 a forward whirl, Im < 0 a backward
 * whirl at |Im|. A mode with no whirl direction (straight-line orbits, no lateral
 * motion) is listed once, with Im >= 0. Rigid-body roots (|lambda| below 1e-6 of the
 * largest) are not listed. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

typedef struct droot {
    double complex lam;
    double fwd; /* share of the lateral amplitude in the forward coordinate */
} droot;

/* Two steps of inverse iteration for the quadratic problem (lambda^2 M_c + lambda D_c +
 * K_c) c = 0 from (lam, c) (Ruhe's Newton step: x = Q(lam)^-1 Q'(lam) c, lam -= w^H c /
 * w^H x with w the starting c), so the root does not carry the linearisation's
 * rounding (the QZ of a pencil with K ~ 1e9 next to M ~ 1). Xc: K_c, D_c, M_c; work: n^2
 * + 2n complex, piv n. */
static double complex refine(const double complex *Xc, int n, double complex lam,
                             const double complex *c0, double complex *work, lapack_int *piv)
{
    const double complex *K = Xc, *D = Xc + (size_t)n * n, *M = Xc + (size_t)2 * n * n;
    double complex *Q = work, *x = work + (size_t)n * n, *c = x + n;
    memcpy(c, c0, (size_t)n * sizeof *c);
    double complex wc = 0;
    for (int i = 0; i < n; i++)
        wc += conj(c0[i]) * c[i];
    for (int it = 0; it < 2; it++) {
        for (size_t e = 0; e < (size_t)n * n; e++)
            Q[e] = (lam * M[e] + D[e]) * lam + K[e];
        for (int i = 0; i < n; i++) {
            double complex s = 0;
            for (int j = 0; j < n; j++)
                s += (2 * lam * M[i + (size_t)j * n] + D[i + (size_t)j * n]) * c[j];
            x[i] = s;
        }
        if (LAPACKE_zgesv(LAPACK_COL_MAJOR, n, 1, Q, n, piv, x, n) != 0) break; /* exact */
        double complex wx = 0;
        for (int i = 0; i < n; i++)
            wx += conj(c0[i]) * x[i];
        if (wx == 0) break;
        lam -= wc / wx;
        for (int i = 0; i < n; i++)
            c[i] = x[i] * (wc / wx);
    }
    return lam;
}

static int cmp_root(const void *a, const void *b)
{
    const droot *x = a, *y = b;
    double ax = cabs(x->lam), ay = cabs(y->lam);
    if (ax != ay) return (ax > ay) - (ax < ay);
    return (cimag(x->lam) < cimag(y->lam)) - (cimag(x->lam) > cimag(y->lam));
}

void gd_directional_free(gd_directional_result *r)
{
    if (!r) return;
    free(r->modes);
    free(r);
}

gd_status gd_modal_directional(const gd_system *sys, const gd_modal_options *opt,
                               gd_directional_result **out, gd_error *err)
{
    *out = NULL;
    const gd_model *m = sys->model;
    int n = sys->ndof, n2 = 2 * n;
    gd_status st = GD_OK;
    double *M = malloc((size_t)n * n * sizeof *M), *D = malloc((size_t)n * n * sizeof *D),
           *K = malloc((size_t)n * n * sizeof *K);
    double complex *T = calloc((size_t)n * n, sizeof *T), *W = malloc((size_t)n * n * sizeof *W);
    double complex *A = calloc((size_t)n2 * n2, sizeof *A), *B = calloc((size_t)n2 * n2, sizeof *B);
    double complex *al = malloc((size_t)n2 * sizeof *al), *be = malloc((size_t)n2 * sizeof *be);
    double complex *V = malloc((size_t)n2 * n2 * sizeof *V);
    int *partner = malloc((size_t)n * sizeof *partner), *flip = calloc((size_t)n, sizeof *flip);
    droot *roots = malloc((size_t)n2 * sizeof *roots);
    int *idx = malloc((size_t)n2 * sizeof *idx), *members = malloc((size_t)n2 * sizeof *members);
    double complex *F = malloc((size_t)n2 * n2 * sizeof *F),
                   *S = malloc((size_t)n2 * n2 * sizeof *S);
    double complex *Xc = malloc((size_t)3 * n * n * sizeof *Xc),
                   *cv = malloc((size_t)n * sizeof *cv),
                   *rw = malloc(((size_t)n * n + 2 * (size_t)n) * sizeof *rw);
    lapack_int *piv = malloc((size_t)n * sizeof *piv);
    double *mu = malloc((size_t)n2 * sizeof *mu), *lsc = malloc((size_t)n2 * sizeof *lsc),
           *rsc = malloc((size_t)n2 * sizeof *rsc);
    gd_directional_result *res = calloc(1, sizeof *res);
    if (!M || !D || !K || !T || !W || !A || !B || !al || !be || !V || !partner || !flip || !roots ||
        !idx || !members || !F || !S || !mu || !lsc || !rsc || !Xc || !cv || !rw || !piv || !res)
        goto nomem;
    gd_system_dense_at(sys, opt->speed, opt->law_state, M, D, K);
    if (opt->kind == GD_MODAL_UNDAMPED) memset(D, 0, (size_t)n * n * sizeof *D);
    /* T: [x; y] = 1/2 [1 1; -i i] [p; pbar] at each node with both; identity elsewhere */
    for (int i = 0; i < n; i++) {
        partner[i] = -1;
        T[i + (size_t)i * n] = 1;
    }
    for (int node = 0; node < m->nnodes; node++) {
        int ix = gd_system_dof(sys, node, GD_X), iy = gd_system_dof(sys, node, GD_Y);
        if (ix < 0 || iy < 0) continue;
        partner[ix] = iy; /* c[ix] = p, c[iy] = pbar */
        partner[iy] = -2;
        flip[ix] = m->shafts[m->nodes[node].shaft].speed_ratio < 0;
        T[ix + (size_t)ix * n] = 0.5;
        T[ix + (size_t)iy * n] = 0.5;
        T[iy + (size_t)ix * n] = -0.5 * I;
        T[iy + (size_t)iy * n] = 0.5 * I;
    }
    /* X_c = T^H X T into the blocks of A and B */
    double *mats[3] = {K, D, M};
    for (int t = 0; t < 3; t++) {
        const double *X = mats[t];
        for (int j = 0; j < n; j++) /* W = X T */
            for (int i = 0; i < n; i++) {
                double complex s = 0;
                for (int k = 0; k < n; k++)
                    if (T[k + (size_t)j * n] != 0) s += X[i + (size_t)k * n] * T[k + (size_t)j * n];
                W[i + (size_t)j * n] = s;
            }
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double complex s = 0;
                for (int k = 0; k < n; k++)
                    if (T[k + (size_t)i * n] != 0)
                        s += conj(T[k + (size_t)i * n]) * W[k + (size_t)j * n];
                Xc[(size_t)t * n * n + i + (size_t)j * n] = s;
                if (t < 2)
                    A[n + i + (size_t)(t * n + j) * n2] = -s; /* -K_c | -D_c */
                else
                    B[n + i + (size_t)(n + j) * n2] = s;
            }
    }
    for (int i = 0; i < n; i++) {
        A[i + (size_t)(n + i) * n2] = 1;
        B[i + (size_t)i * n2] = 1;
    }
    /* balanced (scaling as well as permuting): K ~ 1e9 next to M ~ 1 otherwise costs
       digits against the real solver's mass-normalised problem */
    lapack_int ilo, ihi;
    double abnrm, bbnrm;
    lapack_int info =
        LAPACKE_zggevx(LAPACK_COL_MAJOR, 'B', 'N', 'V', 'N', n2, A, n2, B, n2, al, be, NULL, 1, V,
                       n2, &ilo, &ihi, lsc, rsc, &abnrm, &bbnrm, NULL, NULL);
    if (info != 0) {
        st = gd_error_set(err, GD_ENUMERIC, m->file, 0, 0, "", "",
                          "the complex eigensolver did not converge (LAPACK info %d)", (int)info);
        goto done;
    }
    double lmax = 0;
    for (int j = 0; j < n2; j++)
        if (cabs(be[j]) > 1e-13 * cabs(al[j]) && cabs(al[j] / be[j]) > lmax)
            lmax = cabs(al[j] / be[j]);
    /* finite, non-rigid roots, then clusters of equal ones (an isotropic rotor at rest
       has double roots, whose vectors LAPACK mixes): within a cluster the vectors are
       recombined to maximise the share of p, so the forward and backward circles
       separate */
    int nf = 0, nr = 0;
    for (int j = 0; j < n2; j++) {
        if (!(cabs(be[j]) > 1e-13 * cabs(al[j]))) continue; /* infinite: massless */
        double complex lam = al[j] / be[j];
        if (cabs(lam) <= 1e-6 * lmax) continue; /* rigid body */
        idx[nf++] = j;
    }
    for (int a = 0; a < nf; a++) {
        if (idx[a] < 0) continue;
        double complex la = al[idx[a]] / be[idx[a]];
        int c = 0;
        for (int b = a; b < nf; b++)
            if (idx[b] >= 0 && cabs(al[idx[b]] / be[idx[b]] - la) <= 1e-7 * lmax) {
                members[c++] = idx[b];
                idx[b] = -1;
            }
        /* F = V^H P_f V and S = V^H (P_f + P_b) V over the cluster's vectors (the
           displacement half of the state vectors) */
        for (int x = 0; x < c; x++)
            for (int y = 0; y < c; y++) {
                double complex f = 0, t = 0;
                const double complex *vx = V + (size_t)members[x] * n2,
                                     *vy = V + (size_t)members[y] * n2;
                for (int i = 0; i < n; i++) {
                    if (partner[i] < 0) continue;
                    int fi = flip[i] ? partner[i] : i, bi = flip[i] ? i : partner[i];
                    double complex pf = conj(vx[fi]) * vy[fi];
                    f += pf;
                    t += pf + conj(vx[bi]) * vy[bi];
                }
                F[x + (size_t)y * c] = f;
                S[x + (size_t)y * c] = t;
            }
        int ok = LAPACKE_zhegv(LAPACK_COL_MAJOR, 1, 'V', 'U', c, F, c, S, c, mu) == 0;
        for (int x = 0; x < c; x++) {
            double w = ok ? mu[x] : NAN; /* S singular: no lateral motion */
            int tie = !(w == w) || fabs(w - 0.5) <= 1e-6;
            /* the roots carried by p; a tie (no direction) keeps Im >= 0 */
            if (tie ? cimag(la) < -1e-12 * lmax : w < 0.5) continue;
            /* the recombined vector's displacement half, to refine the root from */
            for (int i = 0; i < n; i++) {
                double complex s = 0;
                for (int y = 0; y < c; y++)
                    s += V[(size_t)members[y] * n2 + i] * (ok ? F[y + (size_t)x * c] : y == x);
                cv[i] = s;
            }
            roots[nr].lam = refine(Xc, n, la, cv, rw, piv);
            roots[nr].fwd = w;
            nr++;
        }
    }
    qsort(roots, (size_t)nr, sizeof *roots, cmp_root);
    int k = opt->nmodes > 0 && opt->nmodes < nr ? opt->nmodes : nr;
    res->modes = calloc((size_t)(k > 0 ? k : 1), sizeof *res->modes);
    if (!res->modes) goto nomem;
    res->nmodes = k;
    res->speed = opt->speed;
    for (int j = 0; j < k; j++) {
        gd_directional_mode *d = &res->modes[j];
        d->lambda_re = creal(roots[j].lam);
        d->lambda_im = cimag(roots[j].lam);
        /* p carries the kept root: its whirl is the sense of Im, and the forward
           component of the motion is p's share at Im > 0, pbar's at Im < 0 */
        double fr = roots[j].fwd;
        int none = !(fr == fr) || fabs(2 * fr - 1) <= 2e-6;
        if (none && d->lambda_im < 0) d->lambda_im = -d->lambda_im;
        d->whirl = none ? GD_WHIRL_NONE : d->lambda_im > 0 ? GD_WHIRL_FORWARD : GD_WHIRL_BACKWARD;
        d->forward_fraction = (d->lambda_im >= 0 ? fr : 1 - fr) + 0.0;
    }
    *out = res;
    res = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce the model size",
                      "out of memory in the directional modal analysis (%d states)", n2);
done:
    gd_directional_free(res);
    free(M);
    free(D);
    free(K);
    free(T);
    free(W);
    free(A);
    free(B);
    free(al);
    free(be);
    free(V);
    free(partner);
    free(flip);
    free(roots);
    free(idx);
    free(members);
    free(F);
    free(S);
    free(mu);
    free(lsc);
    free(rsc);
    free(Xc);
    free(cv);
    free(rw);
    free(piv);
    return st;
}
