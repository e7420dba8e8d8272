/* Study analysis `modal` (geardyn/modal.h): the modes at one speed.
 * Options: speed (default 0), modes (lowest kept, default all), kind
 * (auto | undamped | damped). Outputs per mode k (ascending natural frequency, rigid-body
 * modes included, as `geardyn modal` lists them). */
#include <math.h>
#include <stdlib.h>

#include "geardyn/modal.h"
#include "study/study_impl.h"

static const char *const KEYS[] = {"speed", "modes", "kind", NULL};
static const char *const KINDS[] = {"auto", "undamped", "damped", NULL};

enum { F_HZ, W_N, W_D, ZETA, LOGDEC, NMODES };
static const gd_study_output_def OUTPUTS[] = {
    {"frequency_hz", 1, "natural frequency of mode k, Hz"},
    {"omega_n", 1, "natural frequency of mode k, rad/s"},
    {"omega_d", 1, "damped frequency of mode k, rad/s"},
    {"zeta", 1, "damping ratio of mode k"},
    {"logdec", 1, "log decrement of mode k"},
    {"nmodes", 0, "number of modes found"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    gd_modal_options *o = malloc(sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    gd_modal_options_init(o);
    /* no left vectors, as `geardyn modal`: they are no output here, and asking for them
     * kept every case on the dense solver where the CLI takes the sparse one when it is
     * cheaper (frequencies 1e-11 apart, not the CLI's numbers bit for bit) */
    o->want_left = 0;
    if (!map) return GD_OK;
    long modes = 0;
    int kind = 0;
    if (gd_yread_qty(r, map, "speed", "analysis", GD_QTY_ANGULAR_SPEED, GD_YNONNEG, &o->speed,
                     NULL) ||
        gd_yread_int(r, map, "modes", "analysis", 1, 1000000, 0, &modes, NULL) ||
        gd_yread_str(r, map, "kind", "analysis", KINDS, 0, NULL, &kind, NULL))
        return GD_EINPUT;
    o->nmodes = (int)modes;
    o->kind = (gd_modal_kind)kind;
    return GD_OK;
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    gd_modal_result *res;
    gd_status st = gd_modal_solve(in->sys, opts, &res, err);
    if (st) return st;
    for (int i = 0; i < nreq; i++) {
        int k = req[i].k;
        const gd_mode *md = k >= 1 && k <= res->nmodes ? &res->modes[k - 1] : NULL;
        double v = NAN;
        switch (req[i].def) {
        case F_HZ:
            v = md ? md->frequency_hz : NAN;
            break;
        case W_N:
            v = md ? md->omega_n : NAN;
            break;
        case W_D:
            v = md ? md->omega_d : NAN;
            break;
        case ZETA:
            v = md ? md->damping_ratio : NAN;
            break;
        case LOGDEC:
            v = md ? md->log_decrement : NAN;
            break;
        case NMODES:
            v = res->nmodes;
            break;
        }
        values[i] = v;
    }
    gd_modal_free(res);
    return GD_OK;
}

static double operating_speed(const void *opts)
{
    return ((const gd_modal_options *)opts)->speed;
}

const gd_study_runner gd_study_modal = {.name = "modal",
                                        .keys = KEYS,
                                        .operating_speed = operating_speed,
                                        .options = options,
                                        .outputs = OUTPUTS,
                                        .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                        .run = run};
