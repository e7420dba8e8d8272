/* Sparse LU by KLU (SuiteSparse): the symbolic analysis (BTF, then AMD's or a minimum-degree
 * ordering per block, whichever predicts fewer flops: ordering.c) is done
 * once per pattern and shared read-only by every thread; each point of a sweep factors
 * its own numeric values with its own klu_common, so threads never share state. A fresh
 * factorisation (with its own pivoting) per point keeps results independent of the
 * order in which a thread visits the points. */
#include <math.h>
#include <string.h>

#include "linalg/linalg_impl.h"

gd_status gd_splu_analyze(const gd_pattern *a, gd_splu_symbolic *s, gd_error *err)
{
    memset(s, 0, sizeof *s);
    klu_defaults(&s->common);
    gd_order_choice ch = {0};
    s->common.ordering = 3; /* gd_order_block: AMD or minimum degree per block */
    s->common.user_order = gd_order_block;
    s->common.user_data = &ch;
    s->sym = klu_analyze(a->n, a->colptr, a->rowind, &s->common);
    s->common.user_data = NULL;
    if (!s->sym)
        return gd_error_set(
            err,
            s->common.status == KLU_OUT_OF_MEMORY || ch.out_of_memory ? GD_ENOMEM : GD_ENUMERIC, "",
            0, 0, "", "", "sparse analysis failed (KLU status %d)", s->common.status);
    /* KLU leaves the flops of a user ordering unset; its own count for the blocks of 3
     * or fewer it orders naturally (klu_analyze.c) */
    double flops = ch.flops;
    for (int b = 0; b < s->sym->nblocks; b++) {
        double nk = s->sym->R[b + 1] - s->sym->R[b];
        if (nk <= 3) flops += nk * (nk - 1) / 2 + (nk - 1) * nk * (2 * nk - 1) / 6;
    }
    s->sym->est_flops = flops;
    s->nmd = ch.nmd;
    return GD_OK;
}

void gd_splu_symbolic_free(gd_splu_symbolic *s)
{
    if (s->sym) klu_free_symbolic(&s->sym, &s->common);
    s->sym = NULL;
}

int gd_splu_factor(gd_splu *lu, const gd_pattern *a, const gd_splu_symbolic *s, const double *x,
                   int is_complex, int row_scaling)
{
    memset(lu, 0, sizeof *lu);
    klu_defaults(&lu->common);
    if (!row_scaling) lu->common.scale = 0;
    lu->is_complex = is_complex;
    /* KLU takes non-const pointers but does not modify its inputs */
    klu_symbolic *sym = s->sym;
    if (is_complex)
        lu->num = klu_z_factor(a->colptr, a->rowind, (double *)x, sym, &lu->common);
    else
        lu->num = klu_factor(a->colptr, a->rowind, (double *)x, sym, &lu->common);
    if (!lu->num) return lu->common.status == KLU_OUT_OF_MEMORY ? -1 : 1;
    if (is_complex)
        klu_z_rcond(sym, lu->num, &lu->common);
    else
        klu_rcond(sym, lu->num, &lu->common);
    lu->rcond = lu->common.rcond;
    if (!(lu->rcond > 1e-14)) return 1;
    return 0;
}

int gd_splu_refactor(gd_splu *lu, const gd_pattern *a, const gd_splu_symbolic *s, const double *x)
{
    if (!lu->num) return 1;
    /* without row scaling, KLU's pass over the input only checks it, as the
     * factorisation already did for this pattern */
    if (lu->common.scale == 0) lu->common.scale = -1;
    int ok = lu->is_complex
                 ? klu_z_refactor(a->colptr, a->rowind, (double *)x, s->sym, lu->num, &lu->common)
                 : klu_refactor(a->colptr, a->rowind, (double *)x, s->sym, lu->num, &lu->common);
    if (!ok) return lu->common.status == KLU_OUT_OF_MEMORY ? -1 : 1;
    if (lu->is_complex)
        klu_z_rcond(s->sym, lu->num, &lu->common);
    else
        klu_rcond(s->sym, lu->num, &lu->common);
    lu->rcond = lu->common.rcond;
    return lu->rcond > 1e-14 ? 0 : 1;
}

void gd_splu_solve(gd_splu *lu, const gd_splu_symbolic *s, int n, int nrhs, double *b)
{
    if (lu->is_complex)
        klu_z_solve(s->sym, lu->num, n, nrhs, b, &lu->common);
    else
        klu_solve(s->sym, lu->num, n, nrhs, b, &lu->common);
}

void gd_splu_free(gd_splu *lu)
{
    if (lu->num) {
        if (lu->is_complex)
            klu_z_free_numeric(&lu->num, &lu->common);
        else
            klu_free_numeric(&lu->num, &lu->common);
    }
    lu->num = NULL;
}
