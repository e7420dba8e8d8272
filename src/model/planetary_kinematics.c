/* A planetary set's kinematics (Willis: (w_s - w_c) Z_s = -(w_r - w_c) Z_r, the planet
 * (w_p - w_c) Z_p = -(w_s - w_c) Z_s), its mesh frequency and its assembly condition
 * ([Parker2000]: planet n fits when (Z_s + Z_r) psi_n / 2 pi is a whole number).
 * docs/planetary.md. */
#include <math.h>
#include <string.h>

#include "geardyn/planetary.h"

#define PI 3.14159265358979323846

void gd_planetary_kinematics_of(const gd_planetary *g, gd_planetary_kinematics *out)
{
    memset(out, 0, sizeof *out);
    int teeth = g->teeth[0] > 0;
    /* teeth, or pitch radii in their place (proportional for one module) */
    double zs = teeth ? g->teeth[0] : g->base_radius[0] / cos(g->pressure_angle[0]);
    double zr = teeth ? g->teeth[1] : g->base_radius[1] / cos(g->pressure_angle[1]);
    double zp = teeth ? g->teeth[2] : g->base_radius[2] / cos(g->pressure_angle[0]);
    out->has_teeth = teeth;
    out->teeth_ratio = zr / zs;
    double *w = out->speed;
    switch (g->held) {
    case GD_PLANETARY_RING: /* sun in, carrier out */
        out->input = GD_PLANETARY_SUN;
        w[0] = 1, w[1] = 0, w[2] = zs / (zs + zr);
        break;
    case GD_PLANETARY_CARRIER: /* star: sun in, ring out, reversed */
        out->input = GD_PLANETARY_SUN;
        w[0] = 1, w[1] = -zs / zr, w[2] = 0;
        break;
    case GD_PLANETARY_SUN: /* ring in, carrier out */
        out->input = GD_PLANETARY_RING;
        w[0] = 0, w[1] = 1, w[2] = zr / (zs + zr);
        break;
    default:
        out->input = -1;
        w[0] = w[1] = w[2] = NAN;
    }
    out->planet_speed = w[2] - (w[0] - w[2]) * zs / zp;
    out->mesh_order = teeth ? zs * fabs(w[0] - w[2]) : NAN;
    out->assembles = teeth ? 1 : -1;
    for (int n = 0; n < g->nplanets && n < GD_PLANETARY_MAX_PLANETS; n++) {
        double x = (zs + zr) * g->planet_angle[n] / (2 * PI);
        out->assembly[n] = teeth ? x : NAN;
        if (teeth && fabs(x - floor(x + 0.5)) > 1e-3) out->assembles = 0;
    }
    out->sun_teeth_per_planet = teeth && g->equally_spaced ? zs / g->nplanets : NAN;
}
