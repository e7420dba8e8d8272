/* Internals of the harmonic balance solver shared by its source files. */
#ifndef GD_PERIODIC_IMPL_H
#define GD_PERIODIC_IMPL_H
#include <fftw3.h>
#include <klu.h>

#include "geardyn/periodic.h"

/* Harmonic balance workspace for nf free DOFs, H harmonics, N samples per period.
 * Unknowns X[h * nf + i], h = 0 mean, 2k-1 cos k, 2k sin k; the bordered Newton system
 * has one more row (continuation constraint) and column (derivative in the parameter). */
typedef struct hb {
    int nf, H, nh, N, n;
    double *tq, *tv, *tf; /* nf x N samples, DOF-major (tq[i * N + j]) */
    double *sq, *sv;      /* nterm x N term derivatives */
    double *y, *f;        /* 2 nf, nf: one sample */
    double *E, *Ed;       /* N x nh basis and its derivative in the phase, E[h * N + j] */
    fftw_plan fwd_f, inv_q, inv_v;
    int nterm;
    const gd_tr_term *term;
    /* bordered Jacobian, CSC with sorted rows */
    int nnz;
    int *Ap, *Ai;
    double *Ax;
    int miss; /* an entry outside the pattern was met: rebuild it */
    klu_symbolic *sym;
    klu_numeric *num;
    klu_common com;
    /* pattern collection */
    int ntrip, captrip;
    int *ti, *tj;
    /* low-rank path (lowrank.c): J = L - U C W^T with L block diagonal per harmonic */
    int solver;   /* 0 automatic, 1 sparse LU of the whole system, 2 low-rank */
    int r;        /* rank nterm x nh */
    double *Gall; /* nterm x nh x nh: the terms' harmonic couplings G_t */
    size_t nGall;
    int *Lp, *Li;   /* CSC pattern of a 2 nf harmonic block (cos, sin) */
    double *Lx;     /* values of one block */
    int *L0p, *L0i; /* pattern of the mean block (nf) */
    double *L0x;
    klu_symbolic *Lsym, *L0sym;
    klu_numeric **Lnum; /* H + 1 */
    double *P;          /* n x r: L^-1 U */
    double *S;          /* r x r capacitance I - W^T P C, LU factors */
    int *Spiv;
    double *xc;      /* n: J^-1 dRdp */
    double *brow;    /* n + 1: the bordering row */
    double denom;    /* d - row . J^-1 c */
    double *wr, *wz; /* r workspaces */
    long stage_id;   /* set by the caller: the problem the next factorisation is of */
    long L_id;       /* the problem and frequency L and P were made for */
    double L_w;
} hb;

/* The low-rank (Woodbury) factorisation of the bordered system and its solve, used by
 * gd_hb_factor / gd_hb_solve when solver is 2, or 0 with a large system whose nonlinear
 * rank is small. */
int gd_hb_lowrank_factor(hb *h, gd_transient *tr, double w, const double *dRdp, const double *row);
void gd_hb_lowrank_solve(hb *h, double *b);
void gd_hb_lowrank_solve_J(hb *h, double *x);
int gd_hb_use_lowrank(const hb *h);
void gd_hb_lowrank_free(hb *h);

int gd_hb_init(hb *h, int nf, int H, int N);
void gd_hb_free(hb *h);
/* R = L(w) X - F(X) with the problem tr at angular frequency w; also the samples' term
 * derivatives when jac. Returns 0, or 1 if a force is not finite. */
int gd_hb_residual(hb *h, gd_transient *tr, double w, const double *X, double *R, int jac,
                   double *scale);
/* G_t of every term from the last residual's samples (jac = 1) at w, into Gall. 0 ok. */
int gd_hb_couplings(hb *h, double w);
/* Fills the bordered matrix: the Jacobian of the last residual (jac = 1) at w, column
 * dRdp (NULL: zeros) and the last row (row, length n + 1). Rebuilds the pattern and the
 * symbolic analysis when needed; factors. 0 ok, 1 singular. */
int gd_hb_factor(hb *h, gd_transient *tr, double w, const double *dRdp, const double *row);
/* Solves the factored bordered system in place (b of length n + 1). */
void gd_hb_solve(hb *h, double *b);
/* q(t), q'(t) (nf each) from the coefficients at phase tau = w t. */
void gd_hb_eval(const hb *h, double w, const double *X, double tau, double *q, double *v);

/* Floquet multipliers of the variational equations about the solution X (nf free DOFs,
 * period 2 pi / w): mu_re, mu_im of length 2 nf. bl: GD_REC_MESH_STATE records of the
 * backlash meshes (nbl), whose contact changes split the steps. 0 ok. */
int gd_hb_floquet(const hb *h, gd_transient *tr, double w, const double *X, int steps,
                  const gd_tr_record *bl, int nbl, double *mu_re, double *mu_im);

#endif
