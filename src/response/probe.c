/* Probes (what a response is measured on) as linear functionals of the complex
 * amplitudes: a DOF, or the force of an element, which its kind gives as rows over its
 * local DOFs (geardyn/elements.h force_row): the dynamic mesh force F = k d + c d'
 * with d = a . q, the force a bearing transmits in one direction. The probe syntax
 * (PROBE:NAME, PROBE:NAME.DIR) is the kinds' own (gd_element_type.probe). */
#include <stdio.h>
#include <string.h>

#include "geardyn/probe.h"

const gd_element_type *gd_probe_element(const char *text, const char **rest)
{
    for (int k = 0; k < gd_nelement_types; k++) {
        const gd_element_type *t = gd_element_types[k];
        size_t n = t->probe ? strlen(t->probe) : 0;
        if (n && !strncmp(text, t->probe, n) && text[n] == ':') {
            if (rest) *rest = text + n + 1;
            return t;
        }
    }
    return NULL;
}

int gd_probe_instance(const gd_system *sys, const gd_element_type *t, const char *name)
{
    const char *cname;
    for (int c = 0, i; c < sys->ncomponents; c++)
        if (gd_system_component(sys, c, &i, &cname) == t && !strcmp(cname, name)) return i;
    return -1;
}

/* Appends the probe of instance i of t in direction dir; 0 when out is full. */
static int add(const gd_system *sys, const gd_element_type *t, int i, gd_dof dir, gd_probe *out,
               int *n, int cap)
{
    if (*n >= cap) return 0;
    gd_probe *p = &out[(*n)++];
    memset(p, 0, sizeof *p);
    p->element = t;
    p->index = i;
    p->dir = dir;
    const char *name = t->component_name(sys->model, t->component(sys->model, i));
    if (t->probe_dirs)
        snprintf(p->name, sizeof p->name, "%s:%s.%s", t->probe, name, gd_dof_names[dir]);
    else
        snprintf(p->name, sizeof p->name, "%s:%s", t->probe, name);
    return 1;
}

int gd_probe_defaults(const gd_system *sys, gd_probe *out, int cap)
{
    const gd_model *m = sys->model;
    int n = 0;
    for (int dirs = 0; dirs < 2; dirs++)
        for (int k = 0; k < gd_nelement_types; k++) {
            const gd_element_type *t = gd_element_types[k];
            if (!t->probe || t->probe_dirs != dirs) continue;
            for (int i = 0; i < t->count(m); i++) {
                if (!dirs) {
                    add(sys, t, i, GD_X, out, &n, cap);
                    continue;
                }
                int node[2];
                t->nodes(m, i, node);
                for (int d = GD_X; d <= GD_Y; d++)
                    if (gd_system_dof(sys, node[0], (gd_dof)d) >= 0)
                        add(sys, t, i, (gd_dof)d, out, &n, cap);
            }
        }
    return n;
}

void gd_probe_functional(const gd_system *sys, const gd_probe *p, double speed, gd_functional *f)
{
    memset(f, 0, sizeof *f);
    if (!p->element) {
        f->n = 1;
        f->dof[0] = p->index;
        f->k[0] = 1.0;
        return;
    }
    f->is_force = 1;
    const gd_element_type *t = p->element;
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
