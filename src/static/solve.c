/* The linear static solve K_FF q_F = f_F on the Jacobi scaling D K_FF D y = D f_F,
 * q_F = D y (LU, LAPACK), so translations and rotations weigh alike; and the stiffness
 * the hold search sees with laws that carry load. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "static/static_impl.h"
#include "system/system_impl.h"

/* q (zeroed) on the free DOFs from K_FF q_F = f_F. */
gd_status gd_st_solve_linear(const gd_system *sys, const double *K, const double *f,
                             const int *held, double *q, gd_error *err)
{
    const int n = sys->ndof;
    int nf = 0;
    memset(q, 0, (size_t)n * sizeof *q);
    int *fr = malloc((size_t)(n > 0 ? n : 1) * sizeof *fr);
    double *A = NULL, *d = NULL, *b = NULL;
    lapack_int *piv = NULL;
    gd_status st = GD_OK;
    if (!fr) goto oom;
    for (int i = 0; i < n; i++)
        if (!held[i]) fr[nf++] = i;
    if (nf == 0) goto out;
    A = malloc((size_t)nf * nf * sizeof *A);
    d = malloc((size_t)nf * sizeof *d);
    b = malloc((size_t)nf * sizeof *b);
    piv = malloc((size_t)nf * sizeof *piv);
    if (!A || !d || !b || !piv) goto oom;
    for (int a = 0; a < nf; a++) {
        double kaa = K[fr[a] + (size_t)fr[a] * n];
        d[a] = kaa > 0 ? 1 / sqrt(kaa) : 1;
    }
    for (int c = 0; c < nf; c++)
        for (int a = 0; a < nf; a++)
            A[a + (size_t)c * nf] = d[a] * K[fr[a] + (size_t)fr[c] * n] * d[c];
    for (int a = 0; a < nf; a++)
        b[a] = d[a] * f[fr[a]];
    lapack_int info = LAPACKE_dgesv(LAPACK_COL_MAJOR, nf, 1, A, nf, piv, b, nf);
    if (info != 0) {
        st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "", "",
                          "the held stiffness is singular (LU pivot %d)", (int)info);
        goto out;
    }
    for (int a = 0; a < nf; a++)
        q[fr[a]] = d[a] * b[a];
    goto out;
oom:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
out:
    free(fr);
    free(A);
    free(d);
    free(b);
    free(piv);
    return st;
}

/* Kd = K with a small grounded stiffness on every direction a supporting law acts on, so
 * that the hold search counts those directions as held (a rotor on journal bearings has
 * no bearing element but is not free): 1e-6 of the largest diagonal, far above the
 * null-space threshold of holds.c (1e-10) and far below any real stiffness's effect on
 * it. */
void gd_st_supported_stiffness(const gd_system *sys, const double *K, double *Kd)
{
    const size_t n = (size_t)sys->ndof;
    memcpy(Kd, K, n * n * sizeof *Kd);
    double kmax = 0;
    for (size_t i = 0; i < n; i++)
        kmax = fmax(kmax, fabs(K[i + i * n]));
    const double kreg = 1e-6 * (kmax > 0 ? kmax : 1.0);
    for (int l = 0; l < sys->nlaws; l++) {
        const gd_law *L = &sys->laws[l];
        if (!(L->type->flags & GD_LAW_SUPPORT)) continue;
        for (int a = 0; a < L->ndofs; a++)
            if (L->dof[a] >= 0) Kd[(size_t)L->dof[a] * (n + 1)] += kreg;
    }
}
