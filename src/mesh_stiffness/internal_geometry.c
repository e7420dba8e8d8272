/* Involute geometry of an internal pair: an external gear (planet, gear[0]) inside an
 * internal gear (ring, gear[1]), after ISO 21771 with the ring's tooth count taken as
 * negative, written here with positive counts (formulas in [KHK] Sec. 5.1 and
 * docs/mesh-stiffness.md, "Internal pairs"):
 *   a0 = (r2 - r1),  inv a_wt = inv a_t - 2 tan a_n (x1 + x2) / (z2 - z1),
 *   a = a0 cos a_t / cos a_wt,  r_a2 = r2 - (h_a* + x2) m_n,  r_f2 = r2 + (h_f* - x2) m_n,
 * x2 with the ISO sign (positive thickens the ring's teeth). Both base-circle tangent
 * points N1, N2 lie on the same side of the contact: with s measured from N1 toward the
 * pitch point C, the ring's roll length is s + N1N2 (N1N2 = a sin a_wt), and the path of
 * contact runs from the ring tip, s_A = sqrt(r_a2^2 - r_b2^2) - N1N2, to the planet tip,
 * s_E = sqrt(r_a1^2 - r_b1^2) (the internal-pair eps_alpha of [KHK] Sec. 5).
 * Interference checks ([KHK] Sec. 5.2): the ring tip outside its base circle, involute
 * interference (s_A outside the planet's base circle), the planet tip inside the
 * ring's form circle, trochoid interference ([KHK] Eq. (5-6)), and both tip clearances. */
#include <math.h>
#include <stdio.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

double gd_ms_ring_half_angle_base(const gd_gear_pair_geometry *g, double at)
{
    const gd_gear_geometry *w = &g->gear[1];
    /* the ring's tooth is the space of an external gear: half tooth angle at the
     * reference circle s/(2 r), s = m_t (pi/2 + 2 x tan a_n); toward the base circle it
     * narrows by inv(at) */
    return (GD_MS_PI / 2 + 2 * w->profile_shift * tan(g->normal_pressure_angle)) / w->teeth -
           gd_ms_involute(at);
}

static gd_status ring_radii(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d, gd_error *err)
{
    char msg[400], hint[300];
    const gd_gear_geometry *w = &g->gear[1];
    const double mn = g->normal_module, an = g->normal_pressure_angle;
    const double at = d->transverse_pressure_angle;
    const double r = d->pitch_radius[1], rb = d->base_radius[1];
    double ra = w->tip_radius > 0 ? w->tip_radius : r - (w->addendum_coef + w->profile_shift) * mn;
    double rf =
        w->root_radius > 0 ? w->root_radius : r + (w->dedendum_coef - w->profile_shift) * mn;
    d->tip_radius[1] = ra;
    d->root_radius[1] = rf;
    if (!(rf > ra)) {
        snprintf(msg, sizeof msg,
                 "the internal gear's root radius %.4g mm must exceed its tip radius %.4g mm "
                 "(its teeth point inward)",
                 rf * 1e3, ra * 1e3);
        return gd_ms_geometry_fail(err,
                                   w->root_radius > 0 ? "driven.root_radius" : "driven.tip_radius",
                                   "check the radii and the dedendum coefficient", msg);
    }
    if (!(ra > rb * (1 + 1e-9))) {
        /* the involute exists only outside the base circle: [KHK] Sec. 5.2 (a) */
        double xmax = (r - rb) / mn - w->addendum_coef;
        snprintf(msg, sizeof msg,
                 "involute interference: the internal gear's tip radius %.4g mm is not above its "
                 "base radius %.4g mm, so its tips have no involute",
                 ra * 1e3, rb * 1e3);
        snprintf(hint, sizeof hint,
                 "use more ring teeth, a ring profile shift of at most %.3f (ISO sign: negative "
                 "moves the tip outward) or a larger tip radius",
                 xmax);
        return gd_ms_geometry_fail(
            err, w->tip_radius > 0 ? "driven.tip_radius" : "driven.profile_shift", hint, msg);
    }
    /* form circle: end of the basic rack's straight flank (a shaper cutter generates a
     * slightly different one; the rack is the ISO 21771 approximation) */
    double hstar = w->dedendum_coef - w->fillet_radius_coef * (1 - sin(an));
    double rF = r + (hstar - w->profile_shift) * mn;
    if (rF > rf) rF = rf;
    d->form_roll[1] = sqrt(rF * rF - rb * rb);
    double b2 = gd_ms_ring_half_angle_base(g, at);
    d->half_angle_base[1] = b2;
    if (!(b2 + gd_ms_involute(acos(rb / ra)) > 0)) {
        snprintf(msg, sizeof msg,
                 "the internal gear's teeth come to a point outside its tip radius %.4g mm",
                 ra * 1e3);
        return gd_ms_geometry_fail(err, "driven.tip_radius",
                                   "enlarge the ring's tip radius or its profile shift", msg);
    }
    if (!(b2 + gd_ms_involute(acos(rb / rf)) < GD_MS_PI / w->teeth)) {
        snprintf(msg, sizeof msg,
                 "the internal gear's tooth spaces close before its root radius %.4g mm", rf * 1e3);
        return gd_ms_geometry_fail(err, "driven.root_radius",
                                   "reduce the ring's root radius or dedendum", msg);
    }
    double rim = w->bore_radius > 0 ? w->bore_radius : rf + 3 * mn; /* documented default */
    d->bore_radius[1] = rim;
    if (!(rim > rf + mn)) {
        snprintf(msg, sizeof msg,
                 "the internal gear's rim outer radius %.4g mm leaves less than one module "
                 "outside its root radius %.4g mm",
                 rim * 1e3, rf * 1e3);
        return gd_ms_geometry_fail(
            err, "driven.bore_radius",
            "for an internal gear bore_radius is the rim's outer radius: give "
            "one above root radius + module",
            msg);
    }
    return GD_OK;
}

/* [KHK] Eq. (5-6): theta1 z1/z2 + inv a_w - inv a_a2 >= theta2, the planet tip's
 * trochoid (relative to the ring) clearing the ring tip as the teeth leave contact. */
static double trochoid_margin(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d)
{
    double a = d->center_distance, ra1 = d->tip_radius[0], ra2 = d->tip_radius[1];
    double c1 = (ra2 * ra2 - ra1 * ra1 - a * a) / (2 * a * ra1);
    double c2 = (a * a + ra2 * ra2 - ra1 * ra1) / (2 * a * ra2);
    if (c1 < -1) c1 = -1;
    if (c1 > 1) c1 = 1;
    if (c2 < -1) c2 = -1;
    if (c2 > 1) c2 = 1;
    double inv_w = gd_ms_involute(d->working_pressure_angle);
    double th1 = acos(c1) + gd_ms_involute(acos(d->base_radius[0] / ra1)) - inv_w;
    double th2 = acos(c2);
    return th1 * g->gear[0].teeth / g->gear[1].teeth + inv_w -
           gd_ms_involute(acos(d->base_radius[1] / ra2)) - th2;
}

gd_status gd_ms_internal_derive(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d,
                                gd_error *err)
{
    char msg[400], hint[300];
    gd_status st;
    const double an = g->normal_pressure_angle;
    const double at = d->transverse_pressure_angle;
    const int z1 = g->gear[0].teeth, z2 = g->gear[1].teeth;
    const double x1 = g->gear[0].profile_shift, x2 = g->gear[1].profile_shift;
    d->internal = 1;
    if (z2 <= z1) {
        snprintf(msg, sizeof msg,
                 "the internal gear has %d teeth, not more than the %d of the gear inside it", z2,
                 z1);
        return gd_ms_geometry_fail(err, "driven.teeth",
                                   "an internal pair needs more ring teeth than pinion teeth (for "
                                   "20 deg pairs about 10 more, [KHK] Sec. 5.2)",
                                   msg);
    }
    const double a0 = d->pitch_radius[1] - d->pitch_radius[0];
    d->reference_center_distance = a0;
    double inv_w = gd_ms_involute(at) - 2.0 * tan(an) * (x1 + x2) / (z2 - z1);
    if (!(inv_w > 1e-9)) {
        snprintf(msg, sizeof msg,
                 "profile shifts %g + %g leave no working pressure angle for %d / %d teeth "
                 "(inv a_w = %.4g)",
                 x1, x2, z1, z2, inv_w);
        return gd_ms_geometry_fail(err, "driven.profile_shift",
                                   "reduce the sum of the profile shifts (ISO sign: positive "
                                   "thickens the ring's teeth)",
                                   msg);
    }
    double aw_shift = gd_ms_inverse_involute(inv_w);
    double a_shift = a0 * cos(at) / cos(aw_shift);
    double a = a_shift, aw = aw_shift;
    const double rbd = d->base_radius[1] - d->base_radius[0];
    if (g->center_distance > 0) {
        a = g->center_distance;
        /* the planet moves into the ring's teeth as a grows: a zero-backlash distance is
         * the largest one */
        if (a > a_shift * (1 + 1e-9)) {
            snprintf(msg, sizeof msg,
                     "centre distance %.6g mm is above %.6g mm, the zero-backlash distance of "
                     "this internal pair for profile shifts %g + %g: the teeth would jam",
                     a * 1e3, a_shift * 1e3, x1, x2);
            return gd_ms_geometry_fail(err, "center_distance",
                                       "reduce the centre distance or the profile shifts, or leave "
                                       "it out to derive it",
                                       msg);
        }
        if (!(a > rbd)) {
            snprintf(msg, sizeof msg,
                     "centre distance %.4g mm does not exceed the difference of the base radii "
                     "%.4g mm",
                     a * 1e3, rbd * 1e3);
            return gd_ms_geometry_fail(err, "center_distance",
                                       "leave it out to derive it from the profile shifts", msg);
        }
        aw = acos(rbd / a);
    }
    d->center_distance = a;
    d->working_pressure_angle = aw;
    d->tip_shortening = 0; /* not applied to internal pairs */
    if ((st = gd_ms_external_gear(g, d, 0, err))) return st;
    if ((st = ring_radii(g, d, err))) return st;

    const double ra1 = d->tip_radius[0], rf1 = d->root_radius[0];
    const double ra2 = d->tip_radius[1], rf2 = d->root_radius[1];
    d->tip_clearance[0] = rf2 - (a + ra1);
    d->tip_clearance[1] = (ra2 - a) - rf1;
    if (d->tip_clearance[0] < 0) {
        snprintf(msg, sizeof msg,
                 "negative tip clearance %.4g mm: the driver tip reaches %.4g mm from the ring's "
                 "centre, beyond the ring's root radius %.4g mm",
                 d->tip_clearance[0] * 1e3, (a + ra1) * 1e3, rf2 * 1e3);
        return gd_ms_geometry_fail(err, "driver.tip_radius",
                                   "reduce the driver's tip radius or enlarge the ring's dedendum",
                                   msg);
    }
    if (d->tip_clearance[1] < 0) {
        snprintf(msg, sizeof msg,
                 "negative tip clearance %.4g mm: the ring's tip (%.4g mm) reaches below the "
                 "driver's root circle (limit: ring tip radius >= %.4g mm)",
                 d->tip_clearance[1] * 1e3, ra2 * 1e3, (a + rf1) * 1e3);
        return gd_ms_geometry_fail(err, "driven.tip_radius",
                                   "enlarge the ring's tip radius or reduce the driver's dedendum",
                                   msg);
    }
    const double rb1 = d->base_radius[0], rb2 = d->base_radius[1];
    const double L = a * sin(aw);
    d->line_of_action = L;
    d->contact_end = sqrt(ra1 * ra1 - rb1 * rb1);
    d->contact_start = sqrt(ra2 * ra2 - rb2 * rb2) - L;
    /* [KHK] Sec. 5.2 (a): the ring's tip must meet the driver on its involute, outside
     * its base circle (the rack-cut driver's form circle lies a little above: a contact
     * between them is reported by contact_start < form_roll[0], not refused) */
    if (d->contact_start < 1e-12 * L) {
        snprintf(msg, sizeof msg,
                 "involute interference: the ring's tip meets the driver %.4g mm inside its "
                 "base circle ([KHK] Sec. 5.2 (a): z1/z2 >= 1 - tan a_a2 / tan a_w)",
                 -d->contact_start * 1e3);
        snprintf(hint, sizeof hint,
                 "reduce the ring's addendum (larger ring tip radius), use more ring teeth, or "
                 "give the driver a positive profile shift");
        return gd_ms_geometry_fail(err, "driven.tip_radius", hint, msg);
    }
    if (d->contact_end + L > d->form_roll[1] + 1e-12) {
        snprintf(msg, sizeof msg,
                 "tip interference: the driver's tip meets the ring %.4g mm from its base circle, "
                 "beyond the ring's usable involute that ends at %.4g mm",
                 (d->contact_end + L) * 1e3, d->form_roll[1] * 1e3);
        return gd_ms_geometry_fail(err, "driver.tip_radius",
                                   "reduce the driver's tip radius or addendum", msg);
    }
    d->trochoid_margin = trochoid_margin(g, d);
    if (d->trochoid_margin < 0) {
        snprintf(msg, sizeof msg,
                 "trochoid interference ([KHK] Eq. 5-6, margin %.4g rad < 0): the driver's tips "
                 "cut into the ring's tips as %d / %d teeth leave contact",
                 d->trochoid_margin, z1, z2);
        return gd_ms_geometry_fail(err, "driven.teeth",
                                   "use at least about 10 more ring teeth than driver teeth, or "
                                   "a ring profile shift that moves its tip outward (negative, "
                                   "ISO sign)",
                                   msg);
    }
    return gd_ms_contact_ratios(g, d, err);
}
