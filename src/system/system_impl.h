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
    const gd_system *sys;
} gd_dynmat;

gd_status gd_dynmat_build(const gd_system *sys, gd_dynmat *out, gd_error *err);
void gd_dynmat_free(gd_dynmat *a);
/* k += K_b(W), c += C_b(W): the speed-dependent terms on the pattern (either may be
 * NULL). */
void gd_dynmat_add_speed_terms(const gd_dynmat *a, double speed, double *k, double *c);
/* k = K + K_b(W), d = C + C_b(W) + W G on the pattern (nnz each). */
void gd_dynmat_at(const gd_dynmat *a, double speed, double *k, double *d);

/* Factors the complex dynamic stiffness Z(w) = K - w^2 M + i w D (k, d from
 * gd_dynmat_at; z: 2 nnz scratch). Returns as gd_splu_factor. */
int gd_dynmat_factor_at(const gd_dynmat *a, const gd_splu_symbolic *s, const double *k,
                        const double *d, double w, double *z, gd_splu *lu);

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
