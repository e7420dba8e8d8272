/* Starts of harmonic balance other than rest.
 *
 * Static start: where the model has laws that carry a static load (GD_LAW_SUPPORT: a
 * journal or rolling bearing, a polynomial spring), the zeroth harmonic starts from their
 * static equilibrium under the problem's mean loads (gd_system_law_state_loads), not from
 * rest: at rest a rolling bearing with clearance carries nothing and has no stiffness, so
 * the first Newton step is singular, and a journal bearing's eccentricity under load is a
 * long way from the centre.
 *
 * Warm start from a short transient: where Newton from rest fails (a strongly nonlinear
 * resonance whose basin does not hold the rest state), the problem is integrated from
 * rest by transient's own integrator over some periods of the HB frequency and the last
 * period's state, sampled at N phases, becomes the Fourier coefficients Newton starts
 * from. A stable orbit attracts the integration; an unstable one does not, so this only
 * helps where the answer is stable. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

#define TWO_PI 6.28318530717958647692

/* The free DOF of each model DOF (-1: prescribed or not a state), ndof entries, owned
 * by the caller; NULL when out of memory. */
static int *free_of_dofs(const gd_transient *tr, int ndof)
{
    int *free_of = malloc((size_t)(ndof > 0 ? ndof : 1) * sizeof *free_of);
    if (!free_of) return NULL;
    for (int d = 0; d < ndof; d++) {
        gd_tr_record rec = {GD_REC_DISP, d, 0};
        int k = -1;
        free_of[d] = gd_transient_record_dofs(tr, &rec, &k, 1) == 1 ? k : -1;
    }
    return free_of;
}

int gd_hb_static_start(const gd_system *sys, const gd_transient_spec *spec, const gd_transient *tr,
                       double speed, int nf, double *X)
{
    const gd_model *m = sys->model;
    int support = 0;
    for (int i = 0; i < m->nlaws && !support; i++)
        support = (m->laws[i].type->flags & GD_LAW_SUPPORT) != 0;
    if (!support) return 0;
    const int n = sys->ndof;
    double *f0 = calloc((size_t)n * 2, sizeof *f0);
    int *free_of = free_of_dofs(tr, n), found = 0;
    if (f0 && free_of) {
        double *q = f0 + n;
        for (int k = 0; k < spec->nloads; k++)
            if (spec->loads[k].dof >= 0 && spec->loads[k].dof < n)
                f0[spec->loads[k].dof] += gd_load_law_mean(&spec->loads[k].law);
        found = gd_system_law_state_loads(sys, speed, f0, q);
        for (int d = 0; d < n && found; d++)
            if (free_of[d] >= 0 && free_of[d] < nf) X[free_of[d]] = q[d];
    }
    free(f0);
    free(free_of);
    return found;
}

int gd_hb_warm_start(const gd_system *sys, const gd_transient_spec *spec, double speed, double w,
                     int H, int periods, double *X)
{
    gd_transient *tr = NULL;
    gd_error err;
    if (gd_transient_new(sys, spec, speed, &tr, &err)) return 1;
    const int nf = gd_transient_nstates(tr) / 2;
    int N = 16;
    while (N < 4 * (H + 1))
        N *= 2;
    const double T = TWO_PI / w, t1 = periods * T;
    double *ts = malloc((size_t)N * sizeof *ts);
    int *free_of = NULL, rc = 1, ndof = 0;
    gd_transient_result *r = NULL;
    if (!ts) goto done;
    for (int j = 0; j < N; j++)
        ts[j] = t1 - T + T * j / N;
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = t1;
    o.record_from = t1 - T;
    o.output_interval = T;
    o.sample_times = ts;
    o.nsample_times = N;
    o.init = spec->nloads ? GD_TR_INIT_STATIC : GD_TR_INIT_REST;
    if (gd_transient_run(tr, &o, NULL, 0, &r, &err) || r->nsamples != N) goto done;
    ndof = r->ndof;
    free_of = free_of_dofs(tr, ndof);
    if (!free_of) goto done;
    const int nh = 2 * H + 1;
    memset(X, 0, (size_t)nf * nh * sizeof *X);
    for (int d = 0; d < ndof; d++) {
        int i = free_of[d];
        if (i < 0 || i >= nf) continue;
        for (int j = 0; j < N; j++) {
            double q = r->sample_q[(size_t)j * ndof + d], ph = TWO_PI * j / N;
            X[i] += q / N;
            for (int k = 1; k <= H; k++) {
                X[(size_t)(2 * k - 1) * nf + i] += 2.0 / N * q * cos(k * ph);
                X[(size_t)(2 * k) * nf + i] += 2.0 / N * q * sin(k * ph);
            }
        }
    }
    rc = 0;
done:
    free(ts);
    free(free_of);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    return rc;
}
