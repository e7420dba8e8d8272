/* Budgets and the cost rule of `--method auto` from counted work, never from clocks
 * (issue 33 item 2, issue 38 L7): the same command makes the same decisions on an idle
 * and on a loaded machine, so its output is the same bit for bit. Work is counted in
 * floating-point operations of the known kernels (sparse products, dense products, FFTs,
 * law evaluations) and shown as seconds at a nominal GD_PER_FLOPS (docs/periodic.md,
 * "Deterministic budgets"). */
#include <math.h>

#include "geardyn/transient_model.h"
#include "periodic/periodic_impl.h"

double gd_per_work_seconds(double flops)
{
    return flops / GD_PER_FLOPS;
}

/* One right-hand side: K q and D v (2 flops per stored entry), the mass solve (its
 * factor about twice M's entries), every local law term (GD_PER_TERM_FLOPS: a contact
 * test, a stiffness from a table, the force and its direction) and the state update. A
 * problem without the local form (cams with include_acceleration) is counted from its
 * spec: two terms per mesh, damper and cam (its lift table and derivatives), one per
 * law and load, and the cams' low-rank inertia update (2 nf^2 each). On the Ducati train
 * that counts about 7 us at 2 GFlop/s against 3.8 us measured per right-hand side by
 * `transient` at rtol 1e-6 (its budgets err on the short side; without the spec: 0.2 us). */
double gd_per_rhs_flops(gd_transient *tr, const gd_transient_spec *spec)
{
    int nf, nterm, ngroup;
    long knz;
    gd_hb_memory_params_tr(tr, &nf, &nterm, &ngroup, &knz);
    double terms = nterm, extra = 0.0;
    if (gd_transient_terms(tr, NULL) < 0 && spec) {
        terms = 2.0 * (spec->nmeshes + spec->nsfds + spec->ncams) + spec->nlaws + spec->nloads;
        extra = 2.0 * spec->ncams * (double)nf * nf;
    }
    return 4.0 * (double)knz + GD_PER_TERM_FLOPS * terms + extra + 10.0 * nf;
}

/* One harmonic balance Newton step at H harmonics and N samples (gd_hb_residual,
 * gd_hb_factor, one solve): the sample synthesis and analysis (two real FFTs of N per free
 * DOF, 2.5 N log2 N each), the laws at every sample, the terms' harmonic couplings
 * ((2H + 1)^2 each), the block-diagonal linear part per harmonic (about 20 flops per
 * entry of its pattern) and the dense coupling of the laws' directions over the
 * harmonics (the capacitance of rank ngroup (2H + 1): 2/3 r^3). */
double gd_per_hb_step_flops(gd_transient *tr, int H, int N)
{
    int nf, nterm, ngroup;
    long knz;
    gd_hb_memory_params_tr(tr, &nf, &nterm, &ngroup, &knz);
    const double nh = 2.0 * H + 1.0, r = (double)ngroup * nh;
    return 2.0 * nf * 2.5 * N * log2((double)N) + (double)N * GD_PER_TERM_FLOPS * nterm +
           2.0 * nterm * nh * nh + 20.0 * nh * (double)knz + 2.0 / 3.0 * r * r * r;
}
