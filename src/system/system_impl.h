/* Internals of the system module shared with the analyses: the dynamic stiffness
 * s^2 M + s D(W) + K(W) on one sparse pattern (dynamic_matrix.c). */
#ifndef GD_SYSTEM_IMPL_H
#define GD_SYSTEM_IMPL_H
#include "geardyn/system.h"
#include "linalg/linalg_impl.h"

/* ---- dynamic_matrix.c: M, C, G, K and the speed-dependent elements on one pattern ---- */
typedef struct gd_dyn_term {
    int instance; /* index in sys->instances of an element with GD_TERM_SPEED */
    int pos[GD_ELEMENT_MAX_DOFS * GD_ELEMENT_MAX_DOFS]; /* pattern position of local (i, j),
                                                          row-major, or -1 */
} gd_dyn_term;

typedef struct gd_dynmat {
    gd_pattern pat; /* the union pattern */
    double *m, *c, *g, *k;
    int ntab;
    gd_dyn_term *tab;
    int *law_pos; /* sys->law_block: pattern position of each law block entry, or -1 */
    const gd_system *sys;
} gd_dynmat;

gd_status gd_dynmat_build(const gd_system *sys, gd_dynmat *out, gd_error *err);
void gd_dynmat_free(gd_dynmat *a);
/* k += K_b(W), c += C_b(W): the speed-dependent terms on the pattern (either may be
 * NULL). */
void gd_dynmat_add_speed_terms(const gd_dynmat *a, double speed, double *k, double *c);
/* k = K + K_b(W) + K_laws(W), d = C + C_b(W) + W G + C_laws(W) on the pattern (nnz
 * each): the laws linearised about the static state at W (law_state.c). */
void gd_dynmat_at(const gd_dynmat *a, double speed, double *k, double *d);
/* The same with the laws linearised about state (ndof; NULL: solved at speed). */
void gd_dynmat_at_state(const gd_dynmat *a, double speed, const double *state, double *k,
                        double *d);

/* Factors the complex dynamic stiffness Z(w) = K - w^2 M + i w D (k, d from
 * gd_dynmat_at; z: 2 nnz scratch). Returns as gd_splu_factor. */
int gd_dynmat_factor_at(const gd_dynmat *a, const gd_splu_symbolic *s, const double *k,
                        const double *d, double w, double *z, gd_splu *lu);

/* ---- dense.c ---- */
/* gd_system_dense without the laws: M, C + C_b(W) + W G, K + K_b(W). */
void gd_system_dense_linear(const gd_system *sys, double speed, double *M, double *D, double *K);

/* ---- law_state.c: the laws of the registry in the linear analyses ---- */
/* sys->laws from the model's laws with a linearisation, made by gd_system_law_instance
 * (rates and spins per unit reference speed); every law's DOFs are checked there, the
 * ones without a linearisation too: a law on a direction that is not an active DOF is
 * its located error. */
gd_status gd_system_make_laws(gd_system *sys, gd_error *err);
/* f (ndof, zeroed here): the model's excitation loads at their mean (if loads) and
 * gravity on the masses (if gravity): the static analysis's mean load. */
void gd_system_mean_loads(const gd_system *sys, int loads, int gravity, double *f);
/* Newton with a backtracking line search for K q = f0 + sum f_law(q) (K dense ndof^2 at
 * reference speed W, the laws' velocities zero at t = 0) from q (in: the start, out: the
 * state), the held DOFs (held[i] != 0; held NULL: none) kept where they start. Returns 1
 * converged (residual <= 1e-10 of |f0| over the free DOFs), 0 not; *resnorm (may be
 * NULL) gets that relative residual. */
int gd_system_law_equilibrium(const gd_system *sys, double speed, const double *K, const double *f0,
                              const int *held, double *q, double *resnorm);
/* f (ndof) = sum of the laws' forces at state q, velocities zero, t = 0. */
void gd_system_law_forces(const gd_system *sys, double speed, const double *q, double *f);
/* The records of law i (sys->laws) at state q into out (at most cap); returns the count. */
int gd_system_law_records(const gd_system *sys, int i, double speed, const double *q, double *out,
                          int cap);
/* The laws' K and C about the static state at W, law after law, each a column-major
 * ndofs x ndofs block (sys->law_block doubles each). */
void gd_system_law_blocks(const gd_system *sys, double speed, double *Kb, double *Cb);
/* gd_system_law_state started from q0 (ndof; NULL: from 0), the state of a neighbouring
 * speed (a Campbell sweep's previous speed: a few Newton steps instead of the climb from
 * rest); where it does not converge from q0, from 0 as gd_system_law_state. */
int gd_system_law_state_from(const gd_system *sys, double speed, const double *q0, double *q);
/* gd_system_law_blocks about a given state (ndof; NULL: gd_system_law_state at speed). */
void gd_system_law_blocks_at(const gd_system *sys, double speed, const double *state, double *Kb,
                             double *Cb);
/* gd_system_dense with the laws linearised about state (ndof; NULL: solved at speed). */
void gd_system_dense_at(const gd_system *sys, double speed, const double *state, double *M,
                        double *D, double *K);
/* D += the laws' C, K += their K (dense ndof^2, either may be NULL). */
void gd_system_add_laws_dense(const gd_system *sys, double speed, double *D, double *K);

/* ---- strain_energy.c ---- */
/* The motion type a DOF's motion counts as (rz torsional, z axial, rx/ry tilt, else
 * lateral). */
gd_motion gd_system_dof_motion(gd_dof d);
/* gd_system_strain_energy (by_motion, may be NULL, and by_component) and its table (may be
 * NULL) at once, with the laws' stiffness blocks law_K given (gd_system_law_blocks' layout,
 * the K the modes were computed with; NULL: the laws left out): no static solve. */
double gd_system_strain_energy_laws(const gd_system *sys, double speed, const double *law_K,
                                    const double *re, const double *im, double *by_motion,
                                    double *by_component, double *table);

/* ---- condense.c ---- */
/* Static condensation of massless DOFs: master = DOFs with mass, slave = without. */
typedef struct gd_condense {
    int N, nm, ns;
    int *master, *slave;
    double *kss_lu; /* LU of K_ss */
    int *ipiv;
    double *ksm;   /* ns x nm */
    double *kms_t; /* ns x nm: K_ms^T */
} gd_condense;

gd_status gd_condense_setup(const gd_system *sys, const double *K, const double *D, gd_condense *c,
                            gd_error *err);
double *gd_condense_matrix(const gd_condense *c, const double *A, int is_stiffness);
void gd_condense_expand(const gd_condense *c, const double *um, double *u, int left, double *work);
void gd_condense_free(gd_condense *c);

#endif
