/* A planetary set's meshes from its tooth geometry (docs/planetary.md, "Meshes from
 * geometry"): the sun-planet pair (external, the sun driving) and the planet-ring pair
 * (internal, the planet driving the ring) of docs/mesh-stiffness.md give the set's base
 * radii, carrier radius (the common centre distance), operating pressure angles, contact
 * ratios and TVMS; [ParkerLin2004]'s sun-ring phase (gd_planet_sun_ring_phase) places the
 * ring mesh's TVMS behind the sun mesh's. Both tables are written over the sun's rotation
 * relative to the carrier (one mesh period 2 pi / Z_s), the variable of the set's mesh laws. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

void gd_planetary_geometry_init(gd_planetary_geometry *g)
{
    memset(g, 0, sizeof *g);
    g->pressure_angle = 20.0 * 3.14159265358979323846 / 180.0;
    gd_tvms_options_init(&g->tvms);
}

static void pair_of(const gd_planetary_spec *s, int ring, gd_gear_pair_geometry *p)
{
    const gd_planetary_geometry *G = s->geometry;
    gd_gear_pair_geometry_init(p);
    /* sun-planet: sun drives the planet; ring-planet: the planet drives the ring */
    int a = ring ? 2 : 0, b = ring ? 1 : 2;
    p->gear[0].teeth = s->teeth[a];
    p->gear[0].profile_shift = G->profile_shift[a];
    p->gear[1].teeth = s->teeth[b];
    p->gear[1].profile_shift = G->profile_shift[b];
    p->normal_module = G->module;
    p->normal_pressure_angle = G->pressure_angle;
    p->helix_angle = s->helix_angle;
    p->face_width = G->face_width;
    p->internal = ring;
}

/* The pitch point's passage in mesh periods after a pair starts contact (the TVMS
 * origin): gd_planet_sun_ring_phase's events to the tables' origins. */
static double pitch_delay(const gd_gear_pair_derived *d)
{
    return (d->pitch_point - d->contact_start) / d->base_pitch_transverse;
}

/* k(driver angle) over its first cycle as k(sun angle relative to the carrier): the
 * driver's angle times z_driver / Z_s; the transverse stiffness (the set's model is
 * transverse). */
static gd_status sun_angle_table(const gd_tvms_result *r, double scale, double period,
                                 gd_table **out, gd_error *err)
{
    int n = (int)r->points;
    double *x = malloc((size_t)n * 2 * sizeof *x);
    if (!x) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    for (int i = 0; i < n; i++) {
        x[i] = r->angle_rad[i] * scale;
        x[n + i] = r->stiffness[i] * r->transverse_factor;
    }
    gd_status st = gd_table_new(n, x, x + n, period, GD_INTERP_LINEAR, out, err);
    free(x);
    return st;
}

gd_status gd_build_planetary_geometry(const gd_model *m, gd_planetary_spec *s, const char *path,
                                      gd_planetary *g, gd_error *err)
{
    const gd_planetary_geometry *G = s->geometry;
    char q[200];
    gd_build_path(q, sizeof q, path, "geometry");
    if (s->teeth[0] <= 0 || s->teeth[1] <= 0 || s->teeth[2] <= 0)
        return gd_build_fail(m, err, s->loc, q, q, "give `teeth: {sun, ring, planet}`",
                             "the tooth geometry needs the set's teeth");
    if (s->base_radius[0] > 0 || s->base_radius[1] > 0 || s->base_radius[2] > 0 ||
        s->carrier_radius > 0)
        return gd_build_fail(m, err, s->loc, q, q,
                             "leave out base_radius and carrier_radius: the geometry gives them",
                             "base radii or carrier radius given with the tooth geometry");
    gd_status st;
    if ((st = gd_build_positive(m, err, s->loc, q, "module", G->module, 0)) ||
        (st = gd_build_positive(m, err, s->loc, q, "face_width", G->face_width, 0)))
        return st;
    gd_gear_pair_geometry pair[2];
    for (int k = 0; k < 2; k++) {
        pair_of(s, k, &pair[k]);
        gd_tvms_result *r = NULL;
        gd_error e = {0};
        if ((st = gd_tvms_compute(&pair[k], &G->tvms, &r, &e))) {
            char f[sizeof e.field + 240];
            snprintf(f, sizeof f, "%s.%s%s%s", q, k ? "ring_planet" : "sun_planet",
                     e.field[0] ? "." : "", e.field);
            return gd_build_fail(m, err, s->loc, q, f, e.hint, "%s mesh: %s",
                                 k ? "ring-planet" : "sun-planet", e.message);
        }
        g->tvms[k] = r;
    }
    const gd_gear_pair_derived *ds = &g->tvms[0]->geom, *dr = &g->tvms[1]->geom;
    double gamma_rs = 0.0;
    gd_error e = {0};
    if ((st = gd_planet_sun_ring_phase(&pair[0], &pair[1], &gamma_rs, &e))) {
        char f[sizeof e.field + 240];
        snprintf(f, sizeof f, "%s.%s", q, e.field);
        return gd_build_fail(m, err, s->loc, q, f, e.hint, "%s", e.message);
    }
    /* the sun pair's origin to its pitch event, gamma_rs to the ring pair's pitch event,
       back to the ring pair's origin */
    double lag = pitch_delay(ds) + gamma_rs - pitch_delay(dr);
    if (!s->has_sun_ring_phase) s->sun_ring_phase = lag - floor(lag);
    s->base_radius[0] = ds->base_radius[0];
    s->base_radius[1] = dr->base_radius[1];
    s->base_radius[2] = ds->base_radius[1];
    s->carrier_radius = ds->center_distance;
    s->pressure_angle[0] = ds->working_pressure_angle;
    s->pressure_angle[1] = dr->working_pressure_angle;
    for (int k = 0; k < 2; k++) {
        const gd_tvms_result *r = g->tvms[k];
        g->contact_ratio[k] = r->geom.contact_ratio_total;
        if (!(s->mesh_stiffness[k] > 0)) s->mesh_stiffness[k] = r->mean * r->transverse_factor;
        /* a table given in mesh_laws wins over the geometry's */
        if (s->mesh_law[k].tvms.n > 0) continue;
        double scale = k ? (double)s->teeth[2] / s->teeth[0] : 1.0;
        if ((st = sun_angle_table(r, scale, 2 * 3.14159265358979323846 / s->teeth[0],
                                  &g->mesh_law[k].tvms, &e)))
            return gd_build_fail(m, err, s->loc, q, q, "", "%s", e.message);
        g->mesh_law[k].active = 1;
    }
    return GD_OK;
}
