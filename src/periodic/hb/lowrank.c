/* Condensation of the linear DOFs onto the nonlinear ones, done exactly as a low-rank
 * update: the harmonic balance Jacobian is
 *   J = L - sum_t (u_t (x) I) G_t (w_t (x) I)^T,
 * L the linear part, block diagonal over the harmonics (each cos/sin pair one 2 nf
 * block, factored as one complex nf matrix: factor_block), and each nonlinear law a
 * rank-one spatial term u_t w_t^T (a mesh: a a^T and a e_driver^T, the TVMS following
 * the driver angle) coupling the harmonics through G_t. Terms sharing their force
 * direction u form one group g (terms zero at every sample are left out),
 *   J = L - sum_g (u_g (x) I) Y_g,   Y_g = sum_{t in g} G_t (w_t (x) I)^T,
 * so the rank is ngroup (2H + 1) (a mesh contributes one direction, not two: half the
 * rank and an eighth of the dense LU of a grouping by term), and the Woodbury identity
 *   J^-1 = L^-1 + L^-1 U (I - Y L^-1 U)^-1 Y L^-1
 * needs H + 1 sparse factorizations of the size of the model (KLU, one symbolic
 * analysis) and one dense r x r LU (LAPACK), instead of the sparse LU of the whole
 * coupled system whose fill is dense on every nonlinear DOF across all harmonics. The
 * continuation's bordered system is solved by block elimination on top; Newton's own
 * right-hand sides need no block solves after the first (solve_L_from_base). */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

void gd_hb_lowrank_free(hb *h)
{
    if (h->Lnum)
        for (int k = 0; k <= h->H; k++)
            if (h->Lnum[k]) klu_free_numeric(&h->Lnum[k], &h->com);
    free(h->Lnum);
    free(h->Lrcond);
    h->Lrcond = NULL;
    if (h->Lsym) klu_free_symbolic(&h->Lsym, &h->com);
    free(h->Lx);
    free(h->zb);
    free(h->P);
    free(h->S);
    free(h->Spiv);
    free(h->xc);
    free(h->brow);
    free(h->wr);
    free(h->wz);
    free(h->tgroup);
    free(h->grep);
    free(h->Z0);
    free(h->F0);
    free(h->urow);
    free(h->urow_of);
    free(h->Umat);
    free(h->fitw);
    gd_hb_cap_free(h);
    h->cap_iter = 0;
    h->tgroup = h->grep = h->urow = h->urow_of = NULL;
    h->Z0 = h->F0 = h->Umat = h->fitw = NULL;
    h->base_ok = 0;
    h->ugram_ok = 0;
    h->nur = 0;
    h->Lnum = NULL;
    h->Spiv = NULL;
    h->nLx = 0;
    h->Lx = h->zb = h->P = h->S = h->xc = h->brow = h->wr = h->wz = NULL;
    h->Lsym = NULL;
}

/* Factors harmonic block k on the union pattern: k = 0 the real K; k > 0 the complex
 * Z_k = K - (k w)^2 M - i k w D, which acts on Q_ck + i Q_sk as the real cos/sin pair
 *   [K - k^2 w^2 M, k w D; -k w D, K - k^2 w^2 M]
 * does on (Q_ck, Q_sk): half the order and a quarter of the entries, so a complex LU of
 * the model's size instead of a real one of twice it. */
static int factor_block(hb *h, double w, int k)
{
    const int nz = h->Unz;
    const double kw = k * w, kw2 = kw * kw;
    const int cplx = k > 0;
    if (!cplx)
        memcpy(h->Lx, h->UK, (size_t)nz * sizeof *h->Lx);
    else
        for (int p = 0; p < nz; p++) {
            h->Lx[2 * p] = h->UK[p] - kw2 * h->UM[p];
            h->Lx[2 * p + 1] = -kw * h->UD[p];
        }
    /* The blocks have almost no fill (the 378-DOF helical model: 3355 entries, L and U
     * 2001 each), so a factorization is mostly KLU's allocation and pivot search: keep
     * the pivot order of the last one of this block (the previous speed) and refactor,
     * unless its pivots have degraded (reciprocal pivot ratio 1000 times below the
     * last full factorization's): then pivot anew. */
    if (h->Lnum[k]) {
        int ok = cplx ? klu_z_refactor(h->Up, h->Ui, h->Lx, h->Lsym, h->Lnum[k], &h->com)
                      : klu_refactor(h->Up, h->Ui, h->Lx, h->Lsym, h->Lnum[k], &h->com);
        if (ok &&
            (cplx ? klu_z_rcond(h->Lsym, h->Lnum[k], &h->com)
                  : klu_rcond(h->Lsym, h->Lnum[k], &h->com)) &&
            h->com.rcond > 1e-3 * h->Lrcond[k] && h->com.rcond > 1e-14)
            return 0;
        klu_free_numeric(&h->Lnum[k], &h->com);
    }
    h->Lnum[k] = cplx ? klu_z_factor(h->Up, h->Ui, h->Lx, h->Lsym, &h->com)
                      : klu_factor(h->Up, h->Ui, h->Lx, h->Lsym, &h->com);
    if (!h->Lnum[k] || h->com.status != KLU_OK) return 1;
    if (!(cplx ? klu_z_rcond(h->Lsym, h->Lnum[k], &h->com)
               : klu_rcond(h->Lsym, h->Lnum[k], &h->com)))
        return 1;
    h->Lrcond[k] = h->com.rcond;
    return 0;
}

/* Slot a (harmonic index) -> block k and offset of that slot inside the block. */
static void slot_of(const hb *h, int a, int *k, int *off)
{
    *k = (a + 1) / 2;
    *off = (a && !(a & 1)) ? h->nf : 0;
}

/* Solves block k > 0 in place on its cos and sin halves (xc, xs of length nf). */
static void solve_block(hb *h, int k, double *xc, double *xs)
{
    const int nf = h->nf;
    for (int i = 0; i < nf; i++) {
        h->zb[2 * i] = xc[i];
        h->zb[2 * i + 1] = xs[i];
    }
    klu_z_solve(h->Lsym, h->Lnum[k], nf, 1, h->zb, &h->com);
    for (int i = 0; i < nf; i++) {
        xc[i] = h->zb[2 * i];
        xs[i] = h->zb[2 * i + 1];
    }
}

/* y = L^-1 b over all blocks (b, y of length n; may alias). */
static void solve_L(hb *h, const double *b, double *y)
{
    const int nf = h->nf;
    if (y != b) memcpy(y, b, (size_t)h->n * sizeof *y);
    klu_solve(h->Lsym, h->Lnum[0], nf, 1, y, &h->com);
    for (int k = 1; k <= h->H; k++)
        solve_block(h, k, y + (size_t)(2 * k - 1) * nf, y + (size_t)2 * k * nf);
}

static int bsize(const hb *h, int k)
{
    return k ? 2 * h->nf : h->nf;
}

static int same_u(const gd_tr_term *a, const gd_tr_term *b)
{
    if (a->nu != b->nu) return 0;
    for (int i = 0; i < a->nu; i++)
        if (a->u_idx[i] != b->u_idx[i] || a->u[i] != b->u[i]) return 0;
    return 1;
}

int gd_hb_term_groups(const hb *h, int *tgroup, int *grep)
{
    int ng = 0;
    for (int t = 0; t < h->nterm; t++) {
        if (h->tactive && !h->tactive[t]) { /* zero over the period: no part in J */
            if (tgroup) tgroup[t] = -1;
            continue;
        }
        int first = t;
        for (int t2 = 0; t2 < t && first == t; t2++)
            if ((!h->tactive || h->tactive[t2]) && same_u(&h->term[t2], &h->term[t])) first = t2;
        if (first == t) {
            if (grep) grep[ng] = t;
            if (tgroup) tgroup[t] = ng;
            ng++;
        } else if (tgroup) {
            tgroup[t] = tgroup[first];
        }
    }
    return ng;
}

int gd_hb_lowrank_factor(hb *h, gd_transient *tr, double w, const double *dRdp, const double *row)
{
    const int nf = h->nf, nh = h->nh, n = h->n, nt = h->nterm, bw = 2 * nf;
    if (gd_hb_term_activity(h)) return 1;
    int *tg = malloc((size_t)(nt > 0 ? nt : 1) * sizeof *tg),
        *gr = malloc((size_t)(nt > 0 ? nt : 1) * sizeof *gr);
    if (!tg || !gr) {
        free(tg);
        free(gr);
        return 1;
    }
    const int ng = gd_hb_term_groups(h, tg, gr), r = ng * nh;
    /* above the crossover no r x r capacitance and no nh x nh couplings (capacitance.c) */
    const int iter = gd_hb_cap_iterative(h->solver, r);
    if (!iter && gd_hb_couplings(h, w)) {
        free(tg);
        free(gr);
        return 1;
    }
    int regroup = iter != h->cap_iter || (iter && h->cap_nt != nt) || !h->tgroup ||
                  h->ngroup != ng || memcmp(h->tgroup, tg, (size_t)nt * sizeof *tg) ||
                  memcmp(h->grep, gr, (size_t)ng * sizeof *gr);
    if (!h->Lnum || h->r != r || regroup) {
        gd_hb_lowrank_free(h);
        h->L_id = 0;
        h->r = r;
        h->Lnum = calloc((size_t)h->H + 1, sizeof *h->Lnum);
        h->Lrcond = calloc((size_t)h->H + 1, sizeof *h->Lrcond);
        h->zb = malloc((size_t)2 * (nf > 0 ? nf : 1) * (ng > 1 ? ng : 1) * sizeof *h->zb);
        h->P = malloc((size_t)(r > 0 ? r : 1) * bw * sizeof *h->P);
        h->S = iter ? malloc(sizeof *h->S)
                    : malloc((size_t)(r > 0 ? r : 1) * (r > 0 ? r : 1) * sizeof *h->S);
        h->Spiv = malloc((size_t)(r > 0 ? r : 1) * sizeof *h->Spiv);
        h->xc = malloc((size_t)n * sizeof *h->xc);
        h->brow = malloc((size_t)(n + 1) * sizeof *h->brow);
        h->wr = malloc((size_t)(r > 0 ? r : 1) * sizeof *h->wr);
        h->wz = malloc((size_t)(r > 0 ? r : 1) * sizeof *h->wz);
        h->ngroup = ng;
        h->tgroup = tg;
        h->grep = gr;
        tg = gr = NULL;
        h->cap_iter = iter;
        h->cap_nt = nt;
        if (iter && gd_hb_cap_alloc(h)) return 1;
        if (!h->Lnum || !h->Lrcond || !h->zb || !h->P || !h->S || !h->Spiv || !h->xc || !h->brow ||
            !h->wr || !h->wz)
            return 1;
    }
    free(tg);
    free(gr);
    /* L and P depend only on the problem and the frequency: a fixed-value Newton (and
     * the requested points) reuses them, only the capacitance follows the iterate */
    int fresh = !(h->L_id == h->stage_id && h->L_w == w && h->stage_id > 0);
    if (fresh) {
        if (gd_hb_linear_union(h, tr)) return 1;
        if (!h->Lsym || h->Lsym_pat != h->Upat_id || h->nLx < 2 * (size_t)h->Unz) {
            for (int k = 0; k <= h->H; k++) /* numeric objects belong to the analysis */
                if (h->Lnum[k]) klu_free_numeric(&h->Lnum[k], &h->com);
            if (h->Lsym) klu_free_symbolic(&h->Lsym, &h->com);
            free(h->Lx);
            h->nLx = 2 * (size_t)(h->Unz > 0 ? h->Unz : 1);
            h->Lx = malloc(h->nLx * sizeof *h->Lx);
            h->Lsym = h->Lx ? klu_analyze(nf, h->Up, h->Ui, &h->com) : NULL;
            if (!h->Lsym) return 1;
            h->Lsym_pat = h->Upat_id;
        }
    }
    if (fresh) h->base_ok = 0; /* a new L: the next Newton solve starts a new base */
    for (int k = 0; fresh && k <= h->H; k++)
        if (factor_block(h, w, k)) {
            h->L_id = 0;
            return 1;
        }
    h->L_id = h->stage_id;
    h->L_w = w;
    /* P = L^-1 U, column (g, a) held inside its block (length bw): for k > 0 one complex
     * solve z = Z_k^-1 u gives the cos column (Re z, Im z) and the sin column i z; the
     * groups' right-hand sides go to KLU together */
    for (int k = 0; fresh && k <= h->H; k++) {
        if (k) memset(h->zb, 0, (size_t)2 * nf * ng * sizeof *h->zb);
        for (int g = 0; g < ng; g++) {
            const gd_tr_term *tm = &h->term[h->grep[g]];
            double *pc = h->P + ((size_t)g * nh + (k ? 2 * k - 1 : 0)) * bw;
            if (!k) {
                memset(pc, 0, (size_t)bw * sizeof *pc);
                for (int i = 0; i < tm->nu; i++)
                    pc[tm->u_idx[i]] = tm->u[i];
                klu_solve(h->Lsym, h->Lnum[0], nf, 1, pc, &h->com);
                continue;
            }
            for (int i = 0; i < tm->nu; i++)
                h->zb[2 * ((size_t)g * nf + tm->u_idx[i])] = tm->u[i];
        }
        if (!k) continue;
        klu_z_solve(h->Lsym, h->Lnum[k], nf, ng, h->zb, &h->com);
        for (int g = 0; g < ng; g++) {
            double *pc = h->P + ((size_t)g * nh + 2 * k - 1) * bw, *ps = pc + bw;
            const double *z = h->zb + (size_t)2 * g * nf; /* column (g, 2k) follows (g, 2k - 1) */
            for (int i = 0; i < nf; i++) {
                pc[i] = ps[nf + i] = z[2 * i];
                pc[nf + i] = z[2 * i + 1];
                ps[i] = -z[2 * i + 1];
            }
        }
    }
    if (iter) {
        if (gd_hb_cap_factor(h, w, fresh)) return 1;
        goto bordering;
    }
    /* S = I - Y P: column (g, a) of P is non-zero only in the block of slot a, so
     * w_t^T P_(g,a) has at most two non-zero slots b, each scattering G_t[., b] */
    memset(h->S, 0, (size_t)r * r * sizeof *h->S);
    for (int i = 0; i < r; i++)
        h->S[(size_t)i * r + i] = 1.0;
    for (int g = 0; g < ng; g++)
        for (int a = 0; a < nh; a++) {
            int k, off;
            slot_of(h, a, &k, &off);
            const double *p = h->P + ((size_t)g * nh + a) * bw;
            double *Scol = h->S + ((size_t)g * nh + a) * r;
            int slots[2] = {k ? 2 * k - 1 : 0, 2 * k}, ns = k ? 2 : 1;
            for (int t = 0; t < nt; t++) {
                if (h->tgroup[t] < 0) continue;
                const gd_tr_term *wt = &h->term[t];
                const double *G = h->Gall + (size_t)t * nh * nh; /* G[b * nh + a] = G_ab */
                double *Sg = Scol + (size_t)h->tgroup[t] * nh;
                for (int q = 0; q < ns; q++) {
                    int b = slots[q], o = q ? nf : 0;
                    double m = 0.0;
                    for (int j = 0; j < wt->nw; j++)
                        m += wt->w[j] * p[o + wt->w_idx[j]];
                    if (m == 0.0) continue;
                    const double *Gb = G + (size_t)b * nh;
                    for (int a2 = 0; a2 < nh; a2++)
                        Sg[a2] -= m * Gb[a2];
                }
            }
        }
    if (r && LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, r, r, h->S, r, h->Spiv)) return 1;
bordering:
    /* bordering: x_c = J^-1 dRdp, denominator d - row . x_c */
    memcpy(h->brow, row, (size_t)(n + 1) * sizeof *row);
    h->denom = row[n];
    if (dRdp) {
        memcpy(h->xc, dRdp, (size_t)n * sizeof *h->xc);
        gd_hb_lowrank_solve_J(h, h->xc);
        for (int i = 0; i < n; i++)
            h->denom -= row[i] * h->xc[i];
    } else {
        memset(h->xc, 0, (size_t)n * sizeof *h->xc);
    }
    return isfinite(h->denom) && h->denom != 0.0 ? 0 : 1;
}

/* x += P s, s of length r (slot-major within each group: s[g * nh + a]) */
static void add_P(hb *h, const double *s, double *x)
{
    const int nf = h->nf, nh = h->nh, bw = 2 * nf;
    for (int g = 0; g < h->ngroup; g++)
        for (int a = 0; a < nh; a++) {
            double v = s[(size_t)g * nh + a];
            if (v == 0.0) continue;
            int k, off;
            slot_of(h, a, &k, &off);
            const double *p = h->P + ((size_t)g * nh + a) * bw;
            double *xb = x + (size_t)(k ? 2 * k - 1 : 0) * nf;
            for (int i = 0; i < bsize(h, k); i++)
                xb[i] += p[i] * v;
        }
}

/* x = y + P S^-1 Y y for y = L^-1 b given in x: the Woodbury correction */
static void woodbury(hb *h, double *x)
{
    const int nf = h->nf, nh = h->nh, nt = h->nterm, r = h->r;
    if (!r) return;
    if (h->cap_iter) {
        gd_hb_cap_Yy(h, x, h->wz);
        if (gd_hb_cap_solve(h, h->wz, 1e-12, NULL) == 1) { /* stalled: a clear failure */
            for (int i = 0; i < h->n; i++)
                x[i] = NAN;
            return;
        }
        add_P(h, h->wz, x);
        return;
    }
    /* z = Y y (per term: the slots of w_t^T y through G_t), s = S^-1 z, x += P s */
    memset(h->wz, 0, (size_t)r * sizeof *h->wz);
    for (int t = 0; t < nt; t++) {
        if (h->tgroup[t] < 0) continue;
        const gd_tr_term *tm = &h->term[t];
        for (int b = 0; b < nh; b++) {
            double z = 0.0;
            for (int j = 0; j < tm->nw; j++)
                z += tm->w[j] * x[(size_t)b * nf + tm->w_idx[j]];
            h->wr[b] = z;
        }
        cblas_dgemv(CblasColMajor, CblasNoTrans, nh, nh, 1.0, h->Gall + (size_t)t * nh * nh, nh,
                    h->wr, 1, 1.0, h->wz + (size_t)h->tgroup[t] * nh, 1);
    }
    LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', r, 1, h->S, r, h->Spiv, h->wz, r);
    add_P(h, h->wz, x);
}

void gd_hb_lowrank_solve_J(hb *h, double *x)
{
    solve_L(h, x, x);
    woodbury(h, x);
}

/* The bordered row: b (n + 1) holds J^-1 b_n in its first n entries, beta the last. */
static void border(hb *h, double *b, double beta)
{
    const int n = h->n;
    double y = beta;
    for (int i = 0; i < n; i++)
        y -= h->brow[i] * b[i];
    y /= h->denom;
    for (int i = 0; i < n; i++)
        b[i] -= y * h->xc[i];
    b[n] = y;
}

void gd_hb_lowrank_solve(hb *h, double *b)
{
    double beta = b[h->n];
    gd_hb_lowrank_solve_J(h, b);
    border(h, b, beta);
}

/* The groups' u vectors as a dense nur x ngroup matrix over the DOFs they touch. */
static int make_umat(hb *h)
{
    const int nf = h->nf, ng = h->ngroup;
    if (h->Umat) return 0;
    h->urow = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *h->urow);
    h->urow_of = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *h->urow_of);
    h->fitw = malloc((size_t)(ng > 0 ? ng : 1) * (ng + h->nh) * sizeof *h->fitw);
    if (!h->urow || !h->urow_of || !h->fitw) return 1;
    for (int i = 0; i < nf; i++)
        h->urow_of[i] = -1;
    h->nur = 0;
    for (int g = 0; g < ng; g++) {
        const gd_tr_term *tm = &h->term[h->grep[g]];
        for (int j = 0; j < tm->nu; j++)
            if (h->urow_of[tm->u_idx[j]] < 0) {
                h->urow_of[tm->u_idx[j]] = h->nur;
                h->urow[h->nur++] = tm->u_idx[j];
            }
    }
    h->Umat = calloc((size_t)(h->nur > 0 ? h->nur : 1) * (ng > 0 ? ng : 1), sizeof *h->Umat);
    if (!h->Umat) return 1;
    for (int g = 0; g < ng; g++) {
        const gd_tr_term *tm = &h->term[h->grep[g]];
        for (int j = 0; j < tm->nu; j++)
            h->Umat[(size_t)g * h->nur + h->urow_of[tm->u_idx[j]]] = tm->u[j];
    }
    /* U^T U and its Cholesky factor, once per grouping (ugram_ok 0: directions dependent) */
    double *A = h->fitw;
    for (int g = 0; g < ng; g++)
        for (int g2 = 0; g2 < ng; g2++) {
            double m = 0.0;
            for (int q = 0; q < h->nur; q++)
                m += h->Umat[(size_t)g * h->nur + q] * h->Umat[(size_t)g2 * h->nur + q];
            A[(size_t)g2 * ng + g] = m;
        }
    h->ugram_ok = ng > 0 && !LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'U', ng, A, ng);
    return 0;
}

/* b (n) := L^-1 b for b = -R(X) from the base at X0: -X + L^-1 F(X0) + P dPhi, with dPhi
 * the least-squares fit of F(X) - F(X0) by the groups' directions. 0 when the fit leaves
 * more than 1e-3 |b| unexplained (then the caller solves): an inexact step would only
 * slow Newton down, the residual decides convergence. */
static int solve_L_from_base(hb *h, const double *X, double *b)
{
    const int nf = h->nf, nh = h->nh, ng = h->ngroup, n = h->n, nur = h->nur;
    if (!h->base_ok || !h->Fh_ok || !h->ugram_ok) return 0;
    double bn = 0.0;
    for (int i = 0; i < n; i++)
        bn += b[i] * b[i];
    /* normal equations: (U^T U) dPhi_a = U^T dF_a for every slot a at once */
    const double *A = h->fitw;
    double *B = h->fitw + (size_t)ng * ng;
    for (int a = 0; a < nh; a++)
        for (int g = 0; g < ng; g++) {
            double m = 0.0;
            for (int q = 0; q < nur; q++) {
                size_t at = (size_t)a * nf + h->urow[q];
                m += h->Umat[(size_t)g * nur + q] * (h->Fh[at] - h->F0[at]);
            }
            B[(size_t)a * ng + g] = m;
        }
    if (LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'U', ng, nh, A, ng, B, ng)) return 0;
    /* what the fit leaves: every entry of dF - U dPhi */
    double miss = 0.0;
    for (int a = 0; a < nh; a++)
        for (int i = 0; i < nf; i++) {
            size_t at = (size_t)a * nf + i;
            double d = h->Fh[at] - h->F0[at];
            int q = h->urow_of[i];
            for (int g = 0; q >= 0 && g < ng; g++)
                d -= h->Umat[(size_t)g * nur + q] * B[(size_t)a * ng + g];
            miss += d * d;
        }
    if (!(miss <= 1e-6 * bn)) return 0;
    for (int i = 0; i < n; i++)
        b[i] = h->Z0[i] - X[i];
    /* + P dPhi (dPhi in B, slot-major: B[a * ng + g]) */
    for (int a = 0; a < nh; a++)
        for (int g = 0; g < ng; g++)
            h->wr[(size_t)g * nh + a] = B[(size_t)a * ng + g];
    add_P(h, h->wr, b);
    return 1;
}

void gd_hb_lowrank_solve_newton(hb *h, const double *X, double *b)
{
    const int n = h->n;
    double beta = b[n];
    if (!solve_L_from_base(h, X, b)) {
        solve_L(h, b, b);
        /* the base: L^-1 F(X) = X + L^-1 (-R(X)) */
        if (h->Fh_ok && !make_umat(h) && (h->Z0 || (h->Z0 = malloc((size_t)n * sizeof *h->Z0))) &&
            (h->F0 || (h->F0 = malloc((size_t)n * sizeof *h->F0)))) {
            for (int i = 0; i < n; i++)
                h->Z0[i] = X[i] + b[i];
            memcpy(h->F0, h->Fh, (size_t)n * sizeof *h->F0);
            h->base_ok = 1;
        }
    }
    woodbury(h, b);
    border(h, b, beta);
}
