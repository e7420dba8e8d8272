/* Planetary mesh phasing ([ParkerLin2004], docs/mesh-stiffness.md "Planet mesh
 * phasing"): phases between planets, the phasing classes of the Drivetrain Hub
 * examples ([DrivetrainHubPlanetary]), the sums of Parker's mode-suppression rule
 * ([Parker2000]), the assembly condition, and the sun-ring phase of a planet. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "geardyn/mesh_stiffness.h"
#include "harness.h"

static const double PI = 3.14159265358979323846;

static void equal_angles(int n, double *psi)
{
    for (int k = 0; k < n; k++)
        psi[k] = 2 * PI * k / n;
}

/* |sum_n exp(i 2 pi l gamma_n) exp(i q psi_n)| */
static double phase_sum(const double *gamma, const double *psi, int n, int l, int q)
{
    double complex s = 0;
    for (int k = 0; k < n; k++)
        s += cexp(I * (2 * PI * l * gamma[k] + q * psi[k]));
    return cabs(s);
}

TEST(equally_spaced_in_phase)
{
    /* Z_s / N and Z_r / N whole: every mesh in phase with planet 0 */
    double psi[4], gs[4], gr[4];
    gd_error err;
    equal_angles(4, psi);
    REQUIRE(gd_planet_mesh_phases(24, 72, 4, psi, 1, gs, gr, &err) == GD_OK);
    for (int k = 0; k < 4; k++) {
        CHECK_ABS(gs[k], 0, 1e-12);
        CHECK_ABS(gr[k], 0, 1e-12);
    }
    /* 3 planets, Z_s = 22: gamma_s = frac(22 k / 3) = 0, 1/3, 2/3; the ring the opposite
     * sign: Z_r = 68, frac(-68 k / 3) = 0, 1/3, 2/3 (assembly makes them equal) */
    double p3[3], s3[3], r3[3];
    equal_angles(3, p3);
    REQUIRE(gd_planet_mesh_phases(22, 68, 3, p3, 1, s3, r3, &err) == GD_OK);
    CHECK_ABS(s3[1], 1.0 / 3, 1e-12);
    CHECK_ABS(s3[2], 2.0 / 3, 1e-12);
    for (int k = 0; k < 3; k++)
        CHECK_ABS(r3[k], s3[k], 1e-12);
    /* clockwise sun: the phases change sign */
    REQUIRE(gd_planet_mesh_phases(22, 68, 3, p3, -1, s3, r3, &err) == GD_OK);
    CHECK_ABS(s3[1], 2.0 / 3, 1e-12);
    CHECK_ABS(s3[2], 1.0 / 3, 1e-12);
}

/* [DrivetrainHubPlanetary] "Phasing types" with equally spaced planets, k = Z_r mod N:
 * (N, Z_r, Z_s) = (4, 48, 16) in-phase (torque reinforced, radial forces cancelled),
 * (4, 51, 17) sequential-phase (torque cancelled, forces reinforced), (4, 54, 18) and
 * (5, 52, 18) counter-phase (both cancelled); their metrics: torque |sum e^{i phi}| / N,
 * forces |sum cos(psi) e^{i phi}| / (N/2) + |sum sin(psi) e^{i phi}| / (N/2). */
TEST(drivetrain_hub_phasing_types)
{
    static const struct {
        int n, zr, zs;
        double torque, force;
    } cases[] = {{4, 48, 16, 1, 0}, {4, 51, 17, 0, 2}, {4, 54, 18, 0, 0}, {5, 52, 18, 0, 0}};
    for (int c = 0; c < 4; c++) {
        int n = cases[c].n;
        double psi[5], gr[5], gs[5];
        gd_error err;
        equal_angles(n, psi);
        REQUIRE(gd_planet_mesh_phases(cases[c].zs, cases[c].zr, n, psi, 1, gs, gr, &err) == GD_OK);
        double complex t = 0, fx = 0, fy = 0;
        for (int k = 0; k < n; k++) {
            double complex e = cexp(I * 2 * PI * gr[k]);
            t += e;
            fx += cos(psi[k]) * e;
            fy += sin(psi[k]) * e;
        }
        CHECK_ABS(cabs(t) / n, cases[c].torque, 1e-12);
        CHECK_ABS((cabs(fx) + cabs(fy)) / (0.5 * n), cases[c].force, 1e-12);
        /* the sun meshes (assembled: the same phases) classify alike */
        for (int k = 0; k < n; k++)
            CHECK_ABS(gs[k], gr[k], 1e-12);
    }
}

/* [Parker2000]: with N equally spaced planets, mesh harmonic l reaches the rotational
 * modes only when l Z_s / N is whole (sum_n exp(i 2 pi l gamma_sn) = N, else 0), the
 * translational modes only when (l Z_s +- 1) / N is (sum_n exp(i 2 pi l gamma_sn)
 * exp(+-i psi_n) = N, else 0), otherwise only the planet modes. */
TEST(parker_suppression_sums)
{
    static const int sets[][3] = {{31, 89, 5}, {24, 72, 4}, {25, 71, 4}, {20, 70, 3}, {19, 71, 6}};
    for (int c = 0; c < 5; c++) {
        int zs = sets[c][0], zr = sets[c][1], n = sets[c][2];
        double psi[6], gs[6], gr[6];
        gd_error err;
        equal_angles(n, psi);
        REQUIRE(gd_planet_mesh_phases(zs, zr, n, psi, 1, gs, gr, &err) == GD_OK);
        for (int l = 1; l <= 30; l++) {
            int rot = (l * zs) % n == 0;
            int tp = (l * zs + 1) % n == 0, tm = (l * zs - 1) % n == 0;
            CHECK_ABS(phase_sum(gs, psi, n, l, 0), rot ? n : 0, 1e-9);
            CHECK_ABS(phase_sum(gs, psi, n, l, 1), tp ? n : 0, 1e-9);
            CHECK_ABS(phase_sum(gs, psi, n, l, -1), tm ? n : 0, 1e-9);
            /* the ring meshes obey the same rule with Z_r (the phases are equal) */
            CHECK_ABS(phase_sum(gr, psi, n, l, 0), (l * zr) % n == 0 ? n : 0, 1e-9);
            /* for N >= 3 at most one class is excited */
            if (n >= 3) CHECK(rot + tp + tm <= 1);
        }
    }
}

TEST(assembly_and_input_errors)
{
    gd_error err;
    double psi[2] = {0, 100 * PI / 180}, g[2];
    /* 360 / (24 + 72) = 3.75 deg: 100 deg cannot be assembled, 101.25 deg can */
    CHECK(gd_planet_mesh_phases(24, 72, 2, psi, 1, g, g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "planet_angles[1]");
    CHECK(strstr(err.hint, "101.25 deg") != NULL);
    psi[1] = 101.25 * PI / 180;
    CHECK(gd_planet_mesh_phases(24, 72, 2, psi, 1, g, NULL, &err) == GD_OK);
    CHECK_ABS(g[1], 0.75, 1e-9); /* frac(24 * 101.25 / 360) = frac(6.75) */
    CHECK(gd_planet_mesh_phases(24, 30, 2, psi, 1, g, g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "ring_teeth");
    CHECK(gd_planet_mesh_phases(24, 72, 0, psi, 1, g, g, &err) == GD_EINPUT);
    CHECK(gd_planet_mesh_phases(24, 72, 2, psi, 0, g, g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "sun_direction");
    psi[1] = NAN;
    CHECK(gd_planet_mesh_phases(24, 72, 2, psi, 1, g, g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "planet_angles[1]");
}

/* sun (driver) - planet and planet (driver) - ring (internal) meshes of one set */
static void set_meshes(gd_gear_pair_geometry *sp, gd_gear_pair_geometry *rp, int zs, int zp, int zr)
{
    gd_gear_pair_geometry_init(sp);
    gd_gear_pair_geometry_init(rp);
    sp->normal_module = rp->normal_module = 2e-3;
    sp->face_width = rp->face_width = 0.02;
    sp->gear[0].teeth = zs;
    sp->gear[1].teeth = zp;
    rp->gear[0].teeth = zp;
    rp->gear[1].teeth = zr;
    rp->internal = 1;
}

TEST(sun_ring_phase)
{
    gd_gear_pair_geometry sp, rp;
    gd_error err;
    double g = -1;
    /* without profile shifts the phase is the planet tooth count's parity: across the
     * planet a tooth faces a tooth (odd count: a space faces a tooth, and the two meshes
     * use opposite flanks) */
    set_meshes(&sp, &rp, 25, 23, 71);
    REQUIRE(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_OK);
    CHECK_ABS(g, 0, 1e-12);
    set_meshes(&sp, &rp, 24, 24, 72);
    REQUIRE(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_OK);
    CHECK_ABS(g, 0.5, 1e-12);
    /* a planet shifted by x_p with sun and ring shifted by -x_p keeps both working
     * angles at 20 deg; its teeth are thicker by 2 x_p m tan 20 deg on the (common)
     * pitch circle, so the sun-side flank reaches its pitch point later and the
     * ring-side flank earlier, each by x_p m tan 20 deg of the pitch pi m: gamma_rs falls
     * by 2 x_p tan 20 deg / pi */
    for (int k = 1; k <= 3; k++) {
        double xp = 0.1 * k;
        set_meshes(&sp, &rp, 25, 23, 71);
        sp.gear[1].profile_shift = rp.gear[0].profile_shift = xp;
        sp.gear[0].profile_shift = rp.gear[1].profile_shift = -xp;
        REQUIRE(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_OK);
        double want = 1 - 2 * xp * tan(20 * PI / 180) / PI;
        CHECK_ABS(g, want, 1e-9);
    }
    /* shifts that move the working angles: the pitch points move along both lines of
     * action; gamma_rs from the closed form with the working angles */
    set_meshes(&sp, &rp, 25, 23, 71);
    sp.gear[0].profile_shift = 0.2; /* the sun: a_ws up; the ring's x -0.2 keeps a */
    rp.gear[1].profile_shift = -0.2;
    gd_gear_pair_derived ds, dr;
    REQUIRE(gd_gear_pair_derive(&sp, &ds, &err) == GD_OK);
    REQUIRE(gd_gear_pair_derive(&rp, &dr, &err) == GD_OK);
    CHECK_REL(ds.center_distance, dr.center_distance, 1e-12); /* both 48.388 mm */
    REQUIRE(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_OK);
    double inv_s = tan(ds.working_pressure_angle) - ds.working_pressure_angle;
    double inv_r = tan(dr.working_pressure_angle) - dr.working_pressure_angle;
    double inv_t = tan(20 * PI / 180) - 20 * PI / 180;
    double v = 11 + 23 * (inv_s + inv_r - 2 * inv_t) / (2 * PI);
    CHECK_ABS(g, v - floor(v), 1e-12);
    CHECK(g > 0.01); /* the working angles moved the pitch points */
    /* without the ring's shift the carrier radii differ: a located error */
    rp.gear[1].profile_shift = 0;
    CHECK(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "ring_planet.center_distance");
    /* mismatched planets and wrong mesh kinds are located */
    set_meshes(&sp, &rp, 25, 23, 71);
    rp.gear[0].teeth = 24;
    CHECK(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "ring_planet.driver.teeth");
    set_meshes(&sp, &rp, 25, 23, 71);
    rp.internal = 0;
    CHECK(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "ring_planet.internal");
    set_meshes(&sp, &rp, 25, 23, 71);
    rp.gear[1].teeth = 30; /* the ring's tip inside its base circle */
    rp.gear[0].teeth = 23;
    CHECK(gd_planet_sun_ring_phase(&sp, &rp, &g, &err) == GD_EINPUT);
    CHECK(strncmp(err.field, "ring_planet.", 12) == 0);
}

/* gamma_rs by a kinematic construction in Cartesian coordinates, independent of the
 * closed form's flank bookkeeping: the planet (centre at the origin, the set's centre
 * at (-a, 0)) has its tooth flanks built point by point as involutes unwound from the
 * base circle; for each mesh the contacting flank is the one whose outward normal at the
 * pitch point is the direction the mating tooth pushes (from the drive: the sun turning
 * counterclockwise pushes the planet at P_s = (-r_ws, 0) along (sin a_ws, cos a_ws); the
 * planet pushes the ring at P_r = (r_wr, 0) along (sin a_wr, -cos a_wr)); the planet turns
 * clockwise, so the event of a mesh is when its flank's pitch-circle point, rotated,
 * reaches the pitch point, and the lag is the difference of those times in periods. */
static double flank_crossing(double rb, double phi0, int side, double rw, double *nx, double *ny)
{
    /* side +1: unwinds clockwise from phi0 (tooth's counterclockwise flank), -1 the other */
    double u = sqrt((rw / rb) * (rw / rb) - 1);
    double qx[3], qy[3];
    for (int j = 0; j < 3; j++) {
        double uu = u + (j - 1) * 1e-6, tau = phi0 - side * uu;
        /* point of the string of length rb uu from the tangent point tau */
        qx[j] = rb * (cos(tau) - side * uu * sin(tau));
        qy[j] = rb * (sin(tau) + side * uu * cos(tau));
    }
    /* tangent by central difference; the outward normal points away from the tooth:
     * toward increasing polar angle for side +1 */
    double tx = qx[2] - qx[0], ty = qy[2] - qy[0], n = hypot(tx, ty);
    double mx = -ty / n, my = tx / n; /* tangent turned counterclockwise */
    double ex = -qy[1], ey = qx[1];   /* counterclockwise direction at the point */
    if ((mx * ex + my * ey) * side < 0) mx = -mx, my = -my;
    *nx = mx, *ny = my;
    return atan2(qy[1], qx[1]);
}

TEST(sun_ring_phase_by_construction)
{
    /* tooth counts with Z_r = Z_s + 2 Z_p, and two with Z_r = Z_s + 2 Z_p + 1 whose ring
     * shift is solved for the common carrier radius (both working angles differ) */
    static const struct {
        int zs, zp, zr;
        double xs, xp, xr;
        int solve;
    } sets[] = {{25, 23, 71, 0, 0, 0, 0},         {24, 24, 72, 0, 0, 0, 0},
                {25, 23, 71, -0.3, 0.3, -0.3, 0}, {25, 23, 71, 0.2, 0, -0.2, 0},
                {20, 30, 81, 0.5, 0.4, 0, 1},     {21, 25, 72, 0.45, 0.2, 0, 1}};
    for (int c = 0; c < 6; c++) {
        gd_gear_pair_geometry sp, rp;
        gd_gear_pair_derived ds, dr;
        gd_error err;
        set_meshes(&sp, &rp, sets[c].zs, sets[c].zp, sets[c].zr);
        sp.gear[0].profile_shift = sets[c].xs;
        sp.gear[1].profile_shift = rp.gear[0].profile_shift = sets[c].xp;
        rp.gear[1].profile_shift = sets[c].xr;
        if (sets[c].solve) {
            /* the ring's shift for the sun-planet centre distance a: cos a_wr = a0r cos 20 / a,
             * x_p + x_r = (inv 20 - inv a_wr) (z_r - z_p) / (2 tan 20) */
            REQUIRE(gd_gear_pair_derive(&sp, &ds, &err) == GD_OK);
            double a20 = 20 * PI / 180, a0r = 1e-3 * (sets[c].zr - sets[c].zp);
            double awr = acos(a0r * cos(a20) / ds.center_distance);
            rp.gear[1].profile_shift =
                (tan(a20) - a20 - (tan(awr) - awr)) * (sets[c].zr - sets[c].zp) / (2 * tan(a20)) -
                sets[c].xp;
        }
        REQUIRE(gd_gear_pair_derive(&sp, &ds, &err) == GD_OK);
        REQUIRE(gd_gear_pair_derive(&rp, &dr, &err) == GD_OK);
        double g = -1;
        if (gd_planet_sun_ring_phase(&sp, &rp, &g, &err)) {
            fprintf(stderr, "  set %d: %s: %s\n", c, err.field, err.message);
            CHECK(0);
            continue;
        }
        const int zp = sets[c].zp;
        const double rb = ds.base_radius[1], at = ds.transverse_pressure_angle;
        const double bb = (PI / 2 + 2 * sets[c].xp * tan(20 * PI / 180)) / zp + tan(at) - at;
        const double aws = ds.working_pressure_angle, awr = dr.working_pressure_angle;
        const double pitch = 2 * PI / zp;
        double event[2] = {0, 0};
        int found[2] = {0, 0};
        for (int mesh = 0; mesh < 2; mesh++) {
            double rw = rb / cos(mesh ? awr : aws), target = mesh ? 0 : PI;
            double fx = mesh ? sin(awr) : -sin(aws), fy = mesh ? -cos(awr) : -cos(aws);
            for (int side = -1; side <= 1; side += 2) {
                double nx, ny;
                double ang = flank_crossing(rb, side * bb, side, rw, &nx, &ny);
                double th = target - ang; /* planet rotation that brings it to P */
                double rx = cos(th) * nx - sin(th) * ny, ry = sin(th) * nx + cos(th) * ny;
                if (rx * fx + ry * fy > 0.999) {
                    /* clockwise at unit rate: the rotation th is reached at t = -th */
                    double t = -th / pitch;
                    event[mesh] = t - floor(t);
                    found[mesh]++;
                }
            }
        }
        REQUIRE(found[0] == 1 && found[1] == 1);
        double lag = event[1] - event[0];
        lag -= floor(lag);
        if (lag > 1 - 1e-9) lag = 0;
        fprintf(stderr, "  set %d: gamma_rs %.9f, construction %.9f\n", c, g, lag);
        CHECK_ABS(g, lag, 1e-7); /* the finite-difference normal only picks the flank */
    }
}

RUN_TESTS(T(equally_spaced_in_phase), T(drivetrain_hub_phasing_types), T(parker_suppression_sums),
          T(assembly_and_input_errors), T(sun_ring_phase), T(sun_ring_phase_by_construction))
