/* Study analysis `frf` (geardyn/frf.h): one input, one output, over a frequency range.
 * Options: input (NODE.DOF or torque:NODE), output (NODE.DOF or mesh:NAME),
 * frequencies {from, to, count} (required), speed, method (direct | modal). Outputs:
 * the largest magnitude over the range and its frequency. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/frf.h"
#include "study/study_impl.h"

static const char *const KEYS[] = {"input", "output", "frequencies", "speed", "method", NULL};
static const char *const METHODS[] = {"direct", "modal", NULL};

typedef struct frf_opts {
    char input[160], output[160];
    gd_study_sweep freqs;
    double speed;
    int method;
} frf_opts;

enum { PEAK, PEAK_HZ };
static const gd_study_output_def OUTPUTS[] = {
    {"peak_magnitude", 0, "largest |H| over the frequencies"},
    {"peak_frequency_hz", 0, "frequency of the largest |H|, Hz"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    frf_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    const char *in = NULL, *outp = NULL;
    if (gd_study_read_sweep(r, map, "frequencies", &o->freqs) ||
        gd_yread_str(r, map, "input", "analysis", NULL, GD_YREQ, &in, NULL, NULL) ||
        gd_yread_str(r, map, "output", "analysis", NULL, GD_YREQ, &outp, NULL, NULL) ||
        gd_yread_qty(r, map, "speed", "analysis", GD_QTY_ANGULAR_SPEED, GD_YNONNEG, &o->speed,
                     NULL) ||
        gd_yread_str(r, map, "method", "analysis", METHODS, 0, NULL, &o->method, NULL))
        return GD_EINPUT;
    snprintf(o->input, sizeof o->input, "%s", in);
    snprintf(o->output, sizeof o->output, "%s", outp);
    return GD_OK;
}

static gd_status probes(const gd_system *sys, const frf_opts *o, gd_probe *pout, int *din,
                        gd_error *err)
{
    gd_probe pin;
    int dout;
    gd_status st = gd_study_probe(sys, o->input, &pin, din, err);
    if (!st && *din < 0)
        st = gd_error_set(err, GD_EINPUT, "", 0, 0, "analysis.input",
                          "an input is NODE.DOF or torque:NODE", "'%s' is not a DOF", o->input);
    if (!st) st = gd_study_probe(sys, o->output, pout, &dout, err);
    return st;
}

static gd_status check(const gd_system *sys, const void *opts, gd_error *err)
{
    gd_probe pout;
    int din;
    return probes(sys, opts, &pout, &din, err);
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    const frf_opts *o = opts;
    gd_probe pout;
    int din;
    gd_status st = probes(in->sys, o, &pout, &din, err);
    if (st) return st;
    double *f = gd_study_sweep_values(&o->freqs);
    if (!f) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    gd_frf_options fo;
    gd_frf_options_init(&fo);
    fo.nfreq = (int)o->freqs.count;
    fo.freqs = f;
    fo.speed = o->speed;
    fo.ninputs = 1;
    fo.inputs = &din;
    fo.noutputs = 1;
    fo.outputs = &pout;
    fo.method = o->method ? GD_FRF_MODAL : GD_FRF_DIRECT;
    fo.nthreads = 1;
    gd_frf_result *res;
    st = gd_frf(in->sys, &fo, &res, err);
    if (st) {
        free(f);
        return st;
    }
    double peak;
    long k = gd_study_peak(res->re, res->im, (size_t)res->nfreq, &peak);
    double at = k >= 0 ? f[k] / (2 * M_PI) : NAN;
    for (int i = 0; i < nreq; i++)
        values[i] = req[i].def == PEAK ? peak : at;
    gd_frf_free(res);
    free(f);
    return GD_OK;
}

static double operating_speed(const void *opts)
{
    return ((const frf_opts *)opts)->speed;
}

const gd_study_runner gd_study_frf = {.name = "frf",
                                      .keys = KEYS,
                                      .operating_speed = operating_speed,
                                      .options = options,
                                      .check = check,
                                      .outputs = OUTPUTS,
                                      .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                      .run = run};
