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
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/multifreq/qphb_impl.h"
#include "transient/transient_impl.h"

#define TWO_PI 6.28318530717958647692
/* cycles of the lowest base over which a quasi-periodic point's transition matrix is taken */
#define LYAP_CYCLES 20
/* the integrator's tolerance of the monodromy (the co-prime gearbox at 900 rpm: |mu|max 0.001721 at
 * 1e-5, 1e-6 and 1e-8, in 0.9, 1.7 and 6 s CPU) */
#define STAB_RTOL 1e-4

int gd_qp_stability(gd_transient *tr, const gd_qp_bases *b, const double *X, const int *k, int nk,
                    int nf, int max_states, gd_periodic_point *p, char *note, size_t cap)
{
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
    if (n > max_states) { /* a perturbation's decay over two common periods by transients
                             was tried: the full co-prime gearbox (274 states) integrates
                             one common period in 26 s CPU, about 100 s a point */
        snprintf(note, cap,
                 "stability not computed: %d states, over the %d of a dense monodromy "
                 "(--shoot-dense-max)",
                 n, max_states);
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
    int rc = 0;
    if (gd_transient_monodromy(tr, 0.0, T, y0, &o, phi, NULL, &err) != GD_OK) {
        snprintf(note, cap, "stability not computed: the monodromy failed (%.150s)", err.message);
    } else if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n, phi, n, wr, wi, NULL, 1, NULL, 1)) {
        snprintf(note, cap, "stability not computed: the eigenvalues did not converge");
    } else {
        double mx = 0.0;
        for (int i = 0; i < n; i++)
            mx = fmax(mx, hypot(wr[i], wi[i]));
        p->mu_max = mx;
        p->stable = mx < 1.0;
        p->stability_method = GD_PER_MULTIFREQ;
        free(p->mu_re);
        free(p->mu_im);
        p->mu_re = wr;
        p->mu_im = wi;
        p->nmult = n;
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
