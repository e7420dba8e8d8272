/* Study analysis `static` (geardyn/static.h): equilibrium under the mean loads, an
 * input torque and gravity, as `geardyn static` runs it (docs/static.md). Options:
 * torque (N m, default 0), input and hold (node names, defaults as the CLI), gravity
 * (default true). Outputs, per mesh k or bearing k in model order: the mesh force, its
 * misalignment f_sh and tilt in the plane of action, the radial bearing reaction; the
 * largest lateral deflection of any node, the first hold's reaction and the load-sharing
 * factor of each planetary set. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/static.h"
#include "study/study_impl.h"

static const char *const KEYS[] = {"torque", "input", "hold", "gravity", NULL};

typedef struct st_opts {
    double torque;
    int gravity;
    char input[GD_NODE_NAME_MAX], hold[GD_NODE_NAME_MAX];
} st_opts;

enum { MESH_FORCE, F_SH, TILT, BEARING, MAX_DEFLECTION, HOLD, LOAD_SHARING };
static const gd_study_output_def OUTPUTS[] = {
    {"mesh_force", 1, "normal force of mesh k, N"},
    {"f_sh", 1, "misalignment of mesh k from the deformations (face width x tilt), m"},
    {"tilt_in_plane", 1, "relative tilt of mesh k's gears in the plane of action, rad"},
    {"bearing_force", 1, "radial reaction |(Fx, Fy)| of bearing k, N"},
    {"max_deflection", 0, "largest lateral deflection |(x, y)| of any node, m"},
    {"hold_reaction", 0, "reaction of the first held DOF (motor or output torque), N m"},
    {"load_sharing", 1, "load-sharing factor K_gamma of planetary set k (docs/planetary.md)"},
};

static gd_status options(gd_yreader *r, const gd_ynode *map, void **out)
{
    st_opts *o = calloc(1, sizeof *o);
    if (!(*out = o)) return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
    const char *in = NULL, *hold = NULL;
    int has_g = 0;
    if (gd_yread_qty(r, map, "torque", "analysis", GD_QTY_TORQUE, 0, &o->torque, NULL) ||
        gd_yread_str(r, map, "input", "analysis", NULL, 0, &in, NULL, NULL) ||
        gd_yread_str(r, map, "hold", "analysis", NULL, 0, &hold, NULL, NULL) ||
        gd_yread_bool(r, map, "gravity", "analysis", 0, &o->gravity, &has_g))
        return GD_EINPUT;
    if (!has_g) o->gravity = 1;
    snprintf(o->input, sizeof o->input, "%s", in ? in : "");
    snprintf(o->hold, sizeof o->hold, "%s", hold ? hold : "");
    return GD_OK;
}

/* opt from o on sys's model: GD_EINPUT for a node name it does not have. */
static gd_status make(const gd_system *sys, const st_opts *o, gd_static_options *opt, gd_error *err)
{
    gd_static_options_init(opt);
    opt->input_torque = o->torque;
    opt->gravity = o->gravity;
    const char *names[2] = {o->input, o->hold}, *keys[2] = {"analysis.input", "analysis.hold"};
    int *nodes[2] = {&opt->input_node, &opt->hold_node};
    for (int i = 0; i < 2; i++) {
        if (!names[i][0]) continue;
        *nodes[i] = gd_model_find_node(sys->model, names[i]);
        if (*nodes[i] < 0)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, keys[i],
                                "give the name of one of the model's nodes", "no node named '%s'",
                                names[i]);
    }
    return GD_OK;
}

static gd_status check(const gd_system *sys, const void *opts, gd_error *err)
{
    gd_static_options opt;
    return make(sys, opts, &opt, err);
}

static gd_status run(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err)
{
    gd_static_options opt;
    gd_static_result *r;
    gd_status st = make(in->sys, opts, &opt, err);
    if (st || (st = gd_static_run(in->sys, &opt, &r, err))) return st;
    double dmax = 0;
    for (int p = 0; p < r->nnodes; p++)
        dmax = fmax(dmax, hypot(r->u[p * GD_NODE_DOFS + GD_X], r->u[p * GD_NODE_DOFS + GD_Y]));
    for (int i = 0; i < nreq; i++) {
        int k = req[i].k - 1, mk = k >= 0 && k < r->nmeshes, bk = k >= 0 && k < r->nbearings;
        switch (req[i].def) {
        case MESH_FORCE:
            values[i] = mk ? r->meshes[k].force : NAN;
            break;
        case F_SH:
            values[i] = mk ? r->meshes[k].f_sh : NAN;
            break;
        case TILT:
            values[i] = mk ? r->meshes[k].tilt_in_plane : NAN;
            break;
        case BEARING:
            values[i] = bk ? hypot(r->bearings[k].force[0], r->bearings[k].force[1]) : NAN;
            break;
        case MAX_DEFLECTION:
            values[i] = dmax;
            break;
        case LOAD_SHARING: {
            gd_static_planetary_loads pl;
            values[i] = k >= 0 && k < in->sys->model->nplanetary &&
                                !gd_static_planetary(in->sys, r, k, &pl, NULL)
                            ? pl.load_sharing
                            : NAN;
            break;
        }
        default:
            values[i] = r->nholds > 0 ? r->holds[0].reaction : NAN;
            break;
        }
    }
    gd_static_free(r);
    return GD_OK;
}

const gd_study_runner gd_study_static = {.name = "static",
                                         .keys = KEYS,
                                         .options = options,
                                         .check = check,
                                         .outputs = OUTPUTS,
                                         .noutputs = sizeof OUTPUTS / sizeof OUTPUTS[0],
                                         .run = run};
