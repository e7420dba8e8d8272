/* The system's matrices at a speed as separate sparse matrices (gd_system_matrices):
 * the values come from the dynamic matrix (one pattern for M, C, G, K and the
 * speed-table bearings), each matrix keeps only its own non-zeros. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "system/system_impl.h"

/* Copies the non-zero values v on pattern p into out. 0 ok, 1 out of memory. */
static int compress(const gd_pattern *p, const double *v, gd_csc *out)
{
    int nnz = 0;
    for (int k = 0; k < p->nnz; k++)
        nnz += v[k] != 0.0;
    out->n = p->n;
    out->colptr = malloc((size_t)(p->n + 1) * sizeof *out->colptr);
    out->rowind = malloc((size_t)(nnz ? nnz : 1) * sizeof *out->rowind);
    out->values = malloc((size_t)(nnz ? nnz : 1) * sizeof *out->values);
    if (!out->colptr || !out->rowind || !out->values) return 1;
    int at = 0;
    out->colptr[0] = 0;
    for (int j = 0; j < p->n; j++) {
        for (int k = p->colptr[j]; k < p->colptr[j + 1]; k++)
            if (v[k] != 0.0) {
                out->rowind[at] = p->rowind[k];
                out->values[at++] = v[k];
            }
        out->colptr[j + 1] = at;
    }
    return 0;
}

static void clear(gd_csc *a)
{
    if (a) memset(a, 0, sizeof *a);
}

gd_status gd_system_matrices(const gd_system *sys, double speed, gd_csc *M, gd_csc *K, gd_csc *C,
                             gd_csc *G, gd_error *err)
{
    clear(M);
    clear(K);
    clear(C);
    clear(G);
    if (!isfinite(speed))
        return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "speed",
                            "give a finite reference speed in rad/s", "speed %g is not finite",
                            speed);
    gd_dynmat a;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    size_t z = (size_t)(a.pat.nnz ? a.pat.nnz : 1);
    double *k = malloc(z * sizeof *k), *c = malloc(z * sizeof *c);
    int bad = !k || !c;
    if (!bad) {
        /* K + K_b(W) and C + C_b(W): the damping without W G */
        memcpy(k, a.k, (size_t)a.pat.nnz * sizeof *k);
        memcpy(c, a.c, (size_t)a.pat.nnz * sizeof *c);
        gd_dynmat_add_speed_terms(&a, speed, k, c);
    }
    bad = bad || (M && compress(&a.pat, a.m, M)) || (K && compress(&a.pat, k, K)) ||
          (C && compress(&a.pat, c, C)) || (G && compress(&a.pat, a.g, G));
    free(k);
    free(c);
    gd_dynmat_free(&a);
    if (!bad) return GD_OK;
    gd_csc *out[4] = {M, K, C, G};
    for (int i = 0; i < 4; i++)
        if (out[i]) gd_csc_free(out[i]);
    return gd_error_set(err, GD_ENOMEM, sys->model->file, 0, 0, "", "",
                        "out of memory for the system matrices");
}
