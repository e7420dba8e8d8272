/* Static (Guyan) condensation of a system's massless DOFs on dense matrices: the DOFs
 * with no inertia are eliminated through K_ss u_s = -K_sm u_m, which is exact for the
 * undamped problem and for damping that does not act on them. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "system/system_impl.h"

void gd_condense_free(gd_condense *c)
{
    free(c->master);
    free(c->slave);
    free(c->kss_lu);
    free(c->ipiv);
    free(c->ksm);
    free(c->kms_t);
    memset(c, 0, sizeof *c);
}

static double *submatrix(const double *A, int N, const int *rows, int nr, const int *cols, int nc)
{
    double *S = malloc((size_t)(nr > 0 ? nr : 1) * (size_t)(nc > 0 ? nc : 1) * sizeof *S);
    if (!S) return NULL;
    for (int j = 0; j < nc; j++)
        for (int i = 0; i < nr; i++)
            S[i + (size_t)j * nr] = A[rows[i] + (size_t)cols[j] * N];
    return S;
}

gd_status gd_condense_setup(const gd_system *sys, const double *K, const double *D, gd_condense *c,
                            gd_error *err)
{
    int N = sys->ndof;
    memset(c, 0, sizeof *c);
    c->N = N;
    c->master = malloc((size_t)N * sizeof *c->master);
    c->slave = malloc((size_t)(sys->nmassless > 0 ? sys->nmassless : 1) * sizeof *c->slave);
    if (!c->master || !c->slave) goto nomem;
    for (int i = 0; i < N; i++) {
        if (sys->massless[i])
            c->slave[c->ns++] = i;
        else
            c->master[c->nm++] = i;
    }
    if (c->ns == 0) return GD_OK;
    char label[160];
    if (D)
        for (int k = 0; k < c->ns; k++)
            for (int j = 0; j < N; j++) {
                int s = c->slave[k];
                if (D[s + (size_t)j * N] != 0.0 || D[j + (size_t)s * N] != 0.0) {
                    gd_system_dof_label(sys, s, label, sizeof label);
                    const gd_loc *loc = &sys->model->nodes[sys->dof_node[s]].loc;
                    gd_error_set(err, GD_EINPUT, sys->model->file, loc->line, loc->column, label,
                                 "give the node a mass or inertia (a disk), or remove the "
                                 "damper on it",
                                 "DOF %s has damping or gyroscopic terms but no mass", label);
                    gd_condense_free(c);
                    return GD_EINPUT;
                }
            }
    c->kss_lu = submatrix(K, N, c->slave, c->ns, c->slave, c->ns);
    c->ksm = submatrix(K, N, c->slave, c->ns, c->master, c->nm);
    double *kms = submatrix(K, N, c->master, c->nm, c->slave, c->ns);
    c->ipiv = malloc((size_t)c->ns * sizeof *c->ipiv);
    if (!c->kss_lu || !c->ksm || !kms || !c->ipiv) {
        free(kms);
        goto nomem;
    }
    /* transpose K_ms for the left-vector expansion */
    c->kms_t = malloc((size_t)c->ns * (size_t)c->nm * sizeof *c->kms_t);
    if (!c->kms_t) {
        free(kms);
        goto nomem;
    }
    for (int i = 0; i < c->nm; i++)
        for (int j = 0; j < c->ns; j++)
            c->kms_t[j + (size_t)i * c->ns] = kms[i + (size_t)j * c->nm];
    free(kms);
    lapack_int info = LAPACKE_dgetrf(LAPACK_COL_MAJOR, c->ns, c->ns, c->kss_lu, c->ns, c->ipiv);
    double maxdiag = 0, mindiag = INFINITY;
    for (int k = 0; k < c->ns; k++) {
        double v = fabs(c->kss_lu[k + (size_t)k * c->ns]);
        if (v > maxdiag) maxdiag = v;
        if (v < mindiag) mindiag = v;
    }
    if (info != 0 || !(mindiag > 1e-13 * maxdiag)) {
        int bad = c->slave[info > 0 ? info - 1 : 0];
        gd_system_dof_label(sys, bad, label, sizeof label);
        const gd_loc *loc = &sys->model->nodes[sys->dof_node[bad]].loc;
        gd_error_set(err, GD_EINPUT, sys->model->file, loc->line, loc->column, label,
                     "give the node a mass or inertia, or a spring that holds it",
                     "the massless DOFs cannot be condensed: DOF %s has no mass and is not "
                     "held by any stiffness",
                     label);
        gd_condense_free(c);
        return GD_EINPUT;
    }
    return GD_OK;
nomem:
    gd_condense_free(c);
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
}

/* Reduced matrix A_mm - A_ms K_ss^-1 K_sm for K; plain A_mm for M and D. */
double *gd_condense_matrix(const gd_condense *c, const double *A, int is_stiffness)
{
    int N = c->N, nm = c->nm, ns = c->ns;
    double *R = submatrix(A, N, c->master, nm, c->master, nm);
    if (!R || !is_stiffness || ns == 0) return R;
    double *X = malloc((size_t)ns * (size_t)nm * sizeof *X);
    double *Ams = submatrix(A, N, c->master, nm, c->slave, ns);
    if (!X || !Ams) {
        free(X);
        free(Ams);
        free(R);
        return NULL;
    }
    memcpy(X, c->ksm, (size_t)ns * (size_t)nm * sizeof *X);
    LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', ns, nm, c->kss_lu, ns, c->ipiv, X, ns);
    for (int j = 0; j < nm; j++)
        for (int k = 0; k < ns; k++) {
            double x = X[k + (size_t)j * ns];
            if (x == 0.0) continue;
            for (int i = 0; i < nm; i++)
                R[i + (size_t)j * nm] -= Ams[i + (size_t)k * nm] * x;
        }
    free(X);
    free(Ams);
    return R;
}

/* Full vector from master values: slaves u_s = -K_ss^-1 K_sm u_m (or, for left
 * vectors, -K_ss^-T K_ms^T v_m). */
void gd_condense_expand(const gd_condense *c, const double *um, double *u, int left, double *work)
{
    for (int i = 0; i < c->nm; i++)
        u[c->master[i]] = um[i];
    if (c->ns == 0) return;
    const double *B = left ? c->kms_t : c->ksm;
    for (int k = 0; k < c->ns; k++) {
        double s = 0;
        for (int i = 0; i < c->nm; i++)
            s += B[k + (size_t)i * c->ns] * um[i];
        work[k] = -s;
    }
    LAPACKE_dgetrs(LAPACK_COL_MAJOR, left ? 'T' : 'N', c->ns, 1, c->kss_lu, c->ns, c->ipiv, work,
                   c->ns);
    for (int k = 0; k < c->ns; k++)
        u[c->slave[k]] = work[k];
}
