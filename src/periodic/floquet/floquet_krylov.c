/* The Floquet multipliers of largest modulus of a harmonic balance solution without the
 * dense monodromy (docs/periodic.md, "Stability at scale"). The monodromy is the one of
 * floquet.c, the product over the same Magnus steps of exp(Omega_k),
 *   Omega = h/2 (A1 + A2) + sqrt(3)/12 h^2 [A2, A1],
 * but only its action on a vector is formed: Krylov-Schur (linalg/krylov_schur.c) on
 * monodromy-vector products finds the nev largest multipliers to a relative residual.
 *
 * One product applies every step's exponential to the vector by a truncated Taylor series
 * with scaling (Al-Mohy & Higham 2011, SIAM J. Sci. Comput. 33, Sec. 3: s substeps of
 * exp(Omega / s), each summed until two successive terms are below the unit roundoff of
 * the sum), in balanced variables z = [q; q' / c] (c = sqrt of the 1-norm of M^-1 K) so
 * that the 1-norm bound of Omega that sets s is near its spectral radius. Omega's action
 * needs no dense matrix: A(t) = A0 + B(t) with the constant part
 *   A0 z = [c y; M^-1 (-K x / c - D y)]           (sparse K, D; M by sparse LU, KLU)
 * and the rank-nterm local part B(t) z = [0; sum_t (sq_t w_t.x / c + sv_t w_t.y) M^-1 u_t]
 * (gd_transient_local's terms, M^-1 u_t formed once), and
 *   [A2, A1] z = A0 (A1 z - A2 z) + B2 A1 z - B1 A2 z,
 * so one Omega action costs two A0 actions (two sparse solves) and four rank-nterm
 * updates. Cost per product: sum over the steps of about 8 |Omega_k| Omega actions. */
#include <klu.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg_impl.h"
#include "periodic/periodic_impl.h"

/* scaled norm per Taylor substep: 3.5^28 / 28! < 1e-16, and the largest term
 * 3.5^3 / 3! = 7 loses at most 3 bits to cancellation */
#define THETA 3.5
#define MAX_TERMS 60

typedef struct kq {
    int nf, n2, nterm, nsub;
    const gd_tr_term *term;
    gd_csc K, D;
    double c; /* velocity scale of the balanced variables */
    klu_symbolic *sym;
    klu_numeric *num;
    klu_common com;
    int *Mp, *Mi; /* copies of M's pattern (KLU wants int, non-const) */
    double *Mx;
    double *Mu;  /* nterm x nf: M^-1 u_t */
    double *Mun; /* nterm: 1-norm of M^-1 u_t times max |w_t| */
    double nA0;  /* 1-norm of the balanced A0 */
    double *dt;  /* nsub step lengths (s) */
    double *s;   /* nsub x 4 nterm: sq, sv at the first Gauss point, then the second */
    int *sub;    /* nsub: Taylor substeps */
    double *a0, *p1, *p2, *d, *t, *f, *trm, *r; /* work vectors (n2; r: nf) */
    int overflow;
    int over_budget; /* the budget passed: the products stop (zeros) */
    double budget;   /* seconds of counted work (0: none, work.c) */
    double action;   /* flops of one Omega action (counted: action_flops) */
    double setup;    /* flops of the set-up (the orbit at the Gauss points) */
    int products;
    long omega_products;
} kq;

static double inf_norm(const double *x, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m = fabs(x[i]) > m ? fabs(x[i]) : m;
    return m;
}

/* out = A0 z (balanced) */
static void apply_A0(kq *k, const double *z, double *out)
{
    const int nf = k->nf;
    const double *x = z, *y = z + nf;
    double *r = k->r;
    memset(r, 0, (size_t)nf * sizeof *r);
    const double ic = 1.0 / k->c;
    for (int j = 0; j < nf; j++) {
        double xj = x[j] * ic, yj = y[j];
        for (int p = k->K.colptr[j]; p < k->K.colptr[j + 1]; p++)
            r[k->K.rowind[p]] -= k->K.values[p] * xj;
        for (int p = k->D.colptr[j]; p < k->D.colptr[j + 1]; p++)
            r[k->D.rowind[p]] -= k->D.values[p] * yj;
    }
    klu_solve(k->sym, k->num, nf, 1, r, &k->com);
    for (int i = 0; i < nf; i++) {
        out[i] = k->c * y[i];
        out[nf + i] = r[i];
    }
}

/* out += B z for the term derivatives sq, sv (nterm each) */
static void add_B(const kq *k, const double *sq, const double *sv, const double *z, double *out)
{
    const int nf = k->nf;
    const double ic = 1.0 / k->c;
    for (int t = 0; t < k->nterm; t++) {
        if (sq[t] == 0.0 && sv[t] == 0.0) continue;
        const gd_tr_term *tm = &k->term[t];
        double wx = 0.0, wy = 0.0;
        for (int b = 0; b < tm->nw; b++) {
            wx += tm->w[b] * z[tm->w_idx[b]];
            wy += tm->w[b] * z[nf + tm->w_idx[b]];
        }
        double g = sq[t] * wx * ic + sv[t] * wy;
        if (g == 0.0) continue;
        const double *mu = k->Mu + (size_t)t * nf;
        for (int i = 0; i < nf; i++)
            out[nf + i] += g * mu[i];
    }
}

/* out = Omega_j z */
static void apply_omega(kq *k, int j, const double *z, double *out)
{
    const int n2 = k->n2, nt = k->nterm;
    const double *sq1 = k->s + (size_t)j * 4 * nt, *sv1 = sq1 + nt, *sq2 = sv1 + nt,
                 *sv2 = sq2 + nt;
    const double h = k->dt[j], c2 = sqrt(3.0) / 12.0 * h * h;
    apply_A0(k, z, k->a0);
    memcpy(k->p1, k->a0, (size_t)n2 * sizeof *k->p1);
    memcpy(k->p2, k->a0, (size_t)n2 * sizeof *k->p2);
    add_B(k, sq1, sv1, z, k->p1); /* A1 z */
    add_B(k, sq2, sv2, z, k->p2); /* A2 z */
    for (int i = 0; i < n2; i++)
        k->d[i] = k->p1[i] - k->p2[i];
    apply_A0(k, k->d, k->t); /* A0 (A1 - A2) z */
    add_B(k, sq2, sv2, k->p1, k->t);
    for (int i = 0; i < n2; i++)
        k->d[i] = 0.0;
    add_B(k, sq1, sv1, k->p2, k->d);
    for (int i = 0; i < n2; i++)
        out[i] = 0.5 * h * (k->p1[i] + k->p2[i]) + c2 * (k->t[i] - k->d[i]);
    k->omega_products++;
}

/* The monodromy-vector product y = Phi x (Krylov-Schur's operator). */
static void monodromy_product(void *ctx, const double *x, double *y)
{
    kq *k = ctx;
    const int n2 = k->n2;
    k->products++;
    if (k->budget > 0 && !k->over_budget &&
        gd_per_work_seconds(k->setup + k->action * (double)k->omega_products) > k->budget)
        k->over_budget = 1;
    if (k->over_budget) { /* Krylov-Schur runs out its iterations on zeros: cheap */
        memset(y, 0, (size_t)n2 * sizeof *y);
        return;
    }
    double *z = y, *f = k->f, *trm = k->trm;
    memcpy(z, x, (size_t)n2 * sizeof *z);
    for (int j = 0; j < k->nsub && !k->overflow; j++) {
        const double inv = 1.0 / k->sub[j];
        for (int s = 0; s < k->sub[j]; s++) {
            /* z <- exp(Omega / s) z = sum_m (Omega / s)^m z / m! */
            memcpy(f, z, (size_t)n2 * sizeof *f);
            memcpy(trm, z, (size_t)n2 * sizeof *trm);
            double prev = inf_norm(trm, n2);
            for (int m = 1; m <= MAX_TERMS; m++) {
                apply_omega(k, j, trm, z); /* z is free until the sum is done */
                const double sc = inv / m;
                for (int i = 0; i < n2; i++) {
                    trm[i] = z[i] * sc;
                    f[i] += trm[i];
                }
                double cur = inf_norm(trm, n2), nf_ = inf_norm(f, n2);
                if (!isfinite(nf_)) {
                    k->overflow = 1;
                    break;
                }
                if (cur + prev <= 1.1e-16 * nf_) break;
                prev = cur;
            }
            memcpy(z, f, (size_t)n2 * sizeof *z);
        }
    }
    if (k->overflow) /* Krylov-Schur must not see inf or NaN: the caller reports it */
        for (int i = 0; i < n2; i++)
            y[i] = 0.0;
}

/* Small problems: Phi from the products of the unit vectors, its eigenvalues by dgeev,
 * largest modulus first. 0 ok, 2 overflow, 1 other failures. */
static int all_multipliers(kq *k, double *mu_re, double *mu_im)
{
    const int n2 = k->n2;
    double *P = malloc((size_t)n2 * n2 * sizeof *P), *e = calloc((size_t)n2, sizeof *e);
    int rc = 1;
    if (!P || !e) goto out;
    for (int j = 0; j < n2 && !k->overflow; j++) {
        e[j] = 1.0;
        monodromy_product(k, e, P + (size_t)j * n2);
        e[j] = 0.0;
    }
    if (k->overflow) {
        rc = 2;
        goto out;
    }
    double dummy[1];
    if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n2, P, n2, mu_re, mu_im, dummy, 1, dummy, 1))
        goto out;
    gd_hb_sort_multipliers(mu_re, mu_im, n2);
    rc = 0;
out:
    free(P);
    free(e);
    return rc;
}

static void kq_free(kq *k)
{
    if (k->num) klu_free_numeric(&k->num, &k->com);
    if (k->sym) klu_free_symbolic(&k->sym, &k->com);
    free(k->Mp);
    free(k->Mi);
    free(k->Mx);
    free(k->Mu);
    free(k->Mun);
    free(k->dt);
    free(k->s);
    free(k->sub);
    free(k->a0);
}

/* M's sparse LU, M^-1 u_t, the balance c and |A0|_1. 0 ok. */
static int kq_setup(kq *k, gd_transient *tr)
{
    const int nf = k->nf;
    gd_csc M;
    gd_transient_matrices(tr, &M, &k->D, &k->K);
    int nnz = M.colptr[nf];
    k->Mp = malloc((size_t)(nf + 1) * sizeof *k->Mp);
    k->Mi = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *k->Mi);
    k->Mx = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *k->Mx);
    k->Mu = malloc(((size_t)k->nterm * nf + 1) * sizeof *k->Mu);
    k->Mun = malloc(((size_t)k->nterm + 1) * sizeof *k->Mun);
    k->a0 = malloc((9 * (size_t)k->n2) * sizeof *k->a0);
    if (!k->Mp || !k->Mi || !k->Mx || !k->Mu || !k->Mun || !k->a0) return 1;
    k->p1 = k->a0 + k->n2;
    k->p2 = k->p1 + k->n2;
    k->d = k->p2 + k->n2;
    k->t = k->d + k->n2;
    k->f = k->t + k->n2;
    k->trm = k->f + k->n2;
    k->r = k->trm + k->n2; /* nf, with room to spare */
    memcpy(k->Mp, M.colptr, (size_t)(nf + 1) * sizeof *k->Mp);
    memcpy(k->Mi, M.rowind, (size_t)nnz * sizeof *k->Mi);
    memcpy(k->Mx, M.values, (size_t)nnz * sizeof *k->Mx);
    klu_defaults(&k->com);
    k->sym = klu_analyze(nf, k->Mp, k->Mi, &k->com);
    if (!k->sym) return 1;
    k->num = klu_factor(k->Mp, k->Mi, k->Mx, k->sym, &k->com);
    if (!k->num) return 1;
    /* column 1-norms of M^-1 K and M^-1 D, one sparse solve per column */
    double *col = k->r, nK = 0.0, nD = 0.0;
    for (int pass = 0; pass < 2; pass++) {
        const gd_csc *A = pass ? &k->D : &k->K;
        for (int j = 0; j < nf; j++) {
            if (A->colptr[j] == A->colptr[j + 1]) continue;
            memset(col, 0, (size_t)nf * sizeof *col);
            for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
                col[A->rowind[p]] += A->values[p];
            klu_solve(k->sym, k->num, nf, 1, col, &k->com);
            double s = 0.0;
            for (int i = 0; i < nf; i++)
                s += fabs(col[i]);
            if (pass)
                nD = s > nD ? s : nD;
            else
                nK = s > nK ? s : nK;
        }
    }
    /* |A0|_1 = max(|M^-1 K|_1 / c, c + |M^-1 D|_1): least near c = sqrt(|M^-1 K|_1) */
    k->c = nK > 0 ? sqrt(nK) : 1.0;
    k->nA0 = fmax(nK / k->c, k->c + nD);
    /* The 1-norm overstates the size that matters: the Taylor terms grow like
     * |A0^p|^(1/p), which tends to the spectral radius (Al-Mohy & Higham 2011, Sec. 4:
     * their d_p); for a finite-element shaft M^-1 K is far from normal and the 1-norm was
     * 7 times the largest natural frequency (the [JMSTHelical] model). Estimated by 24 powers from
     * a fixed start vector, the largest |A0^p x|^(1/p) / |x| for p = 8..24, times 1.25; the series
     * is still summed until its terms fall below the rounding of the sum. */
    {
        double *x = k->f, *y = k->trm;
        for (int i = 0; i < k->n2; i++)
            x[i] = 1.0 + 0.5 * sin(1.0 + 7.0 * i); /* fixed: deterministic */
        double nx = inf_norm(x, k->n2), lg = 0.0, best = 0.0;
        for (int p = 1; p <= 24; p++) {
            apply_A0(k, x, y);
            double ny = inf_norm(y, k->n2);
            if (!(ny > 0) || !isfinite(ny)) break;
            lg += log(ny / nx);
            for (int i = 0; i < k->n2; i++)
                x[i] = y[i] / ny;
            nx = 1.0;
            if (p >= 8) best = fmax(best, exp(lg / p));
        }
        if (best > 0 && 1.25 * best < k->nA0) k->nA0 = 1.25 * best;
    }
    for (int t = 0; t < k->nterm; t++) {
        const gd_tr_term *tm = &k->term[t];
        double *mu = k->Mu + (size_t)t * nf, wmax = 0.0;
        memset(mu, 0, (size_t)nf * sizeof *mu);
        for (int a = 0; a < tm->nu; a++)
            mu[tm->u_idx[a]] += tm->u[a];
        klu_solve(k->sym, k->num, nf, 1, mu, &k->com);
        for (int b = 0; b < tm->nw; b++)
            wmax = fabs(tm->w[b]) > wmax ? fabs(tm->w[b]) : wmax;
        double s = 0.0;
        for (int i = 0; i < nf; i++)
            s += fabs(mu[i]);
        k->Mun[t] = s * wmax;
    }
    return k->com.status < KLU_OK;
}

/* Flops of one Omega action (apply_omega): two A0 products (K and D, 2 flops per entry,
 * the mass solve about 4 per entry of M) and four B products (each term 4 nw + 2 nf). */
static double action_flops(const kq *k)
{
    double bf = 0.0;
    for (int t = 0; t < k->nterm; t++)
        bf += 4.0 * k->term[t].nw + 2.0 * k->nf;
    const double a0 =
        2.0 * (k->K.colptr[k->nf] + k->D.colptr[k->nf]) + 4.0 * k->Mp[k->nf] + 4.0 * k->nf;
    return 2.0 * a0 + 4.0 * bf + 12.0 * k->n2;
}

/* Whether the multipliers would pass the budget: the counted flops of one Omega action
 * times the actions of the fewest products a search needs (the Krylov space's, or n2 for
 * all of them), at 20 Taylor terms per substep (the series stops at 28 for the scaled norm
 * 3.5, often earlier). 1 with msg set. */
static int over_budget(kq *k, int nev, char *msg)
{
    double actions = 0.0;
    for (int j = 0; j < k->nsub; j++)
        actions += 20.0 * k->sub[j];
    const int ncv = 2 * nev + 12 < k->n2 - 1 ? 2 * nev + 12 : k->n2 - 1;
    const int least = nev + 4 > k->n2 ? k->n2 : ncv;
    const double product = gd_per_work_seconds(k->action * actions),
                 need = gd_per_work_seconds(k->setup) + least * product;
    if (need <= k->budget) return 0;
    /* the length is used, so a message cut at 160 bytes is not an error */
    int len = snprintf(msg, 160,
                       "stability not computed: the Krylov multipliers of %d states need at least "
                       "%.3g s (%d products of %.3g s, counted work), over the %g s budget per "
                       "point",
                       k->n2, need, least, product, k->budget);
    return len > 0;
}

/* 1-norm bound of the balanced B for the term derivatives sq, sv */
static double norm_B(const kq *k, const double *sq, const double *sv)
{
    double s = 0.0;
    for (int t = 0; t < k->nterm; t++)
        s += k->Mun[t] * fmax(fabs(sq[t]) / k->c, fabs(sv[t]));
    return s;
}

int gd_hb_floquet_krylov(const hb *h, gd_transient *tr, double om, const double *X, int steps,
                         const gd_tr_record *bl, int nbl, int nev, double tol, double budget,
                         double *mu_re, double *mu_im, int *nmu, int *products, char *msg)
{
    kq k = {0};
    k.budget = budget;
    k.nf = h->nf;
    k.n2 = 2 * h->nf;
    *nmu = 0;
    *products = 0;
    msg[0] = '\0';
    k.nterm = gd_transient_terms(tr, &k.term);
    if (k.nterm < 0) return 1;
    int rc = 1;
    double *tb = NULL, *y = NULL;
    gd_ks_result ks = {0};
    if (kq_setup(&k, tr)) {
        snprintf(msg, 160, "stability not computed: the mass matrix could not be factored");
        goto done;
    }
    k.action = action_flops(&k);
    if (gd_hb_magnus_steps(h, tr, om, X, steps, bl, nbl, &tb, &k.nsub)) goto done;
    const int nt = k.nterm;
    k.dt = malloc((size_t)k.nsub * sizeof *k.dt);
    k.s = malloc(((size_t)k.nsub * 4 * nt + 1) * sizeof *k.s);
    k.sub = malloc((size_t)k.nsub * sizeof *k.sub);
    y = malloc(2 * (size_t)k.nf * sizeof *y);
    double *sq = malloc(2 * ((size_t)nt + 1) * sizeof *sq);
    if (!k.dt || !k.s || !k.sub || !y || !sq) {
        free(sq);
        goto done;
    }
    /* the Gauss-point term derivatives of every step, once for all products */
    const double g1 = 0.5 - sqrt(3.0) / 6.0, g2 = 0.5 + sqrt(3.0) / 6.0;
    for (int j = 0; j < k.nsub; j++) {
        /* the set-up alone evaluates the orbit twice per step (O(nf H) each): a long
         * period at a high H can pass the budget before a product is formed */
        if (budget > 0 && j == 0) {
            /* counted: two orbit evaluations per step (4 nf (2 H + 1) flops each) and the
             * laws there */
            const double per = 2.0 * (4.0 * k.nf * (2.0 * h->H + 1.0) + GD_PER_TERM_FLOPS * nt);
            k.setup = per * k.nsub;
            const double need = gd_per_work_seconds(k.setup);
            if (need > budget) {
                int len = snprintf(msg, 160,
                                   "stability not computed: the Krylov multipliers' set-up alone "
                                   "(%d Magnus steps, %d states) would take about %.3g s, "
                                   "over the %g s budget per point",
                                   k.nsub, k.n2, need, budget);
                free(sq);
                if (len < 0) msg[0] = '\0';
                rc = 4;
                goto done;
            }
        }
        double a = tb[j], dtau = tb[j + 1] - a, dt = dtau / om;
        double *sj = k.s + (size_t)j * 4 * nt, nb[2];
        for (int g = 0; g < 2; g++) {
            double tau = a + (g ? g2 : g1) * dtau;
            gd_hb_eval(h, om, X, tau, y, y + k.nf);
            gd_transient_local(tr, tau / om, y, NULL, sq, sq + nt + 1);
            memcpy(sj + 2 * g * nt, sq, (size_t)nt * sizeof *sj);
            memcpy(sj + (2 * g + 1) * nt, sq + nt + 1, (size_t)nt * sizeof *sj);
            nb[g] = norm_B(&k, sj + 2 * g * nt, sj + (2 * g + 1) * nt);
        }
        /* |Omega| <= h (|A0| + max |Bg|) + c2 (2 |A0| |B1 - B2| + 2 |B1| |B2|) */
        double bound =
            dt * (k.nA0 + fmax(nb[0], nb[1])) +
            sqrt(3.0) / 12.0 * dt * dt * (2.0 * k.nA0 * (nb[0] + nb[1]) + 2.0 * nb[0] * nb[1]);
        k.dt[j] = dt;
        if (!isfinite(bound) || bound > 1e9) { /* no finite product: too few steps */
            free(sq);
            rc = 2;
            goto done;
        }
        k.sub[j] = bound > THETA ? (int)ceil(bound / THETA) : 1;
    }
    free(sq);
    if (budget > 0 && over_budget(&k, nev, msg)) {
        rc = 4;
        goto done;
    }
    if (nev + 4 > k.n2) {
        /* as many wanted as there are states: the monodromy's columns by n2 products, and
         * every multiplier (LAPACK dgeev) */
        rc = all_multipliers(&k, mu_re, mu_im);
        *products = k.products;
        if (!rc) *nmu = k.n2;
        goto done;
    }
    int nevk = nev, ncv = 2 * nevk + 12 < k.n2 - 1 ? 2 * nevk + 12 : k.n2 - 1;
    gd_status st = gd_krylov_schur(monodromy_product, &k, k.n2, 1, nevk, ncv, tol, 100, NULL, &ks);
    *products = k.products;
    if (k.overflow) {
        rc = 2;
        goto done;
    }
    if (k.over_budget) {
        snprintf(msg, 160,
                 "stability not computed: the Krylov multipliers of %d states passed the "
                 "%g s budget per point (counted work) after %d monodromy-vector products",
                 k.n2, budget, k.products);
        rc = 4;
        goto done;
    }
    if (st != GD_OK || ks.nconv < 1) {
        snprintf(msg, 160,
                 "stability not computed: the %d largest Floquet multipliers did not converge "
                 "(Krylov-Schur on monodromy-vector products, tolerance %.1e)",
                 nevk, tol);
        rc = 3;
        goto done;
    }
    for (int i = 0; i < ks.nconv; i++) {
        mu_re[i] = ks.mu_re[i];
        mu_im[i] = ks.mu_im[i];
    }
    gd_hb_sort_multipliers(mu_re, mu_im, ks.nconv);
    *nmu = ks.nconv;
    rc = 0;
done:
    gd_ks_result_free(&ks);
    free(tb);
    free(y);
    kq_free(&k);
    return rc;
}
