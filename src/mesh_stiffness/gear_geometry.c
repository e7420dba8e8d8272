/* Involute geometry of a spur or helical pair: transverse quantities, working pressure
 * angle, tip/root radii, path of contact and contact ratios, with the checks that make
 * a pair physical (undercut, pointed tip, interference, clearance, contact ratio).
 * Contact ratio definitions as in [JMSTHelical] Table 1: eps_alpha = g_alpha / p_bt and
 * eps_beta = b sin(beta) / (pi m_n), with normal module and normal pressure angle. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static const char *const GEAR_NAME[2] = {"driver", "driven"};

void gd_gear_pair_geometry_init(gd_gear_pair_geometry *g)
{
    memset(g, 0, sizeof *g);
    for (int i = 0; i < 2; i++) {
        gd_gear_geometry *w = &g->gear[i];
        w->addendum_coef = 1.0;
        w->dedendum_coef = 1.25;
        w->fillet_radius_coef = 0.38; /* ISO 53 profile A */
        w->E = 2.06e11;
        w->poisson = 0.3;
    }
    g->normal_pressure_angle = 20.0 * GD_MS_PI / 180.0;
    g->hand = 1;
}

static gd_status check_inputs(const gd_gear_pair_geometry *g, gd_error *err)
{
    char msg[400], hint[300], field[64];
    const double deg = GD_MS_PI / 180.0;
    if (!(g->normal_module > 0))
        return gd_ms_geometry_fail(err, "normal_module", "give the normal module, e.g. \"2 mm\"",
                                   "normal module must be positive");
    /* ship and mill gears reach 50 mm; past 1 m the lengths are not gears */
    if (g->normal_module > 1.0) {
        snprintf(msg, sizeof msg, "normal module %g m is over 1 m", g->normal_module);
        return gd_ms_geometry_fail(
            err, "normal_module",
            "give the module in length units, e.g. \"2 mm\" (the largest gears have "
            "about 50 mm)",
            msg);
    }
    if (!(g->normal_pressure_angle > 0 && g->normal_pressure_angle < 45 * deg)) {
        double a = g->normal_pressure_angle;
        if (a >= 1 && a <= 45)
            snprintf(hint, sizeof hint,
                     "angles are in rad unless a unit is given: did you mean '%g deg'?", a);
        else
            snprintf(hint, sizeof hint, "give a value between 0 and 45 deg, e.g. \"20 deg\"");
        snprintf(msg, sizeof msg, "normal pressure angle %g rad is outside (0, 45 deg)", a);
        return gd_ms_geometry_fail(err, "normal_pressure_angle", hint, msg);
    }
    if (!(g->helix_angle >= 0 && g->helix_angle < 45 * deg)) {
        double a = g->helix_angle;
        if (a >= 1 && a < 45)
            snprintf(hint, sizeof hint,
                     "angles are in rad unless a unit is given: did you mean '%g deg'?", a);
        else
            snprintf(hint, sizeof hint,
                     "give a value from 0 (spur) up to 45 deg; the hand is given by 'hand'");
        snprintf(msg, sizeof msg, "helix angle %g rad is outside [0, 45 deg)", a);
        return gd_ms_geometry_fail(err, "helix_angle", hint, msg);
    }
    if (!(g->face_width > 0))
        return gd_ms_geometry_fail(err, "face_width", "give the face width, e.g. \"20 mm\"",
                                   "face width must be positive");
    /* the widest gears are about 60 modules wide (ISO 6336 b/m_n); 1000 modules leaves
     * room for any real face and keeps the slices and their stiffness sums finite (a
     * face of 1e300 m made every slice's stiffness 0, issue 23) */
    if (g->face_width > 1000 * g->normal_module) {
        snprintf(msg, sizeof msg, "face width %g m is over 1000 normal modules (%g m)",
                 g->face_width, 1000 * g->normal_module);
        return gd_ms_geometry_fail(
            err, "face_width",
            "give the face width in length units (e.g. \"20 mm\"); real gears are up "
            "to about 60 modules wide",
            msg);
    }
    if (g->hand != 1 && g->hand != -1)
        return gd_ms_geometry_fail(err, "hand", "use right or left",
                                   "hand must be right (+1) or left (-1)");
    if (!(g->center_distance >= 0))
        return gd_ms_geometry_fail(err, "center_distance",
                                   "give a positive centre distance or leave it out",
                                   "centre distance must not be negative");
    for (int i = 0; i < 2; i++) {
        const gd_gear_geometry *w = &g->gear[i];
        const char *gn = GEAR_NAME[i];
        if (w->teeth < 5) {
            snprintf(field, sizeof field, "%s.teeth", gn);
            snprintf(msg, sizeof msg, "%d teeth is below the limit of 5", w->teeth);
            return gd_ms_geometry_fail(err, field, "give the number of teeth (at least 5)", msg);
        }
        if (!(w->addendum_coef > 0 && w->addendum_coef <= 2)) {
            snprintf(field, sizeof field, "%s.addendum_coef", gn);
            snprintf(msg, sizeof msg, "addendum coefficient %g is outside (0, 2]",
                     w->addendum_coef);
            return gd_ms_geometry_fail(err, field,
                                       "the standard value is 1.0 (times the normal module)", msg);
        }
        if (!(w->dedendum_coef > 0 && w->dedendum_coef <= 2.5)) {
            snprintf(field, sizeof field, "%s.dedendum_coef", gn);
            snprintf(msg, sizeof msg, "dedendum coefficient %g is outside (0, 2.5]",
                     w->dedendum_coef);
            return gd_ms_geometry_fail(err, field,
                                       "the standard value is 1.25 (times the normal module)", msg);
        }
        if (!(w->fillet_radius_coef >= 0 && w->fillet_radius_coef < 0.6)) {
            snprintf(field, sizeof field, "%s.fillet_radius_coef", gn);
            snprintf(msg, sizeof msg, "rack tip fillet coefficient %g is outside [0, 0.6)",
                     w->fillet_radius_coef);
            return gd_ms_geometry_fail(err, field, "the ISO 53 profile A value is 0.38", msg);
        }
        if (!(fabs(w->profile_shift) <= 2)) {
            snprintf(field, sizeof field, "%s.profile_shift", gn);
            snprintf(msg, sizeof msg, "profile shift %g is outside [-2, 2]", w->profile_shift);
            return gd_ms_geometry_fail(
                err, field, "profile shift is a coefficient of the module, typically -0.5..1", msg);
        }
        if (!(w->E > 0) || !(w->poisson > -1 && w->poisson < 0.5)) {
            snprintf(field, sizeof field, "%s.material", gn);
            return gd_ms_geometry_fail(err, field,
                                       "give E > 0 and a Poisson ratio between -1 and 0.5",
                                       "material is not physical");
        }
        if (!(w->tip_radius >= 0) || !(w->root_radius >= 0) || !(w->bore_radius >= 0)) {
            snprintf(field, sizeof field, "%s.%s", gn,
                     !(w->tip_radius >= 0)    ? "tip_radius"
                     : !(w->root_radius >= 0) ? "root_radius"
                                              : "bore_radius");
            return gd_ms_geometry_fail(err, field,
                                       "give a positive radius or leave it out to derive it",
                                       "radius must not be negative");
        }
    }
    return GD_OK;
}

gd_status gd_gear_pair_derive(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d,
                              gd_error *err)
{
    gd_status st = check_inputs(g, err);
    if (st) return st;
    memset(d, 0, sizeof *d);
    char msg[400], field[64];
    const double mn = g->normal_module, an = g->normal_pressure_angle, beta = g->helix_angle;
    const double mt = mn / cos(beta);
    const double at = atan(tan(an) / cos(beta));
    const int z1 = g->gear[0].teeth, z2 = g->gear[1].teeth;
    const double x1 = g->gear[0].profile_shift, x2 = g->gear[1].profile_shift;
    d->transverse_module = mt;
    d->transverse_pressure_angle = at;
    d->base_helix_angle = atan(tan(beta) * cos(at));
    for (int i = 0; i < 2; i++) {
        d->pitch_radius[i] = 0.5 * g->gear[i].teeth * mt;
        d->base_radius[i] = d->pitch_radius[i] * cos(at);
    }
    if (g->internal) return gd_ms_internal_derive(g, d, err);
    const double a0 = d->pitch_radius[0] + d->pitch_radius[1];
    d->reference_center_distance = a0;
    /* zero-backlash working pressure angle from the shifts */
    double inv_w = gd_ms_involute(at) + 2.0 * tan(an) * (x1 + x2) / (z1 + z2);
    double aw_shift = gd_ms_inverse_involute(inv_w);
    double a_shift = a0 * cos(at) / cos(aw_shift);
    double a = a_shift, aw = aw_shift;
    if (g->center_distance > 0) {
        a = g->center_distance;
        if (a <= d->base_radius[0] + d->base_radius[1]) {
            snprintf(msg, sizeof msg,
                     "centre distance %.4g mm does not exceed the sum of base radii %.4g mm",
                     a * 1e3, (d->base_radius[0] + d->base_radius[1]) * 1e3);
            return gd_ms_geometry_fail(err, "center_distance",
                                       "leave it out to derive it from the profile shifts", msg);
        }
        if (a < a_shift * (1 - 1e-9)) {
            snprintf(msg, sizeof msg,
                     "centre distance %.6g mm is below %.6g mm, the zero-backlash distance for "
                     "profile shifts %g + %g: the teeth would jam",
                     a * 1e3, a_shift * 1e3, x1, x2);
            return gd_ms_geometry_fail(err, "center_distance",
                                       "enlarge the centre distance or reduce the profile shifts",
                                       msg);
        }
        aw = acos(a0 * cos(at) / a);
    }
    d->center_distance = a;
    d->working_pressure_angle = aw;
    double k = (x1 + x2) - (a - a0) / mn; /* tip shortening keeps the standard clearance */
    d->tip_shortening = k > 0 ? k : 0;

    for (int i = 0; i < 2; i++)
        if ((st = gd_ms_external_gear(g, d, i, err))) return st;
    for (int i = 0; i < 2; i++) {
        d->tip_clearance[i] = a - d->tip_radius[i] - d->root_radius[1 - i];
        if (d->tip_clearance[i] < 0) {
            snprintf(field, sizeof field, "%s.tip_radius", GEAR_NAME[i]);
            snprintf(msg, sizeof msg,
                     "negative tip clearance %.4g mm: the %s tip (%.4g mm) reaches below the %s "
                     "root circle (limit: tip radius <= %.4g mm)",
                     d->tip_clearance[i] * 1e3, GEAR_NAME[i], d->tip_radius[i] * 1e3,
                     GEAR_NAME[1 - i], (a - d->root_radius[1 - i]) * 1e3);
            return gd_ms_geometry_fail(
                err, field,
                "reduce the tip radius or the other gear's dedendum, or enlarge the centre "
                "distance",
                msg);
        }
    }
    const double N1N2 = a * sin(aw);
    const double rb1 = d->base_radius[0], rb2 = d->base_radius[1];
    d->line_of_action = N1N2;
    d->contact_end = sqrt(d->tip_radius[0] * d->tip_radius[0] - rb1 * rb1);
    d->contact_start = N1N2 - sqrt(d->tip_radius[1] * d->tip_radius[1] - rb2 * rb2);
    if (d->contact_start < d->form_roll[0] - 1e-12) {
        snprintf(msg, sizeof msg,
                 "tip interference: the driven tip meets the driver %.4g mm from its base circle, "
                 "below the usable involute that starts at %.4g mm",
                 d->contact_start * 1e3, d->form_roll[0] * 1e3);
        return gd_ms_geometry_fail(
            err, "driven.tip_radius",
            "reduce the driven tip radius or addendum, or give the driver a positive profile shift",
            msg);
    }
    if (N1N2 - d->contact_end < d->form_roll[1] - 1e-12) {
        snprintf(msg, sizeof msg,
                 "tip interference: the driver tip meets the driven gear %.4g mm from its base "
                 "circle, below the usable involute that starts at %.4g mm",
                 (N1N2 - d->contact_end) * 1e3, d->form_roll[1] * 1e3);
        return gd_ms_geometry_fail(
            err, "driver.tip_radius",
            "reduce the driver tip radius or addendum, or give the driven gear a positive "
            "profile shift",
            msg);
    }
    return gd_ms_contact_ratios(g, d, err);
}
