/* The building blocks of the harmonic-balance Jacobian that the dense and the low-rank
 * solvers (hb.c, lowrank.c) both use: the linear matrices K, M and D on one union
 * pattern (the harmonic blocks K - (k w)^2 M -+ k w D in one pass), and each nonlinear
 * term's coupling matrix G between the harmonics from the Fourier moments of its
 * samples (docs/periodic.md). */
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

/* The union pattern of K, M and D (sorted CSC over the nf free DOFs) with each matrix's
 * values on it (UK, UM, UD): the harmonic blocks K - (k w)^2 M -+ k w D in one pass. The
 * pattern id changes only when the pattern does (the low-rank path keeps its symbolic
 * analysis while it holds). 0 ok, 1 out of memory. */
int gd_hb_linear_union(hb *h, gd_transient *tr)
{
    const int nf = h->nf;
    gd_csc A[3];
    gd_transient_matrices(tr, &A[1], &A[2], &A[0]); /* M, D, K -> A = {K, M, D} */
    size_t cap = (size_t)A[0].colptr[nf] + A[1].colptr[nf] + A[2].colptr[nf];
    if (!h->umark) {
        h->umark = malloc((size_t)(nf > 0 ? nf : 1) * sizeof *h->umark);
        h->Up = malloc((size_t)(nf + 1) * sizeof *h->Up);
        h->Uq = malloc((size_t)(nf + 1) * sizeof *h->Uq);
        if (!h->umark || !h->Up || !h->Uq) return 1;
    }
    if (h->ucap < cap) {
        free(h->Ui);
        free(h->Ui2);
        free(h->UK);
        h->ucap = 0;
        h->Ui = malloc((cap ? cap : 1) * sizeof *h->Ui);
        h->Ui2 = malloc((cap ? cap : 1) * sizeof *h->Ui2);
        h->UK = malloc(3 * (cap ? cap : 1) * sizeof *h->UK);
        if (!h->Ui || !h->Ui2 || !h->UK) return 1;
        h->ucap = cap;
        h->Unz = -1; /* no pattern held */
    }
    /* the pattern into Uq / Ui2, compared with the held Up / Ui */
    int *mark = h->umark, nz = 0;
    for (int i = 0; i < nf; i++)
        mark[i] = -1;
    h->Uq[0] = 0;
    for (int j = 0; j < nf; j++) {
        for (int m = 0; m < 3; m++)
            for (int q = A[m].colptr[j]; q < A[m].colptr[j + 1]; q++) {
                int i = A[m].rowind[q];
                if (mark[i] == j) continue;
                mark[i] = j;
                int at = nz++; /* insertion keeps the column sorted (columns are short) */
                while (at > h->Uq[j] && h->Ui2[at - 1] > i) {
                    h->Ui2[at] = h->Ui2[at - 1];
                    at--;
                }
                h->Ui2[at] = i;
            }
        h->Uq[j + 1] = nz;
    }
    if (nz != h->Unz || memcmp(h->Up, h->Uq, (size_t)(nf + 1) * sizeof *h->Up) ||
        memcmp(h->Ui, h->Ui2, (size_t)nz * sizeof *h->Ui)) {
        int *t = h->Up;
        h->Up = h->Uq;
        h->Uq = t;
        t = h->Ui;
        h->Ui = h->Ui2;
        h->Ui2 = t;
        h->Unz = nz;
        h->Upat_id++;
    }
    h->UM = h->UK + nz;
    h->UD = h->UM + nz;
    memset(h->UK, 0, 3 * (size_t)nz * sizeof *h->UK);
    double *U[3] = {h->UK, h->UM, h->UD};
    for (int m = 0; m < 3; m++)
        for (int j = 0; j < nf; j++)
            for (int q = A[m].colptr[j]; q < A[m].colptr[j + 1]; q++) {
                int lo = h->Up[j], hi = h->Up[j + 1] - 1, i = A[m].rowind[q];
                while (lo < hi) { /* the row is in the column: binary search */
                    int mid = (lo + hi) / 2;
                    if (h->Ui[mid] < i)
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                U[m][lo] += A[m].values[q];
            }
    return 0;
}

/* Moments (1/N) sum_j s_j cos(p tau_j) and sin, p = 0..2H, from the half-complex DFT
 * of the samples (p reduced modulo N, so the sums equal the sampled ones exactly). */
static void trig_moments(const hb *h, const double *hc, double *C, double *S)
{
    const int N = h->N;
    for (int p = 0; p <= 2 * h->H; p++) {
        int q = p % N, sg = 1;
        if (q > N / 2) {
            q = N - q;
            sg = -1;
        }
        C[p] = hc[q] / N;
        S[p] = (q == 0 || 2 * q == N) ? 0.0 : -sg * hc[N - q] / N;
    }
}

/* (1/N) sum_j s_j f_a(ka tau_j) f_b(kb tau_j), f = cos (0) or sin (1), by the product
 * formulas: only the moments of s at ka - kb and ka + kb enter. */
static double product_moment(const double *C, const double *S, int fa, int ka, int fb, int kb)
{
    int dm = ka - kb, dp = ka + kb;
    double cm = C[dm < 0 ? -dm : dm], sm = dm < 0 ? -S[-dm] : S[dm];
    if (!fa && !fb) return 0.5 * (cm + C[dp]);
    if (fa && fb) return 0.5 * (cm - C[dp]);
    if (fa) return 0.5 * (S[dp] + sm);
    return 0.5 * (S[dp] - sm);
}

/* G_ab from the Fourier moments of s_q and s_v (O(N log N + nh^2) per term instead of
 * the O(N nh^2) sample sum): the product of two basis functions is a sum of two
 * harmonics, so G is Toeplitz-plus-Hankel in the harmonic index. */
int gd_hb_couplings(hb *h, double w)
{
    const int nh = h->nh, N = h->N, H = h->H;
    size_t need = (size_t)(h->nterm > 0 ? h->nterm : 1) * nh * nh;
    if (h->nGall < need) {
        free(h->Gall);
        h->Gall = malloc(need * sizeof *h->Gall);
        h->nGall = h->Gall ? need : 0;
        if (!h->Gall) return 1;
    }
    /* the moments through the single-row plan (unaligned: any two buffers of N) */
    double *buf = malloc((size_t)2 * N * sizeof *buf), *hc = buf ? buf + N : NULL;
    double *mom = malloc((size_t)4 * (2 * H + 1) * sizeof *mom);
    if (!buf || !mom) {
        free(buf);
        free(mom);
        return 1;
    }
    double *Cq = mom, *Sq = Cq + 2 * H + 1, *Cv = Sq + 2 * H + 1, *Sv = Cv + 2 * H + 1;
    free(h->tactive);
    h->tactive = malloc((size_t)(h->nterm > 0 ? h->nterm : 1) * sizeof *h->tactive);
    if (!h->tactive) {
        free(buf);
        free(mom);
        return 1;
    }
    for (int t = 0; t < h->nterm; t++) {
        /* a term that is zero in every sample (a constant load's) has G = 0: the low-rank
         * path leaves it out of the rank */
        const double *sq = h->sq + (size_t)t * N, *sv = h->sv + (size_t)t * N;
        int on = 0;
        for (int j = 0; j < N && !on; j++)
            on = sq[j] != 0.0 || sv[j] != 0.0;
        h->tactive[t] = (unsigned char)on;
        double *G = h->Gall + (size_t)t * nh * nh;
        if (!on) {
            memset(G, 0, (size_t)nh * nh * sizeof *G);
            continue;
        }
        memcpy(buf, h->sq + (size_t)t * N, (size_t)N * sizeof *buf);
        fftw_execute_r2r(h->row_fwd, buf, hc);
        trig_moments(h, hc, Cq, Sq);
        memcpy(buf, h->sv + (size_t)t * N, (size_t)N * sizeof *buf);
        fftw_execute_r2r(h->row_fwd, buf, hc);
        trig_moments(h, hc, Cv, Sv);
        for (int b = 0; b < nh; b++) {
            int kb = (b + 1) / 2, fb = b && !(b & 1);
            /* phi_b' = -kb sin (cos basis) or kb cos (sin basis) */
            int fd = !fb;
            double cd = fb ? kb : -kb;
            for (int a = 0; a < nh; a++) {
                int ka = (a + 1) / 2, fa = a && !(a & 1);
                double g = product_moment(Cq, Sq, fa, ka, fb, kb);
                if (kb) g += w * cd * product_moment(Cv, Sv, fa, ka, fd, kb);
                G[(size_t)b * nh + a] = (a ? 2.0 : 1.0) * g;
            }
        }
    }
    free(buf);
    free(mom);
    return 0;
}
