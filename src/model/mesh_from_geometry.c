/* A mesh's gear size, angles and stiffness from its geometry (docs/mesh-stiffness.md):
 * the derived base radii and working pressure angle, and with `stiffness from
 * geometry` the TVMS k(driver angle) whose mean is the linear stiffness; and the
 * mesh's time-integration tables over its mesh period. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"
#include "model/build_impl.h"

#define PI 3.14159265358979323846

/* An error of gd_gear_pair_derive / gd_tvms_compute, whose field is relative to the
 * geometry (or, for the options, the stiffness) of the mesh. */
static gd_status locate_geometry_error(const gd_model *m, const gd_mesh *g, const char *path,
                                       gd_status st, gd_error *err)
{
    if (!err) return st;
    const gd_field_locator *l = &m->build->locator;
    if (l->locate_geometry && l->locate_geometry(l->ctx, path, err)) return st;
    gd_gear_pair_error_prefix(err, path);
    snprintf(err->file, sizeof err->file, "%s", m->file);
    err->line = g->loc.line;
    err->column = g->loc.column;
    return st;
}

static double table_mean(const gd_table *t, double period)
{
    const int n = 2048;
    double s = 0;
    for (int i = 0; i < n; i++)
        s += gd_table_eval(t, period * i / n, NULL, NULL);
    return s / n;
}

gd_status gd_build_mesh_from_geometry(gd_model *m, int k, gd_error *err)
{
    gd_mesh *g = &m->meshes[k];
    const gd_bmesh *bm = &m->build->meshes[k];
    gd_status st;
    if (bm->has_geometry) {
        gd_gear_pair_derived der;
        if ((st = gd_gear_pair_derive(&bm->geometry, &der, err)))
            return locate_geometry_error(m, g, bm->path, st, err);
        for (int i = 0; i < 2; i++) {
            g->teeth[i] = bm->geometry.gear[i].teeth;
            g->base_radius[i] = der.base_radius[i];
        }
        g->pressure_angle = der.working_pressure_angle;
        g->helix_angle = bm->geometry.helix_angle;
        g->base_helix_angle = der.base_helix_angle;
        g->hand = bm->geometry.hand;
        g->face_width = bm->geometry.face_width;
        if (bm->from_geometry && bm->options.contact_analysis) {
            /* the loaded stiffness and, as the mesh's error, delta - F0 / k_L */
            double *e = NULL;
            if ((st = gd_ms_loaded_tvms(&bm->geometry, &bm->options, &g->tvms, &e, err)))
                return locate_geometry_error(m, g, bm->path, st, err);
            st = gd_table_new((int)g->tvms->points, g->tvms->angle_rad, e, g->tvms->mesh_period_rad,
                              GD_INTERP_LINEAR, &g->dyn.ste, err);
            free(e);
            if (st) return st;
            g->stiffness = g->tvms->mean;
        } else if (bm->from_geometry) {
            if ((st = gd_tvms_compute(&bm->geometry, &bm->options, &g->tvms, err)))
                return locate_geometry_error(m, g, bm->path, st, err);
            g->stiffness = g->tvms->mean;
        }
    }
    double period = g->teeth[0] > 0 ? 2 * PI / g->teeth[0] : 0;
    char q[220];
    if (bm->tvms.n) {
        gd_build_path(q, sizeof q, bm->path, "tvms");
        if ((st = gd_build_make_table(m, err, g->loc, q, &bm->tvms, period, &g->dyn.tvms)))
            return st;
        /* a table gives the mean stiffness unless one is given */
        if (!(g->stiffness > 0)) g->stiffness = table_mean(g->dyn.tvms, period);
    }
    if (bm->ste.n) {
        gd_build_path(q, sizeof q, bm->path, "transmission_error");
        if ((st = gd_build_make_table(m, err, g->loc, q, &bm->ste, period, &g->dyn.ste))) return st;
    }
    return GD_OK;
}
