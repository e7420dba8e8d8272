/* The cost of a dense (LAPACK) modal solve of a system, for a user deciding whether to
 * ask for it: time by the cost model of method.c, peak memory from the arrays the dense
 * path holds at once (modal.c, state_space.c, undamped.c). */
#include "modal/modal_impl.h"

void gd_modal_dense_cost(const gd_system *sys, int damped, double *seconds, double *bytes)
{
    double n = sys->ndof;
    if (seconds) *seconds = gd_cost_dense(sys->ndof, damped, 0);
    /* damped: M, D, K and their condensed copies (6 n^2), the state matrix, its
       Hessenberg form and the Schur work copy (3 (2n)^2); undamped: M, D, K, the
       condensed pair and the vectors (6 n^2). Doubles of 8 bytes. */
    if (bytes) *bytes = 8.0 * n * n * (damped ? 18.0 : 6.0);
}
