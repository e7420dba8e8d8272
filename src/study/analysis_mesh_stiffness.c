/* Study analysis `mesh-stiffness` (geardyn/mesh_stiffness.h): contact ratios and the
 * time-varying mesh stiffness of one mesh's gear pair, read from the model file's
 * `geometry:` (as `geardyn mesh-stiffness` does). Options: mesh (name; default the
 * first with a geometry), method, points, slices. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/study_impl.h"

static const char *const KEYS[] = {"mesh", "method", "points", "slices", NULL};
static const char *const METHODS[] = {"energy", "iso6336", "single-pair-law", "square", NULL};

typedef struct ms_opts {
    char mesh[128];
    int has_method, method;
    long points, slices; /* 0: the file's */
} ms_opts;

enum { MEAN, MAX, MIN, P2P, CR_T, CR_F, CR_TOT, HARM, ISO };
static const gd_study_output_def OUTPUTS[] = {
    {"mean", 0, "mean mesh stiffness, N/m"},
    {"max", 0, "largest mesh stiffness, N/m"},
    {"min", 0, "smallest mesh stiffness, N/m"},
    {"peak_to_peak", 0, "max - min, N/m"},
    {"contact_ratio_transverse", 0, "transverse contact ratio"},
    {"contact_ratio_face", 0, "face (overlap) contact ratio"},
    {"contact_ratio_total", 0, "total contact ratio"},
    {"harmonic_amplitude", 1, "amplitude of the k-th mesh harmonic, N/m"},
    {"iso_mesh_stiffness", 0, "ISO 6336-1 c_gamma_alpha b, N/m"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    ms_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    if (!map) return GD_OK;
    const char *mesh = NULL;
    if (gd_yread_str(r, map, "mesh", "analysis", NULL, 0, &mesh, NULL, NULL) ||
        gd_yread_str(r, map, "method", "analysis", METHODS, 0, NULL, &o->method, &o->has_method) ||
        gd_yread_int(r, map, "points", "analysis", 8, 1000000, 0, &o->points, NULL) ||
        gd_yread_int(r, map, "slices", "analysis", 1, 100000, 0, &o->slices, NULL))
        return GD_EINPUT;
    if (mesh) snprintf(o->mesh, sizeof o->mesh, "%s", mesh);
    return GD_OK;
}

static const char *mesh_name(const void *opts)
{
    const ms_opts *o = opts;
    return o->mesh[0] ? o->mesh : NULL;
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    const ms_opts *o = opts;
    gd_tvms_options t = *in->tvms;
    if (o->has_method) t.method = (gd_tvms_method)o->method;
    if (o->points) t.points = (int)o->points;
    if (o->slices) t.slices = (int)o->slices;
    int nh = 0;
    for (int i = 0; i < nreq; i++)
        if (req[i].def == HARM && req[i].k > nh) nh = req[i].k;
    if (nh > t.harmonics) t.harmonics = nh;
    gd_tvms_result *res;
    gd_status st = gd_tvms_compute(in->geom, &t, &res, err);
    if (st) return st;
    for (int i = 0; i < nreq; i++) {
        double v = NAN;
        switch (req[i].def) {
        case MEAN:
            v = res->mean;
            break;
        case MAX:
            v = res->max;
            break;
        case MIN:
            v = res->min;
            break;
        case P2P:
            v = res->peak_to_peak;
            break;
        case CR_T:
            v = res->geom.contact_ratio_transverse;
            break;
        case CR_F:
            v = res->geom.contact_ratio_face;
            break;
        case CR_TOT:
            v = res->geom.contact_ratio_total;
            break;
        case HARM:
            v = gd_study_kth(res->harmonic_amplitude, res->harmonics, req[i].k);
            break;
        case ISO:
            v = res->iso_mesh_stiffness_alpha;
            break;
        }
        values[i] = v;
    }
    gd_tvms_free(res);
    return GD_OK;
}

const gd_study_runner gd_study_mesh_stiffness = {.name = "mesh-stiffness",
                                                 .gear_pair = 1,
                                                 .keys = KEYS,
                                                 .options = options,
                                                 .mesh_name = mesh_name,
                                                 .outputs = OUTPUTS,
                                                 .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                                 .run = run};
