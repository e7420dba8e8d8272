/* Stability of a multi-frequency harmonic balance point (qphb_impl.h, gd_qp_stability).
 * Where the bases have a common period T (whole orders, as a gearbox's tooth counts give),
 * the slice theta = W t of the torus is periodic with T, so its stability is that of a
 * periodic orbit: the Floquet multipliers, the eigenvalues of the monodromy of the
 * variational equations integrated over T from the slice's state at t = 0 (the time-domain
 * equations themselves, not the truncated series: on a mesh stiffness that varies with
 * time the variational equations do not depend on the orbit). Without a common period the
 * response is quasi-periodic and has no monodromy; the transition matrix over LYAP_CYCLES
 * cycles of the lowest base then gives the largest Lyapunov exponent's estimate
 * (Guskov & Thouverez 2012 discuss the torus' stability; the estimate is stated as such). */
#include <cblas.h>
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/multifreq/qphb_impl.h"
#include "periodic/periodic_impl.h"
#include "transient/transient_impl.h"

#define TWO_PI 6.28318530717958647692
/* cycles of the lowest base over which a quasi-periodic point's transition matrix is taken */
#define LYAP_CYCLES 20
/* the integrator's tolerance of the monodromy (the co-prime gearbox at 900 rpm: |mu|max 0.001721 at
 * 1e-5, 1e-6 and 1e-8, in 0.9, 1.7 and 6 s CPU) */
#define STAB_RTOL 1e-4

/* Magnus steps per cycle of the highest base (the co-prime gearbox, 2144 steps over its
 * common period: |mu|max 0.0414482 at 1800 rpm, 0.0414480 at 64 steps a cycle and 0.041448 by the
 * integrated monodromy at rtol 1e-5 .. 1e-8; 0.0414640 at 16, overflow at 4) */
#define MAGNUS_PER_CYCLE 32

/* out (n x n, column-major, zeroed first) = A */
static void dense_of(const gd_csc *A, int n, double *out)
{
    memset(out, 0, (size_t)n * n * sizeof *out);
    for (int j = 0; j < n; j++)
        for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
            out[(size_t)j * n + A->rowind[p]] += A->values[p];
}

/* The monodromy over the common period T = 2 pi / w0 (phi, n x n column-major, n = 2 nf)
 * by the fourth-order Magnus method with two Gauss points (Blanes, Casas, Oteo & Ros
 * 2009, Eq. 4.3; as gd_hb_floquet, floquet.c),
 *   Omega = h/2 (A1 + A2) + sqrt(3)/12 h^2 [A2, A1],   Phi <- exp(Omega) Phi,
 * A(t) = [0, c I; M^-1 (J_q - K) / c, M^-1 (J_v - D)] in the balanced state [c q; q'] (c
 * about the highest natural frequency: floquet.c says why), J_q, J_v the local force
 * derivatives (gd_transient_local) along the slice. The slice's states at both Gauss
 * points of every step come from two inverse FFTs of its spectrum gathered by order
 * (each coefficient turned by the Gauss point's phase), so no step evaluates the series.
 * 0 ok, 1 no memory, 2 the exponential failed (not finite). */
static int magnus_monodromy(gd_transient *tr, const gd_qp_bases *b, const double *X, const int *k,
                            int nk, int nf, double *phi)
{
    const int n = 2 * nf, d = b->d;
    const double w0 = b->common;
    const gd_tr_term *term = NULL;
    const int nt = gd_transient_terms(tr, &term);
    long top = 0;
    long *ord = malloc((size_t)nk * sizeof *ord);
    if (!ord || nt < 0) {
        free(ord);
        return 1;
    }
    for (int j = 0; j < nk; j++) {
        double w = 0.0;
        for (int g = 0; g < d; g++)
            w += k[(size_t)j * d + g] * b->W[g];
        ord[j] = lround(w / w0);
        if (labs(ord[j]) > top) top = labs(ord[j]);
    }
    const long steps = MAGNUS_PER_CYCLE * (b->order > 0 ? b->order : 1);
    const long m = (2 * top + 2 + steps - 1) / steps, Nf = steps * m;
    const double h = TWO_PI / w0 / (double)steps,
                 gc[2] = {0.5 - sqrt(3.0) / 6.0, 0.5 + sqrt(3.0) / 6.0};
    const size_t nn = (size_t)n * n, ff = (size_t)nf * nf;
    fftw_complex *sp = fftw_malloc((size_t)Nf * sizeof *sp);
    double *ys = malloc((size_t)4 * nf * steps * sizeof *ys); /* [gauss][q|v][i][step] */
    double *buf =
        malloc((3 * ff + 12 * nn + (size_t)(2 * nt + 2 + 2 * n) + (size_t)nf * (nt > 0 ? nt : 1)) *
               sizeof *buf);
    int *ipiv = malloc((size_t)(n > nf ? n : nf) * sizeof *ipiv);
    fftw_plan pl = sp ? fftw_plan_dft_1d((int)Nf, sp, sp, FFTW_BACKWARD, FFTW_ESTIMATE) : NULL;
    int rc = 1;
    if (!sp || !ys || !buf || !ipiv || !pl) goto done;
    for (int g = 0; g < 2; g++)
        for (int i = 0; i < nf; i++)
            for (int deriv = 0; deriv < 2; deriv++) {
                memset(sp, 0, (size_t)Nf * sizeof *sp);
                if (!deriv) sp[0] = X[i];
                for (int j = 1; j < nk; j++) {
                    const long o = ord[j];
                    double complex z =
                        0.5 * (X[(size_t)(2 * j - 1) * nf + i] - I * X[(size_t)2 * j * nf + i]) *
                        cexp(I * (double)o * w0 * gc[g] * h);
                    if (deriv) z *= I * (double)o * w0;
                    sp[((o % Nf) + Nf) % Nf] += z;
                    sp[((-o % Nf) + Nf) % Nf] += conj(z);
                }
                fftw_execute(pl);
                double *dst = ys + ((size_t)(2 * g + deriv) * nf + i) * steps;
                for (long s = 0; s < steps; s++)
                    dst[s] = creal(sp[s * m]);
            }
    double *Minv = buf, *BK = Minv + ff, *BD = BK + ff, *A1 = BD + ff, *A2 = A1 + nn, *Om = A2 + nn,
           *E = Om + nn, *P = E + nn, *Tm = P + nn, *W = Tm + nn; /* W: 6 nn */
    double *sq = W + 6 * nn, *sv = sq + nt + 1, *y = sv + nt + 1, *mu = y + 2 * n;
    gd_csc M, D, K;
    gd_transient_matrices(tr, &M, &D, &K);
    dense_of(&M, nf, Tm);
    memset(Minv, 0, ff * sizeof *Minv);
    for (int i = 0; i < nf; i++)
        Minv[(size_t)i * nf + i] = 1.0;
    if (LAPACKE_dgesv(LAPACK_COL_MAJOR, nf, nf, Tm, nf, ipiv, Minv, nf)) goto done;
    dense_of(&K, nf, E);
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, nf, nf, -1.0, Minv, nf, E, nf, 0.0,
                BK, nf);
    dense_of(&D, nf, E);
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, nf, nf, nf, -1.0, Minv, nf, E, nf, 0.0,
                BD, nf);
    double kmax = 0.0; /* the balance: about the highest natural frequency */
    for (int i = 0; i < nf; i++)
        kmax = fmax(kmax, fabs(BK[(size_t)i * nf + i]));
    const double bal = kmax > 0 ? sqrt(kmax) : 1.0;
    for (int t = 0; t < nt; t++) { /* M^-1 u_t */
        double *mt = mu + (size_t)t * nf;
        for (int i = 0; i < nf; i++) {
            double s = 0.0;
            for (int a = 0; a < term[t].nu; a++)
                s += Minv[(size_t)term[t].u_idx[a] * nf + i] * term[t].u[a];
            mt[i] = s;
        }
    }
    memset(phi, 0, nn * sizeof *phi);
    for (int i = 0; i < n; i++)
        phi[(size_t)i * n + i] = 1.0;
    tr->law_time = NULL;
    rc = 2;
    for (long s = 0; s < steps; s++) {
        for (int g = 0; g < 2; g++) {
            double *A = g ? A2 : A1;
            for (int i = 0; i < nf; i++) {
                y[i] = ys[((size_t)(2 * g) * nf + i) * steps + s];
                y[nf + i] = ys[((size_t)(2 * g + 1) * nf + i) * steps + s];
            }
            gd_transient_local(tr, ((double)s + gc[g]) * h, y, NULL, sq, sv);
            memset(A, 0, nn * sizeof *A);
            for (int i = 0; i < nf; i++)
                A[(size_t)(nf + i) * n + i] = bal;
            for (int j = 0; j < nf; j++)
                for (int i = 0; i < nf; i++) {
                    A[(size_t)j * n + nf + i] = BK[(size_t)j * nf + i] / bal;
                    A[(size_t)(nf + j) * n + nf + i] = BD[(size_t)j * nf + i];
                }
            for (int t = 0; t < nt; t++) { /* + M^-1 u_t (s_t w_t^T) */
                const double *mt = mu + (size_t)t * nf;
                for (int e = 0; e < term[t].nw; e++) {
                    const int col = term[t].w_idx[e];
                    const double a = sq[t] * term[t].w[e] / bal, v = sv[t] * term[t].w[e];
                    if (a != 0.0)
                        for (int i = 0; i < nf; i++)
                            A[(size_t)col * n + nf + i] += a * mt[i];
                    if (v != 0.0)
                        for (int i = 0; i < nf; i++)
                            A[(size_t)(nf + col) * n + nf + i] += v * mt[i];
                }
            }
        }
        /* Omega = h/2 (A1 + A2) + sqrt(3)/12 h^2 (A2 A1 - A1 A2) */
        const double c2 = sqrt(3.0) / 12.0 * h * h;
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, c2, A2, n, A1, n, 0.0, Om,
                    n);
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, -c2, A1, n, A2, n, 1.0, Om,
                    n);
        for (size_t e = 0; e < nn; e++)
            Om[e] += 0.5 * h * (A1[e] + A2[e]);
        if (gd_expm_dense(n, Om, E, W, ipiv)) goto done;
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0, E, n, phi, n, 0.0, P,
                    n);
        memcpy(phi, P, nn * sizeof *phi);
    }
    for (size_t e = 0; e < nn; e++)
        if (!isfinite(phi[e])) goto done;
    rc = 0;
done:
    if (pl) fftw_destroy_plan(pl);
    fftw_free(sp);
    free(ys);
    free(buf);
    free(ipiv);
    free(ord);
    return rc;
}

/* The slice's coefficients gathered by whole order n = k . W / w0 into the single-frequency
 * layout of hb.c (the mean, then the cosine and sine rows of orders 1..top; a harmonic of
 * negative order enters with its sine negated, one of order 0 adds its cosine to the
 * mean), so the periodic orbit's tools (floquet_reduced.c) take the slice as they take a
 * harmonic balance solution of period 2 pi / w0. NULL when out of memory. */
static double *slice_series(const gd_qp_bases *b, const double *X, const int *k, int nk, int nf,
                            int *top_out)
{
    long top = 0;
    long *ord = malloc((size_t)nk * sizeof *ord);
    if (!ord) return NULL;
    for (int j = 0; j < nk; j++) {
        double w = 0.0;
        for (int g = 0; g < b->d; g++)
            w += k[(size_t)j * b->d + g] * b->W[g];
        ord[j] = lround(w / b->common);
        if (labs(ord[j]) > top) top = labs(ord[j]);
    }
    double *Xs = calloc((size_t)(2 * top + 1) * nf, sizeof *Xs);
    if (Xs) {
        memcpy(Xs, X, (size_t)nf * sizeof *Xs);
        for (int j = 1; j < nk; j++) {
            const long o = labs(ord[j]);
            const double sg = ord[j] < 0 ? -1.0 : 1.0;
            const double *xc = X + (size_t)(2 * j - 1) * nf, *xs = X + (size_t)2 * j * nf;
            double *dc = o ? Xs + (size_t)(2 * o - 1) * nf : Xs, *ds = Xs + (size_t)2 * o * nf;
            for (int i = 0; i < nf; i++) {
                dc[i] += xc[i];
                if (o) ds[i] += sg * xs[i];
            }
        }
    }
    *top_out = (int)top;
    free(ord);
    return Xs;
}

/* the largest step count the reduced basis doubles to (floquet_reduced.c's own cap) */
#define REDUCED_STEPS_CAP 131072

/* The multipliers of a model over max_states states: the slice (a periodic orbit of the
 * common period) handed to the reduced basis of floquet_reduced.c (the modes of (sym K, M)
 * below opt->floquet_cutoff (0: 4) times the highest base, the residual flexibility of the
 * rest along the laws' directions, fourth-order Magnus steps of the local part doubled
 * from 8 per cycle of the highest base until two counts agree; the discarded modes'
 * multipliers estimated one by one). wr, wi: 2 nf. 0 ok (*nmu set), else note says why. */
static int reduced_multipliers(gd_transient *tr, const gd_qp_bases *b, const double *X,
                               const int *k, int nk, int nf, const gd_periodic_options *opt,
                               double *wr, double *wi, int *nmu, char *note, size_t cap)
{
    int top = 0, nbasis = 0, used = 0;
    double *Xs = slice_series(b, X, k, nk, nf, &top);
    char msg[160] = "";
    if (!Xs) {
        snprintf(note, cap, "stability not computed: out of memory");
        return 1;
    }
    hb h;
    memset(&h, 0, sizeof h);
    h.nf = nf;
    h.H = top;
    const double fc = opt->floquet_cutoff > 0 ? opt->floquet_cutoff : 4.0;
    const int s0 = gd_floquet_reduced_first_steps(b->order > 0 ? b->order : 1);
    tr->law_time = NULL;
    int rc =
        gd_hb_floquet_reduced(&h, tr, b->common, Xs, 0, s0, REDUCED_STEPS_CAP, &used, NULL, 0,
                              fc * b->W[b->d - 1], opt->floquet_budget, wr, wi, nmu, &nbasis, msg);
    if (h.fmodes_free) h.fmodes_free(h.fmodes);
    free(Xs);
    if (rc)
        snprintf(note, cap, "%s%s", strncmp(msg, "stability", 9) ? "stability not computed: " : "",
                 msg[0] ? msg : "the reduced basis failed");
    else
        snprintf(note, cap,
                 "stability: %d states, over the %d of a dense monodromy: the reduced basis "
                 "(%d vectors, %d Magnus steps)",
                 2 * nf, opt->shoot_dense_max > 0 ? opt->shoot_dense_max : 64, nbasis, used);
    return rc;
}

int gd_qp_stability(gd_transient *tr, const gd_qp_bases *b, const double *X, const int *k, int nk,
                    int nf, const gd_periodic_options *opt, gd_periodic_point *p, char *note,
                    size_t cap)
{
    const int max_states = opt->shoot_dense_max > 0 ? opt->shoot_dense_max : 64;
    const int n = 2 * nf, d = b->d;
    note[0] = '\0';
    const int periodic = b->common > 0;
    const double T = periodic ? TWO_PI / b->common : LYAP_CYCLES * TWO_PI / b->W[0];
    double *y0 = calloc((size_t)n, sizeof *y0),
           *phi = n <= max_states ? malloc((size_t)n * n * sizeof *phi) : malloc(sizeof *phi),
           *wr = malloc((size_t)n * sizeof *wr), *wi = malloc((size_t)n * sizeof *wi);
    if (!y0 || !phi || !wr || !wi) {
        free(y0);
        free(phi);
        free(wr);
        free(wi);
        return 1;
    }
    /* the slice's state at t = 0: q = X_0 + sum C_k, q' = sum Omega_k S_k */
    for (int i = 0; i < nf; i++)
        y0[i] = X[i];
    for (int j = 1; j < nk; j++) {
        double w = 0.0;
        for (int g = 0; g < d; g++)
            w += k[(size_t)j * d + g] * b->W[g];
        for (int i = 0; i < nf; i++) {
            y0[i] += X[(size_t)(2 * j - 1) * nf + i];
            y0[nf + i] += w * X[(size_t)2 * j * nf + i];
        }
    }
    int nmu = n, red = -1;
    if (n > max_states && periodic && gd_transient_nswitches(tr) == 0) {
        red = reduced_multipliers(tr, b, X, k, nk, nf, opt, wr, wi, &nmu, note, cap);
        if (red) {
            free(y0);
            free(phi);
            free(wr);
            free(wi);
            return 0;
        }
    } else if (n > max_states) {
        snprintf(note, cap,
                 "stability not computed: %d states, over the %d of a dense monodromy "
                 "(--shoot-dense-max), and %s",
                 n, max_states,
                 periodic ? "contact changes (the reduced basis needs smooth laws)"
                          : "no common period");
        free(y0);
        free(phi);
        free(wr);
        free(wi);
        return 0;
    }
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.rtol = STAB_RTOL;
    o.atol_q *= STAB_RTOL / 1e-6;
    o.atol_v *= STAB_RTOL / 1e-6;
    gd_error err;
    tr->law_time = NULL;
    int rc = 0, mg = -1;
    /* smooth laws on a common period: the Magnus monodromy on the slice; contact changes
     * (backlash) or no common period: the integrated one */
    if (red == 0) {
        mg = 0; /* the reduced multipliers are in wr, wi */
    } else if (periodic && gd_transient_nswitches(tr) == 0) {
        mg = magnus_monodromy(tr, b, X, k, nk, nf, phi);
        if (mg == 1) rc = 1;
    }
    if (mg == 1) {
        snprintf(note, cap, "stability not computed: out of memory");
    } else if (mg != 0 && gd_transient_monodromy(tr, 0.0, T, y0, &o, phi, NULL, &err) != GD_OK) {
        snprintf(note, cap, "stability not computed: the monodromy failed (%.150s)", err.message);
    } else if (red != 0 &&
               LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n, phi, n, wr, wi, NULL, 1, NULL, 1)) {
        snprintf(note, cap, "stability not computed: the eigenvalues did not converge");
    } else {
        double mx = 0.0;
        for (int i = 0; i < nmu; i++)
            mx = fmax(mx, hypot(wr[i], wi[i]));
        p->mu_max = mx;
        p->stable = mx < 1.0;
        p->stability_method = GD_PER_MULTIFREQ;
        free(p->mu_re);
        free(p->mu_im);
        p->mu_re = wr;
        p->mu_im = wi;
        p->nmult = nmu;
        wr = wi = NULL;
        if (!periodic)
            snprintf(note, cap,
                     "stability: no common period; the transition matrix over %d cycles of "
                     "the lowest base (a Lyapunov estimate: |mu|max^(1/%d) per cycle)",
                     LYAP_CYCLES, LYAP_CYCLES);
    }
    free(y0);
    free(phi);
    free(wr);
    free(wi);
    return rc;
}
