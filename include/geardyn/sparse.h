/* Sparse matrices in compressed sparse columns, the form the system's matrices take.
 *
 * Ownership and threads: a gd_csc owns its three arrays; gd_csc_free frees them and
 * leaves the struct zeroed. Reading one matrix from several threads is safe. */
#ifndef GEARDYN_SPARSE_H
#define GEARDYN_SPARSE_H
#include "geardyn/export.h"

/* Compressed sparse columns, square n x n, row indices sorted within each column. */
typedef struct gd_csc {
    int n;
    int *colptr; /* n + 1 */
    int *rowind; /* colptr[n] */
    double *values;
} gd_csc;

GD_API void gd_csc_free(gd_csc *a);

#endif
