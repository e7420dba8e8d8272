/* Outputs of a static solution: the reactions of the supports from their local
 * stiffness and the displacements of their nodes (the force a support exerts on its node
 * is -K_local u_local), and per mesh its force and misalignment.
 *
 * Mesh force: the mesh deflection d = a . q along the contact normal gives F = k d; the
 * force on the gears is -F a (a of src/elements/gear_mesh.c, helical [JMSTHelical] Eqs. 14-16),
 * its components F cos(bb) cos(alpha_wt) (tangential), F cos(bb) sin(alpha_wt) (radial)
 * and F sin(bb) (axial).
 *
 * Misalignment: with n the drive-flank line of action in the transverse plane (as in
 * gear_mesh.c) and theta = (rx, ry) the relative tilt driver - driven, a point of the
 * driver's face at axial offset zeta moves zeta (theta x z) relative to the driven gear,
 * whose part along n is zeta theta . (z x n): the tilt in the plane of action, which
 * opens or closes the flank gap linearly across the face. Over the face width b it is
 * the mesh misalignment from deformations f_sh of ISO 6336-1 (clause 7, helix deviation
 * measured along the line of action in the transverse plane); with no manufacturing part
 * f_ma the equivalent misalignment F_beta_x = |f_sh| (method B: deformations computed
 * by an elastic model of shafts and bearings). The tilt theta . n turns the axes out of
 * that plane; it changes the gap only to second order and is reported for information. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "static/static_impl.h"

static void support_force(const gd_system *sys, const gd_element_instance *in, double speed,
                          const double *q, double *force6)
{
    double K[GD_ELEMENT_MAX_DOFS * GD_ELEMENT_MAX_DOFS], u[GD_ELEMENT_MAX_DOFS];
    int nl = in->nlocal;
    in->type->matrices(sys->model, in->index, speed, NULL, K, NULL, NULL);
    for (int j = 0; j < nl; j++)
        u[j] = in->dof[j] >= 0 ? q[in->dof[j]] : 0;
    for (int a = 0; a < 6; a++) {
        double s = 0;
        for (int b = 0; b < nl; b++)
            s += K[a * nl + b] * u[b];
        force6[a] = -s;
    }
}

static void mesh_outputs(const gd_system *sys, int k, const double *q, const double *u,
                         gd_static_mesh *o)
{
    const gd_mesh *g = &sys->model->meshes[k];
    gd_mesh_vector mv;
    gd_system_mesh_vector(sys, k, &mv);
    double d = 0;
    for (int j = 0; j < mv.n; j++)
        d += mv.a[j] * q[mv.dof[j]];
    double F = g->stiffness * d, bb = g->base_helix_angle, al = g->pressure_angle;
    o->force = F;
    for (int j = 0; j < mv.n; j++) {
        int node = sys->dof_node[mv.dof[j]];
        double *on = node == g->driver ? o->on_driver : o->on_driven;
        on[sys->dof_type[mv.dof[j]]] = -F * mv.a[j];
    }
    o->tangential = F * cos(bb) * cos(al);
    o->radial = F * cos(bb) * sin(al);
    o->axial = F * sin(bb);
    /* the transverse line of action n, as gear_mesh.c builds it */
    double s = g->driver_sense >= 0 ? 1.0 : -1.0, gam = g->line_of_centres;
    double ep[2] = {-sin(gam), cos(gam)}, th = -s * al;
    double n[2] = {s * (ep[0] * cos(th) - ep[1] * sin(th)),
                   s * (ep[0] * sin(th) + ep[1] * cos(th))};
    const double *ud = u + (size_t)g->driver * GD_NODE_DOFS;
    const double *un = u + (size_t)g->driven * GD_NODE_DOFS;
    double tx = ud[GD_RX] - un[GD_RX], ty = ud[GD_RY] - un[GD_RY];
    o->tilt_in_plane = -tx * n[1] + ty * n[0];
    o->tilt_out_of_plane = tx * n[0] + ty * n[1];
    o->face_width = g->face_width;
    o->f_sh = g->face_width > 0 ? g->face_width * o->tilt_in_plane : NAN;
    o->f_beta_x = fabs(o->f_sh);
}

void gd_st_outputs(const gd_system *sys, gd_static_result *res)
{
    for (int e = 0; e < sys->ninstances; e++) {
        const gd_element_instance *in = &sys->instances[e];
        double f6[6];
        if (in->type == &gd_element_bearing) {
            support_force(sys, in, res->speed, res->q, f6);
            gd_static_reaction *r = &res->bearings[in->index];
            memcpy(r->force, f6, sizeof r->force);
            memcpy(r->moment, f6 + 3, sizeof r->moment);
        } else if (in->type == &gd_element_spring) {
            support_force(sys, in, res->speed, res->q, f6);
            res->springs[in->index] = f6[sys->model->springs[in->index].dof];
        }
    }
    for (int k = 0; k < res->nmeshes; k++)
        mesh_outputs(sys, k, res->q, res->u, &res->meshes[k]);
}
