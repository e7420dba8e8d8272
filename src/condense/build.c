/* Building the condensation once (docs/condense.md): the damped, gyroscopic modes with
 * right and left eigenvectors ([MMT2018] Eqs. 9-15), the rigid-body modes M-orthonormal,
 * and the static correction of the discarded modes, W^T (K_e^+ - sum_kept -u v^T/lambda) W
 * ([CraigKurdila2006], residual flexibility), K_e^+ the elastic flexibility under inertia relief:
 * K x = P^T W with P^T = I - M R R^T (the load balanced by the rigid modes' inertia),
 * solved with one DOF per rigid mode held (chosen by a pivoted QR of R^T) and the rigid
 * part removed afterwards, x -= R R^T M x ([GeradinRixen2015] inertia relief). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "condense/condense_impl.h"
#include "geardyn/modal.h"
#include "linalg/linalg_impl.h"
#include "modal/modal_impl.h"
#include "system/system_impl.h"

void gd_condense_options_init(gd_condense_options *o)
{
    memset(o, 0, sizeof *o);
}

void gd_condense_destroy(gd_condensation *c)
{
    if (!c) return;
    free(c->lam);
    free(c->pair);
    free(c->U);
    free(c->Cm);
    free(c->Bm);
    free(c->R);
    free(c->Rc);
    free(c->Xres);
    free(c->G);
    free(c->A);
    free(c->B);
    free(c->C);
    free(c);
}

void gd_condense_info_get(const gd_condensation *c, gd_condense_info *info)
{
    *info = c->info;
}

/* y = A x, A dense N x N column-major. */
static void matvec(const double *A, int N, const double *x, double *y)
{
    memset(y, 0, (size_t)N * sizeof *y);
    for (int j = 0; j < N; j++) {
        double xj = x[j];
        if (xj == 0.0) continue;
        const double *a = A + (size_t)j * N;
        for (int i = 0; i < N; i++)
            y[i] += a[i] * xj;
    }
}

/* y = A^T x. */
static void matvec_t(const double *A, int N, const double *x, double *y)
{
    for (int j = 0; j < N; j++) {
        const double *a = A + (size_t)j * N;
        double s = 0;
        for (int i = 0; i < N; i++)
            s += a[i] * x[i];
        y[j] = s;
    }
}

/* The structure's matrices, dense (N x N column-major) or as values on a sparse pattern. */
typedef struct ops {
    int N;
    const double *Md, *Dd, *Kd;
    const gd_pattern *p;
    const double *m, *d, *k;
} ops;

/* y = A x (tr: A^T x) for A = M, D or K ('M', 'D', 'K'). */
static void apply(const ops *o, char which, int tr, const double *x, double *y)
{
    int N = o->N;
    if (!o->p) {
        const double *A = which == 'M' ? o->Md : which == 'D' ? o->Dd : o->Kd;
        if (tr)
            matvec_t(A, N, x, y);
        else
            matvec(A, N, x, y);
        return;
    }
    const double *v = which == 'M' ? o->m : which == 'D' ? o->d : o->k;
    memset(y, 0, (size_t)N * sizeof *y);
    for (int j = 0; j < N; j++)
        for (int q = o->p->colptr[j]; q < o->p->colptr[j + 1]; q++) {
            int i = o->p->rowind[q];
            if (tr)
                y[j] += v[q] * x[i];
            else
                y[i] += v[q] * x[j];
        }
}

static double maxabs(const double *x, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(x[i]));
    return m;
}

/* The rigid modes of mr, M-orthonormal (Gram-Schmidt twice), checked free of stiffness and
 * damping on both sides (K r = K^T r = D r = D^T r = 0), as the exact -r r^T / w^2 term
 * needs. */
static gd_status rigid_modes(gd_condensation *c, const gd_modal_result *mr, const ops *o, double *t,
                             double *t2, const char *file, gd_error *err)
{
    int N = c->N, nr = 0;
    for (int j = 0; j < mr->nmodes; j++)
        nr += mr->modes[j].rigid_body;
    c->nr = nr;
    if (!nr) return GD_OK;
    if (!(c->R = malloc((size_t)N * nr * sizeof *c->R)))
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    size_t nv = o->p ? (size_t)o->p->nnz : (size_t)N * N;
    double kn = maxabs(o->p ? o->k : o->Kd, nv), dn = maxabs(o->p ? o->d : o->Dd, nv);
    int b = 0;
    for (int j = 0; j < mr->nmodes; j++) {
        if (!mr->modes[j].rigid_body) continue;
        double *r = c->R + (size_t)b * N;
        memcpy(r, mr->shape_re + (size_t)j * N, (size_t)N * sizeof *r);
        for (int pass = 0; pass < 2; pass++)
            for (int a = 0; a < b; a++) {
                const double *ra = c->R + (size_t)a * N;
                apply(o, 'M', 0, r, t);
                double s = 0;
                for (int i = 0; i < N; i++)
                    s += ra[i] * t[i];
                for (int i = 0; i < N; i++)
                    r[i] -= s * ra[i];
            }
        apply(o, 'M', 0, r, t);
        double mm = 0;
        for (int i = 0; i < N; i++)
            mm += r[i] * t[i];
        double rn = maxabs(r, (size_t)N), bad = 0;
        apply(o, 'K', 0, r, t);
        apply(o, 'K', 1, r, t2);
        bad = fmax(maxabs(t, (size_t)N), maxabs(t2, (size_t)N)) / (kn * rn * N);
        apply(o, 'D', 0, r, t);
        apply(o, 'D', 1, r, t2);
        double badd =
            fmax(maxabs(t, (size_t)N), maxabs(t2, (size_t)N)) / ((dn > 0 ? dn : 1) * rn * N);
        if (!(mm > 0) || bad > 1e-8 || badd > 1e-8)
            return gd_error_set(err, GD_EINPUT, file, 0, 0, "damping",
                                "condense a model whose free motions carry no stiffness or "
                                "damping (e.g. no damping to ground on a free train)",
                                "rigid-body mode %d is not free of stiffness and damping "
                                "(K r, D r = %.2g, %.2g relative)",
                                b + 1, bad, badd);
        for (int i = 0; i < N; i++)
            r[i] /= sqrt(mm);
        b++;
    }
    return GD_OK;
}

static gd_status singular(gd_error *err, const char *file, int nr, double rcond)
{
    return gd_error_set(err, GD_ENUMERIC, file, 0, 0, "bearings",
                        "support the model (bearings or springs to ground) or remove the "
                        "unconstrained parts: only motions without stiffness and damping "
                        "(a free train's rotation) are allowed",
                        "the stiffness is singular beyond its %d rigid-body modes "
                        "(reciprocal condition %.2g)",
                        nr, rcond);
}

/* Yf (nf x nc) = the free rows of the solution of K' x = Y with K' the sparse K whose held
 * rows and columns are the identity (and Y's held rows 0). */
static gd_status sparse_held_solve(const ops *o, const int *held, const double *Y, int nc,
                                   const int *fr, int nf, double *Yf, const char *file,
                                   gd_error *err)
{
    const gd_pattern *p = o->p;
    int N = o->N;
    gd_splu_symbolic sym;
    gd_status st = gd_splu_analyze(p, &sym, err);
    if (st) return st;
    double *kk = malloc((size_t)p->nnz * sizeof *kk), *x = malloc((size_t)N * nc * sizeof *x);
    if (!kk || !x) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    for (int j = 0; j < N; j++)
        for (int q = p->colptr[j]; q < p->colptr[j + 1]; q++) {
            int i = p->rowind[q];
            kk[q] = held[i] || held[j] ? (i == j ? 1.0 : 0.0) : o->k[q];
        }
    for (int j = 0; j < N; j++)
        if (held[j] && p->diag[j] < 0) {
            st = singular(err, file, -1, 0);
            goto done;
        }
    for (int j = 0; j < nc; j++)
        for (int i = 0; i < N; i++)
            x[i + (size_t)j * N] = held[i] ? 0.0 : Y[i + (size_t)j * N];
    gd_splu lu;
    int rc = gd_splu_factor(&lu, p, &sym, kk, 0, 1);
    if (rc) {
        double rcond = lu.rcond;
        gd_splu_free(&lu);
        st = rc < 0 ? gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory")
                    : singular(err, file, N - nf, rcond);
        goto done;
    }
    gd_splu_solve(&lu, &sym, N, nc, x);
    gd_splu_free(&lu);
    for (int j = 0; j < nc; j++)
        for (int i = 0; i < nf; i++)
            Yf[i + (size_t)j * nf] = x[fr[i] + (size_t)j * N];
done:
    free(kk);
    free(x);
    gd_splu_symbolic_free(&sym);
    return st;
}

/* X = K_e^+ Y (N x nc, overwritten in place): the elastic static solution under inertia
 * relief (Y already balanced: R^T Y = 0). */
static gd_status elastic_solve(gd_condensation *c, const ops *o, double *Y, const char *file,
                               gd_error *err)
{
    int N = c->N, nc = c->nc, nr = c->nr, nf = N - nr;
    gd_status st = GD_OK;
    int *held = calloc((size_t)N, sizeof *held), *jpvt = calloc((size_t)N, sizeof *jpvt);
    int *fr = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *fr),
        *ipiv = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *ipiv);
    double *Rt = malloc((size_t)(nr > 0 ? nr : 1) * N * sizeof *Rt),
           *tau = malloc((size_t)(nr + 1) * sizeof *tau);
    size_t nk = o->p ? 1 : (size_t)(nf > 0 ? nf : 1) * (nf > 0 ? nf : 1);
    double *Kff = malloc(nk * sizeof *Kff);
    double *Yf = malloc((size_t)(nf > 0 ? nf : 1) * nc * sizeof *Yf),
           *t = malloc((size_t)N * sizeof *t);
    if (!held || !jpvt || !fr || !ipiv || !Rt || !tau || !Kff || !Yf || !t) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce the model size", "out of memory");
        goto done;
    }
    if (nr) { /* one held DOF per rigid mode: the pivots of a column-pivoted QR of R^T */
        for (int j = 0; j < N; j++)
            for (int b = 0; b < nr; b++)
                Rt[b + (size_t)j * nr] = c->R[j + (size_t)b * N];
        if (LAPACKE_dgeqp3(LAPACK_COL_MAJOR, nr, N, Rt, nr, jpvt, tau)) {
            st = gd_error_set(err, GD_ENUMERIC, file, 0, 0, "", "", "QR of the rigid modes failed");
            goto done;
        }
        for (int b = 0; b < nr; b++)
            held[jpvt[b] - 1] = 1;
    }
    for (int i = 0, k = 0; i < N; i++)
        if (!held[i]) fr[k++] = i;
    if (o->p) { /* sparse: the held rows and columns replaced by the identity, KLU */
        if ((st = sparse_held_solve(o, held, Y, nc, fr, nf, Yf, file, err))) goto done;
    } else {
        for (int j = 0; j < nf; j++)
            for (int i = 0; i < nf; i++)
                Kff[i + (size_t)j * nf] = o->Kd[fr[i] + (size_t)fr[j] * N];
        for (int j = 0; j < nc; j++)
            for (int i = 0; i < nf; i++)
                Yf[i + (size_t)j * nf] = Y[fr[i] + (size_t)j * N];
        double anorm = LAPACKE_dlange(LAPACK_COL_MAJOR, '1', nf, nf, Kff, nf), rcond = 0;
        int info = nf ? LAPACKE_dgetrf(LAPACK_COL_MAJOR, nf, nf, Kff, nf, ipiv) : 0;
        if (nf && !info) LAPACKE_dgecon(LAPACK_COL_MAJOR, '1', nf, Kff, nf, anorm, &rcond);
        if (info || (nf && !(rcond > 1e-14))) {
            st = singular(err, file, nr, rcond);
            goto done;
        }
        if (nf) LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', nf, nc, Kff, nf, ipiv, Yf, nf);
    }
    /* residual of K x = y, for the info */
    double res = 0, ymax = maxabs(Y, (size_t)N * nc);
    for (int j = 0; j < nc; j++) {
        double *x = Y + (size_t)j * N;       /* becomes the solution */
        memcpy(t, x, (size_t)N * sizeof *t); /* y */
        memset(x, 0, (size_t)N * sizeof *x);
        for (int i = 0; i < nf; i++)
            x[fr[i]] = Yf[i + (size_t)j * nf];
        double *kx = malloc((size_t)N * sizeof *kx);
        if (!kx) {
            st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
            goto done;
        }
        apply(o, 'K', 0, x, kx);
        for (int i = 0; i < N; i++)
            res = fmax(res, fabs(kx[i] - t[i]));
        /* x -= R R^T M x: the elastic part, M-orthogonal to the rigid modes */
        apply(o, 'M', 0, x, kx);
        for (int b = 0; b < nr; b++) {
            const double *r = c->R + (size_t)b * N;
            double s = 0;
            for (int i = 0; i < N; i++)
                s += r[i] * kx[i];
            for (int i = 0; i < N; i++)
                x[i] -= s * r[i];
        }
        free(kx);
    }
    c->info.static_check = ymax > 0 ? res / ymax : 0;
done:
    free(held);
    free(jpvt);
    free(fr);
    free(ipiv);
    free(Rt);
    free(tau);
    free(Kff);
    free(Yf);
    free(t);
    return st;
}

/* The held DOFs' rows and columns of the dense M, D, K cleared, K's diagonal there 1:
 * the clamped structure embedded in the full numbering (a held DOF's static solution and
 * every mode's shape there are 0). */
static void clamp_dense(int N, const int *held, double *M, double *D, double *K)
{
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            if (held[i] || held[j]) {
                size_t p = i + (size_t)j * N;
                M[p] = D[p] = 0.0;
                K[p] = i == j ? 1.0 : 0.0;
            }
}

/* The damped modes of the clamped structure (M, D, K from clamp_dense) with their left
 * vectors: the held DOFs join the statically condensed (massless) ones, eliminated with
 * K_sm = 0, i.e. held at 0 (the dense solver's Guyan step, src/system/condense.c). */
static gd_status clamped_modes(const gd_system *sys, const int *held, const gd_modal_options *mo,
                               const double *M, const double *D, const double *K,
                               gd_modal_result **mr, gd_error *err)
{
    const int N = sys->ndof;
    gd_system s = *sys; /* a view: the massless flags replaced */
    int *ml = malloc((size_t)N * sizeof *ml);
    if (!ml) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    s.nmassless = 0;
    for (int i = 0; i < N; i++) {
        ml[i] = sys->massless[i] || held[i];
        s.nmassless += ml[i];
    }
    s.massless = ml;
    gd_condense cond = {0};
    gd_status st = gd_condense_setup(&s, K, D, &cond, err);
    if (!st) st = gd_modal_state_space(&s, mo, &cond, M, D, K, mr, err);
    gd_condense_free(&cond);
    free(ml);
    return st;
}

/* v scaled to v^T (2 lambda M + D) u = 1 on the dense matrices (what the refinement does
 * on the sparse problem, left out for a clamped structure: its pattern is the free one's) */
static void normalise_left(int N, const double *M, const double *D, double complex lam,
                           const double complex *u, double complex *v)
{
    double complex s = 0;
    for (int j = 0; j < N; j++) {
        if (u[j] == 0) continue;
        for (int i = 0; i < N; i++)
            s += v[i] * (2.0 * lam * M[i + (size_t)j * N] + D[i + (size_t)j * N]) * u[j];
    }
    if (s != 0)
        for (int i = 0; i < N; i++)
            v[i] /= s;
}

gd_status gd_condense_build(const gd_system *sys, const gd_condense_coords *cc,
                            const gd_condense_options *opt, gd_condensation **out, gd_error *err)
{
    *out = NULL;
    const char *file = sys->model->file;
    int N = sys->ndof, nc = cc ? cc->n : 0;
    if (nc < 1)
        return gd_error_set(err, GD_EINPUT, file, 0, 0, "coordinates",
                            "add the meshes' or laws' coordinates (gd_condense_coords_meshes)",
                            "no coordinates to condense on");
    for (int e = 0; e < cc->nnz; e++)
        if (cc->dof[e] < 0 || cc->dof[e] >= N)
            return gd_error_set(err, GD_EINPUT, file, 0, 0, "coordinates",
                                "build the coordinates on this system",
                                "a coordinate names DOF %d, outside the %d DOFs", cc->dof[e], N);
    if (!isfinite(opt->speed) || opt->nmodes < 0)
        return gd_error_set(err, GD_EINPUT, file, 0, 0, isfinite(opt->speed) ? "nmodes" : "speed",
                            "give a finite speed and nmodes >= 0 (0: all)",
                            "bad condensation options (speed %g, nmodes %d)", opt->speed,
                            opt->nmodes);
    const int *held = opt->held;
    for (int e = 0; held && e < cc->nnz; e++)
        if (held[cc->dof[e]] && cc->a[e] != 0.0)
            return gd_error_set(err, GD_EINPUT, file, 0, 0, "coordinates",
                                "leave the held DOFs out of the coordinates",
                                "a coordinate acts on held DOF %d", cc->dof[e]);
    if (held && opt->method == GD_CONDENSE_SPARSE)
        return gd_error_set(err, GD_EINPUT, file, 0, 0, "method", "use the dense method",
                            "held DOFs need the dense condensation");
    int sparse =
        !held &&
        (opt->method == GD_CONDENSE_SPARSE ||
         (opt->method == GD_CONDENSE_AUTO && opt->nmodes > 0 && N > GD_CONDENSE_DENSE_MAX));
    if (sparse && opt->nmodes < 1)
        return gd_error_set(err, GD_EINPUT, file, 0, 0, "nmodes",
                            "give the number of modes to keep (the sparse method computes the "
                            "lowest ones only)",
                            "the sparse condensation needs nmodes > 0");
    size_t nn = sparse ? 1 : (size_t)N * N;
    gd_condensation *c = calloc(1, sizeof *c);
    double *M = malloc(nn * sizeof *M), *D = malloc(nn * sizeof *D), *K = malloc(nn * sizeof *K);
    double *W = calloc((size_t)N * nc, sizeof *W), *t = malloc((size_t)N * sizeof *t),
           *t2 = malloc((size_t)N * sizeof *t2);
    double *ks = NULL, *ds = NULL;
    gd_dynmat dm;
    int have_a = 0;
    gd_modal_result *mr = NULL;
    double complex *V = NULL;
    gd_status st = GD_OK;
    ops o = {N, M, D, K, NULL, NULL, NULL, NULL};
    if (!c || !M || !D || !K || !W || !t || !t2) {
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "reduce the model size",
                          "out of memory for dense %d x %d matrices", N, N);
        goto done;
    }
    c->N = N;
    c->nc = nc;
    for (int k = 0; k < nc; k++)
        for (int e = cc->start[k]; e < cc->start[k + 1]; e++)
            W[cc->dof[e] + (size_t)k * N] += cc->a[e];
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.speed = opt->speed;
    mo.kind = GD_MODAL_DAMPED; /* left vectors in one normalisation, damped or not */
    if (sparse) {
        /* the structure on its sparse pattern; the lowest modes by shift-invert Krylov
           (right vectors: the refinement finds the left ones), with room for a few rigid
           modes and the first discarded one */
        if ((st = gd_dynmat_build(sys, &dm, err))) goto done;
        have_a = 1;
        ks = malloc((size_t)dm.pat.nnz * sizeof *ks);
        ds = malloc((size_t)dm.pat.nnz * sizeof *ds);
        if (!ks || !ds) {
            st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
            goto done;
        }
        gd_dynmat_at(&dm, opt->speed, ks, ds);
        o = (ops){N, NULL, NULL, NULL, &dm.pat, dm.m, ds, ks};
        mo.nmodes = opt->nmodes + 8 < N ? opt->nmodes + 8 : N;
        mo.want_left = 0;
        if ((st = gd_modal_solve_sparse(sys, &mo, 0.0, &mr, err))) goto done;
    } else {
        gd_system_dense(sys, opt->speed, M, D, K);
        mo.nmodes = 0; /* the dense solver computes them all anyway: the first discarded known */
        mo.want_left = 1;
        mo.method = GD_EIG_DENSE;
        if (held) {
            clamp_dense(N, held, M, D, K);
            if ((st = clamped_modes(sys, held, &mo, M, D, K, &mr, err))) goto done;
        } else if ((st = gd_modal_solve(sys, &mo, &mr, err)))
            goto done;
        if (!mr->left_re || !mr->left_im) {
            st = gd_error_set(err, GD_ENUMERIC, file, 0, 0, "", "",
                              "the modal solve gave no left vectors");
            goto done;
        }
    }
    if ((st = rigid_modes(c, mr, &o, t, t2, file, err))) goto done;
    int nel = 0;
    for (int j = 0; j < mr->nmodes; j++)
        nel += !mr->modes[j].rigid_body;
    int nm = opt->nmodes > 0 && opt->nmodes < nel ? opt->nmodes : nel;
    if (sparse && nm >= nel) nm = nel - 1; /* one more than kept, to know the first discarded */
    if (nm < 1) {
        st = gd_error_set(err, GD_EINPUT, file, 0, 0, "nmodes", "keep more modes",
                          "no elastic mode to keep");
        goto done;
    }
    c->nm = nm;
    c->info.ndof = N;
    c->info.ncoords = nc;
    c->info.nkept = nm;
    c->info.ndiscarded = nel - nm;
    c->info.nrigid = c->nr;
    c->info.first_discarded = INFINITY;
    c->lam = malloc((size_t)(nm + 1) * sizeof *c->lam);
    c->pair = malloc((size_t)(nm + 1) * sizeof *c->pair);
    c->U = malloc((size_t)N * (nm + 1) * sizeof *c->U);
    c->Cm = malloc((size_t)nc * (nm + 1) * sizeof *c->Cm);
    c->Bm = malloc((size_t)nc * (nm + 1) * sizeof *c->Bm);
    c->Rc = calloc((size_t)nc * (c->nr + 1), sizeof *c->Rc);
    c->G = malloc((size_t)nc * nc * sizeof *c->G);
    if (!c->lam || !c->pair || !c->U || !c->Cm || !c->Bm || !c->Rc || !c->G) {
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        goto done;
    }
    V = malloc((size_t)N * (nm + 1) * sizeof *V);
    if (!V) {
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        goto done;
    }
    c->info.zeta_discarded = 0;
    for (int j = 0, k = 0; j < mr->nmodes; j++) {
        const gd_mode *md = &mr->modes[j];
        if (md->rigid_body) continue;
        if (k >= nm) { /* discarded: the estimate's frequency and damping */
            if (k == nm) c->info.first_discarded = hypot(md->lambda_re, md->lambda_im);
            double z = -md->lambda_re / hypot(md->lambda_re, md->lambda_im);
            c->info.zeta_discarded = fmax(c->info.zeta_discarded, fmin(z, 1.0));
            k++;
            continue;
        }
        c->lam[k] = md->lambda_re + I * md->lambda_im;
        c->pair[k] = md->lambda_im > 0;
        const double *ur = mr->shape_re + (size_t)j * N, *ui = mr->shape_im + (size_t)j * N;
        double complex *u = c->U + (size_t)k * N, *v = V + (size_t)k * N;
        for (int i = 0; i < N; i++) {
            u[i] = ur[i] + I * ui[i];
            /* without left vectors (sparse): the right one starts the left inverse iteration */
            v[i] = mr->left_re ? mr->left_re[i + (size_t)j * N] + I * mr->left_im[i + (size_t)j * N]
                               : u[i];
        }
        k++;
    }
    if (sparse) { /* only the first discarded mode is known: its damping and the kept ones' */
        c->info.ndiscarded = N - c->nr - nm;
        for (int k = 0; k < nm; k++)
            c->info.zeta_discarded =
                fmax(c->info.zeta_discarded, fmin(-creal(c->lam[k]) / cabs(c->lam[k]), 1.0));
    }
    if (held)
        for (int k = 0; k < nm; k++)
            normalise_left(N, M, D, c->lam[k], c->U + (size_t)k * N, V + (size_t)k * N);
    else if ((st = gd_condense_refine(sys, opt->speed, nm, c->lam, c->U, V, 2, &c->info.refine_step,
                                      err)))
        goto done;
    for (int k = 0; k < nm; k++) {
        const double complex *u = c->U + (size_t)k * N, *v = V + (size_t)k * N;
        for (int a = 0; a < nc; a++) {
            double complex cu = 0, bv = 0;
            for (int e = cc->start[a]; e < cc->start[a + 1]; e++) {
                cu += cc->a[e] * u[cc->dof[e]];
                bv += cc->a[e] * v[cc->dof[e]];
            }
            c->Cm[a + (size_t)k * nc] = cu;
            c->Bm[a + (size_t)k * nc] = bv;
        }
    }
    for (int b = 0; b < c->nr; b++)
        for (int a = 0; a < nc; a++) {
            double s = 0;
            for (int e = cc->start[a]; e < cc->start[a + 1]; e++)
                s += cc->a[e] * c->R[cc->dof[e] + (size_t)b * N];
            c->Rc[a + (size_t)b * nc] = s;
        }
    /* Y = P^T W = W - M R (R^T W): the coordinate loads balanced by the rigid inertia */
    for (int b = 0; b < c->nr; b++) {
        apply(&o, 'M', 0, c->R + (size_t)b * N, t);
        for (int a = 0; a < nc; a++) {
            double rw = c->Rc[a + (size_t)b * nc];
            for (int i = 0; i < N; i++)
                W[i + (size_t)a * N] -= t[i] * rw;
        }
    }
    if ((st = elastic_solve(c, &o, W, file, err))) goto done;
    /* static correction: X - sum_kept (-u b^T / lambda + its conjugate) */
    for (int k = 0; k < nm; k++) {
        double f = c->pair[k] ? 2.0 : 1.0;
        const double complex *u = c->U + (size_t)k * N;
        for (int a = 0; a < nc; a++) {
            double complex bl = c->Bm[a + (size_t)k * nc] / c->lam[k];
            double *x = W + (size_t)a * N;
            for (int i = 0; i < N; i++)
                x[i] += f * creal(u[i] * bl);
        }
    }
    c->Xres = W;
    W = NULL;
    for (int b = 0; b < nc; b++)
        for (int a = 0; a < nc; a++) {
            double s = 0;
            for (int e = cc->start[a]; e < cc->start[a + 1]; e++)
                s += cc->a[e] * c->Xres[cc->dof[e] + (size_t)b * N];
            c->G[a + (size_t)b * nc] = s;
        }
    c->info.residual = maxabs(c->G, (size_t)nc * nc);
    if (gd_condense_build_lti(c)) {
        st = gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        goto done;
    }
    *out = c;
    c = NULL;
done:
    gd_condense_destroy(c);
    gd_modal_free(mr);
    free(V);
    free(ks);
    free(ds);
    if (have_a) gd_dynmat_free(&dm);
    free(M);
    free(D);
    free(K);
    free(W);
    free(t);
    free(t2);
    return st;
}
