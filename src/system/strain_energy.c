/* Modal strain energy 1/2 Re(u^H K u) by element, split into motion types (002 Tables
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

double gd_system_strain_energy(const gd_system *s, double speed, const double *re, const double *im,
                               double *by_motion, double *by_component)
{
    const gd_model *m = s->model;
    double total = 0;
    for (int k = 0; k < GD_NMOTIONS; k++)
        by_motion[k] = 0;
    if (by_component)
        for (int c = 0; c < s->ncomponents; c++)
            by_component[c] = 0;
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
        double en = t->strain_energy ? t->strain_energy(m, in->index, K, ur, ui, by_motion)
                                     : split_by_dof(K, n, ur, ui, t->motion, by_motion);
        total += en;
        if (by_component) by_component[in->component] += en;
    }
    return total;
}
