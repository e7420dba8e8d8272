/* Internals of the transient problem shared by its source files. */
#ifndef GD_TRANSIENT_INTERNAL_H
#define GD_TRANSIENT_INTERNAL_H
#include <cs.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "geardyn/transient.h"

typedef struct tr_unb {
    int dx, dy;
    double force;                 /* U omega^2 */
    double omega;                 /* signed shaft speed */
    double phase;                 /* angle of the heavy spot at t = 0 from +x */
    double ratio, amount, phase0; /* shaft's speed ratio, U (kg m), model phase (run-up) */
} tr_unb;

/* A modal reduction (reduce.c): the problem's coordinates x = [q_B; eta] and the
 * physical DOFs q = T x. */
typedef struct gd_tr_reduction {
    int nfull, nb, nr, nmodes;
    int *kept;    /* nfull: index in x of a kept DOF, or -1 */
    int *irow;    /* nfull: row of TI of an interior DOF, or -1 */
    double *rate; /* nfull: nominal speed of each physical DOF */
    double *TI;   /* interior rows of T, row-major (nI x nr): [Psi Phi] */
    double *MTI;  /* rows of M_II Phi in columns nb.. (projection of a state) */
} gd_tr_reduction;

/* The condensed structure a problem is integrated on (condensed.c): states x of the kept
 * modes, coordinates = the nc DOFs the laws and unbalances act on. */
#include "geardyn/condense.h"
#define GD_TR_CONDENSE_EXC 5.0     /* auto cut-off: 5 x the highest excitation frequency */
#define GD_TR_CONDENSE_CONTACT 2.5 /* and 2.5 x the highest mesh contact frequency */
#define GD_TR_CONDENSE_DENSE_MAX 3000
typedef struct gd_tr_condensed {
    gd_condensation *c;
    gd_condense_info info;
    int ns, nc;
    int *dof;                    /* nc: system DOF of each coordinate */
    const double *A, *B, *C, *G; /* the condensation's (ns x ns, ns x nc, nc x ns, nc x nc) */
    double *CA, *CB;             /* nc x ns, nc x nc */
    double *dK, *dD;             /* nc x nc: K_L, C_L of the model's laws at S */
    double *u;                   /* nc: the coordinate forces of the last evaluation */
    double *Fq, *Fv, *L;         /* nc x nc: the forces' tangent, the loop matrix (LU) */
    int *lpiv;
    int loop, lok, have_tangent;
    int *modes;                  /* nlaw: the laws' modes the tangent was taken in */
    double *D;                   /* nc x ns: du/dx */
    SUNMatrix Jm;                /* ns x ns: CVODE's dense Jacobian (gd_tr_condensed_solver) */
    double rtol, atol_q, atol_v; /* the run's tolerances (gd_tr_condensed_ewt) */
    double *yscale;              /* 2 nc: the coordinates' largest |C x|, |C A x| so far */
    double *ewt;                 /* ns: the error weights at those scales */
    double *CCA;                 /* 2 nc x ns: [C; C A] */
    double *xout, *yout;         /* the last state given to outputs() and its [C x; C A x] */
    int have_out;
    int have_ewt;
    int *partner; /* ns: the other state of each state's mode (itself if none) */
    int a_blocks; /* 1: A couples only partners (the modal basis) */
    double *work;
    double cutoff, w_exc, w_contact, est_rel;
    long loop_iters, setups;
} gd_tr_condensed;
void gd_tr_condensed_free(gd_tr_condensed *k);
void gd_tr_condensed_rhs(gd_transient *tr, double t, const double *x, double *xdot);
/* q, v (length n) at (t, x): every DOF when all, else only the coordinates' DOFs. */
void gd_tr_condensed_fill(gd_transient *tr, double t, const double *x, double *q, double *v,
                          int all);
/* CVODE's Jacobian of the condensed model (user data: the gd_transient): A + B du/dx. */
int gd_tr_condensed_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix Jac, void *ud,
                        N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);
/* SUNDIALS' dense direct solver on the condensed state, its matrix held by tr->cond until
 * gd_tr_condensed_solver_free (before the context is freed). NULL: out of memory. */
SUNLinearSolver gd_tr_condensed_solver(gd_transient *tr, N_Vector y, SUNContext ctx);
void gd_tr_condensed_solver_free(gd_transient *tr);
void gd_tr_condensed_atol(const gd_transient *tr, double atol_q, double atol_v, double *atol);
/* Before a run: its tolerances for the error weights, their scales cleared. */
void gd_tr_condensed_tolerances(gd_transient *tr, double rtol, double atol_q, double atol_v);
/* CVODE's error-weight function of the condensed state (user data: the gd_transient). */
int gd_tr_condensed_ewt(N_Vector y, N_Vector ewt, void *ud);
/* Before a run: the loop's start and the cached tangent cleared. */
void gd_tr_condensed_reset(gd_transient *tr);

struct gd_transient {
    const gd_system *sys;
    int n, nf, np;
    int *fidx;     /* n: free index of each DOF, -1 if prescribed */
    int *free_dof; /* nf */
    gd_tr_prescribed *pres;
    double speed;
    double *rate;        /* n: nominal speed of each DOF (ratio W for rz, else 0) */
    cs *K, *D, *M;       /* full, at the speed */
    cs *Mff, *Kff, *Dff; /* free blocks */
    css *Msym;
    csn *Mnum; /* Cholesky of M_ff */
    cs *S;     /* preconditioner M_ff + g D_ff + g^2 K_ff */
    int *mapM, *mapD, *mapK;
    css *Ssym;
    csn *Snum;
    double gamma;
    int nmodel_mesh;
    int nall_mesh;           /* with the planetary sets' meshes (gd_model_mesh_count) */
    gd_mesh_vector *model_a; /* every model mesh, for records */
    int *nl_of_mesh;         /* model mesh -> index in law[] (its mesh law), or -1 */
    /* the laws of the registry (gd_transient_spec_laws): the spec's meshes
     * (gd_law_backlash_mesh), its dampers, its loads, spec.laws, then its cams
     * (gd_law_cam_torque); dofs are the problem's (remapped by a reduction) */
    int nlaw;
    gd_law *law;
    /* nlaw: each law's own time, borrowed (multi-frequency harmonic balance,
     * src/periodic/multifreq: a law read at the phase of its base frequency on the torus);
     * NULL, the default: every law at the problem's t */
    const double *law_time;
    int nmesh;     /* law[0 .. nmesh - 1]: the spec's meshes (contact statistics) */
    int nsfd_law;  /* law[nmesh .. nmesh + nsfd_law - 1]: the spec's dampers (GD_REC_SFD_*) */
    int law_spec0; /* law[law_spec0 + i]: spec.laws[i] (GD_REC_LAW) */
    /* law_order[0 .. nlaw_plain - 1]: the laws without an assembled part, then those with
     * one (GD_LAW_ASSEMBLED: the meshes), in law order: the right-hand side's two passes */
    int *law_order;
    int nlaw_plain;
    double lq[GD_LAW_MAX_DOFS], lv[GD_LAW_MAX_DOFS], lf[GD_LAW_MAX_DOFS]; /* workspaces */
    int nunb;
    tr_unb *unb;
    /* the laws' configuration-dependent inertias (GD_LAW_INERTIA, gd_law_type.inertia):
     * nin distinct free DOFs; the right-hand side solves (M_ff + E diag(mu) E^T) q'' = r
     * by the Woodbury identity */
    int nin;
    int *in_free; /* nin: free index */
    int *in_slot; /* nlaw x GD_LAW_MAX_DOFS: slot of each local DOF of an inertia law (-1: a
                     prescribed or absent DOF); NULL without inertia laws */
    int *in_code; /* nlaw: 0 a law without inertia, else 2 + the slot of its local DOF 0
                     (1: DOF 0 prescribed or absent); NULL without inertia laws */
    double *Z;    /* nf x nin: M_ff^-1 e_j */
    double *G;    /* nin x nin: E^T Z */
    double *mu, *A, *wv;
    int nroot; /* the laws' switches (gd_law_nswitches), in law order */
    /* workspaces (n each) */
    double *q, *v, *acc, *r, *w1, *w2;
    char msg[256];         /* last solver message */
    void *mono;            /* gd_transient_monodromy's workspace while it runs */
    gd_tr_reduction *red;  /* NULL: the physical DOFs */
    gd_tr_condensed *cond; /* NULL: not condensed (condensed.c) */
    /* its operations, set by condensed.c (through pointers: rhs.c and problem.c do not
     * depend on condensed.c, which uses their forces and problem) */
    void (*cond_fill)(gd_transient *tr, double t, const double *x, double *q, double *v, int all);
    void (*cond_rhs)(gd_transient *tr, double t, const double *x, double *xdot);
    void (*cond_free)(gd_tr_condensed *k);
    int nterm; /* local force terms (local_forces.c), built on first use; -1 unsupported */
    gd_tr_term *term;
    /* run-up (speed_profile.c): the profile while a run uses it, else NULL */
    const gd_speed_profile *prof;
    double *prof_cum;  /* a table's speed integral at its rows */
    int prof_sign;     /* sense of the profile's speeds */
    double *ratio;     /* n: speed ratio of each rz DOF's shaft (0 other DOFs) */
    int nunb_all;      /* unbalances on a turning shaft (nunb: 0 at speed 0) */
    cs *Gy;            /* gyroscopic matrix per unit reference speed (full DOFs) */
    double *law_ratio; /* nlaw x (GD_LAW_MAX_DOFS + 2): ratios of the laws' rates, spins */
    /* a run-up with speed-table bearings: K(W_j) - K(W), C(W_j) - C(W) at nsd speeds
     * W_j evenly over the profile's range (interpolated linearly at W(t)) */
    int nsd;
    double sd_w0, sd_dw;
    cs **sd_K, **sd_C;
};

/* ---- speed_profile.c ---- */
/* Uses profile p (NULL: none) for the next run: its table's integral at the rows. 0 ok,
 * 1 out of memory. */
/* A cs view of a gd_csc (no copy: valid while a is). */
cs gd_tr_cs_view(const gd_csc *a);
int gd_tr_profile_set(gd_transient *tr, const gd_speed_profile *p);
/* The profile's angle, speed and acceleration at t (from cum when not NULL). */
void gd_tr_profile_eval(const gd_speed_profile *p, const double *cum, double t, double *angle,
                        double *speed, double *accel);
/* Speed-table bearings of a run-up: the differences of K and C from the reference speed
 * at GD_TR_SD_SPEEDS speeds over the profile's range (none without speed tables); freed
 * by gd_tr_profile_set(tr, NULL). 0 ok, 1 out of memory or a matrix failure. */
#define GD_TR_SD_SPEEDS 65
int gd_tr_profile_bearings(gd_transient *tr);
/* r -= (K(W) - K(W_ref)) q + (C(W) - C(W_ref)) v, interpolated at speed W. */
void gd_tr_profile_bearing_forces(const gd_transient *tr, double w, const double *q,
                                  const double *v, double *r);
/* The laws' rates (rate t = ratio phi) and spins (ratio W) at t of a run-up. */
void gd_tr_profile_laws(gd_transient *tr, double t, double phi, double w);

/* Fills q, v, acc (length n) at time t from the state y: free DOFs from y, prescribed
 * ones from their laws (acc is zero on free DOFs). */
void gd_tr_fill(gd_transient *tr, double t, const double *y, double *q, double *v, double *acc);
/* The static initial state at t into y (2 nf: q, then q' = 0), static_start.c; a train
 * free in torsion starts from its state under inertia relief; a model whose laws carry
 * the static load (bearings) from the static analysis's equilibrium under the run's loads
 * at t, with its holds (or its located error). */
gd_status gd_tr_static_state(gd_transient *tr, double t, double *y, gd_error *err);
/* Law L's local view of (t, q, v) (full DOF vectors) in lq, lv (length L->ndofs). */
/* The time law i is read at: its own (law_time) or the problem's t. */
static inline double gd_tr_law_t(const gd_transient *tr, int i, double t)
{
    return tr->law_time ? tr->law_time[i] : t;
}
void gd_tr_law_point(const gd_law *L, double t, const double *q, const double *v, double *lq,
                     double *lv, gd_law_point *x);
/* record_value.c: value of a record at (t, q, v) (full DOF vectors) with the current
 * contact states. */
double gd_tr_record_value(gd_transient *tr, const gd_tr_record *rec, double t, const double *q,
                          const double *v);
/* Net generalised force r (length n) at (t, q, v, acc) with the current contact states,
 * without the inertia of the free DOFs; tr->mu receives the laws' inertias on the free
 * DOFs (GD_LAW_INERTIA), the prescribed DOFs' get -m q'' in r. */
void gd_tr_residual(gd_transient *tr, double t, const double *q, const double *v, const double *acc,
                    double *r);
/* gd_tr_residual without the free-free linear part K_ff q_f + D_ff q_f' when
 * skip_free_linear (the local form: what the frequency domain does not already hold). */
void gd_tr_forces(gd_transient *tr, double t, const double *q, const double *v, const double *acc,
                  double *r, int skip_free_linear);
/* x = M_ff^-1 b (b, x of length nf; b is overwritten). */
void gd_tr_mass_solve(gd_transient *tr, double *b, double *x);
/* Root functions: every law's switches (gd_law_type.switches), in law order. */
void gd_tr_roots(gd_transient *tr, double t, const double *y, double *g);
/* With tr->q, tr->v filled at t: the mode of law L when its switches are clearly past
 * (two crossings in one step the root-finding missed), else its current mode. */
int gd_tr_missed_mode(gd_transient *tr, const gd_law *L, double t);
/* Law L's local view of (t, tr->q, tr->v), in tr->lq, tr->lv. */
void gd_tr_law_here(gd_transient *tr, const gd_law *L, double t, gd_law_point *x);
/* Preconditioner set-up (sparse LU of M + g D + g^2 K) and solve. 0 ok. */
int gd_tr_prec_setup(gd_transient *tr, double gamma);
void gd_tr_prec_solve(gd_transient *tr, const double *r, double *z);

/* ---- problem.c ---- */
gd_status gd_tr_linear_setup(gd_transient *tr, gd_error *err);
/* Dense column-major n x n to compressed columns, exact zeros dropped (NULL: no memory). */
cs *gd_tr_cs_from_dense(int n, const double *A);
/* Block A(rows, cols) as a new nr x nc matrix; rmap, cmap: index in A -> index in the
 * block, or -1 (NULL: no memory). */
cs *gd_tr_cs_block(const cs *A, const int *rmap, const int *cmap, int nr, int nc);

/* Frees M, K, D, the free blocks, the mass factor and the preconditioner pattern. */
void gd_tr_release_linear(gd_transient *tr);

/* ---- reduce.c ---- */
void gd_tr_reduction_free(gd_tr_reduction *r);
/* Physical DOF i (of the system) from the problem's coordinates x. */
double gd_tr_full_value(const gd_transient *tr, int i, const double *x);
double gd_tr_full_rate(const gd_transient *tr, int i);
/* x (nr) from a physical state (nfull): kept DOFs as they are, modal amplitudes by
 * M-orthogonal projection of the interior motion not explained by them. */
void gd_tr_project(const gd_transient *tr, const double *full, double *x);

/* ---- contact_stats.c: contact statistics, shared by the integrators ---- */
typedef struct gd_tr_contact_track {
    double since; /* time of the last state change */
} gd_tr_contact_track;
/* Adds [t0, t1], clipped to t >= from, to the time spent in contact state `state`. */
void gd_tr_contact_account(gd_tr_contact_stats *cs_, gd_contact state, double t0, double t1,
                           double from);
/* Law i changes to mode ns at time t: a mesh law's (i < nmesh) contact statistics over
 * [from, t_end] and its entry in res's contact-event log (its approach speed from the
 * state in tr->q, tr->v, which the caller has filled at t). */
void gd_tr_change_state(gd_transient *tr, int i, gd_contact ns, double t, double from,
                        gd_transient_result *res, gd_tr_contact_track *track);

/* ---- gen_alpha.c ---- */
/* Integrates from opt->t_start with the state y = [q_f; q_f'] (updated to the last
 * sample) and fills res's samples t, values and counters; from, dt: the sampling. */
gd_status gd_tr_run_gen_alpha(gd_transient *tr, const gd_transient_options *opt,
                              const gd_tr_record *records, int nrecords, double from, double dt,
                              double *y, gd_transient_result *res, gd_tr_contact_track *track,
                              gd_error *err);

/* ---- run.c ---- */
/* gd_transient_run without the global error estimate of the CVODE methods
 * (global_error.c wraps it with that estimate). */
gd_status gd_tr_run_once(gd_transient *tr, const gd_transient_options *opt,
                         const gd_tr_record *records, int nrecords, gd_transient_result **out,
                         gd_error *err);

/* ---- linear.c ---- */
/* Degree m of the (m, m) Pade approximant the linear method advances the free motion by
 * (src/transient/linear.c). */
#define GD_TR_LTI_PADE 8
/* 1 when the problem is linear and time-invariant, forced by unbalances only (GD_TR_LTI
 * applies); else 0. why (len) receives the reason either way. */
int gd_tr_lti_reason(const gd_transient *tr, char *why, size_t len);
/* GD_TR_LTI from the state y (updated to the end) into res's samples, step and
 * error_estimate; as gd_tr_run_gen_alpha. */
gd_status gd_tr_run_lti(gd_transient *tr, const gd_transient_options *opt,
                        const gd_tr_record *records, int nrecords, double from, double dt,
                        double *y, gd_transient_result *res, gd_error *err);

/* CVODE for the problem (user data ud): method, tolerances (rtol, vector atol), step
 * limits and stop time from opt, SPGMR with left preconditioning by psetup/psolve (or,
 * on a condensed problem with psetup NULL, the dense solver with its Jacobian), and
 * nroot root functions (0: none). *flag != 0 or NULL on failure; the caller frees the
 * memory and *LS. Messages go to tr->msg. */
void *gd_tr_cvode_new(SUNContext ctx, const gd_transient_options *opt, double t0, double t_stop,
                      N_Vector y, N_Vector atol, CVRhsFn rhs, CVRootFn root, int nroot,
                      CVLsPrecSetupFn psetup, CVLsPrecSolveFn psolve, void *ud, gd_transient *tr,
                      SUNLinearSolver *LS, int *flag);
/* CVODE preconditioner set-up of the problem (user data: the gd_transient). */
int gd_tr_cv_psetup(sunrealtype t, N_Vector y, N_Vector fy, sunbooleantype jok,
                    sunbooleantype *jcur, sunrealtype gamma, void *ud);
/* CVODE preconditioner solve (user data: the gd_transient): the problem's preconditioner
 * on every block of 2 nf of the vector (one for a run; 1 + 2 nf for the monodromy). */
int gd_tr_cv_psolve(sunrealtype t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z,
                    sunrealtype gamma, sunrealtype delta, int lr, void *ud);
/* CVODE error handler writing to the problem's msg (user data: the gd_transient). */
void gd_tr_cv_err(int code, const char *module, const char *function, char *msg, void *ud);

#endif
