/* Internals shared by the undamped and state-space modal solvers. */
#ifndef GD_MODAL_IMPL_H
#define GD_MODAL_IMPL_H
#include <complex.h>

#include "geardyn/modal.h"
#include "system/system_impl.h"

/* Energy shares, dominant motion/component and whirl of a mode with full shape u, the
 * laws' strain energy left out (their components 0): the solvers' first labels. */
void gd_mode_finish(const gd_system *sys, double speed, gd_mode *md, const double *re,
                    const double *im, double *comp_share);
/* The same with the laws' stiffness blocks law_K (gd_system_law_blocks' layout; NULL: as
 * gd_mode_finish). */
void gd_mode_finish_laws(const gd_system *sys, double speed, const double *law_K, gd_mode *md,
                         const double *re, const double *im, double *comp_share);
/* Every elastic mode of r finished again with the laws' stiffness about law_state (ndof;
 * NULL: solved at r's speed), the K the modes were computed with, so a linearised bearing
 * law's strain energy is its own component's (strain_energy.c). GD_OK or GD_ENOMEM. */
gd_status gd_modal_energies_laws(const gd_system *sys, gd_modal_result *r, const double *law_state);
double complex gd_normalise_max(double *re, double *im, int n);
/* The eigenvalue lambda = lr + i li of an elastic mode (li >= 0) and what follows from it:
 * natural and damped frequency, damping ratio, log decrement, overdamped, unstable. */
void gd_mode_set_lambda(gd_mode *md, double lr, double li);

/* ---- rigid_modes.c ---- */
/* The motion type a DOF's motion counts as (rz torsional, z axial, rx/ry tilt, else
 * lateral). */
gd_motion gd_dof_motion(gd_dof d);
/* An orthonormal basis (n x r, malloc'd into *basis) of the right null space of the
 * n x n matrix A: the singular values <= tol. Returns r (0: none, *basis NULL), or -1
 * when out of memory or the SVD fails. */
int gd_null_space(const double *A, int n, double tol, double **basis);
/* Replaces the r full shapes U (ndof x r, independent rigid-body motions) by
 * combinations that each move in one motion type where the span allows: spin first,
 * then axial, lateral, tilt (a vector belongs to a type when over half its kinetic
 * energy, by the diagonal of M, is in it). Independence is kept. */
void gd_rigid_separate(const gd_system *sys, double *U, int r);
/* Modes 0 .. kr-1 of res are the rigid-body modes U (ndof x kr): shapes, labels. */
void gd_rigid_modes_fill(const gd_system *sys, double speed, gd_modal_result *res, const double *U,
                         int kr);
/* The null space of K (values k on a's pattern) from r0 starting vectors U (n x r0,
 * e.g. an eigensolver's rigid-body vectors, however mixed): three steps of block
 * inverse iteration with (K + sigma M)^-1 M, M-orthonormalised, keeping the vectors
 * with |K u| <= tol |M u|. They replace the first r columns of U; returns r, or -1 when
 * out of memory or K + sigma M is singular. */
int gd_rigid_null_sparse(const gd_dynmat *a, const gd_splu_symbolic *sym, const double *k,
                         double sigma, double tol, double *U, int r0);

/* Eigenvalues of (Kr, Mr) (n x n, condensed) within this of zero are rigid-body modes:
 * 1e-12 of the largest diagonal ratio K_ii / M_ii. */
double gd_modal_zero_tol(const double *Kr, const double *Mr, int n);

gd_status gd_modal_undamped(const gd_system *sys, const gd_modal_options *opt, const gd_condense *c,
                            const double *M, const double *K, gd_modal_result **out, gd_error *err);
gd_status gd_modal_state_space(const gd_system *sys, const gd_modal_options *opt,
                               const gd_condense *c, const double *M, const double *D,
                               const double *K, gd_modal_result **out, gd_error *err);

/* The dense (LAPACK) solver behind gd_modal_solve, whatever opt->method says. */
gd_status gd_modal_solve_dense(const gd_system *sys, const gd_modal_options *opt,
                               gd_modal_result **out, gd_error *err);

/* The undamped natural frequencies only, by the dense solver's matrices, condensation
 * and rigid-body rule (gd_modal_solve_dense with GD_MODAL_UNDAMPED), without vectors or
 * mode properties: for counting modes (Campbell's default mode count). *omega (the
 * caller frees it) holds *n ascending values, -1 for a rigid-body mode, sqrt|lambda| for a
 * divergence; *omega NULL (GD_OK) where K is not symmetric (the general problem: ask
 * gd_modal_solve). */
gd_status gd_modal_undamped_frequencies(const gd_system *sys, const gd_modal_options *opt,
                                        double **omega, int *n, gd_error *err);

/* Allocates a result for nmodes modes (shapes zeroed). */
gd_modal_result *gd_modal_result_new(const gd_system *sys, int nmodes, int with_left);

/* ---- sparse_modes.c ---- */
/* Lowest opt->nmodes damped modes at opt->speed by shift-invert about sigma = -shift
 * (shift <= 0: automatic), reusing a built pattern and symbolic analysis. */
typedef struct gd_sparse_ws {
    gd_ks_work ks;
    double *k, *d;
    /* Warm start along a sweep (Campbell): with chain set, each solve leaves the sums
     * w1 = sum (Re u + Im u) and w2 = sum (Re + Im)(lambda u) of its modes in warm
     * (2 n, allocated on first use) and the next solve starts its Krylov space from
     * [w1; w2 / g] (v0, 2 n), in the span of the previous speed's wanted vectors.
     * warm_ok: warm holds a previous solve's sums (clear it to start cold). */
    int chain, warm_ok;
    double *warm, *v0;
    /* gd_sparse_track's buffers and complex factorisations, kept from one continued
     * speed to the next (sparse_track.c; NULL until first used), and the function
     * that frees them (set with them; gd_sparse_ws_free calls it) */
    struct gd_track_cache *track;
    void (*track_free)(struct gd_sparse_ws *ws);
} gd_sparse_ws;
/* Turns the warm start on for an n-DOF pattern (allocates warm, v0; warm_ok stays as
 * it is). 0 ok, 1 out of memory. */
int gd_sparse_ws_chain(gd_sparse_ws *ws, int n);
/* Stores the warm-start sums of the modes of r (with their shapes) in ws->warm and
 * sets warm_ok; nothing when warm is not allocated. */
void gd_sparse_ws_remember(gd_sparse_ws *ws, const gd_modal_result *r);
/* Workspace for nmodes modes of the pattern a (0 ok, 1 out of memory). */
int gd_sparse_ws_init(gd_sparse_ws *w, const gd_dynmat *a, int nmodes);
void gd_sparse_ws_free(gd_sparse_ws *w);
/* ws may be NULL (allocated per call). */
gd_status gd_sparse_modes(const gd_dynmat *a, const gd_splu_symbolic *sym,
                          const gd_modal_options *opt, double shift, gd_sparse_ws *ws,
                          gd_modal_result **out, gd_error *err);
/* ---- residual.c: gd_mode.residual and residual_floor ---- */
/* Of one mode md with the shape ur + i ui (n = a's size); w: 13 n scratch. */
void gd_mode_residual(const gd_dynmat *a, const double *k, const double *d, gd_mode *md,
                      const double *ur, const double *ui, double *w);
/* Of every mode of r, on a's pattern with k, d at r's speed (d NULL: undamped); *worst
 * and *worst_floor (may be NULL): the largest over the elastic modes. GD_ENOMEM or GD_OK. */
gd_status gd_modal_residuals_on(const gd_dynmat *a, const double *k, const double *d,
                                gd_modal_result *r, double *worst, double *worst_floor);
/* The same, building the sparse matrices of sys, its laws linearised about law_state
 * (ndof; NULL: solved at r's speed). */
gd_status gd_modal_residuals(const gd_system *sys, gd_modal_result *r, const double *law_state,
                             gd_error *err);
/* gd_sparse_modes to the precision opt->tol asks (GD_MODAL_TOL_DEFAULT when 0): the
 * Krylov-Schur tolerance tightened 100-fold while an elastic mode's residual is above
 * tol and above 100 times its rounding floor (at most to 1e-14); residuals filled. */
gd_status gd_sparse_modes_to_tol(const gd_dynmat *a, const gd_splu_symbolic *sym,
                                 const gd_modal_options *opt, double shift, gd_sparse_ws *ws,
                                 gd_modal_result **out, gd_error *err);
/* ---- sparse_project.c ---- */
/* The lowest opt->nmodes damped modes at opt->speed from the undamped modes (block
 * shift-invert Lanczos), the damped problem projected on them and refined and checked for
 * completeness by gd_sparse_track; *out NULL with GD_OK where the rule of sparse_project.c
 * sends the solve to Krylov-Schur (gd_sparse_modes). ws: as for gd_sparse_modes (its k, d
 * and Krylov work, 2 n by at least 20 vectors). */
gd_status gd_sparse_modes_projected(const gd_dynmat *a, const gd_splu_symbolic *sym,
                                    const gd_modal_options *opt, gd_sparse_ws *ws,
                                    gd_modal_result **out, gd_error *err);
/* ---- sparse_track.c: continuation along a sweep ---- */
/* The modes of prev (a result of this pattern at a nearby speed, with its shapes: the
 * same count, rigid-body modes first; prev2, may be NULL, the one before it, for a
 * linear prediction) refined to opt->speed by per-cluster residual
 * inverse iteration with Rayleigh-Ritz, then checked for completeness by a deflated
 * shift-invert Krylov check (sparse_track.c). *out NULL with GD_OK when the
 * continuation cannot vouch for the result (the caller falls back to gd_sparse_modes);
 * GD_ENOMEM when out of memory. ws: as for gd_sparse_modes (its k, d and Krylov work).
 * *hard: 1 when the continuation declined or struggled (a cluster needed many passes,
 * the completeness check was close): the caller had better use Krylov-Schur next. */
gd_status gd_sparse_track(const gd_dynmat *a, const gd_splu_symbolic *sym,
                          const gd_modal_options *opt, const gd_modal_result *prev,
                          const gd_modal_result *prev2, gd_sparse_ws *ws, gd_modal_result **out,
                          int *hard, gd_error *err);
/* The modes of r (computed at opt->speed, e.g. by Krylov-Schur) refined in place by the
 * same iteration to the residual opt->tol (GD_TRACK_TOL when 0 or coarser), undamped
 * ones (opt->kind GD_MODAL_UNDAMPED, D = 0) too; *out NULL when it cannot vouch. */
gd_status gd_sparse_refine(const gd_dynmat *a, const gd_splu_symbolic *sym,
                           const gd_modal_options *opt, const gd_modal_result *r, gd_sparse_ws *ws,
                           gd_modal_result **out, gd_error *err);
/* Forgets the factorisations gd_sparse_track keeps in ws (at the start of a chain: a
 * chain's numbers must not depend on the chains its thread did before). */
void gd_sparse_track_reset(gd_sparse_ws *ws);
void gd_sparse_track_free(gd_sparse_ws *ws);
/* sqrt(min K_ii / M_ii) (1e3 when no DOF has both): an element's frequency, of the
 * order of the lowest modes' only on a coarse mesh; bounds the automatic shift
 * (gd_sparse_shift_auto). */
double gd_sparse_diag_frequency(const gd_dynmat *a, const double *k);
/* The automatic shift s (sigma = -s), the state scaling g and the magnitude below
 * which an eigenvalue counts as a rigid-body zero, for the values k on a's pattern:
 * a tenth of the lowest Rayleigh quotient of the uniform motions of each DOF type,
 * within [1e-6, 1e-3] of gd_sparse_diag_frequency (sparse_modes.c says why). */
void gd_sparse_shift_auto(const gd_dynmat *a, const double *k, double *s, double *g, double *zero);
/* Krylov sizes for nmodes modes of an n-DOF system: nev Ritz values (both members of
 * each conjugate pair) in a basis of at most ncv vectors. */
void gd_sparse_ks_sizes(int n, int nmodes, int *nev, int *ncv);

/* ---- method_cost.c: dense or sparse, by a measured cost model ---- */
/* 1 when the sparse solver can give these modes: nmodes > 0, mass on every DOF and a
 * Krylov basis smaller than the state (2 nmodes + 16 < n). */
int gd_sparse_applicable(const gd_system *sys, int nmodes);
/* Estimated seconds of one dense solve of n DOFs (state space 2n when damped, the
 * symmetric problem otherwise) and of one sparse solve of nmodes modes on the pattern
 * p with its symbolic analysis sym (factorisation, shift-invert products,
 * orthogonalisation). */
double gd_cost_dense(int n, int damped, int nmodes);
double gd_cost_sparse(const gd_pattern *p, const gd_splu_symbolic *sym, int nmodes);
/* 1 when the damped (state-space) problem is the one to solve at this speed: asked for,
 * or AUTO and the damping at the speed is not zero. */
int gd_modal_damped_at(const gd_dynmat *a, const gd_modal_options *opt, double *k, double *d);

#endif
