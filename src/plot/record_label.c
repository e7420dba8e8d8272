/* The label, quantity and unit of a record of the transient problem (time histories of
 * gd_plot_transient, one-period statistics of gd_plot_periodic). */
#include "plot/plot_impl.h"

void pl_record_describe(const gd_system *sys, const gd_tr_record *rec, char *name, size_t n,
                        const char **quantity, const char **unit)
{
    const gd_model *m = sys->model;
    char dof[120] = "";
    int is_dof = rec->kind <= GD_REC_SPEED_RATIO;
    if (is_dof && rec->index >= 0 && rec->index < sys->ndof)
        gd_system_dof_label(sys, rec->index, dof, sizeof dof);
    int rot =
        is_dof && rec->index >= 0 && rec->index < sys->ndof && sys->dof_type[rec->index] >= GD_RX;
    const char *mesh = rec->kind >= GD_REC_MESH_FORCE && rec->kind <= GD_REC_MESH_STIFFNESS &&
                               rec->index >= 0 && rec->index < m->nmeshes
                           ? m->meshes[rec->index].name
                           : "";
    switch (rec->kind) {
    case GD_REC_DISP:
        *quantity = "displacement", *unit = rot ? "rad" : "m";
        snprintf(name, n, "%s", dof);
        break;
    case GD_REC_VEL:
        *quantity = "velocity", *unit = rot ? "rad/s" : "m/s";
        snprintf(name, n, "%s velocity", dof);
        break;
    case GD_REC_ANGLE:
        *quantity = "total angle", *unit = "rad";
        snprintf(name, n, "%s angle", dof);
        break;
    case GD_REC_SPEED:
        *quantity = "total speed", *unit = "rad/s";
        snprintf(name, n, "%s speed", dof);
        break;
    case GD_REC_SPEED_RATIO: {
        char d2[120] = "";
        if (rec->index2 >= 0 && rec->index2 < sys->ndof)
            gd_system_dof_label(sys, rec->index2, d2, sizeof d2);
        *quantity = "speed ratio", *unit = "-";
        snprintf(name, n, "%s / %s", dof, d2);
        break;
    }
    case GD_REC_MESH_FORCE:
        *quantity = "mesh force", *unit = "N";
        snprintf(name, n, "%s force", mesh);
        break;
    case GD_REC_MESH_DEFLECTION:
        *quantity = "mesh deflection", *unit = "m";
        snprintf(name, n, "%s deflection", mesh);
        break;
    case GD_REC_MESH_STATE:
        *quantity = "contact state (1 drive flank, 0 separated, -1 coast flank)", *unit = "-";
        snprintf(name, n, "%s contact", mesh);
        break;
    case GD_REC_MESH_STIFFNESS:
        *quantity = "mesh stiffness", *unit = "N/m";
        snprintf(name, n, "%s stiffness", mesh);
        break;
    case GD_REC_SFD_FX:
    case GD_REC_SFD_FY:
        *quantity = "damper force", *unit = "N";
        snprintf(name, n, "damper %d %s", rec->index, rec->kind == GD_REC_SFD_FX ? "Fx" : "Fy");
        break;
    case GD_REC_LAW: {
        /* a law of the model's `laws:` list and one of its type's records */
        const gd_model_law *L =
            rec->index >= 0 && rec->index < m->nlaws ? &m->laws[rec->index] : NULL;
        const gd_law_record *r = L && rec->index2 >= 0 && rec->index2 < L->type->nrecords
                                     ? &L->type->records[rec->index2]
                                     : NULL;
        *quantity = r ? r->name : "law record", *unit = r ? r->unit : "";
        snprintf(name, n, "%s %s", L ? L->name : "law", r ? r->name : "");
        break;
    }
    default:
        *quantity = "damper eccentricity", *unit = "e/c";
        snprintf(name, n, "damper %d eccentricity", rec->index);
    }
}
