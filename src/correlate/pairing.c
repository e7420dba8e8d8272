/* Measured modes against the model's: the undamped modes at rest (the FE frequencies
 * of [MMT2018] Tables 4-5), paired in order by dynamic programming over the cost
 * |ln(f_test / f_model)| + (1 - MAC), each model mode used once. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "correlate/correlate_impl.h"
#include "geardyn/ema.h"

void gd_corr_table_free(gd_corr_table *t)
{
    if (!t) return;
    free(t->pairs);
    free(t);
}

gd_status gd_corr_model_modes(const gd_system *sys, gd_corr_modes *out, gd_error *err)
{
    memset(out, 0, sizeof *out);
    int n = sys->ndof;
    double *M = malloc((size_t)n * n * sizeof *M), *K = malloc((size_t)n * n * sizeof *K);
    double *w = malloc((size_t)n * sizeof *w);
    if (!M || !K || !w) {
        free(M), free(K), free(w);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    gd_system_dense(sys, 0, M, NULL, K);
    /* K phi = lambda M phi; dsygv returns M-orthonormal vectors: phi^T M phi = 1 */
    lapack_int info = LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'V', 'L', n, K, n, M, n, w);
    free(M);
    if (info) {
        free(K), free(w);
        return gd_error_set(err, GD_ENUMERIC, "", 0, 0, "modes",
                            "the model needs mass on every DOF (no massless DOF)",
                            "the undamped eigenproblem failed (LAPACK info %d)", (int)info);
    }
    /* elastic modes: leave out the rigid-body ones (lambda ~ 0 against the largest) */
    double lmax = fabs(w[n - 1]);
    out->n = 0;
    out->ndof = n;
    out->lambda = w;
    out->phi = K;
    int k = 0;
    for (int j = 0; j < n; j++) {
        if (w[j] <= 1e-10 * lmax) continue;
        if (k != j) {
            w[k] = w[j];
            memmove(K + (size_t)k * n, K + (size_t)j * n, (size_t)n * sizeof *K);
        }
        k++;
    }
    out->n = k;
    return GD_OK;
}

void gd_corr_modes_free(gd_corr_modes *m)
{
    free(m->lambda);
    free(m->phi);
    memset(m, 0, sizeof *m);
}

double gd_corr_hz(const gd_corr_modes *m, int j)
{
    return sqrt(m->lambda[j]) / (2 * M_PI);
}

gd_status gd_corr_pair_modes(const gd_corr_modes *md, const gd_measured_modes *mm,
                             gd_corr_table **out, gd_error *err)
{
    *out = NULL;
    int nt = mm->nmodes, na = md->n;
    if (nt < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "modes", "measure at least one mode",
                            "no measured mode to correlate");
    if (na < nt)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "modes",
                            "the model has fewer elastic modes than were measured",
                            "%d measured modes, %d model modes", nt, na);
    /* cost[i][j] and the order-keeping assignment: D[i][j] = best cost of pairing the
     * first i measured modes within the first j model modes */
    double *cost = malloc((size_t)nt * na * sizeof *cost);
    double *mac = malloc((size_t)nt * na * sizeof *mac);
    double *D = malloc((size_t)(nt + 1) * (na + 1) * sizeof *D);
    double *vr = malloc((size_t)(mm->ndofs + 1) * sizeof *vr);
    gd_corr_table *t = calloc(1, sizeof *t);
    if (t) t->pairs = calloc((size_t)nt, sizeof *t->pairs);
    if (!cost || !mac || !D || !vr || !t || !t->pairs) {
        free(cost), free(mac), free(D), free(vr), gd_corr_table_free(t);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    for (int i = 0; i < nt; i++)
        for (int j = 0; j < na; j++) {
            double c = fabs(log(mm->hz[i] / gd_corr_hz(md, j))), a = NAN;
            if (mm->ndofs > 1 && mm->shape_re) {
                for (int d = 0; d < mm->ndofs; d++)
                    vr[d] = mm->sign[d] * md->phi[(size_t)j * md->ndof + mm->dof[d]];
                a = gd_ema_mac(mm->ndofs, mm->shape_re + (size_t)i * mm->ndofs,
                               mm->shape_im ? mm->shape_im + (size_t)i * mm->ndofs : NULL, vr,
                               NULL);
                c += 1 - a;
            }
            cost[i * na + j] = c;
            mac[i * na + j] = a;
        }
    /* measured modes in ascending frequency keep their order in the pairing */
    int *ord = malloc((size_t)nt * sizeof *ord);
    for (int i = 0; i < nt; i++)
        ord[i] = i;
    for (int i = 1; i < nt; i++)
        for (int k = i; k > 0 && mm->hz[ord[k]] < mm->hz[ord[k - 1]]; k--) {
            int tmp = ord[k];
            ord[k] = ord[k - 1];
            ord[k - 1] = tmp;
        }
#define DD(i, j) D[(size_t)(i) * (na + 1) + (j)]
    for (int j = 0; j <= na; j++)
        DD(0, j) = 0;
    for (int i = 1; i <= nt; i++) {
        DD(i, i - 1) = INFINITY;
        for (int j = i; j <= na; j++) {
            double take = DD(i - 1, j - 1) + cost[ord[i - 1] * na + j - 1];
            double skip = j > i ? DD(i, j - 1) : INFINITY;
            DD(i, j) = take <= skip ? take : skip;
        }
    }
    double ss = 0;
    for (int i = nt, j = na; i > 0; j--) {
        if (j > i && DD(i, j) == DD(i, j - 1)) continue;
        int m = ord[i - 1];
        gd_corr_pair *p = &t->pairs[m];
        p->measured = m;
        p->model = j - 1;
        p->f_test = mm->hz[m];
        p->f_model = gd_corr_hz(md, j - 1);
        p->diff_pct = 100 * (p->f_model - p->f_test) / p->f_model;
        p->mac = mac[m * na + j - 1];
        p->zeta_test = mm->zeta ? mm->zeta[m] : NAN;
        ss += p->diff_pct * p->diff_pct;
        i--;
    }
#undef DD
    t->npairs = nt;
    t->rms_pct = sqrt(ss / nt);
    free(cost), free(mac), free(D), free(vr), free(ord);
    *out = t;
    return GD_OK;
}

gd_status gd_correlate_modes(const gd_system *sys, const gd_measured_modes *mm, gd_corr_table **out,
                             gd_error *err)
{
    *out = NULL;
    gd_corr_modes md;
    gd_status st = gd_corr_model_modes(sys, &md, err);
    if (st) return st;
    st = gd_corr_pair_modes(&md, mm, out, err);
    gd_corr_modes_free(&md);
    return st;
}
