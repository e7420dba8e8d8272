/* Exact condensation of the linear structure onto the coordinates where nonlinear laws act
 * (docs/condense.md): a mesh's deflection along its line of action d = a . q, a bearing's
 * x and y DOFs. With W (ndof x nc) the coordinates' vectors and forces f = W u applied
 * through them, the structure M q'' + D q' + K q = W u is seen only through
 *
 *   y = W^T q:   H_c(w) = W^T (K - w^2 M + i w D)^-1 W            (frequency domain)
 *                x' = A x + B u,  y = C x + G u                    (time domain)
 *
 * built once from the damped (gyroscopic) modes with right and left eigenvectors
 * ([MMT2018] Eqs. 14-15; [PetrovEwins2003] receptance-based condensation), the kept modes
 * summed and the discarded ones replaced by their static (residual flexibility) part
 * G = W^T (K_e^+ - sum_kept -u v^T / lambda) W ([CraigKurdila2006] residual flexibility), with
 * rigid-body modes (a train free in torsion) as exact -r r^T / w^2 terms and K_e^+ the
 * elastic flexibility under inertia relief. With every mode kept (nmodes = 0) the result
 * equals the direct solve to round-off (3e-10 on seed 002; at a peak of damping ratio z,
 * round-off times 1/(2 z), as for any method). The structure is the one gd_modal_solve sees: M, K
 * and D of gd_system_dense at the speed (laws linearised about their static state).
 *
 * Ownership and threads: a gd_condense_coords is the caller's value (gd_condense_coords_init,
 * freed by gd_condense_coords_release). gd_condense_build returns a condensation the caller
 * frees with gd_condense_destroy; it copies what it needs (the system and the coordinates
 * may be freed after it). A built condensation is read-only: every function taking a const
 * gd_condensation * may be called from several threads at once. */
#ifndef GEARDYN_CONDENSE_H
#define GEARDYN_CONDENSE_H
#include "geardyn/export.h"
#include "geardyn/system.h"

#define GD_CONDENSE_LABEL_MAX 64

/* Law coordinates: coordinate k is y_k = sum a[e] q[dof[e]] over e = start[k] ..
 * start[k + 1] - 1. */
typedef struct gd_condense_coords {
    int n;                                /* coordinates */
    int nnz;                              /* entries */
    int *start;                           /* n + 1 */
    int *dof;                             /* nnz: system DOF indices */
    double *a;                            /* nnz */
    char (*label)[GD_CONDENSE_LABEL_MAX]; /* n: "mesh:<name>", "<law>.<node>.<dof>" */
    int cap, nnz_cap;
} gd_condense_coords;

GD_API void gd_condense_coords_init(gd_condense_coords *c);
GD_API void gd_condense_coords_release(gd_condense_coords *c);
/* Appends one coordinate (n entries; DOFs in 0 .. ndof-1, finite weights, not all zero).
 * label may be NULL ("c<k>"). GD_EINPUT names the bad entry. */
GD_API gd_status gd_condense_coords_add(gd_condense_coords *c, const gd_system *sys,
                                        const char *label, int n, const int *dof, const double *a,
                                        gd_error *err);
/* Appends every gear mesh's deflection along its line of action (gd_system_mesh_vector),
 * labelled "mesh:<name>"; a mesh on no active DOF is skipped. */
GD_API gd_status gd_condense_coords_meshes(gd_condense_coords *c, const gd_system *sys,
                                           gd_error *err);
/* Appends every DOF a registry law of the model acts on (sys->laws: bearings, dampers,
 * contacts), each as a unit vector labelled "<law>.<dof label>", once even when several
 * laws share it. */
GD_API gd_status gd_condense_coords_laws(gd_condense_coords *c, const gd_system *sys,
                                         gd_error *err);

/* How the modes are found. DENSE: every mode of the first-order problem by LAPACK
 * (O(ndof^3) time, O(ndof^2) memory; left vectors from it). SPARSE: the lowest nmodes + 1
 * elastic modes by shift-invert Krylov-Schur on the sparse problem (gd_modal_solve_sparse:
 * needs mass on every DOF), the left vectors by inverse iteration on the transpose; the
 * static correction by KLU. AUTO: SPARSE when nmodes > 0 and ndof > GD_CONDENSE_DENSE_MAX.
 * Both refine the kept modes on the sparse problem (two-sided inverse iteration). */
typedef enum gd_condense_method {
    GD_CONDENSE_AUTO,
    GD_CONDENSE_DENSE,
    GD_CONDENSE_SPARSE
} gd_condense_method;
#define GD_CONDENSE_DENSE_MAX 2000

typedef struct gd_condense_options {
    double speed; /* reference speed, rad/s */
    int nmodes;   /* elastic modes kept (the lowest); 0: all (exact to round-off; dense) */
    gd_condense_method method; /* default AUTO */
    /* ndof flags (NULL: none): 1 where the DOF is held at zero, its rows and columns of
       M, D, K removed (the structure of the free DOFs, clamped there: a prescribed
       motion then enters as coordinate forces through the coupling blocks, applied by
       the caller). DENSE only; a coordinate on a held DOF is GD_EINPUT. Borrowed. */
    const int *held;
} gd_condense_options;
GD_API void gd_condense_options_init(gd_condense_options *o);

typedef struct gd_condensation gd_condensation;

typedef struct gd_condense_info {
    int ndof, ncoords;
    int nkept;              /* elastic modes summed (a conjugate pair counts once) */
    int ndiscarded;         /* elastic modes replaced by the static correction */
    int nrigid;             /* rigid-body modes, summed exactly */
    double first_discarded; /* |lambda| of the lowest discarded mode, rad/s; INFINITY if none */
    double zeta_discarded;  /* largest damping ratio among the discarded modes (SPARSE: the
                               first discarded and the kept ones, the others being unknown) */
    double residual;        /* largest |entry| of the static correction G */
    double static_check;    /* relative residual of the elastic static solve */
    double refine_step;     /* largest relative eigenvalue change in the refinement of the
                               kept modes on the sparse problem (refine.c) */
} gd_condense_info;

/* Builds the condensation of sys at opt->speed on the coordinates c (c->n >= 1): the
 * modes (opt->method), two complex sparse factorisations per kept mode (refinement), one
 * static solve with nc right-hand sides. Errors: GD_EINPUT (no coordinates, a coordinate outside
 * the system, rigid modes that carry stiffness or damping), GD_ENUMERIC (a stiffness singular
 * beyond its rigid modes), GD_ENOMEM. */
GD_API gd_status gd_condense_build(const gd_system *sys, const gd_condense_coords *c,
                                   const gd_condense_options *opt, gd_condensation **out,
                                   gd_error *err);
GD_API void gd_condense_destroy(gd_condensation *c);
GD_API void gd_condense_info_get(const gd_condensation *c, gd_condense_info *info);

/* H (2 nc^2 doubles): the receptance at w >= 0 (rad/s), column-major nc x nc, complex
 * interleaved (re, im): H[2 (i + nc j)] is y_i per unit u_j. At w = 0 with rigid modes it
 * is the elastic flexibility under inertia relief (the rigid term, infinite, left out:
 * the mean of a free train is the periodic solver's own). est (may be NULL): an estimate
 * of the largest entry error from the discarded modes, max|G| |w^2 - 2 i z w_d w| /
 * |w_d^2 - w^2 + 2 i z w_d w| (a mode's dynamic over static response, less one) with w_d
 * their lowest |lambda| and z their largest damping ratio (0 when every mode is kept). */
GD_API void gd_condense_receptance(const gd_condensation *c, double w, double *H, double *est);
/* The full response at w of coordinate forces u (nc complex, interleaved): q (ndof
 * complex, interleaved) = (K - w^2 M + i w D)^-1 W u with the same modal sum and static
 * correction (w > 0 with rigid modes; at w = 0 their term is left out, as above). */
GD_API void gd_condense_recover(const gd_condensation *c, double w, const double *u, double *q);

/* The reduced model in the time domain, real, on the same basis: states x = the kept
 * modes' (2 per conjugate pair: real and imaginary part; 1 per real mode) and the rigid
 * modes' (amplitude and its rate), inputs u = forces at the coordinates, outputs y = the
 * coordinates: x' = A x + B u, y = C x + G u (G the static correction: an algebraic
 * feedthrough). All column-major, owned by the condensation (read-only). */
typedef struct gd_condense_lti {
    int nstates, ncoords;
    const double *A; /* nstates x nstates */
    const double *B; /* nstates x ncoords */
    const double *C; /* ncoords x nstates */
    const double *G; /* ncoords x ncoords */
} gd_condense_lti;
GD_API void gd_condense_state_space(const gd_condensation *c, gd_condense_lti *out);
/* The full displacement q (ndof) from the reduced state x (nstates) and the coordinate
 * forces u (ncoords) at the same instant. */
GD_API void gd_condense_recover_state(const gd_condensation *c, const double *x, const double *u,
                                      double *q);

/* Reference: H_c at nfreq frequencies by the direct sparse solve (KLU on
 * K - w^2 M + i w D with the coordinates as right-hand sides, as gd_frf's direct method).
 * H: 2 nc^2 nfreq doubles, frequency f at H + 2 nc^2 f; a singular point (w = 0 on a free
 * train) is NAN. */
GD_API gd_status gd_condense_direct(const gd_system *sys, const gd_condense_coords *c, double speed,
                                    int nfreq, const double *w, double *H, gd_error *err);
/* The exact full response at one frequency by the direct sparse solve: q (ndof complex,
 * interleaved) = (K - w^2 M + i w D)^-1 W u for coordinate forces u (nc complex): the
 * recovery for a model too large for every mode. GD_ENUMERIC when Z(w) is singular (w = 0
 * on a free train). */
GD_API gd_status gd_condense_direct_recover(const gd_system *sys, const gd_condense_coords *c,
                                            double speed, double w, const double *u, double *q,
                                            gd_error *err);

#endif
