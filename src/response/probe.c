/* Probes (what a response is measured on) as linear functionals of the complex
 * amplitudes: a DOF, or the force of an element, which its kind gives as rows over its
 * local DOFs (geardyn/elements.h force_row): the dynamic mesh force F = k d + c d'
 * with d = a . q, the force a bearing transmits in one direction. */
#include <string.h>

#include "geardyn/probe.h"

/* The element kind whose force a probe kind measures. */
static const gd_element_type *probe_element(gd_probe_kind kind)
{
    return kind == GD_PROBE_MESH ? &gd_element_mesh : &gd_element_bearing;
}

void gd_probe_functional(const gd_system *sys, const gd_probe *p, double speed, gd_functional *f)
{
    memset(f, 0, sizeof *f);
    if (p->kind == GD_PROBE_DOF) {
        f->n = 1;
        f->dof[0] = p->index;
        f->k[0] = 1.0;
        return;
    }
    f->is_force = 1;
    const gd_element_type *t = probe_element(p->kind);
    const gd_element_instance *in = NULL;
    for (int e = 0; e < sys->ninstances && !in; e++)
        if (sys->instances[e].type == t && sys->instances[e].index == p->index)
            in = &sys->instances[e];
    if (!in) return;
    double k[GD_ELEMENT_MAX_DOFS], c[GD_ELEMENT_MAX_DOFS];
    t->force_row(sys->model, p->index, speed, p->dir, k, c);
    for (int a = 0; a < in->nlocal; a++) {
        if (in->dof[a] < 0 || (k[a] == 0 && c[a] == 0)) continue;
        f->dof[f->n] = in->dof[a];
        f->k[f->n] = k[a];
        f->c[f->n] = c[a];
        f->n++;
    }
}
