/* Lumped spring and damper on one DOF type (a coupling, a torsional spring between a
 * motor and a shaft, a support in one direction): stiffness k and damping c acting on
 * the relative motion of DOF `dof` of two nodes, or of one node against ground. A is
 * the 6 x 6 matrix with k at (dof, dof) and zeros elsewhere (C likewise with c); the
 * local stiffness is A to ground or [A -A; -A A] between two nodes (connector.c): the
 * shaft springs K_t between motor, gears and load of [Kumar2011]'s lumped model, and the shaft
 * and gear-body springs of [Benini2004]'s timing gear train. */
#include <string.h>

#include "elements/elements_impl.h"

static int spring_count(const gd_model *m)
{
    return m->nsprings;
}

static int spring_nodes(const gd_model *m, int i, int node[2])
{
    return gd_connector_nodes(m->springs[i].node1, m->springs[i].node2, node);
}

static unsigned spring_terms(const gd_model *m, int i)
{
    (void)m;
    (void)i;
    return GD_TERM_K | GD_TERM_C;
}

static void spring_coefficients(const gd_spring *s, double K6[36], double C6[36])
{
    memset(K6, 0, 36 * sizeof *K6);
    memset(C6, 0, 36 * sizeof *C6);
    K6[s->dof * 7] = s->stiffness;
    C6[s->dof * 7] = s->damping;
}

static void spring_matrices(const gd_model *m, int i, double speed, double *M, double *K, double *C,
                            double *G)
{
    (void)speed;
    const gd_spring *s = &m->springs[i];
    int nn = s->node2 >= 0 ? 2 : 1, n = 6 * nn;
    double K6[36], C6[36];
    spring_coefficients(s, K6, C6);
    if (M) memset(M, 0, (size_t)(n * n) * sizeof *M);
    if (G) memset(G, 0, (size_t)(n * n) * sizeof *G);
    if (K) gd_connector_expand(K6, nn, K);
    if (C) gd_connector_expand(C6, nn, C);
}

static int spring_ncomponents(const gd_model *m)
{
    return m->nsprings;
}

static int spring_component(const gd_model *m, int i)
{
    (void)m;
    return i;
}

static const char *spring_name(const gd_model *m, int c)
{
    return m->springs[c].name;
}

/* The spring's force in direction dir: k (u1 - u2) + c (v1 - v2) when dir is its DOF. */
static void spring_force_row(const gd_model *m, int i, double speed, gd_dof dir, double *k,
                             double *c)
{
    (void)speed;
    const gd_spring *s = &m->springs[i];
    double K6[36], C6[36];
    spring_coefficients(s, K6, C6);
    gd_connector_row(K6, C6, s->node2 >= 0 ? 2 : 1, dir, k, c);
}

const gd_element_type gd_element_spring = {
    .name = "spring",
    .count = spring_count,
    .nodes = spring_nodes,
    .terms = spring_terms,
    .matrices = spring_matrices,
    .motion = gd_support_motion,
    .ncomponents = spring_ncomponents,
    .component = spring_component,
    .component_name = spring_name,
    .force_row = spring_force_row,
};
