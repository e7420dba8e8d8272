/* Modal strain energy 1/2 Re(u^H K u) by element, split into motion types ([JMSTHelical] Tables
 * 4-7 name each mode by its dominant shaft and motion) and summed per component. Each
 * element kind says how its energy splits (geardyn/elements.h); this file only loops
 * over the elements, then over the laws linearised about the operating point (a rolling
 * bearing given by its geometry), each its own component after the elements': their
 * stiffness is part of the K the modes are computed with, so leaving it out credited a
 * mode carried by such bearings to the shaft they hold (reducer_three_stage's output
 * shaft on its bearings at 174.6 Hz: 99.6 % "output"). */
#include <stdlib.h>
#include <string.h>

#include "system/system_impl.h"

gd_motion gd_system_dof_motion(gd_dof d)
{
    return d == GD_RZ                   ? GD_MOTION_TORSIONAL
           : d == GD_Z                  ? GD_MOTION_AXIAL
           : (d == GD_RX || d == GD_RY) ? GD_MOTION_TILT
                                        : GD_MOTION_LATERAL;
}

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

/* 1/2 Re(u^H K u) of the laws' blocks law_K (gd_system_law_blocks' layout), each local
 * DOF's share to the motion of its system DOF, law i to component ncomponents - nlaws + i */
static double law_energies(const gd_system *s, const double *law_K, const double *re,
                           const double *im, double *by_motion, double *by_component, double *table)
{
    double total = 0;
    size_t at = 0;
    int c0 = s->ncomponents - s->nlaws;
    for (int i = 0; i < s->nlaws; i++) {
        const gd_law *L = &s->laws[i];
        int nd = L->ndofs;
        const double *K = law_K + at;
        at += (size_t)nd * nd;
        double en = 0;
        for (int a = 0; a < nd; a++) {
            int ia = L->dof[a];
            if (ia < 0) continue;
            double fr = 0, fi = 0;
            for (int b = 0; b < nd; b++) {
                int ib = L->dof[b];
                if (ib < 0) continue;
                fr += K[a + (size_t)nd * b] * re[ib];
                fi += K[a + (size_t)nd * b] * (im ? im[ib] : 0.0);
            }
            double e = 0.5 * (re[ia] * fr + (im ? im[ia] : 0.0) * fi);
            gd_motion mo = gd_system_dof_motion(s->dof_type[ia]);
            by_motion[mo] += e;
            if (table) table[(size_t)(c0 + i) * GD_NMOTIONS + mo] += e;
            en += e;
        }
        if (by_component) by_component[c0 + i] += en;
        total += en;
    }
    return total;
}

/* The energies by motion, by component (may be NULL) and by both (table, may be NULL:
 * ncomponents x GD_NMOTIONS, row c); the laws' with law_K (NULL: left out, 0). */
static double energies(const gd_system *s, double speed, const double *law_K, const double *re,
                       const double *im, double *by_motion, double *by_component, double *table)
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
    if (law_K && s->nlaws) total += law_energies(s, law_K, re, im, by_motion, by_component, table);
    return total;
}

double gd_system_strain_energy_laws(const gd_system *s, double speed, const double *law_K,
                                    const double *re, const double *im, double *by_motion,
                                    double *by_component, double *table)
{
    double bm[GD_NMOTIONS];
    return energies(s, speed, law_K, re, im, by_motion ? by_motion : bm, by_component, table);
}

/* The laws' K about the static state at speed (NULL: no laws or out of memory; the
 * caller frees it) */
static double *law_blocks(const gd_system *s, double speed)
{
    if (!s->nlaws) return NULL;
    double *Kb = malloc((size_t)s->law_block * 2 * sizeof *Kb);
    if (Kb) gd_system_law_blocks(s, speed, Kb, Kb + s->law_block);
    return Kb;
}

double gd_system_strain_energy(const gd_system *s, double speed, const double *re, const double *im,
                               double *by_motion, double *by_component)
{
    double *Kb = law_blocks(s, speed);
    double e = energies(s, speed, Kb, re, im, by_motion, by_component, NULL);
    free(Kb);
    return e;
}

double gd_system_strain_energy_table(const gd_system *s, double speed, const double *re,
                                     const double *im, double *table)
{
    double by_motion[GD_NMOTIONS];
    double *Kb = law_blocks(s, speed);
    double e = energies(s, speed, Kb, re, im, by_motion, NULL, table);
    free(Kb);
    return e;
}

int gd_system_component_shafts(const gd_system *s, int c, int shafts[2], double weights[2])
{
    const gd_model *m = s->model;
    int index, nodes[2] = {-1, -1};
    const char *name;
    if (c >= s->ncomponents - s->nlaws && c < s->ncomponents) {
        /* a law: the shafts of its DOFs' nodes (two at most: a law joins two nodes) */
        const gd_law *L = &s->laws[c - (s->ncomponents - s->nlaws)];
        int n = 0;
        for (int a = 0; a < L->ndofs; a++) {
            if (L->dof[a] < 0) continue;
            int sh = m->nodes[s->dof_node[L->dof[a]]].shaft;
            if ((n < 1 || shafts[0] != sh) && (n < 2 || shafts[1] != sh) && n < 2) shafts[n++] = sh;
        }
        for (int k = 0; k < n; k++)
            weights[k] = 1.0 / n;
        return n;
    }
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
