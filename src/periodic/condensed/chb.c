/* Condensed harmonic balance: the equations on the laws' coordinates (chb.h). */
#include "periodic/condensed/chb.h"

#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#ifndef TWO_PI
#define TWO_PI 6.28318530717958647692
#endif

/* GMRES: Krylov dimension, restarts, and the linear solve's tolerance relative to the
 * Newton right-hand side (a tight inexact Newton: two or three steps from a warm start). */
#define CHB_KRYLOV 40
#define CHB_RESTARTS 4
#define CHB_ETA 1e-9

struct gd_chb {
    int nf, H, N, nh, nc, n;
    /* the coordinates: sparse columns, entries sorted by DOF */
    int *cstart, *cidx, ccap;
    double *cval;
    double *gram; /* nc x nc: (C^T C)^-1, full */
    int nterm;
    int *tu, *tw;      /* per term: its u's and w's coordinate (-1: the term is empty) */
    double *tsu, *tsw; /* and their scales: u_t = tsu c_tu */
    int built;         /* coordinates made (for nterm terms) */
    int na;            /* they cannot serve (none, dependent): GD_CHB_NA */
    int pays;          /* few enough to pay (4 nc <= nf, the recovery's memory within 2 GB) */
    /* receptances of one problem */
    long stage_id;
    double w;
    int have;
    double *Hk;  /* (H + 1) nc^2 complex: C^T Z_k^-1 C, column-major */
    double *Pk;  /* (H + 1) nf nc complex: Z_k^-1 C */
    double *x0k; /* (H + 1) nf complex: Z_k^-1 r_k */
    double *y0;  /* n: C^T x0 in the cos / sin layout */
    klu_symbolic *sym;
    long sym_pat;
    klu_common com;
    klu_numeric **num; /* H + 1: each harmonic's LU, refactored at the next problem */
    double *rcond0;    /* H + 1: its reciprocal pivot ratio at the last pivoting factor */
    int *rrow, nr;     /* the DOFs where r is not zero at some sample */
    /* samples */
    double *ys, *vs;   /* nc x N: coordinate samples (row-major per coordinate) */
    double *gs;        /* nc x N: coordinate forces */
    double *rs;        /* nr x N: the forces outside span C on the rows rrow (setup only) */
    size_t rs_cap;     /* rows rs holds room for */
    int *rrow_of;      /* nf: the row of a DOF in rs, -1 none */
    double *fmag;      /* nf: |f| + |C g| on the coordinates' DOFs (setup only) */
    int primed;        /* gs, jq, jv hold the forces at the start (the setup's samples) */
    double *jq, *jv;   /* N nc^2: the samples' local Jacobians dg/dy, dg/dy' */
    double *yfull, *f; /* 2 nf, nf */
    double *st;        /* 2 nterm */
    double *z, *cf;    /* nc each */
    double *buf;       /* 2 N */
    fftw_plan inv, fwd;
    /* Newton and GMRES */
    double *R, *dY, *Gk; /* n each */
    double *pre;         /* (H + 1) nc^2 complex: LU of I - H_k T_k */
    lapack_int *piv;     /* (H + 1) nc */
    SUNContext sctx;
    N_Vector vb, vx;
    SUNLinearSolver ls;
    long solves, gmres_iters;
    /* the pattern of the last receptances (a lender's is compared with the borrower's) */
    int *lp, *li, lnz;
    gd_chb *lender; /* gd_chb_lend: borrowed, NULL none */
    long lent;      /* harmonics taken from a lender (diagnostics) */
};

static void free_numerics(gd_chb *c)
{
    if (c->num)
        for (int k = 0; k <= c->H; k++)
            if (c->num[k]) klu_z_free_numeric(&c->num[k], &c->com);
    free(c->num);
    c->num = NULL;
}

void gd_chb_free(gd_chb *c)
{
    if (!c) return;
    free_numerics(c);
    free(c->rcond0);
    free(c->lp);
    free(c->li);
    free(c->rrow);
    free(c->rrow_of);
    free(c->fmag);
    if (c->sym) klu_free_symbolic(&c->sym, &c->com);
    free(c->cstart);
    free(c->cidx);
    free(c->cval);
    free(c->gram);
    free(c->tu);
    free(c->tw);
    free(c->tsu);
    free(c->tsw);
    free(c->Hk);
    free(c->Pk);
    free(c->x0k);
    free(c->y0);
    free(c->ys);
    free(c->vs);
    free(c->gs);
    free(c->rs);
    free(c->jq);
    free(c->jv);
    free(c->yfull);
    free(c->f);
    free(c->st);
    free(c->z);
    free(c->cf);
    if (c->buf) fftw_free(c->buf);
    if (c->inv) fftw_destroy_plan(c->inv);
    if (c->fwd) fftw_destroy_plan(c->fwd);
    free(c->R);
    free(c->dY);
    free(c->Gk);
    free(c->pre);
    free(c->piv);
    if (c->ls) SUNLinSolFree(c->ls);
    if (c->vb) N_VDestroy(c->vb);
    if (c->vx) N_VDestroy(c->vx);
    if (c->sctx) SUNContext_Free(&c->sctx);
    free(c);
}

gd_chb *gd_chb_new(int nf, int H, int N)
{
    gd_chb *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->nf = nf;
    c->H = H;
    c->N = N;
    c->nh = 2 * H + 1;
    c->stage_id = -1;
    c->sym_pat = -1;
    klu_defaults(&c->com);
    /* no row scaling: KLU recomputes it at every refactorization (23 % of one on seed 002,
     * 0.13 M of 0.54 M instructions); the pivots are still guarded by the reciprocal
     * pivot ratio (receptances), and the receptances agree with the full solve as well
     * (tests/periodic/test_condensed_hb.c: 2.5e-14 against 3.2e-14 with scaling) */
    c->com.scale = -1;
    c->buf = fftw_malloc(2 * (size_t)c->N * sizeof *c->buf);
    c->yfull = calloc(2 * (size_t)c->nf, sizeof *c->yfull);
    c->f = malloc((size_t)c->nf * sizeof *c->f);
    c->cstart = calloc(1, sizeof *c->cstart);
    if (!c->buf || !c->yfull || !c->f || !c->cstart) goto fail;
    c->inv = fftw_plan_r2r_1d(c->N, c->buf, c->buf + c->N, FFTW_HC2R, FFTW_ESTIMATE);
    c->fwd = fftw_plan_r2r_1d(c->N, c->buf, c->buf + c->N, FFTW_R2HC, FFTW_ESTIMATE);
    if (!c->inv || !c->fwd) goto fail;
    return c;
fail:
    gd_chb_free(c);
    return NULL;
}

int gd_chb_ncoords(const gd_chb *c)
{
    return c ? c->nc : 0;
}

void gd_chb_counts(const gd_chb *c, long *solves, long *gmres_iters)
{
    if (solves) *solves = c ? c->solves : 0;
    if (gmres_iters) *gmres_iters = c ? c->gmres_iters : 0;
}

void gd_chb_lend(gd_chb *c, gd_chb *lender)
{
    if (c && lender != c) c->lender = lender;
}

long gd_chb_lent(const gd_chb *c)
{
    return c ? c->lent : 0;
}

/* ---------------------------------------------------------------- coordinates */

/* The coordinate equal to the sparse vector (idx, val) up to a scale (*s: vec = s c_j),
 * appended when new. Returns its index, -1 out of memory. */
static int coord_of(gd_chb *c, int n, const int *idx0, const double *val0, double *s)
{
    int idx[12];
    double val[12], vmax = 0.0;
    for (int e = 0; e < n; e++) { /* sorted by DOF (insertion: at most 12 entries) */
        int at = e;
        while (at > 0 && idx[at - 1] > idx0[e]) {
            idx[at] = idx[at - 1];
            val[at] = val[at - 1];
            at--;
        }
        idx[at] = idx0[e];
        val[at] = val0[e];
        vmax = fmax(vmax, fabs(val0[e]));
    }
    for (int j = 0; j < c->nc; j++) {
        const int p = c->cstart[j];
        if (c->cstart[j + 1] - p != n) continue;
        int same = 1;
        for (int e = 0; e < n && same; e++)
            same = c->cidx[p + e] == idx[e];
        if (!same) continue;
        const double r = val[0] / c->cval[p];
        for (int e = 0; e < n && same; e++)
            same = fabs(val[e] - r * c->cval[p + e]) <= 1e-13 * vmax;
        if (same) {
            *s = r;
            return j;
        }
    }
    const int p = c->cstart[c->nc];
    if (p + n > c->ccap) {
        int cap = 2 * (p + n) + 16;
        int *ci = realloc(c->cidx, (size_t)cap * sizeof *ci);
        if (!ci) return -1;
        c->cidx = ci;
        double *cv = realloc(c->cval, (size_t)cap * sizeof *cv);
        if (!cv) return -1;
        c->cval = cv;
        c->ccap = cap;
    }
    int *cs = realloc(c->cstart, (size_t)(c->nc + 2) * sizeof *cs);
    if (!cs) return -1;
    c->cstart = cs;
    memcpy(c->cidx + p, idx, (size_t)n * sizeof *idx);
    memcpy(c->cval + p, val, (size_t)n * sizeof *val);
    c->cstart[c->nc + 1] = p + n;
    *s = 1.0;
    return c->nc++;
}

/* The coordinates from the terms of tr and the factor of their Gram matrix. 0 ok (c->na
 * set when they cannot serve), 1 out of memory. */
static int build_coords(gd_chb *c, gd_transient *tr)
{
    const gd_tr_term *term;
    const int nt = gd_transient_terms(tr, &term);
    if (c->built && nt == c->nterm) return 0;
    c->built = 1;
    c->na = 0;
    c->nc = 0;
    c->cstart[0] = 0;
    c->nterm = nt;
    if (nt <= 0) {
        c->na = 1;
        return 0;
    }
    free(c->tu);
    free(c->tw);
    free(c->tsu);
    free(c->tsw);
    c->tu = malloc((size_t)nt * sizeof *c->tu);
    c->tw = malloc((size_t)nt * sizeof *c->tw);
    c->tsu = malloc((size_t)nt * sizeof *c->tsu);
    c->tsw = malloc((size_t)nt * sizeof *c->tsw);
    if (!c->tu || !c->tw || !c->tsu || !c->tsw) return 1;
    /* the force directions first: every force must lie in their span */
    for (int t = 0; t < nt; t++) {
        c->tu[t] = c->tw[t] = -1;
        if (!term[t].nu || !term[t].nw) continue;
        c->tu[t] = coord_of(c, term[t].nu, term[t].u_idx, term[t].u, &c->tsu[t]);
        if (c->tu[t] < 0) return 1;
    }
    for (int t = 0; t < nt; t++) {
        if (c->tu[t] < 0) continue;
        c->tw[t] = coord_of(c, term[t].nw, term[t].w_idx, term[t].w, &c->tsw[t]);
        if (c->tw[t] < 0) return 1;
    }
    const int nc = c->nc;
    /* it pays with few coordinates; Z_k^-1 C and Z_k^-1 r_k are kept for the recovery */
    const double bytes = 16.0 * (c->H + 1) * c->nf * (nc + 1);
    c->pays = 4 * nc <= c->nf && bytes <= 2e9;
    if (nc == 0) {
        c->na = 1;
        return 0;
    }
    free(c->gram);
    c->gram = calloc((size_t)nc * nc, sizeof *c->gram);
    double *dense = calloc((size_t)c->nf, sizeof *dense);
    if (!c->gram || !dense) {
        free(dense);
        return 1;
    }
    for (int i = 0; i < nc; i++) {
        for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
            dense[c->cidx[p]] = c->cval[p];
        for (int j = 0; j < nc; j++) {
            double s = 0.0;
            for (int p = c->cstart[j]; p < c->cstart[j + 1]; p++)
                s += dense[c->cidx[p]] * c->cval[p];
            c->gram[i + (size_t)nc * j] = s;
        }
        for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
            dense[c->cidx[p]] = 0.0;
    }
    free(dense);
    double dmax = 0.0;
    for (int i = 0; i < nc; i++)
        dmax = fmax(dmax, c->gram[i + (size_t)nc * i]);
    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', nc, c->gram, nc)) {
        c->na = 1; /* dependent coordinates */
        return 0;
    }
    for (int i = 0; i < nc; i++)
        if (c->gram[i + (size_t)nc * i] * c->gram[i + (size_t)nc * i] < 1e-12 * dmax) {
            c->na = 1;
            return 0;
        }
    if (LAPACKE_dpotri(LAPACK_COL_MAJOR, 'L', nc, c->gram, nc)) {
        c->na = 1;
        return 0;
    }
    for (int j = 0; j < nc; j++) /* the upper triangle from the lower */
        for (int i = 0; i < j; i++)
            c->gram[i + (size_t)nc * j] = c->gram[j + (size_t)nc * i];
    return 0;
}

int gd_chb_applies(gd_chb *c, gd_transient *tr)
{
    if (!c) return -1;
    if (build_coords(c, tr)) return -1;
    if (c->nterm <= 0 || c->nc == 0) return -1;
    return c->na || !c->pays ? 0 : 1;
}

/* z := (C^T C)^-1 z */
static void gram_solve(const gd_chb *c, double *z)
{
    const int nc = c->nc;
    double t[64], *x = nc <= 64 ? t : c->cf;
    memcpy(x, z, (size_t)nc * sizeof *z);
    for (int i = 0; i < nc; i++) {
        double s = 0.0;
        for (int j = 0; j < nc; j++)
            s += c->gram[i + (size_t)nc * j] * x[j];
        z[i] = s;
    }
}

/* ---------------------------------------------------------------- workspace */

static int alloc_work(gd_chb *c)
{
    const int nc = c->nc, N = c->N, H = c->H, nf = c->nf;
    c->n = nc * c->nh;
    const size_t n = (size_t)c->n;
#define ALLOC(p, cnt)                                                                              \
    do {                                                                                           \
        free(p);                                                                                   \
        (p) = malloc((size_t)(cnt) * sizeof *(p));                                                 \
        if (!(p)) return 1;                                                                        \
    } while (0)
    ALLOC(c->Hk, 2 * (size_t)(H + 1) * nc * nc);
    ALLOC(c->Pk, 2 * (size_t)(H + 1) * nf * nc);
    ALLOC(c->x0k, 2 * (size_t)(H + 1) * nf);
    ALLOC(c->y0, n);
    ALLOC(c->ys, (size_t)nc * N);
    ALLOC(c->vs, (size_t)nc * N);
    ALLOC(c->gs, (size_t)nc * N);
    ALLOC(c->jq, (size_t)N * nc * nc);
    ALLOC(c->jv, (size_t)N * nc * nc);
    ALLOC(c->st, 2 * (size_t)(c->nterm > 0 ? c->nterm : 1));
    ALLOC(c->z, nc);
    ALLOC(c->cf, nc);
    ALLOC(c->R, n);
    ALLOC(c->dY, n);
    ALLOC(c->Gk, n);
    ALLOC(c->pre, 2 * (size_t)(H + 1) * nc * nc);
    ALLOC(c->piv, (size_t)(H + 1) * nc);
#undef ALLOC
    if (c->ls) SUNLinSolFree(c->ls);
    if (c->vb) N_VDestroy(c->vb);
    if (c->vx) N_VDestroy(c->vx);
    c->ls = NULL;
    c->vb = c->vx = NULL;
    if (!c->sctx && SUNContext_Create(NULL, &c->sctx)) return 1;
    c->vb = N_VNew_Serial((sunindextype)n, c->sctx);
    c->vx = N_VNew_Serial((sunindextype)n, c->sctx);
    if (!c->vb || !c->vx) return 1;
    c->ls = SUNLinSol_SPGMR(c->vx, SUN_PREC_RIGHT, CHB_KRYLOV, c->sctx);
    if (!c->ls) return 1;
    SUNLinSol_SPGMRSetMaxRestarts(c->ls, CHB_RESTARTS);
    return 0;
}

/* ---------------------------------------------------------------- samples */

/* Samples (row-major per coordinate: out[i * N + j]) of the coordinates Y (cos / sin
 * layout, nc per harmonic), or of their phase derivative (deriv). */
static void synth(gd_chb *c, const double *Y, int deriv, double *out)
{
    const int nc = c->nc, N = c->N, H = c->H;
    double *b = c->buf;
    for (int i = 0; i < nc; i++) {
        memset(b, 0, (size_t)N * sizeof *b);
        if (!deriv) b[0] = Y[i];
        for (int k = 1; k <= H; k++) { /* as hb.c's fill_row */
            double cc = Y[(size_t)(2 * k - 1) * nc + i], sn = Y[(size_t)2 * k * nc + i];
            b[k] = 0.5 * (deriv ? k * sn : cc);
            b[N - k] = -0.5 * (deriv ? -k * cc : sn);
        }
        fftw_execute(c->inv);
        memcpy(out + (size_t)i * N, b + N, (size_t)N * sizeof *out);
    }
}

/* Harmonics 0..H of the rows of s (nrow x N, row-major) into G (cos / sin layout with
 * stride nrow), as hb.c's residual does. */
static void analyse(gd_chb *c, const double *s, int nrow, double *G)
{
    const int N = c->N, H = c->H;
    double *b = c->buf, *o = c->buf + c->N;
    for (int i = 0; i < nrow; i++) {
        memcpy(b, s + (size_t)i * N, (size_t)N * sizeof *b);
        fftw_execute(c->fwd);
        G[i] = o[0] / N;
        for (int k = 1; k <= H; k++) {
            G[(size_t)(2 * k - 1) * nrow + i] = 2.0 * o[k] / N;
            G[(size_t)2 * k * nrow + i] = -2.0 * o[N - k] / N;
        }
    }
}

/* The forces at every sample of the coordinates Y: g into gs; with jac the local
 * Jacobians into jq, jv; with rsave the part of f outside span C into rs, on the rows
 * where it is not zero (rrow, nr: set empty by the caller). 0 ok, 1 a force not finite,
 * 2 out of memory. */
static int forces(gd_chb *c, gd_transient *tr, double w, const double *Y, int jac, int rsave)
{
    const int nc = c->nc, N = c->N, nf = c->nf, nt = c->nterm;
    synth(c, Y, 0, c->ys);
    synth(c, Y, 1, c->vs);
    double *q = c->yfull, *v = c->yfull + nf;
    int bad = 0;
    for (int j = 0; j < N; j++) {
        /* q = C (C^T C)^-1 y: the laws read it only through the coordinates */
        for (int i = 0; i < nc; i++)
            for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                q[c->cidx[p]] = v[c->cidx[p]] = 0.0;
        for (int deriv = 0; deriv < 2; deriv++) {
            const double *src = deriv ? c->vs : c->ys;
            double *dst = deriv ? v : q;
            for (int i = 0; i < nc; i++)
                c->z[i] = src[(size_t)i * N + j] * (deriv ? w : 1.0);
            gram_solve(c, c->z);
            for (int i = 0; i < nc; i++)
                for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                    dst[c->cidx[p]] += c->cval[p] * c->z[i];
        }
        const double t = TWO_PI * j / N / w;
        gd_transient_local(tr, t, c->yfull, c->f, jac ? c->st : NULL, jac ? c->st + nt : NULL);
        for (int i = 0; i < nc; i++) {
            double s = 0.0;
            for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                s += c->cval[p] * c->f[c->cidx[p]];
            c->z[i] = s;
        }
        gram_solve(c, c->z);
        for (int i = 0; i < nc; i++) {
            if (!isfinite(c->z[i])) bad = 1;
            c->gs[(size_t)i * N + j] = c->z[i];
        }
        if (rsave) {
            /* r = f - C g: on the coordinates' DOFs a remainder at rounding level
             * (|r| <= 1e-13 (|f| + |C g|): a law force lies in span C by its contract) is
             * zero, not a load: otherwise it would put an r_k at every harmonic and an
             * extra right-hand side into every receptance solve (seed 002: 24 rows of
             * 6e-15 N against forces of 1e2 N) */
            for (int i = 0; i < nc; i++)
                for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                    c->fmag[c->cidx[p]] = fabs(c->f[c->cidx[p]]);
            for (int i = 0; i < nc; i++)
                for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++) {
                    const double cg = c->cval[p] * c->z[i];
                    c->f[c->cidx[p]] -= cg;
                    c->fmag[c->cidx[p]] += fabs(cg);
                }
            for (int i = 0; i < nc; i++)
                for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                    if (fabs(c->f[c->cidx[p]]) <= 1e-13 * c->fmag[c->cidx[p]])
                        c->f[c->cidx[p]] = 0.0;
            for (int i = 0; i < nf; i++) {
                if (c->f[i] == 0.0) continue;
                int row = c->rrow_of[i];
                if (row < 0) { /* a new row: zero at the samples before */
                    if ((size_t)c->nr == c->rs_cap) {
                        size_t cap = 2 * c->rs_cap + 4;
                        double *r = realloc(c->rs, cap * N * sizeof *r);
                        if (!r) return 2;
                        c->rs = r;
                        c->rs_cap = cap;
                    }
                    row = c->rrow_of[i] = c->nr;
                    c->rrow[c->nr++] = i;
                    memset(c->rs + (size_t)row * N, 0, (size_t)N * sizeof *c->rs);
                }
                c->rs[(size_t)row * N + j] = c->f[i];
            }
        }
        if (jac) { /* dg/dy = sum_t sq_t su_t sw_t e_u e_w^T (chb.h) */
            double *Jq = c->jq + (size_t)j * nc * nc, *Jv = c->jv + (size_t)j * nc * nc;
            memset(Jq, 0, (size_t)nc * nc * sizeof *Jq);
            memset(Jv, 0, (size_t)nc * nc * sizeof *Jv);
            for (int k = 0; k < nt; k++) {
                if (c->tu[k] < 0) continue;
                const double s = c->tsu[k] * c->tsw[k];
                const size_t at = (size_t)c->tu[k] + (size_t)nc * c->tw[k];
                Jq[at] += c->st[k] * s;
                Jv[at] += c->st[nt + k] * s;
            }
        }
    }
    return bad;
}

/* ---------------------------------------------------------------- receptances */

/* Z_k per harmonic from the union pattern of K, M, D (hb_blocks.c): its complex sparse LU
 * (refactored with the last problem's pivot order while its pivots hold, as lowrank.c),
 * Z_k^-1 [C, r_k], H_k and y0. r (the samples c->rs) enters only on the DOFs where it is
 * not zero, and only at the harmonics where it is. 0 ok, GD_CHB_NA singular,
 * GD_CHB_NOMEM. */
/* y0's harmonic k: C^T x0 (x0 = Z_k^-1 r_k, nf complex) in the cos / sin layout. */
static void project_r(gd_chb *c, int k, const double *x0)
{
    const int nc = c->nc;
    for (int i = 0; i < nc; i++) {
        double re = 0.0, im = 0.0;
        for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++) {
            re += c->cval[p] * x0[2 * c->cidx[p]];
            im += c->cval[p] * x0[2 * c->cidx[p] + 1];
        }
        if (k == 0) {
            c->y0[i] = re;
        } else {
            c->y0[(size_t)(2 * k - 1) * nc + i] = re;
            c->y0[(size_t)2 * k * nc + i] = -im;
        }
    }
}

/* The harmonics 0 .. the returned count - 1 whose receptances the lender (gd_chb_lend)
 * holds for this problem: the same stage and frequency, coordinates and pattern of
 * K, M, D (the same Z_k). 0: none. */
static int lender_harmonics(const gd_chb *c, const gd_chb_linear *h, long stage_id, double w)
{
    const gd_chb *d = c->lender;
    const int nf = c->nf, nc = c->nc;
    if (!d || !d->have || d->stage_id != stage_id || d->w != w || d->nf != nf || d->nc != nc ||
        !d->num || !d->lp || d->lnz != h->Up[nf])
        return 0;
    if (memcmp(d->lp, h->Up, (size_t)(nf + 1) * sizeof *h->Up) ||
        memcmp(d->li, h->Ui, (size_t)d->lnz * sizeof *h->Ui))
        return 0;
    const int ne = c->cstart[nc];
    if (memcmp(d->cstart, c->cstart, (size_t)(nc + 1) * sizeof *c->cstart) ||
        memcmp(d->cidx, c->cidx, (size_t)ne * sizeof *c->cidx) ||
        memcmp(d->cval, c->cval, (size_t)ne * sizeof *c->cval))
        return 0;
    return (d->H < c->H ? d->H : c->H) + 1;
}

/* The pattern of these receptances kept (a borrower compares it). 0 ok, 1 no memory. */
static int keep_pattern(gd_chb *c, const gd_chb_linear *h)
{
    const int nf = c->nf, nz = h->Up[nf];
    if (c->lp && c->lnz == nz && !memcmp(c->lp, h->Up, (size_t)(nf + 1) * sizeof *h->Up) &&
        !memcmp(c->li, h->Ui, (size_t)nz * sizeof *h->Ui))
        return 0;
    free(c->lp);
    free(c->li);
    c->lp = malloc((size_t)(nf + 1) * sizeof *c->lp);
    c->li = malloc((size_t)(nz > 0 ? nz : 1) * sizeof *c->li);
    if (!c->lp || !c->li) {
        free(c->lp);
        free(c->li);
        c->lp = c->li = NULL;
        return 1;
    }
    memcpy(c->lp, h->Up, (size_t)(nf + 1) * sizeof *h->Up);
    memcpy(c->li, h->Ui, (size_t)nz * sizeof *h->Ui);
    c->lnz = nz;
    return 0;
}

static int receptances(gd_chb *c, const gd_chb_linear *h, long stage_id, double w)
{
    const int nf = c->nf, nc = c->nc, H = c->H;
    if (!c->sym || c->sym_pat != h->pat_id) {
        free_numerics(c);
        if (c->sym) klu_free_symbolic(&c->sym, &c->com);
        c->sym = klu_analyze(nf, (int *)h->Up, (int *)h->Ui, &c->com);
        if (!c->sym) return GD_CHB_NA;
        c->sym_pat = h->pat_id;
    }
    if (!c->num) {
        c->num = calloc((size_t)H + 1, sizeof *c->num);
        free(c->rcond0);
        c->rcond0 = calloc((size_t)H + 1, sizeof *c->rcond0);
        if (!c->num || !c->rcond0) return GD_CHB_NOMEM;
    }
    const int nr = c->nr;
    const int nz = h->Up[nf];
    double *Zx = malloc(2 * (size_t)(nz > 0 ? nz : 1) * sizeof *Zx);
    double *B = malloc(2 * (size_t)nf * (nc + 1) * sizeof *B);
    double *rk = malloc((size_t)(nr > 0 ? nr : 1) * c->nh * sizeof *rk);
    int rc = GD_CHB_NOMEM;
    if (!Zx || !B || !rk) goto done;
    analyse(c, c->rs, nr, rk); /* r_k on those rows (cos / sin layout, stride nr) */
    if (keep_pattern(c, h)) goto done;
    rc = GD_CHB_NA;
    gd_chb *d = c->lender;
    const int nlent = lender_harmonics(c, h, stage_id, w);
    for (int k = 0; k <= H; k++) {
        const double kw = k * w, kw2 = kw * kw;
        /* the right-hand sides r_k where they are not zero */
        int with_r = 0;
        double *br = B + 2 * (size_t)nc * nf;
        for (int q = 0; q < nr; q++) {
            double re = k ? rk[(size_t)(2 * k - 1) * nr + q] : rk[q];
            double im = k ? -rk[(size_t)2 * k * nr + q] : 0.0; /* r_k = r_c - i r_s */
            with_r |= re != 0.0 || im != 0.0;
        }
        if (k < nlent && d->num[k]) {
            /* the lender's Z_k: its H_k and Z_k^-1 C as they are, Z_k^-1 r_k by its LU (this
             * LU, not refreshed, is dropped: a later problem factors anew) */
            if (c->num[k]) klu_z_free_numeric(&c->num[k], &c->com);
            memcpy(c->Pk + 2 * (size_t)k * nf * nc, d->Pk + 2 * (size_t)k * nf * nc,
                   2 * (size_t)nf * nc * sizeof *B);
            memcpy(c->Hk + 2 * (size_t)k * nc * nc, d->Hk + 2 * (size_t)k * nc * nc,
                   2 * (size_t)nc * nc * sizeof *B);
            double *x0 = c->x0k + 2 * (size_t)k * nf;
            memset(x0, 0, 2 * (size_t)nf * sizeof *x0);
            if (with_r) {
                for (int q = 0; q < nr; q++) {
                    x0[2 * c->rrow[q]] = k ? rk[(size_t)(2 * k - 1) * nr + q] : rk[q];
                    x0[2 * c->rrow[q] + 1] = k ? -rk[(size_t)2 * k * nr + q] : 0.0;
                }
                if (!klu_z_solve(d->sym, d->num[k], nf, 1, x0, &d->com)) goto done;
                for (int p = 0; p < 2 * nf; p++)
                    if (!isfinite(x0[p])) goto done;
            }
            project_r(c, k, x0);
            c->lent++;
            continue;
        }
        for (int p = 0; p < nz; p++) {
            Zx[2 * p] = h->UK[p] - kw2 * h->UM[p];
            Zx[2 * p + 1] = kw * h->UD[p];
        }
        int fresh = !c->num[k];
        if (!fresh) { /* the pivot order of the last problem, unless the pivots degraded */
            fresh = !klu_z_refactor((int *)h->Up, (int *)h->Ui, Zx, c->sym, c->num[k], &c->com) ||
                    !klu_z_rcond(c->sym, c->num[k], &c->com) ||
                    !(c->com.rcond >= 1e-3 * c->rcond0[k]);
            if (fresh) klu_z_free_numeric(&c->num[k], &c->com);
        }
        if (fresh) {
            c->num[k] = klu_z_factor((int *)h->Up, (int *)h->Ui, Zx, c->sym, &c->com);
            if (!c->num[k] || !klu_z_rcond(c->sym, c->num[k], &c->com)) goto done;
            c->rcond0[k] = c->com.rcond;
        }
        /* the right-hand sides: C, and r_k where it is not zero */
        memset(B, 0, 2 * (size_t)nf * (nc + with_r) * sizeof *B);
        for (int i = 0; i < nc; i++)
            for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                B[2 * ((size_t)i * nf + c->cidx[p])] = c->cval[p];
        if (with_r)
            for (int q = 0; q < nr; q++) {
                br[2 * c->rrow[q]] = k ? rk[(size_t)(2 * k - 1) * nr + q] : rk[q];
                br[2 * c->rrow[q] + 1] = k ? -rk[(size_t)2 * k * nr + q] : 0.0;
            }
        if (!klu_z_solve(c->sym, c->num[k], nf, nc + with_r, B, &c->com)) goto done;
        for (int p = 0; p < 2 * nf * (nc + with_r); p++)
            if (!isfinite(B[p])) goto done;
        memcpy(c->Pk + 2 * (size_t)k * nf * nc, B, 2 * (size_t)nf * nc * sizeof *B);
        if (with_r)
            memcpy(c->x0k + 2 * (size_t)k * nf, br, 2 * (size_t)nf * sizeof *B);
        else
            memset(c->x0k + 2 * (size_t)k * nf, 0, 2 * (size_t)nf * sizeof *B);
        /* H_k = C^T Z_k^-1 C, y0_k = C^T Z_k^-1 r_k */
        double *Hk = c->Hk + 2 * (size_t)k * nc * nc;
        for (int j = 0; j < nc; j++)
            for (int i = 0; i < nc; i++) {
                const double *col = B + 2 * (size_t)j * nf;
                double re = 0.0, im = 0.0;
                for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++) {
                    re += c->cval[p] * col[2 * c->cidx[p]];
                    im += c->cval[p] * col[2 * c->cidx[p] + 1];
                }
                Hk[2 * (i + (size_t)nc * j)] = re;
                Hk[2 * (i + (size_t)nc * j) + 1] = im;
            }
        project_r(c, k, c->x0k + 2 * (size_t)k * nf);
    }
    rc = GD_CHB_OK;
done:
    free(Zx);
    free(B);
    free(rk);
    return rc;
}

/* out = H_k G_k per harmonic (cos / sin layout, stride nc), complex X = c - i s. */
static void apply_H(const gd_chb *c, const double *G, double *out)
{
    const int nc = c->nc, H = c->H;
    for (int k = 0; k <= H; k++) {
        const double *Hk = c->Hk + 2 * (size_t)k * nc * nc;
        for (int i = 0; i < nc; i++) {
            double re = 0.0, im = 0.0;
            for (int j = 0; j < nc; j++) {
                double gr = k ? G[(size_t)(2 * k - 1) * nc + j] : G[j];
                double gi = k ? -G[(size_t)2 * k * nc + j] : 0.0;
                double hr = Hk[2 * (i + (size_t)nc * j)], hi = Hk[2 * (i + (size_t)nc * j) + 1];
                re += hr * gr - hi * gi;
                im += hr * gi + hi * gr;
            }
            if (k == 0) {
                out[i] = re;
            } else {
                out[(size_t)(2 * k - 1) * nc + i] = re;
                out[(size_t)2 * k * nc + i] = -im;
            }
        }
    }
}

/* ---------------------------------------------------------------- Newton's linear solve */

typedef struct op {
    gd_chb *c;
    double w;
} op;

/* z = J v = v - H (dG/dY) v: the samples' local Jacobians applied to v's samples, AFT. */
static int atimes(void *data, N_Vector vv, N_Vector zz)
{
    op *o = data;
    gd_chb *c = o->c;
    const int nc = c->nc, N = c->N;
    const double *v = N_VGetArrayPointer(vv);
    double *z = N_VGetArrayPointer(zz);
    double *dy = c->ys, *dv = c->vs; /* the samples of Y are not needed during the solve */
    synth(c, v, 0, dy);
    synth(c, v, 1, dv);
    for (int j = 0; j < N; j++) {
        const double *Jq = c->jq + (size_t)j * nc * nc, *Jv = c->jv + (size_t)j * nc * nc;
        for (int i = 0; i < nc; i++) {
            double s = 0.0;
            for (int l = 0; l < nc; l++)
                s += Jq[i + (size_t)nc * l] * dy[(size_t)l * N + j] +
                     Jv[i + (size_t)nc * l] * o->w * dv[(size_t)l * N + j];
            c->gs[(size_t)i * N + j] = s;
        }
    }
    analyse(c, c->gs, nc, c->Gk);
    apply_H(c, c->Gk, z);
    for (int i = 0; i < c->n; i++)
        z[i] = v[i] - z[i];
    return 0;
}

/* The preconditioner: I - H_k (Tq + i k w Tv) per harmonic with T the samples' mean
 * local Jacobians, LU-factored. 0 ok, 1 singular. */
static int precond_setup(gd_chb *c, double w)
{
    const int nc = c->nc, N = c->N, H = c->H;
    double *Tq = calloc(2 * (size_t)nc * nc, sizeof *Tq), *Tv = Tq + nc * nc;
    if (!Tq) return 1;
    for (int j = 0; j < N; j++)
        for (int e = 0; e < nc * nc; e++) {
            Tq[e] += c->jq[(size_t)j * nc * nc + e] / N;
            Tv[e] += c->jv[(size_t)j * nc * nc + e] / N;
        }
    int rc = 0;
    for (int k = 0; k <= H && !rc; k++) {
        const double *Hk = c->Hk + 2 * (size_t)k * nc * nc;
        lapack_complex_double *A = (lapack_complex_double *)(c->pre + 2 * (size_t)k * nc * nc);
        for (int i = 0; i < nc; i++)
            for (int j = 0; j < nc; j++) {
                double re = i == j, im = 0.0;
                for (int l = 0; l < nc; l++) {
                    double hr = Hk[2 * (i + (size_t)nc * l)], hi = Hk[2 * (i + (size_t)nc * l) + 1];
                    double tr = Tq[l + (size_t)nc * j], ti = k * w * Tv[l + (size_t)nc * j];
                    re -= hr * tr - hi * ti;
                    im -= hr * ti + hi * tr;
                }
                double *a = (double *)&A[i + (size_t)nc * j];
                a[0] = re;
                a[1] = im;
            }
        rc = LAPACKE_zgetrf(LAPACK_COL_MAJOR, nc, nc, A, nc, c->piv + (size_t)k * nc) != 0;
    }
    free(Tq);
    return rc;
}

static int psolve(void *data, N_Vector rr, N_Vector zz, sunrealtype tol, int lr)
{
    (void)tol;
    (void)lr;
    op *o = data;
    gd_chb *c = o->c;
    const int nc = c->nc, H = c->H;
    const double *r = N_VGetArrayPointer(rr);
    double *z = N_VGetArrayPointer(zz);
    double b[2 * 64];
    double *bb = nc <= 64 ? b : malloc(2 * (size_t)nc * sizeof *bb);
    if (!bb) return -1;
    for (int k = 0; k <= H; k++) {
        for (int i = 0; i < nc; i++) {
            bb[2 * i] = k ? r[(size_t)(2 * k - 1) * nc + i] : r[i];
            bb[2 * i + 1] = k ? -r[(size_t)2 * k * nc + i] : 0.0;
        }
        LAPACKE_zgetrs(LAPACK_COL_MAJOR, 'N', nc, 1,
                       (const lapack_complex_double *)(c->pre + 2 * (size_t)k * nc * nc), nc,
                       c->piv + (size_t)k * nc, (lapack_complex_double *)bb, nc);
        for (int i = 0; i < nc; i++) {
            if (k == 0) {
                z[i] = bb[0 + 2 * i];
            } else {
                z[(size_t)(2 * k - 1) * nc + i] = bb[2 * i];
                z[(size_t)2 * k * nc + i] = -bb[2 * i + 1];
            }
        }
    }
    if (bb != b) free(bb);
    return 0;
}

/* ---------------------------------------------------------------- the solve */

/* R = Y - y0 - H G(Y) (with the local Jacobians when jac); *rel its norm over the scale
 * max(|Y|, |y0 + H G|). 0 ok, 1 a force not finite. */
static int residual(gd_chb *c, gd_transient *tr, double w, const double *Y, int jac, double *rel)
{
    /* the setup's samples are those of this Y (the start) with their Jacobians */
    if (!(c->primed && jac) && forces(c, tr, w, Y, jac, 0)) return 1;
    c->primed = 0;
    analyse(c, c->gs, c->nc, c->Gk);
    apply_H(c, c->Gk, c->R);
    double rn = 0.0, sy = 0.0, sf = 0.0;
    for (int i = 0; i < c->n; i++) {
        double lin = c->y0[i] + c->R[i];
        c->R[i] = Y[i] - lin;
        rn += c->R[i] * c->R[i];
        sy += Y[i] * Y[i];
        sf += lin * lin;
    }
    double sc = sqrt(fmax(sy, sf));
    *rel = sc > 0 ? sqrt(rn) / sc : sqrt(rn);
    return 0;
}

int gd_chb_solve(gd_chb *c, const gd_chb_linear *lin, gd_transient *tr, long stage_id, double w,
                 double *X, double tol, int *iters)
{
    const int nf = c->nf, H = c->H;
    *iters = 0;
    c->primed = 0;
    if (stage_id != c->stage_id) c->built = 0; /* a new problem: its terms' vectors anew */
    if (build_coords(c, tr)) return GD_CHB_NOMEM;
    if (c->na) return GD_CHB_NA;
    const int nc = c->nc;
    if (c->n != nc * c->nh || !c->R) {
        if (alloc_work(c)) return GD_CHB_NOMEM;
        c->have = 0;
    }
    double *Y = malloc((size_t)c->n * sizeof *Y);
    if (!Y) return GD_CHB_NOMEM;
    /* the start: the coordinates of X */
    for (int hh = 0; hh < c->nh; hh++)
        for (int i = 0; i < nc; i++) {
            double s = 0.0;
            for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                s += c->cval[p] * X[(size_t)hh * nf + c->cidx[p]];
            Y[(size_t)hh * nc + i] = s;
        }
    int rc = GD_CHB_OK;
    if (!c->have || c->stage_id != stage_id || c->w != w) {
        c->have = 0;
        if (!c->rrow_of) {
            c->rrow_of = malloc((size_t)nf * sizeof *c->rrow_of);
            c->rrow = malloc((size_t)nf * sizeof *c->rrow);
            c->fmag = malloc((size_t)nf * sizeof *c->fmag);
            if (!c->rrow_of || !c->rrow || !c->fmag) {
                rc = GD_CHB_NOMEM;
                goto done;
            }
            for (int i = 0; i < nf; i++)
                c->rrow_of[i] = -1;
            c->nr = 0;
        }
        for (int q = 0; q < c->nr; q++)
            c->rrow_of[c->rrow[q]] = -1;
        c->nr = 0;
        /* with the Jacobians: the first Newton residual is at this Y (primed) */
        int fr = forces(c, tr, w, Y, 1, 1);
        c->primed = !fr;
        if (fr) {
            rc = fr == 2 ? GD_CHB_NOMEM : GD_CHB_NOCONV;
            goto done;
        }
        rc = receptances(c, lin, stage_id, w);
        if (rc) goto done;
        c->have = 1;
        c->stage_id = stage_id;
        c->w = w;
    }
    op o = {c, w};
    SUNLinSolSetATimes(c->ls, &o, atimes);
    SUNLinSolSetPreconditioner(c->ls, &o, NULL, psolve);
    if (SUNLinSolInitialize(c->ls) || SUNLinSolSetup(c->ls, NULL)) {
        rc = GD_CHB_NOMEM;
        goto done;
    }
    rc = GD_CHB_NOCONV;
    double rel = INFINITY, prev = INFINITY;
    for (int it = 0; it <= 30; it++) {
        *iters = it;
        if (residual(c, tr, w, Y, 1, &rel)) break;
        if (rel <= tol) {
            rc = GD_CHB_OK;
            break;
        }
        if (it == 30 || (it >= 3 && rel > 0.5 * prev)) break; /* not converging: the full solve */
        prev = rel;
        if (precond_setup(c, w)) break;
        double *b = N_VGetArrayPointer(c->vb), *x = N_VGetArrayPointer(c->vx);
        double bn = 0.0;
        for (int i = 0; i < c->n; i++) {
            b[i] = -c->R[i];
            bn += b[i] * b[i];
            x[i] = 0.0;
        }
        SUNLinSolSetZeroGuess(c->ls, SUNTRUE);
        int ls = SUNLinSolSolve(c->ls, NULL, c->vx, c->vb, CHB_ETA * sqrt(bn));
        c->gmres_iters += SUNLinSolNumIters(c->ls);
        if (ls < 0) break;
        for (int i = 0; i < c->n; i++)
            Y[i] += x[i];
    }
    if (rc == GD_CHB_OK) {
        /* the full response: X_k = Z_k^-1 r_k + (Z_k^-1 C) G_k */
        for (int k = 0; k <= H; k++) {
            const double *P = c->Pk + 2 * (size_t)k * nf * nc, *x0 = c->x0k + 2 * (size_t)k * nf;
            for (int i = 0; i < nf; i++) {
                double re = x0[2 * i], im = x0[2 * i + 1];
                for (int j = 0; j < nc; j++) {
                    double gr = k ? c->Gk[(size_t)(2 * k - 1) * nc + j] : c->Gk[j];
                    double gi = k ? -c->Gk[(size_t)2 * k * nc + j] : 0.0;
                    double pr = P[2 * ((size_t)j * nf + i)], pi = P[2 * ((size_t)j * nf + i) + 1];
                    re += pr * gr - pi * gi;
                    im += pr * gi + pi * gr;
                }
                if (k == 0) {
                    X[i] = re;
                } else {
                    X[(size_t)(2 * k - 1) * nf + i] = re;
                    X[(size_t)2 * k * nf + i] = -im;
                }
            }
        }
        c->solves++;
    }
done:
    free(Y);
    return rc;
}

/* ---------------------------------------------------------------- the check */

/* sum_k |C G_k|^2 over the cos / sin layout of G (stride nc); v: nf scratch, zero on
 * entry and on return. */
static double coord_norm2(const gd_chb *c, const double *G, double *v)
{
    const int nc = c->nc;
    double s = 0.0;
    for (int hh = 0; hh < c->nh; hh++) {
        const double *g = G + (size_t)hh * nc;
        for (int i = 0; i < nc; i++)
            for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                v[c->cidx[p]] += c->cval[p] * g[i];
        for (int i = 0; i < nc; i++)
            for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++) {
                s += v[c->cidx[p]] * v[c->cidx[p]];
                v[c->cidx[p]] = 0.0;
            }
    }
    return s;
}

int gd_chb_check(gd_chb *c, gd_transient *tr, double w, const double *X, double *rel)
{
    if (!c || !c->have || c->nr > 0 || c->solves % 16 == 1) return 1;
    const int nc = c->nc, nf = c->nf, n = c->n;
    double *Ys = malloc(2 * (size_t)n * sizeof *Ys), *Gs = Ys + n;
    double *v = calloc((size_t)nf, sizeof *v);
    int rc = 1;
    if (!Ys || !v) goto done;
    for (int hh = 0; hh < c->nh; hh++) /* C^T X */
        for (int i = 0; i < nc; i++) {
            double s = 0.0;
            for (int p = c->cstart[i]; p < c->cstart[i + 1]; p++)
                s += c->cval[p] * X[(size_t)hh * nf + c->cidx[p]];
            Ys[(size_t)hh * nc + i] = s;
        }
    if (forces(c, tr, w, Ys, 0, 0)) goto done;
    analyse(c, c->gs, nc, Gs);
    /* |F| = |C G(C^T X)| (r = 0); |L X| = |C G(Y)| up to e_k */
    const double f2 = coord_norm2(c, Gs, v), l2 = coord_norm2(c, c->Gk, v);
    for (int i = 0; i < n; i++)
        Gs[i] = c->Gk[i] - Gs[i];
    const double r2 = coord_norm2(c, Gs, v), sc = sqrt(fmax(f2, l2));
    *rel = sc > 0 ? sqrt(r2) / sc : sqrt(r2);
    rc = !isfinite(*rel);
done:
    free(Ys);
    free(v);
    return rc;
}
