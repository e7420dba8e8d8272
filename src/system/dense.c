/* The system's dense matrices at a speed without the laws (gd_system_dense_linear):
 * M, C + C_b(W) + W G and K + K_b(W), the speed-dependent elements looping over the
 * element registry. gd_system_dense adds the laws' linearisation to these
 * (law_state.c). */
#include <string.h>

#include "elements/elements_impl.h"
#include "linalg/linalg_impl.h"
#include "system/system_impl.h"

/* A += local (n x n) at the instance's active DOFs (A dense column-major ndof^2). */
static void add_dense_local(const gd_system *s, const gd_element_instance *in, const double *local,
                            double *A)
{
    size_t n = (size_t)s->ndof;
    for (int a = 0; a < in->nlocal; a++)
        for (int b = 0; b < in->nlocal; b++)
            if (in->dof[a] >= 0 && in->dof[b] >= 0)
                A[(size_t)in->dof[a] + (size_t)in->dof[b] * n] += local[a * in->nlocal + b];
}

void gd_system_dense_linear(const gd_system *s, double speed, double *M, double *D, double *K)
{
    size_t nn = (size_t)s->ndof * (size_t)s->ndof;
    if (M) {
        memset(M, 0, nn * sizeof *M);
        gd_csc_add_dense(&s->M, 1.0, M);
    }
    if (D) {
        memset(D, 0, nn * sizeof *D);
        gd_csc_add_dense(&s->C, 1.0, D);
        gd_csc_add_dense(&s->G, speed, D);
    }
    if (K) {
        memset(K, 0, nn * sizeof *K);
        gd_csc_add_dense(&s->K, 1.0, K);
    }
    if (!s->has_speed_dependent) return;
    for (int e = 0; e < s->ninstances; e++) {
        const gd_element_instance *in = &s->instances[e];
        if (!(in->terms & GD_TERM_SPEED)) continue;
        double Kl[144], Cl[144];
        in->type->matrices(s->model, in->index, speed, NULL, Kl, Cl, NULL);
        if (K) add_dense_local(s, in, Kl, K);
        if (D) add_dense_local(s, in, Cl, D);
    }
}
