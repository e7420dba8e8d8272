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
    for (int i = 0; i < model->nplanetary; i++) {
        gd_planetary *g = &model->planetary[i];
        free(g->planet_angle), free(g->pin_error), free(g->pin_error_radial);
        free(g->instance_name);
        for (int k = 0; k < 2; k++) {
            gd_table_free(g->mesh_law[k].tvms);
            free(g->mesh_phase[k]);
            gd_tvms_free(g->tvms[k]);
        }
    }
    free(model->planetary);
    free(model->idlers);
    free(model->synchronisers);
    free(model->gears);
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

int gd_model_mesh_count(const gd_model *model)
{
    int n = model->nmeshes;
    for (int s = 0; s < model->nplanetary; s++)
        n += 2 * model->planetary[s].nplanets;
    return n;
}

int gd_model_planetary_mesh(const gd_model *model, int i, int *set, int *ring, int *planet)
{
    if (i < model->nmeshes) return 0;
    i -= model->nmeshes;
    for (int s = 0; s < model->nplanetary; s++) {
        int N = model->planetary[s].nplanets;
        if (i < 2 * N) {
            if (set) *set = s;
            if (ring) *ring = i / N;
            if (planet) *planet = i % N;
            return 1;
        }
        i -= 2 * N;
    }
    return 0;
}

const char *gd_model_mesh_name(const gd_model *model, int i)
{
    int s, ring, n;
    if (i >= 0 && i < model->nmeshes) return model->meshes[i].name;
    if (i < 0 || !gd_model_planetary_mesh(model, i, &s, &ring, &n)) return "";
    const gd_planetary *g = &model->planetary[s];
    return g->instance_name[3 + (1 + ring) * g->nplanets + n]; /* the element's order */
}

int gd_model_idler_of_node(const gd_model *model, int node)
{
    for (int i = 0; i < model->nidlers; i++)
        if (model->idlers[i].node == node) return i;
    return -1;
}

void gd_model_shaft_order_label(const gd_model *model, int s, char *buf, int cap)
{
    const gd_shaft *sh = &model->shafts[s];
    int idler = sh->nnodes == 1 ? gd_model_idler_of_node(model, sh->first_node) : -1;
    if (idler < 0) {
        snprintf(buf, (size_t)cap, "1x %.80s", sh->name);
        return;
    }
    /* an idler's 1x is named from its meshes: "1x idler gear3" (issue 37: not a shaft) */
    int n = snprintf(buf, (size_t)cap, "1x idler");
    int nm = 0;
    for (int k = 0; k < model->nmeshes && n < cap; k++) {
        const gd_mesh *g = &model->meshes[k];
        if (g->driver != sh->first_node && g->driven != sh->first_node) continue;
        n += snprintf(buf + n, (size_t)(cap - n), "%s%.40s", nm++ ? "+" : " ", g->name);
    }
    if (!nm && n < cap) snprintf(buf + n, (size_t)(cap - n), " %.60s", sh->name);
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
    /* a planetary set's members and planets carry their mass on their nodes (the
       element's M, src/elements/planetary.c): a planet or ring housing is no 0 kg shaft */
    for (int k = 0; k < model->nplanetary; k++) {
        const gd_planetary *g = &model->planetary[k];
        for (int b = 0; b < GD_PLANETARY_NMEMBERS; b++) {
            int node = g->member[b].node;
            if (node < 0 || node >= model->nnodes || model->nodes[node].shaft != shaft) continue;
            out->mass += g->member[b].mass;
            out->polar_inertia += g->member[b].inertia;
        }
        for (int p = 0; p < g->nplanets; p++) {
            int node = g->first_planet + p;
            if (node < 0 || node >= model->nnodes || model->nodes[node].shaft != shaft) continue;
            out->mass += g->planet_mass;
            out->polar_inertia += g->planet_inertia;
        }
    }
}
