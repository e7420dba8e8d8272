/* Study analysis `unbalance` (geardyn/unbalance.h): the steady response to the model's
 * unbalances at one output over a speed range. Options: output (NODE.DOF or
 * mesh:NAME), speeds {from, to, count} (required). Outputs: the largest amplitude over
 * the speeds and shaft harmonics, and its speed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/unbalance.h"
#include "study/study_impl.h"

static const char *const KEYS[] = {"output", "speeds", NULL};

typedef struct ub_opts {
    char output[160];
    gd_study_sweep speeds;
} ub_opts;

enum { PEAK, PEAK_RPM };
static const gd_study_output_def OUTPUTS[] = {
    {"peak_amplitude", 0, "largest amplitude over speeds and harmonics (m, rad or N)"},
    {"peak_speed_rpm", 0, "speed of the largest amplitude, rpm"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    ub_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    const char *outp = NULL;
    if (gd_study_read_sweep(r, map, "speeds", &o->speeds) ||
        gd_yread_str(r, map, "output", "analysis", NULL, GD_YREQ, &outp, NULL, NULL))
        return GD_EINPUT;
    snprintf(o->output, sizeof o->output, "%s", outp);
    return GD_OK;
}

static gd_status check(const gd_system *sys, const void *opts, gd_error *err)
{
    const ub_opts *o = opts;
    gd_probe p;
    int dof;
    return gd_study_probe(sys, o->output, &p, &dof, err);
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    const ub_opts *o = opts;
    gd_probe p;
    int dof;
    gd_status st = gd_study_probe(in->sys, o->output, &p, &dof, err);
    if (st) return st;
    double *sp = gd_study_sweep_values(&o->speeds);
    if (!sp) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    gd_unbalance_options uo;
    gd_unbalance_options_init(&uo);
    uo.nspeeds = (int)o->speeds.count;
    uo.speeds = sp;
    uo.noutputs = 1;
    uo.outputs = &p;
    uo.nthreads = 1;
    gd_unbalance_result *res;
    st = gd_unbalance_response(in->sys, &uo, &res, err);
    if (st) {
        free(sp);
        return st;
    }
    /* one output: the responses are harmonic-major, [h * nspeeds + s] */
    double peak;
    long k = gd_study_peak(res->re, res->im, (size_t)res->nharmonics * (size_t)res->nspeeds, &peak);
    double at = k >= 0 ? sp[k % res->nspeeds] * 30 / M_PI : NAN;
    for (int i = 0; i < nreq; i++)
        values[i] = req[i].def == PEAK ? peak : at;
    gd_unbalance_free(res);
    free(sp);
    return GD_OK;
}

/* a sweep: the equilibrium solved at each speed */
static double operating_speed(const void *opts)
{
    (void)opts;
    return -1;
}

const gd_study_runner gd_study_unbalance = {.name = "unbalance",
                                            .operating_speed = operating_speed,
                                            .keys = KEYS,
                                            .options = options,
                                            .check = check,
                                            .outputs = OUTPUTS,
                                            .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                            .run = run};
