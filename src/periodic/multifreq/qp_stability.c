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

/* periods of the perturbation check (beyond a dense monodromy's states) and its integrator
 * tolerance: the perturbation (1e-2 of the orbit's scale: the laws are linear in the state but for
 * the TVMS angle) decays by |mu| a period, so after two it is still far above the integration error
 */
#define DECAY_PERIODS 2
#define DECAY_RTOL 1e-7
#define DECAY_EPS 1e-2

/* The state (free DOFs, y = [q; q']) integrated over [t0, t0 + T] in place. 0 ok. */
static int advance(gd_transient *tr, double t0, double T, double *y, double *q, double *v,
                   char *note, size_t cap)
{
    const int nf = tr->nf;
    memset(q, 0, (size_t)tr->n * sizeof *q);
    memset(v, 0, (size_t)tr->n * sizeof *v);
    for (int i = 0; i < nf; i++) {
        q[tr->free_dof[i]] = y[i];
        v[tr->free_dof[i]] = y[nf + i];
    }
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.rtol = DECAY_RTOL;
    o.atol_q *= DECAY_RTOL / 1e-6;
    o.atol_v *= DECAY_RTOL / 1e-6;
    o.t_start = t0;
    o.t_end = t0 + T;
    o.record_from = t0;
    o.output_interval = T;
    o.init = GD_TR_INIT_GIVEN;
    o.q0 = q;
    o.v0 = v;
    gd_transient_result *r = NULL;
    gd_error err;
    if (gd_transient_run(tr, &o, NULL, 0, &r, &err) != GD_OK) {
        snprintf(note, cap, "stability not computed: the perturbed transient failed (%.120s)",
                 err.message);
        return 1;
    }
    for (int i = 0; i < nf; i++) {
        y[i] = r->q_end[tr->free_dof[i]];
        y[nf + i] = r->v_end[tr->free_dof[i]];
    }
    gd_transient_result_free(r);
    return 0;
}

/* Beyond a dense monodromy: the decay of a perturbation of the slice's state over
 * DECAY_PERIODS periods T, by two transients (the state and the perturbed one), the
 * ratio of the scaled difference over the last period as |mu|max's estimate (a power
 * iteration's step). 0 done (note says how), 1 no memory or failed (note says why). */
static int perturbation_decay(gd_transient *tr, const double *y0, double T, gd_periodic_point *p,
                              char *note, size_t cap)
{
    const int nf = tr->nf, n = 2 * nf;
    double *a = malloc((size_t)n * sizeof *a), *b = malloc((size_t)n * sizeof *b),
           *q = malloc((size_t)tr->n * sizeof *q), *v = malloc((size_t)tr->n * sizeof *v);
    int rc = 1;
    if (!a || !b || !q || !v) goto done;
    double sq = 0.0, sv = 0.0; /* the orbit's scales */
    for (int i = 0; i < nf; i++) {
        sq = fmax(sq, fabs(y0[i]));
        sv = fmax(sv, fabs(y0[nf + i]));
    }
    if (!(sq > 0)) sq = 1.0;
    if (!(sv > 0)) sv = 1.0;
    memcpy(a, y0, (size_t)n * sizeof *a);
    for (int i = 0; i < n; i++) /* a deterministic direction touching every state */
        b[i] = y0[i] + DECAY_EPS * (i < nf ? sq : sv) * (((i * 7919) % 13) - 6) / 6.0;
    double last = 0.0, ratio = NAN;
    for (int i = 0; i < n; i++)
        last = fmax(last, fabs(b[i] - a[i]) / (i < nf ? sq : sv));
    for (int k = 0; k < DECAY_PERIODS; k++) {
        if (advance(tr, k * T, T, a, q, v, note, cap) || advance(tr, k * T, T, b, q, v, note, cap))
            goto done;
        double dn = 0.0;
        for (int i = 0; i < n; i++)
            dn = fmax(dn, fabs(b[i] - a[i]) / (i < nf ? sq : sv));
        ratio = dn / last;
        last = dn;
    }
    p->mu_max = ratio;
    p->stable = ratio < 1.0;
    p->stability_method = GD_PER_MULTIFREQ;
    snprintf(note, cap,
             "stability from the decay of a perturbation over %d common periods (%d states, "
             "over a dense monodromy's): |mu|max estimated %.3g",
             DECAY_PERIODS, n, ratio);
    rc = 0;
done:
    free(a);
    free(b);
    free(q);
    free(v);
    return rc;
}

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
    if (n > max_states) {
        int rc = 0;
        if (!periodic)
            snprintf(note, cap,
                     "stability not computed: %d states, over the %d of a dense monodromy, "
                     "and no common period",
                     n, max_states);
        else
            rc = perturbation_decay(tr, y0, T, p, note, cap) && !note[0];
        free(y0);
        free(phi);
        free(wr);
        free(wi);
        return rc;
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
