/* Continuation of the lowest damped modes from one speed of a sweep to the next
 * (Campbell): each mode is refined from the previous speed's eigenpair instead of being
 * found again by shift-invert Krylov-Schur (sparse_modes.c), whose ~55 Krylov vectors,
 * their orthogonalisation and the Hessenberg QR of their Rayleigh quotient cost most of
 * a Campbell diagram.
 *
 * Modes whose previous eigenvalues lie within 1 % of each other form a cluster (the
 * forward and backward whirl of one lateral mode at low speed, repeated eigenvalues),
 * refined together. For a cluster: a complex factorisation of P(sigma) = sigma^2 M +
 * sigma D + K at sigma near its eigenvalues (one kept from an earlier speed when its
 * shift is still near enough, else a fresh one at the first Ritz values); a basis Q (n x q,
 * complex) starting from the previous eigenvectors; Rayleigh-Ritz on the quadratic
 * problem, Q^H P(lambda) Q s = 0 (linearised, q <= 26), the values nearest the previous
 * ones kept; each residual r = P(lambda) x that fails the tolerance adds
 * P(sigma)^-1 r to Q (residual inverse iteration, Neumaier, SIAM J. Numer. Anal. 22,
 * 1985, accelerated by the projection; after the first pass a cluster that split corrects
 * each member at its own Ritz value until its residual is below GD_TRACK_OWN_SHIFT), until
 * every residual passes or the basis is full. Then a completeness check: shift-invert at today's
 * real shift -s, deflated by the refined vectors (gd_ks_deflated_top); a remaining eigenvalue
 * nearer -s than the farthest refined one is a mode the continuation missed (one coming down from
 * above the window, or a copy of a repeated value).
 *
 * Any failure (a cluster of more than GD_TRACK_MAXC modes, an overdamped or nearly
 * rigid mode, no convergence within the basis, a rigid-body mode whose shape is no
 * longer in K's null space, a missed mode) returns no result, and the caller solves
 * that speed by Krylov-Schur (the fallback). A caller that asks for fewer modes than the
 * previous speed has (gd_modal_options.nmodes: Campbell's guard band above its window)
 * gets those at least: a cluster above them that fails is dropped with all above it,
 * and the completeness check vouches for the needed ones only (a double mode the
 * window's edge cuts, as the planetary set's translational pairs at rest, then neither
 * wanders between its split values nor makes the check hard). */
#include <cblas.h>
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

#define PI 3.14159265358979323846
/* Relative residual ||P(lambda) x|| / (|lambda| ||P'(lambda) x||) of an accepted mode: the
 * first-order eigenvalue error of a simple, well-conditioned mode; the Galerkin projection
 * makes the actual error about its square. Measured on bench/models/rig366.yaml (100 speeds,
 * 12 modes): frequencies within 2e-12 (relative) of Krylov-Schur's, whose own tolerance
 * is 1e-9 in the first-order form. */
#define GD_TRACK_TOL 1e-10
#define GD_TRACK_STALL 1e-8
/* relative distance of the eigenvalues of one cluster: a pair split further is refined as
 * two modes, each at its own shift (a cluster's shift at the mean gains only the
 * half-split over the distance to the next mode per pass). 1e-2 to 3e-3: campbell
 * instructions -4.5 % on the planetary set of bench/bench_planetary.sh, -1.9 % on its
 * parallel train, -2.1 % on rig366 (100 speeds), no fallback; 1e-3 a little less again,
 * 3e-4 sent the parallel train's split pairs to Krylov-Schur (+38 %) */
#define GD_TRACK_CLUSTER 3e-3
#define GD_TRACK_MAXC 6   /* largest cluster refined together */
#define GD_TRACK_MAXQ 8   /* basis columns per cluster member */
#define GD_TRACK_MAXIT 8  /* Rayleigh-Ritz passes per cluster */
#define GD_TRACK_TIE 1e-9 /* relative distance of two predictions taken as equal */
#define GD_TRACK_OWN_SHIFT                                                                         \
    1e-7 /* a split cluster's members correct at their own values above it                         \
          */
/* Complex factorisations kept from speed to speed (at most GD_TRACK_SLOTS, within
 * GD_TRACK_LU_BYTES per workspace): a cluster whose shift lies within GD_TRACK_REUSE
 * of its distance to the other modes from a kept one corrects with that one, for one
 * pass (residual inverse iteration gains at least a digit per pass at that distance;
 * the eigenvalues move by 1e-7 to 3e-4 of themselves per speed step on rig366, and its
 * passes grew from 2016 to 2043 per sweep while the fresh factorisations fell from 876
 * to 132); a second correction gets a fresh factorisation. */
#define GD_TRACK_SLOTS 16
#define GD_TRACK_LU_BYTES (64.0 * 1024 * 1024)
#define GD_TRACK_REUSE 0.1
/* A speed whose completeness check settles at the loose residual is easy: the next speed
 * is continued too. A hard one (a mode just outside the window: near-double modes cut by
 * its edge, as on a finely meshed, weakly gyroscopic shaft) hands the rest of its chain
 * to Krylov-Schur, where the continuation costs more than it saves. */
/* The completeness check: Krylov to this residual, and a margin below the farthest refined
 * mode's shift-invert magnitude (as the deflated checks of krylov_schur.c) */
#define GD_TRACK_CHECK_TOL 1e-4
#define GD_TRACK_CHECK_MARGIN 1e-3
#define GD_TRACK_LOOSE_TOL 1e-2
#define GD_TRACK_LOOSE_MARGIN 2e-2

/* The nonzero values of one matrix on the pattern, by column (M, D and K each fill
 * about half of their union's pattern) */
typedef struct track_csc {
    int *cp, *ri; /* n + 1, nnz */
    double *v;    /* nnz */
} track_csc;

static void csc_compact(const gd_pattern *p, const double *x, track_csc *c)
{
    int t = 0;
    for (int j = 0; j < p->n; j++) {
        c->cp[j] = t;
        for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++)
            if (x[q] != 0) {
                c->ri[t] = p->rowind[q];
                c->v[t++] = x[q];
            }
    }
    c->cp[p->n] = t;
}

/* y = A x for a complex x */
static void csc_mul(const track_csc *c, int n, const double complex *x, double complex *y)
{
    memset(y, 0, (size_t)n * sizeof *y);
    for (int j = 0; j < n; j++) {
        double complex xj = x[j];
        for (int q = c->cp[j]; q < c->cp[j + 1]; q++)
            y[c->ri[q]] += c->v[q] * xj;
    }
}

/* a^H b, in real arithmetic (no complex-multiply special cases in the loop) */
static double complex cdot(const double complex *a, const double complex *b, int n)
{
    const double *x = (const double *)a, *y = (const double *)b;
    double sr = 0, si = 0;
#pragma omp simd reduction(+ : sr, si)
    for (int i = 0; i < n; i++) {
        sr += x[2 * i] * y[2 * i] + x[2 * i + 1] * y[2 * i + 1];
        si += x[2 * i] * y[2 * i + 1] - x[2 * i + 1] * y[2 * i];
    }
    return sr + I * si;
}

/* y += a x (complex), in real arithmetic */
static void caxpy(int n, double complex a, const double complex *x, double complex *y)
{
    const double *u = (const double *)x;
    double *v = (double *)y, ar = creal(a), ai = cimag(a);
#pragma omp simd
    for (int i = 0; i < n; i++) {
        double ur = u[2 * i], ui = u[2 * i + 1];
        v[2 * i] += ar * ur - ai * ui;
        v[2 * i + 1] += ar * ui + ai * ur;
    }
}

/* a^H m, a^H d, a^H k in one sweep over a (the three projections of one basis pair) */
static void cdot3(const double complex *a, const double complex *m, const double complex *d,
                  const double complex *k, int n, double complex *out)
{
    const double *x = (const double *)a, *y1 = (const double *)m, *y2 = (const double *)d,
                 *y3 = (const double *)k;
    double r1 = 0, i1 = 0, r2 = 0, i2 = 0, r3 = 0, i3 = 0;
#pragma omp simd reduction(+ : r1, i1, r2, i2, r3, i3)
    for (int i = 0; i < n; i++) {
        double xr = x[2 * i], xi = x[2 * i + 1];
        r1 += xr * y1[2 * i] + xi * y1[2 * i + 1];
        i1 += xr * y1[2 * i + 1] - xi * y1[2 * i];
        r2 += xr * y2[2 * i] + xi * y2[2 * i + 1];
        i2 += xr * y2[2 * i + 1] - xi * y2[2 * i];
        r3 += xr * y3[2 * i] + xi * y3[2 * i + 1];
        i3 += xr * y3[2 * i + 1] - xi * y3[2 * i];
    }
    out[0] = r1 + I * i1;
    out[1] = r2 + I * i2;
    out[2] = r3 + I * i3;
}

/* r += cm m + cd d + ck k (complex), in one sweep over r: a Ritz vector's residual
 * P(lambda) x from the basis' products */
static void caxpy3(int n, double complex cm, const double complex *m, double complex cd,
                   const double complex *d, double complex ck, const double complex *k,
                   double complex *r)
{
    const double *u1 = (const double *)m, *u2 = (const double *)d, *u3 = (const double *)k;
    double *v = (double *)r, ar = creal(cm), ai = cimag(cm), br = creal(cd), bi = cimag(cd),
           cr = creal(ck), ci = cimag(ck);
#pragma omp simd
    for (int i = 0; i < n; i++) {
        double mr = u1[2 * i], mi = u1[2 * i + 1], dr = u2[2 * i], di = u2[2 * i + 1],
               kr = u3[2 * i], ki = u3[2 * i + 1];
        v[2 * i] += ar * mr - ai * mi + br * dr - bi * di + cr * kr - ci * ki;
        v[2 * i + 1] += ar * mi + ai * mr + br * di + bi * dr + cr * ki + ci * kr;
    }
}

static double cnrm(const double complex *a, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += creal(a[i]) * creal(a[i]) + cimag(a[i]) * cimag(a[i]);
    return sqrt(s);
}

/* Orthogonalises v against the q columns of Q (twice) and normalises it; 0 when v is
 * (numerically) in their span. */
static int corth(const double complex *Q, int n, int q, double complex *v)
{
    double before = cnrm(v, n);
    if (!(before > 0) || !isfinite(before)) return 0;
    for (int pass = 0; pass < 2; pass++)
        for (int c = 0; c < q; c++) {
            const double complex *qc = Q + (size_t)c * n;
            caxpy(n, -cdot(qc, v, n), qc, v);
        }
    double after = cnrm(v, n);
    if (!(after > 1e-10 * before)) return 0;
    for (int i = 0; i < n; i++)
        v[i] /= after;
    return 1;
}

typedef struct found {
    double complex lam;
    double complex *x; /* n, unit 2-norm */
} found;

/* A kept factorisation of R P(sg) R (R = diag(|P_ii|^-1/2), rs) */
typedef struct track_slot {
    gd_splu lu;
    double *rs; /* n */
    double complex sg;
    long used; /* the stamp of its last use (the least recently used is replaced) */
    int valid;
} track_slot;

typedef struct track_ws {
    int n, qmax;
    double complex *Q, *MQ, *DQ, *KQ;            /* n x qmax */
    double complex *Mq, *Dq, *Kq;                /* qmax x qmax */
    double complex *A2, *B2, *VR, *al, *be, *Mw; /* 2 qmax x 2 qmax, 2 qmax */
    double complex *r, *t;                       /* n */
    double complex *z;                           /* the complex pattern values, nnz */
    track_csc cm, cd, ck;                        /* M, D, K at this speed */
    const double *msrc;                          /* the values cm holds */
    track_slot slot[GD_TRACK_SLOTS];
    int nslot, maxslot; /* slots in use, allowed (by GD_TRACK_LU_BYTES) */
    long stamp;
    track_slot *cur; /* the factorisation of the current cluster */
    int fresh;       /* cur was factored for this cluster */
    int passes;      /* the most Rayleigh-Ritz passes a cluster took */
} track_ws;

/* gd_sparse_track's workspace, kept in gd_sparse_ws from speed to speed */
typedef struct gd_track_cache {
    int n, nnz, km;
    track_ws w;
    found *fd;
    double complex *X, *lam0, *x0;
    int *match;
    double *L, *v, *hl;
    gd_shift_invert op; /* the completeness check's P(-s) (its pivot order reused) */
    double *p;          /* nnz */
} gd_track_cache;

/* Solves M x = t in place (M: n x n, column-major, overwritten) by Gaussian
 * elimination with partial pivoting on |Re| + |Im|, as LAPACK's zgetf2, without its
 * call overheads (n <= 12 here, a few per Rayleigh-Ritz pass); 0 on a zero pivot. */
static int small_solve(int n, double complex *M, double complex *t)
{
    for (int c = 0; c < n; c++) {
        int p = c;
        double pm = -1;
        for (int i = c; i < n; i++) {
            double a = fabs(creal(M[i + c * n])) + fabs(cimag(M[i + c * n]));
            if (a > pm) {
                pm = a;
                p = i;
            }
        }
        if (!(pm > 0)) return 0;
        if (p != c) {
            for (int j = c; j < n; j++) {
                double complex x = M[c + j * n];
                M[c + j * n] = M[p + j * n];
                M[p + j * n] = x;
            }
            double complex x = t[c];
            t[c] = t[p];
            t[p] = x;
        }
        double complex ip = 1.0 / M[c + c * n];
        for (int i = c + 1; i < n; i++) {
            double complex f = M[i + c * n] * ip;
            if (f == 0) continue;
            for (int j = c + 1; j < n; j++)
                M[i + j * n] -= f * M[c + j * n];
            t[i] -= f * t[c];
        }
    }
    for (int c = n - 1; c >= 0; c--) {
        double complex x = t[c];
        for (int j = c + 1; j < n; j++)
            x -= M[c + j * n] * t[j];
        t[c] = x / M[c + c * n];
    }
    return 1;
}

/* The eigenvalue of the q2 x q2 pencil (A, B) nearest sg by Rayleigh quotient iteration
 * (the start vector [e_e; sg e_e]: the basis' column e is the mode's previous
 * eigenvector): 1 with *lam and v (unit norm; the first q2 / 2 entries are the Ritz
 * vector's coefficients), 0 when it does not settle in 8 steps. Mw (q2 x q2), t (q2):
 * scratch. */
static int small_rqi(int q2, const double complex *A, const double complex *B, double complex sg,
                     int e, double complex *Mw, double complex *t, double complex *v,
                     double complex *lam)
{
    int q = q2 / 2;
    memset(v, 0, (size_t)q2 * sizeof *v);
    v[e] = 1;
    v[q + e] = sg;
    for (int it = 0; it < 8; it++) {
        /* t = (A - sg B)^-1 B v by blocks (A = [0 I; -Kq -Dq], B = [I 0; 0 Mq]): the
         * first block row gives t2 = v1 + sg t1, the second then
         * (Kq + sg Dq + sg^2 Mq) t1 = -Mq v2 - (Dq + sg Mq) v1, a q x q solve in place
         * of the 2q x 2q one (an eighth of the elimination) */
        for (int j = 0; j < q; j++)
            for (int i = 0; i < q; i++) {
                size_t ij = q + i + (size_t)(q + j) * q2; /* Mq[i, j] in B, -Dq[i, j] in A */
                double complex mq = B[ij], dq = -A[ij], kq = -A[q + i + (size_t)j * q2];
                Mw[i + (size_t)j * q] = kq + sg * (dq + sg * mq);
            }
        for (int i = 0; i < q; i++) {
            double complex sum = 0;
            for (int j = 0; j < q; j++) {
                size_t ij = q + i + (size_t)(q + j) * q2;
                sum += B[ij] * v[q + j] + (sg * B[ij] - A[ij]) * v[j];
            }
            t[i] = -sum;
        }
        if (!small_solve(q, Mw, t)) return 0;
        for (int i = 0; i < q; i++)
            t[q + i] = v[i] + sg * t[i];
        /* t = (A - sg B)^-1 B v = mu v at convergence, lambda = sg + 1 / mu */
        double complex vt = cdot(v, t, q2), vv = cdot(v, v, q2);
        double nt = cnrm(t, q2);
        if (!(nt > 0) || !isfinite(nt) || vt == 0) return 0;
        double complex next = sg + vv / vt;
        for (int i = 0; i < q2; i++)
            v[i] = t[i] / nt;
        if (cabs(next - sg) <= 1e-14 * cabs(next)) {
            *lam = next;
            return 1;
        }
        sg = next;
    }
    return 0;
}

static int track_lu(const gd_dynmat *a, const gd_splu_symbolic *sym, const double *k,
                    const double *d, double complex sg, double gap, int reuse, track_ws *w);

/* The c modes of one cluster (previous eigenvalues lam0, vectors x0, n x c) at the
 * values k, d: their eigenpairs into out. 0 ok, 1 not converged (fall back), -1 no
 * memory. */
static int refine_cluster(const gd_dynmat *a, const gd_splu_symbolic *sym, const double *k,
                          const double *d, int c, const double complex *lam0,
                          const double complex *x0, int nx0, double gap, double tol, track_ws *w,
                          found *out)
{
    const gd_pattern *p = &a->pat;
    int n = p->n, q = 0, qmax = GD_TRACK_MAXQ * c, rc = 1;
    /* factored: a factorisation for this pass' corrections; reuse: a kept one may
     * serve; fresh_prev: the previous pass' corrections came from a fresh one (only
     * then does a residual that stops falling mean the rounding floor) */
    int factored = 0, reuse = 1, fresh_prev = 1, own = 0;
    for (int i = 0; i < nx0 && q < qmax; i++) {
        double complex *v = w->Q + (size_t)q * n;
        memcpy(v, x0 + (size_t)i * n, (size_t)n * sizeof *v);
        if (corth(w->Q, n, q, v)) q++;
    }
    int done = 0; /* columns whose products are in MQ, DQ, KQ and the projections */
    int conv[GD_TRACK_MAXC], used[2 * GD_TRACK_MAXC * GD_TRACK_MAXQ];
    double last[GD_TRACK_MAXC];
    for (int it = 0; it < GD_TRACK_MAXIT && q > 0; it++) {
        for (int j = done; j < q; j++) {
            csc_mul(&w->cm, n, w->Q + (size_t)j * n, w->MQ + (size_t)j * n);
            csc_mul(&w->cd, n, w->Q + (size_t)j * n, w->DQ + (size_t)j * n);
            csc_mul(&w->ck, n, w->Q + (size_t)j * n, w->KQ + (size_t)j * n);
        }
        /* the projections Q^H X Q, grown by the new rows and columns */
        for (int j = 0; j < q; j++)
            for (int i = 0; i < q; i++) {
                if (i < done && j < done) continue;
                double complex pr[3];
                cdot3(w->Q + (size_t)i * n, w->MQ + (size_t)j * n, w->DQ + (size_t)j * n,
                      w->KQ + (size_t)j * n, n, pr);
                w->Mq[i + (size_t)j * qmax] = pr[0];
                w->Dq[i + (size_t)j * qmax] = pr[1];
                w->Kq[i + (size_t)j * qmax] = pr[2];
            }
        done = q;
        /* [0 I; -Kq -Dq] v = lambda [I 0; 0 Mq] v */
        int q2 = 2 * q;
        memset(w->A2, 0, (size_t)q2 * q2 * sizeof *w->A2);
        memset(w->B2, 0, (size_t)q2 * q2 * sizeof *w->B2);
        for (int i = 0; i < q; i++) {
            w->A2[i + (size_t)(q + i) * q2] = 1;
            w->B2[i + (size_t)i * q2] = 1;
            for (int j = 0; j < q; j++) {
                w->A2[q + i + (size_t)j * q2] = -w->Kq[i + (size_t)j * qmax];
                w->A2[q + i + (size_t)(q + j) * q2] = -w->Dq[i + (size_t)j * qmax];
                w->B2[q + i + (size_t)(q + j) * q2] = w->Mq[i + (size_t)j * qmax];
            }
        }
        /* each mode's Ritz pair by Rayleigh quotient iteration on the small pencil from
         * its prediction (the extrapolated value, then the previous pass'): a few small
         * solves, and more accurate than QZ, whose errors scale with the pencil's norm
         * (the stiff modes' in the projections: on a 10k-DOF gearbox's cluster of three
         * QZ's Ritz values left the residuals at 1e-7); QZ when an iteration fails or two
         * do not settle apart, each nearest its own prediction (predictions within
         * GD_TRACK_TIE of each other, the members of a double mode at rest, are a tie:
         * either assignment is right; taking it as a failure sent every pass of every
         * pair of the planetary set's first continued speed to QZ, 28 M of its 553 M
         * instructions, bench/bench_planetary.sh) */
        /* each member's reference: its prediction, then its previous pass' Ritz value (a
         * pair whose values moved past each other's predictions then keeps its
         * assignment by Rayleigh quotient iteration instead of going to QZ, as the
         * planetary set's pairs at a chain's first continued speed did) */
        double complex ref[GD_TRACK_MAXC];
        for (int m = 0; m < c; m++)
            ref[m] = it ? out[m].lam : lam0[m];
        int nritz = q2, byrqi = c <= q;
        for (int m = 0; m < c && byrqi; m++) {
            byrqi = small_rqi(q2, w->A2, w->B2, ref[m], m, w->Mw, w->t, w->VR + (size_t)m * q2,
                              &w->al[m]);
            w->be[m] = 1;
        }
        for (int m = 0; m < c && byrqi; m++)
            for (int j = 0; j < c; j++)
                if (j != m && (cabs(w->al[m] - ref[j]) <=
                                   cabs(w->al[m] - ref[m]) - GD_TRACK_TIE * cabs(ref[m]) ||
                               cabs(w->al[m] - w->al[j]) <= 1e-8 * cabs(w->al[m])))
                    byrqi = 0;
        if (byrqi) {
            nritz = c;
        } else if (LAPACKE_zggev(LAPACK_COL_MAJOR, 'N', 'V', q2, w->A2, q2, w->B2, q2, w->al, w->be,
                                 NULL, 1, w->VR, q2)) {
            break;
        }
        memset(used, 0, sizeof used);
        int nadd = 0, allconv = 1;
        for (int m = 0; m < c; m++) {
            /* the Ritz value nearest this mode's reference */
            int best = -1;
            double bd = INFINITY;
            for (int j = 0; j < nritz; j++) {
                double complex al = w->al[j], be = w->be[j];
                double nb = creal(be) * creal(be) + cimag(be) * cimag(be),
                       na = creal(al) * creal(al) + cimag(al) * cimag(al);
                if (used[j] || !(nb > 1e-28 * na)) continue;
                double complex dl = al / be - ref[m];
                double dist = creal(dl) * creal(dl) + cimag(dl) * cimag(dl);
                if (dist < bd) {
                    bd = dist;
                    best = j;
                }
            }
            if (best < 0) goto fail;
            used[best] = 1;
            double complex lam = w->al[best] / w->be[best];
            const double complex *s = w->VR + (size_t)best * q2;
            double complex *x = out[m].x;
            memset(x, 0, (size_t)n * sizeof *x);
            memset(w->r, 0, (size_t)n * sizeof *w->r);
            for (int j = 0; j < q; j++) { /* x = Q s, r = P(lambda) x */
                const double complex *qj = w->Q + (size_t)j * n, *mj = w->MQ + (size_t)j * n,
                                     *dj = w->DQ + (size_t)j * n, *kj = w->KQ + (size_t)j * n;
                double complex sj = s[j];
                caxpy(n, sj, qj, x);
                caxpy3(n, sj * lam * lam, mj, sj * lam, dj, sj, kj, w->r);
            }
            /* x^H P'(lambda) x = s^H (2 lambda Mq + Dq) s, from the projections */
            double complex dp = 0;
            for (int j = 0; j < q; j++)
                for (int i = 0; i < q; i++)
                    dp += conj(s[i]) *
                          (2 * lam * w->Mq[i + (size_t)j * qmax] + w->Dq[i + (size_t)j * qmax]) *
                          s[j];
            double nx = cnrm(x, n), nr = cnrm(w->r, n);
            if (!(nx > 0)) goto fail;
            for (int i = 0; i < n; i++)
                x[i] /= nx;
            out[m].lam = lam;
            /* converged, or stalled at the rounding floor of P(lambda) x (stiff elements
             * beside slow modes: eps (element frequency / mode's)^2), below GD_TRACK_STALL */
            double rel = nr * nx / (cabs(lam) * cabs(dp));
            conv[m] = rel <= tol ||
                      (it > 0 && fresh_prev && rel <= GD_TRACK_STALL && rel > 0.1 * last[m]);
            last[m] = rel;
            if (conv[m]) continue;
            allconv = 0;
            /* residual inverse iteration: the correction P(sigma)^-1 r joins the basis,
             * sigma the mean of the cluster's first Ritz values (already far nearer the
             * eigenvalues than the extrapolation) */
            if (q + nadd >= qmax) continue;
            if (it > 0 && c > 1 && rel > GD_TRACK_OWN_SHIFT) {
                /* a cluster that split (a double mode under the gyroscopic terms): each
                 * member corrects at its own Ritz value while far from converged (the
                 * mean shift gains only the half-split over the distance to the next
                 * mode per pass); near convergence the mean again (a shift at the value
                 * itself leaves a correction all along the vector already in the basis) */
                int fr = track_lu(a, sym, k, d, lam, gap, 0, w);
                if (fr) return fr < 0 ? -1 : 1;
                factored = 1;
                own = 1;
            } else if (!factored) {
                double complex sg = 0;
                for (int i = 0; i < c; i++)
                    sg += (m == i ? lam : lam0[i]) / c;
                /* the later members' Ritz values are not picked yet: their predictions */
                for (int i = 0; i < m; i++)
                    sg += (out[i].lam - lam0[i]) / c;
                int fr = track_lu(a, sym, k, d, sg, gap, reuse, w);
                if (fr) return fr < 0 ? -1 : 1;
                factored = 1;
            }
            double complex *v = w->Q + (size_t)(q + nadd) * n;
            const double *rs = w->cur->rs;
            memcpy(v, w->r, (size_t)n * sizeof *v);
            for (int i = 0; i < n; i++)
                v[i] *= rs[i];
            gd_splu_solve(&w->cur->lu, sym, n, 1, (double *)v);
            for (int i = 0; i < n; i++)
                v[i] *= rs[i];
            if (corth(w->Q, n, q + nadd, v)) nadd++;
        }
        fresh_prev = !factored || w->fresh;
        if (own) { /* the next pass' mean shift: a fresh factorisation */
            factored = 0;
            reuse = 0;
            own = 0;
        }
        if (factored && !w->fresh) { /* a kept factorisation serves one pass */
            factored = 0;
            reuse = 0;
        }
        if (allconv) {
            if (it + 1 > w->passes) w->passes = it + 1;
            rc = 0;
            break;
        }
        if (nadd == 0) break;
        q += nadd;
    }
fail:
    return rc;
}

/* Factors P(sigma) (complex) for sigma a little off sg: a mode the speed does not move
 * (axial, torsional) would otherwise make it singular. 1e-6 |sg| away, inverse
 * iteration still gains about four digits per step on a mode 1 % from the next; the
 * pivot order of the speed's first factorisation serves the others (refactor: a poorer
 * pivot costs convergence, which the residuals measure, not accuracy). 0 ok, 1 singular,
 * -1 no memory. */
static int factor_shift(const gd_dynmat *a, const gd_splu_symbolic *sym, const double *k,
                        const double *d, double complex sg, track_ws *w, track_slot *sl)
{
    const gd_pattern *p = &a->pat;
    gd_splu *lu = &sl->lu;
    int fr = 1;
    for (double off = 1e-6; fr == 1 && off < 2e-3; off *= 1e3) {
        double complex so = sg + off * cabs(sg) * (0.6 + 0.8 * I);
        for (int q = 0; q < p->nnz; q++)
            w->z[q] = so * so * a->m[q] + so * d[q] + k[q];
        /* R P R with R = diag(|P_ii|^-1/2), as shift_invert.c: no KLU row scaling (a
         * complex modulus per entry) */
        double *rs = sl->rs;
        for (int j = 0; j < p->n; j++) {
            double djj = p->diag[j] >= 0 ? cabs(w->z[p->diag[j]]) : 0;
            rs[j] = djj > 0 && isfinite(djj) ? 1.0 / sqrt(djj) : 1.0;
        }
        for (int j = 0; j < p->n; j++)
            for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++)
                w->z[q] *= rs[p->rowind[q]] * rs[j];
        if (lu->num) fr = gd_splu_refactor(lu, p, sym, (const double *)w->z);
        if (fr == 1) {
            gd_splu_free(lu);
            fr = gd_splu_factor(lu, p, sym, (const double *)w->z, 1, 0);
        }
        sl->sg = so;
    }
    return fr;
}

/* Points w->cur at a factorisation for the shift sg of a cluster gap away from the
 * other modes: a kept one within GD_TRACK_REUSE gap when reuse allows (w->fresh = 0),
 * else a fresh one (w->fresh = 1) in the slot nearest sg when within gap / 2 (the
 * cluster's own from an earlier speed), a new slot, or the least recently used. 0 ok,
 * 1 singular, -1 no memory. */
static int track_lu(const gd_dynmat *a, const gd_splu_symbolic *sym, const double *k,
                    const double *d, double complex sg, double gap, int reuse, track_ws *w)
{
    int best = -1;
    double bd = INFINITY;
    w->stamp++;
    for (int i = 0; i < w->nslot; i++)
        if (w->slot[i].valid && cabs(w->slot[i].sg - sg) < bd) {
            bd = cabs(w->slot[i].sg - sg);
            best = i;
        }
    if (reuse && best >= 0 && bd <= GD_TRACK_REUSE * gap) {
        w->cur = &w->slot[best];
        w->cur->used = w->stamp;
        w->fresh = 0;
        return 0;
    }
    int t = best >= 0 && bd <= 0.5 * gap ? best : -1;
    for (int i = 0; t < 0 && i < w->nslot; i++)
        if (!w->slot[i].valid) t = i;
    if (t < 0 && w->nslot < (w->maxslot > 0 ? w->maxslot : 1)) {
        track_slot *sl = &w->slot[w->nslot];
        if (!sl->rs) sl->rs = malloc((size_t)w->n * sizeof *sl->rs);
        if (!sl->rs) return -1;
        t = w->nslot++;
    }
    if (t < 0) {
        t = 0;
        for (int i = 1; i < w->nslot; i++)
            if (w->slot[i].used < w->slot[t].used) t = i;
    }
    track_slot *sl = &w->slot[t];
    sl->valid = 0;
    int fr = factor_shift(a, sym, k, d, sg, w, sl);
    if (fr) return fr;
    sl->valid = 1;
    sl->used = w->stamp;
    w->cur = sl;
    w->fresh = 1;
    /* the budget, from the first factorisation's size (entries of L and U, complex,
     * with their row indices) */
    if (w->maxslot == 0 && sl->lu.num) {
        double bytes = 24.0 * ((double)sl->lu.num->lnz + sl->lu.num->unz) + 64.0 * w->n;
        double cnt = GD_TRACK_LU_BYTES / bytes;
        w->maxslot = cnt >= GD_TRACK_SLOTS ? GD_TRACK_SLOTS : cnt >= 1 ? (int)cnt : 1;
    }
    return 0;
}

typedef struct track_order {
    int idx;
    double mag;
} track_order;

static int cmp_order(const void *a, const void *b)
{
    const track_order *x = a, *y = b;
    if (x->mag != y->mag) return (x->mag > y->mag) - (x->mag < y->mag);
    return x->idx - y->idx;
}

typedef struct si_ctx {
    gd_shift_invert *op;
    const gd_splu_symbolic *sym;
} si_ctx;

static void si_apply(void *ctx, const double *x, double *y)
{
    si_ctx *c = ctx;
    gd_shift_invert_apply(c->op, c->sym, x, y);
}

/* Appends v (2n real) to the orthonormal columns L[:, 0:*nl] when independent
 * (classical Gram-Schmidt, as BLAS matrix-vector products; h: nl scratch). */
static void lock_vector(double *L, int n2, int *nl, double *v, double *h)
{
    double before = cblas_dnrm2(n2, v, 1), after = before;
    if (!(before > 0)) return;
    /* a second pass only when the first cancelled more than half the norm's square
     * (Daniel, Gragg, Kaufman and Stewart, Math. Comp. 30, 1976): the vectors of
     * distinct modes rarely do */
    for (int pass = 0; pass < 2 && *nl > 0; pass++) {
        double prev = after;
        cblas_dgemv(CblasColMajor, CblasTrans, n2, *nl, 1.0, L, n2, v, 1, 0.0, h, 1);
        cblas_dgemv(CblasColMajor, CblasNoTrans, n2, *nl, -1.0, L, n2, h, 1, 1.0, v, 1);
        after = cblas_dnrm2(n2, v, 1);
        if (after > 0.70710678118654752 * prev) break;
    }
    if (!(after > 1e-8 * before)) return;
    double *dst = L + (size_t)(*nl) * n2;
    for (int i = 0; i < n2; i++)
        dst[i] = v[i] / after;
    (*nl)++;
}

static void slots_free(track_ws *w)
{
    for (int i = 0; i < w->nslot; i++) {
        gd_splu_free(&w->slot[i].lu);
        w->slot[i].valid = 0;
    }
    w->nslot = 0;
}

void gd_sparse_track_reset(gd_sparse_ws *ws)
{
    gd_track_cache *tc = ws->track;
    if (!tc) return;
    slots_free(&tc->w);
    gd_splu_free(&tc->op.lu);
}

void gd_sparse_track_free(gd_sparse_ws *ws)
{
    gd_track_cache *tc = ws->track;
    if (!tc) return;
    track_ws *w = &tc->w;
    slots_free(w);
    for (int i = 0; i < GD_TRACK_SLOTS; i++)
        free(w->slot[i].rs);
    void *bufs[] = {w->cm.cp, w->cm.ri,  w->cm.v, w->cd.cp, w->cd.ri, w->cd.v, w->ck.cp,
                    w->ck.ri, w->ck.v,   w->Q,    w->MQ,    w->DQ,    w->KQ,   w->Mq,
                    w->Dq,    w->Kq,     w->A2,   w->B2,    w->VR,    w->Mw,   w->al,
                    w->be,    w->r,      w->t,    w->z,     tc->fd,   tc->X,   tc->lam0,
                    tc->x0,   tc->match, tc->L,   tc->v,    tc->hl,   tc->p};
    for (size_t i = 0; i < sizeof bufs / sizeof *bufs; i++)
        free(bufs[i]);
    gd_shift_invert_free(&tc->op);
    free(tc);
    ws->track = NULL;
}

/* ws's track cache for n DOFs, nnz pattern entries and km modes (made or grown as
 * needed; NULL when out of memory) */
static gd_track_cache *cache_get(gd_sparse_ws *ws, int n, int nnz, int km)
{
    gd_track_cache *tc = ws->track;
    if (tc && tc->n == n && tc->nnz == nnz && tc->km >= km) return tc;
    gd_sparse_track_free(ws);
    tc = ws->track = calloc(1, sizeof *tc);
    if (!tc) return NULL;
    ws->track_free = gd_sparse_track_free;
    tc->n = n;
    tc->nnz = nnz;
    tc->km = km;
    track_ws *w = &tc->w;
    size_t qmax = GD_TRACK_MAXQ * GD_TRACK_MAXC, q2 = 2 * qmax, nn = (size_t)n, k1 = km + 1;
    w->n = n;
    w->qmax = (int)qmax;
    w->Q = malloc(nn * qmax * sizeof *w->Q);
    w->MQ = malloc(nn * qmax * sizeof *w->MQ);
    w->DQ = malloc(nn * qmax * sizeof *w->DQ);
    w->KQ = malloc(nn * qmax * sizeof *w->KQ);
    w->Mq = malloc(qmax * qmax * sizeof *w->Mq);
    w->Dq = malloc(qmax * qmax * sizeof *w->Dq);
    w->Kq = malloc(qmax * qmax * sizeof *w->Kq);
    w->A2 = malloc(q2 * q2 * sizeof *w->A2);
    w->B2 = malloc(q2 * q2 * sizeof *w->B2);
    w->VR = malloc(q2 * q2 * sizeof *w->VR);
    w->Mw = malloc(q2 * q2 * sizeof *w->Mw);
    w->al = malloc(q2 * sizeof *w->al);
    w->be = malloc(q2 * sizeof *w->be);
    w->r = malloc(nn * sizeof *w->r);
    w->t = malloc((nn > q2 ? nn : q2) * sizeof *w->t);
    w->z = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *w->z);
    tc->fd = calloc(k1, sizeof *tc->fd);
    tc->X = malloc(nn * k1 * sizeof *tc->X);
    tc->lam0 = malloc(k1 * sizeof *tc->lam0);
    tc->x0 = malloc(nn * 2 * GD_TRACK_MAXC * sizeof *tc->x0);
    tc->match = malloc(k1 * sizeof *tc->match);
    tc->L = malloc(2 * nn * (2 * k1) * sizeof *tc->L);
    tc->v = malloc(2 * nn * sizeof *tc->v);
    tc->hl = malloc(2 * k1 * sizeof *tc->hl);
    tc->p = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *tc->p);
    track_csc *cs[3] = {&w->cm, &w->cd, &w->ck};
    for (int i = 0; i < 3; i++) {
        cs[i]->cp = malloc((nn + 1) * sizeof *cs[i]->cp);
        cs[i]->ri = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *cs[i]->ri);
        cs[i]->v = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *cs[i]->v);
        if (!cs[i]->cp || !cs[i]->ri || !cs[i]->v) {
            gd_sparse_track_free(ws);
            return NULL;
        }
    }
    if (!w->Q || !w->MQ || !w->DQ || !w->KQ || !w->Mq || !w->Dq || !w->Kq || !w->A2 || !w->B2 ||
        !w->VR || !w->Mw || !w->al || !w->be || !w->r || !w->t || !w->z || !tc->fd || !tc->X ||
        !tc->lam0 || !tc->x0 || !tc->match || !tc->L || !tc->v || !tc->hl || !tc->p) {
        gd_sparse_track_free(ws);
        return NULL;
    }
    return tc;
}

/* The completeness check's shift-invert operator at sigma (as gd_shift_invert_setup),
 * refactored with the pivot order of the previous speed's when there is one. 0 ok, 1
 * singular, -1 no memory. */
static int check_op(gd_track_cache *tc, const gd_dynmat *a, const gd_splu_symbolic *sym,
                    double sigma, double g, const double *k, const double *d)
{
    gd_shift_invert *op = &tc->op;
    const gd_pattern *pt = &a->pat;
    if (!op->lu.num || !op->r || !op->work) {
        gd_shift_invert_free(op);
        return gd_shift_invert_setup(op, pt, a->m, sym, sigma, g, k, d);
    }
    op->sigma = sigma;
    op->scale = g;
    op->m = a->m;
    op->d = d;
    double *p = tc->p;
    for (int i = 0; i < pt->nnz; i++)
        p[i] = sigma * sigma * a->m[i] + sigma * d[i] + k[i];
    for (int j = 0; j < pt->n; j++) { /* R P R, as gd_shift_invert_setup */
        int q = pt->diag[j];
        double djj = q >= 0 ? fabs(p[q]) : 0;
        op->r[j] = djj > 0 && isfinite(djj) ? 1.0 / sqrt(djj) : 1.0;
    }
    for (int j = 0; j < pt->n; j++)
        for (int q = pt->colptr[j]; q < pt->colptr[j + 1]; q++)
            p[q] *= op->r[pt->rowind[q]] * op->r[j];
    int rc = gd_splu_refactor(&op->lu, pt, sym, p);
    if (rc == 1) {
        gd_splu_free(&op->lu);
        rc = gd_splu_factor(&op->lu, pt, sym, p, 0, 0);
    }
    return rc;
}

static gd_status track(const gd_dynmat *a, const gd_splu_symbolic *sym, const gd_modal_options *opt,
                       const gd_modal_result *prev, const gd_modal_result *prev2, gd_sparse_ws *ws,
                       gd_modal_result **out, int *hard, gd_error *err, int undamped_ok)
{
    *out = NULL;
    *hard = 1;
    const gd_system *sys = a->sys;
    int n = a->pat.n, nnz = a->pat.nnz, km = prev ? prev->nmodes : 0;
    if (!prev || !prev->shape_re || !prev->shape_im || prev->ndof != n || km < 1 ||
        (opt->kind == GD_MODAL_UNDAMPED && !undamped_ok) || sys->nmassless > 0)
        return GD_OK;
    gd_status st = GD_OK;
    double *k = ws->k, *d = ws->d;
    gd_dynmat_at_state(a, opt->speed, opt->law_state, k, d);
    if (opt->kind == GD_MODAL_UNDAMPED) memset(d, 0, (size_t)nnz * sizeof *d);
    int any_d = 0;
    for (int i = 0; i < nnz; i++)
        any_d |= d[i] != 0;
    int conservative = !any_d && gd_pattern_symmetric(&a->pat, k);
    double s, g, rtol;
    gd_sparse_shift_auto(a, k, &s, &g, &rtol);
    /* rigid-body modes first (sorted so), kept when still in K's null space */
    int kr = 0;
    while (kr < km && prev->modes[kr].rigid_body)
        kr++;
    for (int j = kr; j < km; j++)
        if (prev->modes[j].rigid_body || prev->modes[j].lambda_im <= 0 ||
            hypot(prev->modes[j].lambda_re, prev->modes[j].lambda_im) < 10 * rtol)
            return GD_OK; /* overdamped or near-rigid modes: Krylov-Schur sorts those */
    int nel = km - kr, n2 = 2 * n, ok = 0;
    /* the modes the caller needs (gd_modal_options.nmodes, rigid ones included); prev's
     * others are a guard band that may be dropped */
    int need = opt->nmodes > 0 && opt->nmodes < km && !undamped_ok ? opt->nmodes : km;
    double kmax = 0;
    for (int q = 0; q < nnz; q++)
        kmax = fmax(kmax, fabs(k[q]));
    gd_track_cache *tc = cache_get(ws, n, nnz, km);
    if (!tc) goto nomem;
    track_ws *wp = &tc->w;
    /* a one-shot solve (no chain: gd_sparse_modes_to_tol) keeps no factorisation for a later
     * speed: with one slot each factorisation after the first is a refactorisation with its
     * pivot order (klu_refactor, no pivot search) */
    if (!ws->chain) wp->maxslot = 1;
    found *fd = tc->fd;
    double complex *X = tc->X, *lam0 = tc->lam0, *x0 = tc->x0;
    int *match = tc->match;
    double *L = tc->L, *v = tc->v, *hl = tc->hl;
    gd_shift_invert *op = &tc->op;
    gd_modal_result *res = NULL;
    wp->passes = 0;
    if (wp->msrc != a->m) {
        csc_compact(&a->pat, a->m, &wp->cm);
        wp->msrc = a->m;
    }
    csc_compact(&a->pat, d, &wp->cd);
    csc_compact(&a->pat, k, &wp->ck);
    int nl = 0;
    /* rigid-body shapes u: |K u| at rounding level, and [u; 0], [0; u] span the
     * defective zero's invariant subspace of the first-order form */
    for (int j = 0; j < kr; j++) {
        const double *u = prev->shape_re + (size_t)j * n;
        double nu = 0, nk = 0;
        for (int i = 0; i < n; i++)
            nu = fmax(nu, fabs(u[i]));
        memset(v, 0, (size_t)n2 * sizeof *v);
        gd_pattern_mul2(&a->pat, k, u, d, u, v); /* K u + D u */
        for (int i = 0; i < n; i++)
            nk = fmax(nk, fabs(v[i]));
        if (!(nk <= 1e-9 * kmax * nu)) goto done;
        memset(v, 0, (size_t)n2 * sizeof *v);
        memcpy(v, u, (size_t)n * sizeof *v);
        lock_vector(L, n2, &nl, v, hl);
        memset(v, 0, (size_t)n2 * sizeof *v);
        memcpy(v + n, u, (size_t)n * sizeof *v);
        lock_vector(L, n2, &nl, v, hl);
    }
    /* the elastic modes, cluster by cluster */
    for (int j = 0; j < nel; j++) {
        const gd_mode *md = &prev->modes[kr + j];
        lam0[j] = md->lambda_re + I * md->lambda_im;
        fd[j].x = X + (size_t)j * n;
    }
    /* the speed before: each mode's nearest value there (when the nearest both ways)
     * extrapolates the eigenvalue linearly, and its vector joins the start basis (with the
     * previous one it spans the linear extrapolation of the eigenvector) */
    int have2 = prev2 && prev2->shape_re && prev2->shape_im && prev2->nmodes >= km &&
                prev2->ndof == n && isfinite(opt->speed) && prev2->speed != prev->speed;
    double ratio = have2 ? (opt->speed - prev->speed) / (prev->speed - prev2->speed) : 0;
    for (int j = 0; j < nel; j++) {
        match[j] = -1;
        if (!have2 || prev2->modes[kr + j].rigid_body) continue;
        int best = -1;
        double bd = INFINITY;
        for (int i = kr; i < prev2->nmodes; i++) {
            double dd = cabs(prev2->modes[i].lambda_re + I * prev2->modes[i].lambda_im - lam0[j]);
            if (dd < bd) {
                bd = dd;
                best = i;
            }
        }
        if (best < 0) continue;
        double complex l2 = prev2->modes[best].lambda_re + I * prev2->modes[best].lambda_im;
        int back = -1;
        bd = INFINITY;
        for (int i = 0; i < nel; i++)
            if (cabs(lam0[i] - l2) < bd) {
                bd = cabs(lam0[i] - l2);
                back = i;
            }
        if (back != j) continue;
        match[j] = best;
    }
    for (int j = 0; j < nel; j++)
        if (match[j] >= 0) {
            const gd_mode *m2 = &prev2->modes[match[j]];
            lam0[j] += ratio * (lam0[j] - (m2->lambda_re + I * m2->lambda_im));
        }
    for (int j0 = 0; j0 < nel;) {
        int j1 = j0 + 1;
        while (j1 < nel && cabs(lam0[j1] - lam0[j1 - 1]) <= GD_TRACK_CLUSTER * cabs(lam0[j1]))
            j1++;
        int c = j1 - j0;
        if (c > GD_TRACK_MAXC) {
            if (kr + j0 < need) goto done;
            nel = j0; /* above the window: dropped (see below) */
            break;
        }
        int nx0 = 0;
        for (int m = 0; m < c; m++) {
            const double *re = prev->shape_re + (size_t)(kr + j0 + m) * n,
                         *im = prev->shape_im + (size_t)(kr + j0 + m) * n;
            for (int i = 0; i < n; i++)
                x0[(size_t)nx0 * n + i] = re[i] + I * im[i];
            nx0++;
        }
        for (int m = 0; m < c; m++) {
            if (match[j0 + m] < 0) continue;
            const double *re = prev2->shape_re + (size_t)match[j0 + m] * n,
                         *im = prev2->shape_im + (size_t)match[j0 + m] * n;
            for (int i = 0; i < n; i++)
                x0[(size_t)nx0 * n + i] = re[i] + I * im[i];
            nx0++;
        }
        /* the cluster's distance to the other modes (its shift's, to the nearest) */
        double complex mid = 0;
        for (int m = 0; m < c; m++)
            mid += lam0[j0 + m] / c;
        double gap = cabs(mid);
        for (int j = 0; j < nel; j++)
            if (j < j0 || j >= j1) gap = fmin(gap, cabs(lam0[j] - mid));
        /* a modal solve's own precision (gd_modal_options.tol) when finer */
        double tol = opt->tol > 0 ? fmin(opt->tol, GD_TRACK_TOL) : GD_TRACK_TOL;
        int rc = refine_cluster(a, sym, k, d, c, lam0 + j0, x0, nx0, gap, tol, wp, fd + j0);
        if (rc < 0) goto nomem;
        if (rc > 0) {
            /* a cluster of the guard band above the caller's window (a pair its edge cuts,
             * whose one member's refinement wanders between the two split values; a mode
             * leaving upwards): dropped with all above it, the check then covers the rest */
            if (kr + j0 < need) goto done;
            nel = j0;
            break;
        }
        j0 = j1;
    }
    /* completeness: no eigenvalue of the shift-invert operator outside the found ones
     * above the smallest |mu| = 1 / |lambda + s| of the modes the caller needs (the
     * need - kr largest found; the guard band's are deflated but not vouched for: a mode
     * just above the window's edge then costs nothing) */
    double thr = INFINITY;
    int want = need - kr < 1 ? 1 : need - kr;
    for (int j = 0; j < nel; j++) {
        double complex lam = fd[j].lam;
        if (cimag(lam) < 0) lam = conj(lam);
        fd[j].lam = lam;
        if (!(hypot(creal(lam), cimag(lam)) > rtol)) goto done;
    }
    for (int j = 0; j < nel; j++) {
        /* mode j's rank by |lambda + s| (ties by index): the want-th sets thr, fewer
         * modes than want the farthest */
        double dj = cabs(fd[j].lam + s);
        int rank = 0;
        for (int i = 0; i < nel; i++) {
            double di = cabs(fd[i].lam + s);
            rank += di < dj || (di == dj && i < j);
        }
        if (rank == want - 1 || (rank == nel - 1 && nel < want)) thr = 1.0 / dj;
    }
    for (int j = 0; j < nel; j++) {
        double complex lam = fd[j].lam;
        for (int part = 0; part < 2; part++) {
            for (int i = 0; i < n; i++) {
                double complex z1 = fd[j].x[i], z2 = lam * fd[j].x[i] / g;
                v[i] = part ? cimag(z1) : creal(z1);
                v[n + i] = part ? cimag(z2) : creal(z2);
            }
            lock_vector(L, n2, &nl, v, hl);
        }
    }
    /* the completeness check; a refinement of this speed's own Krylov-Schur modes
     * (undamped_ok: gd_sparse_refine) needs none, Krylov-Schur found them all */
    if (!undamped_ok) {
        int rcs = check_op(tc, a, sym, -s, g, k, d);
        if (rcs < 0) goto nomem;
        if (rcs > 0) goto done;
        si_ctx ctx = {op, sym};
        /* first to a loose residual, which settles a clear gap; to the tight one otherwise */
        double top = 0;
        st = gd_ks_deflated_top(si_apply, &ctx, n2, L, nl, GD_TRACK_LOOSE_TOL, &ws->ks, &top);
        if (!st && !(top < thr * (1 - GD_TRACK_LOOSE_MARGIN)) &&
            top < thr * (1 + GD_TRACK_LOOSE_MARGIN)) {
            st = gd_ks_deflated_top(si_apply, &ctx, n2, L, nl, GD_TRACK_CHECK_TOL, &ws->ks, &top);
            wp->passes = GD_TRACK_MAXIT; /* a mode just outside the window: hard */
            if (!st && !(top < thr * (1 - GD_TRACK_CHECK_MARGIN))) top = INFINITY;
        } else if (!st && !(top < thr * (1 - GD_TRACK_LOOSE_MARGIN))) {
            top = INFINITY;
        }
        if (st == GD_ENOMEM) goto nomem;
        if (st || !(top < thr)) {
            st = GD_OK;
            goto done;
        }
    }
    /* the result, as gd_sparse_modes gives it */
    track_order *ord = malloc((size_t)(nel > 0 ? nel : 1) * sizeof *ord);
    if (!ord) goto nomem;
    for (int j = 0; j < nel; j++) {
        double complex lam = fd[j].lam;
        if (conservative) { /* as gd_sparse_modes: lambda^2 = -omega^2 exactly */
            double l2 = creal(lam * lam);
            lam = l2 < 0 ? I * sqrt(-l2) : sqrt(l2);
            fd[j].lam = lam;
        }
        ord[j] = (track_order){j, cabs(lam)};
    }
    qsort(ord, (size_t)nel, sizeof *ord, cmp_order);
    km = kr + nel;
    res = gd_modal_result_new(sys, km, 0);
    if (!res) {
        free(ord);
        goto nomem;
    }
    res->damped = any_d || opt->kind == GD_MODAL_DAMPED || !conservative;
    res->sparse = 1;
    res->speed = opt->speed;
    gd_rigid_modes_fill(sys, opt->speed, res, prev->shape_re, kr);
    for (int j = kr; j < km; j++) {
        gd_mode *md = &res->modes[j];
        const found *f = &fd[ord[j - kr].idx];
        md->rigid_body = 0;
        gd_mode_set_lambda(md, creal(f->lam), cimag(f->lam));
        double *re = res->shape_re + (size_t)j * n, *im = res->shape_im + (size_t)j * n;
        for (int i = 0; i < n; i++) {
            re[i] = creal(f->x[i]);
            im[i] = cimag(f->x[i]);
        }
        gd_normalise_max(re, im, n);
        gd_mode_finish(sys, opt->speed, md, re, im,
                       res->energy_by_component + (size_t)j * sys->ncomponents);
    }
    free(ord);
    ok = 1;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the mode continuation");
done:
    if (ok) {
        *out = res;
        res = NULL;
        *hard = wp->passes > GD_TRACK_MAXIT - 1;
    }
    gd_modal_free(res);
    return st;
}

gd_status gd_sparse_track(const gd_dynmat *a, const gd_splu_symbolic *sym,
                          const gd_modal_options *opt, const gd_modal_result *prev,
                          const gd_modal_result *prev2, gd_sparse_ws *ws, gd_modal_result **out,
                          int *hard, gd_error *err)
{
    return track(a, sym, opt, prev, prev2, ws, out, hard, err, 0);
}

gd_status gd_sparse_refine(const gd_dynmat *a, const gd_splu_symbolic *sym,
                           const gd_modal_options *opt, const gd_modal_result *r, gd_sparse_ws *ws,
                           gd_modal_result **out, gd_error *err)
{
    int hard;
    return track(a, sym, opt, r, NULL, ws, out, &hard, err, 1);
}
