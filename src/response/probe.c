/* Probes (what a response is measured on) as linear functionals of the complex
 * amplitudes: a DOF, the dynamic mesh force F = k d + c d' with d = a . q (000 Fig. 3
 * uses K_m (r_p theta_p + r_g theta_g)), and the force a bearing transmits in one
 * direction, the row of K_b dq + C_b dq' with dq = q(node) - q(node2). */
#include <math.h>
#include <string.h>

#include "elements/elements_impl.h"
#include "geardyn/probe.h"

const char *const gd_frf_quantity_names[3] = {"receptance", "mobility", "accelerance"};

void gd_probe_functional(const gd_system *sys, const gd_probe *p, double speed, gd_functional *f)
{
    memset(f, 0, sizeof *f);
    const gd_model *m = sys->model;
    if (p->kind == GD_PROBE_DOF) {
        f->n = 1;
        f->dof[0] = p->index;
        f->k[0] = 1.0;
        return;
    }
    f->is_force = 1;
    if (p->kind == GD_PROBE_MESH) {
        gd_mesh_vector v;
        gd_system_mesh_vector(sys, p->index, &v);
        const gd_mesh *g = &m->meshes[p->index];
        for (int j = 0; j < v.n; j++) {
            f->dof[j] = v.dof[j];
            f->k[j] = g->stiffness * v.a[j];
            f->c[j] = g->damping * v.a[j];
        }
        f->n = v.n;
        return;
    }
    const gd_bearing *b = &m->bearings[p->index];
    gd_bearing_coeffs c;
    gd_bearing_coeffs_at(b, fabs(m->shafts[m->nodes[b->node].shaft].speed_ratio * speed), &c);
    double Kb[36], Cb[36];
    gd_bearing_matrices(&c, Kb, Cb);
    int d = (int)p->dir;
    for (int side = 0; side < 2; side++) {
        int node = side ? b->node2 : b->node;
        if (node < 0) continue;
        double sg = side ? -1.0 : 1.0;
        for (int e = 0; e < 6; e++) {
            int i = gd_system_dof(sys, node, (gd_dof)e);
            double kv = Kb[d * 6 + e], cv = Cb[d * 6 + e];
            if (i < 0 || (kv == 0 && cv == 0)) continue;
            f->dof[f->n] = i;
            f->k[f->n] = sg * kv;
            f->c[f->n] = sg * cv;
            f->n++;
        }
    }
}
