/* gd_blas_set_threads: the library's OpenBLAS, linked into libgeardyn.so with hidden
 * symbols when GD_STATIC_DEPS (CMakeLists.txt: no dynamic OpenBLAS to relocate at every
 * start-up), so the one call that reaches it is the library's own. */
#include <cblas.h>

#include "geardyn/blas.h"

void gd_blas_set_threads(int n)
{
    openblas_set_num_threads(n > 0 ? n : 1);
}
