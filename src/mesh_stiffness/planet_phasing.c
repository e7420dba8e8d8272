/* Mesh phasing of a planetary set ([ParkerLin2004]): the phases of the sun-planet and
 * ring-planet meshes between planets, from the tooth counts and planet angles, and the
 * phase between a planet's ring and sun meshes, from the geometry of both meshes.
 * Derivation in docs/mesh-stiffness.md, "Planet mesh phasing". */
#include <math.h>
#include <stdio.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

/* frac(v) in [0, 1), with values within 1e-9 of a whole number taken as 0 (angles such
 * as 2 pi k / N carry rounding) */
static double frac01(double v)
{
    double f = v - floor(v);
    if (f > 1 - 1e-9 || f < 1e-9) f = 0;
    return f;
}

gd_status gd_planet_mesh_phases(int sun_teeth, int ring_teeth, int planets, const double *psi,
                                int sun_direction, double *gamma_s, double *gamma_r, gd_error *err)
{
    char field[64];
    if (sun_teeth < 5)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "sun_teeth", "give at least 5 teeth",
                            "sun tooth count %d is below 5", sun_teeth);
    if (ring_teeth <= sun_teeth + 9)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "ring_teeth",
                            "the ring needs the sun's teeth plus twice the planet's",
                            "ring tooth count %d leaves no room for planets around a %d-tooth sun",
                            ring_teeth, sun_teeth);
    if (planets < 1 || !psi)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "planet_angles", "give one angle per planet",
                            "no planets given");
    if (sun_direction != 1 && sun_direction != -1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "sun_direction",
                            "+1: the sun turns counterclockwise relative to the carrier, -1: "
                            "clockwise",
                            "sun direction %d is not +1 or -1", sun_direction);
    const double zsum = sun_teeth + ring_teeth;
    for (int n = 0; n < planets; n++) {
        double p = psi[n];
        snprintf(field, sizeof field, "planet_angles[%d]", n);
        if (!isfinite(p))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, field, "give a finite angle",
                                "planet angle is not a number");
        /* a planet meshes with both sun and ring only where (Z_s + Z_r) psi / 2 pi is whole
         * ([ParkerLin2004]: then gamma_s = gamma_r) */
        double k = zsum * p / (2 * GD_MS_PI);
        if (fabs(k - nearbyint(k)) > 1e-6) {
            double near = 2 * GD_MS_PI * nearbyint(k) / zsum;
            char hint[200];
            snprintf(hint, sizeof hint,
                     "planets assemble at multiples of 360/(Z_s + Z_r) = %.6g deg: the nearest is "
                     "%.6g deg",
                     360.0 / zsum, near * 180 / GD_MS_PI);
            return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint,
                                "a planet at %.6g deg cannot be assembled with %d sun and %d ring "
                                "teeth ((Z_s + Z_r) psi / 360 deg = %.6g is not whole)",
                                p * 180 / GD_MS_PI, sun_teeth, ring_teeth, k);
        }
        double t = p / (2 * GD_MS_PI);
        if (gamma_s) gamma_s[n] = frac01(sun_direction * sun_teeth * t);
        if (gamma_r) gamma_r[n] = frac01(-sun_direction * ring_teeth * t);
    }
    return GD_OK;
}

static gd_status pair_error(gd_error *err, const char *which, gd_status st)
{
    char f[sizeof err->field];
    snprintf(f, sizeof f, "%s%s%.100s", which, err->field[0] ? "." : "", err->field);
    snprintf(err->field, sizeof err->field, "%s", f);
    return st;
}

static gd_status mismatch(gd_error *err, const char *field, const char *what, double a, double b)
{
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field,
                        "the sun-planet and ring-planet meshes share the planet and the carrier",
                        "%s differs between the sun-planet (%.6g) and ring-planet (%.6g) meshes",
                        what, a, b);
}

gd_status gd_planet_sun_ring_phase(const gd_gear_pair_geometry *sp, const gd_gear_pair_geometry *rp,
                                   double *gamma_rs, gd_error *err)
{
    gd_gear_pair_derived ds, dr;
    gd_status st;
    if (sp->internal)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "sun_planet.internal",
                            "the sun-planet mesh is external", "the sun-planet mesh is internal");
    if (!rp->internal)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "ring_planet.internal",
                            "set internal on the ring-planet mesh (the ring is its driven gear)",
                            "the ring-planet mesh is not internal");
    if ((st = gd_gear_pair_derive(sp, &ds, err))) return pair_error(err, "sun_planet", st);
    if ((st = gd_gear_pair_derive(rp, &dr, err))) return pair_error(err, "ring_planet", st);
    const gd_gear_geometry *ps = &sp->gear[1], *pr = &rp->gear[0];
    if (ps->teeth != pr->teeth)
        return mismatch(err, "ring_planet.driver.teeth", "the planet's tooth count", ps->teeth,
                        pr->teeth);
    if (fabs(ps->profile_shift - pr->profile_shift) > 1e-9)
        return mismatch(err, "ring_planet.driver.profile_shift", "the planet's profile shift",
                        ps->profile_shift, pr->profile_shift);
    if (fabs(sp->normal_module - rp->normal_module) > 1e-9 * sp->normal_module)
        return mismatch(err, "ring_planet.normal_module", "the normal module", sp->normal_module,
                        rp->normal_module);
    if (fabs(sp->normal_pressure_angle - rp->normal_pressure_angle) > 1e-9)
        return mismatch(err, "ring_planet.normal_pressure_angle", "the normal pressure angle",
                        sp->normal_pressure_angle, rp->normal_pressure_angle);
    if (fabs(sp->helix_angle - rp->helix_angle) > 1e-9)
        return mismatch(err, "ring_planet.helix_angle", "the helix angle", sp->helix_angle,
                        rp->helix_angle);
    /* the carrier radius: within a micrometre per metre (the shifts set both) */
    if (fabs(ds.center_distance - dr.center_distance) > 1e-6 * ds.center_distance)
        return gd_error_set(
            err, GD_EINPUT, "", 0, 0, "ring_planet.center_distance",
            "choose profile shifts (or centre distances) that give both meshes the "
            "same centre distance",
            "the sun-planet centre distance %.6g mm and the ring-planet one %.6g mm "
            "differ: the planet cannot sit on one carrier radius",
            ds.center_distance * 1e3, dr.center_distance * 1e3);
    const double zp = pr->teeth, at = ds.transverse_pressure_angle;
    double v = 0.5 * (zp - 1) +
               (zp * (gd_ms_involute(ds.working_pressure_angle) +
                      gd_ms_involute(dr.working_pressure_angle) - 2 * gd_ms_involute(at)) -
                4 * pr->profile_shift * tan(sp->normal_pressure_angle)) /
                   (2 * GD_MS_PI);
    *gamma_rs = frac01(v);
    return GD_OK;
}
