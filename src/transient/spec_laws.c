/* The laws of a transient spec as registry instances (gd_transient_spec_laws): the
 * meshes, dampers and loads of the typed spec made into gd_law_backlash_mesh, gd_law_sfd
 * and gd_law_load instances, then the spec's own laws, then its cams (gd_law_cam_torque,
 * one per valve), each with its nominal rates at the reference speed. The one place
 * where a spec becomes the list every solver loops over. */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/model.h"
#include "elements/elements_impl.h"
#include "geardyn/transient.h"

static double dof_rate(const gd_system *sys, int dof, double speed)
{
    if (dof < 0 || sys->dof_type[dof] != GD_RZ) return 0.0;
    const gd_model *m = sys->model;
    return m->shafts[m->nodes[sys->dof_node[dof]].shaft].speed_ratio * speed;
}

/* A planetary set's mesh n (docs/planetary.md, "Meshes as laws"): the set's mesh vector
 * (gd_planetary_mesh_vector: the member's and the planet's x, y, rz), its assembled
 * k a a^T and c a a^T, the tables read at the sun's nominal angle relative to the carrier
 * (no driver DOF: the mesh's parametric excitation follows the nominal motion) delayed by
 * the planet's phase ([ParkerLin2004]). */
static void planetary_mesh_law(const gd_system *sys, const gd_tr_mesh *s, double speed, gd_law *L,
                               gd_mesh_law_data *m)
{
    const gd_model *model = sys->model;
    int set, ring, n;
    gd_model_planetary_mesh(model, s->mesh, &set, &ring, &n);
    const gd_planetary *g = &model->planetary[set];
    gd_law_init(L, &gd_law_backlash_mesh, gd_model_mesh_name(model, s->mesh));
    double a[12];
    gd_planetary_mesh_vector(g, ring, n, a);
    m->na = 0;
    for (int k = 0; k < 12; k++) {
        int node = k < 6 ? g->member[ring ? GD_PLANETARY_RING : GD_PLANETARY_SUN].node
                         : g->first_planet + n;
        int dof = gd_system_dof(sys, node, (gd_dof)(k % 6));
        if (a[k] == 0.0 || dof < 0) continue;
        L->dof[m->na] = dof;
        m->a[m->na++] = a[k];
    }
    L->ndofs = m->na > 0 ? m->na : 1;
    if (m->na == 0) L->dof[0] = -1;
    const gd_shaft *sh = model->shafts;
    double rel = sh[model->nodes[g->member[GD_PLANETARY_SUN].node].shaft].speed_ratio -
                 sh[model->nodes[g->member[GD_PLANETARY_CARRIER].node].shaft].speed_ratio;
    m->drv = -1;
    m->angle_fixed = 1;
    m->sense = rel >= 0 ? 1 : -1;
    m->drv_ratio = rel;
    m->drv_rate = rel * speed;
    m->tvms = s->tvms;
    m->ste = s->ste;
    m->stiffness = s->stiffness;
    m->coast_scale = s->coast_scale >= 0 ? s->coast_scale : 1.0;
    m->damping = s->damping;
    m->damping_per_k = s->damping_per_k;
    m->damping_free = s->damping_free;
    m->backlash = s->backlash;
    m->gap = s->gap;
    /* planet n meets its tooth gamma mesh periods late: k_n(t) = k(t - gamma T) */
    double period = g->teeth[0] > 0 ? 2 * M_PI / g->teeth[0] : 0.0;
    m->angle_offset = s->angle_offset - gd_planetary_mesh_phase(g, ring, n, m->sense) * period;
    m->k_lin = g->mesh_stiffness[ring];
    m->c_lin = g->mesh_damping[ring];
    L->data = m;
    L->mode = GD_CONTACT_DRIVE;
}

/* The mesh law's data of spec mesh s (its mesh vector, driver, assembled linear part). */
static void mesh_law(const gd_system *sys, const gd_transient_spec *spec, const gd_tr_mesh *s,
                     double speed, gd_law *L, gd_mesh_law_data *m)
{
    const gd_model *model = sys->model;
    if (s->mesh >= model->nmeshes) {
        planetary_mesh_law(sys, s, speed, L, m);
        return;
    }
    const gd_mesh *gm = &model->meshes[s->mesh];
    gd_law_init(L, &gd_law_backlash_mesh, gm->name);
    m->tvms = s->tvms;
    m->ste = s->ste;
    m->stiffness = s->stiffness;
    m->coast_scale = s->coast_scale >= 0 ? s->coast_scale : 1.0; /* 0: one-sided */
    m->damping = s->damping;
    m->damping_per_k = s->damping_per_k;
    m->damping_free = s->damping_free;
    m->backlash = s->backlash;
    m->gap = s->gap;
    m->angle_offset = s->angle_offset;
    gd_mesh_vector a;
    gd_system_mesh_vector(sys, s->mesh, &a);
    m->na = a.n;
    for (int j = 0; j < a.n; j++) {
        L->dof[j] = a.dof[j];
        m->a[j] = a.a[j];
    }
    L->ndofs = a.n;
    int drv = gd_system_dof(sys, gm->driver, GD_RZ);
    m->drv = -1;
    for (int j = 0; drv >= 0 && j < a.n; j++)
        if (a.dof[j] == drv) m->drv = j;
    if (drv >= 0 && m->drv < 0 && a.n < GD_LAW_MAX_DOFS) {
        m->drv = a.n;
        L->dof[L->ndofs++] = drv;
    }
    if (L->ndofs == 0) L->ndofs = 1; /* a mesh on absent DOFs: one absent DOF */
    m->drv_ratio = model->shafts[model->nodes[gm->driver].shaft].speed_ratio;
    m->drv_rate = m->drv_ratio * speed;
    m->sense = gm->driver_sense >= 0 ? 1 : -1;
    m->k_lin = gm->stiffness;
    m->c_lin = gd_mesh_linear_damping(gm); /* what the system assembled */
    m->angle_fixed = drv < 0;
    for (int i = 0; i < spec->nprescribed; i++)
        if (spec->prescribed[i].dof == drv) m->angle_fixed = 1;
    L->data = m;
    L->mode = GD_CONTACT_DRIVE;
}

gd_status gd_transient_spec_laws(const gd_system *sys, const gd_transient_spec *spec, double speed,
                                 gd_law **out, int *n, gd_error *err)
{
    *out = NULL;
    *n = 0;
    int total = spec->nmeshes + spec->nsfds + spec->nloads + spec->nlaws + spec->ncams;
    if (spec->nlaws < 0 || (spec->nlaws && !spec->laws))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "laws", "", "laws missing");
    for (int i = 0; i < spec->nmeshes; i++)
        if (spec->meshes[i].mesh < 0 || spec->meshes[i].mesh >= gd_model_mesh_count(sys->model))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "meshes", "", "no such mesh");
    for (int i = 0; i < spec->ncams; i++)
        if (spec->cams[i].dof < 0 || spec->cams[i].dof >= sys->ndof || !spec->cams[i].law)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "cams", "",
                                "cam on no DOF, or lift law missing");
    if (total == 0) return GD_OK;
    /* the meshes' data after the instances, in the same block (one free) */
    gd_law *L =
        calloc((size_t)total * sizeof *L + (size_t)spec->nmeshes * sizeof(gd_mesh_law_data), 1);
    if (!L) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    gd_mesh_law_data *md = (gd_mesh_law_data *)(void *)(L + total);
    int k = 0;
    for (int i = 0; i < spec->nmeshes; i++, k++)
        mesh_law(sys, spec, &spec->meshes[i], speed, &L[k], &md[i]);
    for (int i = 0; i < spec->nsfds; i++, k++) {
        const gd_tr_sfd *s = &spec->sfds[i];
        char name[GD_LAW_NAME_MAX];
        snprintf(name, sizeof name, "sfds[%d]", i);
        gd_law_init(&L[k], &gd_law_sfd, name);
        gd_sfd_law_values(&s->params, &L[k]);
        L[k].dof[0] = gd_system_dof(sys, s->node, GD_X);
        L[k].dof[1] = gd_system_dof(sys, s->node, GD_Y);
        L[k].dof[2] = s->node2 >= 0 ? gd_system_dof(sys, s->node2, GD_X) : -1;
        L[k].dof[3] = s->node2 >= 0 ? gd_system_dof(sys, s->node2, GD_Y) : -1;
    }
    for (int i = 0; i < spec->nloads; i++, k++) {
        char name[GD_LAW_NAME_MAX];
        snprintf(name, sizeof name, "loads[%d]", i);
        gd_law_init(&L[k], &gd_law_load, name);
        L[k].data = &spec->loads[i].law;
        L[k].dof[0] = spec->loads[i].dof;
    }
    for (int i = 0; i < spec->nlaws; i++, k++) {
        L[k] = spec->laws[i];
        const gd_law_type *t = L[k].type;
        if (!t) {
            free(L);
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "laws", "start from gd_law_init",
                                "law %d has no type", i);
        }
        for (int j = 0; j < L[k].ndofs && j < GD_LAW_MAX_DOFS; j++)
            if (L[k].dof[j] < -1 || L[k].dof[j] >= sys->ndof) {
                gd_status st =
                    gd_error_set(err, GD_EINPUT, "", 0, 0, "laws", "use gd_system_dof",
                                 "law '%s' acts on DOF %d, which the system does not have",
                                 L[k].name, L[k].dof[j]);
                free(L);
                return st;
            }
    }
    /* the cams last: their torques are summed after the other laws' on a camshaft */
    for (int i = 0; i < spec->ncams; i++, k++) {
        const gd_tr_cam *c = &spec->cams[i];
        char name[GD_LAW_NAME_MAX];
        snprintf(name, sizeof name, "cams[%d]", i);
        gd_law_init(&L[k], &gd_law_cam_torque, name);
        L[k].data = c->law;
        L[k].dof[0] = c->dof;
        L[k].value[gd_law_param_index(&gd_law_cam_torque, "mass")] = c->mass;
        L[k].value[gd_law_param_index(&gd_law_cam_torque, "phase")] = c->phase;
        L[k].value[gd_law_param_index(&gd_law_cam_torque, "acceleration")] =
            spec->cam_acceleration ? 1.0 : 0.0;
    }
    for (k = 0; k < total; k++) {
        gd_status st = gd_law_check(&L[k], err);
        if (st) {
            free(L);
            return st;
        }
        for (int j = 0; j < L[k].ndofs; j++)
            L[k].rate[j] = dof_rate(sys, L[k].dof[j], speed);
        /* the spin of each side's node: its shaft's nominal speed */
        const gd_law_type *t = L[k].type;
        int per = t->ndirs > 0 ? t->ndirs : 1;
        for (int side = 0; side < (t->two_nodes ? 2 : 1); side++) {
            int d = L[k].dof[side * per];
            const gd_model *m = sys->model;
            L[k].spin[side] =
                d >= 0 ? m->shafts[m->nodes[sys->dof_node[d]].shaft].speed_ratio * speed : 0.0;
        }
    }
    *out = L;
    *n = total;
    return GD_OK;
}
