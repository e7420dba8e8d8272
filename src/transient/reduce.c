/* Modal reduction of the transient problem (Craig & Bampton 1968, AIAA J. 6, 1313):
 * the DOFs any law acts on are kept physical (boundary B: mesh DOFs, squeeze film
 * dampers, loads, unbalances, prescribed DOFs); the others (interior I) are replaced by
 * the fixed-interface normal modes of (K_II, M_II) below a cutoff frequency plus the
 * static constraint modes Psi = -K_II^-1 K_IB, the static correction that makes the
 * reduction exact for static loads on B:
 *
 *     q = T x,  T = [ I    0  ]   x = [q_B; eta],   M_r = T^T M T, D_r = T^T D T,
 *                   [ Psi  Phi]                     K_r = T^T K T.
 *
 * D holds the damping and the gyroscopic W G, K the speed-dependent bearings, both as
 * at the speed; the modes come from the symmetric part of K_II. The reduced problem is
 * an ordinary gd_transient over the coordinates x, so every integrator runs it; the
 * physical DOFs are recovered row by row (records) or in full (q_end) from T.
 * Interior modes: shift-invert Krylov-Schur on (K_II + s M_II)^-1 M_II with s a small
 * positive shift (rigid interior motions stay regular), the number of modes doubled
 * until one above the cutoff has been found. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"
#include "transient/transient_impl.h"

static gd_status fail(gd_error *err, gd_status st, const char *hint, const char *msg)
{
    return gd_error_set(err, st, "", 0, 0, "reduce", hint, "%s", msg);
}

typedef struct lu_op {
    css *S;
    csn *N;
    const cs *M;
    double *w;
    int n;
} lu_op;

static void lu_solve(const lu_op *o, double *b, double *x)
{
    cs_ipvec(o->N->pinv, b, x, o->n);
    cs_lsolve(o->N->L, x);
    cs_usolve(o->N->U, x);
    cs_ipvec(o->S->q, x, b, o->n);
    memcpy(x, b, (size_t)o->n * sizeof *x);
}

/* y = (K + s M)^-1 M x */
static void si_apply(void *ctx, const double *x, double *y)
{
    lu_op *o = ctx;
    memset(o->w, 0, (size_t)o->n * sizeof *o->w);
    cs_gaxpy(o->M, x, o->w);
    lu_solve(o, o->w, y);
}

/* 0 ok, 1 out of memory, 2 singular. */
static int lu_setup(lu_op *o, const cs *A, const cs *M)
{
    memset(o, 0, sizeof *o);
    o->n = A->n;
    o->M = M;
    o->S = cs_sqr(3, A, 0);
    o->w = malloc((size_t)(A->n > 0 ? A->n : 1) * sizeof *o->w);
    if (!o->S || !o->w) return 1;
    /* cs_lu returns NULL for an exactly zero pivot as well as for a failed allocation
     * (its workspaces: a few n-vectors and the factors, small beside what was already
     * allocated here): a zero pivot is by far the likelier, so it is reported as the
     * singular matrix it is, not as memory (issue 23) */
    o->N = cs_lu(A, o->S, 1e-3);
    if (!o->N) return 2;
    /* a zero or tiny pivot: singular (CSparse divides by it without complaint) */
    double mx = 0, mn = INFINITY;
    const cs *U = o->N->U;
    for (int j = 0; j < U->n; j++) {
        double d = fabs(U->x[U->p[j + 1] - 1]);
        mx = fmax(mx, d);
        mn = fmin(mn, d);
    }
    return mn > 1e-13 * mx ? 0 : 2;
}

static void lu_free(lu_op *o)
{
    cs_sfree(o->S);
    cs_nfree(o->N);
    free(o->w);
}

/* Fixed-interface modes below cutoff (rad/s): columns of phi (nI x *nphi, M-normalised,
 * allocated). */
static gd_status interior_modes(const cs *K, const cs *M, double cutoff, double **phi, int *nphi,
                                gd_error *err)
{
    const int n = K->n;
    *phi = NULL;
    *nphi = 0;
    cs *Kt = cs_transpose(K, 1);
    cs *Ks = Kt ? cs_add(K, Kt, 0.5, 0.5) : NULL;
    double shift = 1e-4 * cutoff * cutoff;
    cs *P = Ks ? cs_add(Ks, M, 1.0, shift) : NULL;
    cs_spfree(Kt);
    cs_spfree(Ks);
    lu_op op;
    gd_status st = GD_OK;
    int lr = P ? lu_setup(&op, P, M) : 1;
    if (lr) {
        st = lr == 2 ? fail(err, GD_ENUMERIC, "", "the shifted interior stiffness is singular")
                     : GD_ENOMEM;
        if (P) lu_free(&op);
        cs_spfree(P);
        return st;
    }
    double mu_cut = 1.0 / (cutoff * cutoff + shift);
    gd_ks_result ks = {0};
    for (int nev = 8;; nev *= 2) {
        if (nev > n - 3) nev = n - 3;
        int ncv = 2 * nev + 12 < n - 1 ? 2 * nev + 12 : n - 1;
        if (nev < 1 || ncv <= nev + 1) break;
        gd_ks_result_free(&ks);
        memset(&ks, 0, sizeof ks);
        st = gd_krylov_schur(si_apply, &op, n, n, nev, ncv, 1e-10, 300, NULL, &ks);
        if (st) break;
        double mumin = INFINITY;
        for (int i = 0; i < ks.nconv; i++)
            mumin = fmin(mumin, ks.mu_re[i]);
        if (mumin < mu_cut || nev == n - 3) break;
    }
    if (st) {
        if (st != GD_ENOMEM)
            st = fail(err, GD_ENUMERIC, "raise or lower the cutoff",
                      "the interior modes did not converge");
    } else {
        int k = 0;
        for (int i = 0; i < ks.nconv; i++)
            if (ks.mu_im[i] == 0 && ks.mu_re[i] >= mu_cut) k++;
        *phi = malloc((size_t)(k > 0 ? k : 1) * n * sizeof **phi);
        if (!*phi) {
            st = GD_ENOMEM;
        } else {
            /* M-orthonormal (twice classical Gram-Schmidt): the modes of a double
             * eigenvalue (x and y bending of a round shaft) come as any basis of their
             * plane, and the projection of an initial state needs Phi^T M Phi = I */
            int c = 0;
            for (int i = 0; i < ks.nconv; i++) {
                if (!(ks.mu_im[i] == 0 && ks.mu_re[i] >= mu_cut)) continue;
                double *col = *phi + (size_t)c * n;
                memcpy(col, ks.vec_re + (size_t)i * n, (size_t)n * sizeof *col);
                double mm0 = 0;
                for (int pass = 0; pass < 3; pass++) {
                    memset(op.w, 0, (size_t)n * sizeof *op.w);
                    cs_gaxpy(M, col, op.w);
                    if (pass == 0)
                        for (int r = 0; r < n; r++)
                            mm0 += col[r] * op.w[r];
                    if (pass == 2) break;
                    for (int j = 0; j < c; j++) {
                        const double *pj = *phi + (size_t)j * n;
                        double h = 0;
                        for (int r = 0; r < n; r++)
                            h += pj[r] * op.w[r];
                        for (int r = 0; r < n; r++)
                            col[r] -= h * pj[r];
                    }
                }
                double mm = 0;
                for (int r = 0; r < n; r++)
                    mm += col[r] * op.w[r];
                /* a second Ritz vector of an eigenspace already spanned: drop it */
                if (!(mm > 1e-12 * mm0)) continue;
                for (int r = 0; r < n; r++)
                    col[r] /= sqrt(mm);
                c++;
            }
            *nphi = c;
        }
    }
    gd_ks_result_free(&ks);
    lu_free(&op);
    cs_spfree(P);
    return st;
}

/* Ar = T^T A T (nr x nr, column-major) with T given by the boundary list and TI. */
static int project(const cs *A, int n, const int *bidx, int nb, const int *iidx, int ni,
                   const double *TI, int nr, double *Ar)
{
    double *t = malloc((size_t)n * sizeof *t), *y = malloc((size_t)n * sizeof *y);
    if (!t || !y) {
        free(t);
        free(y);
        return 1;
    }
    for (int c = 0; c < nr; c++) {
        memset(t, 0, (size_t)n * sizeof *t);
        if (c < nb) t[bidx[c]] = 1.0;
        for (int i = 0; i < ni; i++)
            t[iidx[i]] = TI[(size_t)i * nr + c];
        memset(y, 0, (size_t)n * sizeof *y);
        cs_gaxpy(A, t, y);
        for (int r = 0; r < nr; r++) {
            double s = r < nb ? y[bidx[r]] : 0.0;
            for (int i = 0; i < ni; i++)
                s += TI[(size_t)i * nr + r] * y[iidx[i]];
            Ar[r + (size_t)c * nr] = s;
        }
    }
    free(t);
    free(y);
    return 0;
}

static void keep(int *flag, int d)
{
    if (d >= 0) flag[d] = 1;
}

double gd_tr_full_value(const gd_transient *tr, int i, const double *x)
{
    const gd_tr_reduction *r = tr->red;
    if (!r) return x[i];
    if (r->kept[i] >= 0) return x[r->kept[i]];
    const double *row = r->TI + (size_t)r->irow[i] * r->nr;
    double s = 0;
    for (int c = 0; c < r->nr; c++)
        s += row[c] * x[c];
    return s;
}

double gd_tr_full_rate(const gd_transient *tr, int i)
{
    return tr->red ? tr->red->rate[i] : tr->rate[i];
}

void gd_tr_project(const gd_transient *tr, const double *full, double *x)
{
    const gd_tr_reduction *r = tr->red;
    for (int c = 0; c < r->nr; c++)
        x[c] = 0.0;
    for (int i = 0; i < r->nfull; i++)
        if (r->kept[i] >= 0) x[r->kept[i]] = full[i];
    /* eta = Phi^T M_II (q_I - Psi q_B): rows of MTI hold (M_II Phi)^T */
    for (int i = 0; i < r->nfull; i++) {
        if (r->irow[i] < 0) continue;
        const double *row = r->TI + (size_t)r->irow[i] * r->nr;
        double qi = full[i];
        for (int c = 0; c < r->nb; c++)
            qi -= row[c] * x[c];
        const double *mrow = r->MTI + (size_t)r->irow[i] * r->nr;
        for (int c = r->nb; c < r->nr; c++)
            x[c] += mrow[c] * qi;
    }
}

/* Names the rigid motions of the interior DOFs with the boundary held: a uniform axial
 * (z) or torsional (rz) displacement that K_II leaves without force. buf gets e.g.
 * "axial (z) and torsional (rz)", or "" when neither. */
static void free_motions(const gd_transient *tr, const cs *KII, const int *iidx, int ni, char *buf,
                         size_t size)
{
    buf[0] = '\0';
    const gd_system *sys = tr->sys;
    if (tr->n != sys->ndof) return;
    double *v = calloc((size_t)ni, sizeof *v), *y = calloc((size_t)ni, sizeof *y);
    double kmax = 0;
    for (int p = 0; p < KII->p[KII->n]; p++)
        kmax = fmax(kmax, fabs(KII->x[p]));
    static const gd_dof D[2] = {GD_Z, GD_RZ};
    static const char *const NAME[2] = {"axial (z)", "torsional (rz)"};
    for (int k = 0; v && y && k < 2; k++) {
        int any = 0;
        for (int i = 0; i < ni; i++) {
            v[i] = sys->dof_type[iidx[i]] == D[k];
            any |= v[i] != 0;
            y[i] = 0;
        }
        if (!any) continue;
        cs_gaxpy(KII, v, y);
        double r = 0;
        for (int i = 0; i < ni; i++)
            r = fmax(r, fabs(y[i]));
        if (r <= 1e-10 * kmax) {
            size_t len = strlen(buf);
            snprintf(buf + len, size - len, "%s%s", len ? " and " : "", NAME[k]);
        }
    }
    free(v);
    free(y);
}

static gd_status reduce(gd_transient *tr, double cutoff, gd_error *err)
{
    const int n = tr->n;
    gd_status st = GD_ENOMEM;
    int *flag = calloc((size_t)n, sizeof *flag), *bmap = malloc((size_t)n * sizeof *bmap),
        *imap = malloc((size_t)n * sizeof *imap), *bidx = malloc((size_t)n * sizeof *bidx),
        *iidx = malloc((size_t)n * sizeof *iidx);
    cs *KII = NULL, *MII = NULL, *KIB = NULL;
    double *phi = NULL, *TI = NULL, *Ar = NULL;
    lu_op kop = {0};
    gd_tr_reduction *red = NULL;
    if (!flag || !bmap || !imap || !bidx || !iidx) goto done;
    for (int i = 0; i < n; i++)
        if (tr->fidx[i] < 0) flag[i] = 1;
    for (int k = 0; k < tr->nmodel_mesh; k++)
        for (int j = 0; j < tr->model_a[k].n; j++)
            keep(flag, tr->model_a[k].dof[j]);
    for (int k = 0; k < tr->nlaw; k++)
        for (int j = 0; j < tr->law[k].ndofs; j++)
            keep(flag, tr->law[k].dof[j]);
    for (int k = 0; k < tr->nunb; k++) {
        keep(flag, tr->unb[k].dx);
        keep(flag, tr->unb[k].dy);
    }
    int nb = 0, ni = 0;
    for (int i = 0; i < n; i++) {
        bmap[i] = flag[i] ? nb : -1;
        imap[i] = flag[i] ? -1 : ni;
        if (flag[i])
            bidx[nb++] = i;
        else
            iidx[ni++] = i;
    }
    if (ni == 0) { /* nothing to reduce */
        st = GD_OK;
        goto done;
    }
    KII = gd_tr_cs_block(tr->K, imap, imap, ni, ni);
    MII = gd_tr_cs_block(tr->M, imap, imap, ni, ni);
    KIB = gd_tr_cs_block(tr->K, imap, bmap, ni, nb);
    if (!KII || !MII || !KIB) goto done;
    int nphi = 0;
    if (ni > 12) {
        if ((st = interior_modes(KII, MII, cutoff, &phi, &nphi, err))) goto done;
    } else { /* too few for a Krylov basis: keep the interior whole */
        st = GD_OK;
        goto done;
    }
    st = GD_ENOMEM;
    /* Psi = -K_II^-1 K_IB */
    int nr = nb + nphi;
    TI = calloc((size_t)ni * nr, sizeof *TI);
    if (!TI) goto done;
    int lr = lu_setup(&kop, KII, MII);
    if (lr == 2) {
        char what[64], msg[200];
        free_motions(tr, KII, iidx, ni, what, sizeof what);
        snprintf(msg, sizeof msg,
                 "cannot reduce: the DOFs without laws have a free rigid-body motion%s%s "
                 "(their stiffness is singular)",
                 what[0] ? ": " : "", what);
        st = fail(err, GD_EINPUT,
                  "keep the full model, or support the free part (a bearing, a spring, a "
                  "prescribed motion)",
                  msg);
        goto done;
    }
    if (lr) goto done;
    double *col = malloc((size_t)ni * sizeof *col);
    if (!col) goto done;
    for (int c = 0; c < nb; c++) {
        memset(kop.w, 0, (size_t)ni * sizeof *kop.w);
        for (int p = KIB->p[c]; p < KIB->p[c + 1]; p++)
            kop.w[KIB->i[p]] = -KIB->x[p];
        lu_solve(&kop, kop.w, col);
        for (int i = 0; i < ni; i++)
            TI[(size_t)i * nr + c] = col[i];
    }
    free(col);
    for (int c = 0; c < nphi; c++)
        for (int i = 0; i < ni; i++)
            TI[(size_t)i * nr + nb + c] = phi[(size_t)c * ni + i];
    /* reduced matrices */
    Ar = malloc((size_t)3 * nr * nr * sizeof *Ar);
    if (!Ar) goto done;
    if (project(tr->M, n, bidx, nb, iidx, ni, TI, nr, Ar) ||
        project(tr->K, n, bidx, nb, iidx, ni, TI, nr, Ar + (size_t)nr * nr) ||
        project(tr->D, n, bidx, nb, iidx, ni, TI, nr, Ar + (size_t)2 * nr * nr))
        goto done;
    red = calloc(1, sizeof *red);
    if (!red) goto done;
    red->nfull = n;
    red->nb = nb;
    red->nr = nr;
    red->nmodes = nphi;
    red->kept = malloc((size_t)n * sizeof *red->kept);
    red->irow = malloc((size_t)n * sizeof *red->irow);
    red->rate = malloc((size_t)n * sizeof *red->rate);
    red->MTI = calloc((size_t)ni * nr, sizeof *red->MTI);
    if (!red->kept || !red->irow || !red->rate || !red->MTI) goto done;
    memcpy(red->kept, bmap, (size_t)n * sizeof *bmap);
    memcpy(red->irow, imap, (size_t)n * sizeof *imap);
    memcpy(red->rate, tr->rate, (size_t)n * sizeof *tr->rate);
    for (int c = 0; c < nphi; c++) { /* rows of M_II Phi, for the projection of q0 */
        double *mp = kop.w;
        memset(mp, 0, (size_t)ni * sizeof *mp);
        cs_gaxpy(MII, phi + (size_t)c * ni, mp);
        for (int i = 0; i < ni; i++)
            red->MTI[(size_t)i * nr + nb + c] = mp[i];
    }
    red->TI = TI;
    TI = NULL;
    /* the problem over x: matrices, partition, element DOFs */
    cs *Mr = gd_tr_cs_from_dense(nr, Ar), *Kr = gd_tr_cs_from_dense(nr, Ar + (size_t)nr * nr),
       *Dr = gd_tr_cs_from_dense(nr, Ar + (size_t)2 * nr * nr);
    if (!Mr || !Kr || !Dr) {
        cs_spfree(Mr);
        cs_spfree(Kr);
        cs_spfree(Dr);
        goto done;
    }
    gd_tr_release_linear(tr);
    tr->M = Mr;
    tr->K = Kr;
    tr->D = Dr;
    int nf = 0;
    for (int c = 0; c < nr; c++) {
        int full = c < nb ? bidx[c] : -1;
        tr->fidx[c] = full >= 0 && tr->fidx[full] < 0 ? -1 : nf++;
        tr->rate[c] = full >= 0 ? red->rate[full] : 0.0;
    }
    tr->n = nr;
    tr->nf = nf;
    tr->np = nr - nf;
    for (int c = 0; c < nr; c++)
        if (tr->fidx[c] >= 0) tr->free_dof[tr->fidx[c]] = c;
    for (int k = 0; k < tr->np; k++)
        tr->pres[k].dof = bmap[tr->pres[k].dof];
    for (int k = 0; k < tr->nmodel_mesh; k++)
        for (int j = 0; j < tr->model_a[k].n; j++)
            tr->model_a[k].dof[j] = bmap[tr->model_a[k].dof[j]];
    for (int k = 0; k < tr->nlaw; k++)
        for (int j = 0; j < tr->law[k].ndofs; j++)
            if (tr->law[k].dof[j] >= 0) tr->law[k].dof[j] = bmap[tr->law[k].dof[j]];
    for (int k = 0; k < tr->nunb; k++) {
        if (tr->unb[k].dx >= 0) tr->unb[k].dx = bmap[tr->unb[k].dx];
        if (tr->unb[k].dy >= 0) tr->unb[k].dy = bmap[tr->unb[k].dy];
    }
    tr->red = red;
    red = NULL;
    st = gd_tr_linear_setup(tr, err);
    if (st == GD_ENOMEM) st = fail(err, GD_ENOMEM, "", "out of memory");
done:
    if (st == GD_ENOMEM) st = fail(err, GD_ENOMEM, "", "out of memory");
    gd_tr_reduction_free(red);
    lu_free(&kop);
    free(flag);
    free(bmap);
    free(imap);
    free(bidx);
    free(iidx);
    cs_spfree(KII);
    cs_spfree(MII);
    cs_spfree(KIB);
    free(phi);
    free(TI);
    free(Ar);
    return st;
}

gd_status gd_transient_new_reduced(const gd_system *sys, const gd_transient_spec *spec,
                                   double speed, double cutoff, gd_transient **out, gd_error *err)
{
    *out = NULL;
    if (!(cutoff > 0) || !isfinite(cutoff))
        return fail(err, GD_EINPUT, "give a cutoff frequency > 0", "invalid cutoff frequency");
    gd_transient *tr;
    gd_status st = gd_transient_new(sys, spec, speed, &tr, err);
    if (st) return st;
    if (tr->nin > 0) { /* the inertia update's M_ff^-1 e_j are the full model's */
        gd_transient_free(tr);
        return fail(err, GD_EINPUT,
                    "integrate the full model, or leave out the cam "
                    "acceleration term",
                    "the modal reduction does not take cam valve trains with "
                    "include_acceleration (a law's configuration-dependent mass)");
    }
    if ((st = reduce(tr, cutoff, err))) {
        gd_transient_free(tr);
        return st;
    }
    *out = tr;
    return GD_OK;
}

int gd_transient_reduced_size(const gd_transient *tr, int *nkept, int *nmodes)
{
    if (nkept) *nkept = tr->red ? tr->red->nb : tr->n;
    if (nmodes) *nmodes = tr->red ? tr->red->nmodes : 0;
    return tr->n;
}
