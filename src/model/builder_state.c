/* The teardown of a model's build state (m->build: the names, paths and tables kept
 * while the model is built, freed by gd_model_finish and gd_model_free). It uses
 * nothing of the builder, so the model (model.c) frees it without depending on the
 * builder's files. */
#include <stdlib.h>

#include "model/build_impl.h"

void gd_build_free_shaft(gd_bshaft *bs, int nsections)
{
    free(bs->path);
    free(bs->material);
    for (int j = 0; j < nsections && bs->section_material; j++)
        free(bs->section_material[j]);
    free(bs->section_material);
    for (int j = 0; j < bs->nstations; j++) {
        free(bs->stations[j].name);
        free(bs->stations[j].path);
    }
    free(bs->stations);
}

static void free_table(gd_btable *t)
{
    free(t->x);
    free(t->y);
}

static void free_items(gd_bitem *items, int n)
{
    for (int i = 0; i < n && items; i++) {
        free(items[i].path);
        free(items[i].node);
        free(items[i].node2);
        free(items[i].material);
    }
    free(items);
}

void gd_model_build_free(gd_model *m)
{
    gd_model_build *b = m->build;
    if (!b) return;
    for (int i = 0; i < m->nmaterials && b->material_path; i++)
        free(b->material_path[i]);
    free(b->material_path);
    for (int i = 0; i < m->nshafts && b->shafts; i++)
        gd_build_free_shaft(&b->shafts[i], m->shafts[i].nsections);
    free(b->shafts);
    free_items(b->disks, m->ndisks);
    free_items(b->bearings, m->nbearings);
    free_items(b->springs, m->nsprings);
    free_items(b->unbalances, m->nunbalances);
    free_items(b->excitations, m->nexcitations);
    free_items(b->prescribed, m->nprescribed);
    free_items(b->cams, m->ncams);
    free_items(b->laws, m->nlaws);
    for (int i = 0; i < m->nmeshes && b->meshes; i++) {
        gd_bmesh *g = &b->meshes[i];
        free(g->path);
        free(g->driver);
        free(g->driven);
        free_table(&g->tvms);
        free_table(&g->ste);
    }
    free(b->meshes);
    for (int i = 0; i < m->nplanetary && b->planetary; i++) {
        free(b->planetary[i].path);
        for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++)
            free(b->planetary[i].node[j]);
    }
    free(b->planetary);
    for (int i = 0; i < m->nidlers && b->idlers; i++) {
        free(b->idlers[i].path);
        free(b->idlers[i].on);
    }
    free(b->idlers);
    for (int k = 0; k < m->nsynchronisers && b->syncs; k++) {
        free(b->syncs[k].path);
        free(b->syncs[k].node);
        free(b->syncs[k].idlers[0]);
        free(b->syncs[k].idlers[1]);
        free(b->syncs[k].engaged);
    }
    free(b->syncs);
    for (int i = 0; i < m->ngears && b->gears; i++) {
        free(b->gears[i].path);
        free(b->gears[i].idler);
    }
    free(b->gears);
    for (int i = 0; i < m->nexcitations && b->excitation_tables; i++)
        free_table(&b->excitation_tables[i]);
    for (int i = 0; i < m->nprescribed && b->prescribed_tables; i++)
        free_table(&b->prescribed_tables[i]);
    for (int i = 0; i < m->ncams && b->cam_tables; i++)
        free_table(&b->cam_tables[i]);
    free(b->excitation_tables);
    free(b->prescribed_tables);
    free(b->cam_tables);
    free(b->reference_shaft);
    free(b);
    m->build = NULL;
}
