/* Linear time-invariant response (GD_TR_LTI): M q'' + D q' + K q = f(t) with f the
 * unbalance forces, sums of harmonics U w^2 (cos, sin)(w t + phi) at each shaft's speed.
 *
 * The motion is split into the forced harmonic response and a free motion,
 *   y = y_p + z,  y_p(t) = Re sum_w Y_w e^(i w t),  z' = A z,  z(t0) = y(t0) - y_p(t0),
 * with (K - w^2 M + i w D) Q_w = F_w (one complex sparse solve per distinct speed: exact)
 * and A = [0 I; -M^-1 K, -M^-1 D]. The free motion is advanced by the (8,8) Pade
 * approximant of the exponential (PADE_M below), z_{k+1} = R(h A) z_k: order 16,
 * A-stable, |R| -> 1 at infinite step (modes the step does not resolve keep their
 * amplitude, so comparing two steps sees them: they are not silently damped away). In
 * partial fractions
 *   R(hA) = I + sum_j g_j (I - (h / r_j) A)^-1,  g_j = -P(r_j) / (r_j Q'(r_j)),
 * over the roots r_j of the denominator Q (four complex conjugate pairs: four complex
 * solves per step), evaluated as increments (step() says why). (I - c A) x = b is
 * solved in second-order form,
 *   (M + c D + c^2 K) x_v = M b_v - c K b_q,  x_q = b_q + c x_v,
 * with a complex sparse LU (CXSparse) per root and step size. Until issue 35 the (4,4)
 * approximant (order 8, two solves per step): the 366-DOF rotor's record needed steps of
 * 2.5e-5 s there, 1e-4 s here, at 0.51 of the instructions.
 *
 * Error control: the run at step h is compared with the run at 2h over the samples (the
 * records, each relative to its peak; the end displacements when nothing is recorded).
 * Where h resolves the motion better than 2h the difference d is the error of the run at
 * 2h, and that run is returned with d as its estimate: the error of the run at h is below
 * d by the next fall of the error, which the falls seen do not tell (42-DOF ROSS rotor:
 * 33, 1.3, 25, 11 from 8 dt down; returning the run at h with d said 25 times its error,
 * issue 35). The first level's run at 2h takes every output time, those between its own
 * samples by a step of h from its state (the run goes on from its own samples), so that
 * it can be returned. Once the steps resolve the motion the error falls as h^p
 * (p = 2 PADE_M) and the run at h is Richardson's d / (2^p - 1) from the truth: that run
 * is returned with that estimate (the bound d overstated its error 250 times on the MMT
 * rig with p = 8, issue 35). That regime is seen, not assumed: the difference of the runs
 * at 4h and 2h must be at least 2^(p-2) times d (an observed order of p - 2 or more) and
 * the one before at least 2^(p-4) times that (the first level compares runs at 8, 4 and 2
 * times its step for it). The step is
 * halved until the estimate is within rtol. */
#include <complex.h>
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "transient/transient_impl.h"

/* Degree of the Pade approximant (even: its roots are complex-conjugate pairs). Order
 * 2 PADE_M; the step that keeps the phase error of e^(i w h) below 2.5e-6 per radian is
 * w h = 1.70 for m = 4 (2 solves per step), 4.06 for 6 (3), 6.85 for 8 (4), 9.89 for 10
 * (5): 8 takes half the solves of 4 per unit of time for the modes it resolves, and the
 * largest residue |g_j| is 3.5e3 (round-off 1e-12 per step; 4.1e4 for 10, 31 for 4). */
#define PADE_M GD_TR_LTI_PADE
#define NROOT (PADE_M / 2) /* roots of Q with Im > 0 */
#define NCACHE 4           /* step sizes kept factored */
#define MAXLEVEL 24

typedef cs_complex_t cplx;

/* A complex LU in split real and imaginary arrays (the step's solves run on them: plain
 * real arithmetic the compiler vectorises, without C99 complex multiplication's
 * infinity checks); patterns borrowed from N, diagonals stored inverted. */
typedef struct split_lu {
    double *lr, *li, *ur, *ui; /* values of N->L, N->U */
} split_lu;

typedef struct lti_factor {
    double h;
    cs_cin *N[NROOT];
    split_lu s[NROOT];
} lti_factor;

typedef struct lti {
    gd_transient *tr;
    int nf;
    cplx r[NROOT], g[NROOT]; /* roots of Q (upper half plane), residues g_j */
    cs_ci *S;                /* complex matrix with the pattern of tr->S */
    cs_cis *sym;
    lti_factor cache[NCACHE];
    int ncache, next;
    int nw;              /* distinct unbalance speeds */
    double *w;           /* nw */
    cplx *Q;             /* nw x nf: harmonic amplitudes of q_p */
    double *kv, *kq;     /* K z_v, then K z_q + D z_v (each nf) */
    cplx *b, *x;         /* nf each */
    double *sr, *si;     /* nf each: split solve vectors */
    double *z, *zn, *zs; /* 2 nf each */
    long steps, factors;
} lti;

int gd_tr_lti_reason(const gd_transient *tr, char *why, size_t len)
{
    int nother = 0, first = -1;
    if (tr->cond) {
        snprintf(why, len, "condensed model");
        return 0;
    }
    for (int i = 0; i < tr->nlaw; i++)
        if (!(tr->law[i].type->flags & GD_LAW_ASSEMBLED) && nother++ == 0) first = i;
    if (nother > 0) {
        const gd_law *L = &tr->law[first];
        snprintf(why, len, "law %s (%s)%s", L->name, L->type->name,
                 nother > 1 ? " and others" : "");
        return 0;
    }
    if (tr->np > 0) {
        snprintf(why, len, "prescribed DOFs");
        return 0;
    }
    /* laws with an assembled linear part (meshes): linear only as assembled */
    for (int i = 0; i < tr->nlaw; i++) {
        const gd_law *L = &tr->law[i];
        unsigned f = gd_law_flags(L);
        if (!(f & GD_LAW_ASSEMBLED) || !(f & GD_LAW_TANGENT)) continue;
        if (L->type == &gd_law_backlash_mesh) {
            const gd_mesh_law_data *s = L->data;
            snprintf(why, len, "mesh %s: %s", L->name,
                     s->backlash ? "backlash"
                     : s->tvms   ? "time-varying stiffness"
                     : s->ste    ? "transmission error"
                                 : "a law other than the assembled stiffness");
        } else {
            snprintf(why, len, "law %s (%s)", L->name, L->type->name);
        }
        return 0;
    }
    snprintf(why, len, "linear, time-invariant");
    return 1;
}

/* The (PADE_M, PADE_M) Pade approximant of exp: P(z) = sum p_j z^j with
 * p_j = (2m - j)! m! / ((2m)! j! (m - j)!), Q(z) = P(-z); its roots and residues. 0 ok. */
static int pade_roots(lti *L)
{
#if PADE_M == 8
    /* the roots (Im > 0) and residues below, computed in long double: on a platform or
     * under a tool (valgrind) where long double is double they are 6e-10 off, a relative
     * error of every mode's frequency (the free oscillator: 1.1e-8 of q0 instead of 3e-12) */
    static const double tab[NROOT][4] = {
        {5.677967897795261, 12.707822597209754, 19.217565114473427, -4.412742963811378},
        {8.7365784344048052, 8.8288850009430782, -228.99680408192077, 256.58396244856158},
        {10.409681581273764, 5.2323503052850544, 620.89672209595881, -1568.9532556344918},
        {11.17577208652617, 1.7352288907055731, -411.11748312851171, 3486.1620810111158},
    };
    for (int k = 0; k < NROOT; k++) {
        L->r[k] = tab[k][0] + tab[k][1] * _Complex_I;
        L->g[k] = tab[k][2] + tab[k][3] * _Complex_I;
    }
    return 0;
#endif
    enum { m = PADE_M, n = 2 * PADE_M };
    double p[n / 2 + 1], q[n / 2 + 1];
    p[0] = 1.0;
    for (int j = 1; j <= m; j++) /* p_j / p_(j-1) = (m - j + 1) / (j (2m - j + 1)) */
        p[j] = p[j - 1] * (m - j + 1) / ((double)j * (2 * m - j + 1));
    for (int j = 0; j <= m; j++)
        q[j] = (j % 2 ? -1.0 : 1.0) * p[j];
    /* companion matrix of the monic Q */
    double C[m * m], wr[m], wi[m];
    memset(C, 0, sizeof C);
    for (int i = 0; i < m; i++)
        C[(m - 1) * m + i] = -q[i] / q[m]; /* last column */
    for (int i = 1; i < m; i++)
        C[(i - 1) * m + i] = 1.0; /* subdiagonal */
    if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', m, C, m, wr, wi, NULL, 1, NULL, 1)) return 1;
    /* Newton on Q polishes each root, and the residues are evaluated, in long double:
     * the residues (up to 3.5e3 for m = 8) cancel in sum g_j / r_j = R'(0) = 1, whose
     * error is a relative error of every mode's frequency (6e-10 in double) */
    long double pl[m + 1], ql[m + 1];
    pl[0] = 1.0L;
    for (int j = 1; j <= m; j++)
        pl[j] = pl[j - 1] * (m - j + 1) / ((long double)j * (2 * m - j + 1));
    for (int j = 0; j <= m; j++)
        ql[j] = (j % 2 ? -1.0L : 1.0L) * pl[j];
    int k = 0;
    for (int i = 0; i < m && k < NROOT; i++) {
        if (!(wi[i] > 0)) continue;
        long double complex r = wr[i] + wi[i] * _Complex_I, P = 0, dQ = 0, zp = 1;
        for (int it = 0; it < 6; it++) {
            long double complex qv = 0, dq = 0;
            for (int j = m; j >= 0; j--) { /* Horner: Q and Q' */
                dq = dq * r + qv;
                qv = qv * r + ql[j];
            }
            r -= qv / dq;
        }
        for (int j = 0; j <= m; j++) {
            P += pl[j] * zp;
            if (j < m) dQ += (j + 1) * ql[j + 1] * zp;
            zp *= r;
        }
        L->r[k] = (cplx)r;
        L->g[k] = (cplx)(-P / (r * dQ));
        k++;
    }
    return k == NROOT ? 0 : 1;
}

/* Factors M + c D + c^2 K into *N. 0 ok. */
static int factor_c(lti *L, cplx c, cs_cin **N)
{
    const gd_transient *tr = L->tr;
    const int nf = L->nf;
    cs_ci *S = L->S;
    memset(S->x, 0, (size_t)S->p[nf] * sizeof *S->x);
    for (int p = 0; p < tr->Mff->p[nf]; p++)
        S->x[tr->mapM[p]] += tr->Mff->x[p];
    for (int p = 0; p < tr->Dff->p[nf]; p++)
        S->x[tr->mapD[p]] += c * tr->Dff->x[p];
    for (int p = 0; p < tr->Kff->p[nf]; p++)
        S->x[tr->mapK[p]] += c * c * tr->Kff->x[p];
    *N = cs_ci_lu(S, L->sym, 1e-3);
    L->factors++;
    return *N ? 0 : 1;
}

static void split_free(split_lu *s)
{
    free(s->lr);
    memset(s, 0, sizeof *s);
}

/* The split copy of N's factors. 0 ok. */
static int split_make(const cs_cin *N, split_lu *s)
{
    const cs_ci *Lf = N->L, *Uf = N->U;
    int n = Lf->n, nl = Lf->p[n], nu = Uf->p[n];
    s->lr = malloc((size_t)2 * (nl + nu) * sizeof *s->lr);
    if (!s->lr) return 1;
    s->li = s->lr + nl;
    s->ur = s->li + nl;
    s->ui = s->ur + nu;
    for (int p = 0; p < nl; p++) {
        s->lr[p] = creal(Lf->x[p]);
        s->li[p] = cimag(Lf->x[p]);
    }
    for (int p = 0; p < nu; p++) {
        s->ur[p] = creal(Uf->x[p]);
        s->ui[p] = cimag(Uf->x[p]);
    }
    for (int j = 0; j < n; j++) { /* diagonals: first of L's column, last of U's */
        cplx dl = 1.0 / Lf->x[Lf->p[j]], du = 1.0 / Uf->x[Uf->p[j + 1] - 1];
        s->lr[Lf->p[j]] = creal(dl);
        s->li[Lf->p[j]] = cimag(dl);
        s->ur[Uf->p[j + 1] - 1] = creal(du);
        s->ui[Uf->p[j + 1] - 1] = cimag(du);
    }
    return 0;
}

/* (xr, xi) = N^-1 (br, bi) with the split factors (cs_lsolve, cs_usolve's order). */
static void split_solve(const cs_cin *N, const split_lu *s, const int *q, int n, const double *br,
                        const double *bi, double *xr, double *xi, double *wr, double *wi)
{
    const int *Lp = N->L->p, *Li = N->L->i, *Up = N->U->p, *Ui = N->U->i;
    for (int k = 0; k < n; k++) {
        wr[N->pinv[k]] = br[k];
        wi[N->pinv[k]] = bi[k];
    }
    for (int j = 0; j < n; j++) {
        int p0 = Lp[j];
        double dr = s->lr[p0], di = s->li[p0];
        double a = wr[j] * dr - wi[j] * di, b = wr[j] * di + wi[j] * dr;
        wr[j] = a;
        wi[j] = b;
        for (int p = p0 + 1; p < Lp[j + 1]; p++) {
            int i = Li[p];
            wr[i] -= s->lr[p] * a - s->li[p] * b;
            wi[i] -= s->lr[p] * b + s->li[p] * a;
        }
    }
    for (int j = n - 1; j >= 0; j--) {
        int pd = Up[j + 1] - 1;
        double dr = s->ur[pd], di = s->ui[pd];
        double a = wr[j] * dr - wi[j] * di, b = wr[j] * di + wi[j] * dr;
        wr[j] = a;
        wi[j] = b;
        for (int p = Up[j]; p < pd; p++) {
            int i = Ui[p];
            wr[i] -= s->ur[p] * a - s->ui[p] * b;
            wi[i] -= s->ur[p] * b + s->ui[p] * a;
        }
    }
    for (int k = 0; k < n; k++) {
        xr[q[k]] = wr[k];
        xi[q[k]] = wi[k];
    }
}

/* x = N^-1 b (b overwritten). */
static void lu_solve(lti *L, const cs_cin *N, cplx *b, cplx *x)
{
    cs_ci_ipvec(N->pinv, b, x, L->nf);
    cs_ci_lsolve(N->L, x);
    cs_ci_usolve(N->U, x);
    cs_ci_ipvec(L->sym->q, x, b, L->nf);
    memcpy(x, b, (size_t)L->nf * sizeof *x);
}

static void lti_free(lti *L)
{
    for (int i = 0; i < L->ncache; i++)
        for (int j = 0; j < NROOT; j++) {
            cs_ci_nfree(L->cache[i].N[j]);
            split_free(&L->cache[i].s[j]);
        }
    cs_ci_spfree(L->S);
    cs_ci_sfree(L->sym);
    free(L->w);
    free(L->Q);
    free(L->kv);
    free(L->b);
    free(L->sr);
    free(L->z);
}

/* The factors for step h (cached). NULL: singular or no memory. */
static lti_factor *factors_for(lti *L, double h)
{
    for (int i = 0; i < L->ncache; i++)
        if (fabs(L->cache[i].h - h) <= 1e-12 * h) return &L->cache[i];
    lti_factor *f;
    if (L->ncache < NCACHE) {
        f = &L->cache[L->ncache++];
    } else {
        f = &L->cache[L->next];
        L->next = (L->next + 1) % NCACHE;
        for (int j = 0; j < NROOT; j++) {
            f->N[j] = cs_ci_nfree(f->N[j]);
            split_free(&f->s[j]);
        }
    }
    memset(f, 0, sizeof *f);
    f->h = h;
    for (int j = 0; j < NROOT; j++)
        if (factor_c(L, h / L->r[j], &f->N[j]) || split_make(f->N[j], &f->s[j])) {
            f->h = -1; /* never matches */
            return NULL;
        }
    return f;
}

static int lti_init(lti *L, gd_transient *tr)
{
    memset(L, 0, sizeof *L);
    L->tr = tr;
    const int nf = tr->nf;
    L->nf = nf;
    if (pade_roots(L)) return 1;
    const cs *S = tr->S;
    L->S = cs_ci_spalloc(nf, nf, S->p[nf], 1, 0);
    L->w = malloc((size_t)(tr->nunb > 0 ? tr->nunb : 1) * sizeof *L->w);
    L->Q = calloc((size_t)(tr->nunb > 0 ? tr->nunb : 1) * nf, sizeof *L->Q);
    L->kv = malloc((size_t)2 * nf * sizeof *L->kv);
    L->b = malloc((size_t)2 * nf * sizeof *L->b);
    L->sr = malloc((size_t)4 * (nf > 0 ? nf : 1) * sizeof *L->sr);
    L->z = malloc((size_t)6 * nf * sizeof *L->z);
    if (!L->S || !L->w || !L->Q || !L->kv || !L->b || !L->z || !L->sr) return 1;
    L->si = L->sr + nf;
    L->kq = L->kv + nf;
    L->x = L->b + nf;
    L->zn = L->z + 2 * nf;
    L->zs = L->z + 4 * nf;
    memcpy(L->S->p, S->p, (size_t)(nf + 1) * sizeof *S->p);
    memcpy(L->S->i, S->i, (size_t)S->p[nf] * sizeof *S->i);
    L->sym = cs_ci_sqr(1, L->S, 0);
    if (!L->sym) return 1;
    /* harmonic response per distinct speed: (K - w^2 M + i w D) Q = F is
     * -w^2 (M + c D + c^2 K) Q = F with c = 1 / (i w) */
    for (int u = 0; u < tr->nunb; u++) {
        const tr_unb *ub = &tr->unb[u];
        if (ub->omega == 0.0 || ub->force == 0.0) continue;
        int g = 0;
        while (g < L->nw && L->w[g] != ub->omega)
            g++;
        if (g == L->nw) L->w[L->nw++] = ub->omega;
        /* f_x = Re(F e^(i phi) e^(i w t)), f_y = Re(-i F e^(i phi) e^(i w t)) */
        cplx F = ub->force * cexp(ub->phase * _Complex_I);
        if (ub->dx >= 0 && tr->fidx[ub->dx] >= 0) L->Q[(size_t)g * nf + tr->fidx[ub->dx]] += F;
        if (ub->dy >= 0 && tr->fidx[ub->dy] >= 0)
            L->Q[(size_t)g * nf + tr->fidx[ub->dy]] += -_Complex_I * F;
    }
    for (int g = 0; g < L->nw; g++) {
        double w = L->w[g];
        cs_cin *N = NULL;
        if (factor_c(L, 1.0 / (w * _Complex_I), &N)) return 2;
        cplx *Q = L->Q + (size_t)g * nf;
        for (int i = 0; i < nf; i++)
            L->b[i] = -Q[i] / (w * w);
        lu_solve(L, N, L->b, Q);
        cs_ci_nfree(N);
    }
    return 0;
}

/* y += s * y_p(t) (y = [q; v], length 2 nf). */
static void add_particular(const lti *L, double t, double s, double *y)
{
    const int nf = L->nf;
    for (int g = 0; g < L->nw; g++) {
        double w = L->w[g];
        cplx e = cexp(w * t * _Complex_I);
        const cplx *Q = L->Q + (size_t)g * nf;
        for (int i = 0; i < nf; i++) {
            cplx a = Q[i] * e;
            y[i] += s * creal(a);
            y[nf + i] += s * creal(w * _Complex_I * a);
        }
    }
}

/* One step of the free motion z (2 nf) over h. 0 ok.
 * With sum_j g_j = 0 (R(0) = 1), R(hA) z = z + sum_j g_j c_j (I - c_j A)^-1 A z with
 * c_j = h / r_j: the solves give the increment, not the new state, so their round-off is
 * relative to the increment (O(w h) of z for a resolved mode). Solving for the state, as
 * R(hA) = I + sum g_j (I - c_j A)^-1, cancels the terms g_j x_j ~ g_j z to the step's
 * change: an error of |g_j| times the solve's, per step (2e-9 of the peak per step with
 * the (8,8) approximant, |g_j| up to 3.5e3, on the 366-DOF rotor). In second-order form
 * (A z)_q = z_v, M (A z)_v = -(K z_q + D z_v), so the right-hand side
 * M (Az)_v - c K (Az)_q = -(K z_q + D z_v) - c K z_v needs no mass solve. */
static int step(lti *L, const lti_factor *f, double h)
{
    gd_transient *tr = L->tr;
    const int nf = L->nf;
    double *zq = L->z, *zv = L->z + nf;
    memset(L->kv, 0, (size_t)2 * nf * sizeof *L->kv);
    cs_gaxpy(tr->Kff, zv, L->kv);
    cs_gaxpy(tr->Kff, zq, L->kq);
    cs_gaxpy(tr->Dff, zv, L->kq);
    memcpy(L->zn, L->z, (size_t)2 * nf * sizeof *L->zn);
    double *br = L->sr, *bi = L->si, *xr = L->sr + 2 * nf, *xi = L->sr + 3 * nf;
    double *wr = (double *)L->b, *wi = wr + nf; /* L->b: 2 nf complex = 4 nf doubles */
    for (int j = 0; j < NROOT; j++) {
        cplx c = h / L->r[j], g2 = 2.0 * L->g[j] * c;
        double cr = creal(c), ci = cimag(c), gr = creal(g2), gi = cimag(g2);
        for (int i = 0; i < nf; i++) {
            br[i] = -L->kq[i] - cr * L->kv[i];
            bi[i] = -ci * L->kv[i];
        }
        split_solve(f->N[j], &f->s[j], L->sym->q, nf, br, bi, xr, xi, wr, wi);
        /* conjugate root: the conjugate solution, so the pair adds 2 Re(g c x), with
         * x_q = z_v + c x_v */
        for (int i = 0; i < nf; i++) {
            double qr = zv[i] + cr * xr[i] - ci * xi[i], qi = cr * xi[i] + ci * xr[i];
            L->zn[i] += gr * qr - gi * qi;
            L->zn[nf + i] += gr * xr[i] - gi * xi[i];
        }
    }
    memcpy(L->z, L->zn, (size_t)2 * nf * sizeof *L->z);
    L->steps++;
    return 0;
}

/* Advances the free motion from *t to t1 in equal steps of at most h. */
static int advance(lti *L, double *t, double t1, double h)
{
    double span = t1 - *t;
    if (!(span > 0)) return 0;
    long ns = (long)ceil(span / h * (1.0 - 1e-12));
    if (ns < 1) ns = 1;
    double hs = span / ns;
    lti_factor *f = factors_for(L, hs);
    if (!f) return 1;
    for (long s = 0; s < ns; s++)
        if (step(L, f, hs)) return 1;
    *t = t1;
    return 0;
}

/* One run at step h, sampling every stride-th output time into vals (nrec x nout, only
 * those columns written), the end state into yend (2 nf). With side set the output times
 * between are sampled too, each from the run's last state by one step to it (which
 * leaves the run itself as it was): the run at 2 dt then has every sample, and can be
 * returned. 0 ok. */
static int pass(lti *L, const gd_transient_options *opt, const gd_tr_record *records, int nrec,
                double from, double dt, int nout, double h, int stride, int side, const double *y0,
                double *vals, double *yend)
{
    gd_transient *tr = L->tr;
    const int nf = L->nf;
    double *y = yend;
    memcpy(L->z, y0, (size_t)2 * nf * sizeof *L->z);
    add_particular(L, opt->t_start, -1.0, L->z);
    double t = opt->t_start;
    for (int k = 0; k < nout; k++) {
        double tk = from + k * dt;
        if (tk > opt->t_end || k == nout - 1) tk = fmin(tk, opt->t_end);
        const int between = k % stride && k != nout - 1;
        if (between && !side) continue;
        if (between) {
            double ts = t;
            memcpy(L->zs, L->z, (size_t)2 * nf * sizeof *L->zs);
            if (advance(L, &ts, tk, h)) return 1;
        } else if (advance(L, &t, tk, h)) {
            return 1;
        }
        memcpy(y, L->z, (size_t)2 * nf * sizeof *y);
        add_particular(L, tk, 1.0, y);
        gd_tr_fill(tr, tk, y, tr->q, tr->v, NULL);
        for (int r = 0; r < nrec; r++)
            vals[(size_t)r * nout + k] = gd_tr_record_value(tr, &records[r], tk, tr->q, tr->v);
        if (between) memcpy(L->z, L->zs, (size_t)2 * nf * sizeof *L->z);
    }
    if (advance(L, &t, opt->t_end, h)) return 1;
    memcpy(y, L->z, (size_t)2 * nf * sizeof *y);
    add_particular(L, opt->t_end, 1.0, y);
    return 0;
}

/* Largest difference of the records (over the columns both runs sampled), each relative
 * to its peak in run a; of the end displacements (relative to their peak) when nothing
 * is recorded. The records are what the user asked for: the end state carries the high
 * modes no record shows, which on the 42-DOF ROSS rotor made the estimate of a gear's
 * record 1000 times its error (issue 35). */
static double difference(const double *va, const double *vb, int nrec, int nout, int stride,
                         const double *ya, const double *yb, int nf)
{
    double e = 0.0;
    for (int r = 0; r < nrec; r++) {
        const double *a = va + (size_t)r * nout, *b = vb + (size_t)r * nout;
        double pk = 0.0, d = 0.0;
        for (int k = 0; k < nout; k++)
            pk = fmax(pk, fabs(a[k]));
        for (int k = 0; k < nout; k++)
            if (k % stride == 0 || k == nout - 1) d = fmax(d, fabs(a[k] - b[k]));
        if (pk > 0) e = fmax(e, d / pk);
    }
    if (nrec > 0) return e;
    double pk = 0.0, d = 0.0;
    for (int i = 0; i < nf; i++) {
        pk = fmax(pk, fabs(ya[i]));
        d = fmax(d, fabs(ya[i] - yb[i]));
    }
    if (pk > 0) e = fmax(e, d / pk);
    return e;
}

gd_status gd_tr_run_lti(gd_transient *tr, const gd_transient_options *opt,
                        const gd_tr_record *records, int nrecords, double from, double dt,
                        double *y, gd_transient_result *res, gd_error *err)
{
    char why[160];
    if (!gd_tr_lti_reason(tr, why, sizeof why))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method", "use bdf, adams or galpha",
                            "the linear time-invariant method does not take this model: %s", why);
    const int nf = tr->nf, nout = res->nout, nr = nrecords > 0 ? nrecords : 1;
    lti L;
    int ist = lti_init(&L, tr);
    /* zeroed: a coarse run fills only its own samples, and difference() takes the peak
     * of its first run over every sample */
    double *va = calloc((size_t)nr * nout, sizeof *va);
    double *vb = calloc((size_t)nr * nout, sizeof *vb);
    double *vc = calloc((size_t)nr * nout, sizeof *vc);
    double *ya = malloc((size_t)6 * (nf > 0 ? nf : 1) * sizeof *ya);
    double *y0 = malloc((size_t)2 * (nf > 0 ? nf : 1) * sizeof *y0);
    gd_status st = GD_OK;
    if (ist == 2) {
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "speed", "change the speed",
                          "the harmonic response matrix is singular at an unbalance speed");
        goto done;
    }
    if (ist || !va || !vb || !vc || !ya || !y0) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    double *yb = ya + 2 * nf, *yc = ya + 4 * nf;
    memcpy(y0, y, (size_t)2 * nf * sizeof *y0);
    const double limit = opt->max_steps > 0 ? (double)opt->max_steps : 50e6;
    const double span = opt->t_end - opt->t_start;
    /* the coarse run at 2 dt has every sample (the ones between by a step of dt from
     * its states), so that it can be returned; later levels' coarse run is the previous
     * level's */
    double h = dt, e = INFINITY, e_prev = INFINITY, est = INFINITY;
    int richardson = 0;
    double gmax = 0;
    for (int j = 0; j < NROOT; j++)
        gmax = fmax(gmax, cabs(L.g[j]));
    if (pass(&L, opt, records, nrecords, from, dt, nout, 2 * dt, 2, 1, y0, vb, yb)) goto singular;
    /* the runs at 4 dt and 8 dt (3/8 of the first level's steps): their differences tell
     * whether the first level is in the h^p regime already. vc holds the run at 8 dt,
     * then the one at 4 dt (each compared at its own samples) */
    if (pass(&L, opt, records, nrecords, from, dt, nout, 8 * dt, 8, 0, y0, vc, yc)) goto singular;
    double *v4 = calloc((size_t)nr * nout, sizeof *v4),
           *y4 = malloc((size_t)2 * (nf > 0 ? nf : 1) * sizeof *y4);
    if (!v4 || !y4) {
        free(v4);
        free(y4);
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    int bad4 = pass(&L, opt, records, nrecords, from, dt, nout, 4 * dt, 4, 0, y0, v4, y4);
    double d8 = bad4 ? INFINITY : difference(v4, vc, nrecords, nout, 8, y4, yc, nf);
    double d4 = bad4 ? INFINITY : difference(vb, v4, nrecords, nout, 4, yb, y4, nf);
    free(v4);
    free(y4);
    if (bad4) goto singular;
    double ratio_prev = d4 > 0 ? d8 / d4 : 0;
    for (int level = 0;; level++) {
        if (span / h > limit) {
            st = gd_error_set(err, GD_EINPUT, "", 0, 0, "rtol",
                              "loosen rtol, or raise max_steps if it is meant",
                              "the linear method needs steps below %.3g s to reach rtol %g "
                              "(difference %.3g at that step): %.3g steps, over the limit of %.0f",
                              h, opt->rtol, e, span / h, limit);
            goto done;
        }
        if (pass(&L, opt, records, nrecords, from, dt, nout, h, 1, 0, y0, va, ya)) goto singular;
        e = difference(va, vb, nrecords, nout, 1, ya, yb, nf);
        double before = level == 0 ? d4 : e_prev, ratio = e > 0 ? before / e : 0;
        /* the h^p regime: the difference falls 2^(p-2) times or more (order p - 2 or
         * more) after falling at least 2^(p-4) times before (p = 8: 64 and 16). A first steep fall
         * after slow ones is the step passing the highest modes, where the run reaches its
         * round-off floor (the 366-DOF rotor: 4, then 136 at 7.8e-7 s with a true error of 3e-9):
         * the run at 2h is returned there, the difference its estimate (a rule from the falls seen,
         * e / (fall
         * - 1), was tried for issue 35: the next fall is not the last one, 1.3 then 25 on
         * the 42-DOF rotor, and it claimed 9e-7 where the 366-DOF rotor's error was 5.5e-6) */
        richardson =
            ratio >= ldexp(1.0, 2 * PADE_M - 2) && ratio_prev >= ldexp(1.0, 2 * PADE_M - 4);
        /* Richardson's estimate has a floor: each step's round-off, up to max |g_j| eps
         * of the state, adds up as a random walk over the steps (the free oscillator at
         * w h = 1: error 3e-12 of q0 after 100 steps, where d / 65535 said 2e-17) */
        est =
            richardson ? e / (ldexp(1.0, 2 * PADE_M) - 1) + gmax * DBL_EPSILON * sqrt(span / h) : e;
        ratio_prev = ratio;
        /* a difference that grows with more steps is the round-off of the steps, not
         * the truncation: the floor of the method on this model */
        if (est <= opt->rtol || level == MAXLEVEL || e > e_prev) break;
        e_prev = e;
        /* the fine run becomes the coarse one */
        double *t = va;
        va = vb;
        vb = t;
        memcpy(yb, ya, (size_t)2 * nf * sizeof *yb);
        h *= 0.5;
        /* no step of this level recurs: free its factors (memory on large models) */
        for (int i = 0; i < L.ncache; i++)
            for (int j = 0; j < NROOT; j++) {
                L.cache[i].N[j] = cs_ci_nfree(L.cache[i].N[j]);
                split_free(&L.cache[i].s[j]);
            }
        L.ncache = L.next = 0;
    }
    /* Returned: outside the h^p regime the coarse run, whose error the difference is
     * (the error of the run at h is below it by the next fall, which the falls seen do
     * not tell: on the 42-DOF ROSS rotor 33, 1.3, 25, 11, 49 from 8 dt down; returning
     * the run at h with d as its estimate said 25 times its error, issue 35) */
    const double *vout = richardson ? va : vb, *yout = richardson ? ya : yb;
    memcpy(res->values, vout, (size_t)nrecords * nout * sizeof *vout);
    for (int k = 0; k < nout; k++) {
        double tk = from + k * dt;
        if (tk > opt->t_end || k == nout - 1) tk = fmin(tk, opt->t_end);
        res->t[k] = tk;
    }
    memcpy(y, yout, (size_t)2 * nf * sizeof *y);
    res->steps = L.steps;
    res->prec_setups = L.factors;
    res->step = richardson ? h : 2 * h;
    res->error_estimate = est;
    goto done;
singular:
    st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "step", "use the bdf method",
                      "the linear method's step matrix is singular");
done:
    lti_free(&L);
    free(va);
    free(vb);
    free(vc);
    free(ya);
    free(y0);
    return st;
}
