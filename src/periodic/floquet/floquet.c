/* Floquet multipliers of a harmonic balance solution: the monodromy matrix of the
 * variational equations linearised about q(t),
 *   dz/dt = A(t) z,   A = [0, I; M^-1 (J_q(t) - K), M^-1 (J_v(t) - D)]
 * (propagated in the balanced state [C x; x'], C = diag(cs): see the balance below),
 * J_q, J_v the local force derivatives of gd_transient_local along the HB orbit
 * (evaluated at any t from the coefficients, not only at the AFT samples), integrated over
 * one period by the fourth-order Magnus method with two Gauss points (Iserles & Norsett
 * 1999; Blanes, Casas, Oteo & Ros 2009, Eq. 4.3):
 *   Omega = h/2 (A1 + A2) + sqrt(3)/12 h^2 [A2, A1],   Phi <- exp(Omega) Phi,
 * exact for constant A however stiff, and the matrix exponential by scaling and squaring
 * with a diagonal Pade approximant of degree 8 (Higham 2005, Table 2.3: ample for
 * |Omega| / 2^s <= 1/2). The multipliers are the eigenvalues of Phi (LAPACK dgeev). */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "linalg/linalg_impl.h"
#include "periodic/periodic_impl.h"

#define TWO_PI 6.28318530717958647692

/* E = exp(A), n x n column-major; W: 6 n^2 workspace, ipiv: n. 0 ok. */
static int expm(int n, const double *A, double *E, double *W, int *ipiv)
{
    const int p = 8;
    size_t nn = (size_t)n * n;
    double *X = W, *Nm = W + nn, *Dm = W + 2 * nn, *T = W + 3 * nn, *S = W + 4 * nn;
    const double norm = LAPACKE_dlange_work(LAPACK_COL_MAJOR, '1', n, n, A, n, NULL);
    /* a non-finite Omega (an overflowed step) has no exponential; log2 of a finite norm
     * is at most 1024, so s <= 1025 and the cast cannot overflow (norm / 0.5 itself
     * overflows to inf above DBL_MAX / 2: found by fuzz_inputs at speeds of 1e-154) */
    if (!isfinite(norm)) return 1;
    int s = norm > 0.5 ? (int)ceil(log2(norm) + 1.0) : 0;
    double scale = ldexp(1.0, -s);
    for (size_t k = 0; k < nn; k++)
        S[k] = A[k] * scale;
    memset(Nm, 0, nn * sizeof *Nm);
    memset(Dm, 0, nn * sizeof *Dm);
    memset(X, 0, nn * sizeof *X);
    for (int i = 0; i < n; i++)
        Nm[(size_t)i * n + i] = Dm[(size_t)i * n + i] = X[(size_t)i * n + i] = 1.0;
    double c = 1.0;
    for (int k = 1; k <= p; k++) {
        c *= (double)(p - k + 1) / (double)(k * (2 * p - k + 1));
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0, S, n, X, n, 0.0, T, n);
        memcpy(X, T, nn * sizeof *X);
        double sg = (k & 1) ? -c : c;
        for (size_t m = 0; m < nn; m++) {
            Nm[m] += c * X[m];
            Dm[m] += sg * X[m];
        }
    }
    if (LAPACKE_dgesv(LAPACK_COL_MAJOR, n, n, Dm, n, ipiv, Nm, n)) return 1;
    for (int k = 0; k < s; k++) {
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0, Nm, n, Nm, n, 0.0, T,
                    n);
        memcpy(Nm, T, nn * sizeof *Nm);
    }
    memcpy(E, Nm, nn * sizeof *E);
    return 0;
}

typedef struct fq_work {
    int nf, n2, nterm;
    const gd_tr_term *term;
    double *Minv, *Kd, *Dd; /* nf x nf dense */
    double *cs;             /* nf: the balance, z = [cs x; x'] (one value: see below) */
    double *J, *P;          /* nf x nf */
    double *sq, *sv, *y;
} fq_work;

/* out = A (dense n x n; A is n x n) */
static void dense_from(const gd_csc *A, int n, double *out)
{
    memset(out, 0, (size_t)n * n * sizeof *out);
    gd_csc_add_dense(A, 1.0, out);
}

/* A(t) (n2 x n2) at phase tau of the solution, in the balanced state [cs x; x']:
 * A = [0, C; M^-1 J_q C^-1, M^-1 J_v], C = diag(cs) */
static void build_A(fq_work *w, const hb *h, gd_transient *tr, double om, const double *X,
                    double tau, double *A)
{
    const int nf = w->nf, n2 = w->n2;
    gd_hb_eval(h, om, X, tau, w->y, w->y + nf);
    gd_transient_local(tr, tau / om, w->y, NULL, w->sq, w->sv);
    memset(A, 0, (size_t)n2 * n2 * sizeof *A);
    for (int i = 0; i < nf; i++)
        A[(size_t)(nf + i) * n2 + i] = w->cs[i];
    for (int part = 0; part < 2; part++) {
        const double *L = part ? w->Dd : w->Kd, *s = part ? w->sv : w->sq;
        for (size_t k = 0; k < (size_t)nf * nf; k++)
            w->J[k] = -L[k];
        for (int t = 0; t < w->nterm; t++) {
            const gd_tr_term *tm = &w->term[t];
            if (s[t] == 0.0) continue;
            for (int b = 0; b < tm->nw; b++)
                for (int a = 0; a < tm->nu; a++)
                    w->J[(size_t)tm->w_idx[b] * nf + tm->u_idx[a]] += s[t] * tm->u[a] * tm->w[b];
        }
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, nf, nf, 1.0, w->Minv, nf, w->J,
                    nf, 0.0, w->P, nf);
        for (int j = 0; j < nf; j++) {
            const double sc = part ? 1.0 : 1.0 / w->cs[j];
            for (int i = 0; i < nf; i++)
                A[(size_t)(j + part * nf) * n2 + nf + i] = sc * w->P[(size_t)j * nf + i];
        }
    }
}

/* The contact states of the backlash meshes at phase tau, as one number. */
static long contact_code(const hb *h, gd_transient *tr, double om, const double *X, double tau,
                         const gd_tr_record *bl, int nbl, double *y)
{
    long code = 0;
    if (!nbl) return 0;
    gd_hb_eval(h, om, X, tau, y, y + h->nf);
    for (int i = 0; i < nbl; i++)
        code = 3 * code + 1 + (long)gd_transient_record_value(tr, &bl[i], tau / om, y);
    return code;
}

int gd_hb_magnus_steps(const hb *h, gd_transient *tr, double om, const double *X, int steps,
                       const gd_tr_record *bl, int nbl, double **tau, int *nsub)
{
    double *y = malloc(2 * (size_t)h->nf * sizeof *y);
    int cap = steps + 1, n = 0;
    double *b = malloc((size_t)(cap + 1) * sizeof *b);
    *tau = NULL;
    *nsub = 0;
    if (!y || !b) {
        free(y);
        free(b);
        return 1;
    }
    b[0] = 0.0;
    for (int k = 0; k < steps; k++) {
        /* one step, split at every contact change of a backlash mesh (located by
         * bisection on the states along the orbit) so no Gauss point straddles a jump
         * of A(t) */
        double a = TWO_PI * k / steps, e1 = TWO_PI * (k + 1) / steps;
        long sa = contact_code(h, tr, om, X, a, bl, nbl, y);
        while (a < e1) {
            double e = e1;
            if (nbl && contact_code(h, tr, om, X, e1, bl, nbl, y) != sa) {
                double lo = a, hi = e1;
                for (int it = 0; it < 60 && hi - lo > 1e-15 * TWO_PI; it++) {
                    double mid = 0.5 * (lo + hi);
                    if (contact_code(h, tr, om, X, mid, bl, nbl, y) == sa)
                        lo = mid;
                    else
                        hi = mid;
                }
                e = hi;
            }
            if (n + 1 >= cap) {
                double *nb = realloc(b, (size_t)(2 * cap + 1) * sizeof *nb);
                if (!nb) {
                    free(y);
                    free(b);
                    return 1;
                }
                b = nb;
                cap *= 2;
            }
            b[++n] = e;
            if (e < e1) sa = contact_code(h, tr, om, X, e, bl, nbl, y);
            a = e;
        }
    }
    free(y);
    *tau = b;
    *nsub = n;
    return 0;
}

int gd_hb_floquet(const hb *h, gd_transient *tr, double om, const double *X, int steps,
                  const gd_tr_record *bl, int nbl, double *mu_re, double *mu_im)
{
    char msg[160];
    return gd_hb_floquet_budget(h, tr, om, X, steps, bl, nbl, 0.0, mu_re, mu_im, msg);
}

int gd_hb_floquet_budget(const hb *h, gd_transient *tr, double om, const double *X, int steps,
                         const gd_tr_record *bl, int nbl, double budget, double *mu_re,
                         double *mu_im, char *msg)
{
    msg[0] = '\0';
    const int nf = h->nf, n2 = 2 * nf;
    size_t nn = (size_t)n2 * n2, ff = (size_t)nf * nf;
    fq_work w = {0};
    w.nf = nf;
    w.n2 = n2;
    w.nterm = gd_transient_terms(tr, &w.term);
    if (w.nterm < 0) return 1;
    int rc = 1;
    double *buf =
        malloc((5 * ff + 11 * nn + 2 * (size_t)(w.nterm + 1) + 3 * (size_t)nf) * sizeof *buf);
    int *ipiv = malloc((size_t)n2 * sizeof *ipiv);
    if (!buf || !ipiv) goto done;
    w.Minv = buf;
    w.Kd = w.Minv + ff;
    w.Dd = w.Kd + ff;
    w.J = w.Dd + ff;
    w.P = w.J + ff;
    double *A1 = w.P + ff, *A2 = A1 + nn, *Om = A2 + nn, *Ex = Om + nn, *Phi = Ex + nn,
           *T = Phi + nn, *W = T + nn; /* W: the 5 nn of expm */
    w.sq = buf + 5 * ff + 11 * nn;
    w.sv = w.sq + w.nterm + 1;
    w.y = w.sv + w.nterm + 1;
    w.cs = w.y + 2 * nf;
    gd_csc M, D, K;
    gd_transient_matrices(tr, &M, &D, &K);
    dense_from(&K, nf, w.Kd);
    dense_from(&D, nf, w.Dd);
    dense_from(&M, nf, w.J);
    memset(w.Minv, 0, ff * sizeof *w.Minv);
    for (int i = 0; i < nf; i++)
        w.Minv[(size_t)i * nf + i] = 1.0;
    if (LAPACKE_dgesv(LAPACK_COL_MAJOR, nf, nf, w.J, nf, ipiv, w.Minv, nf)) goto done;
    /* the balance c = sqrt(max_i (M^-1 K)_ii) (about the highest natural frequency; 1
     * without a stiffness), the same for every DOF (as the Krylov path's, floquet_krylov.c).
     * Unbalanced, A's 1-norm is set by the w_max^2 entries of M^-1 K, and the scaling and
     * squaring cuts the period into about 2 |A|_1 T pieces whatever the step count, in
     * which the slow modes are lost in the rounding of I + S: a bias of every multiplier.
     * On the [JMSTHelical] model cut to 178 states at 2500 rpm (|A|_1 5.5e12 1/s^2),
     * |mu|max 5.6e-6 too large, every multiplier up to 9.2e-6 off, against LAPACK's
     * eigenvalues of the constant part and the reduced basis; balanced (|A|_1 6.6e6),
     * |mu|max within 5e-11 of the reduced basis's (docs/periodic.md, "Stability at scale";
     * tests/periodic/test_floquet_reduced.c, stiff_dof_dense_equals_reduced) */
    {
        double kmax = 0.0;
        for (int i = 0; i < nf; i++)
            kmax = fmax(kmax, fabs(cblas_ddot(nf, w.Minv + i, nf, w.Kd + (size_t)i * nf, 1)));
        for (int i = 0; i < nf; i++)
            w.cs[i] = kmax > 0 ? sqrt(kmax) : 1.0;
    }
    memset(Phi, 0, nn * sizeof *Phi);
    for (int i = 0; i < n2; i++)
        Phi[(size_t)i * n2 + i] = 1.0;
    const double g1 = 0.5 - sqrt(3.0) / 6.0, g2 = 0.5 + sqrt(3.0) / 6.0;
    double *tb = NULL;
    int nsub = 0;
    if (gd_hb_magnus_steps(h, tr, om, X, steps, bl, nbl, &tb, &nsub)) goto done;
    {
        /* every step costs the same dense products, counted (work.c): three products of
         * n2^3 and an exponential of about 8 more, with the two A's (about 30 n2^3 flops),
         * so the budget is decided before the first step, the same on every run */
        const double need = gd_per_work_seconds(30.0 * pow(n2, 3) * nsub);
        if (budget > 0 && need > budget) {
            snprintf(msg, 160,
                     "stability not computed: the dense monodromy of %d states would take "
                     "about %.3g s (%d Magnus steps, counted work), over the %g s budget per "
                     "point",
                     n2, need, nsub, budget);
            rc = 4;
            free(tb);
            goto done;
        }
    }
    for (int k = 0; k < nsub; k++) {
        double a = tb[k], dtau = tb[k + 1] - a, dt = dtau / om;
        build_A(&w, h, tr, om, X, a + g1 * dtau, A1);
        build_A(&w, h, tr, om, X, a + g2 * dtau, A2);
        /* Omega = dt/2 (A1 + A2) + sqrt(3)/12 dt^2 (A2 A1 - A1 A2) */
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n2, n2, n2, 1.0, A2, n2, A1, n2, 0.0,
                    Om, n2);
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n2, n2, n2, -1.0, A1, n2, A2, n2,
                    1.0, Om, n2);
        double c2 = sqrt(3.0) / 12.0 * dt * dt;
        for (size_t m = 0; m < nn; m++)
            Om[m] = 0.5 * dt * (A1[m] + A2[m]) + c2 * Om[m];
        if (expm(n2, Om, Ex, W, ipiv)) {
            rc = 2;
            free(tb);
            goto done;
        }
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n2, n2, n2, 1.0, Ex, n2, Phi, n2,
                    0.0, T, n2);
        memcpy(Phi, T, nn * sizeof *Phi);
    }
    free(tb);
    /* LAPACK's eigenvalue solvers are undefined on inf and NaN (dgeev wrote outside its
     * arrays): steps too long for the orbit make Phi overflow */
    for (size_t m = 0; m < nn; m++)
        if (!isfinite(Phi[m])) {
            rc = 2;
            goto done;
        }
    {
        double *dummy = T;
        if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n2, Phi, n2, mu_re, mu_im, dummy, 1, dummy,
                          1))
            goto done;
    }
    rc = 0;
done:
    free(buf);
    free(ipiv);
    return rc;
}

/* the same exponential for the multi-frequency stability (multifreq/qp_stability.c) */
int gd_expm_dense(int n, const double *A, double *E, double *W, int *ipiv)
{
    return expm(n, A, E, W, ipiv);
}
