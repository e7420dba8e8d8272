/* Internals shared by the sweeps (Campbell, FRF, unbalance): the dynamic stiffness on
 * one sparse pattern, the KLU factorisation, the shift-invert operator and the
 * Krylov-Schur eigensolver. Nothing here is global; every object is owned by its
 * caller, and the read-only ones (pattern, symbolic analysis) are shared by threads. */
#ifndef GD_SWEEP_INTERNAL_H
#define GD_SWEEP_INTERNAL_H
#include <klu.h>

#include "geardyn/modal.h"
#include "geardyn/system.h"

/* ---- sparse_dynamic.c: M, C, G, K and the speed-table bearings on one pattern ---- */
typedef struct gd_dyn_bearing {
    int bearing;
    int pos[144]; /* union position of local (i, j) of the 12 x 12 [A -A; -A A], or -1 */
} gd_dyn_bearing;

typedef struct gd_dynmat {
    int n, nnz;
    int *colptr, *rowind; /* union pattern, rows sorted within each column */
    double *m, *c, *g, *k;
    int ntab;
    gd_dyn_bearing *tab;
    int *diag; /* position of (j, j), or -1 */
    const gd_system *sys;
} gd_dynmat;

gd_status gd_dynmat_build(const gd_system *sys, gd_dynmat *out, gd_error *err);
void gd_dynmat_free(gd_dynmat *a);
/* k = K + K_b(W), d = C + C_b(W) + W G on the pattern (nnz each). */
void gd_dynmat_at(const gd_dynmat *a, double speed, double *k, double *d);
/* y = S x + T z for values s, t on the pattern (real): one pass over the pattern. */
void gd_dynmat_mul2(const gd_dynmat *a, const double *s, const double *x, const double *t,
                    const double *z, double *y);
/* Union position of (row, col), or -1. */
int gd_dynmat_find(const gd_dynmat *a, int row, int col);

/* ---- sparse_lu.c: KLU, symbolic analysis once, numeric factorisation per point ---- */
typedef struct gd_splu_symbolic {
    klu_symbolic *sym;
    klu_common common;
} gd_splu_symbolic;

typedef struct gd_splu {
    klu_numeric *num;
    klu_common common;
    int is_complex;
    double rcond; /* min |diag U| / max |diag U| */
} gd_splu;

gd_status gd_splu_analyze(const gd_dynmat *a, gd_splu_symbolic *s, gd_error *err);
void gd_splu_symbolic_free(gd_splu_symbolic *s);
/* Factors the matrix with values x (real nnz, or complex interleaved 2 nnz), with
 * KLU's row scaling or without it (for a matrix the caller has scaled). Returns 0, 1
 * when singular, -1 when out of memory. */
int gd_splu_factor(gd_splu *lu, const gd_dynmat *a, const gd_splu_symbolic *s, const double *x,
                   int is_complex, int row_scaling);
/* Solves A x = b in place (complex: interleaved), nrhs columns of leading dimension n. */
void gd_splu_solve(gd_splu *lu, const gd_splu_symbolic *s, int n, int nrhs, double *b);
void gd_splu_free(gd_splu *lu);

/* Factors the complex dynamic stiffness Z(w) = K - w^2 M + i w D (k, d from
 * gd_dynmat_at; z: 2 nnz scratch). Returns as gd_splu_factor. */
int gd_dynmat_factor_at(const gd_dynmat *a, const gd_splu_symbolic *s, const double *k,
                        const double *d, double w, double *z, gd_splu *lu);

/* ---- sparse_shift_invert.c: (A - sigma B)^-1 B of the first-order form ---- */
/* For lambda^2 M + lambda D + K with z = [u; lambda u / g], A = [0 gI; -K -gD],
 * B = [I 0; 0 gM] and a real shift sigma: y = (A - sigma B)^-1 B x needs only
 * P(sigma) = sigma^2 M + sigma D + K:  P y1 = -(M (g x2 + sigma x1) + D x1),
 * y2 = (x1 + sigma y1) / g. */
typedef struct gd_shift_invert {
    const gd_dynmat *a;
    int n;
    double sigma, scale; /* sigma, g */
    const double *m, *d; /* values on the pattern */
    gd_splu lu;          /* of R P(sigma) R */
    double *r;           /* n: the symmetric diagonal scaling R = diag(|P_ii|^-1/2) */
    double *work;        /* 2 n */
} gd_shift_invert;

/* Factors P(sigma) for the pattern values k, d (m from the pattern), state scaling
 * g > 0. Returns 0, 1 when P(sigma) is singular, -1 when out of memory. */
int gd_shift_invert_setup(gd_shift_invert *op, const gd_dynmat *a, const gd_splu_symbolic *s,
                          double sigma, double scale, const double *k, const double *d);
void gd_shift_invert_apply(gd_shift_invert *op, const gd_splu_symbolic *s, const double *x,
                           double *y);
void gd_shift_invert_free(gd_shift_invert *op);

/* ---- sparse_krylov_schur.c: largest-magnitude eigenpairs of a real operator ---- */
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
    double *V, *H, *T, *Q, *X, *S, *work, *wr, *wr2, *wi, *h, *h2, *b, *res, *Z;
    int *sel, *grp, *ifail;
    struct mag_index *order;
} gd_ks_work;
int gd_ks_work_init(gd_ks_work *w, int n, int ncv); /* 0 ok, 1 out of memory */
void gd_ks_work_free(gd_ks_work *w);
/* nev wanted eigenvalues of largest magnitude of the n x n operator (both members of
 * a conjugate pair count), basis size at most ncv (> nev + 2), relative residual tol;
 * the eigenvectors' first nout rows (unit 2-norm over them). Deterministic: a fixed
 * start vector. Returns GD_OK, GD_ENUMERIC (no convergence within maxit restarts) or
 * GD_ENOMEM. */
gd_status gd_krylov_schur(gd_op_fn op, void *ctx, int n, int nout, int nev, int ncv, double tol,
                          int maxit, gd_ks_work *ws, gd_ks_result *out); /* ws may be NULL */
void gd_ks_result_free(gd_ks_result *r);

/* ---- sparse_modal.c ---- */
/* Lowest opt->nmodes damped modes at opt->speed by shift-invert about sigma = -shift
 * (shift <= 0: automatic), reusing a built pattern and symbolic analysis. */
typedef struct gd_sparse_ws {
    gd_ks_work ks;
    double *k, *d;
} gd_sparse_ws;
/* Workspace for nmodes modes of the pattern a (0 ok, 1 out of memory). */
int gd_sparse_ws_init(gd_sparse_ws *w, const gd_dynmat *a, int nmodes);
void gd_sparse_ws_free(gd_sparse_ws *w);
/* ws may be NULL (allocated per call). */
gd_status gd_sparse_modes(const gd_dynmat *a, const gd_splu_symbolic *sym,
                          const gd_modal_options *opt, double shift, gd_sparse_ws *ws,
                          gd_modal_result **out, gd_error *err);
/* sqrt(min K_ii / M_ii): a frequency of the order of the lowest modes' (1 when no
 * DOF has both). The automatic shift is 1e-3 of it, far below the lowest elastic
 * mode of most models; the state scaling g is this frequency itself. */
double gd_sparse_diag_frequency(const gd_dynmat *a, const double *k);

#endif
