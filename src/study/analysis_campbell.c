/* Study analysis `campbell` (geardyn/campbell.h): damped modes over speed, critical
 * speeds and the onset of instability. Options: speeds {from, to, count} (required),
 * modes (tracked, default 8), kind (auto | undamped | damped). The sweep runs on one
 * thread: the study is parallel over cases instead. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/campbell.h"
#include "study/study_impl.h"

static const char *const KEYS[] = {"speeds", "modes", "kind", NULL};
static const char *const KINDS[] = {"auto", "undamped", "damped", NULL};

typedef struct cb_opts {
    gd_study_sweep speeds;
    long modes;
    int kind;
} cb_opts;

enum { CRIT_RPM, CRIT_HZ, NCRIT, ONSET };
static const gd_study_output_def OUTPUTS[] = {
    {"critical_speed_rpm", 1, "k-th critical speed (all orders, by speed), rpm"},
    {"critical_frequency_hz", 1, "frequency at the k-th critical speed, Hz"},
    {"ncritical", 0, "number of critical speeds in the range"},
    {"instability_onset_rpm", 0, "speed where a mode turns unstable, rpm (NaN: stable)"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    cb_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    o->modes = 8;
    if (gd_study_read_sweep(r, map, "speeds", &o->speeds)) return GD_EINPUT;
    if (gd_yread_int(r, map, "modes", "analysis", 1, 100000, 0, &o->modes, NULL) ||
        gd_yread_str(r, map, "kind", "analysis", KINDS, 0, NULL, &o->kind, NULL))
        return GD_EINPUT;
    return GD_OK;
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    const cb_opts *o = opts;
    double *speeds = gd_study_sweep_values(&o->speeds);
    if (!speeds) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    gd_campbell_options co;
    gd_campbell_options_init(&co);
    co.nspeeds = (int)o->speeds.count;
    co.speeds = speeds;
    co.nmodes = (int)o->modes;
    co.kind = (gd_modal_kind)o->kind;
    co.nthreads = 1;
    gd_campbell_result *res;
    gd_status st = gd_campbell(in->sys, &co, &res, err);
    free(speeds);
    if (st) return st;
    for (int i = 0; i < nreq; i++) {
        int k = req[i].k;
        const gd_critical_speed *c = k >= 1 && k <= res->ncritical ? &res->critical[k - 1] : NULL;
        double v = NAN;
        switch (req[i].def) {
        case CRIT_RPM:
            v = c ? c->speed_rpm : NAN;
            break;
        case CRIT_HZ:
            v = c ? c->frequency_hz : NAN;
            break;
        case NCRIT:
            v = res->ncritical;
            break;
        case ONSET:
            v = res->instability_onset * 30 / M_PI;
            break;
        }
        values[i] = v;
    }
    gd_campbell_free(res);
    return GD_OK;
}

/* a sweep: the equilibrium solved at each speed */
static double operating_speed(const void *opts)
{
    (void)opts;
    return -1;
}

const gd_study_runner gd_study_campbell = {.name = "campbell",
                                           .operating_speed = operating_speed,
                                           .keys = KEYS,
                                           .options = options,
                                           .outputs = OUTPUTS,
                                           .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                           .run = run};
