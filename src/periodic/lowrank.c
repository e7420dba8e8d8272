/* Condensation of the linear DOFs onto the nonlinear ones, done exactly as a low-rank
 * update: the harmonic balance Jacobian is
 *   J = L - sum_t (u_t (x) I) G_t (w_t (x) I)^T,
 * L the linear part, block diagonal over the harmonics (each cos/sin pair one sparse
 * 2 nf block), and each nonlinear law a rank-one spatial term u_t w_t^T (a mesh: a a^T)
 * coupling the harmonics through G_t. With U, C, W stacking the terms (rank
 * r = nterm (2H + 1)), the Woodbury identity
 *   J^-1 = L^-1 + L^-1 U C (I - W^T L^-1 U C)^-1 W^T L^-1
 * needs H + 1 sparse factorizations of the size of the model (KLU, one symbolic
 * analysis) and one dense r x r LU (LAPACK), instead of the sparse LU of the whole
 * coupled system whose fill is dense on every nonlinear DOF across all harmonics. The
 * continuation's bordered system is solved by block elimination on top. */
#include <cs.h>
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
    if (h->Lsym) klu_free_symbolic(&h->Lsym, &h->com);
    if (h->L0sym) klu_free_symbolic(&h->L0sym, &h->com);
    free(h->Lp);
    free(h->Li);
    free(h->Lx);
    free(h->L0p);
    free(h->L0i);
    free(h->L0x);
    free(h->P);
    free(h->S);
    free(h->Spiv);
    free(h->xc);
    free(h->brow);
    free(h->wr);
    free(h->wz);
    h->Lnum = NULL;
    h->Lp = h->Li = h->L0p = h->L0i = h->Spiv = NULL;
    h->Lx = h->L0x = h->P = h->S = h->xc = h->brow = h->wr = h->wz = NULL;
}

/* Harmonic block k (k = 0: K, nf; else the 2 nf cos/sin block) as a sorted CSC. */
static cs *block(const hb *h, gd_transient *tr, double w, int k)
{
    const int nf = h->nf, m = k ? 2 * nf : nf;
    gd_csc M, D, K;
    gd_transient_matrices(tr, &M, &D, &K);
    int nz = K.colptr[nf] + M.colptr[nf] + D.colptr[nf];
    cs *T = cs_spalloc(m, m, (k ? 4 : 1) * (nz > 0 ? nz : 1), 1, 1);
    if (!T) return NULL;
    double kw = k * w, kw2 = kw * kw;
    for (int half = 0; half < (k ? 2 : 1); half++) {
        int o = half * nf;
        for (int j = 0; j < nf; j++) {
            for (int p = K.colptr[j]; p < K.colptr[j + 1]; p++)
                cs_entry(T, o + K.rowind[p], o + j, K.values[p]);
            for (int p = M.colptr[j]; p < M.colptr[j + 1]; p++)
                cs_entry(T, o + M.rowind[p], o + j, -kw2 * M.values[p]);
            if (!k) continue;
            /* cos rows take +kw D on sin columns; sin rows -kw D on cos columns */
            for (int p = D.colptr[j]; p < D.colptr[j + 1]; p++)
                cs_entry(T, o + D.rowind[p], (half ? 0 : nf) + j, (half ? -kw : kw) * D.values[p]);
        }
    }
    cs *C = cs_compress(T);
    cs_spfree(T);
    if (!C || !cs_dupl(C)) {
        cs_spfree(C);
        return NULL;
    }
    cs *Ct = cs_transpose(C, 1), *S = Ct ? cs_transpose(Ct, 1) : NULL; /* sorts the rows */
    cs_spfree(C);
    cs_spfree(Ct);
    return S;
}

/* Factors block k; the symbolic analysis is (re)made when the pattern differs. */
static int factor_block(hb *h, gd_transient *tr, double w, int k)
{
    cs *A = block(h, tr, w, k);
    if (!A) return 1;
    int **Pp = k ? &h->Lp : &h->L0p, **Pi = k ? &h->Li : &h->L0i;
    klu_symbolic **sym = k ? &h->Lsym : &h->L0sym;
    int n = A->n, nz = A->p[n];
    int same = *sym && *Pp && (*Pp)[n] == nz && !memcmp(*Pp, A->p, (size_t)(n + 1) * sizeof(int)) &&
               !memcmp(*Pi, A->i, (size_t)nz * sizeof(int));
    if (!same) {
        if (*sym) klu_free_symbolic(sym, &h->com);
        free(*Pp);
        free(*Pi);
        *Pp = malloc((size_t)(n + 1) * sizeof(int));
        *Pi = malloc((size_t)(nz > 0 ? nz : 1) * sizeof(int));
        if (!*Pp || !*Pi) {
            cs_spfree(A);
            return 1;
        }
        memcpy(*Pp, A->p, (size_t)(n + 1) * sizeof(int));
        memcpy(*Pi, A->i, (size_t)nz * sizeof(int));
        *sym = klu_analyze(n, *Pp, *Pi, &h->com);
    }
    if (h->Lnum[k]) klu_free_numeric(&h->Lnum[k], &h->com);
    h->Lnum[k] = *sym ? klu_factor(A->p, A->i, A->x, *sym, &h->com) : NULL;
    cs_spfree(A);
    return h->Lnum[k] && h->com.status == KLU_OK ? 0 : 1;
}

/* Slot a (harmonic index) -> block k and offset of that slot inside the block. */
static void slot_of(const hb *h, int a, int *k, int *off)
{
    *k = (a + 1) / 2;
    *off = (a && !(a & 1)) ? h->nf : 0;
}

/* y = L^-1 b over all blocks (b, y of length n; may alias). */
static void solve_L(hb *h, const double *b, double *y)
{
    if (y != b) memcpy(y, b, (size_t)h->n * sizeof *y);
    klu_solve(h->L0sym, h->Lnum[0], h->nf, 1, y, &h->com);
    for (int k = 1; k <= h->H; k++)
        klu_solve(h->Lsym, h->Lnum[k], 2 * h->nf, 1, y + (size_t)(2 * k - 1) * h->nf, &h->com);
}

static int bsize(const hb *h, int k)
{
    return k ? 2 * h->nf : h->nf;
}

int gd_hb_lowrank_factor(hb *h, gd_transient *tr, double w, const double *dRdp, const double *row)
{
    const int nf = h->nf, nh = h->nh, n = h->n, nt = h->nterm;
    const int r = nt * nh, bw = 2 * nf;
    if (gd_hb_couplings(h, w)) return 1;
    if (!h->Lnum || h->r != r) {
        gd_hb_lowrank_free(h);
        h->L_id = 0;
        h->r = r;
        h->Lnum = calloc((size_t)h->H + 1, sizeof *h->Lnum);
        h->P = malloc((size_t)(r > 0 ? r : 1) * bw * sizeof *h->P);
        h->S = malloc((size_t)(r > 0 ? r : 1) * (r > 0 ? r : 1) * sizeof *h->S);
        h->Spiv = malloc((size_t)(r > 0 ? r : 1) * sizeof *h->Spiv);
        h->xc = malloc((size_t)n * sizeof *h->xc);
        h->brow = malloc((size_t)(n + 1) * sizeof *h->brow);
        h->wr = malloc((size_t)(r > 0 ? r : 1) * sizeof *h->wr);
        h->wz = malloc((size_t)(r > 0 ? r : 1) * sizeof *h->wz);
        if (!h->Lnum || !h->P || !h->S || !h->Spiv || !h->xc || !h->brow || !h->wr || !h->wz)
            return 1;
    }
    /* L and P depend only on the problem and the frequency: a fixed-value Newton (and
     * the requested points) reuses them, only the capacitance follows the iterate */
    int fresh = !(h->L_id == h->stage_id && h->L_w == w && h->stage_id > 0);
    for (int k = 0; fresh && k <= h->H; k++)
        if (factor_block(h, tr, w, k)) {
            h->L_id = 0;
            return 1;
        }
    h->L_id = h->stage_id;
    h->L_w = w;
    /* P = L^-1 U, column (t, a) held inside its block (length bw) */
    for (int t = 0; fresh && t < nt; t++) {
        const gd_tr_term *tm = &h->term[t];
        for (int a = 0; a < nh; a++) {
            int k, off;
            slot_of(h, a, &k, &off);
            double *p = h->P + ((size_t)t * nh + a) * bw;
            memset(p, 0, (size_t)bw * sizeof *p);
            for (int i = 0; i < tm->nu; i++)
                p[off + tm->u_idx[i]] = tm->u[i];
            if (k)
                klu_solve(h->Lsym, h->Lnum[k], bw, 1, p, &h->com);
            else
                klu_solve(h->L0sym, h->Lnum[0], nf, 1, p, &h->com);
        }
    }
    /* S = I - (W^T P) C; (W^T P) is non-zero only between slots of one block */
    memset(h->S, 0, (size_t)r * r * sizeof *h->S);
    for (int i = 0; i < r; i++)
        h->S[(size_t)i * r + i] = 1.0;
    for (int t = 0; t < nt; t++)
        for (int a = 0; a < nh; a++) {
            int k, off;
            slot_of(h, a, &k, &off);
            const double *p = h->P + ((size_t)t * nh + a) * bw;
            const double *G = h->Gall + (size_t)t * nh * nh; /* G[b * nh + a] = G_ab */
            int slots[2] = {k ? 2 * k - 1 : 0, 2 * k}, ns = k ? 2 : 1;
            for (int t2 = 0; t2 < nt; t2++) {
                const gd_tr_term *w2 = &h->term[t2];
                for (int q = 0; q < ns; q++) {
                    int b2 = slots[q], o2 = q ? nf : 0;
                    double m = 0.0;
                    for (int j = 0; j < w2->nw; j++)
                        m += w2->w[j] * p[o2 + w2->w_idx[j]];
                    if (m == 0.0) continue;
                    /* row (t2, b2); columns (t, b): - m G_t[a][b] */
                    double *Srow = h->S + (size_t)t2 * nh + b2;
                    for (int b = 0; b < nh; b++)
                        Srow[((size_t)t * nh + b) * r] -= m * G[(size_t)b * nh + a];
                }
            }
        }
    if (r && LAPACKE_dgetrf(LAPACK_COL_MAJOR, r, r, h->S, r, h->Spiv)) return 1;
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

void gd_hb_lowrank_solve_J(hb *h, double *x)
{
    const int nf = h->nf, nh = h->nh, nt = h->nterm, r = h->r, bw = 2 * nf;
    solve_L(h, x, x);
    if (!r) return;
    /* z = W^T y, s = S^-1 z, v = C s, x += P v */
    for (int t = 0; t < nt; t++) {
        const gd_tr_term *tm = &h->term[t];
        for (int b = 0; b < nh; b++) {
            double z = 0.0;
            for (int j = 0; j < tm->nw; j++)
                z += tm->w[j] * x[(size_t)b * nf + tm->w_idx[j]];
            h->wz[(size_t)t * nh + b] = z;
        }
    }
    LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', r, 1, h->S, r, h->Spiv, h->wz, r);
    for (int t = 0; t < nt; t++) {
        const double *G = h->Gall + (size_t)t * nh * nh;
        for (int a = 0; a < nh; a++) {
            double v = 0.0;
            for (int b = 0; b < nh; b++)
                v += G[(size_t)b * nh + a] * h->wz[(size_t)t * nh + b];
            int k, off;
            slot_of(h, a, &k, &off);
            const double *p = h->P + ((size_t)t * nh + a) * bw;
            double *xb = x + (size_t)(k ? 2 * k - 1 : 0) * nf;
            for (int i = 0; i < bsize(h, k); i++)
                xb[i] += p[i] * v;
        }
    }
}

void gd_hb_lowrank_solve(hb *h, double *b)
{
    const int n = h->n;
    double beta = b[n];
    gd_hb_lowrank_solve_J(h, b);
    double y = beta;
    for (int i = 0; i < n; i++)
        y -= h->brow[i] * b[i];
    y /= h->denom;
    for (int i = 0; i < n; i++)
        b[i] -= y * h->xc[i];
    b[n] = y;
}
