/* Planetary gear set: the lumped lateral-torsional model of [LinParker1999] (Sec. 2,
 * Eqs. 1-6), with the carrier-frame gyroscopic and centripetal terms of [CooleyParker2012]
 * (Eq. 1) when the carrier turns. docs/planetary.md has the derivation.
 *
 * Coordinates: sun, ring and carrier are model nodes (x, y, rz); planet n is a node of
 * its own (x, y in the model axes, rz its rotation), at angle psi_n on the carrier.
 * [LinParker1999] write the planet in radial/tangential coordinates zeta_n, eta_n and every
 * rotation as u = r theta; here zeta_n = x cos psi_n + y sin psi_n, eta_n = -x sin psi_n +
 * y cos psi_n and theta is the node's rz, so the two models are the same up to a change of
 * coordinates (the tests solve both).
 *
 * Instances of set s with N planets, in this order (3 + 4N):
 *   0..2      member bodies (sun, ring, carrier; 1 node): M = diag(m, m, I) on x, y, rz,
 *             K = diag(k_support, k_support, k_torsion);
 *   3..       planet bodies (1 node): M = diag(m_p, m_p, I_p);
 *   then      sun-planet meshes (sun, planet): K = k_sp a a^T, [LinParker1999] Eq. 2:
 *               d_sn = -x_s sin psi_sn + y_s cos psi_sn + r_s th_s
 *                      + x_n sin psi_sn - y_n cos psi_sn + r_p th_n,  psi_sn = psi_n - alpha_s
 *             ring-planet meshes (ring, planet), Eq. 3 (internal mesh):
 *               d_rn = -x_r sin psi_rn + y_r cos psi_rn + r_r th_r
 *                      + x_n sin psi_rn - y_n cos psi_rn - r_p th_n,  psi_rn = psi_n + alpha_r
 *             planet bearings (carrier, planet), Eq. 4: the planet against its pin, which the
 *             carrier moves by its translation and r_c th_c tangentially:
 *               d_radial = e_r . (u_n - u_c),  d_tangential = e_t . (u_n - u_c) - r_c th_c.
 * After every set's 3 + 4N instances, when the carrier turns: each set's N bearing preloads
 * (carrier, planet n), below; their energy counts in the bearing's strain-energy component.
 * A rigid rotation of the whole set gives d_sn = th (r_s + r_p - r_c cos alpha_s), zero for a
 * consistent geometry (tests). With the carrier turning at Omega = ratio W (the speed ratio
 * of the carrier's shaft), every body's translations, taken in the carrier frame, get the
 * Coriolis term 2 m Omega [0 -1; 1 0] (G per unit reference speed: ratio x that) and the
 * centripetal softening -m Omega^2 on x and y ([CooleyParker2012] Eq. 1, G and K_Omega). A set
 * whose members sit on shafts modelled in the fixed frame gives these terms to its planets only
 * (gd_planetary.carrier_frame_all 0): an approximation, docs/planetary.md.
 * The planets' centrifugal load F = m_p Omega^2 r_c preloads each bearing radially; measured in
 * the turning carrier the bearing's radial deformation has the second-order part
 * th_c e_t . (u_n - u_c) - r_c th_c^2 / 2, and the preload's work on it,
 *   E_n = F (th_c e_t . (u_n - u_c) - r_c th_c^2 / 2) = F (th_c d_tangential + r_c th_c^2 / 2),
 * is the bearing's geometric stiffness (gd_planetary.centrifugal_stiffness, default on; not in
 * [CooleyParker2012] Eq. 1). It cancels the planets' -m_p Omega^2 in a rotation of the set, so a
 * set free to turn keeps its rigid-body mode at 0 Hz at any carrier speed (docs/planetary.md).
 * An instance of its own, speed-dependent, so the bearing's constant K stays in the system's
 * constant K (and in its Rayleigh damping). */
#include <math.h>
#include <string.h>

#include "elements/elements_impl.h"

enum { BODY, PLANET, SUN_MESH, RING_MESH, BEARING, PRELOAD };

static double preload_ratio(const gd_model *m, const gd_planetary *g);

/* The sets' 3 + 4N instances (each its own strain-energy component). */
static int pl_ncomponents(const gd_model *m)
{
    int n = 0;
    for (int s = 0; s < m->nplanetary; s++)
        n += 3 + 4 * m->planetary[s].nplanets;
    return n;
}

/* Set, kind and index within the kind of instance i; *component: its strain-energy component
 * (a preload's: its bearing's). */
static const gd_planetary *locate_in(const gd_model *m, int i, int *kind, int *k, int *component)
{
    *kind = BODY;
    *k = 0;
    int c0 = 0;
    *component = i;
    for (int s = 0; s < m->nplanetary; s++) {
        const gd_planetary *g = &m->planetary[s];
        int N = g->nplanets, n = 3 + 4 * N;
        if (i >= n) {
            i -= n;
            c0 += n;
            continue;
        }
        if (i < 3) {
            *kind = BODY;
            *k = i;
        } else {
            *kind = PLANET + (i - 3) / N;
            *k = (i - 3) % N;
        }
        return g;
    }
    c0 = 0;
    for (int s = 0; s < m->nplanetary; s++) {
        const gd_planetary *g = &m->planetary[s];
        int N = g->nplanets;
        if (preload_ratio(m, g) != 0) {
            if (i < N) {
                *kind = PRELOAD;
                *k = i;
                *component = c0 + 3 + 3 * N + i;
                return g;
            }
            i -= N;
        }
        c0 += 3 + 4 * N;
    }
    return NULL;
}

static const gd_planetary *locate(const gd_model *m, int i, int *kind, int *k)
{
    int c;
    return locate_in(m, i, kind, k, &c);
}

static int pl_count(const gd_model *m)
{
    int n = pl_ncomponents(m);
    for (int s = 0; s < m->nplanetary; s++)
        if (preload_ratio(m, &m->planetary[s]) != 0) n += m->planetary[s].nplanets;
    return n;
}

static int pl_nodes(const gd_model *m, int i, int node[2])
{
    int kind, k;
    const gd_planetary *g = locate(m, i, &kind, &k);
    node[1] = -1;
    switch (kind) {
    case BODY:
        node[0] = g->member[k].node;
        return 1;
    case PLANET:
        node[0] = g->first_planet + k;
        return 1;
    case SUN_MESH:
        node[0] = g->member[GD_PLANETARY_SUN].node;
        break;
    case RING_MESH:
        node[0] = g->member[GD_PLANETARY_RING].node;
        break;
    default:
        node[0] = g->member[GD_PLANETARY_CARRIER].node;
        break;
    }
    node[1] = g->first_planet + k;
    return 2;
}

/* The carrier's speed ratio: the carrier frame turns at ratio x the reference speed. */
static double carrier_ratio(const gd_model *m, const gd_planetary *g)
{
    return m->shafts[m->nodes[g->member[GD_PLANETARY_CARRIER].node].shaft].speed_ratio;
}

/* The carrier speed ratio for a body of this kind: 0 for a central member when only the
 * planets are in the carrier frame. */
static double frame_ratio(const gd_model *m, const gd_planetary *g, int kind)
{
    return kind == BODY && !g->carrier_frame_all ? 0.0 : carrier_ratio(m, g);
}

/* The carrier speed ratio of the planets' centrifugal bearing preload (0: left out, or no
 * planet mass). The planets are in the carrier frame whatever carrier_frame says. */
static double preload_ratio(const gd_model *m, const gd_planetary *g)
{
    return g->centrifugal_stiffness && g->planet_mass > 0 ? carrier_ratio(m, g) : 0.0;
}

static void body_values(const gd_planetary *g, int kind, int k, double *mass, double *inertia,
                        double *ks, double *kt)
{
    if (kind == BODY) {
        *mass = g->member[k].mass;
        *inertia = g->member[k].inertia;
        *ks = g->member[k].k_support;
        *kt = g->member[k].k_torsion;
    } else {
        *mass = g->planet_mass;
        *inertia = g->planet_inertia;
        *ks = *kt = 0;
    }
}

static unsigned pl_terms(const gd_model *m, int i)
{
    int kind, k;
    const gd_planetary *g = locate(m, i, &kind, &k);
    if (kind == SUN_MESH || kind == RING_MESH)
        return GD_TERM_K | (g->mesh_damping[kind - SUN_MESH] > 0 ? GD_TERM_C : 0);
    if (kind == BEARING) return GD_TERM_K;
    if (kind == PRELOAD) return GD_TERM_K | GD_TERM_SPEED;
    double mass, inertia, ks, kt;
    body_values(g, kind, k, &mass, &inertia, &ks, &kt);
    unsigned t = GD_TERM_M | (ks > 0 || kt > 0 ? GD_TERM_K : 0);
    if (mass > 0 && frame_ratio(m, g, kind) != 0) t |= GD_TERM_G | GD_TERM_SPEED | GD_TERM_K;
    return t;
}

void gd_planetary_mesh_vector(const gd_planetary *g, int ring, int n, double a[12])
{
    memset(a, 0, 12 * sizeof *a);
    double psi = ring ? g->planet_angle[n] + g->pressure_angle[1]
                      : g->planet_angle[n] - g->pressure_angle[0];
    a[GD_X] = -sin(psi);
    a[GD_Y] = cos(psi);
    a[GD_RZ] = g->base_radius[ring ? 1 : 0];
    a[6 + GD_X] = sin(psi);
    a[6 + GD_Y] = -cos(psi);
    a[6 + GD_RZ] = ring ? -g->base_radius[2] : g->base_radius[2];
}

void gd_planetary_bearing_vectors(const gd_planetary *g, int n, double radial[12],
                                  double tangential[12])
{
    memset(radial, 0, 12 * sizeof *radial);
    memset(tangential, 0, 12 * sizeof *tangential);
    double c = cos(g->planet_angle[n]), s = sin(g->planet_angle[n]);
    radial[GD_X] = -c;
    radial[GD_Y] = -s;
    radial[6 + GD_X] = c;
    radial[6 + GD_Y] = s;
    tangential[GD_X] = s;
    tangential[GD_Y] = -c;
    tangential[GD_RZ] = -g->carrier_radius;
    tangential[6 + GD_X] = -s;
    tangential[6 + GD_Y] = c;
}

static void outer_add(double *K, double k, const double a[12])
{
    for (int r = 0; r < 12; r++)
        for (int s = 0; s < 12; s++)
            K[r * 12 + s] += k * a[r] * a[s];
}

void gd_planetary_centrifugal_stiffness(const gd_planetary *g, int n, double carrier_speed,
                                        double K[144])
{
    memset(K, 0, 144 * sizeof *K);
    double r[12], t[12];
    gd_planetary_bearing_vectors(g, n, r, t);
    double F = g->planet_mass * carrier_speed * carrier_speed * g->carrier_radius;
    /* E = F (th_c t . q + r_c th_c^2 / 2): Hessian F (e_th t^T + t e_th^T + r_c e_th e_th^T) */
    for (int a = 0; a < 12; a++) {
        K[GD_RZ * 12 + a] += F * t[a];
        K[a * 12 + GD_RZ] += F * t[a];
    }
    K[GD_RZ * 12 + GD_RZ] += F * g->carrier_radius;
}

static void pl_matrices(const gd_model *m, int i, double speed, double *M, double *K, double *C,
                        double *G)
{
    int kind, k;
    const gd_planetary *g = locate(m, i, &kind, &k);
    int nn = (kind == BODY || kind == PLANET) ? 6 : 12;
    size_t bytes = (size_t)(nn * nn) * sizeof(double);
    if (M) memset(M, 0, bytes);
    if (K) memset(K, 0, bytes);
    if (C) memset(C, 0, bytes);
    if (G) memset(G, 0, bytes);
    if (kind == SUN_MESH || kind == RING_MESH) {
        double a[12];
        gd_planetary_mesh_vector(g, kind == RING_MESH, k, a);
        if (K) outer_add(K, g->mesh_stiffness[kind - SUN_MESH], a);
        if (C) outer_add(C, g->mesh_damping[kind - SUN_MESH], a);
        return;
    }
    if (kind == BEARING) {
        double r[12], t[12];
        gd_planetary_bearing_vectors(g, k, r, t);
        if (K) {
            outer_add(K, g->bearing_stiffness, r);
            outer_add(K, g->bearing_stiffness, t);
        }
        return;
    }
    if (kind == PRELOAD) {
        if (K) gd_planetary_centrifugal_stiffness(g, k, preload_ratio(m, g) * speed, K);
        return;
    }
    double mass, inertia, ks, kt, ratio = frame_ratio(m, g, kind);
    body_values(g, kind, k, &mass, &inertia, &ks, &kt);
    if (M) {
        M[GD_X * 6 + GD_X] = M[GD_Y * 6 + GD_Y] = mass;
        M[GD_RZ * 6 + GD_RZ] = inertia;
    }
    if (K) {
        double w = ratio * speed;
        K[GD_X * 6 + GD_X] = K[GD_Y * 6 + GD_Y] = ks - mass * w * w;
        K[GD_RZ * 6 + GD_RZ] = kt;
    }
    if (G) {
        G[GD_X * 6 + GD_Y] = -2 * mass * ratio;
        G[GD_Y * 6 + GD_X] = 2 * mass * ratio;
    }
}

static void pl_speed_pattern(const gd_model *m, int i, int *acts)
{
    int kind, k;
    locate(m, i, &kind, &k);
    int node[2], nn = pl_nodes(m, i, node);
    memset(acts, 0, (size_t)(6 * nn) * sizeof *acts);
    acts[GD_X] = acts[GD_Y] = 1;
    if (kind == PRELOAD) /* carrier x, y, rz; planet x, y */
        acts[GD_RZ] = acts[6 + GD_X] = acts[6 + GD_Y] = 1;
}

/* One strain-energy component per instance (its nodes give its shafts), a preload's its
 * bearing's. */
static int pl_component(const gd_model *m, int i)
{
    int kind, k, c;
    locate_in(m, i, &kind, &k, &c);
    return c;
}

static const char *pl_component_name(const gd_model *m, int c)
{
    for (int s = 0; s < m->nplanetary; s++) {
        int n = 3 + 4 * m->planetary[s].nplanets;
        if (c < n) return m->planetary[s].instance_name[c];
        c -= n;
    }
    return "";
}

const gd_element_type gd_element_planetary = {
    .name = "planetary",
    .count = pl_count,
    .nodes = pl_nodes,
    .terms = pl_terms,
    .matrices = pl_matrices,
    .speed_pattern = pl_speed_pattern,
    .motion = gd_support_motion,
    .ncomponents = pl_ncomponents,
    .component = pl_component,
    .component_name = pl_component_name,
};
