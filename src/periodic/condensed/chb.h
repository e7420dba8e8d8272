/* Condensed harmonic balance (docs/periodic.md, "Condensed harmonic balance"; issue 33
 * item 4): the harmonic balance equations of the transient problem,
 *   Z_k X_k = F_k(X),   Z_k = K - (k w)^2 M + i k w D,   k = 0 .. H,
 * solved with the laws' coordinates as the only unknowns. Every law force lies along its
 * terms' directions u_t and reads the DOFs only through their w_t (gd_transient_local's
 * contract: df/dq = sum sq_t u_t w_t^T), so with C the distinct u_t and w_t (nc columns)
 * the forces split, per sample, into f = C g + r with g = (C^T C)^-1 C^T f and r the part
 * outside span C, which no law moves (loads, prescribed motion). With y = C^T q,
 *   Y_k = C^T Z_k^-1 r_k + H_k G_k(Y),   H_k = C^T Z_k^-1 C   (nc x nc per harmonic)
 * ([PetrovEwins2003] Sec. 2, the receptance-based condensation; [KrackGross2019] Sec. 3.4),
 * nc (2 H + 1) unknowns, the TVMS a convolution of harmonics evaluated by the same AFT
 * (the same N samples) as the full solve. Newton's linear systems J = I - H T(Y) are
 * solved by GMRES (SUNDIALS SPGMR), preconditioned by the harmonic-diagonal part of T
 * (its sample mean: I - H_k (T_q + i k w T_v) per harmonic, nc x nc). The receptances come
 * from one complex sparse LU of Z_k per harmonic (exact, as gd_condense_direct), kept with
 * Z_k^-1 C and Z_k^-1 r_k for the recovery X_k = Z_k^-1 (r_k + C G_k) after convergence.
 * The recovered X is checked against the full residual (gd_hb_residual) by the caller. */
#ifndef GD_PERIODIC_CONDENSED_CHB_H
#define GD_PERIODIC_CONDENSED_CHB_H
#include <fftw3.h>
#include <klu.h>

#include "geardyn/transient.h"

/* The linear part of the problem: K, M, D on one sorted CSC pattern over the nf free DOFs
 * (hb_blocks.c's gd_hb_linear_union), pat_id changing with the pattern. Borrowed. */
typedef struct gd_chb_linear {
    const int *Up, *Ui;
    const double *UK, *UM, *UD;
    long pat_id;
} gd_chb_linear;

typedef struct gd_chb gd_chb;

/* Outcome of gd_chb_solve. */
enum {
    GD_CHB_OK = 0,
    GD_CHB_NA = 1,     /* does not apply to this problem (no terms, dependent coordinates,
                          too many coordinates, a singular Z_k): use the full solve */
    GD_CHB_NOCONV = 2, /* Newton or GMRES did not converge */
    GD_CHB_NOMEM = 3
};

/* Workspace for nf free DOFs, H harmonics and N AFT samples (those of the harmonic balance
 * workspace it serves); freed by gd_chb_free. NULL: no memory. */
gd_chb *gd_chb_new(int nf, int H, int N);
void gd_chb_free(gd_chb *c);
/* The coordinate count of the last problem (0 before the first solve). */
int gd_chb_ncoords(const gd_chb *c);
/* 1 when the condensed solve pays for problem tr (coordinates well below the DOFs:
 * 4 nc <= nf), 0 when not, -1 when it cannot apply (no law terms). */
int gd_chb_applies(gd_chb *c, gd_transient *tr);
/* Solves the harmonic balance equations of tr (its linear part lin) at frequency w (stage_id: the
 * problem's identity, the receptances being reused while it holds) from the start X (nf (2H+1),
 * full coefficients): X receives the full solution on GD_CHB_OK. tol: the condensed
 * residual's relative tolerance; *iters the Newton iterations. */
int gd_chb_solve(gd_chb *c, const gd_chb_linear *lin, gd_transient *tr, long stage_id, double w,
                 double *X, double tol, int *iters);
/* Lends lender's receptances to c (borrowed; NULL: none): c's next solve of the problem
 * the lender solved last (the same stage, frequency, coordinates and pattern of K, M, D:
 * the same Z_k) takes H_k and Z_k^-1 C of the harmonics both hold from it, and
 * Z_k^-1 r_k from its LU, instead of factoring Z_k (the truncation estimate's solve at
 * 2 H + 1 after the point's at H: H + 1 of its 2 H + 2 factorizations). */
void gd_chb_lend(gd_chb *c, gd_chb *lender);
/* The harmonics c took from a lender so far (diagnostics). */
long gd_chb_lent(const gd_chb *c);
/* The full harmonic balance residual of the X the last gd_chb_solve returned, relative
 * to the scale of gd_hb_residual (the larger of |L X| and |F|), from the coordinates
 * only: with X_k = Z_k^-1 (r_k + C G_k(Y)) and the laws reading X through C^T X,
 *   Z_k X_k - F_k(X) = C (G_k(Y) - G_k(C^T X)) + e_k,
 * e_k the rounding of the sparse solves (docs/periodic.md, "Condensed harmonic balance").
 * One more evaluation of the laws at the samples, no transform of the DOFs and no
 * product with K, M, D. Returns 0 with *rel set; 1 when the full check is due instead:
 * the first solve of this workspace and every 16th after it (a count: e_k and the laws'
 * contract, every force in span C, are checked on a schedule), a load outside span C
 * (r not zero) or a force not finite. */
int gd_chb_check(gd_chb *c, gd_transient *tr, double w, const double *X, double *rel);
/* Counters (diagnostics): condensed solves that converged, GMRES iterations so far. */
void gd_chb_counts(const gd_chb *c, long *solves, long *gmres_iters);

#endif
