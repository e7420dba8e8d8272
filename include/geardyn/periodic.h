/* Periodic steady state by harmonic balance (docs/periodic.md): the response of the
 * transient problem (transient.h: every nonlinear and time-varying law, evaluated by the
 * integrator's own code through gd_transient_local) as a truncated Fourier series
 *
 *   q(t) = Q_0 + sum_{k=1..H} Q_ck cos(k w t) + Q_sk sin(k w t),   w = w_0 / N,
 *
 * w_0 the fundamental frequency of the model's excitations (shaft speeds through the gear
 * ratios, tooth-mesh frequencies, fixed-frequency loads) and N the subharmonic order.
 * The nonlinear forces' Fourier coefficients and their Jacobian come from the
 * alternating frequency-time scheme (FFTW half-complex transforms over the samples of
 * one period); Newton's linear systems are factored sparsely with KLU, the symbolic
 * analysis once per branch (and harmonic count). Continuation: pseudo-arclength in the
 * reference speed or in a model parameter (a `--set` path, the model rebuilt per value),
 * with step control, through folds. Stability: Floquet multipliers, the eigenvalues of
 * the monodromy matrix of the variational equations linearised about the HB solution
 * (fourth-order Magnus steps, exact for constant coefficients), and bifurcations located
 * along the branch (fold, period doubling, Neimark-Sacker, branch point).
 *
 * Ownership and threads: gd_periodic_run returns a result the caller frees with
 * gd_periodic_result_free; the system, spec and records are borrowed for the call. A run
 * allocates its own problems and workspaces, so separate runs may go in parallel on one
 * system (never with a transient run on a shared gd_transient: none is shared).
 */
#ifndef GEARDYN_PERIODIC_H
#define GEARDYN_PERIODIC_H
#include "geardyn/export.h"
#include "geardyn/error.h"
#include "geardyn/system.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"

typedef enum gd_per_method {
    GD_PER_ARCLENGTH = 0, /* pseudo-arclength: follows folds, reports every crossing of a
                             requested speed (several on a hysteresis loop) */
    GD_PER_SEQUENTIAL = 1 /* natural parameter: one solution per speed, each from the last
                             (a run-up; jumps at folds) */
} gd_per_method;

/* How the orbit is found (docs/periodic.md): harmonic balance (the library's default),
 * shooting (Newton on the period map of transient's integrator, continued as `method`
 * says; every law transient has, cams with include_acceleration included), or auto (the
 * CLI's default): shooting where a law is not smooth, else the cheaper of the two by a
 * cost counted from the model's sizes (gd_periodic_choose); a requested point the chosen
 * method fails is handed to the other, solved there alone, and says so
 * (gd_periodic_point.method, reason). */
/* GD_PER_MULTIFREQ: multi-frequency (quasi-periodic) harmonic balance, one base frequency
 * per independent mesh group, the response a Fourier series on their torus (docs/
 * periodic.md, "Several base frequencies"): a train whose meshes' frequencies have a long
 * common period (co-prime tooth counts) without the harmonics of that period; speed
 * continuation (natural), no Floquet multipliers (the response has no period). */
/* GD_PER_REDUCED_SHOOTING: for a model whose laws are linear in the state at fixed time
 * (gear meshes without backlash: TVMS, STE; constant loads), the orbit of the problem
 * linearised at its static state by one Magnus sweep in a reduced basis (the modes below
 * 30 kHz and the laws' residual flexibility): x0 = (I - Phi)^-1 p, no harmonic truncation,
 * each point at S and 2 S steps (the change is its error column), the multipliers of the
 * same monodromy; natural continuation; GD_EINPUT naming the law on other models
 * (docs/periodic.md, "Reduced shooting"). */
typedef enum gd_per_kind {
    GD_PER_HB = 0,
    GD_PER_SHOOTING = 1,
    GD_PER_AUTO = 2,
    GD_PER_MULTIFREQ = 3,
    GD_PER_REDUCED_SHOOTING = 4
} gd_per_kind;
/* The Floquet multipliers of harmonic balance points (gd_periodic_options.floquet). */
enum { GD_FLOQUET_AUTO = 0, GD_FLOQUET_DENSE = 1, GD_FLOQUET_KRYLOV = 2, GD_FLOQUET_REDUCED = 3 };
GD_API const char *gd_per_kind_name(gd_per_kind k);

struct gd_periodic_point;
/* The largest AFT sample count and Magnus step count per period (2^20): each sample
 * holds the state and forces of every free DOF, so 2^31 samples would ask for about
 * 100 GB; 2^20 resolves 500000 harmonics, far past the 1000 allowed. */
#define GD_PERIODIC_MAX_SAMPLES (1 << 20)

typedef struct gd_periodic_options {
    int harmonics;         /* H >= 1 (default 10) */
    int adaptive;          /* 1: H from the least that holds every excitation's fundamental,
                              doubled at each point until the records agree with those at
                              twice H to harmonic_tol (the point reports the finer solution) */
    double harmonic_tol;   /* truncation tolerance: the relative change of every record's
                              peak-to-peak and of its harmonic amplitudes (relative to its
                              largest) between H and 2 H (default 0.01) */
    int max_harmonics;     /* cap of H (0, default: the largest whose workspace fits in
                              memory_limit) */
    int subharmonic;       /* N >= 1: solutions of period N T_0 (default 1) */
    int samples;           /* AFT samples per period; 0: 4 (H + 1) rounded up to 2^k,
                              at least 16; at most GD_PERIODIC_MAX_SAMPLES */
    double tol;            /* Newton: relative residual (default 1e-10) */
    int max_iter;          /* Newton iterations per point (default 30) */
    int stability;         /* 1 (default): Floquet multipliers and bifurcations */
    int monodromy_steps;   /* Magnus steps per period; 0: 4 x samples, at least 256 (the
                              reduced basis: its own count, 8 per period of the top
                              excitation order doubled until two counts agree, at most
                              131072); at most GD_PERIODIC_MAX_SAMPLES */
    int floquet;           /* how the multipliers are found (docs/periodic.md, "Stability at
                              scale"): GD_FLOQUET_AUTO (default: dense up to floquet_dmax
                              states and floquet_budget, reduced else), GD_FLOQUET_DENSE (every
                              multiplier, the dense 2 nf x 2 nf monodromy), GD_FLOQUET_KRYLOV (the
                              floquet_count largest by Krylov-Schur on monodromy-vector
                              products over the same Magnus steps; no dense matrix),
                              GD_FLOQUET_REDUCED (the monodromy in a reduced basis: the
                              modes below floquet_cutoff and the residual flexibility along
                              the local laws' directions; the discarded modes' multipliers
                              estimated one by one; where its eigenvector basis is
                              ill-conditioned, as with a free rotation, dense up to
                              floquet_dmax states and Krylov above) */
    int floquet_count;     /* Krylov: multipliers wanted (0: 8); doubled while all but one of
                              them lie outside the unit circle, so the count outside and the
                              next one in (which the bifurcations are located by) are known */
    int floquet_dmax;      /* auto: the dense monodromy up to this many states 2 nf (0: 300,
                              from the measured costs, docs/periodic.md) */
    double floquet_budget; /* seconds for one point's multipliers (0, the library default:
                              no limit; the CLI's is 30), of counted work: operations counted
                              from the sizes (the Magnus steps' dense products, the Krylov
                              products' sparse actions, the reduced basis's set-up and steps)
                              at a nominal 2 GFlop/s, never a clock, so the same run decides
                              the same way on any machine; a point whose multipliers would
                              take longer keeps its orbit with stability not computed, and
                              its reason says how long they would take */
    double floquet_cutoff; /* reduced: the modes kept, up to this multiple of the highest
                              excitation frequency (the top of gd_periodic_fundamental's
                              orders, e.g. the highest tooth-mesh frequency; 0: 4, from the
                              measured convergence, docs/periodic.md) */
    gd_per_method method;
    gd_per_kind kind;    /* GD_PER_HB (default), GD_PER_SHOOTING or GD_PER_AUTO (shooting
                            by arclength: dense up to shoot_dense_max states, above it
                            matrix-free, GMRES on monodromy-vector products) */
    double shoot_rtol;   /* shooting: the integrator's relative tolerance (0: 1e-9); the
                            absolute ones are 1e-3 of it times the orbit's largest
                            displacement and velocity, and Newton stops at a scaled
                            |P(y) - y| of max(tol, 100 shoot_rtol) */
    int shoot_dense_max; /* shooting: the dense monodromy up to this many states (0: 64);
                            above, Newton-Krylov (GMRES on monodromy-vector products, one
                            integrated period each) and the largest multipliers by
                            Arnoldi */
    int shoot_stability; /* harmonic balance points' multipliers: 0 (the library's default)
                            from the Magnus monodromy about the truncated Fourier orbit; 1
                            where a law is not smooth (a switch or a kink) from the orbit
                            corrected by shooting (a few Newton steps on the period map from
                            the Fourier orbit's state, then its integrated monodromy: the
                            multipliers of a solution of the time-domain equations), and
                            at a reported point whose truncation estimate is not within
                            harmonic_tol on a model of up to shoot_dense_max states; which
                            GD_PER_AUTO takes; 2 always from the corrected orbit. A point
                            whose correction fails keeps the Magnus multipliers and its
                            reason says why (gd_periodic_point.stability_method) */
    double shoot_budget; /* shooting: seconds per point (0, default: no limit) of counted
                            work: the integrator's right-hand sides, counted, times their
                            counted flops at a nominal 2 GFlop/s (a monodromy: 0.7 (2 n + 1)
                            periods); a point whose next integration would pass it stops, not
                            converged, with what it saw (the warm start's change per period,
                            the residual) */
    int both_directions; /* 1: also the run from the end back to the start */
    int max_steps;       /* continuation steps per direction; 0: 50 x count + 200 */
    int solver;          /* Newton's linear solver: 0 automatic (low-rank for 2000+
                            unknowns whose nonlinear rank is a quarter or less), 1 sparse
                            LU of the whole coupled system (KLU), 2 low-rank: the linear
                            DOFs condensed onto the nonlinear laws (Woodbury), its
                            capacitance by dense LU below rank 1000 and by GMRES from it;
                            3 / 4: low-rank with the iterative / dense capacitance always
                            (docs/periodic.md, "Two linear solvers") */
    int estimate;        /* 1 (default): every converged point is solved again at 2 H and carries
                            the change of its records as its truncation error estimate (the
                            harmonic_error_* fields); 0: not (adaptive H always estimates) */
    double memory_limit; /* bytes for one harmonic balance workspace (0: half of the
                            physical memory); H beyond it is refused or not tried */
    int condensed;       /* harmonic balance on the laws' coordinates only (docs/periodic.md,
                            "Condensed harmonic balance"): 0 (default) wherever it applies
                            (every fixed-value solve of a model whose law coordinates are at
                            most a quarter of its free DOFs), its solution checked against
                            the full residual, a failure handed to the full Newton; 1
                            always (a point it cannot solve fails); -1 never */
    /* Called after every point is final (converged or not), in branch order, from the
     * calling thread: p the point (valid during the call only: the result's array grows),
     * index its place in the result, progress the share of the requested range (and
     * directions) covered so far, 0..1. May be NULL. */
    void (*on_point)(const struct gd_periodic_point *p, int index, double progress, void *user);
    /* Called after every accepted step of an arclength branch (harmonic balance or
     * shooting), from the calling thread, value the continued quantity there (rad/s for a
     * speed or a load frequency, else the parameter's own value): a long stretch between
     * requested points is then never silent. Steps are not points: nothing to store.
     * May be NULL. */
    void (*on_step)(double value, void *user);
    void *user;
} gd_periodic_options;
GD_API void gd_periodic_options_init(gd_periodic_options *opt);

/* Continuation in a model parameter instead of the speed. The analysis reads no files:
 * the caller's rebuild makes the problem at each value (the CLI loads the model file
 * with "PATH=VALUE" added to its overrides, model_file.h) and hands over a new model, its
 * system and its transient spec, which gd_periodic_run frees (gd_transient_model_free,
 * gd_system_free, gd_model_free). On failure rebuild returns the status with err filled
 * and hands over nothing. It is called from the thread of gd_periodic_run. */
typedef gd_status (*gd_periodic_rebuild)(double value, void *data, gd_model **model,
                                         gd_system **sys, gd_transient_model **tm, gd_error *err);
typedef struct gd_periodic_param {
    gd_periodic_rebuild rebuild;
    void *data;       /* passed to rebuild */
    const char *name; /* the parameter, for messages (e.g. "bearings.support_a.sfd.clearance") */
    double speed;     /* the fixed reference speed, rad/s */
    /* 1: the values are the frequency (rad/s) of the time-harmonic loads of the caller's
     * sys and spec (every GD_LOAD_HARMONIC_TIME load; several keep their ratios to the
     * first), at the fixed speed; rebuild and data are not used and no model is rebuilt */
    int load_frequency;
} gd_periodic_param;

typedef struct gd_per_record_stats {
    double mean, rms, peak_to_peak;
    double *amplitude, *phase_deg; /* H + 1 each: harmonic k of w (k = 0: mean, phase 0);
                                      x = sum_k A_k cos(k w t + phase_k) */
    /* truncation estimate (NaN when not estimated): |change| of the peak-to-peak between
     * the two harmonic counts compared, relative to it; the largest change of a harmonic
     * amplitude A_k (k >= 1), relative to the largest A_k */
    double p2p_error, amp_error;
} gd_per_record_stats;

typedef struct gd_periodic_point {
    double speed;     /* reference speed, rad/s */
    double parameter; /* continuation parameter value (NaN when continuing in speed) */
    int direction;    /* +1 from the start, -1 the return run (both_directions) */
    int converged;
    char reason[256]; /* why not converged, or why a converged point has no
                         multipliers (stable -1 with stability on) */
    int harmonics;    /* H used */
    double omega;     /* w, rad/s (period 2 pi / w) */
    double residual;  /* relative residual |R| / max(|L X|, |F|) */
    int iterations;
    int stable;    /* 1 stable, 0 unstable, -1 not computed */
    double mu_max; /* max |Floquet multiplier| (NaN if not computed) */
    int nmult;     /* 2 nfree, or the count found by Krylov (0 if not computed) */
    /* nmult multipliers (largest modulus first when found by Krylov) */
    double *mu_re, *mu_im;
    /* 1: the multipliers are the nmult largest by Krylov-Schur, 0: every one from the
     * dense monodromy (or none) */
    int floquet_krylov;
    /* > 0: the multipliers come from the monodromy in a reduced basis of that many vectors
     * (GD_FLOQUET_REDUCED): its 2 floquet_basis multipliers, then the discarded modes'
     * estimates while there is room, all largest first; 0 otherwise */
    int floquet_basis;
    /* the Magnus steps per period of the multipliers (0: none computed): monodromy_steps,
     * or the reduced method's own choice (docs/periodic.md, "Stability at scale") */
    int floquet_steps;
    int nfree;    /* coefficients: coef[h * nfree + i], h = 0 mean, 2k-1 cos k, 2k sin k */
    double *coef; /* over the free DOFs of gd_transient (increasing DOF order) */
    gd_per_record_stats *records; /* nrecords */
    /* harmonic truncation: the point at H compared with the solution at harmonics_ref
     * (2 H; with adaptive H the reported point is the finer one and harmonics_ref the
     * coarser); the largest p2p_error / amp_error over the records (with no records: the
     * change of the coefficients relative to their norm, in both); harmonic_ok 1 when
     * both are within harmonic_tol, 0 when not (the reason says so), -1 not estimated */
    int harmonics_ref;
    double harmonic_error_p2p, harmonic_error_amp;
    int harmonic_ok;
    /* how the orbit was found (GD_PER_HB or GD_PER_SHOOTING: with kind auto a point the
     * chosen method failed is handed to the other, and its reason says so) and how its
     * multipliers were (the monodromy of the variational equations about that orbit:
     * GD_PER_HB the Magnus monodromy about the truncated Fourier orbit, GD_PER_SHOOTING the
     * integrated monodromy of an orbit that solves the time-domain equations; -1 none) */
    gd_per_kind method;
    int stability_method;
} gd_periodic_point;

typedef enum gd_bifurcation_type {
    GD_BIF_FOLD = 0,
    GD_BIF_PERIOD_DOUBLING = 1,
    GD_BIF_NEIMARK_SACKER = 2,
    GD_BIF_BRANCH_POINT = 3
} gd_bifurcation_type;
GD_API const char *gd_bifurcation_name(gd_bifurcation_type t);

typedef struct gd_bifurcation {
    gd_bifurcation_type type;
    double speed, parameter; /* located value (parameter NaN when continuing in speed) */
    int direction;
    double mu_re, mu_im; /* the critical multiplier at the located point (fold: NaN) */
} gd_bifurcation;

typedef struct gd_periodic_result {
    int npoints;
    gd_periodic_point *points; /* one per crossing of a requested value, branch order */
    int nbifurcations;
    gd_bifurcation *bifurcations;
    int nrecords;
    int steps;          /* continuation steps taken */
    double cpu_seconds; /* of the whole run (reported only: nothing is decided by it) */
    gd_per_kind method; /* the method that ran (GD_PER_HB or GD_PER_SHOOTING) */
    /* with kind auto: why it was chosen, with the counted costs, and how many failed
     * points were handed to the other method ("" otherwise) */
    char method_note[256];
} gd_periodic_result;

/* Speeds: nvalues requested reference speeds (rad/s), in increasing or decreasing order;
 * the branch runs from values[0] to values[nvalues - 1]. param (may be NULL): continue in
 * that parameter over values instead (the speed is param->speed). Records are evaluated
 * over one period (GD_REC_ANGLE is not periodic: GD_EINPUT). sys and spec are the
 * problem for speed continuation (ignored with param). Errors: GD_EINPUT for bad options
 * or records, a model without excitations whose period is undefined only makes the
 * points' converged 0 with the reason. */
GD_API gd_status gd_periodic_run(const gd_system *sys, const gd_transient_spec *spec,
                                 const gd_periodic_param *param, const double *values, int nvalues,
                                 const gd_periodic_options *opt, const gd_tr_record *records,
                                 int nrecords, gd_periodic_result **out, gd_error *err);
GD_API void gd_periodic_result_free(gd_periodic_result *r);

/* Fundamental frequency w_0 (rad/s) of the problem's excitations at reference speed W:
 * the largest w_0 of which every excitation frequency is a whole multiple (at most 10000);
 * max_order (may be NULL) receives the highest multiple (an excitation harmonic balance
 * must resolve: H >= max_order x subharmonic).
 * GD_EINPUT with the reason when the period is undefined (no excitation, incommensurate
 * frequencies, a prescribed motion that is not periodic). */
/* Bytes of one harmonic balance workspace with H harmonics for the problem of sys and
 * spec at speed (an estimate, within a factor of about 2: the sample buffers, the
 * terms' harmonic couplings, the low-rank capacitance or the sparse LU's fill). */
GD_API double gd_periodic_memory(const gd_system *sys, const gd_transient_spec *spec, double speed,
                                 int H);

/* The method GD_PER_AUTO takes for the problem at speed (or param's first value):
 * shooting where harmonic balance cannot represent a law (cams with include_acceleration)
 * or where its workspace at an automatic H does not fit in memory_limit; else by a cost
 * counted, never clocked (the same decision on every run): one harmonic balance Newton
 * step at the first H (t_h: the FFTs, the laws at every sample, the harmonic couplings, the
 * block LU and the laws' dense capacitance, counted) and one period integrated from rest
 * at the shooting tolerance (t_p: its right-hand sides, counted by the integrator, times
 * their counted flops; stopped once shooting could no longer win); the estimates 8 t_h x (3
 * with the truncation estimate) plus the multipliers with stability, against 5 (2 n + 1)
 * t_p for dense shooting (n states) or 340 t_p for Newton-Krylov. Where a law is not smooth
 * (a switch: backlash, contact; a kink: a unilateral spring) shooting wins up to 20 times
 * harmonic balance's cost: its orbits solve the time-domain equations, so its multipliers
 * and bifurcations are those of the dynamics. Ties go to harmonic balance
 * (docs/periodic.md). note (may be NULL, 256 bytes) receives the reason with the numbers.
 * Reads no files; thread-safe on separate problems. */
GD_API gd_per_kind gd_periodic_choose(const gd_system *sys, const gd_transient_spec *spec,
                                      const gd_periodic_param *param, double value,
                                      const gd_periodic_options *opt, char *note);

GD_API gd_status gd_periodic_fundamental(const gd_system *sys, const gd_transient_spec *spec,
                                         double speed, double *w0, int *max_order, gd_error *err);

#endif
