/* Study analysis `transient` (geardyn/transient.h): time integration at a constant
 * speed with the model's nonlinear laws (backlash, TVMS, dampers), as `geardyn
 * transient` runs it. Options: revolutions or duration (one required), speed (default
 * the model's), from (fraction of the run before statistics start, default 0.5, as the
 * CLI), mesh (the mesh whose force and contacts are kept; default the first), rtol,
 * method (auto | bdf | adams; auto as the CLI's default), start (rest | static), max_steps (the
 * per-case step limit, default 50 million: a case that needs more fails with the reason before it
 * runs, and the others go on), condense (none | auto | all: the structure condensed onto the
 * laws' DOFs, gd_transient_new_condensed, with the automatic cut-off or every mode).
 * Statistics are over the recorded window. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/rattle.h"
#include "geardyn/transient_model.h"
#include "study/study_impl.h"

static const char *const KEYS[] = {"revolutions", "duration", "speed",  "from",
                                   "mesh",        "rtol",     "method", "start",
                                   "max_steps",   "condense", NULL};
static const char *const CONDENSE[] = {"none", "auto", "all", NULL};
static const char *const METHODS[] = {"auto", "bdf", "adams", NULL};
static const gd_tr_method METHOD_OF[] = {GD_TR_AUTO, GD_TR_BDF, GD_TR_ADAMS};
static const char *const STARTS[] = {"rest", "static", NULL};

typedef struct tr_opts {
    double revolutions, duration, speed, from, rtol;
    int has_speed, method, start, condense;
    long max_steps;
    char mesh[128];
} tr_opts;

enum {
    F_MAX,
    F_MIN,
    F_MEAN,
    F_RMS,
    F_P2P,
    F_STD,
    LOSSES,
    COAST,
    DRIVE,
    SEPARATED,
    R_SEP,
    R_SEP_HW,
    R_DRIVE,
    R_COAST,
    R_INT,
    R_INT_HW,
    R_VRMS
};
static const gd_study_output_def OUTPUTS[] = {
    {"mesh_force_max", 0, "largest mesh force, N"},
    {"mesh_force_min", 0, "smallest mesh force, N"},
    {"mesh_force_mean", 0, "mean mesh force, N"},
    {"mesh_force_rms", 0, "root mean square of the mesh force, N"},
    {"mesh_force_p2p", 0, "peak-to-peak mesh force, N"},
    {"mesh_force_std", 0, "standard deviation of the mesh force, N"},
    {"contact_losses", 0, "drive -> separated transitions of the mesh (backlash)"},
    {"coast_impacts", 0, "separated -> coast-side impacts"},
    {"drive_impacts", 0, "separated -> drive-side re-contacts"},
    {"separated_time", 0, "time out of contact, s"},
    /* rattle metrics (geardyn/rattle.h: 10 batches, 95 %) over the recorded window */
    {"separated_fraction", 0, "fraction of the window out of contact"},
    {"separated_fraction_hw", 0, "its 95 % half-width (batch means)"},
    {"drive_impacts_per_s", 0, "drive-flank impacts per second"},
    {"coast_impacts_per_s", 0, "coast-flank impacts per second"},
    {"rattle_intensity", 0, "impact energy per second m_e v^2 / 2, W"},
    {"rattle_intensity_hw", 0, "its 95 % half-width (batch means), W"},
    {"impact_speed_rms", 0, "RMS of the impact speeds, m/s"},
};

/* The rattle metrics of spec mesh k over [t0, t1] (zeros when the mesh has no events
 * and stays in contact). */
static gd_status rattle_of(gd_transient *tr, const gd_transient_result *res, int k, double t0,
                           double t1, gd_rattle_metrics *m, gd_error *err)
{
    gd_rattle_event *ev =
        malloc((size_t)(res->ncontact_events > 0 ? res->ncontact_events : 1) * sizeof *ev);
    if (!ev) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    int n = 0;
    for (int i = 0; i < res->ncontact_events; i++) {
        const gd_tr_contact_event *e = &res->contact_events[i];
        if (e->mesh == k) ev[n++] = (gd_rattle_event){e->t, e->from, e->to, e->velocity};
    }
    gd_rattle_options o;
    gd_rattle_options_init(&o);
    o.t0 = t0;
    o.t1 = t1;
    const gd_tr_contact_stats *c = &res->contacts[k];
    o.state0 = c->drive_time > 0 ? 1 : (c->coast_time > 0 ? -1 : 0);
    gd_error merr;
    if (gd_transient_mesh_mass(tr, k, &o.mass, &merr)) o.mass = 0.0;
    gd_status st = gd_rattle_metrics_eval(ev, n, &o, m, err);
    free(ev);
    return st;
}

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    tr_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    o->from = 0.5;
    o->rtol = 1e-6;
    int has_rev = 0, has_dur = 0;
    if (!map ||
        gd_yread_qty(r, map, "revolutions", "analysis", GD_QTY_DIMLESS, GD_YPOS, &o->revolutions,
                     &has_rev) ||
        gd_yread_qty(r, map, "duration", "analysis", GD_QTY_TIME, GD_YPOS, &o->duration,
                     &has_dur) ||
        gd_yread_qty(r, map, "speed", "analysis", GD_QTY_ANGULAR_SPEED, GD_YPOS, &o->speed,
                     &o->has_speed) ||
        gd_yread_qty(r, map, "from", "analysis", GD_QTY_DIMLESS, GD_YNONNEG, &o->from, NULL) ||
        gd_yread_qty(r, map, "rtol", "analysis", GD_QTY_DIMLESS, GD_YPOS, &o->rtol, NULL) ||
        gd_yread_str(r, map, "method", "analysis", METHODS, 0, NULL, &o->method, NULL) ||
        gd_yread_str(r, map, "start", "analysis", STARTS, 0, NULL, &o->start, NULL) ||
        gd_yread_str(r, map, "condense", "analysis", CONDENSE, 0, NULL, &o->condense, NULL) ||
        gd_yread_int(r, map, "max_steps", "analysis", 1, 2000000000, 0, &o->max_steps, NULL))
        return map ? GD_EINPUT
                   : gd_yfail(r, map, "analysis",
                              "e.g. `analysis: {type: transient, revolutions: 2}`",
                              "a transient needs revolutions or duration");
    if (has_rev == has_dur)
        return gd_yfail(r, map, "analysis", "give `revolutions: N` or `duration: T`, not both",
                        has_rev ? "revolutions and duration both given"
                                : "a transient needs revolutions or duration");
    if (o->from >= 1)
        return gd_yfail(r, gd_ymap_get(map, "from"), "analysis.from",
                        "a fraction of the run in [0, 1)", "from = %g", o->from);
    const char *mesh = NULL;
    if (gd_yread_str(r, map, "mesh", "analysis", NULL, 0, &mesh, NULL, NULL)) return GD_EINPUT;
    if (mesh) snprintf(o->mesh, sizeof o->mesh, "%s", mesh);
    return GD_OK;
}

static int mesh_of(const gd_system *sys, const tr_opts *o)
{
    return o->mesh[0] ? gd_model_find_mesh(sys->model, o->mesh) : 0;
}

static gd_status check(const gd_system *sys, const void *opts, gd_error *err)
{
    const tr_opts *o = opts;
    if (sys->model->nmeshes == 0)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "analysis", "use a model with a gear mesh",
                            "the model has no mesh to record");
    if (mesh_of(sys, o) < 0)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "analysis.mesh",
                            "give the name of one of the model's meshes", "no mesh named '%s'",
                            o->mesh);
    if (o->revolutions > 0 && !o->has_speed && !(sys->model->speed > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "analysis.speed",
                            "give `speed:` here or in the model, or use `duration:`",
                            "revolutions need a reference speed");
    return GD_OK;
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    const tr_opts *o = opts;
    const gd_system *sys = in->sys;
    gd_status st = check(sys, o, err);
    if (st) return st;
    double speed = o->has_speed ? o->speed : sys->model->speed;
    double t_end = o->duration > 0 ? o->duration : 2 * M_PI * o->revolutions / speed;
    int mesh = mesh_of(sys, o);
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_transient_result *res = NULL;
    st = gd_transient_model_build(sys, &tm, err);
    if (!st)
        st = o->condense ? gd_transient_new_condensed(sys, &tm->spec, speed,
                                                      o->condense == 1 ? -1.0 : 0.0, &tr, err)
                         : gd_transient_new(sys, &tm->spec, speed, &tr, err);
    if (!st) {
        gd_transient_options opt;
        gd_transient_options_init(&opt);
        opt.t_end = t_end;
        opt.record_from = o->from * t_end;
        /* as `geardyn transient`: 2000 samples, at least 32 per revolution */
        opt.output_interval = (t_end - opt.record_from) / 2000.0;
        if (speed > 0 && 2 * M_PI / speed / 32 < opt.output_interval)
            opt.output_interval = fmax(2 * M_PI / speed / 32, (t_end - opt.record_from) / 2e6);
        opt.rtol = o->rtol;
        opt.method = METHOD_OF[o->method];
        opt.init = o->start ? GD_TR_INIT_STATIC : GD_TR_INIT_REST;
        opt.max_steps = o->max_steps;
        gd_tr_record rec = {GD_REC_MESH_FORCE, mesh, 0};
        st = gd_transient_run(tr, &opt, &rec, 1, &res, err);
    }
    if (!st) {
        const gd_tr_stats *f = &res->stats[0];
        int k = gd_transient_model_mesh_index(tm, mesh);
        const gd_tr_contact_stats *c = k >= 0 ? &res->contacts[k] : NULL;
        gd_rattle_metrics rm;
        memset(&rm, 0, sizeof rm);
        int want = 0;
        for (int i = 0; i < nreq; i++)
            want |= req[i].def >= R_SEP;
        if (want && k >= 0) st = rattle_of(tr, res, k, o->from * t_end, t_end, &rm, err);
        for (int i = 0; st == GD_OK && i < nreq; i++) {
            double v = NAN;
            switch (req[i].def) {
            case F_MAX:
                v = f->max;
                break;
            case F_MIN:
                v = f->min;
                break;
            case F_MEAN:
                v = f->mean;
                break;
            case F_RMS:
                v = f->rms;
                break;
            case F_P2P:
                v = f->peak_to_peak;
                break;
            case F_STD:
                v = f->std;
                break;
            case LOSSES:
                v = c ? c->contact_losses : 0;
                break;
            case COAST:
                v = c ? c->coast_impacts : 0;
                break;
            case DRIVE:
                v = c ? c->drive_impacts : 0;
                break;
            case SEPARATED:
                v = c ? c->separated_time : 0;
                break;
            case R_SEP:
                v = rm.separated.mean;
                break;
            case R_SEP_HW:
                v = rm.separated.half_width;
                break;
            case R_DRIVE:
                v = rm.drive_rate.mean;
                break;
            case R_COAST:
                v = rm.coast_rate.mean;
                break;
            case R_INT:
                v = rm.intensity.mean;
                break;
            case R_INT_HW:
                v = rm.intensity.half_width;
                break;
            case R_VRMS:
                v = rm.v_rms;
                break;
            }
            values[i] = v;
        }
    }
    gd_transient_result_free(res);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    return st;
}

const gd_study_runner gd_study_transient = {.name = "transient",
                                            .keys = KEYS,
                                            .options = options,
                                            .check = check,
                                            .outputs = OUTPUTS,
                                            .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                            .run = run};
