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
    double *tq, *tv, *tf; /* nf x N samples (tq[j * nf + i]) or spectra (tf[i * N + k]) */
    double *sq, *sv;      /* nterm x N term derivatives */
    double *y;            /* 2 nf: one sample */
    double *smp;          /* gd_hb_samples' spectra and samples, 3 x nsmp */
    /* union pattern of K, M, D (gd_hb_linear_union) */
    int *Up, *Ui, Unz;    /* sorted CSC, nf columns */
    double *UK, *UM, *UD; /* values on it (one allocation, UK first) */
    long Upat_id;         /* changes with the pattern */
    int *Uq, *Ui2, *umark;
    size_t ucap;
    size_t nsmp;
    fftw_plan fwd_f, inv_q;
    fftw_plan row_fwd, row_inv; /* one row of N (rowbuf -> rowbuf + N) */
    double *rowbuf;             /* 2 N */
    int *win, nin;              /* input support: the DOFs the forces read (nin -1: all) */
    int *win2;                  /* the next one, compared with it */
    unsigned char *rowmark;     /* nf: rows with a non-zero force sample */
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
    /* low-rank path (lowrank.c): J = L - U Y with L block diagonal per harmonic */
    int solver;             /* 0 automatic, 1 sparse LU of the whole system, 2 low-rank */
    int r;                  /* rank ngroup x nh */
    int ngroup;             /* terms grouped by their force direction u (lowrank.c) */
    int *tgroup;            /* nterm: the group of each term */
    int *grep;              /* ngroup: a term of each group (its u) */
    double *Gall;           /* nterm x nh x nh: the terms' harmonic couplings G_t */
    unsigned char *tactive; /* nterm: the term is non-zero in some sample (its G too) */
    double *Fh;             /* n: the force coefficients F(X) of the last residual */
    int Fh_ok;
    size_t nGall;
    double *Lx; /* values of one block on the union pattern (complex for k > 0) */
    size_t nLx;
    long Lsym_pat;      /* the union pattern id Lsym was made for */
    double *zb;         /* 2 nf: one complex right-hand side */
    klu_symbolic *Lsym; /* one analysis for the real mean and the complex harmonics */
    klu_numeric **Lnum; /* H + 1 */
    double *Lrcond;     /* H + 1: KLU's rcond at each block's last pivoting factorization */
    double *P;          /* n x r: L^-1 U */
    double *S;          /* r x r capacitance I - W^T P C, LU factors */
    int *Spiv;
    double *xc;      /* n: J^-1 dRdp */
    double *brow;    /* n + 1: the bordering row */
    double denom;    /* d - row . J^-1 c */
    double *wr, *wz; /* r workspaces */
    /* Newton solves at one L (lowrank.c): L^-1 F(X) = L^-1 F(X0) + P dPhi, the force
     * change dF = U dPhi lying along the groups' directions */
    double *Z0, *F0; /* n: L^-1 F(X0) and F(X0) at the first solve with this L */
    int base_ok;
    int *urow, nur; /* the DOFs of the groups' u vectors; urow_of: inverse (nf, -1) */
    int *urow_of;
    double *Umat;  /* nur x ngroup, column-major */
    double *fitw;  /* ngroup x ngroup: Cholesky factor of U^T U; then ngroup x nh */
    int ugram_ok;  /* that factor exists (independent directions) */
    long stage_id; /* set by the caller: the problem the next factorisation is of */
    long L_id;     /* the problem and frequency L and P were made for */
    double L_w;
    /* the iterative capacitance (capacitance.c), used instead of S above the crossover */
    int cap_iter;       /* 1: no S; S z = b by preconditioned GMRES */
    int cap_nt;         /* nterm the workspace below was made for */
    double *cT;         /* (H + 1) x nterm x ngroup complex: w_t^T Z_k^-1 u_g */
    double *cpre;       /* (H + 1) x ngroup^2 complex: LU of the mean capacitance per harmonic */
    int *cpiv;          /* (H + 1) x ngroup */
    double *cq;         /* 2 nterm N: the samples s_q and w s_v of the factorized iterate */
    double *cwork;      /* GMRES workspace */
    long cap_iters;     /* GMRES iterations so far (diagnostics) */
    double cap_resid;   /* the largest relative residual a solve ended with */
    double alias;       /* the last residual's aliasing floor: the force content in the top
                           quarter below the Nyquist harmonic, relative to the residual's scale */
    struct gd_chb *chb; /* the condensed solve's workspace (condensed/chb.h), or NULL */
    struct gd_floquet_modes *fmodes; /* floquet_reduced.c's modes of (K, M), or NULL */
    /* and their destructor, set with them (hb/ does not call into floquet/: no circle) */
    void (*fmodes_free)(struct gd_floquet_modes *);
} hb;
void gd_floquet_modes_free(struct gd_floquet_modes *m);

/* The low-rank (Woodbury) factorisation of the bordered system and its solve, used by
 * gd_hb_factor / gd_hb_solve when solver is 2, or 0 with a large system whose nonlinear
 * rank is small. */
/* The rank from which the capacitance is solved iteratively when the solver is automatic
 * (0 or 2): measured on the two-stage gearbox, docs/periodic.md "Two linear solvers". */
#ifndef GD_HB_CAP_CROSSOVER
#define GD_HB_CAP_CROSSOVER 1000
#endif
/* 1 when the capacitance of rank r is solved iteratively: solver 3 always, 4 never, else
 * from GD_HB_CAP_CROSSOVER. */
int gd_hb_cap_iterative(int solver, int r);
/* tactive from the last residual's term samples (what gd_hb_couplings also sets). 0 ok. */
int gd_hb_term_activity(hb *h);
/* Workspace for rank h->r, h->ngroup, h->nterm; 0 ok, 1 out of memory. */
int gd_hb_cap_alloc(hb *h);
void gd_hb_cap_free(hb *h);
/* Transfer scalars from h->P (fresh: L changed) and the mean preconditioner from the last
 * residual's samples at w. 0 ok. */
int gd_hb_cap_factor(hb *h, double w, int fresh);
/* wz (r) = Y x for x in the harmonic unknowns (n). */
void gd_hb_cap_Yy(hb *h, const double *x, double *wz);
/* b := S^-1 b by GMRES to the relative residual tol; *iters the iterations (may be NULL).
 * 0 converged, 2 only to 1e-8 (the result is kept), 1 not even that. */
int gd_hb_cap_solve(hb *h, double *b, double tol, int *iters);
int gd_hb_lowrank_factor(hb *h, gd_transient *tr, double w, const double *dRdp, const double *row);
void gd_hb_lowrank_solve(hb *h, double *b);
void gd_hb_lowrank_solve_J(hb *h, double *x);
int gd_hb_use_lowrank(const hb *h);
/* Groups the terms by equal u: tgroup[t] (nterm) and a representative term per group
 * grep[g]; either may be NULL (then only the count). Returns the number of groups. */
int gd_hb_term_groups(const hb *h, int *tgroup, int *grep);
void gd_hb_lowrank_free(hb *h);

int gd_hb_init(hb *h, int nf, int H, int N);
/* The union pattern of the problem's K, M, D with their values on it (Up, Ui, UK, UM,
 * UD); Upat_id changes when the pattern does. 0 ok, 1 out of memory. */
int gd_hb_linear_union(hb *h, gd_transient *tr);
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
/* The same for Newton's right-hand side b = -R(X) (bordered), X the point of the last
 * gd_hb_residual: the low-rank path then needs no block solves after the first at a
 * factorization (the forces change only along the laws' directions). */
void gd_hb_solve_newton(hb *h, const double *X, double *b);
void gd_hb_lowrank_solve_newton(hb *h, const double *X, double *b);
/* q and q' at N equally spaced phases of one period, sample-major (q[j * nd + m] for DOF
 * dofs[m]; dofs NULL: every DOF, nd = nf, by batched transforms), into the workspace's
 * buffers (*q, *v; valid until the next call). 0 ok; 1 if N <= 2 H or no memory. */
int gd_hb_samples(hb *h, double w, const double *X, int N, const int *dofs, int nd, double **q,
                  double **v);
/* q(t), q'(t) (nf each) from the coefficients at phase tau = w t. */
void gd_hb_eval(const hb *h, double w, const double *X, double tau, double *q, double *v);

/* Floquet multipliers of the variational equations about the solution X (nf free DOFs,
 * period 2 pi / w): mu_re, mu_im of length 2 nf. bl: GD_REC_MESH_STATE records of the
 * backlash meshes (nbl), whose contact changes split the steps. 0 ok, 2 when the
 * monodromy matrix is not finite (too few steps for the orbit), 1 other failures. */
int gd_hb_floquet(const hb *h, gd_transient *tr, double w, const double *X, int steps,
                  const gd_tr_record *bl, int nbl, double *mu_re, double *mu_im);
/* As gd_hb_floquet within a budget (seconds of counted work at GD_PER_FLOPS, 0: none): 4
 * when the multipliers would take longer (counted before the first step), with msg (160
 * bytes) saying by how much. */
int gd_hb_floquet_budget(const hb *h, gd_transient *tr, double w, const double *X, int steps,
                         const gd_tr_record *bl, int nbl, double budget, double *mu_re,
                         double *mu_im, char *msg);
/* E = exp(A) (n x n, column-major) by scaling and squaring with the Pade approximant of
 * gd_hb_floquet; W: 6 n^2 workspace, ipiv: n. 0 ok, 1 A not finite or singular. */
int gd_expm_dense(int n, const double *A, double *E, double *W, int *ipiv);
/* The Magnus step boundaries of gd_hb_floquet (phases 0..2 pi): `steps` equal steps,
 * each split at the contact changes of the backlash meshes bl. *tau (nsub + 1 entries,
 * the caller frees). 0 ok, 1 out of memory. */
int gd_hb_magnus_steps(const hb *h, gd_transient *tr, double w, const double *X, int steps,
                       const gd_tr_record *bl, int nbl, double **tau, int *nsub);
/* The nev Floquet multipliers of largest modulus of the same Magnus monodromy as
 * gd_hb_floquet (the same steps), without forming it (floquet_krylov.c): Krylov-Schur on
 * monodromy-vector products, each step's exponential applied to the vector by a
 * truncated Taylor series with scaling. mu_re, mu_im: at least nev; *nmu receives the
 * count delivered (nev, or one more when a conjugate pair straddles the cut), each with
 * a relative residual within tol; *products the monodromy-vector products used. 0 ok,
 * 2 the products overflowed (too few steps), 3 no convergence (a cluster of equal
 * moduli across the cut: ask for more), 4 over the budget (seconds of counted work, 0:
 * none: the products a search needs counted before the first, or their count passed), 1 other
 * failures; msg (160 bytes) says why. */
int gd_hb_floquet_krylov(const hb *h, gd_transient *tr, double w, const double *X, int steps,
                         const gd_tr_record *bl, int nbl, int nev, double tol, double budget,
                         double *mu_re, double *mu_im, int *nmu, int *products, char *msg);

/* The multipliers of the monodromy in a reduced basis (floquet_reduced.c): the modes of
 * (sym K, M) below wcut (rad/s) and the discarded modes' residual flexibility along the
 * terms' u and w, the reduced constant part diagonalised (its exponential exact), each step
 * a fourth-order Magnus step of the rank-nterm local part in the interaction picture.
 * steps > 0: that many steps per period; 0: s0 steps, doubled until two counts' moduli
 * agree where stability is decided (each within 1 % of its distance from the unit circle,
 * at least 1e-7), at most steps_cap; *steps_used (may be
 * NULL) the count taken. mu_re,
 * mu_im: at least 2 nf; *nmu = 2 r of them, largest modulus first, *nbasis = r. 0 ok, 2 not
 * finite (too few steps, a count given), 4 over the budget (seconds of counted
 * work, 0: none), 5 no
 * usable basis (an ill-conditioned eigenvector basis: a free rotation's Jordan block; or too
 * many DOFs for the dense modes): use another method, 6 the steps' own count did not settle
 * (or overflowed) by steps_cap, 1 other failures; msg (160 bytes) says why. */
/* The reduced basis's first step count of its own: 8 per period of the top excitation
 * order (top: the period's count of them), a power of 2, at least 256. */
int gd_floquet_reduced_first_steps(long top);
int gd_hb_floquet_reduced(hb *h, gd_transient *tr, double w, const double *X, int steps, int s0,
                          int steps_cap, int *steps_used, const gd_tr_record *bl, int nbl,
                          double wcut, double budget, double *mu_re, double *mu_im, int *nmu,
                          int *nbasis, char *msg);

/* The periodic orbit of the problem linearised at rest (a linear time-periodic system:
 * the laws' terms at q = 0) in the reduced basis of gd_hb_floquet_reduced with the cut-off
 * wcut (rad/s), exact in time to the steps: one pass of `steps` Magnus steps gives the
 * monodromy Phi and the forced response p from the static state x_s = K^-1 f(t, 0), the
 * orbit starts at (I - Phi)^-1 p, a second pass of max(steps, steps_out) steps evaluates
 * the nrec records at every step's end: their mean and peak-to-peak (nrec each), *nbasis the basis,
 * *mumax (may be NULL) the largest multiplier of the reduced monodromy. 0 ok, 2 msg says why, else
 * failures. */
int gd_hb_orbit_reduced(hb *h, gd_transient *tr, double om, int steps, int steps_out, double wcut,
                        const gd_tr_record *rec, int nrec, double *mean, double *p2p, int *nbasis,
                        double *mumax, char *msg);
/* The same with the orbit's samples and multipliers (the method row of reduced shooting,
 * rshoot/): x->values (nrec x x->n, record k at sample j, time j T / n, n = max(steps,
 * steps_out)) and x->mu (the 2 x->nmu = 2 (2 nbasis) real then imaginary parts of the
 * reduced monodromy's eigenvalues), both allocated here, the caller's to free (also on a
 * failure: set them NULL before). */
typedef struct gd_orbit_samples {
    double *values;
    int n;
    double *mu;
    int nmu;
} gd_orbit_samples;
int gd_hb_orbit_reduced_out(hb *h, gd_transient *tr, double om, int steps, int steps_out,
                            double wcut, const gd_tr_record *rec, int nrec, double *mean,
                            double *p2p, int *nbasis, double *mumax, gd_orbit_samples *x,
                            char *msg);

/* Static start (warmstart.c): where the model has laws that carry a static load
 * (GD_LAW_SUPPORT), the zeroth harmonic of X (its first nf entries; the rest untouched)
 * set to the laws' static equilibrium at speed under the spec's mean loads. Returns 1
 * when set, 0 when the model has no such law or no equilibrium was found (X untouched). */
int gd_hb_static_start(const gd_system *sys, const gd_transient_spec *spec, const gd_transient *tr,
                       double speed, int nf, double *X);

/* Warm start (warmstart.c): the coefficients X (nf (2 H + 1)) of the last of `periods`
 * periods (2 pi / w) of a transient from rest (static equilibrium with loads) of the
 * problem at speed. 0 ok. */
int gd_hb_warm_start(const gd_system *sys, const gd_transient_spec *spec, double speed, double w,
                     int H, int periods, double *X);

/* Truncation estimate (truncation.c): per record, the change of the peak-to-peak and of the
 * harmonic amplitudes between the coarse solution (Hc) and the fine one (Hf), stored in
 * fine's p2p_error / amp_error; the largest over the records in *p2p, *amp. */
void gd_hb_truncation(const gd_per_record_stats *coarse, int Hc, gd_per_record_stats *fine, int Hf,
                      int nrec, const double *zero, double *p2p, double *amp);
/* Per record the size (|mean| + peak-to-peak) below which it is zero to rounding, from the
 * coefficients X (n of them) at frequency w with H harmonics: 1e-12 of the largest
 * coefficient for a DOF displacement, times H w for a velocity; 0 (never zero) for the
 * other records, whose units the coefficients do not carry. */
void gd_hb_record_zero(const gd_tr_record *rec, int nrec, const double *X, int n, int H, double w,
                       double *zero);
/* The n multipliers in place, largest modulus first (stable: multipliers.c). */
void gd_hb_sort_multipliers(double *mu_re, double *mu_im, int n);
/* |Xc - Xf| / |Xf| over the coefficients (Xc padded with zeros from nc to nfine). */
double gd_hb_coef_change(const double *Xc, int nc, const double *Xf, int nfine);
/* Bytes of one workspace (an estimate) and the limit of the options. */
double gd_hb_memory(int nf, int H, int N, int nterm, int ngroup, long knz);
double gd_hb_memory_limit(const gd_periodic_options *opt);
/* What gd_hb_memory needs of a problem (one transient problem built). 0 ok. */
int gd_hb_memory_params(const gd_system *sys, const gd_transient_spec *spec, double speed, int *nf,
                        int *nterm, int *ngroup, long *knz);
void gd_hb_memory_params_tr(gd_transient *tr, int *nf, int *nterm, int *ngroup, long *knz);
int gd_hb_samples_for(int H); /* the default AFT samples: 4 (H + 1) up to 2^k, >= 16 */
/* Statistics of one record from Nr samples over one period (points.c): mean, rms,
 * peak-to-peak, harmonics 0..H (plan: R2HC of length Nr, buf -> out). 0 ok. */
int gd_per_sample_stats(const double *v, int Nr, int H, fftw_plan plan, double *buf, double *out,
                        gd_per_record_stats *st);

/* The spec with its time-harmonic loads at frequency value (frequency.c): *out a copy of
 * spec whose loads are *loads (the caller frees it). 0 ok; 1 with msg (no such load). */
int gd_per_frequency_spec(const gd_transient_spec *spec, double value, gd_tr_load **loads,
                          gd_transient_spec *out, char *msg, size_t cap);

/* One step of regula falsi, Illinois variant, on the bracket [s0, s1] whose values g0, g1
 * differ in sign: g, the value at sig, replaces the end of its sign and halves the other
 * end's value (so a retained end cannot stall the bracket). Returns the next sig. */
static inline double gd_per_illinois(double sig, double g, double *s0, double *g0, double *s1,
                                     double *g1)
{
    if ((g < 0) == (*g0 < 0)) {
        *s0 = sig;
        *g0 = g;
        *g1 *= 0.5;
    } else {
        *s1 = sig;
        *g1 = g;
        *g0 *= 0.5;
    }
    return *s0 - *g0 * (*s1 - *s0) / (*g1 - *g0);
}

/* Counted work (work.c): budgets and auto's cost rule are decided from operation counts,
 * shown as seconds at the nominal rate GD_PER_FLOPS, never from clocks (the same command
 * gives the same output). GD_PER_TERM_FLOPS: one law term evaluated (contact test, table
 * stiffness, force and direction). */
#define GD_PER_FLOPS 2e9
#define GD_PER_TERM_FLOPS 200.0
double gd_per_work_seconds(double flops);
double gd_per_rhs_flops(gd_transient *tr, const gd_transient_spec *spec);
double gd_per_hb_step_flops(gd_transient *tr, int H, int N);
/* The options' bounds (run.c: GD_EINPUT naming the field), and the run by one method,
 * opt->kind GD_PER_HB or GD_PER_SHOOTING (run.c); gd_periodic_run (auto.c) resolves
 * GD_PER_AUTO and hands failed points over. */
gd_status gd_per_check_options(const gd_periodic_param *param, const double *values, int nvalues,
                               const gd_periodic_options *opt, const gd_tr_record *records,
                               int nrecords, gd_error *err);
gd_status gd_per_run_kind(const gd_system *sys, const gd_transient_spec *spec,
                          const gd_periodic_param *param, const double *values, int nvalues,
                          const gd_periodic_options *opt, const gd_tr_record *records, int nrecords,
                          gd_periodic_result **out, gd_error *err);
/* The multipliers of the harmonic balance solution X (workspace h, frequency w) at value
 * key from the orbit corrected by shooting (floquet_shooting.c): its state at t = 0
 * corrected by Newton on the period map, the eigenvalues of that orbit's monodromy in
 * mre, mim (2 nf), *nmu of them (the largest by Arnoldi on the matrix-free path), *change
 * the correction scaled as shooting's residual. 0 ok; 1 with msg (cap bytes). */
int gd_per_floquet_shooting(const gd_system *sys, const gd_transient_spec *spec,
                            const gd_periodic_param *param, const gd_periodic_options *opt,
                            double key, const hb *h, double w, const double *X, double *mre,
                            double *mim, int *nmu, double *change, char *msg, size_t cap);
/* 1 when a law of the problem at speed has a switch or a kink (choose.c). */
int gd_per_nonsmooth(const gd_system *sys, const gd_transient_spec *spec, double speed);
/* 1 (with msg, cap bytes) when `--method auto` refuses the problem before solving
 * (refuse.c): a common period too long for harmonic balance's memory at the H it would
 * need and a model the multi-frequency torus cannot take; 0 otherwise. */
int gd_per_qp_refusal(const gd_system *sys, const gd_transient_spec *spec, double speed,
                      const gd_periodic_options *opt, char *msg, size_t cap);

/* A new point appended to r (its array grown by doubling, *cap_points its capacity), every
 * field cleared and the "not computed" values set (stable -1, mu_max and residual NaN,
 * harmonic_ok -1), of method and direction dir; NULL when out of memory. common/point_new.c;
 * one rule for every method's points. */
gd_periodic_point *gd_per_point_new(gd_periodic_result *r, int *cap_points, int dir,
                                    gd_per_kind method);

#endif
