/* Pieces of the involute pair geometry shared by external pairs (gear_geometry.c) and
 * internal pairs (internal_geometry.c): the involute function and its inverse, one
 * external gear's radii with its checks (undercut, pointed tip, radii, bore), and the
 * path of contact's pitches and contact ratios ([JMSTHelical] Table 1). */
#include <math.h>
#include <stdio.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static const char *const GEAR_NAME[2] = {"driver", "driven"};

double gd_ms_involute(double a)
{
    return tan(a) - a;
}

/* Inverse of the involute function by Newton's method (monotone, convex on (0, pi/2)). */
double gd_ms_inverse_involute(double v)
{
    double a = cbrt(3.0 * v); /* inv(a) ~ a^3/3 for small a */
    if (a > 1.2) a = 1.2;
    for (int it = 0; it < 60; it++) {
        double t = tan(a);
        double step = (t - a - v) / (t * t);
        a -= step;
        if (a <= 0) a = 1e-6;
        if (fabs(step) < 1e-15) break;
    }
    return a;
}

gd_status gd_ms_geometry_fail(gd_error *err, const char *field, const char *hint, const char *msg)
{
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint, "%s", msg);
}

/* Radii, form circle, base half angle and bore of external gear i, with the checks
 * that make it physical (undercut, pointed tip, radii, bore). */
gd_status gd_ms_external_gear(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d, int i,
                              gd_error *err)
{
    char msg[400], hint[300], field[64];
    const double mn = g->normal_module, an = g->normal_pressure_angle, beta = g->helix_angle;
    const double at = d->transverse_pressure_angle;
    const gd_gear_geometry *w = &g->gear[i];
    const char *gn = GEAR_NAME[i];
    double r = d->pitch_radius[i], rb = d->base_radius[i];
    double ra = w->tip_radius > 0
                    ? w->tip_radius
                    : r + (w->addendum_coef + w->profile_shift - d->tip_shortening) * mn;
    double rf =
        w->root_radius > 0 ? w->root_radius : r - (w->dedendum_coef - w->profile_shift) * mn;
    d->tip_radius[i] = ra;
    d->root_radius[i] = rf;
    if (!(rf > 0) || !(ra > rf)) {
        snprintf(field, sizeof field, "%s.%s", gn, rf > 0 ? "tip_radius" : "root_radius");
        snprintf(msg, sizeof msg, "tip radius %.4g mm must exceed root radius %.4g mm > 0",
                 ra * 1e3, rf * 1e3);
        return gd_ms_geometry_fail(err, field, "check the radii and the dedendum coefficient", msg);
    }
    if (!(ra > rb * (1 + 1e-9))) {
        snprintf(field, sizeof field, "%s.tip_radius", gn);
        snprintf(msg, sizeof msg, "tip radius %.4g mm is not above the base radius %.4g mm",
                 ra * 1e3, rb * 1e3);
        return gd_ms_geometry_fail(err, field,
                                   "the tip must lie on the involute, above the base circle", msg);
    }
    /* Undercut: the rack's straight flank ends h = (h_fP* - rho*(1 - sin an)) m_n
     * below the datum line; the involute starts at roll length rho_F >= 0 only if
     * x >= h* - z sin^2(at) / (2 cos beta). */
    double hstar = w->dedendum_coef - w->fillet_radius_coef * (1 - sin(an));
    double xmin = hstar - w->teeth * sin(at) * sin(at) / (2 * cos(beta));
    if (w->profile_shift < xmin - 1e-9) {
        snprintf(field, sizeof field, "%s.profile_shift", gn);
        snprintf(msg, sizeof msg,
                 "%d teeth with profile shift %g are undercut: the profile shift must be at "
                 "least %.4f (without shift at least %.1f teeth)",
                 w->teeth, w->profile_shift, xmin, 2 * hstar * cos(beta) / (sin(at) * sin(at)));
        snprintf(hint, sizeof hint, "set %s.profile_shift to %.3f or more, or use more teeth", gn,
                 xmin);
        return gd_ms_geometry_fail(err, field, hint, msg);
    }
    double rho_f = r * sin(at) - (hstar - w->profile_shift) * mn / sin(at);
    if (rho_f < 0) rho_f = 0;
    if (rf > rb) {
        double rr = sqrt(rf * rf - rb * rb);
        if (rr > rho_f) rho_f = rr;
    }
    d->form_roll[i] = rho_f;
    /* half tooth angle on the base circle: s/(2r) + inv(at), s = m_t (pi/2 + 2 x tan an) */
    double a2 = (GD_MS_PI / 2 + 2 * w->profile_shift * tan(an)) / w->teeth + gd_ms_involute(at);
    d->half_angle_base[i] = a2;
    double aa = acos(rb / ra);
    if (a2 - gd_ms_involute(aa) <= 0) {
        snprintf(field, sizeof field, "%s.tip_radius", gn);
        snprintf(msg, sizeof msg, "the tooth comes to a point below the tip radius %.4g mm",
                 ra * 1e3);
        return gd_ms_geometry_fail(err, field,
                                   "reduce the tip radius, the addendum or the profile shift", msg);
    }
    double rbore = w->bore_radius > 0 ? w->bore_radius : 0.5 * rf; /* documented default */
    d->bore_radius[i] = rbore;
    if (!(rbore < rf - mn)) {
        snprintf(field, sizeof field, "%s.bore_radius", gn);
        snprintf(msg, sizeof msg,
                 "bore radius %.4g mm leaves a rim below one module under the root radius %.4g mm",
                 rbore * 1e3, rf * 1e3);
        return gd_ms_geometry_fail(err, field, "give a bore/hub radius below root radius - module",
                                   msg);
    }
    /* [Sainsot2004]'s fillet-foundation polynomials are fitted for 1.4 <= r_f / r_bore <= 7
     * and grow without bound past it (helical_pair1: r_bore 1e-4 m gives 988 N/m, 1e-100 m
     * zero, which the TVMS then reported as "a bug"): refused here, so the C API and the
     * model reader say the same (issue 38 M7). */
    if (!(rf / rbore <= 10.0)) {
        snprintf(field, sizeof field, "%s.bore_radius", gn);
        snprintf(msg, sizeof msg,
                 "bore radius %g m is below a tenth of the root radius %g m: the "
                 "fillet-foundation model [Sainsot2004] holds for root/bore radius ratios up to "
                 "about 7",
                 rbore, rf);
        return gd_ms_geometry_fail(err, field,
                                   "give the hub radius (at least a tenth of the root radius), or "
                                   "leave bore_radius out (half the root radius)",
                                   msg);
    }
    return GD_OK;
}

/* Path of contact, pitches, overlap and contact ratios of derived radii, and the checks
 * of the total contact ratio and the modifications; external and internal pairs. */
gd_status gd_ms_contact_ratios(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d,
                               gd_error *err)
{
    char msg[400];
    const double mn = g->normal_module, an = g->normal_pressure_angle, beta = g->helix_angle;
    const int z1 = g->gear[0].teeth, z2 = g->gear[1].teeth;
    const double rb1 = d->base_radius[0];
    d->pitch_point = rb1 * tan(d->working_pressure_angle);
    d->contact_length = d->contact_end - d->contact_start;
    d->base_pitch_transverse = 2 * GD_MS_PI * rb1 / z1;
    d->base_pitch_normal = GD_MS_PI * mn * cos(an);
    d->overlap_length = g->face_width * tan(d->base_helix_angle);
    d->contact_ratio_transverse = d->contact_length / d->base_pitch_transverse;
    d->contact_ratio_face = g->face_width * sin(beta) / (GD_MS_PI * mn);
    d->contact_ratio_total = d->contact_ratio_transverse + d->contact_ratio_face;
    d->mesh_period = 2 * GD_MS_PI / z1;
    d->ratio = (double)z2 / z1;
    if (d->contact_ratio_total < 1) {
        snprintf(msg, sizeof msg,
                 "total contact ratio %.4f (transverse %.4f + face %.4f) is below the limit 1: "
                 "contact would be lost between tooth pairs",
                 d->contact_ratio_total, d->contact_ratio_transverse, d->contact_ratio_face);
        return gd_ms_geometry_fail(
            err, "",
            "raise the addendum coefficients or tip radii, or the face width / helix angle", msg);
    }
    return gd_ms_mods_check(g, d, err);
}
