/* The dense linear algebra's own threads (OpenBLAS, which the library may carry inside
 * it with its symbols hidden: a program cannot reach openblas_set_num_threads itself,
 * and its own call would set another copy's).
 *
 * Threads: process-wide setting; call it before starting threads that use the library
 * (the CLI does so before a sweep parallel over points). */
#ifndef GEARDYN_BLAS_H
#define GEARDYN_BLAS_H
#include "geardyn/export.h"

/* The number of threads each dense factorisation or product may use (n >= 1); the
 * default is OpenBLAS's (OPENBLAS_NUM_THREADS, else the processors). */
GD_API void gd_blas_set_threads(int n);

#endif
