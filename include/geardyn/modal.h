/* Modal analysis: undamped modes (symmetric generalized eigenproblem) and damped,
 * gyroscopic modes at a speed (state space with right and left eigenvectors,
 * bi-orthonormalised as in [MMT2018] Eqs. 9-13).
 *
 * Ownership and threads: gd_modal_solve and gd_modal_solve_sparse return a result the
 * caller frees with gd_modal_free (modes, shapes, left vectors and energy shares are
 * owned by it). The system is only read: several solves may run concurrently on one
 * system.
 */
#ifndef GEARDYN_MODAL_H
#define GEARDYN_MODAL_H
#include "geardyn/export.h"
#include "geardyn/system.h"

/* A mode with less than this fraction of its strain energy in lateral and tilt motion
 * has whirl GD_WHIRL_NONE (a torsional or axial mode, whatever its small orbits do). */
#define GD_WHIRL_MIN_LATERAL 0.05

typedef enum gd_whirl {
    GD_WHIRL_NONE,     /* no lateral orbit, straight-line orbits, or a mode with less than
                          GD_WHIRL_MIN_LATERAL of lateral and tilt strain energy */
    GD_WHIRL_FORWARD,  /* every orbit turns with its shaft */
    GD_WHIRL_BACKWARD, /* every orbit turns against its shaft */
    GD_WHIRL_MIXED
} gd_whirl;
GD_API extern const char *const gd_whirl_names[4];

typedef enum gd_modal_kind {
    GD_MODAL_AUTO,     /* damped if the model has damping or gyroscopics at speed */
    GD_MODAL_UNDAMPED, /* drop damping and gyroscopic terms */
    GD_MODAL_DAMPED
} gd_modal_kind;

/* Which eigensolver computes the modes. AUTO takes the sparse one when the measured
 * cost model (src/modal/method_cost.c) says it is cheaper for this model and number of
 * modes; the sparse solver gives the lowest modes only (nmodes > 0), right vectors only,
 * and needs mass on every DOF, so AUTO is dense otherwise. */
typedef enum gd_eig_method {
    GD_EIG_AUTO,
    GD_EIG_DENSE, /* LAPACK on the dense problem (all modes, left vectors, condensation) */
    GD_EIG_SPARSE /* shift-invert Krylov-Schur with KLU (gd_modal_solve_sparse) */
} gd_eig_method;

/* The sparse solver's default precision (gd_modal_options.tol = 0): the relative
 * residual of each eigenpair (gd_mode.residual) */
#define GD_MODAL_TOL_DEFAULT 1e-9

typedef struct gd_modal_options {
    double speed; /* reference speed, rad/s */
    int nmodes;   /* lowest modes kept; 0: all */
    gd_modal_kind kind;
    int want_left;        /* compute bi-orthonormal left eigenvectors (damped) */
    gd_eig_method method; /* default AUTO */
    /* The sparse solver iterates until every elastic mode's relative residual
     * (gd_mode.residual) is at most tol, or no longer falls (it has reached
     * residual_floor, the rounding of the model's matrices); 0: GD_MODAL_TOL_DEFAULT.
     * The dense solver (LAPACK) is accurate to rounding and ignores it. */
    double tol;
    /* The state (ndof, borrowed) the system's laws are linearised about at speed; NULL
     * (the default): the operating point solved at speed (gd_system_law_state). A
     * Campbell sweep hands each speed the state it continued from the previous one. */
    const double *law_state;
} gd_modal_options;

typedef struct gd_mode {
    double lambda_re, lambda_im; /* eigenvalue; undamped: (0, omega) */
    double omega_n;              /* natural frequency |lambda|, rad/s */
    double omega_d;              /* damped frequency Im(lambda), rad/s */
    double frequency_hz;         /* omega_n / 2 pi */
    double damping_ratio;        /* -Re(lambda)/|lambda| */
    double log_decrement;        /* 2 pi zeta / sqrt(1 - zeta^2); NAN when overdamped */
    int rigid_body;              /* zero frequency: free motion */
    int overdamped;              /* real eigenvalue */
    int unstable;                /* growing (Re lambda > 0) or negative stiffness */
    gd_whirl whirl;
    double energy_share[GD_NMOTIONS]; /* fractions of modal strain energy */
    gd_motion dominant_motion;
    int dominant_component; /* gd_system component index; -1 for rigid modes and when no
                               component holds strain energy */
    /* Relative residual of the eigenpair (lambda, u) of P(lambda) = lambda^2 M +
     * lambda D + K (D = C + W G; 0 for undamped modes), of every solver:
     *   |P(lambda) u| / (|lambda|^2 |M u| + |lambda| |D u| + |K u|)   (2-norms),
     * about the relative error of the frequency for a well-separated mode (an exact u:
     * exactly |d omega| / omega). A rigid-body mode: |K u| / | |K| |u| |. */
    double residual;
    /* What rounding alone leaves in that residual: eps times the terms that cancel,
     * (|lambda|^2 | |M||u| | + |lambda| | |D||u| | + | |K||u| |) / the denominator above.
     * Large on fine meshes, whose element stiffnesses dwarf a low mode's (about eps
     * (element frequency / mode frequency)^2): no solver gets a residual far below it. */
    double residual_floor;
} gd_mode;

typedef struct gd_modal_result {
    int ndof, nmodes, ncomponents;
    int damped;
    int sparse; /* computed by the sparse (shift-invert) solver */
    double speed;
    gd_mode *modes;              /* ascending natural frequency */
    double *shape_re, *shape_im; /* ndof x nmodes, column-major; largest entry = 1 */
    double *left_re, *left_im;   /* NULL unless requested: v^T (2 lambda M + D) u = 1 */
    double *energy_by_component; /* ncomponents x nmodes, column-major: fractions */
} gd_modal_result;

GD_API void gd_modal_options_init(gd_modal_options *opt);
GD_API gd_status gd_modal_solve(const gd_system *sys, const gd_modal_options *opt,
                                gd_modal_result **out, gd_error *err);
GD_API void gd_modal_free(gd_modal_result *res);
/* Directional modes ([Kumar2011], complex variable approach): the eigenvalues of the
 * equation of motion written for p = x + i y and pbar = x - i y at every node, one per
 * physical mode, signed by its whirl: Im lambda > 0 forward, < 0 backward (about each
 * shaft's own sense of rotation). |lambda| and |Im lambda| equal a damped mode of
 * gd_modal_solve. opt: speed, kind (GD_MODAL_UNDAMPED drops D = C + W G; otherwise it is
 * kept) and nmodes (lowest |lambda|; 0 all). Rigid-body roots are left out. */
typedef struct gd_directional_mode {
    double lambda_re, lambda_im; /* Im > 0: forward whirl at Im; Im < 0: backward */
    double forward_fraction;     /* |p|^2 / (|p|^2 + |pbar|^2) over the lateral DOFs; NAN
                                    with no lateral motion */
    gd_whirl whirl;              /* forward, backward, or none (straight-line orbits or
                                    no lateral motion: then Im >= 0) */
} gd_directional_mode;
typedef struct gd_directional_result {
    int nmodes;
    double speed;
    gd_directional_mode *modes; /* ascending |lambda| */
} gd_directional_result;
GD_API gd_status gd_modal_directional(const gd_system *sys, const gd_modal_options *opt,
                                      gd_directional_result **out, gd_error *err);
GD_API void gd_directional_free(gd_directional_result *res);

/* Strain energy of mode `mode` of r (solved on sys) per shaft and motion type, [JMSTHelical]
 * Tables 4-7: table[s * GD_NMOTIONS + k] (model->nshafts x GD_NMOTIONS, filled by the
 * caller's array) is the fraction of the mode's strain energy in shaft s (its elements,
 * and the bearings, springs and meshes at its nodes, half of one between two shafts)
 * and motion type k; the fractions sum to 1 (all 0 for a rigid-body mode). A shaft's
 * share is its row's sum (Table 4); its row over that sum is Table 7. */
GD_API gd_status gd_modal_energy_by_shaft(const gd_system *sys, const gd_modal_result *r, int mode,
                                          double *table, gd_error *err);

/* Lowest opt->nmodes (> 0) modes by shift-invert Krylov-Schur on the sparse
 * first-order system, real shift sigma = -shift (rad/s; <= 0: automatic). Same result
 * layout as gd_modal_solve, right vectors only (left_re/left_im are NULL). Needs mass
 * on every DOF (sys->nmassless == 0); otherwise GD_EINPUT: use gd_modal_solve. */
GD_API gd_status gd_modal_solve_sparse(const gd_system *sys, const gd_modal_options *opt,
                                       double shift, gd_modal_result **out, gd_error *err);

/* What the dense (LAPACK) solver would cost on sys, damped (state space, 2 ndof) or not
 * (the symmetric problem): *seconds by the measured cost model `--method auto` chooses
 * with, *bytes its peak memory (the n x n matrices and the dense eigenproblem's work
 * arrays). Either pointer may be NULL. For a hint that names what is reachable. */
GD_API void gd_modal_dense_cost(const gd_system *sys, int damped, double *seconds, double *bytes);

/* The class of planetary set `set`'s motion in mode `mode` of r (solved on sys),
 * [LinParker1999] Sec. 4 (docs/planetary.md): rotational (the central members rotate and do
 * not translate, all planets move alike), translational (the central members translate and
 * do not rotate), planet (the central members still), mixed (none of these: unequally spaced
 * planets, or a set coupled to other shafts), or none (the set does not move in the mode). */
typedef enum gd_planetary_class {
    GD_PCLASS_NONE,
    GD_PCLASS_ROTATIONAL,
    GD_PCLASS_TRANSLATIONAL,
    GD_PCLASS_PLANET,
    GD_PCLASS_MIXED,
    GD_PCLASS_COUNT
} gd_planetary_class;
/* "-", "rotational", "translational", "planet", "mixed" */
GD_API extern const char *const gd_planetary_class_names[GD_PCLASS_COUNT];
GD_API gd_planetary_class gd_modal_planetary_class(const gd_system *sys, const gd_modal_result *r,
                                                   int mode, int set);
/* The load of planetary set `set`'s sun-planet meshes (ring 0) or ring-planet meshes (ring 1)
 * at mesh harmonic `harmonic`, per unit static transmission error amplitude, with each
 * planet's mesh phase gamma_n (gd_planetary_mesh_phase, [ParkerLin2004]: frac(Z_s psi_n /
 * 2 pi) for the sun meshes; docs/planetary.md): the complex amplitude F = sum_n k a_n
 * exp(-2 pi i harmonic gamma_n) over the system's DOFs (re, im: ndof, the caller's). With equally
 * spaced planets it excites only rotational modes when harmonic Z_s / N is whole, only
 * translational ones when (harmonic Z_s +- 1) / N is, and otherwise only planet modes. GD_EINPUT
 * without teeth. */
GD_API gd_status gd_planetary_mesh_excitation(const gd_system *sys, int set, int harmonic, int ring,
                                              double *re, double *im, gd_error *err);

#endif
