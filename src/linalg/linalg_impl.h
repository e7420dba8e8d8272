/* Sparse linear algebra shared by the analyses: triplet assembly and compression to
 * columns (CXSparse), a sparse pattern with the products the eigensolvers need, KLU
 * (symbolic analysis once per pattern, numeric factorisation per point), the
 * shift-invert operator of the quadratic eigenproblem and the Krylov-Schur
 * eigensolver. Nothing here knows about models or systems. Nothing is global; every
 * object is owned by its caller, and the read-only ones (pattern, symbolic analysis)
 * may be shared by threads. */
#ifndef GD_LINALG_IMPL_H
#define GD_LINALG_IMPL_H
#include <klu.h>

#include "geardyn/error.h"
#include "geardyn/sparse.h"

/* ---- sparse.c: triplets -> compressed columns ---- */
typedef struct gd_trip {
    int n, cap;
    int *i, *j;
    double *x;
} gd_trip;

int gd_trip_add(gd_trip *t, int i, int j, double x); /* 0 ok, 1 out of memory */
void gd_trip_free(gd_trip *t);
/* Compresses rows/cols mapped through map (raw -> active, -1 dropped) into an n x n
 * CSC matrix. 0 ok, 1 out of memory. */
int gd_trip_compress(const gd_trip *t, const int *map, int n, gd_csc *out);
/* A += scale * S (A dense column-major n x n). */
void gd_csc_add_dense(const gd_csc *s, double scale, double *A);
/* y = S x (real). */
void gd_csc_mul(const gd_csc *s, const double *x, double *y);

/* ---- sparse.c: one pattern for several value arrays ---- */
typedef struct gd_pattern {
    int n, nnz;
    int *colptr, *rowind; /* rows sorted within each column */
    int *diag;            /* position of (j, j), or -1 */
} gd_pattern;

/* Position of (row, col) in the pattern, or -1. */
int gd_pattern_find(const gd_pattern *p, int row, int col);
/* 1 when values k on the pattern are symmetric to 1e-12 of their largest magnitude (an
 * entry whose transpose is outside the pattern compares with 0). */
int gd_pattern_symmetric(const gd_pattern *p, const double *k);
/* y = S x + T z for values s, t on the pattern (real): one pass over the pattern. */
void gd_pattern_mul2(const gd_pattern *p, const double *s, const double *x, const double *t,
                     const double *z, double *y);

/* ---- ordering.c: each KLU block's fill-reducing ordering ---- */
typedef struct gd_order_choice {
    double flops;      /* predicted flops of the blocks ordered so far (as AMD's Info) */
    int nmd;           /* blocks given the minimum-degree order */
    int out_of_memory; /* AMD ran out of memory */
} gd_order_choice;
/* KLU's user_order (klu_common.user_data: a gd_order_choice): AMD's order of the n x n
 * block (cp, ci), or an exact minimum-degree one when it predicts fewer flops. Returns
 * the predicted entries of L (with the diagonal), 0 on failure. */
int gd_order_block(int n, int *cp, int *ci, int *perm, klu_common *common);

/* ---- sparse_lu.c: KLU, symbolic analysis once, numeric factorisation per point ---- */
typedef struct gd_splu_symbolic {
    klu_symbolic *sym; /* est_flops, lnz, unz: of the chosen orderings */
    klu_common common;
    int nmd; /* blocks ordered by minimum degree instead of AMD (ordering.c) */
} gd_splu_symbolic;

typedef struct gd_splu {
    klu_numeric *num;
    klu_common common;
    int is_complex;
    double rcond; /* min |diag U| / max |diag U| */
} gd_splu;

gd_status gd_splu_analyze(const gd_pattern *a, gd_splu_symbolic *s, gd_error *err);
void gd_splu_symbolic_free(gd_splu_symbolic *s);
/* Factors the matrix with values x (real nnz, or complex interleaved 2 nnz), with
 * KLU's row scaling or without it (for a matrix the caller has scaled). Returns 0, 1
 * when singular, -1 when out of memory. */
int gd_splu_factor(gd_splu *lu, const gd_pattern *a, const gd_splu_symbolic *s, const double *x,
                   int is_complex, int row_scaling);
/* Factors new values x on the same pattern with the pivot order of lu's last
 * factorisation (klu_refactor: no pivot search, no allocation), for a matrix near the
 * one lu was factored for. Same returns as gd_splu_factor; on 1 the factors are not
 * usable (factor afresh). */
int gd_splu_refactor(gd_splu *lu, const gd_pattern *a, const gd_splu_symbolic *s, const double *x);
/* Solves A x = b in place (complex: interleaved), nrhs columns of leading dimension n. */
void gd_splu_solve(gd_splu *lu, const gd_splu_symbolic *s, int n, int nrhs, double *b);
void gd_splu_free(gd_splu *lu);

/* ---- shift_invert.c: (A - sigma B)^-1 B of the first-order form ---- */
/* For lambda^2 M + lambda D + K with z = [u; lambda u / g], A = [0 gI; -K -gD],
 * B = [I 0; 0 gM] and a real shift sigma: y = (A - sigma B)^-1 B x needs only
 * P(sigma) = sigma^2 M + sigma D + K:  P y1 = -(M (g x2 + sigma x1) + D x1),
 * y2 = (x1 + sigma y1) / g. */
typedef struct gd_shift_invert {
    const gd_pattern *a;
    int n;
    double sigma, scale; /* sigma, g */
    const double *m, *d; /* values on the pattern */
    gd_splu lu;          /* of R P(sigma) R */
    double *r;           /* n: the symmetric diagonal scaling R = diag(|P_ii|^-1/2) */
    double *work;        /* 2 n */
} gd_shift_invert;

/* Factors P(sigma) for the values m, k, d on the pattern a, state scaling
 * g > 0. Returns 0, 1 when P(sigma) is singular, -1 when out of memory. */
int gd_shift_invert_setup(gd_shift_invert *op, const gd_pattern *a, const double *m,
                          const gd_splu_symbolic *s, double sigma, double scale, const double *k,
                          const double *d);
void gd_shift_invert_apply(gd_shift_invert *op, const gd_splu_symbolic *s, const double *x,
                           double *y);
void gd_shift_invert_free(gd_shift_invert *op);

/* ---- krylov_schur.c: largest-magnitude eigenpairs of a real operator ---- */
typedef void (*gd_op_fn)(void *ctx, const double *x, double *y);
typedef struct gd_ks_result {
    int nconv;
    double *mu_re, *mu_im;   /* nconv eigenvalues of the operator */
    double *vec_re, *vec_im; /* nout x nconv: leading rows of the eigenvectors */
    int iterations;          /* restarts */
} gd_ks_result;
/* Workspace for an n x n operator and basis size ncv; reusable across calls. */
typedef struct gd_ks_work {
    int n, ncv;
    /* Borrowed, n entries, or NULL: the first run's start vector (e.g. the sum of a
     * nearby problem's wanted eigenvectors, a warm start along a sweep) instead of the
     * fixed pseudo-random one; gd_ks_work_init sets NULL. */
    const double *v0;
    double *V, *H, *T, *Q, *X, *S, *work, *wr, *wr2, *wi, *h, *h2, *b, *res, *Z;
    int *sel, *grp, *ifail;
    struct mag_index *order;
} gd_ks_work;
int gd_ks_work_init(gd_ks_work *w, int n, int ncv); /* 0 ok, 1 out of memory */
void gd_ks_work_free(gd_ks_work *w);
/* nev wanted eigenvalues of largest magnitude of the n x n operator (both members of
 * a conjugate pair count), basis size at most ncv (> nev + 2), relative residual tol;
 * the eigenvectors' first nout rows (unit 2-norm over them). Repeated eigenvalues come
 * with every copy (deflated checks from further start vectors, krylov_schur.c).
 * Deterministic: fixed start vectors. iterations counts the first run's restarts.
 * Returns GD_OK, GD_ENUMERIC (no convergence within maxit restarts) or GD_ENOMEM. */
gd_status gd_krylov_schur(gd_op_fn op, void *ctx, int n, int nout, int nev, int ncv, double tol,
                          int maxit, gd_ks_work *ws, gd_ks_result *out); /* ws may be NULL */
void gd_ks_result_free(gd_ks_result *r);
/* The largest eigenvalue magnitude (*top) of the deflated operator (I - L L^T) Op on the
 * complement of the n x nl orthonormal basis L (an invariant subspace of Op: eigenvectors
 * already found), from a Krylov basis of at most 20 vectors converged to the relative
 * residual tol: an eigenvalue of Op that L misses and that is larger than the found ones
 * shows as *top above them (the completeness check of a solve that did not use Krylov).
 * ws: workspace for n (ncv >= 20). GD_OK, GD_ENUMERIC (no convergence) or GD_ENOMEM. */
gd_status gd_ks_deflated_top(gd_op_fn op, void *ctx, int n, const double *L, int nl, double tol,
                             gd_ks_work *ws, double *top);

/* ---- gmres.c: matrix-free Arnoldi and restarted GMRES ---- */
/* y = Op x; 0 ok, nonzero when the product failed (an integration, say): the caller's
 * reason stays in ctx. */
typedef int (*gd_op_try_fn)(void *ctx, const double *x, double *y);
/* Arnoldi on op (n x n) from v0 (normalised here) for at most m steps: V (n x (m + 1)),
 * H ((m + 1) x m, column-major, leading dimension m + 1), the steps taken in *steps. With
 * x (n: GMRES, A x = v0) it stops when the least-squares residual is below tol |v0| and
 * returns x. 0 ok, 1 a product failed, 2 out of memory. */
int gd_arnoldi(gd_op_try_fn op, void *ctx, int n, const double *v0, int m, double *V, double *H,
               int *steps, double tol, double *x);
/* GMRES(m) on op: A x = b (n), each cycle to tol |b - A x0| in its least-squares residual,
 * at most `cycles` cycles; between cycles the true residual b - A x is recomputed (one
 * product) and the restarts stop once its square is below stop2 |b|^2. 0 ok, 1 a product
 * failed, 2 out of memory. */
int gd_gmres(gd_op_try_fn op, void *ctx, int n, int m, const double *b, double *x, double tol,
             double stop2, int cycles);

/* ---- ritz.c: Ritz values of an Arnoldi factorisation and their residuals ---- */
/* The m Ritz values of gd_arnoldi's H (leading dimension ld, m steps: H's (m + 1) x m part
 * read) in (re, im) as LAPACK orders them, and each one's residual |h_{m+1,m}| |e_m^T s_j|
 * (s_j its unit eigenvector of H_m) in res. 0 ok, 1 the eigensolver failed, 2 out of memory. */
int gd_ritz(const double *H, int ld, int m, double *re, double *im, double *res);
/* A stability verdict only where converged Ritz values decide it: 0 (unstable) when one lies
 * outside the circle of radius bound by more than its residual, 1 (stable) when every one
 * lies inside it by more than its residual, -1 otherwise (a value within its residual of
 * the circle: not a verdict). */
int gd_ritz_verdict(const double *re, const double *im, const double *res, int n, double bound);

#endif
