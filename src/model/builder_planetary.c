/* The builder's planetary gear sets (docs/planetary.md): the spec's checks, the planets'
 * generated one-node shafts (gd_model_add_planetary), and the member nodes resolved by
 * gd_model_finish with the "held twice" check. The geometric checks say why a set cannot
 * be built: planets whose outside circles overlap at their spacing, tooth counts that
 * cannot be assembled at the given angles, a ring inside the planets' span. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

#define PI 3.14159265358979323846

const char *const gd_planetary_member_names[GD_PLANETARY_NMEMBERS] = {"sun", "ring", "carrier"};

void gd_planetary_spec_init(gd_planetary_spec *s)
{
    memset(s, 0, sizeof *s);
    s->held = -1;
    s->carrier_frame = -1;
    s->centrifugal_stiffness = 1;
    s->pressure_angle[0] = s->pressure_angle[1] = 20.0 * PI / 180.0;
    s->mesh_law[0].coast_stiffness_ratio = s->mesh_law[1].coast_stiffness_ratio = 1.0;
}

static const char *const SIZE_KEYS[3] = {"sun", "ring", "planet"};

static gd_status fail_at(const gd_model *m, gd_error *err, const gd_planetary_spec *s,
                         const char *path, const char *key, const char *hint, const char *msg)
{
    char fp[240];
    gd_build_path(fp, sizeof fp, path, key);
    return gd_build_fail(m, err, s->loc, fp, fp, hint, "%s", msg);
}

/* Values: signs, ranges, the angles' order. */
static gd_status check_values(const gd_model *m, gd_error *err, const gd_planetary_spec *s,
                              const char *path)
{
    gd_status st;
    char q[200], msg[200];
    for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++) {
        const gd_planetary_member_spec *b = &s->member[j];
        gd_build_path(q, sizeof q, path, gd_planetary_member_names[j]);
        if ((st = gd_build_positive(m, err, s->loc, q, "mass", b->mass, 1)) ||
            (st = gd_build_positive(m, err, s->loc, q, "inertia", b->inertia, 1)) ||
            (st = gd_build_positive(m, err, s->loc, q, "k_support", b->k_support, 1)) ||
            (st = gd_build_positive(m, err, s->loc, q, "k_torsion", b->k_torsion, 1)))
            return st;
    }
    if (s->nplanets < 1 || s->nplanets > GD_PLANETARY_MAX_PLANETS) {
        snprintf(msg, sizeof msg, "%d planets", s->nplanets);
        return fail_at(m, err, s, path, "planets.count", "give 1 to 64 planets", msg);
    }
    gd_build_path(q, sizeof q, path, "planets");
    if ((st = gd_build_positive(m, err, s->loc, q, "mass", s->planet_mass, 0)) ||
        (st = gd_build_positive(m, err, s->loc, q, "inertia", s->planet_inertia, 0)) ||
        (st = gd_build_positive(m, err, s->loc, q, "bearing_stiffness", s->bearing_stiffness, 0)))
        return st;
    for (int k = 0; k < 2; k++) {
        const double *e = k ? s->pin_errors_radial : s->pin_errors;
        for (int n = 0; e && n < s->nplanets; n++)
            if (!isfinite(e[n]) || fabs(e[n]) >= s->carrier_radius) {
                char key[64];
                snprintf(key, sizeof key, "planets.%s[%d]", k ? "pin_errors_radial" : "pin_errors",
                         n);
                snprintf(msg, sizeof msg, "pin error %g m", e[n]);
                return fail_at(m, err, s, path, key,
                               "give small position errors in m (e.g. 20 um), below the carrier "
                               "radius",
                               msg);
            }
    }
    if (s->planet_angles)
        for (int n = 0; n < s->nplanets; n++) {
            double a = s->planet_angles[n];
            int bad = !(a >= 0 && a < 2 * PI) || (n > 0 && !(a > s->planet_angles[n - 1]));
            if (bad) {
                char key[64];
                snprintf(key, sizeof key, "planets.angles[%d]", n);
                snprintf(msg, sizeof msg, "planet angle %g rad (%g deg) out of order or range", a,
                         a * 180 / PI);
                return fail_at(m, err, s, path, key,
                               "give increasing angles in [0, 360 deg) (plain numbers are radians)",
                               msg);
            }
        }
    for (int j = 0; j < 3; j++) {
        gd_build_path(q, sizeof q, path, "base_radius");
        if ((st = gd_build_positive(m, err, s->loc, q, SIZE_KEYS[j], s->base_radius[j], 0)))
            return st;
    }
    if ((st = gd_build_positive(m, err, s->loc, path, "carrier_radius", s->carrier_radius, 0)) ||
        (st = gd_build_positive(m, err, s->loc, path, "planet_tip_radius", s->planet_tip_radius,
                                1)) ||
        (st = gd_build_positive(m, err, s->loc, path, "helix_angle", s->helix_angle, 1)))
        return st;
    for (int j = 0; j < 2; j++) {
        gd_build_path(q, sizeof q, path, "mesh_stiffness");
        if ((st = gd_build_positive(m, err, s->loc, q, SIZE_KEYS[j], s->mesh_stiffness[j], 0)))
            return st;
        gd_build_path(q, sizeof q, path, "mesh_damping");
        if ((st = gd_build_positive(m, err, s->loc, q, SIZE_KEYS[j], s->mesh_damping[j], 1)))
            return st;
        double a = s->pressure_angle[j];
        if (!(a > 0 && a < 60 * PI / 180)) {
            char key[64];
            snprintf(key, sizeof key, "pressure_angle.%s", SIZE_KEYS[j]);
            snprintf(msg, sizeof msg, "pressure angle %g rad is not in (0, 60 deg)", a);
            return fail_at(m, err, s, path, key, "write e.g. `20 deg` (plain numbers are radians)",
                           msg);
        }
    }
    if (s->helix_angle >= 60 * PI / 180)
        return fail_at(m, err, s, path, "helix_angle", "write e.g. `10 deg`",
                       "helix angle not below 60 deg");
    int nteeth = (s->teeth[0] > 0) + (s->teeth[1] > 0) + (s->teeth[2] > 0);
    for (int j = 0; j < 3; j++)
        if (s->teeth[j] < 0 || (s->teeth[j] > 0 && s->teeth[j] < 3) ||
            (nteeth > 0 && nteeth < 3 && s->teeth[j] == 0)) {
            char key[64];
            snprintf(key, sizeof key, "teeth.%s", SIZE_KEYS[j]);
            snprintf(msg, sizeof msg, "teeth number %d", s->teeth[j]);
            return fail_at(m, err, s, path, key,
                           "give the teeth of sun, ring and planet (3 or more each), or none", msg);
        }
    if (s->held < -1 || s->held >= GD_PLANETARY_NMEMBERS)
        return fail_at(m, err, s, path, "held", "hold the sun, the ring, the carrier or none",
                       "unknown held member");
    if (s->held >= 0 && !(s->member[s->held].k_torsion > 0)) {
        char key[64];
        snprintf(key, sizeof key, "%s.k_torsion", gd_planetary_member_names[s->held]);
        snprintf(msg, sizeof msg, "the held %s has no torsional support",
                 gd_planetary_member_names[s->held]);
        return fail_at(m, err, s, path, key,
                       "give the stiffness that holds it (N m/rad), e.g. the housing's", msg);
    }
    return GD_OK;
}

/* Planet n's angle: given, or equally spaced. */
static double planet_angle(const gd_planetary_spec *s, int n)
{
    return s->planet_angles ? s->planet_angles[n] : 2 * PI * n / s->nplanets;
}

/* The planets' outside radius: given, or from the teeth (addendum = one module at the
 * operating pitch circle, r_b / cos(alpha_sp)); 0 when neither is known. */
static double tip_radius(const gd_planetary_spec *s)
{
    if (s->planet_tip_radius > 0) return s->planet_tip_radius;
    if (s->teeth[2] <= 0) return 0;
    double pitch = s->base_radius[2] / cos(s->pressure_angle[0]);
    return pitch + 2 * pitch / s->teeth[2];
}

/* Can the set be built: planets' tips apart, assembly, ring around the planets. */
static gd_status check_geometry(const gd_model *m, gd_error *err, const gd_planetary_spec *s,
                                const char *path)
{
    char msg[300], hint[300];
    int N = s->nplanets;
    double rc = s->carrier_radius, ra = tip_radius(s);
    /* adjacent planets' centres are 2 rc sin(dpsi / 2) apart; their outside circles
       must not touch */
    for (int n = 0; n < N && ra > 0 && N > 1; n++) {
        int k = (n + 1) % N;
        double d = fmod(planet_angle(s, k) - planet_angle(s, n) + 2 * PI, 2 * PI);
        double gap = 2 * rc * sin(d / 2);
        if (gap <= 2 * ra) {
            snprintf(msg, sizeof msg,
                     "planets %d and %d overlap: centres %.4g m apart, outside diameter %.4g m",
                     n + 1, k + 1, gap, 2 * ra);
            snprintf(hint, sizeof hint,
                     "space them at least %.4g deg apart, use fewer or smaller planets, or a "
                     "larger carrier_radius",
                     2 * asin(fmin(1.0, ra / rc)) * 180 / PI);
            return fail_at(m, err, s, path, s->planet_angles ? "planets.angles" : "planets.count",
                           hint, msg);
        }
    }
    /* assembly ([Parker2000], the mesh phase condition): planet n fits when
       (Z_s + Z_r) psi_n / 2 pi is a whole number */
    if (s->teeth[0] > 0) {
        int zs = s->teeth[0] + s->teeth[1];
        for (int n = 1; n < N; n++) {
            double x = zs * planet_angle(s, n) / (2 * PI);
            if (fabs(x - floor(x + 0.5)) > 1e-3) {
                double lo = floor(x) * 360.0 / zs, hi = ceil(x) * 360.0 / zs;
                if (s->planet_angles)
                    snprintf(msg, sizeof msg,
                             "planet %d at %.6g deg cannot be assembled: (Z_s + Z_r) psi / 360 "
                             "= %.6g is not a whole number",
                             n + 1, planet_angle(s, n) * 180 / PI, x);
                else
                    snprintf(msg, sizeof msg,
                             "%d equally spaced planets cannot be assembled: (Z_s + Z_r) / N = "
                             "%d / %d is not a whole number",
                             N, zs, N);
                if (s->planet_angles)
                    snprintf(hint, sizeof hint,
                             "the nearest angles that assemble are %.6g deg and %.6g deg "
                             "(multiples of 360 / (Z_s + Z_r)); or change the teeth",
                             lo, hi);
                else
                    snprintf(hint, sizeof hint,
                             "use a number of planets that divides %d, give `angles:` that are "
                             "multiples of %.6g deg, or change the teeth",
                             zs, 360.0 / zs);
                return fail_at(m, err, s, path, s->planet_angles ? "planets.angles" : "teeth", hint,
                               msg);
            }
        }
    }
    /* the ring's pitch circle must reach around the planets' pitch circles (equal for a
       consistent geometry: r_br - r_bp = rc cos(alpha_rp)); 2 % for rounded data */
    double ca = cos(s->pressure_angle[1]);
    double ring = s->base_radius[1] / ca, span = rc + s->base_radius[2] / ca;
    if (ring < span * (1 - 2e-2)) {
        snprintf(msg, sizeof msg,
                 "the ring (pitch radius %.4g m) is smaller than the planets' span (%.4g m: "
                 "carrier radius plus planet pitch radius)",
                 ring, span);
        return fail_at(m, err, s, path, "base_radius.ring",
                       "check the ring's base radius and the carrier radius", msg);
    }
    return GD_OK;
}

/* What the set owns beyond its angles and names: the meshes' tables, phases and TVMS. */
static void free_mesh_data(gd_planetary *g)
{
    for (int k = 0; k < 2; k++) {
        gd_table_free(g->mesh_law[k].tvms);
        g->mesh_law[k].tvms = NULL;
        free(g->mesh_phase[k]);
        g->mesh_phase[k] = NULL;
        gd_tvms_free(g->tvms[k]);
        g->tvms[k] = NULL;
    }
}

/* The meshes as laws (docs/planetary.md, "Meshes as laws"): values, tables over one sun
 * mesh period, the given phases. */
static gd_status mesh_laws(const gd_model *m, gd_error *err, const gd_planetary_spec *s,
                           const char *path, gd_planetary *g)
{
    static const char *const KIND[2] = {"mesh_laws.sun", "mesh_laws.ring"};
    static const char *const PHASES[2] = {"mesh_phases.sun", "mesh_phases.ring"};
    gd_status st;
    char q[200], msg[200];
    for (int k = 0; k < 2; k++) {
        const gd_planetary_mesh_law_spec *l = &s->mesh_law[k];
        gd_planetary_mesh_law *L = &g->mesh_law[k];
        gd_build_path(q, sizeof q, path, KIND[k]);
        if ((st = gd_build_positive(m, err, s->loc, q, "damping.per_stiffness",
                                    l->damping_per_stiffness, 1)) ||
            (st = gd_build_positive(m, err, s->loc, q, "damping.separated", l->damping_separated,
                                    1)) ||
            (st = gd_build_positive(m, err, s->loc, q, "backlash.gap", l->backlash_gap, 1)) ||
            (st = gd_build_positive(m, err, s->loc, q, "backlash.coast_stiffness_ratio",
                                    l->coast_stiffness_ratio, 1)))
            return st;
        if (l->tvms.n > 0) {
            if (s->teeth[0] <= 0)
                return fail_at(m, err, s, path, KIND[k],
                               "give the set's teeth: the table spans one sun mesh period",
                               "a TVMS table needs the teeth");
            gd_table_free(L->tvms); /* the geometry's, replaced */
            L->tvms = NULL;
            gd_error e = {0};
            if (gd_table_new(l->tvms.n, l->tvms.x, l->tvms.y, 2 * PI / s->teeth[0], l->tvms.interp,
                             &L->tvms, &e)) {
                char key[64];
                snprintf(key, sizeof key, "%s.tvms", KIND[k]);
                return fail_at(m, err, s, path, key,
                               "give increasing angles within one sun mesh period", e.message);
            }
        }
        L->damping_per_stiffness = l->damping_per_stiffness;
        L->damping_separated = l->damping_separated;
        L->backlash = l->backlash;
        L->gap = l->backlash ? l->backlash_gap : 0.0;
        L->coast_stiffness_ratio = l->coast_stiffness_ratio;
        L->active = L->active || L->tvms || l->backlash || l->damping_per_stiffness > 0 ||
                    l->damping_separated > 0;
        if (!s->mesh_phases[k]) continue;
        g->mesh_phase[k] = malloc((size_t)s->nplanets * sizeof *g->mesh_phase[k]);
        if (!g->mesh_phase[k]) return gd_build_oom(m, err);
        for (int n = 0; n < s->nplanets; n++) {
            double v = s->mesh_phases[k][n];
            if (!(v >= 0 && v < 1)) {
                char key[64];
                snprintf(key, sizeof key, "%s[%d]", PHASES[k], n);
                snprintf(msg, sizeof msg, "mesh phase %g is not in [0, 1)", v);
                return fail_at(m, err, s, path, key,
                               "give each planet's phase in mesh periods, from 0 to below 1", msg);
            }
            g->mesh_phase[k][n] = v;
        }
    }
    if (!(s->sun_ring_phase >= 0 && s->sun_ring_phase < 1)) {
        snprintf(msg, sizeof msg, "sun-ring phase %g is not in [0, 1)", s->sun_ring_phase);
        return fail_at(m, err, s, path, "mesh_phases.sun_ring",
                       "give the ring mesh's lag behind the sun mesh in mesh periods", msg);
    }
    g->sun_ring_phase = s->sun_ring_phase;
    return GD_OK;
}

/* One lumped shaft with one node per planet: "<set>.planet<n>", node "<set>.p<n>". */
static gd_status add_planet_shafts(gd_model *m, const gd_planetary_spec *s, const char *path,
                                   gd_error *err)
{
    char q[200];
    gd_build_path(q, sizeof q, path, "planets");
    for (int n = 0; n < s->nplanets; n++) {
        char shaft[GD_NAME_MAX + 16], node[GD_NAME_MAX + 16];
        snprintf(shaft, sizeof shaft, "%s.planet%d", s->name, n + 1);
        snprintf(node, sizeof node, "%s.p%d", s->name, n + 1);
        gd_station_spec st;
        gd_station_spec_init(&st);
        st.name = node;
        st.loc = s->loc;
        gd_shaft_spec sh;
        gd_shaft_spec_init(&sh);
        sh.name = shaft;
        sh.nstations = 1;
        sh.stations = &st;
        sh.loc = s->loc;
        sh.path = q;
        gd_status rc = gd_model_add_shaft(m, &sh, NULL, err);
        if (rc) return rc;
    }
    return GD_OK;
}

gd_status gd_model_add_planetary(gd_model *m, const gd_planetary_spec *spec, int *index,
                                 gd_error *err)
{
    gd_status st;
    gd_planetary_spec copy = *spec; /* the tooth geometry fills in the sizes */
    gd_planetary_spec *s = &copy;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nplanetary;
    char path[160];
    gd_build_item_path(path, sizeof path, s->path, "planetary_sets", idx);
    gd_planetary g;
    memset(&g, 0, sizeof g);
    g.loc = s->loc;
    if ((st = gd_build_name(m, err, s->loc, path, s->name, NULL, g.name))) return st;
    if (strlen(s->name) + 12 >= GD_NAME_MAX)
        return fail_at(m, err, s, path, "name", "use a shorter name",
                       "name too long for the planets' generated names");
    if (s->geometry && (st = gd_build_planetary_geometry(m, s, path, &g, err))) {
        free_mesh_data(&g);
        return st;
    }
    if ((st = check_values(m, err, s, path)) || (st = check_geometry(m, err, s, path)) ||
        (st = mesh_laws(m, err, s, path, &g))) {
        free_mesh_data(&g);
        return st;
    }
    for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++) {
        const gd_planetary_member_spec *b = &s->member[j];
        g.member[j] = (gd_planetary_body){-1, b->mass, b->inertia, b->k_support, b->k_torsion};
    }
    g.held = s->held;
    g.carrier_frame_all = s->carrier_frame; /* -1: decided at finish */
    g.centrifugal_stiffness = s->centrifugal_stiffness != 0;
    g.nplanets = s->nplanets;
    g.equally_spaced = s->planet_angles == NULL;
    memcpy(g.teeth, s->teeth, sizeof g.teeth);
    memcpy(g.base_radius, s->base_radius, sizeof g.base_radius);
    g.carrier_radius = s->carrier_radius;
    memcpy(g.pressure_angle, s->pressure_angle, sizeof g.pressure_angle);
    g.helix_angle = s->helix_angle;
    g.planet_tip_radius = tip_radius(s);
    g.planet_mass = s->planet_mass;
    g.planet_inertia = s->planet_inertia;
    g.bearing_stiffness = s->bearing_stiffness;
    memcpy(g.mesh_stiffness, s->mesh_stiffness, sizeof g.mesh_stiffness);
    memcpy(g.mesh_damping, s->mesh_damping, sizeof g.mesh_damping);
    g.instance_name = malloc((size_t)(3 + 4 * g.nplanets) * sizeof *g.instance_name);

    gd_bplanetary bp;
    memset(&bp, 0, sizeof bp);
    bp.path = gd_build_strdup(path);
    int ok = bp.path != NULL;
    for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++) {
        bp.node[j] = gd_build_strdup(s->member[j].node);
        ok = ok && (!s->member[j].node || bp.node[j]);
    }
    g.planet_angle = malloc((size_t)g.nplanets * sizeof *g.planet_angle);
    if (s->pin_errors) g.pin_error = malloc((size_t)g.nplanets * sizeof *g.pin_error);
    if (s->pin_errors_radial)
        g.pin_error_radial = malloc((size_t)g.nplanets * sizeof *g.pin_error_radial);
    ok = ok && g.planet_angle && g.instance_name && (!s->pin_errors || g.pin_error) &&
         (!s->pin_errors_radial || g.pin_error_radial) &&
         gd_build_grow(&m->planetary, m->nplanetary, sizeof *m->planetary) &&
         gd_build_grow(&m->build->planetary, m->nplanetary, sizeof *m->build->planetary);
    if (!ok) {
        free(bp.path);
        for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++)
            free(bp.node[j]);
        free(g.planet_angle);
        free(g.pin_error);
        free(g.pin_error_radial);
        free(g.instance_name);
        free_mesh_data(&g);
        return gd_build_oom(m, err);
    }
    /* the element's instance names (src/elements/planetary.c's order) */
    static const char *const KINDS[4] = {"planet", "sun_mesh", "ring_mesh", "bearing"};
    for (int j = 0; j < 3; j++)
        snprintf(g.instance_name[j], sizeof g.instance_name[j], "%s.%s", g.name,
                 gd_planetary_member_names[j]);
    for (int k = 0; k < 4; k++)
        for (int n = 0; n < g.nplanets; n++)
            snprintf(g.instance_name[3 + k * g.nplanets + n], sizeof g.instance_name[0], "%s.%s%d",
                     g.name, KINDS[k], n + 1);
    for (int n = 0; n < g.nplanets; n++) {
        g.planet_angle[n] = planet_angle(s, n);
        if (g.pin_error) g.pin_error[n] = s->pin_errors[n];
        if (g.pin_error_radial) g.pin_error_radial[n] = s->pin_errors_radial[n];
    }
    m->planetary[idx] = g;
    m->build->planetary[idx] = bp;
    m->nplanetary++;
    if ((st = add_planet_shafts(m, s, path, err))) return st;
    if (index) *index = idx;
    return GD_OK;
}

/* A node held about z to ground by a bearing or a spring (the item's path), or NULL. */
static const char *held_elsewhere(const gd_model *m, int node)
{
    for (int i = 0; i < m->nbearings; i++) {
        const gd_bearing *b = &m->bearings[i];
        if (b->node == node && b->node2 < 0 && b->coeffs.ktorsion > 0)
            return m->build->bearings[i].path;
    }
    for (int i = 0; i < m->nsprings; i++) {
        const gd_spring *sp = &m->springs[i];
        if (sp->node1 == node && sp->node2 < 0 && sp->dof == GD_RZ && sp->stiffness > 0)
            return m->build->springs[i].path;
    }
    return NULL;
}

gd_status gd_build_resolve_planetary(gd_model *m, gd_error *err)
{
    gd_status st;
    for (int k = 0; k < m->nplanetary; k++) {
        gd_planetary *g = &m->planetary[k];
        const gd_bplanetary *bp = &m->build->planetary[k];
        char q[200], fp[240];
        for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++) {
            gd_build_path(q, sizeof q, bp->path, gd_planetary_member_names[j]);
            if ((st =
                     gd_build_node_ref(m, err, g->loc, q, "node", bp->node[j], &g->member[j].node)))
                return st;
            for (int i = 0; i < j; i++)
                if (g->member[i].node == g->member[j].node)
                    return gd_build_fail(m, err, g->loc, gd_build_path(fp, sizeof fp, q, "node"),
                                         fp, "each member of a set sits on a node of its own",
                                         "the %s and the %s are both on node '%s'",
                                         gd_planetary_member_names[i], gd_planetary_member_names[j],
                                         bp->node[j]);
        }
        if (g->carrier_frame_all < 0) {
            g->carrier_frame_all = 1;
            for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++)
                if (m->shafts[m->nodes[g->member[j].node].shaft].nsections > 0)
                    g->carrier_frame_all = 0;
        }
        char first[GD_NAME_MAX + 16];
        snprintf(first, sizeof first, "%s.p1", g->name);
        g->first_planet = gd_model_find_node(m, first);
        for (int n = 1; n < g->nplanets && g->first_planet >= 0; n++) {
            char nm[GD_NAME_MAX + 16];
            snprintf(nm, sizeof nm, "%s.p%d", g->name, n + 1);
            if (gd_model_find_node(m, nm) != g->first_planet + n) g->first_planet = -1;
        }
        if (g->first_planet < 0)
            return gd_build_fail(m, err, g->loc, bp->path, bp->path,
                                 "rename the set or the nodes named '<set>.p<n>'",
                                 "the planets' nodes of set '%s' clash with other nodes", g->name);
        if (g->held < 0) continue;
        const gd_planetary_body *h = &g->member[g->held];
        const char *who = held_elsewhere(m, h->node);
        for (int i = 0; i < k && !who; i++) {
            const gd_planetary *o = &m->planetary[i];
            if (o->held >= 0 && o->member[o->held].node == h->node)
                who = m->build->planetary[i].path;
        }
        if (who) {
            gd_build_path(fp, sizeof fp, bp->path, "held");
            return gd_build_fail(m, err, g->loc, fp, fp,
                                 "hold a member once: remove `held` here or the torsional support "
                                 "there",
                                 "the %s (node '%s') is held twice: by this set and by %s",
                                 gd_planetary_member_names[g->held], m->nodes[h->node].name, who);
        }
    }
    return GD_OK;
}
