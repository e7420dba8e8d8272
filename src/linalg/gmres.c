/* Matrix-free Arnoldi and restarted GMRES (Saad & Schultz, SIAM J. Sci. Stat. Comput. 7,
 * 1986) on an operator whose product may fail (shooting's monodromy-vector products are
 * integrations of a period: linalg_impl.h, gd_op_try_fn). Modified Gram-Schmidt, the
 * least-squares problem by Givens rotations. SUNDIALS' SPGMR (linked for transient)
 * solves the same problem but differs in its rotations and restarts, and so in the last
 * bits of every shooting result (docs/architecture.md, "periodic"); this keeps them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"

int gd_arnoldi(gd_op_try_fn op, void *ctx, int n, const double *v0, int m, double *V, double *H,
               int *steps, double tol, double *x)
{
    const int N = n, ld = m + 1;
    double beta = 0.0;
    for (int i = 0; i < N; i++)
        beta += v0[i] * v0[i];
    beta = sqrt(beta);
    *steps = 0;
    if (x) memset(x, 0, (size_t)N * sizeof *x);
    if (beta == 0.0) return 0;
    /* cs, sn, g and a rotated copy of one column of H (m + 2) */
    double *cs = malloc(((size_t)3 * (m + 1) + (size_t)m + 2) * sizeof *cs), *sn = cs + m + 1,
           *g = sn + m + 1, *t = g + m + 1;
    if (!cs) return 2;
    memset(g, 0, (size_t)(m + 1) * sizeof *g);
    g[0] = beta;
    memset(H, 0, (size_t)ld * m * sizeof *H);
    for (int i = 0; i < N; i++)
        V[i] = v0[i] / beta;
    int j = 0, rc = 0;
    for (; j < m; j++) {
        double *w = V + (size_t)(j + 1) * N;
        if (op(ctx, V + (size_t)j * N, w)) {
            rc = 1;
            break;
        }
        for (int l = 0; l <= j; l++) { /* modified Gram-Schmidt */
            double hij = 0.0;
            for (int i = 0; i < N; i++)
                hij += w[i] * V[(size_t)l * N + i];
            H[(size_t)j * ld + l] = hij;
            for (int i = 0; i < N; i++)
                w[i] -= hij * V[(size_t)l * N + i];
        }
        double hn = 0.0;
        for (int i = 0; i < N; i++)
            hn += w[i] * w[i];
        hn = sqrt(hn);
        H[(size_t)j * ld + j + 1] = hn;
        if (hn > 0.0)
            for (int i = 0; i < N; i++)
                w[i] /= hn;
        if (x) {
            /* the least-squares problem by Givens rotations, on a copy of column j */
            double *c = H + (size_t)j * ld;
            memcpy(t, c, (size_t)(j + 2) * sizeof *t);
            for (int l = 0; l < j; l++) {
                double a = cs[l] * t[l] + sn[l] * t[l + 1];
                t[l + 1] = -sn[l] * t[l] + cs[l] * t[l + 1];
                t[l] = a;
            }
            double r = hypot(t[j], t[j + 1]);
            cs[j] = r > 0 ? t[j] / r : 1.0;
            sn[j] = r > 0 ? t[j + 1] / r : 0.0;
            g[j + 1] = -sn[j] * g[j];
            g[j] = cs[j] * g[j];
            /* H keeps the unrotated columns: the triangle is rebuilt from them below */
            if (fabs(g[j + 1]) <= tol * beta || hn == 0.0) {
                j++;
                break;
            }
        } else if (hn == 0.0) {
            j++;
            break;
        }
    }
    *steps = j;
    if (x && j > 0 && !rc) {
        /* R y = g: the rotations applied again to H's first j columns */
        double *R = malloc((size_t)(j + 1) * j * sizeof *R), *yy = malloc((size_t)j * sizeof *yy);
        if (!R || !yy) {
            rc = 2;
        } else {
            for (int c = 0; c < j; c++) {
                double *col = R + (size_t)c * (j + 1);
                memcpy(col, H + (size_t)c * ld,
                       (size_t)(c + 2 < j + 1 ? c + 2 : j + 1) * sizeof *col);
                for (int l = 0; l < c; l++) {
                    double a = cs[l] * col[l] + sn[l] * col[l + 1];
                    col[l + 1] = -sn[l] * col[l] + cs[l] * col[l + 1];
                    col[l] = a;
                }
                col[c] = cs[c] * col[c] + sn[c] * col[c + 1];
            }
            for (int r = j - 1; r >= 0; r--) {
                double sum = g[r];
                for (int c = r + 1; c < j; c++)
                    sum -= R[(size_t)c * (j + 1) + r] * yy[c];
                yy[r] = R[(size_t)r * (j + 1) + r] != 0 ? sum / R[(size_t)r * (j + 1) + r] : 0.0;
            }
            for (int c = 0; c < j; c++)
                for (int i = 0; i < N; i++)
                    x[i] += yy[c] * V[(size_t)c * N + i];
        }
        free(R);
        free(yy);
    }
    free(cs);
    return rc;
}

int gd_gmres(gd_op_try_fn op, void *ctx, int n, int m, const double *b, double *x, double tol,
             double stop2, int cycles)
{
    double *V = malloc(((size_t)n * (m + 1) + (size_t)(m + 1) * m + 3 * (size_t)n) * sizeof *V);
    if (!V) return 2;
    double *H = V + (size_t)n * (m + 1), *r = H + (size_t)(m + 1) * m, *dx = r + n, *w = dx + n;
    memcpy(r, b, (size_t)n * sizeof *r);
    memset(x, 0, (size_t)n * sizeof *x);
    int rc = 0;
    for (int cyc = 0; cyc < cycles; cyc++) {
        int steps;
        if ((rc = gd_arnoldi(op, ctx, n, r, m, V, H, &steps, tol, dx))) goto done;
        for (int i = 0; i < n; i++)
            x[i] += dx[i];
        if (cyc == cycles - 1) break;
        /* b - A x */
        if (op(ctx, x, w)) {
            rc = 1;
            goto done;
        }
        double nb = 0.0, n0 = 0.0;
        for (int i = 0; i < n; i++) {
            r[i] = b[i] - w[i];
            nb += r[i] * r[i];
            n0 += b[i] * b[i];
        }
        if (nb <= stop2 * n0) break;
    }
done:
    free(V);
    return rc;
}
