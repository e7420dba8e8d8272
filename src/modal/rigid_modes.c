/* Rigid-body modes: the eigenvectors of lambda = 0 are the null space of K (at lambda
 * = 0, (lambda^2 M + lambda D + K) u = K u = 0, at any speed and damping), so they are
 * taken from it rather than from an eigensolver's vectors of the zero cluster, which is
 * defective in the state space (a Jordan block per rigid motion) and whose computed
 * vectors are numerically arbitrary there, even (nearly) parallel. The basis is then
 * rotated so that each vector moves in one motion type where the model allows it
 * (spin, axial, lateral, tilt), which is how the modes are labelled (gd_mode_finish). */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

int gd_null_space(const double *A, int n, double tol, double **basis)
{
    *basis = NULL;
    double *a = malloc((size_t)n * n * sizeof *a), *s = malloc((size_t)n * sizeof *s);
    double *vt = malloc((size_t)n * n * sizeof *vt), *sup = malloc((size_t)n * sizeof *sup);
    int r = -1;
    if (!a || !s || !vt || !sup) goto out;
    memcpy(a, A, (size_t)n * n * sizeof *a);
    if (LAPACKE_dgesvd(LAPACK_COL_MAJOR, 'N', 'A', n, n, a, n, s, NULL, 1, vt, n, sup) != 0)
        goto out;
    r = 0;
    for (int i = 0; i < n; i++)
        if (s[i] <= tol) r++;
    if (r == 0) goto out;
    /* the last r rows of V^T, as columns */
    if (!(*basis = malloc((size_t)n * r * sizeof **basis))) {
        r = -1;
        goto out;
    }
    for (int j = 0; j < r; j++)
        for (int i = 0; i < n; i++)
            (*basis)[i + (size_t)j * n] = vt[(n - r + j) + (size_t)i * n];
out:
    free(a);
    free(s);
    free(vt);
    free(sup);
    return r;
}

/* C (r x m) <- C X for an m x m X, through tmp (r x m). */
static void times(double *C, int r, int m, const double *X, double *tmp)
{
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, r, m, m, 1.0, C, r, X, m, 0.0, tmp, r);
    memcpy(C, tmp, (size_t)r * m * sizeof *C);
}

void gd_rigid_separate(const gd_system *sys, double *U, int r)
{
    int N = sys->ndof;
    if (r < 2) return;
    /* E_t(a, b) = sum over DOFs i of type t of M_ii U_ia U_ib: kinetic energy by
       motion type, the measure gd_mode_finish labels rigid modes with */
    double *E = calloc((size_t)GD_NMOTIONS * r * r, sizeof *E);
    double *C = calloc((size_t)r * r, sizeof *C), *out = malloc((size_t)r * r * sizeof *out);
    double *A = malloc((size_t)r * r * sizeof *A), *B = malloc((size_t)r * r * sizeof *B);
    double *w = malloc((size_t)r * sizeof *w), *tmp = malloc((size_t)N * r * sizeof *tmp);
    if (!E || !C || !out || !A || !B || !w || !tmp) goto done;
    for (int i = 0; i < N; i++) {
        double m = 0;
        for (int k = sys->M.colptr[i]; k < sys->M.colptr[i + 1]; k++)
            if (sys->M.rowind[k] == i) m = sys->M.values[k];
        double *Et = E + (size_t)gd_dof_motion(sys->dof_type[i]) * r * r;
        for (int a = 0; a < r; a++)
            for (int b = 0; b < r; b++)
                Et[a + (size_t)b * r] += m * U[i + (size_t)a * N] * U[i + (size_t)b * N];
    }
    /* C: the remaining combinations (r x m), from the identity */
    for (int a = 0; a < r; a++)
        C[a + (size_t)a * r] = 1;
    int m = r, done_cols = 0;
    static const gd_motion order[] = {GD_MOTION_TORSIONAL, GD_MOTION_AXIAL, GD_MOTION_LATERAL,
                                      GD_MOTION_TILT};
    for (int t = 0; t < 4 && m > 1; t++) {
        /* max of (c^T E_t c) / (c^T T c) over the remaining span: the generalized
           eigenproblem C^T E_t C x = mu C^T T C x, T = sum of the E's */
        for (int a = 0; a < m; a++)
            for (int b = 0; b < m; b++) {
                double ea = 0, ta = 0;
                for (int p = 0; p < r; p++)
                    for (int q = 0; q < r; q++) {
                        double cc = C[p + (size_t)a * r] * C[q + (size_t)b * r];
                        for (int s = 0; s < GD_NMOTIONS; s++) {
                            double e = E[(size_t)s * r * r + p + (size_t)q * r] * cc;
                            ta += e;
                            if (s == (int)order[t]) ea += e;
                        }
                    }
                A[a + (size_t)b * m] = ea;
                B[a + (size_t)b * m] = ta;
            }
        if (LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'V', 'U', m, A, m, B, m, w) != 0) break;
        times(C, r, m, A, tmp); /* ascending mu: the type's own motions are last */
        int own = 0;
        while (own < m && w[m - 1 - own] > 0.5)
            own++;
        for (int j = m - own; j < m; j++)
            memcpy(out + (size_t)done_cols++ * r, C + (size_t)j * r, (size_t)r * sizeof *C);
        m -= own;
    }
    for (int j = 0; j < m; j++)
        memcpy(out + (size_t)done_cols++ * r, C + (size_t)j * r, (size_t)r * sizeof *C);
    times(U, N, r, out, tmp);
done:
    free(E);
    free(C);
    free(out);
    free(A);
    free(B);
    free(w);
    free(tmp);
}

/* y = S x for values s on the pattern */
static void pattern_mul(const gd_pattern *p, const double *s, const double *x, double *y)
{
    memset(y, 0, (size_t)p->n * sizeof *y);
    for (int j = 0; j < p->n; j++)
        for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++)
            y[p->rowind[q]] += s[q] * x[j];
}

int gd_rigid_null_sparse(const gd_dynmat *a, const gd_splu_symbolic *sym, const double *k,
                         double sigma, double tol, double *U, int r0)
{
    int n = a->pat.n, nnz = a->pat.nnz, r = -1;
    double *x = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *x);
    double *Z = malloc((size_t)n * r0 * sizeof *Z), *y = malloc((size_t)n * sizeof *y);
    gd_splu lu = {0};
    if (!x || !Z || !y) goto out;
    for (int q = 0; q < nnz; q++)
        x[q] = k[q] + sigma * a->m[q];
    if (gd_splu_factor(&lu, &a->pat, sym, x, 0, 1) != 0) goto out;
    int m = r0;
    for (int it = 0; it < 3; it++) {
        /* U <- (K + sigma M)^-1 M U: the null space of K by 1/sigma, a mode at w by
           1/(sigma + w^2) */
        for (int j = 0; j < m; j++)
            pattern_mul(&a->pat, a->m, U + (size_t)j * n, Z + (size_t)j * n);
        gd_splu_solve(&lu, sym, n, m, Z);
        /* M-orthonormal, dropping what is dependent on the columns before it */
        int kept = 0;
        for (int j = 0; j < m; j++) {
            double *z = Z + (size_t)j * n;
            double n0 = 0;
            for (int i = 0; i < n; i++)
                n0 += z[i] * z[i];
            for (int pass = 0; pass < 2; pass++)
                for (int c = 0; c < kept; c++) {
                    const double *u = U + (size_t)c * n;
                    pattern_mul(&a->pat, a->m, u, y);
                    double d = 0;
                    for (int i = 0; i < n; i++)
                        d += z[i] * y[i];
                    for (int i = 0; i < n; i++)
                        z[i] -= d * u[i];
                }
            pattern_mul(&a->pat, a->m, z, y);
            double mm = 0, nz = 0;
            for (int i = 0; i < n; i++) {
                mm += z[i] * y[i];
                nz += z[i] * z[i];
            }
            if (!(mm > 0) || nz <= 1e-16 * n0) continue;
            double sc = 1 / sqrt(mm);
            for (int i = 0; i < n; i++)
                U[i + (size_t)kept * n] = z[i] * sc;
            kept++;
        }
        m = kept;
    }
    /* the null space: |K u| <= tol |M u| (tol = the rigid |lambda|^2) */
    r = 0;
    for (int j = 0; j < m; j++) {
        const double *u = U + (size_t)j * n;
        double kn = 0, mn = 0;
        pattern_mul(&a->pat, k, u, y);
        for (int i = 0; i < n; i++)
            kn += y[i] * y[i];
        pattern_mul(&a->pat, a->m, u, y);
        for (int i = 0; i < n; i++)
            mn += y[i] * y[i];
        if (sqrt(kn) <= tol * sqrt(mn)) {
            if (r != j) memcpy(U + (size_t)r * n, u, (size_t)n * sizeof *U);
            r++;
        }
    }
out:
    gd_splu_free(&lu);
    free(x);
    free(Z);
    free(y);
    return r;
}

void gd_rigid_modes_fill(const gd_system *sys, double speed, gd_modal_result *res, const double *U,
                         int kr)
{
    int N = sys->ndof;
    for (int m = 0; m < kr; m++) {
        gd_mode *md = &res->modes[m];
        double *re = res->shape_re + (size_t)m * N, *im = res->shape_im + (size_t)m * N;
        md->rigid_body = 1;
        memcpy(re, U + (size_t)m * N, (size_t)N * sizeof *re);
        gd_normalise_max(re, im, N);
        gd_mode_finish(sys, speed, md, re, im,
                       res->energy_by_component + (size_t)m * sys->ncomponents);
    }
}
