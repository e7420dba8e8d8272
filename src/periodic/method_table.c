/* The method table (method.h): one row per periodic method. A new method is one folder
 * (its problem per value and the operations of gd_per_arc_ops over its context, driven by
 * arclength.c) and one row here. GD_PER_AUTO is no row: auto.c picks a row per problem
 * (choose.c) and hands a failed point to the other. */
#include "periodic/method.h"
#include "periodic/multifreq/qphb_impl.h"

/* The multi-frequency torus (multifreq/qp_run.c): speed continuation only. */
static gd_status multifreq_run(const gd_per_arc_ops *ops, const gd_system *sys,
                               const gd_transient_spec *spec, const gd_periodic_param *param,
                               const double *values, int nvalues, const gd_periodic_options *opt,
                               const gd_tr_record *records, int nrecords, gd_periodic_result *res,
                               gd_error *err)
{
    (void)ops;
    if (param)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method",
                            "continue in speed, or use hb or shooting",
                            "the multi-frequency harmonic balance continues in speed only");
    if (gd_per_qp_run(sys, spec, values, nvalues, opt, records, nrecords, res))
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    return GD_OK;
}

/* Each row's operations hold its bifurcation rules: detect between two arclength steps,
 * between (NULL: none) between two points of --sequential.
 * - hb (hb_method.c, continuation.c, bifurcation.c, hb/, condensed/, floquet/): a fold where
 *   the chord's parameter turns (a contact law's at the highest tooth of the sampled saw,
 *   zigzags merged); a multiplier through the circle located on the branch by Illinois
 *   iterations; none between sequential points (docs/periodic.md, "Continuation": on the
 *   [JMSTHelical] spur curve the search took 150 s and did not settle).
 * - shooting (shooting/): a fold where the tangent's parameter component changes sign, a
 *   multiplier through the circle, both located on the branch by Illinois iterations;
 *   between sequential points, a multiplier through the circle located by fixed-value
 *   solves (the real one through +1 reported as the fold it usually is).
 * - multifreq (multifreq/): its own speed loop, no row operations.
 * - reduced shooting (rshoot/): natural continuation only (a linear problem: one direct
 *   solve per value, no folds), no bifurcation rule (the verdicts per point). */
static const gd_per_method_row methods[] = {
    {GD_PER_HB, "harmonic_balance", gd_per_hb_run, &gd_per_hb_ops},
    {GD_PER_SHOOTING, "shooting", gd_per_shoot_method, &gd_per_sh_ops},
    {GD_PER_MULTIFREQ, "multi_frequency_hb", multifreq_run, NULL},
    {GD_PER_REDUCED_SHOOTING, "reduced_shooting", gd_per_rs_run, &gd_per_rs_ops},
};

const gd_per_method_row *gd_per_method_find(gd_per_kind kind)
{
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
        if (methods[i].kind == kind) return &methods[i];
    return NULL;
}
