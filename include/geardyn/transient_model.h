/* A transient problem description (gd_transient_spec) made from a model's time-
 * integration data (docs/transient.md, docs/model-format.md): mesh laws (TVMS tables or
 * `stiffness: {from: geometry}`, static transmission error, backlash, damping
 * proportional to the stiffness, damping while separated), squeeze film dampers,
 * applied loads, prescribed motions, cam inertial torques and the unbalance flag.
 *
 * The spec and the arrays it points to are owned by the gd_transient_model; the tables
 * it points to are the model's (borrowed: the model must outlive it), except the TVMS
 * tables made here from `stiffness: {from: geometry}` results, which it owns.
 *
 * Ownership and threads: gd_transient_model_build returns an object the caller frees
 * with gd_transient_model_free; it reads the system and model only, so builds from one
 * system may run concurrently.
 */
#ifndef GEARDYN_TRANSIENT_MODEL_H
#define GEARDYN_TRANSIENT_MODEL_H
#include "geardyn/export.h"
#include "geardyn/system.h"
#include "geardyn/transient.h"

typedef struct gd_transient_model {
    gd_transient_spec spec; /* ready for gd_transient_new */
    gd_tr_mesh *meshes;     /* spec.nmeshes */
    gd_tr_sfd *sfds;
    gd_tr_load *loads;
    gd_tr_prescribed *prescribed;
    gd_tr_cam *cams;  /* one per valve */
    gd_law *laws;     /* spec.nlaws: the model's laws, in its order */
    int *sfd_bearing; /* spec.nsfds: model bearing index of each damper */
    int *cam_of;      /* spec.ncams: model cam index of each valve train */
    int nowned;       /* tables made here */
    gd_table **owned;
} gd_transient_model;

/* Builds the spec from sys->model. A mesh enters the spec when it has any law beyond
 * its constant stiffness and damping (a TVMS table or a geometry TVMS, an STE table,
 * backlash, damping per stiffness or while separated); the others stay linear in K and
 * C. Errors (GD_EINPUT, naming the model file, line and entry): an excitation,
 * prescription or cam on a DOF that is not active, a damper on a node without x and y,
 * a cam without a lift table, a table law without its table. */
GD_API gd_status gd_transient_model_build(const gd_system *sys, gd_transient_model **out,
                                          gd_error *err);
GD_API void gd_transient_model_free(gd_transient_model *tm);

/* Index in tm->spec.meshes of model mesh `mesh`, or -1 when it stays linear. */
GD_API int gd_transient_model_mesh_index(const gd_transient_model *tm, int mesh);
/* Index in tm->spec.sfds of the damper of model bearing `bearing`, or -1. */
GD_API int gd_transient_model_sfd_index(const gd_transient_model *tm, int bearing);

#endif
