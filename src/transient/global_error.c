/* The global error of a CVODE run, estimated by a second run at tolerances
 * GD_TR_EST_FACTOR times tighter. CVODE controls each step's local error, which does
 * not bound the error carried to the records (on the 366-DOF rotor the local control at
 * rtol 1e-6 left 1.8e-5 at a bearing; on the Ducati train 0.75 of a mesh force's peak).
 * With the global error e(tol) ~ C tol^p (tolerance proportionality: Shampine,
 * "Tolerance proportionality in ODE codes", 1989), the difference d of the runs at tol
 * and f tol is e(tol) (1 - f^p), so e(tol) = d / (1 - f^p), which for f = 1/10 is
 * between d and 1.5 d for any p >= 0.5 (taken p = 1: d / 0.9). A looser second run
 * would cost less but needs p, which CVODE does not hold to: measured on the 42-DOF
 * rotor and the Ducati train (docs/transient.md), d / 9 against a run 10 times looser
 * was 0.1-9 times the true error, d / 0.9 against a tighter one 0.9-1.3 times. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "transient/transient_impl.h"

#define GD_TR_EST_FACTOR 0.1

/* Largest difference of b from a over the records, each relative to its peak in a (the
 * end displacements, relative to their peak, when nothing is recorded: the end state
 * holds the angles of a train free in torsion, which are not what the user asked). A record's
 * samples where either run has a gap (NaN) are skipped, and the contact state (-1, 0, 1) is not
 * compared: a step in it a sample early is not an error of its size. */
static double difference(const gd_transient_result *a, const gd_transient_result *b)
{
    double e = 0.0;
    const int nout = a->nout;
    int compared = 0;
    for (int r = 0; r < a->nrecords && nout == b->nout; r++) {
        if (a->records[r].kind == GD_REC_MESH_STATE) continue;
        compared++;
        const double *x = a->values + (size_t)r * nout, *y = b->values + (size_t)r * nout;
        double pk = 0.0, d = 0.0;
        for (int k = 0; k < nout; k++) {
            if (isnan(x[k]) || isnan(y[k])) continue;
            pk = fmax(pk, fabs(x[k]));
            d = fmax(d, fabs(x[k] - y[k]));
        }
        if (pk > 0) e = fmax(e, d / pk);
    }
    if (compared) return e;
    double pk = 0.0, d = 0.0;
    for (int i = 0; i < a->ndof && a->ndof == b->ndof; i++) {
        pk = fmax(pk, fabs(a->q_end[i]));
        d = fmax(d, fabs(a->q_end[i] - b->q_end[i]));
    }
    if (pk > 0) e = fmax(e, d / pk);
    return e;
}

/* res->error_estimate and a clause of res->method_note for the finished CVODE run res
 * of opt (method m): -1 with the reason in the note when the second run fails.
 * res->cpu_seconds includes that run. */
static void estimate(gd_transient *tr, const gd_transient_options *opt, gd_tr_method m,
                     const gd_tr_record *records, int nrecords, gd_transient_result *res)
{
    gd_transient_options o = *opt;
    const double f = GD_TR_EST_FACTOR;
    o.method = m; /* auto resolved: the same method, bit for bit */
    o.rtol = opt->rtol * f;
    o.atol_q *= f;
    o.atol_v *= f;
    o.error_estimate = 0;
    o.progress = NULL;
    o.sample_times = NULL;
    o.nsample_times = 0;
    gd_transient_result *b = NULL;
    gd_error err;
    size_t k = strlen(res->method_note);
    const size_t len = sizeof res->method_note;
    if (gd_tr_run_once(tr, &o, records, nrecords, &b, &err)) {
        res->error_estimate = -1.0;
        snprintf(res->method_note + k, len - k, "; no error estimate (the run at rtol %.3g: %s)",
                 o.rtol, err.message);
        return;
    }
    res->error_estimate = difference(res, b) / (1.0 - f);
    res->cpu_seconds += b->cpu_seconds;
    snprintf(res->method_note + k, len - k, "; estimated error %.2g (against the run at rtol %.3g)",
             res->error_estimate, o.rtol);
    gd_transient_result_free(b);
}

gd_status gd_transient_run(gd_transient *tr, const gd_transient_options *opt,
                           const gd_tr_record *records, int nrecords, gd_transient_result **out,
                           gd_error *err)
{
    gd_status st = gd_tr_run_once(tr, opt, records, nrecords, out, err);
    if (st || !opt->error_estimate) return st;
    /* CVODE's error control is local: the global error from a second run */
    const gd_tr_method m = (*out)->method_used;
    if (m == GD_TR_BDF || m == GD_TR_ADAMS) estimate(tr, opt, m, records, nrecords, *out);
    return GD_OK;
}
