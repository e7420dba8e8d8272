/* The condensed torus (qphb_impl.h, gd_qpc): multi-frequency harmonic balance with the
 * laws' coordinates as the only unknowns. The receptances are shifted by the terms' torus
 * means (Z'_k = Z_k - C (Tq + i W_k Tv) C^T, the time-invariant part of the laws: it holds
 * the gears on their mean mesh stiffness, so Z'_0 is regular where K alone is not), the
 * forces by the same amount (G' = G - (Tq + i W_k Tv) Y), so that
 *   Y_k = C^T Z'_k^-1 r_k + H'_k G'_k(Y),   H'_k = C^T Z'_k^-1 C,
 * and Newton's linear systems I - H'_k (T - Tmean) need no preconditioner for the
 * fluctuation of a mesh stiffness (GMRES, SUNDIALS SPGMR). Real FFTs (FFTW r2c, c2r) of
 * the nc coordinates on the d-dimensional grid. */
#include <complex.h>
#include <klu.h>
#include <lapacke.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include "periodic/multifreq/qphb_impl.h"
#include "signal/fft_planner_impl.h"
#include "transient/transient_impl.h"

/* more coordinates than this: the full torus (the condensation pays with few) */
#define QPC_MAX_COORDS 48

struct gd_qpc {
    gd_transient *tr; /* borrowed */
    const gd_qp_bases *b;
    gd_qp_torus T;
    int nf, nt, nc;
    const gd_tr_term *term;
    double *cd;    /* nf x nc: the coordinates' directions, dense, column-major */
    int *sup, ns;  /* the DOFs any direction touches */
    int *tu, *tw;  /* nt: each term's force and reading coordinate (-1: none) */
    double *tsc;   /* nt: u_t w_t^T = tsc c_tu c_tw^T */
    double *gram;  /* nc x nc: (C^T C)^-1 */
    long n, Nh;    /* unknowns nc (2 nk - 1); points of the half-complex grid */
    long *hp, *hn; /* nk: where +k and -k fall in the half grid (-1: not there) */
    double *rb;    /* nc x Ntot */
    fftw_complex *cb;
    fftw_plan c2r, r2c, r2c1;
    double *ys, *vs, *gs, *jq, *jv; /* nc x Ntot; nt x Ntot: each term's sq tsc, sv tsc */
    double *tq, *tv;                /* nc x nc: the terms' torus means (the shift) */
    double complex *Hk, *Pk, *x0;   /* nk x nc x nc; nk x nf x nc; nk x nf */
    double *y0, *R, *G, *w2, *yfull, *f, *st, *z, *ltime;
    long matvecs;
};

const gd_qp_torus *gd_qpc_torus(const gd_qpc *c)
{
    return &c->T;
}

void gd_qpc_view(gd_qpc *c, gd_qp *q)
{
    memset(q, 0, sizeof *q);
    q->tr = c->tr;
    q->nf = c->nf;
    q->nt = c->nt;
    q->term = c->term;
    q->b = c->b;
    q->T = c->T; /* shared: the view does not free it */
    q->n = gd_qp_unknowns(&c->T, c->nf);
    q->y = c->yfull;
    q->ltime = c->ltime;
}

void gd_qpc_free(gd_qpc *c)
{
    if (!c) return;
    if (c->c2r) fftw_destroy_plan(c->c2r);
    if (c->r2c) fftw_destroy_plan(c->r2c);
    if (c->r2c1) fftw_destroy_plan(c->r2c1);
    fftw_free(c->rb);
    fftw_free(c->cb);
    fftw_free(c->ys);
    fftw_free(c->vs);
    fftw_free(c->gs);
    void *own[] = {c->cd, c->sup, c->tu,    c->tw, c->tsc, c->gram, c->hp,   c->hn,
                   c->jq, c->jv,  c->tq,    c->Hk, c->Pk,  c->x0,   c->y0,   c->R,
                   c->G,  c->w2,  c->yfull, c->f,  c->st,  c->z,    c->ltime};
    for (size_t i = 0; i < sizeof own / sizeof *own; i++)
        free(own[i]);
    if (c->tr) c->tr->law_time = NULL;
    gd_qp_torus_free(&c->T);
    free(c);
}

/* The coordinate along the sparse vector (idx, val) up to a scale (*s: vec = s c_j),
 * appended to cd (room for nf x QPC_MAX_COORDS) when new; -1 when there are too many. */
static int coord_of(gd_qpc *c, int n, const int *idx, const double *val, double *s)
{
    const int nf = c->nf;
    double vmax = 0.0;
    for (int e = 0; e < n; e++)
        vmax = fmax(vmax, fabs(val[e]));
    for (int j = 0; j < c->nc; j++) {
        const double *cj = c->cd + (size_t)j * nf;
        double r = 0.0, cm = 0.0;
        for (int e = 0; e < n; e++)
            if (fabs(cj[idx[e]]) > cm) {
                cm = fabs(cj[idx[e]]);
                r = val[e] / cj[idx[e]];
            }
        if (cm == 0.0) continue;
        int same = 1, cnt = 0;
        for (int i = 0; i < nf; i++)
            cnt += cj[i] != 0.0;
        same = cnt == n;
        for (int e = 0; e < n && same; e++)
            same = fabs(val[e] - r * cj[idx[e]]) <= 1e-13 * vmax;
        if (same) {
            *s = r;
            return j;
        }
    }
    if (c->nc == QPC_MAX_COORDS) return -1;
    double *cj = c->cd + (size_t)c->nc * nf;
    for (int e = 0; e < n; e++)
        cj[idx[e]] += val[e];
    *s = 1.0;
    return c->nc++;
}

/* The coordinates of the problem's terms and their Gram inverse. 0 ok, 1 they cannot
 * serve (none, too many, dependent), 2 no memory. */
static int build_coords(gd_qpc *c)
{
    const int nf = c->nf, nt = c->nt;
    if (nt <= 0) return 1;
    c->cd = calloc((size_t)nf * QPC_MAX_COORDS, sizeof *c->cd);
    c->tu = malloc((size_t)nt * sizeof *c->tu);
    c->tw = malloc((size_t)nt * sizeof *c->tw);
    c->tsc = malloc((size_t)nt * sizeof *c->tsc);
    c->sup = malloc((size_t)nf * sizeof *c->sup);
    if (!c->cd || !c->tu || !c->tw || !c->tsc || !c->sup) return 2;
    for (int pass = 0; pass < 2; pass++) /* force directions first, then the readings */
        for (int t = 0; t < nt; t++) {
            const gd_tr_term *m = &c->term[t];
            if (!m->nu || !m->nw) {
                c->tu[t] = c->tw[t] = -1;
                continue;
            }
            double s;
            int j = pass ? coord_of(c, m->nw, m->w_idx, m->w, &s)
                         : coord_of(c, m->nu, m->u_idx, m->u, &s);
            if (j < 0) return 1;
            if (pass) {
                c->tw[t] = j;
                c->tsc[t] *= s;
            } else {
                c->tu[t] = j;
                c->tsc[t] = s;
            }
        }
    const int nc = c->nc;
    if (nc == 0 || nc > nf) return 1;
    c->gram = calloc((size_t)nc * nc, sizeof *c->gram);
    if (!c->gram) return 2;
    for (int i = 0; i < nc; i++)
        for (int j = 0; j < nc; j++) {
            double s = 0.0;
            for (int k = 0; k < nf; k++)
                s += c->cd[(size_t)i * nf + k] * c->cd[(size_t)j * nf + k];
            c->gram[i + (size_t)nc * j] = s;
        }
    double dmax = 0.0;
    for (int i = 0; i < nc; i++)
        dmax = fmax(dmax, c->gram[i + (size_t)nc * i]);
    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', nc, c->gram, nc)) return 1;
    for (int i = 0; i < nc; i++)
        if (c->gram[i + (size_t)nc * i] * c->gram[i + (size_t)nc * i] < 1e-12 * dmax) return 1;
    if (LAPACKE_dpotri(LAPACK_COL_MAJOR, 'L', nc, c->gram, nc)) return 1;
    for (int j = 0; j < nc; j++)
        for (int i = 0; i < j; i++)
            c->gram[i + (size_t)nc * j] = c->gram[j + (size_t)nc * i];
    c->ns = 0;
    for (int k = 0; k < nf; k++) {
        int on = 0;
        for (int j = 0; j < nc && !on; j++)
            on = c->cd[(size_t)j * nf + k] != 0.0;
        if (on) c->sup[c->ns++] = k;
    }
    return 0;
}

int gd_qpc_applies(gd_transient *tr)
{
    gd_qpc c;
    memset(&c, 0, sizeof c);
    c.nf = gd_transient_nstates(tr) / 2;
    c.nt = gd_transient_terms(tr, &c.term);
    int bc = c.nt > 0 ? build_coords(&c) : -1;
    int ok = bc == 0 ? c.nc : 0;
    free(c.cd);
    free(c.tu);
    free(c.tw);
    free(c.tsc);
    free(c.sup);
    free(c.gram);
    return ok;
}

/* z := (C^T C)^-1 z (nc) */
static void gram_solve(const gd_qpc *c, double *z, double *tmp)
{
    const int nc = c->nc;
    memcpy(tmp, z, (size_t)nc * sizeof *z);
    for (int i = 0; i < nc; i++) {
        double s = 0.0;
        for (int j = 0; j < nc; j++)
            s += c->gram[i + (size_t)nc * j] * tmp[j];
        z[i] = s;
    }
}

static double omega_of(const gd_qp_torus *T, int j)
{
    double w = 0.0;
    for (int g = 0; g < T->d; g++)
        w += T->k[j * T->d + g] * T->W[g];
    return w;
}

/* index of the wrapped harmonic k in the half-complex grid, -1 when its last component
 * falls in the half FFTW does not store */
static long half_index(const gd_qp_torus *T, const int *k, int sign)
{
    long p = 0;
    const int d = T->d;
    for (int g = 0; g < d; g++) {
        const int N = T->N[g];
        const long w = (((sign * k[g]) % N) + N) % N;
        if (g == d - 1) {
            if (w > N / 2) return -1;
            p = p * (N / 2 + 1) + w;
        } else
            p = p * N + w;
    }
    return p;
}

/* Samples (coordinate-major, out[i * Ntot + p]) of the coordinates Y or of their time
 * derivative. */
static void synth(gd_qpc *c, const double *Y, int deriv, double *out)
{
    const int nc = c->nc;
    const long Nh = c->Nh;
    memset(c->cb, 0, (size_t)nc * Nh * sizeof *c->cb);
    for (int i = 0; i < nc; i++) {
        fftw_complex *b = c->cb + (size_t)i * Nh;
        if (!deriv) b[0] = Y[i];
        for (int j = 1; j < c->T.nk; j++) {
            double complex z =
                0.5 * (Y[(size_t)(2 * j - 1) * nc + i] - I * Y[(size_t)2 * j * nc + i]);
            if (deriv) z *= I * omega_of(&c->T, j);
            if (c->hp[j] >= 0) b[c->hp[j]] += z;
            if (c->hn[j] >= 0) b[c->hn[j]] += conj(z);
        }
    }
    fftw_execute_dft_c2r(c->c2r, c->cb, out);
}

/* Coefficients (nc layout) of the coordinate-major samples s on the truncation set. */
static void analyse(gd_qpc *c, double *s, double *G)
{
    const int nc = c->nc;
    const long Nh = c->Nh;
    const double sc = 1.0 / (double)c->T.Ntot;
    fftw_execute_dft_r2c(c->r2c, s, c->cb);
    for (int i = 0; i < nc; i++) {
        const fftw_complex *b = c->cb + (size_t)i * Nh;
        G[i] = creal(b[0]) * sc;
        for (int j = 1; j < c->T.nk; j++) {
            double complex z = c->hp[j] >= 0 ? b[c->hp[j]] : conj(b[c->hn[j]]);
            G[(size_t)(2 * j - 1) * nc + i] = 2.0 * creal(z) * sc;
            G[(size_t)2 * j * nc + i] = -2.0 * cimag(z) * sc;
        }
    }
}

/* Sets each law's time at grid point p; the problem's t (base 1's) returned. */
static double point_times(gd_qpc *c, long p)
{
    gd_qp v;
    v.T = c->T;
    v.b = c->b;
    v.tr = c->tr;
    v.ltime = c->ltime;
    return gd_qp_point_times(&v, p);
}

/* The forces along the coordinates at every grid point of Y into gs (and, with jac, the
 * local Jacobians jq, jv); with r (nf x Ntot, DOF-major) the rest of f there. 0 ok, 1 a
 * force is not finite. */
static int forces(gd_qpc *c, const double *Y, int jac, double *r)
{
    const int nc = c->nc, nf = c->nf, nt = c->nt;
    const long Nt = c->T.Ntot;
    double *q = c->yfull, *v = c->yfull + nf, tmp[QPC_MAX_COORDS];
    synth(c, Y, 0, c->ys);
    synth(c, Y, 1, c->vs);
    int bad = 0;
    for (long p = 0; p < Nt; p++) {
        for (int deriv = 0; deriv < 2; deriv++) { /* q = C (C^T C)^-1 y on the support */
            const double *src = deriv ? c->vs : c->ys;
            double *dst = deriv ? v : q;
            for (int i = 0; i < nc; i++)
                c->z[i] = src[(size_t)i * Nt + p];
            gram_solve(c, c->z, tmp);
            for (int e = 0; e < c->ns; e++) {
                const int k = c->sup[e];
                double s = 0.0;
                for (int i = 0; i < nc; i++)
                    s += c->cd[(size_t)i * nf + k] * c->z[i];
                dst[k] = s;
            }
        }
        const double t = point_times(c, p);
        gd_transient_local(c->tr, t, c->yfull, c->f, jac ? c->st : NULL, jac ? c->st + nt : NULL);
        for (int i = 0; i < nc; i++) {
            double s = 0.0;
            for (int e = 0; e < c->ns; e++)
                s += c->cd[(size_t)i * nf + c->sup[e]] * c->f[c->sup[e]];
            c->z[i] = s;
        }
        gram_solve(c, c->z, tmp);
        for (int i = 0; i < nc; i++) {
            if (!isfinite(c->z[i])) bad = 1;
            c->gs[(size_t)i * Nt + p] = c->z[i];
        }
        if (r) {
            for (int k = 0; k < nf; k++)
                r[(size_t)k * Nt + p] = c->f[k];
            for (int i = 0; i < nc; i++)
                for (int e = 0; e < c->ns; e++)
                    r[(size_t)c->sup[e] * Nt + p] -= c->cd[(size_t)i * nf + c->sup[e]] * c->z[i];
        }
        if (jac) /* dg/dy = sum_t sq_t tsc_t e_tu e_tw^T (the laws read y_tw) */
            for (int k = 0; k < nt; k++) {
                c->jq[(size_t)k * Nt + p] = c->tu[k] < 0 ? 0.0 : c->st[k] * c->tsc[k];
                c->jv[(size_t)k * Nt + p] = c->tu[k] < 0 ? 0.0 : c->st[nt + k] * c->tsc[k];
            }
    }
    c->tr->law_time = NULL;
    return bad;
}

/* The receptances Z'_k^-1 [C r_k] of every harmonic (one sparse complex LU each, KLU on
 * the union pattern of K, M, D and C C^T), H'_k and y0. 0 ok, 1 singular, 2 no memory. */
static int receptances(gd_qpc *c, const double complex *rk)
{
    const int nf = c->nf, nc = c->nc, nk = c->T.nk;
    gd_csc M, D, K;
    gd_transient_matrices(c->tr, &M, &D, &K);
    /* dense marks per column: K, M, D and the shift's support */
    int cap = K.colptr[nf] + M.colptr[nf] + D.colptr[nf] + c->ns * c->ns + nf;
    int *Ap = malloc((size_t)(nf + 1) * sizeof *Ap), *Ai = malloc((size_t)cap * sizeof *Ai),
        *pos = malloc((size_t)nf * sizeof *pos);
    double *AK = calloc((size_t)cap * 4, sizeof *AK), *Ax = malloc((size_t)cap * 2 * sizeof *Ax);
    double complex *B = malloc((size_t)nf * (nc + 1) * sizeof *B);
    unsigned char *insup = calloc((size_t)nf, 1);
    klu_common com;
    klu_symbolic *sym = NULL;
    int rc = 2;
    if (!Ap || !Ai || !pos || !AK || !Ax || !B || !insup) goto done;
    klu_defaults(&com);
    for (int e = 0; e < c->ns; e++)
        insup[c->sup[e]] = 1;
    for (int i = 0; i < nf; i++)
        pos[i] = -1;
    int nz = 0;
    Ap[0] = 0;
    for (int j = 0; j < nf; j++) {
        const int start = nz;
        const gd_csc *mats[3] = {&K, &M, &D};
        for (int m = 0; m < 3; m++)
            for (int p = mats[m]->colptr[j]; p < mats[m]->colptr[j + 1]; p++)
                if (pos[mats[m]->rowind[p]] < 0) {
                    pos[mats[m]->rowind[p]] = nz;
                    Ai[nz++] = mats[m]->rowind[p];
                }
        if (insup[j])
            for (int e = 0; e < c->ns; e++)
                if (pos[c->sup[e]] < 0) {
                    pos[c->sup[e]] = nz;
                    Ai[nz++] = c->sup[e];
                }
        /* sorted rows (insertion: a column holds few) */
        for (int a = start + 1; a < nz; a++)
            for (int b2 = a; b2 > start && Ai[b2 - 1] > Ai[b2]; b2--) {
                int t = Ai[b2];
                Ai[b2] = Ai[b2 - 1];
                Ai[b2 - 1] = t;
            }
        for (int a = start; a < nz; a++)
            pos[Ai[a]] = a;
        /* values: K, M, D, then the shift's real (Tq) and imaginary-per-W (Tv) parts */
        for (int m = 0; m < 3; m++)
            for (int p = mats[m]->colptr[j]; p < mats[m]->colptr[j + 1]; p++)
                AK[(size_t)pos[mats[m]->rowind[p]] * 4 + m] += mats[m]->values[p];
        if (insup[j])
            for (int e = 0; e < c->ns; e++) { /* - (C Tq C^T)[row, j]: Tv into slot 3 */
                const int row = c->sup[e];
                double sq = 0.0, sv = 0.0;
                for (int a = 0; a < nc; a++)
                    for (int b2 = 0; b2 < nc; b2++) {
                        const double cc = c->cd[(size_t)a * nf + row] * c->cd[(size_t)b2 * nf + j];
                        sq += cc * c->tq[a + (size_t)nc * b2];
                        sv += cc * c->tv[a + (size_t)nc * b2];
                    }
                AK[(size_t)pos[row] * 4 + 0] -= sq;
                AK[(size_t)pos[row] * 4 + 3] -= sv;
            }
        for (int a = start; a < nz; a++)
            pos[Ai[a]] = -1;
        Ap[j + 1] = nz;
    }
    sym = klu_analyze(nf, Ap, Ai, &com);
    if (!sym) goto done;
    rc = 1;
    for (int h = 0; h < nk; h++) {
        const double w = omega_of(&c->T, h);
        for (int p = 0; p < nz; p++) {
            const double *a = AK + (size_t)p * 4;
            Ax[2 * p] = a[0] - w * w * a[1];
            Ax[2 * p + 1] = w * (a[2] + a[3]);
        }
        klu_numeric *num = klu_z_factor(Ap, Ai, Ax, sym, &com);
        if (!num) goto done;
        const double complex *r = rk + (size_t)h * nf;
        int withr = 0;
        for (int i = 0; i < nf && !withr; i++)
            withr = r[i] != 0.0;
        for (int a = 0; a < nc; a++)
            for (int i = 0; i < nf; i++)
                B[(size_t)a * nf + i] = c->cd[(size_t)a * nf + i];
        if (withr) memcpy(B + (size_t)nc * nf, r, (size_t)nf * sizeof *B);
        int ok = klu_z_solve(sym, num, nf, nc + withr, (double *)B, &com);
        klu_z_free_numeric(&num, &com);
        if (!ok) goto done;
        double complex *P = c->Pk + (size_t)h * nf * nc, *Hh = c->Hk + (size_t)h * nc * nc,
                       *x0 = c->x0 + (size_t)h * nf;
        memcpy(P, B, (size_t)nf * nc * sizeof *P);
        if (withr)
            memcpy(x0, B + (size_t)nc * nf, (size_t)nf * sizeof *x0);
        else
            memset(x0, 0, (size_t)nf * sizeof *x0);
        double complex y0[QPC_MAX_COORDS];
        for (int a = 0; a < nc; a++) {
            double complex s0 = 0.0;
            for (int e = 0; e < c->ns; e++)
                s0 += c->cd[(size_t)a * nf + c->sup[e]] * x0[c->sup[e]];
            y0[a] = s0;
            for (int b2 = 0; b2 < nc; b2++) {
                double complex s = 0.0;
                for (int e = 0; e < c->ns; e++)
                    s += c->cd[(size_t)a * nf + c->sup[e]] * P[(size_t)b2 * nf + c->sup[e]];
                Hh[a + (size_t)nc * b2] = s;
            }
        }
        for (int a = 0; a < nc; a++) {
            if (h == 0) {
                c->y0[a] = creal(y0[a]);
            } else {
                c->y0[(size_t)(2 * h - 1) * nc + a] = creal(y0[a]);
                c->y0[(size_t)2 * h * nc + a] = -cimag(y0[a]);
            }
        }
    }
    rc = 0;
done:
    if (sym) klu_free_symbolic(&sym, &com);
    free(Ap);
    free(Ai);
    free(pos);
    free(AK);
    free(Ax);
    free(B);
    free(insup);
    return rc;
}

/* out = in - H' (G - Tmean Y) per harmonic, in the cos / sin layout (G: the forces'
 * coefficients, Y: the coordinates', both nc layout). With y0: out -= y0. */
static void apply_h(const gd_qpc *c, const double *Y, const double *G, const double *y0,
                    double *out)
{
    const int nc = c->nc;
    for (int h = 0; h < c->T.nk; h++) {
        const double w = omega_of(&c->T, h);
        double complex g[QPC_MAX_COORDS], y[QPC_MAX_COORDS];
        const size_t oc = (size_t)(h ? 2 * h - 1 : 0) * nc, os = oc + nc;
        for (int a = 0; a < nc; a++) {
            y[a] = h ? Y[oc + a] - I * Y[os + a] : Y[oc + a];
            g[a] = h ? G[oc + a] - I * G[os + a] : G[oc + a];
        }
        for (int a = 0; a < nc; a++) /* G' = G - (Tq + i w Tv) Y */
            for (int b2 = 0; b2 < nc; b2++)
                g[a] -= (c->tq[a + (size_t)nc * b2] + I * w * c->tv[a + (size_t)nc * b2]) * y[b2];
        const double complex *Hh = c->Hk + (size_t)h * nc * nc;
        for (int a = 0; a < nc; a++) {
            double complex s = y[a];
            for (int b2 = 0; b2 < nc; b2++)
                s -= Hh[a + (size_t)nc * b2] * g[b2];
            if (y0) s -= h ? y0[oc + a] - I * y0[os + a] : y0[oc + a];
            out[oc + a] = creal(s);
            if (h) out[os + a] = -cimag(s);
        }
    }
}

/* R = Y - y0 - H' G'(Y); *scale max(|Y|, |y0 + H' G'|); G keeps G(Y). 0 ok, 1 a force
 * not finite. */
static int residual(gd_qpc *c, const double *Y, double *R, double *scale, int sampled)
{
    int bad = sampled ? 0 : forces(c, Y, 1, NULL); /* sampled: gs, jq, jv hold Y's */
    analyse(c, c->gs, c->G);
    apply_h(c, Y, c->G, c->y0, R);
    double ny = 0.0, nr = 0.0;
    for (long i = 0; i < c->n; i++) {
        ny += Y[i] * Y[i];
        nr += (Y[i] - R[i]) * (Y[i] - R[i]);
    }
    *scale = sqrt(fmax(ny, nr));
    return bad;
}

/* residual() as gd_qp_damped_step takes it (the samples are not kept) */
static int step_residual(void *c, const double *Y, double *R, double *scale)
{
    return residual(c, Y, R, scale, 0);
}

/* z = J v = v - H' ((T v) - Tmean v) at the last residual's samples */
static int atimes(void *data, N_Vector vv, N_Vector zz)
{
    gd_qpc *c = data;
    const int nc = c->nc;
    const long Nt = c->T.Ntot;
    const double *v = N_VGetArrayPointer(vv);
    synth(c, v, 0, c->ys);
    synth(c, v, 1, c->vs);
    memset(c->gs, 0, (size_t)nc * Nt * sizeof *c->gs);
    for (int k = 0; k < c->nt; k++) { /* per term: g_tu += sq y_tw + sv y'_tw */
        if (c->tu[k] < 0) continue;
        const double *Jq = c->jq + (size_t)k * Nt, *Jv = c->jv + (size_t)k * Nt,
                     *y = c->ys + (size_t)c->tw[k] * Nt, *yd = c->vs + (size_t)c->tw[k] * Nt;
        double *g = c->gs + (size_t)c->tu[k] * Nt;
        for (long p = 0; p < Nt; p++)
            g[p] += Jq[p] * y[p] + Jv[p] * yd[p];
    }
    analyse(c, c->gs, c->G);
    apply_h(c, v, c->G, NULL, N_VGetArrayPointer(zz));
    c->matvecs++;
    return 0;
}

gd_qpc *gd_qpc_new(gd_transient *tr, const gd_qp_bases *b, int H, char *msg, size_t cap)
{
    gd_fft_planner_init();
    gd_qpc *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(msg, cap, "out of memory");
        return NULL;
    }
    c->tr = tr;
    c->b = b;
    c->nf = gd_transient_nstates(tr) / 2;
    c->nt = gd_transient_terms(tr, &c->term);
    int bc = c->nt > 0 ? build_coords(c) : 1;
    if (bc || gd_qp_torus_init(&c->T, b, H)) {
        snprintf(msg, cap, bc == 1 ? "the laws' coordinates cannot be condensed" : "out of memory");
        gd_qpc_free(c);
        return NULL;
    }
    const int nf = c->nf, nc = c->nc, d = c->T.d, nk = c->T.nk;
    const long Nt = c->T.Ntot;
    c->n = (long)nc * (2L * nk - 1);
    c->Nh = Nt / c->T.N[d - 1] * (c->T.N[d - 1] / 2 + 1);
    const double bytes =
        16.0 * nk * (nf * (nc + 1.0) + nc * nc) + 8.0 * Nt * (3.0 * nc + 2.0 * c->nt + nf);
    if (bytes > 3e9) {
        snprintf(msg, cap,
                 "the condensed torus of order %d (%d harmonics, %ld grid points) on %d DOFs "
                 "needs about %.2g GB, over the 3 GB taken",
                 H, nk, Nt, nf, bytes / 1e9);
        gd_qpc_free(c);
        return NULL;
    }
    c->hp = malloc((size_t)nk * sizeof *c->hp);
    c->hn = malloc((size_t)nk * sizeof *c->hn);
    c->rb = fftw_malloc((size_t)Nt * sizeof *c->rb);
    c->cb = fftw_malloc((size_t)c->Nh * nc * sizeof *c->cb);
    c->ys = fftw_malloc((size_t)Nt * nc * sizeof *c->ys);
    c->vs = fftw_malloc((size_t)Nt * nc * sizeof *c->vs);
    c->gs = fftw_malloc((size_t)Nt * nc * sizeof *c->gs);
    c->jq = malloc((size_t)Nt * c->nt * sizeof *c->jq);
    c->jv = malloc((size_t)Nt * c->nt * sizeof *c->jv);
    c->tq = calloc(2 * (size_t)nc * nc, sizeof *c->tq);
    c->Hk = malloc((size_t)nk * nc * nc * sizeof *c->Hk);
    c->Pk = malloc((size_t)nk * nf * nc * sizeof *c->Pk);
    c->x0 = malloc((size_t)nk * nf * sizeof *c->x0);
    c->y0 = calloc((size_t)c->n, sizeof *c->y0);
    c->R = malloc((size_t)c->n * sizeof *c->R);
    c->G = malloc((size_t)c->n * sizeof *c->G);
    c->w2 = malloc((size_t)c->n * sizeof *c->w2);
    c->yfull = calloc(2 * (size_t)nf, sizeof *c->yfull);
    c->f = malloc((size_t)nf * sizeof *c->f);
    c->st = malloc(2 * (size_t)c->nt * sizeof *c->st);
    c->z = malloc((size_t)nc * sizeof *c->z);
    c->ltime = malloc((size_t)(tr->nlaw > 0 ? tr->nlaw : 1) * sizeof *c->ltime);
    if (!c->hp || !c->hn || !c->rb || !c->cb || !c->ys || !c->vs || !c->gs || !c->jq || !c->jv ||
        !c->tq || !c->Hk || !c->Pk || !c->x0 || !c->y0 || !c->R || !c->G || !c->w2 || !c->yfull ||
        !c->f || !c->st || !c->z || !c->ltime) {
        snprintf(msg, cap, "out of memory");
        gd_qpc_free(c);
        return NULL;
    }
    c->tv = c->tq + (size_t)nc * nc;
    for (int j = 0; j < nk; j++) {
        c->hp[j] = half_index(&c->T, c->T.k + (size_t)j * d, 1);
        c->hn[j] = half_index(&c->T, c->T.k + (size_t)j * d, -1);
    }
    /* real transforms over the nc coordinates (howmany), and one row for the loads */
    c->c2r = fftw_plan_many_dft_c2r(d, c->T.N, nc, c->cb, NULL, 1, (int)c->Nh, c->ys, NULL, 1,
                                    (int)Nt, FFTW_ESTIMATE);
    c->r2c = fftw_plan_many_dft_r2c(d, c->T.N, nc, c->gs, NULL, 1, (int)Nt, c->cb, NULL, 1,
                                    (int)c->Nh, FFTW_ESTIMATE);
    c->r2c1 = fftw_plan_many_dft_r2c(d, c->T.N, 1, c->rb, NULL, 1, (int)Nt, c->cb, NULL, 1,
                                     (int)c->Nh, FFTW_ESTIMATE);
    if (!c->c2r || !c->r2c || !c->r2c1) {
        snprintf(msg, cap, "out of memory");
        gd_qpc_free(c);
        return NULL;
    }
    return c;
}

/* The loads' harmonics r_k (nk x nf): the forces outside the coordinates at Y (no law
 * moves them), with Y's samples and local Jacobians kept. 0 ok, 1 not finite, 2 no
 * memory. */
static int loads(gd_qpc *c, const double *Y, double complex *rk)
{
    const int nf = c->nf;
    const long Nt = c->T.Ntot;
    double *r = malloc((size_t)nf * Nt * sizeof *r);
    if (!r) return 2;
    int bad = forces(c, Y, 1, r);
    memset(rk, 0, (size_t)c->T.nk * nf * sizeof *rk);
    for (int k = 0; k < nf && !bad; k++) {
        int any = 0;
        for (long p = 0; p < Nt && !any; p++)
            any = r[(size_t)k * Nt + p] != 0.0;
        if (!any) continue;
        memcpy(c->rb, r + (size_t)k * Nt, (size_t)Nt * sizeof *c->rb);
        fftw_execute_dft_r2c(c->r2c1, c->rb, c->cb);
        for (int j = 0; j < c->T.nk; j++) { /* complex Z = C - i S = 2 b / Nt (j > 0) */
            double complex z = c->hp[j] >= 0 ? c->cb[c->hp[j]] : conj(c->cb[c->hn[j]]);
            rk[(size_t)j * nf + k] = (j ? 2.0 : 1.0) * z / (double)Nt;
        }
    }
    free(r);
    return bad;
}

/* X (full) from the coordinates Y of the last residual: X_k = x0_k + P'_k G'_k. */
static void recover(gd_qpc *c, const double *Y, double *X)
{
    const int nf = c->nf, nc = c->nc; /* G: the last residual's, at Y */
    for (int h = 0; h < c->T.nk; h++) {
        const double w = omega_of(&c->T, h);
        const size_t oc = (size_t)(h ? 2 * h - 1 : 0) * nc, os = oc + nc;
        double complex g[QPC_MAX_COORDS];
        for (int a = 0; a < nc; a++) {
            g[a] = h ? c->G[oc + a] - I * c->G[os + a] : c->G[oc + a];
            for (int b2 = 0; b2 < nc; b2++) {
                double complex y =
                    h ? Y[(size_t)(2 * h - 1) * nc + b2] - I * Y[(size_t)2 * h * nc + b2] : Y[b2];
                g[a] -= (c->tq[a + (size_t)nc * b2] + I * w * c->tv[a + (size_t)nc * b2]) * y;
            }
        }
        const double complex *P = c->Pk + (size_t)h * nf * nc, *x0 = c->x0 + (size_t)h * nf;
        double *xc = X + (size_t)(h ? 2 * h - 1 : 0) * nf, *xs = xc + nf;
        for (int i = 0; i < nf; i++) {
            double complex s = x0[i];
            for (int a = 0; a < nc; a++)
                s += P[(size_t)a * nf + i] * g[a];
            xc[i] = creal(s);
            if (h) xs[i] = -cimag(s);
        }
    }
}

int gd_qpc_newton(gd_qpc *c, double *X, double tol, int max_iter, double *resid, int *iters,
                  char *msg, size_t cap)
{
    const long n = c->n;
    const int nf = c->nf, nc = c->nc;
    SUNContext ctx = NULL;
    N_Vector x = NULL, bv = NULL;
    SUNLinearSolver LS = NULL;
    double *Y = calloc((size_t)n, sizeof *Y);
    double complex *rk = malloc((size_t)c->T.nk * nf * sizeof *rk);
    int rc = 1;
    *iters = 0;
    *resid = INFINITY;
    if (!Y || !rk) {
        snprintf(msg, cap, "out of memory");
        goto done;
    }
    /* Y = C^T X: the start's coordinates */
    for (long h = 0; h < 2L * c->T.nk - 1; h++)
        for (int a = 0; a < nc; a++) {
            double s = 0.0;
            for (int e = 0; e < c->ns; e++)
                s += c->cd[(size_t)a * nf + c->sup[e]] * X[(size_t)h * nf + c->sup[e]];
            Y[(size_t)h * nc + a] = s;
        }
    /* the loads at rest; the shift: the terms' torus means about the start */
    int lr = loads(c, Y, rk); /* also the start's samples and local Jacobians */
    if (lr) {
        snprintf(msg, cap, lr == 2 ? "out of memory" : "a force is not finite at the start");
        goto done;
    }
    memset(c->tq, 0, 2 * (size_t)nc * nc * sizeof *c->tq);
    for (int k = 0; k < c->nt; k++) {
        if (c->tu[k] < 0) continue;
        double sq = 0.0, sv = 0.0;
        for (long p = 0; p < c->T.Ntot; p++) {
            sq += c->jq[(size_t)k * c->T.Ntot + p];
            sv += c->jv[(size_t)k * c->T.Ntot + p];
        }
        c->tq[c->tu[k] + (size_t)nc * c->tw[k]] += sq / c->T.Ntot;
        c->tv[c->tu[k] + (size_t)nc * c->tw[k]] += sv / c->T.Ntot;
    }
    int rr = receptances(c, rk);
    if (rr) {
        snprintf(msg, cap,
                 rr == 1 ? "a receptance of the condensed torus is singular (a harmonic's "
                           "frequency on an undamped mode)"
                         : "out of memory");
        goto done;
    }
    if (SUNContext_Create(NULL, &ctx)) goto done;
    x = N_VNew_Serial(n, ctx);
    bv = N_VNew_Serial(n, ctx);
    if (!x || !bv) goto done;
    LS = SUNLinSol_SPGMR(x, SUN_PREC_NONE, 40, ctx);
    if (!LS) goto done;
    SUNLinSol_SPGMRSetMaxRestarts(LS, 4);
    SUNLinSol_SPGMRSetGSType(LS, SUN_MODIFIED_GS);
    SUNLinSolSetATimes(LS, c, atimes);
    if (SUNLinSolInitialize(LS)) goto done;
    double scale = 0.0;
    if (residual(c, Y, c->R, &scale, 1)) {
        snprintf(msg, cap, "a force is not finite at the start");
        goto done;
    }
    for (int it = 0;; it++) {
        double nr = 0.0;
        for (long i = 0; i < n; i++)
            nr += c->R[i] * c->R[i];
        nr = sqrt(nr);
        *resid = scale > 0 ? nr / scale : nr;
        if (*resid <= tol) {
            rc = 0;
            break;
        }
        if (it >= max_iter) {
            snprintf(msg, cap,
                     "Newton did not converge in %d steps (relative residual %.2g, condensed "
                     "multi-frequency harmonic balance of order %d)",
                     max_iter, *resid, c->T.H);
            goto done;
        }
        double *bb = N_VGetArrayPointer(bv), *xx = N_VGetArrayPointer(x);
        for (long i = 0; i < n; i++) {
            bb[i] = -c->R[i];
            xx[i] = 0.0;
        }
        int lrc = SUNLinSolSolve(LS, NULL, x, bv, fmax(1e-3 * nr, 0.1 * tol * scale));
        if (lrc < 0) {
            snprintf(msg, cap, "GMRES failed (%d) at Newton step %d", lrc, it);
            goto done;
        }
        if (gd_qp_damped_step(n, Y, xx, nr, step_residual, c, c->w2, c->R, &scale)) {
            snprintf(msg, cap,
                     "Newton stalled at step %d (relative residual %.2g, condensed "
                     "multi-frequency harmonic balance of order %d)",
                     it, *resid, c->T.H);
            goto done;
        }
        memcpy(Y, c->w2, (size_t)n * sizeof *Y);
        (*iters)++;
    }
    recover(c, Y, X);
done:
    if (LS) SUNLinSolFree(LS);
    if (x) N_VDestroy(x);
    if (bv) N_VDestroy(bv);
    if (ctx) SUNContext_Free(&ctx);
    free(Y);
    free(rk);
    return rc;
}

long gd_qpc_matvecs(const gd_qpc *c)
{
    return c->matvecs;
}
