/* Modal analysis on dense matrices (LAPACK). Massless DOFs are condensed statically
 * (Guyan) when they carry no damping; the state-space form follows 004 Eqs. 5-13 but is
 * solved as the standard problem of the mass-normalised companion matrix, whose left
 * eigenvectors give the physical left eigenvectors directly. */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/modal.h"
#include "modal_internal.h"

#define PI 3.14159265358979323846

const char *const gd_whirl_names[4] = {"none", "forward", "backward", "mixed"};

void gd_modal_options_default(gd_modal_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->kind = GD_MODAL_AUTO;
    opt->want_left = 1;
}

void gd_modal_free(gd_modal_result *r)
{
    if (!r) return;
    free(r->modes);
    free(r->shape_re);
    free(r->shape_im);
    free(r->left_re);
    free(r->left_im);
    free(r->energy_by_component);
    free(r);
}

/* ---- static condensation of massless DOFs ---- */

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

/* ---- per-mode properties ---- */

static gd_whirl mode_whirl(const gd_system *sys, const double *re, const double *im)
{
    const gd_model *m = sys->model;
    double maxr = 0;
    for (int node = 0; node < m->nnodes; node++) {
        int ix = gd_system_dof(sys, node, GD_X), iy = gd_system_dof(sys, node, GD_Y);
        if (ix < 0 || iy < 0) continue;
        double complex X = re[ix] + I * im[ix], Y = re[iy] + I * im[iy];
        double r = cabs(X + I * Y) + cabs(X - I * Y);
        if (r > maxr) maxr = r;
    }
    if (!(maxr > 0)) return GD_WHIRL_NONE;
    int fwd = 0, bwd = 0;
    for (int node = 0; node < m->nnodes; node++) {
        int ix = gd_system_dof(sys, node, GD_X), iy = gd_system_dof(sys, node, GD_Y);
        if (ix < 0 || iy < 0) continue;
        double complex X = re[ix] + I * im[ix], Y = re[iy] + I * im[iy];
        /* x + i y = (X + iY)/2 e^{iwt} + conj(X - iY)/2 e^{-iwt}: forward and backward
         * circular components (000 Eqs. 2.5-2.8) */
        double rf = cabs(X + I * Y), rb = cabs(X - I * Y);
        if (rf + rb < 1e-3 * maxr) continue;
        if (m->shafts[m->nodes[node].shaft].speed_ratio < 0) {
            double t = rf;
            rf = rb;
            rb = t;
        }
        double ell = (rf - rb) / (rf + rb);
        if (ell > 1e-3) fwd = 1;
        if (ell < -1e-3) bwd = 1;
    }
    if (fwd && bwd) return GD_WHIRL_MIXED;
    if (fwd) return GD_WHIRL_FORWARD;
    if (bwd) return GD_WHIRL_BACKWARD;
    return GD_WHIRL_NONE;
}

void gd_mode_finish(const gd_system *sys, double speed, gd_mode *md, const double *re,
                    const double *im, double *comp_share)
{
    int nc = sys->ncomponents;
    double by_motion[GD_NMOTIONS];
    double *by_comp = comp_share;
    double total = gd_system_strain_energy(sys, speed, re, im, by_motion, by_comp);
    md->dominant_motion = GD_MOTION_LATERAL;
    md->dominant_component = -1;
    if (md->rigid_body || !(total > 0)) {
        for (int k = 0; k < GD_NMOTIONS; k++)
            md->energy_share[k] = 0;
        for (int c = 0; c < nc; c++)
            by_comp[c] = 0;
        /* a rigid mode is named by how it moves: the largest kinetic DOF type */
        double ke[GD_NMOTIONS] = {0};
        for (int i = 0; i < sys->ndof; i++) {
            double a = re[i] * re[i] + (im ? im[i] * im[i] : 0);
            gd_dof d = sys->dof_type[i];
            int mo = d == GD_RZ                   ? GD_MOTION_TORSIONAL
                     : d == GD_Z                  ? GD_MOTION_AXIAL
                     : (d == GD_RX || d == GD_RY) ? GD_MOTION_TILT
                                                  : GD_MOTION_LATERAL;
            for (int k = sys->M.colptr[i]; k < sys->M.colptr[i + 1]; k++)
                if (sys->M.rowind[k] == i) ke[mo] += sys->M.values[k] * a;
        }
        int best = 0;
        for (int k = 1; k < GD_NMOTIONS; k++)
            if (ke[k] > ke[best]) best = k;
        md->dominant_motion = (gd_motion)best;
    } else {
        int best = 0;
        for (int k = 0; k < GD_NMOTIONS; k++) {
            md->energy_share[k] = by_motion[k] / total;
            if (by_motion[k] > by_motion[best]) best = k;
        }
        md->dominant_motion = (gd_motion)best;
        int bc = 0;
        for (int c = 0; c < nc; c++) {
            by_comp[c] /= total;
            if (by_comp[c] > by_comp[bc]) bc = c;
        }
        md->dominant_component = nc > 0 ? bc : -1;
    }
    /* whirl is relative to the spin; at rest there is no direction to compare with */
    md->whirl = speed != 0.0 ? mode_whirl(sys, re, im) : GD_WHIRL_NONE;
    /* no lateral motion to speak of: no whirl */
    if (!md->rigid_body && total > 0 && md->energy_share[GD_MOTION_LATERAL] < 1e-6 &&
        md->energy_share[GD_MOTION_TILT] < 1e-6)
        md->whirl = GD_WHIRL_NONE;
}

/* Scales a complex vector so its largest entry is 1 + 0i; returns the divisor. */
double complex gd_normalise_max(double *re, double *im, int n)
{
    int best = 0;
    double bm = -1;
    for (int i = 0; i < n; i++) {
        double a = re[i] * re[i] + im[i] * im[i];
        if (a > bm * (1 + 1e-12)) {
            bm = a;
            best = i;
        }
    }
    double complex s = re[best] + I * im[best];
    if (cabs(s) == 0) return 1.0;
    /* times 1/s = conj(s) / |s|^2: one division instead of one per entry */
    double ir = re[best] / bm, ii = -im[best] / bm;
    for (int i = 0; i < n; i++) {
        double zr = re[i] * ir - im[i] * ii, zi = re[i] * ii + im[i] * ir;
        re[i] = zr;
        im[i] = zi;
    }
    re[best] = 1.0;
    im[best] = 0.0;
    return s;
}

static int is_symmetric(const double *A, int n)
{
    double mx = 0;
    for (size_t k = 0; k < (size_t)n * n; k++)
        if (fabs(A[k]) > mx) mx = fabs(A[k]);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < j; i++)
            if (fabs(A[i + (size_t)j * n] - A[j + (size_t)i * n]) > 1e-12 * mx) return 0;
    return 1;
}

static int any_nonzero(const double *A, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (A[k] != 0.0) return 1;
    return 0;
}

gd_status gd_modal_solve(const gd_system *sys, const gd_modal_options *opt, gd_modal_result **out,
                         gd_error *err)
{
    *out = NULL;
    int N = sys->ndof;
    size_t nn = (size_t)N * N;
    double *M = malloc(nn * sizeof *M), *D = malloc(nn * sizeof *D), *K = malloc(nn * sizeof *K);
    gd_condense cond = {0};
    gd_status st = GD_OK;
    if (!M || !D || !K) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce the model size",
                          "out of memory for dense %d x %d matrices", N, N);
        goto done;
    }
    gd_system_dense(sys, opt->speed, M, D, K);
    int damped = opt->kind == GD_MODAL_DAMPED || (opt->kind == GD_MODAL_AUTO && any_nonzero(D, nn));
    if (opt->kind == GD_MODAL_UNDAMPED) memset(D, 0, nn * sizeof *D);
    if (!is_symmetric(K, N)) damped = 1; /* cross-coupled bearings: general problem */
    if ((st = gd_condense_setup(sys, K, damped ? D : NULL, &cond, err))) goto done;
    if (damped)
        st = gd_modal_state_space(sys, opt, &cond, M, D, K, out, err);
    else
        st = gd_modal_undamped(sys, opt, &cond, M, K, out, err);
done:
    gd_condense_free(&cond);
    free(M);
    free(D);
    free(K);
    return st;
}
