/* The condensation's data (docs/condense.md): kept modes, rigid modes, static
 * correction, and the real state-space model on the same basis. */
#ifndef GD_CONDENSE_IMPL_H
#define GD_CONDENSE_IMPL_H
#include <complex.h>

#include "geardyn/condense.h"

struct gd_condensation {
    int N, nc;           /* system DOFs, coordinates */
    int nm, nr, ns;      /* kept elastic modes, rigid modes, states */
    double complex *lam; /* nm eigenvalues (upper half plane or real) */
    int *pair;           /* nm: 1 when the conjugate mode is implied */
    double complex *U;   /* N x nm right vectors */
    double complex *Cm;  /* nc x nm: W^T u */
    double complex *Bm;  /* nc x nm: W^T v (left vectors, v^T (2 lambda M + D) u = 1) */
    double *R;           /* N x nr rigid modes, M-orthonormal */
    double *Rc;          /* nc x nr: W^T r */
    double *Xres;        /* N x nc: the static correction's full columns */
    double *G;           /* nc x nc: W^T Xres */
    double *A, *B, *C;   /* the real state-space model (state_space.c) */
    gd_condense_info info;
};

/* refine.c: iters steps of two-sided inverse iteration with Newton updates of the nm pairs (lam, U, V:
 * N x nm right and left vectors, replaced; V normalised v^T (2 lambda M + D) u = 1).
 * *worst_step: the largest relative eigenvalue change. */
gd_status gd_condense_refine(const gd_system *sys, double speed, int nm, double complex *lam,
                             double complex *U, double complex *V, int iters,
                             double *worst_step, gd_error *err);

/* state_space.c: fills c->ns, A, B, C from the modal data. 0 ok, 1 out of memory. */
int gd_condense_build_lti(gd_condensation *c);

#endif
