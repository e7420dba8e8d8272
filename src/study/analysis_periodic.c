/* Study analysis `periodic` (geardyn/periodic.h): the periodic steady state by harmonic
 * balance over a speed range, continued by pseudo-arclength with Floquet stability, as
 * `geardyn periodic` runs it. Options: speeds {from, to, count} (required), output
 * (mesh:NAME for its force or NODE.DOF for its displacement; default the first mesh's
 * force), harmonics (default 10), subharmonic (default 1), method (arclength |
 * sequential). Outputs summarise the branch: the largest peak-to-peak and harmonic
 * amplitudes of the output, the largest Floquet multiplier modulus, the unstable points
 * and the bifurcations by type. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "study/study_impl.h"

#define PI 3.14159265358979323846

static const char *const KEYS[] = {"speeds", "output", "harmonics", "subharmonic", "method", NULL};
static const char *const METHODS[] = {"arclength", "sequential", NULL};

typedef struct per_opts {
    gd_study_sweep speeds;
    char output[160];
    long harmonics, subharmonic;
    int method;
} per_opts;

enum { P2P_MAX, P2P_RPM, HARM_MAX, MU_MAX, UNSTABLE, CONVERGED, NBIF, NFOLD, NPD, NNS, FIRST_BIF };
static const gd_study_output_def OUTPUTS[] = {
    {"p2p_max", 0, "largest peak-to-peak value of the output over the branch (N, m or rad)"},
    {"p2p_max_speed_rpm", 0, "speed of the largest peak-to-peak value, rpm"},
    {"harmonic_amplitude_max", 1, "largest amplitude of harmonic k of the output"},
    {"floquet_max", 0, "largest |Floquet multiplier| over the converged points (> 1: unstable)"},
    {"unstable_points", 0, "converged points that are unstable"},
    {"converged_points", 0, "points that converged (of one per crossing of a requested speed)"},
    {"nbifurcations", 0, "bifurcations located along the branch"},
    {"nfolds", 0, "folds (turning points, jumps of a run-up)"},
    {"nperiod_doublings", 0, "period-doubling bifurcations"},
    {"nneimark_sacker", 0, "Neimark-Sacker bifurcations (onset of quasi-periodic motion)"},
    {"first_bifurcation_rpm", 0,
     "speed of the first bifurcation along the branch, rpm (nan: none)"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    per_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    o->harmonics = 10;
    o->subharmonic = 1;
    const char *outp = NULL;
    if (gd_study_read_sweep(r, map, "speeds", &o->speeds) ||
        gd_yread_str(r, map, "output", "analysis", NULL, 0, &outp, NULL, NULL) ||
        gd_yread_int(r, map, "harmonics", "analysis", 1, 1000, 0, &o->harmonics, NULL) ||
        gd_yread_int(r, map, "subharmonic", "analysis", 1, 1000, 0, &o->subharmonic, NULL) ||
        gd_yread_str(r, map, "method", "analysis", METHODS, 0, NULL, &o->method, NULL))
        return GD_EINPUT;
    if (outp) snprintf(o->output, sizeof o->output, "%s", outp);
    return GD_OK;
}

/* The output as a record of the transient problem. */
static gd_status record_of(const gd_system *sys, const per_opts *o, gd_tr_record *rec,
                           gd_error *err)
{
    memset(rec, 0, sizeof *rec);
    if (!o->output[0]) {
        if (sys->model->nmeshes == 0)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "analysis.output",
                                "give `output: NODE.DOF` for a model without a mesh",
                                "the model has no mesh whose force to follow");
        rec->kind = GD_REC_MESH_FORCE;
        return GD_OK;
    }
    gd_probe p;
    int dof;
    gd_status st = gd_study_probe(sys, o->output, &p, &dof, err);
    if (st) return st;
    if (p.element && p.element != &gd_element_mesh)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "analysis.output",
                            "use mesh:NAME or NODE.DOF",
                            "periodic follows a mesh force or a displacement, not '%s'", o->output);
    rec->kind = p.element ? GD_REC_MESH_FORCE : GD_REC_DISP;
    rec->index = p.element ? p.index : dof;
    return GD_OK;
}

static gd_status check(const gd_system *sys, const void *opts, gd_error *err)
{
    gd_tr_record rec;
    return record_of(sys, opts, &rec, err);
}

/* The value of request q over the result (NaN where nothing converged). */
static double output(const gd_periodic_result *r, gd_study_request q)
{
    double v = NAN;
    int count = 0;
    switch (q.def) {
    case NBIF:
    case NFOLD:
    case NPD:
    case NNS:
        for (int i = 0; i < r->nbifurcations; i++) {
            gd_bifurcation_type t = r->bifurcations[i].type;
            count += q.def == NBIF || (q.def == NFOLD && t == GD_BIF_FOLD) ||
                     (q.def == NPD && t == GD_BIF_PERIOD_DOUBLING) ||
                     (q.def == NNS && t == GD_BIF_NEIMARK_SACKER);
        }
        return count;
    case FIRST_BIF:
        return r->nbifurcations ? r->bifurcations[0].speed * 30 / PI : NAN;
    default:
        break;
    }
    int at = -1, unstable = 0;
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        if (!p->converged) continue;
        count++;
        unstable += p->stable == 0;
        double x = q.def == HARM_MAX ? (q.k <= p->harmonics ? p->records[0].amplitude[q.k] : NAN)
                   : q.def == MU_MAX ? p->mu_max
                                     : p->records[0].peak_to_peak;
        if (!isnan(x) && (isnan(v) || x > v)) v = x, at = i;
    }
    if (q.def == CONVERGED) return count;
    if (q.def == UNSTABLE) return unstable;
    if (q.def == P2P_RPM) return at >= 0 ? r->points[at].speed * 30 / PI : NAN;
    return v;
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    const per_opts *o = opts;
    gd_tr_record rec;
    gd_status st = record_of(in->sys, o, &rec, err);
    if (st) return st;
    double *sp = gd_study_sweep_values(&o->speeds);
    if (!sp) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    gd_periodic_options opt;
    gd_periodic_options_init(&opt);
    opt.harmonics = (int)o->harmonics;
    opt.subharmonic = (int)o->subharmonic;
    opt.method = o->method ? GD_PER_SEQUENTIAL : GD_PER_ARCLENGTH;
    gd_transient_model *tm = NULL;
    gd_periodic_result *r = NULL;
    st = gd_transient_model_build(in->sys, &tm, err);
    if (!st)
        st = gd_periodic_run(in->sys, &tm->spec, NULL, sp, (int)o->speeds.count, &opt, &rec, 1, &r,
                             err);
    for (int i = 0; !st && i < nreq; i++)
        values[i] = output(r, req[i]);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    free(sp);
    return st;
}

const gd_study_runner gd_study_periodic = {.name = "periodic",
                                           .keys = KEYS,
                                           .options = options,
                                           .check = check,
                                           .outputs = OUTPUTS,
                                           .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                           .run = run};
