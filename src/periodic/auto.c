/* The entry gd_periodic_run: harmonic balance or shooting as asked (run.c), or
 * `--method auto` (GD_PER_AUTO): the method the cost rule picks (gd_periodic_choose) runs
 * the whole branch; a requested point it fails is handed to the other method, solved there
 * alone (natural continuation from its own warm start), and says so in its reason and its
 * method (issue 33 item 3). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "periodic/periodic_impl.h"

static void free_point(gd_periodic_point *p, int nrec)
{
    free(p->coef);
    free(p->mu_re);
    free(p->mu_im);
    if (p->records)
        for (int k = 0; k < nrec; k++) {
            free(p->records[k].amplitude);
            free(p->records[k].phase_deg);
        }
    free(p->records);
}

/* A method's name in a point's reason. */
static const char *prose(gd_per_kind k)
{
    return k == GD_PER_SHOOTING           ? "shooting"
           : k == GD_PER_REDUCED_SHOOTING ? "reduced shooting"
                                          : "harmonic balance";
}

/* Point p (not converged by method `from`) solved by method k alone at its value: replaced
 * by that solution when it converges, else its reason gains method k's. 0 ok, 1 out of
 * memory. */
static int hand_over(const gd_system *sys, const gd_transient_spec *spec,
                     const gd_periodic_param *param, const gd_periodic_options *opt,
                     gd_per_kind from, gd_per_kind k, const gd_tr_record *records, int nrecords,
                     gd_periodic_point *p, int *solved)
{
    gd_periodic_options o = *opt;
    o.kind = k;
    if (o.shoot_stability == 0) o.shoot_stability = 1;
    o.method = GD_PER_SEQUENTIAL;
    o.both_directions = 0;
    o.on_point = NULL;
    o.on_step = NULL;
    o.user = NULL;
    const double v = param ? p->parameter : p->speed;
    gd_periodic_result *r = NULL;
    gd_error err;
    gd_status st = gd_per_run_kind(sys, spec, param, &v, 1, &o, records, nrecords, &r, &err);
    if (st == GD_ENOMEM) return 1;
    const char *other = prose(k), *first = prose(from);
    char was[256];
    snprintf(was, sizeof was, "%s", p->reason);
    if (!st && r->npoints >= 1 && r->points[0].converged) {
        const int dir = p->direction;
        free_point(p, nrecords);
        *p = r->points[0];
        p->direction = dir;
        /* ownership moved: the result keeps no pointers into it */
        r->points[0].coef = r->points[0].mu_re = r->points[0].mu_im = NULL;
        r->points[0].records = NULL;
        char own[256], msg[600];
        snprintf(own, sizeof own, "%s", p->reason);
        if (from == k) /* the same method alone at this value, off its branch */
            snprintf(msg, sizeof msg, "solved by %s alone at this value (%.120s)%s%.80s", other,
                     was, own[0] ? "; " : "", own);
        else
            snprintf(msg, sizeof msg, "solved by %s (%s failed: %.120s)%s%.80s", other, first, was,
                     own[0] ? "; " : "", own);
        snprintf(p->reason, sizeof p->reason, "%.255s", msg);
        (*solved)++;
    } else {
        const char *why = st ? err.message : r && r->npoints ? r->points[0].reason : "no point";
        char msg[600];
        snprintf(msg, sizeof msg, "%.120s; by %s alone: %.110s", was, other, why);
        snprintf(p->reason, sizeof p->reason, "%.255s", msg);
    }
    gd_periodic_result_free(r);
    return 0;
}

gd_status gd_periodic_run(const gd_system *sys, const gd_transient_spec *spec,
                          const gd_periodic_param *param, const double *values, int nvalues,
                          const gd_periodic_options *opt, const gd_tr_record *records, int nrecords,
                          gd_periodic_result **out, gd_error *err)
{
    *out = NULL;
    if (opt->kind != GD_PER_AUTO)
        return gd_per_run_kind(sys, spec, param, values, nvalues, opt, records, nrecords, out, err);
    gd_status cs = gd_per_check_options(param, values, nvalues, opt, records, nrecords, err);
    if (cs) return cs;
    const clock_t c0 = clock(); /* reported only, never decides anything */
    char note[256] = "";
    char refusal[480];
    if (!param && gd_per_qp_refusal(sys, spec, values[0], opt, refusal, sizeof refusal))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method",
                            "run a transient (`geardyn transient`), or --method shooting", "%s",
                            refusal);
    gd_periodic_options o = *opt;
    o.kind = gd_periodic_choose(sys, spec, param, values[0], opt, note);
    /* harmonic balance's multipliers from the time-domain orbit where a law is not smooth */
    if (o.shoot_stability == 0) o.shoot_stability = 1;
    gd_status st =
        gd_per_run_kind(sys, spec, param, values, nvalues, &o, records, nrecords, out, err);
    if (st) return st;
    gd_periodic_result *r = *out;
    /* reduced shooting's failed points go to harmonic balance (full shooting of such a
     * model integrates every DOF: 34 s a period on seed 002) */
    const gd_per_kind other = o.kind == GD_PER_SHOOTING || o.kind == GD_PER_REDUCED_SHOOTING
                                  ? GD_PER_HB
                                  : GD_PER_SHOOTING;
    int failed = 0, solved = 0, alone = 0;
    /* cams with include_acceleration: harmonic balance cannot take them */
    int hb_ok = other != GD_PER_HB || strncmp(note, "shooting: harmonic balance cannot", 33);
    for (int i = 0; i < r->npoints; i++) {
        gd_periodic_point *p = &r->points[i];
        if (p->converged || strstr(p->reason, "period is undefined")) /* no method has one */
            continue;
        int s0 = solved, oom = 0, tried = 0;
        /* a value beyond where shooting's branch stopped (a fold its corrector could not
         * pass, shooting_arclength.c): first shooting alone at it from its own transient,
         * as --sequential would, then harmonic balance */
        if (o.kind == GD_PER_SHOOTING &&
            strstr(p->reason, "--sequential solves each value alone")) {
            tried = 1;
            alone++;
            oom = hand_over(sys, spec, param, opt, o.kind, o.kind, records, nrecords, p, &solved);
        }
        if (!oom && solved == s0 && hb_ok) {
            tried = 1;
            oom = hand_over(sys, spec, param, opt, o.kind, other, records, nrecords, p, &solved);
        }
        failed += tried;
        if (oom) {
            gd_periodic_result_free(r);
            *out = NULL;
            return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        }
    }
    r->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    char run_note[256];
    snprintf(run_note, sizeof run_note, "%s", r->method_note);
    int len = snprintf(r->method_note, sizeof r->method_note, "%s%s%.200s", note,
                       note[0] && run_note[0] ? "; " : "", run_note);
    if (failed && len >= 0 && (size_t)len < sizeof r->method_note)
        snprintf(r->method_note + len, sizeof r->method_note - (size_t)len,
                 alone ? "; %d failed, handed to shooting alone%s: %d solved"
                       : "; %d failed point(s) handed to %s, %d solved there",
                 failed,
                 alone                      ? (hb_ok ? " (then harmonic balance)" : "")
                 : other == GD_PER_SHOOTING ? "shooting"
                                            : "harmonic balance",
                 solved);
    return GD_OK;
}
