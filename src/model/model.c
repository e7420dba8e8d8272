/* Model queries and edits that do not involve parsing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/mesh_stiffness.h"
#include "geardyn/model.h"
#include "model/build_impl.h"

const char *const gd_dof_names[GD_NODE_DOFS] = {"x", "y", "z", "rx", "ry", "rz"};
const char *const gd_coupling_names[3] = {"torsional", "lateral-torsional", "full"};

unsigned gd_coupling_dof_mask(gd_coupling level)
{
    switch (level) {
    case GD_COUPLING_TORSIONAL:
        return GD_DOF_BIT(GD_RZ);
    case GD_COUPLING_LATERAL_TORSIONAL:
        return GD_DOFS_ALL & ~GD_DOF_BIT(GD_Z);
    case GD_COUPLING_FULL:
        return GD_DOFS_ALL;
    }
    return GD_DOFS_ALL;
}

void gd_model_set_coupling(gd_model *model, gd_coupling level)
{
    for (int i = 0; i < model->nmeshes; i++)
        model->meshes[i].coupling = level;
}

gd_status gd_model_restrict_dofs(gd_model *model, unsigned dof_mask, gd_error *err)
{
    unsigned keep = model->dof_mask & dof_mask;
    if (!keep) {
        char have[64] = "";
        for (int k = 0; k < GD_NODE_DOFS; k++)
            if (model->dof_mask & GD_DOF_BIT(k))
                snprintf(have + strlen(have), sizeof have - strlen(have), "%s%s",
                         have[0] ? "," : "", gd_dof_names[k]);
        return gd_error_set(err, GD_EINPUT, model->file, 0, 0, "--dofs",
                            "list some of the model's DOFs",
                            "none of these DOFs is active (the "
                            "model has %s)",
                            have);
    }
    model->dof_mask = keep;
    return GD_OK;
}

void gd_model_free(gd_model *model)
{
    if (!model) return;
    gd_model_build_free(model);
    for (int i = 0; i < model->nshafts; i++)
        free(model->shafts[i].sections);
    for (int i = 0; i < model->nbearings; i++) {
        free(model->bearings[i].table_speed);
        free(model->bearings[i].table);
    }
    free(model->materials);
    free(model->shafts);
    free(model->nodes);
    free(model->elements);
    free(model->disks);
    free(model->bearings);
    free(model->springs);
    for (int i = 0; i < model->nmeshes; i++) {
        gd_tvms_free(model->meshes[i].tvms);
        gd_table_free(model->meshes[i].dyn.tvms);
        gd_table_free(model->meshes[i].dyn.ste);
    }
    for (int i = 0; i < model->nexcitations; i++)
        gd_table_free((gd_table *)model->excitations[i].law.table);
    for (int i = 0; i < model->nprescribed; i++)
        gd_table_free((gd_table *)model->prescribed[i].law.table);
    for (int i = 0; i < model->ncams; i++) {
        gd_table_free((gd_table *)model->cams[i].lift.table);
        free(model->cams[i].valve_mass);
        free(model->cams[i].valve_phase);
    }
    free(model->excitations);
    free(model->prescribed);
    free(model->cams);
    free(model->laws);
    for (int i = 0; i < model->nplanetary; i++)
        free(model->planetary[i].planet_angle), free(model->planetary[i].pin_error),
            free(model->planetary[i].pin_error_radial), free(model->planetary[i].instance_name);
    free(model->planetary);
    free(model->meshes);
    free(model->unbalances);
    free(model);
}

double gd_mesh_linear_damping(const gd_mesh *mesh)
{
    return mesh->damping + mesh->dyn.damping_per_stiffness * mesh->stiffness;
}

int gd_model_find_node(const gd_model *model, const char *name)
{
    for (int i = 0; i < model->nnodes; i++)
        if (!strcmp(model->nodes[i].name, name)) return i;
    return -1;
}

int gd_model_find_shaft(const gd_model *model, const char *name)
{
    for (int i = 0; i < model->nshafts; i++)
        if (!strcmp(model->shafts[i].name, name)) return i;
    return -1;
}

int gd_model_find_mesh(const gd_model *model, const char *name)
{
    for (int i = 0; i < model->nmeshes; i++)
        if (!strcmp(model->meshes[i].name, name)) return i;
    return -1;
}

void gd_model_shaft_summary(const gd_model *model, int shaft, gd_shaft_summary *out)
{
    memset(out, 0, sizeof *out);
    const gd_shaft *s = &model->shafts[shaft];
    out->nnodes = s->nnodes;
    for (int e = 0; e < model->nelements; e++) {
        const gd_element *el = &model->elements[e];
        if (el->shaft != shaft) continue;
        const gd_material *mat = &model->materials[el->material];
        double ro = 0.5 * el->outer_diameter, ri = 0.5 * el->inner_diameter;
        double area = 3.14159265358979323846 * (ro * ro - ri * ri);
        double m = mat->density * area * el->length;
        out->mass += m;
        out->polar_inertia += 0.5 * m * (ro * ro + ri * ri);
        out->length += el->length;
        out->nelements++;
    }
    for (int d = 0; d < model->ndisks; d++) {
        const gd_disk *dk = &model->disks[d];
        if (model->nodes[dk->node].shaft != shaft) continue;
        out->mass += dk->mass;
        out->polar_inertia += dk->polar_inertia;
    }
}
