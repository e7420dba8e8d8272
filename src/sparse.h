/* Sparse assembly: triplets collected per element, then compressed to columns (with
 * duplicates summed) by CXSparse. */
#ifndef GD_SPARSE_H
#define GD_SPARSE_H
#include "geardyn/system.h"

typedef struct gd_trip {
    int n, cap;
    int *i, *j;
    double *x;
} gd_trip;

int gd_trip_add(gd_trip *t, int i, int j, double x); /* 0 ok, 1 out of memory */
void gd_trip_free(gd_trip *t);
/* Compresses rows/cols mapped through map (raw -> active, -1 dropped) into an n x n
 * CSC matrix. 0 ok, 1 out of memory. */
int gd_trip_compress(const gd_trip *t, const int *map, int n, gd_csc *out);
void gd_csc_free(gd_csc *a);
/* A += scale * S (A dense column-major n x n). */
void gd_csc_add_dense(const gd_csc *s, double scale, double *A);
/* y = S x (real). */
void gd_csc_mul(const gd_csc *s, const double *x, double *y);

#endif
