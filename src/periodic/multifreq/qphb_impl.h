/* Multi-frequency (quasi-periodic) harmonic balance: the response of a train whose
 * excitations have d independent base frequencies W_1..W_d (one per mesh group: tooth
 * counts whose ratio is not a small whole number) as a Fourier series on the d-torus,
 *   q(theta) = X_0 + sum_k C_k cos(k . theta) + S_k sin(k . theta),  theta_g = W_g t,
 * over a truncation set of integer vectors k (Guskov & Thouverez, J. Vib. Acoust. 134
 * (2012) 031003; Krack & Gross, Harmonic Balance for Nonlinear Vibration Problems, 2019,
 * ch. 5). d/dt = sum_g W_g d/dtheta_g, so harmonic k has the frequency Omega_k = k . W and
 * the linear part acts on it as on a harmonic of that frequency; the forces are sampled
 * on a d-dimensional grid (AFT, multi-dimensional FFTW), each law read at the phase of
 * its own base frequency. The physical response is the slice theta = W t. */
#ifndef GD_QPHB_IMPL_H
#define GD_QPHB_IMPL_H
#include <complex.h>
#include <fftw3.h>

#include "geardyn/periodic.h"
#include "geardyn/transient.h"

#define GD_QP_MAXD 3

/* The base frequencies of a problem and each law's group. */
typedef struct gd_qp_bases {
    int d;                /* 0: no excitation; 1..GD_QP_MAXD */
    double W[GD_QP_MAXD]; /* rad/s, ascending */
    int nlaw;             /* the problem's laws */
    int *group;           /* nlaw: the base each law is read at (-1: a law without frequency) */
    double common;        /* the common fundamental (rad/s) of the W when they have one whose
                             orders are at most 100000, else 0 */
    long order;           /* the highest W over common (0 without) */
} gd_qp_bases;

/* The base frequencies of the problem tr (built from sys, spec at speed): every law's
 * excitation frequencies (gd_law_type.frequencies) grouped, a law joining a base of which
 * its fundamental is a whole multiple (up to 64 times; or the base one of its own). 0 ok;
 * 1 with msg (cap bytes) when the problem has an excitation the torus does not take
 * (unbalances, prescribed periodic motions: their own time, not a law's), more than
 * GD_QP_MAXD bases, or no memory. b->group is owned: gd_qp_bases_free. */
int gd_qp_find_bases(gd_transient *tr, const gd_system *sys, const gd_transient_spec *spec,
                     double speed, gd_qp_bases *b, char *msg, size_t cap);
void gd_qp_bases_free(gd_qp_bases *b);

/* The truncation set: k = 0, then the half of {k : sum |k_g| W_g <= H W_top, k != 0}
 * (W_top the highest base: each base keeps its harmonics up to H W_top / W_g) whose first
 * non-zero component is positive (-k is the same cosine and sine), lexicographically. */
typedef struct gd_qp_torus {
    int d, H;
    int Hg[GD_QP_MAXD]; /* each base's highest harmonic */
    long span;          /* the box prod (2 H_g + 1) */
    int *box;           /* span: the index of each k of the box in the set, or -1 */
    double W[GD_QP_MAXD];
    int nk; /* harmonics, k = 0 first */
    int *k; /* nk x d */
    int N[GD_QP_MAXD];
    long Ntot;       /* grid points */
    long *pos, *neg; /* nk: the grid (FFT) index of k and of -k */
} gd_qp_torus;

/* The set of order H for the bases (grid: per base the least 2-3-5-smooth size >=
 * 4 (H_g + 1), at least 16). 0 ok, 1 no memory. */
int gd_qp_torus_init(gd_qp_torus *T, const gd_qp_bases *b, int H);
/* The index of harmonic k (d entries) in the set, -1 when not in it. */
int gd_qp_torus_find(const gd_qp_torus *T, const int *k);
void gd_qp_torus_free(gd_qp_torus *T);
/* Unknowns of a torus with nf DOFs: nf (2 nk - 1): X[0 .. nf-1] the mean, then per
 * harmonic j >= 1 the cosine block at (2 j - 1) nf and the sine block at 2 j nf. */
static inline long gd_qp_unknowns(const gd_qp_torus *T, int nf)
{
    return (long)nf * (2L * T->nk - 1);
}

/* One point's solver. */
typedef struct gd_qp {
    gd_transient *tr; /* borrowed */
    int nf, nt;
    const gd_tr_term *term;
    const gd_qp_bases *b; /* borrowed */
    gd_qp_torus T;        /* owned */
    long n;
    fftw_complex *buf; /* nf x Ntot, DOF-major */
    fftw_plan inv, fwd;
    double *qs, *vs, *fs; /* Ntot x nf, sample-major */
    double *sq, *sv;      /* nt x Ntot: the terms' derivatives at the last residual */
    double *ltime;        /* nlaw: each law's time at the current grid point */
    double *y;            /* 2 nf */
    double *st;           /* 2 nt: one sample's term derivatives */
    double complex *P;    /* nk x nf x nf: LU of the mean-term harmonic blocks */
    int *piv;             /* nk x nf */
    double *w1, *w2;      /* n each */
    long matvecs;         /* Jacobian-vector products so far */
} gd_qp;

/* Workspace for the problem tr on the torus of order H. 0 ok; 1 no memory, 2 too large
 * (msg says how large). */
int gd_qp_init(gd_qp *q, gd_transient *tr, const gd_qp_bases *b, int H, char *msg, size_t cap);
void gd_qp_free(gd_qp *q);
/* R = L X - F(X) (n); the terms' derivatives kept for the Jacobian; *scale
 * max(|L X|, |F|). 0 ok, 1 a force is not finite. */
int gd_qp_residual(gd_qp *q, const double *X, double *R, double *scale);
/* The damped Newton step of both tori (full and condensed): w2 = X + lam dx with lam halved
 * (up to 4 times) until the residual res(ctx, w2, R, scale) falls below nr. 0 accepted
 * (w2, R and scale are the accepted point's), 1 stalled. */
typedef int (*gd_qp_residual_fn)(void *ctx, const double *X, double *R, double *scale);
int gd_qp_damped_step(long n, const double *X, const double *dx, double nr, gd_qp_residual_fn res,
                      void *ctx, double *w2, double *R, double *scale);
/* Newton from X (n, in place) to the relative residual tol: Newton-Krylov, GMRES
 * (SUNDIALS SPGMR) on Jacobian-vector products by the AFT of the linearised forces, right-
 * preconditioned by the harmonic blocks with the terms' torus means. *resid the relative
 * residual reached, *iters the Newton steps. 0 converged, 1 not (msg says why). */
int gd_qp_newton(gd_qp *q, double *X, double tol, int max_iter, double *resid, int *iters,
                 char *msg, size_t cap);
/* q(t), q'(t) (nf each) of the slice theta = W t (phases of the bases at t). */
void gd_qp_eval(const gd_qp *q, const double *X, double t, double *qt, double *vt);
/* Samples of X over the grid (sample-major, Ntot x nf; velocities too), into q->qs, q->vs.
 * 0 ok, 1 no memory (a view's buffers). */
int gd_qp_samples(gd_qp *q, const double *X);
/* Sets each law's time at grid point p (the problem's t, returned, is that of base 1). */
double gd_qp_point_times(gd_qp *q, long p);

/* The condensed torus (qpc.c): the laws' coordinates y = C^T q (C: the distinct
 * directions of the terms, nc columns) as the only unknowns, the linear structure by its
 * receptance at each harmonic's frequency,
 *   Y_k = C^T Z_k^-1 r_k + H_k G_k(Y),  H_k = C^T Z_k^-1 C,  Z_k = K - W_k^2 M + i W_k D,
 * (Petrov & Ewins 2003, Sec. 2, on the torus of Guskov & Thouverez 2012) with g = (C^T
 * C)^-1 C^T f the forces along C at each grid point and r the rest (loads: no law moves
 * them). One sparse complex LU (KLU) of Z_k per harmonic gives H_k and Z_k^-1 [C r_k];
 * the full coefficients are recovered after convergence, X_k = Z_k^-1 (r_k + C G_k). Real
 * FFTs over the nc coordinates only: its cost does not grow with the DOFs. */
typedef struct gd_qpc gd_qpc;
/* The coordinate count nc when the problem's terms give independent coordinates, fewer
 * than the free DOFs (the condensed torus applies), else 0. */
int gd_qpc_applies(gd_transient *tr);
/* Workspace on the torus of order H; NULL with msg when it cannot be made. */
gd_qpc *gd_qpc_new(gd_transient *tr, const gd_qp_bases *b, int H, char *msg, size_t cap);
void gd_qpc_free(gd_qpc *c);
const gd_qp_torus *gd_qpc_torus(const gd_qpc *c);
/* Newton-Krylov from the full coefficients X (gd_qp_unknowns(T, nf)): X receives the
 * recovered full solution. Same contract as gd_qp_newton. */
int gd_qpc_newton(gd_qpc *c, double *X, double tol, int max_iter, double *resid, int *iters,
                  char *msg, size_t cap);
/* A view of the problem and torus for the records (gd_qp without the full workspace:
 * gd_qp_samples makes its sample buffers when first called; gd_qp_view_release frees them). */
void gd_qpc_view(gd_qpc *c, gd_qp *q);
void gd_qp_view_release(gd_qp *q);
/* Jacobian-vector products so far. */
long gd_qpc_matvecs(const gd_qpc *c);

/* The stability of a point (qp_stability.c): the Floquet multipliers of the slice over
 * the bases' common period (the integrated monodromy from the slice's state at t = 0;
 * stability_method GD_PER_MULTIFREQ), or without one a Lyapunov estimate (said in note).
 * X: the full coefficients on the harmonics k (nk x d). Up to opt->shoot_dense_max (0: 64)
 * states the dense Magnus monodromy; above, with a common period and smooth laws, the
 * reduced basis of floquet_reduced.c on the slice (note says so), else note says why not.
 * 0 done (p's multipliers set, or note says why not), 1 no memory. */
int gd_qp_stability(gd_transient *tr, const gd_qp_bases *b, const double *X, const int *k, int nk,
                    int nf, const gd_periodic_options *opt, gd_periodic_point *p, char *note,
                    size_t cap);

/* The branch over speed by the torus (qp_run.c): natural continuation, each point from the
 * last; adaptive H (opt->adaptive: 32 raised by half until two orders' records agree to
 * harmonic_tol, at most 48 or max_harmonics) or opt->harmonics; each point's stability
 * (gd_qp_stability) with opt->stability. 0 ok, 1 no memory. */
int gd_per_qp_run(const gd_system *sys, const gd_transient_spec *spec, const double *values,
                  int nvalues, const gd_periodic_options *opt, const gd_tr_record *records,
                  int nrecords, gd_periodic_result *res);

/* The bases of the problem at speed, for `--method auto` (choose.c): d (0: none found or
 * the torus cannot take the problem) with the common fundamental's order (0 when none)
 * and the DOFs nf the torus solves for (the laws' coordinates where it condenses, else
 * the free DOFs). */
int gd_per_qp_probe(const gd_system *sys, const gd_transient_spec *spec, double speed,
                    double W[GD_QP_MAXD], long *order, int *nf, char *msg, size_t cap);
#endif
