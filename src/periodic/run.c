/* The periodic steady state over speed or a model parameter (docs/periodic.md,
 * "Structure"): the options, their bounds, the run by one row of the method table
 * (method.h: harmonic balance in hb_method.c, shooting, the multi-frequency torus), and the
 * result. The shared pseudo-arclength driver is arclength.c; harmonic balance's jobs are in
 * stage.c (the problem per value), corrector.c (Newton, tangent, fixed-value solves),
 * points.c (Floquet, records, the truncation estimate, emitted points), bifurcation.c
 * (location) and continuation.c (its branch and its operations for the driver). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/continuation_impl.h"
#include "periodic/method.h"
#include "periodic/periodic_impl.h"

void gd_periodic_options_init(gd_periodic_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->harmonics = 10;
    opt->harmonic_tol = 0.01;
    opt->max_harmonics = 0;
    opt->estimate = 1;
    opt->subharmonic = 1;
    opt->tol = 1e-10;
    opt->max_iter = 30;
    opt->stability = 1;
    opt->method = GD_PER_ARCLENGTH;
}

const char *gd_bifurcation_name(gd_bifurcation_type t)
{
    switch (t) {
    case GD_BIF_FOLD:
        return "fold";
    case GD_BIF_PERIOD_DOUBLING:
        return "period_doubling";
    case GD_BIF_NEIMARK_SACKER:
        return "neimark_sacker";
    default:
        return "branch_point";
    }
}

/* ---------------------------------------------------------------- problems per value */

gd_status gd_per_check_options(const gd_periodic_param *param, const double *values, int nvalues,
                               const gd_periodic_options *opt, const gd_tr_record *records,
                               int nrecords, gd_error *err)
{
#define BAD(field, hint, ...)                                                                      \
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint, __VA_ARGS__)
    if (nvalues < 1 || !values) BAD("speeds", "give FROM:TO:COUNT", "no values to solve at");
    for (int i = 0; i < nvalues; i++) /* named as given (issue 38 L3: "speeds" for all) */
        if (!isfinite(values[i]))
            BAD(!param                  ? "speeds"
                : param->load_frequency ? "frequency"
                                        : "parameter",
                "", "%s value %d (%g) is not finite", param && param->name ? param->name : "the",
                i + 1, values[i]);
    if (opt->harmonics < 1)
        BAD("harmonics", "give H >= 1", "harmonic count %d out of range", opt->harmonics);
    if (opt->max_harmonics < 0 || opt->memory_limit < 0)
        BAD("max_harmonics", "give 0 (memory decides) or a positive cap",
            "max_harmonics and memory_limit must not be negative");
    if (opt->subharmonic < 1 || opt->subharmonic > 1000)
        BAD("subharmonic", "give N from 1 to 1000 (period N times the fundamental)",
            "subharmonic order %d is outside 1..1000", opt->subharmonic);
    if (!(opt->tol > 0) || opt->tol < 1e-15)
        BAD("tol", "give a tolerance in [1e-15, 1)",
            "tolerance %g is unreachable in double precision", opt->tol);
    if (opt->max_iter < 1) BAD("max_iter", "", "max_iter must be at least 1");
    if (opt->samples < 0 || opt->samples > GD_PERIODIC_MAX_SAMPLES)
        BAD("samples", "give 0 (automatic) or 4..1048576 (2^20)",
            "%d AFT samples per period is outside 0..%d", opt->samples, GD_PERIODIC_MAX_SAMPLES);
    if (opt->monodromy_steps < 0 || opt->monodromy_steps > GD_PERIODIC_MAX_SAMPLES)
        BAD("monodromy_steps", "give 0 (automatic) or 1..1048576 (2^20)",
            "%d Magnus steps per period is outside 0..%d", opt->monodromy_steps,
            GD_PERIODIC_MAX_SAMPLES);
    if (opt->samples && opt->samples < 2 * opt->harmonics + 2)
        BAD("samples", "give at least 2 H + 2", "%d samples cannot resolve %d harmonics",
            opt->samples, opt->harmonics);
    if ((opt->adaptive || opt->estimate) && !(opt->harmonic_tol > 0))
        BAD("harmonic_tol", "", "the harmonic truncation tolerance must be > 0");
    for (int r = 0; r < nrecords; r++)
        if (records[r].kind == GD_REC_ANGLE)
            BAD("record", "record the DOF's displacement (perturbation) instead",
                "a total angle grows with time and has no periodic steady state");
    if (opt->kind < GD_PER_HB || opt->kind > GD_PER_REDUCED_SHOOTING)
        BAD("method", "give hb, shooting, multifreq, reduced-shooting or auto",
            "unknown periodic method %d", (int)opt->kind);
    if (opt->shoot_rtol < 0 ||
        (opt->shoot_rtol > 0 && !(opt->shoot_rtol >= 1e-14 && opt->shoot_rtol < 1e-2)))
        BAD("shoot_rtol", "give 0 (1e-9) or a tolerance in [1e-14, 1e-2)",
            "shooting tolerance %g out of range", opt->shoot_rtol);
    if (opt->floquet < GD_FLOQUET_AUTO || opt->floquet > GD_FLOQUET_REDUCED ||
        opt->floquet_count < 0 || opt->floquet_count > 256 || opt->floquet_dmax < 0)
        BAD("floquet",
            "give floquet 0 (auto), 1 (dense), 2 (krylov) or 3 (reduced), floquet_count 0..256",
            "Floquet options out of range (method %d, count %d, dense_max %d)", opt->floquet,
            opt->floquet_count, opt->floquet_dmax);
    if (!(opt->floquet_cutoff >= 0) || isinf(opt->floquet_cutoff))
        BAD("floquet_cutoff", "give 0 (the default, 4) or a multiple > 0",
            "Floquet cut-off %g out of range", opt->floquet_cutoff);
    if (!(opt->floquet_budget >= 0) || isinf(opt->floquet_budget))
        BAD("floquet_budget", "give CPU seconds > 0, or 0 for no limit",
            "Floquet budget %g s out of range", opt->floquet_budget);
    if (opt->shoot_stability < 0 || opt->shoot_stability > 2)
        BAD("shoot_stability",
            "give 0 (Magnus about the Fourier orbit), 1 (non-smooth laws: the "
            "orbit corrected by shooting) or 2 (always)",
            "shoot_stability %d out of range", opt->shoot_stability);
    if (opt->condensed < -1 || opt->condensed > 1)
        BAD("condensed", "give 0 (where it applies), 1 (always) or -1 (never)",
            "condensed %d out of range", opt->condensed);
    if (opt->shoot_dense_max < 0 || opt->shoot_budget < 0)
        BAD("shoot_dense_max", "give 0 (the default) or a positive value",
            "shoot_dense_max and shoot_budget must not be negative");
#undef BAD
    return GD_OK;
}

gd_status gd_per_run_kind(const gd_system *sys, const gd_transient_spec *spec,
                          const gd_periodic_param *param, const double *values, int nvalues,
                          const gd_periodic_options *opt, const gd_tr_record *records, int nrecords,
                          gd_periodic_result **out, gd_error *err)
{
    *out = NULL;
    clock_t c0 = clock();
    {
        gd_status cs = gd_per_check_options(param, values, nvalues, opt, records, nrecords, err);
        if (cs) return cs;
    }
    const gd_per_method_row *mt = gd_per_method_find(opt->kind);
    if (!mt)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method", "",
                            "auto is resolved by the caller");
    gd_periodic_result *res = calloc(1, sizeof *res);
    if (!res) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    res->nrecords = nrecords;
    res->method = mt->kind;
    gd_status st =
        mt->run(mt->ops, sys, spec, param, values, nvalues, opt, records, nrecords, res, err);
    if (st) {
        gd_periodic_result_free(res);
        return st;
    }
    res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    *out = res;
    return GD_OK;
}

void gd_periodic_result_free(gd_periodic_result *r)
{
    if (!r) return;
    for (int i = 0; i < r->npoints; i++) {
        gd_periodic_point *p = &r->points[i];
        free(p->coef);
        free(p->mu_re);
        free(p->mu_im);
        if (p->records)
            for (int k = 0; k < r->nrecords; k++) {
                free(p->records[k].amplitude);
                free(p->records[k].phase_deg);
            }
        free(p->records);
    }
    free(r->points);
    free(r->bifurcations);
    free(r);
}
