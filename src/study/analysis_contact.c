/* Study analysis `contact` (geardyn/mesh_stiffness.h, gd_ltca_compute): the loaded tooth
 * contact analysis of one mesh's gear pair at one driver torque, as `geardyn
 * mesh-stiffness MODEL --load T` gives it. The gear pair, its micro-geometry and the
 * stiffness options come from the model file (each case's --set applies), so a study
 * sweeps the tip relief under meshes.NAME.geometry.driver.modifications and the load
 * under meshes.NAME.stiffness.load. Options: mesh (default the first with a geometry),
 * load and misalignment (default the file's `stiffness:`), method, points, slices. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/study_impl.h"

static const char *const KEYS[] = {"mesh",   "load", "misalignment", "method", "points",
                                   "slices", NULL};
static const char *const METHODS[] = {"energy", "iso6336", "single-pair-law", "square", NULL};

typedef struct contact_opts {
    char mesh[128];
    int has_method, method;
    int has_load, has_misalignment;
    double load, misalignment; /* N m, m */
    long points, slices;       /* 0: the file's */
} contact_opts;

enum { TE_P2P, TE_MEAN, TE_UNLOADED_P2P, K_MEAN, K_MIN, K_MAX, KHB, FORCE, TORQUE, FLAGGED };
static const gd_study_output_def OUTPUTS[] = {
    {"te_p2p", 0, "loaded transmission error, peak-to-peak over a mesh cycle, m"},
    {"te_mean", 0, "loaded transmission error, mean over a mesh cycle, m"},
    {"te_unloaded_p2p", 0, "no-load transmission error (micro-geometry), peak-to-peak, m"},
    {"k_mean", 0, "mesh stiffness at the load (dF/d delta), mean over a mesh cycle, N/m"},
    {"k_min", 0, "smallest mesh stiffness at the load, N/m"},
    {"k_max", 0, "largest mesh stiffness at the load, N/m"},
    {"face_load_factor", 0, "K_Hbeta: largest cycle-mean line load / (F / b)"},
    {"force", 0, "normal load T / (r_b1 cos beta_b), N"},
    {"torque", 0, "driver torque of the case, N m"},
    {"flagged", 0, "positions with a flag (partial face, edge contact, no contact)"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    contact_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    if (!map) return GD_OK;
    const char *mesh = NULL;
    if (gd_yread_str(r, map, "mesh", "analysis", NULL, 0, &mesh, NULL, NULL) ||
        gd_yread_qty(r, map, "load", "analysis", GD_QTY_TORQUE, GD_YPOS, &o->load, &o->has_load) ||
        gd_yread_qty(r, map, "misalignment", "analysis", GD_QTY_LENGTH, 0, &o->misalignment,
                     &o->has_misalignment) ||
        gd_yread_str(r, map, "method", "analysis", METHODS, 0, NULL, &o->method, &o->has_method) ||
        gd_yread_int(r, map, "points", "analysis", 8, 1000000, 0, &o->points, NULL) ||
        gd_yread_int(r, map, "slices", "analysis", 1, 100000, 0, &o->slices, NULL))
        return GD_EINPUT;
    if (o->has_method && o->method == GD_TVMS_ISO6336)
        return gd_yfail(r, gd_ymap_get(map, "method"), "analysis",
                        "use energy (default), single-pair-law or square",
                        "the contact analysis needs a stiffness law along the contact (iso6336 "
                        "gives one constant)");
    if (mesh) snprintf(o->mesh, sizeof o->mesh, "%s", mesh);
    return GD_OK;
}

static const char *mesh_name(const void *opts)
{
    const contact_opts *o = opts;
    return o->mesh[0] ? o->mesh : NULL;
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    const contact_opts *o = opts;
    gd_tvms_options t = *in->tvms;
    if (o->has_method) t.method = (gd_tvms_method)o->method;
    if (o->points) t.points = (int)o->points;
    if (o->slices) t.slices = (int)o->slices;
    /* the analysis's load wins over the file's; one of the two is needed */
    if (o->has_load) t.load_torque = o->load;
    if (o->has_misalignment) t.misalignment = o->misalignment;
    if (!(t.load_torque > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "analysis.load",
                            "give `load: <driver torque>` in the analysis, or `stiffness: {from: "
                            "contact_analysis, load: ...}` in the mesh",
                            "the contact analysis needs a load (driver torque)");
    gd_ltca_result *res;
    gd_status st = gd_ltca_compute(in->geom, &t, &res, err);
    if (st) return st;
    double umin = INFINITY, umax = -INFINITY;
    for (size_t i = 0; i < res->points; i++) {
        umin = fmin(umin, res->ste_unloaded[i]);
        umax = fmax(umax, res->ste_unloaded[i]);
    }
    for (int i = 0; i < nreq; i++) {
        double v = NAN;
        switch (req[i].def) {
        case TE_P2P:
            v = res->ste_peak_to_peak;
            break;
        case TE_MEAN:
            v = res->ste_mean;
            break;
        case TE_UNLOADED_P2P:
            v = umax - umin;
            break;
        case K_MEAN:
            v = res->stiffness_mean;
            break;
        case K_MIN:
            v = res->stiffness_min;
            break;
        case K_MAX:
            v = res->stiffness_max;
            break;
        case KHB:
            v = res->face_load_factor_cycle;
            break;
        case FORCE:
            v = res->force;
            break;
        case TORQUE:
            v = res->torque;
            break;
        case FLAGGED:
            v = res->flagged;
            break;
        }
        values[i] = v;
    }
    gd_ltca_free(res);
    return GD_OK;
}

const gd_study_runner gd_study_contact = {.name = "contact",
                                          .gear_pair = 1,
                                          .keys = KEYS,
                                          .options = options,
                                          .mesh_name = mesh_name,
                                          .outputs = OUTPUTS,
                                          .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                          .run = run};
