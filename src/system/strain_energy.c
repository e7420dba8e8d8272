/* Modal strain energy 1/2 Re(u^H K u) by element, split into motion types ([JMSTHelical] Tables
 * 4-7 name each mode by its dominant shaft and motion) and summed per component. Each
 * element kind says how its energy splits (geardyn/elements.h); this file only loops
 * over the elements. */
#include <string.h>

#include "geardyn/system.h"

/* 1/2 Re(u^H K u) of an n x n local matrix, each local DOF's share going to
 * motion[a % 6]. DOFs that do not move are skipped. */
static double split_by_dof(const double *K, int n, const double *re, const double *im,
                           const gd_motion *motion, double *by_motion)
{
    double total = 0;
    int act[GD_ELEMENT_MAX_DOFS], na = 0;
    for (int b = 0; b < n; b++)
        if (re[b] != 0 || im[b] != 0) act[na++] = b;
    for (int ia = 0; ia < na; ia++) {
        int a = act[ia];
        double fr = 0, fi = 0;
        for (int ib = 0; ib < na; ib++) {
            int b = act[ib];
            fr += K[a * n + b] * re[b];
            fi += K[a * n + b] * im[b];
        }
        double e = 0.5 * (re[a] * fr + im[a] * fi);
        by_motion[motion[a % 6]] += e;
        total += e;
    }
    return total;
}

/* The energies by motion, by component (may be NULL) and by both (table, may be NULL:
 * ncomponents x GD_NMOTIONS, row c). */
static double energies(const gd_system *s, double speed, const double *re, const double *im,
                       double *by_motion, double *by_component, double *table)
{
    const gd_model *m = s->model;
    double total = 0;
    for (int k = 0; k < GD_NMOTIONS; k++)
        by_motion[k] = 0;
    if (by_component)
        for (int c = 0; c < s->ncomponents; c++)
            by_component[c] = 0;
    if (table) memset(table, 0, (size_t)s->ncomponents * GD_NMOTIONS * sizeof *table);
    for (int e = 0; e < s->ninstances; e++) {
        const gd_element_instance *in = &s->instances[e];
        if (in->component < 0) continue;
        const gd_element_type *t = in->type;
        int n = in->nlocal;
        double ur[GD_ELEMENT_MAX_DOFS], ui[GD_ELEMENT_MAX_DOFS];
        for (int a = 0; a < n; a++) {
            int i = in->dof[a];
            ur[a] = i >= 0 ? re[i] : 0.0;
            ui[a] = i >= 0 && im ? im[i] : 0.0;
        }
        double Kl[GD_ELEMENT_MAX_DOFS * GD_ELEMENT_MAX_DOFS];
        const double *K = in->K;
        if (!K) {
            t->matrices(m, in->index, speed, NULL, Kl, NULL, NULL);
            K = Kl;
        }
        double mo[GD_NMOTIONS] = {0};
        double en = t->strain_energy ? t->strain_energy(m, in->index, K, ur, ui, mo)
                                     : split_by_dof(K, n, ur, ui, t->motion, mo);
        for (int k = 0; k < GD_NMOTIONS; k++) {
            by_motion[k] += mo[k];
            if (table) table[(size_t)in->component * GD_NMOTIONS + k] += mo[k];
        }
        total += en;
        if (by_component) by_component[in->component] += en;
    }
    return total;
}

double gd_system_strain_energy(const gd_system *s, double speed, const double *re, const double *im,
                               double *by_motion, double *by_component)
{
    return energies(s, speed, re, im, by_motion, by_component, NULL);
}

double gd_system_strain_energy_table(const gd_system *s, double speed, const double *re,
                                     const double *im, double *table)
{
    double by_motion[GD_NMOTIONS];
    return energies(s, speed, re, im, by_motion, NULL, table);
}

int gd_system_component_shafts(const gd_system *s, int c, int shafts[2], double weights[2])
{
    const gd_model *m = s->model;
    int index, nodes[2] = {-1, -1};
    const char *name;
    const gd_element_type *t = gd_system_component(s, c, &index, &name);
    if (t == &gd_element_shaft) { /* a shaft's component is the whole shaft */
        shafts[0] = index;
        weights[0] = 1;
        return 1;
    }
    /* any other component is one element: the shafts of its nodes */
    if (!t || !t->nodes) return 0;
    t->nodes(m, index, nodes);
    int n = 0;
    for (int k = 0; k < 2; k++)
        if (nodes[k] >= 0) shafts[n++] = m->nodes[nodes[k]].shaft;
    if (n == 2 && shafts[0] == shafts[1]) n = 1;
    for (int k = 0; k < n; k++)
        weights[k] = 1.0 / n;
    return n;
}
