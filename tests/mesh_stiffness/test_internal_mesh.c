/* Internal (ring-planet) gear pairs: geometry against a published example and a hand
 * calculation ([KHK] Sec. 5.1, docs/mesh-stiffness.md "Internal pairs"), interference
 * checks, the ring tooth's energy integral against the external tooth's, and the TVMS
 * of an internal pair (periodic, mean = the path integral of the pair stiffness over a
 * base pitch, linear in face width, near ISO 6336-1's c_gamma). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/mesh_stiffness.h"
#include "harness.h"
#include "tvms_support.h"
#include "mesh_stiffness/mesh_stiffness_impl.h"

static const double DEG = GD_MS_PI / 180.0;

static double inv(double a)
{
    return tan(a) - a;
}

/* The hand-calculated pair of docs/mesh-stiffness.md ("Internal pairs"): m = 2 mm,
 * 20 deg, z = 20 / 50, x1 = +0.3, x2 = -0.2 (ISO 21771 sign: the ring's tip moved
 * outward by 0.2 m). */
static void hand_pair(gd_gear_pair_geometry *g)
{
    gd_gear_pair_geometry_init(g);
    g->internal = 1;
    g->normal_module = 2e-3;
    g->face_width = 0.02;
    g->gear[0].teeth = 20;
    g->gear[0].profile_shift = 0.3;
    g->gear[1].teeth = 50;
    g->gear[1].profile_shift = -0.2;
}

/* A planetary ring-planet mesh: 30-tooth planet in an 84-tooth ring, module 2 mm. */
static void ring_planet(gd_gear_pair_geometry *g, double b, double beta_deg)
{
    gd_gear_pair_geometry_init(g);
    g->internal = 1;
    g->normal_module = 2e-3;
    g->face_width = b;
    g->helix_angle = beta_deg * DEG;
    g->gear[0].teeth = 30;
    g->gear[0].bore_radius = 0.01;
    g->gear[1].teeth = 84;
}

TEST(hand_calculation_geometry)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    hand_pair(&g);
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    CHECK(d.internal == 1);
    /* hand calculation (docs/mesh-stiffness.md, "Internal pairs"): inv a_w = inv 20 deg
     * - 2 tan 20 deg (0.3 - 0.2) / 30 = 0.0124779, inverted by bisection here */
    double lo = 0.1, hi = 1.2, target = inv(20 * DEG) - 2 * tan(20 * DEG) * 0.1 / 30;
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (inv(mid) < target)
            lo = mid;
        else
            hi = mid;
    }
    const double aw = d.working_pressure_angle;
    CHECK_ABS(aw, lo, 1e-12);
    CHECK_ABS(aw / DEG, 18.88465, 1e-5);                /* docs, 7 digits */
    CHECK_ABS(d.center_distance * 1e3, 29.79456, 1e-5); /* docs, 7 digits */
    CHECK_REL(d.center_distance, 30e-3 * cos(20 * DEG) / cos(lo), 1e-12);
    CHECK_ABS(d.reference_center_distance * 1e3, 30.0, 1e-12);
    CHECK_REL(d.base_radius[0], 20e-3 * cos(20 * DEG), 1e-14);
    CHECK_REL(d.base_radius[1], 50e-3 * cos(20 * DEG), 1e-14);
    CHECK_ABS(d.tip_radius[0] * 1e3, 22.6, 1e-9);  /* 20 + (1 + 0.3) 2 */
    CHECK_ABS(d.tip_radius[1] * 1e3, 48.4, 1e-9);  /* 50 - (1 - 0.2) 2: inside r */
    CHECK_ABS(d.root_radius[0] * 1e3, 18.1, 1e-9); /* 20 - (1.25 - 0.3) 2 */
    CHECK_ABS(d.root_radius[1] * 1e3, 52.9, 1e-9); /* 50 + (1.25 + 0.2) 2 */
    /* g_alpha = sqrt(ra1^2 - rb1^2) - sqrt(ra2^2 - rb2^2) + a sin(a_w)
     *         = 12.55194 - 11.61914 + 9.64342 = 10.57622 mm,
     * eps_alpha = g_alpha / (pi m cos 20) = 10.57622 / 5.90426 = 1.791285 (docs) */
    const double rb1 = d.base_radius[0], rb2 = d.base_radius[1];
    double ga = sqrt(22.6e-3 * 22.6e-3 - rb1 * rb1) - sqrt(48.4e-3 * 48.4e-3 - rb2 * rb2) +
                d.center_distance * sin(aw);
    CHECK_REL(d.contact_length, ga, 1e-12);
    CHECK_ABS(d.contact_length * 1e3, 10.57622, 1e-5);
    CHECK_ABS(d.contact_ratio_transverse, 1.791285, 1e-6);
    CHECK_REL(d.contact_ratio_transverse, ga / (GD_MS_PI * 2e-3 * cos(20 * DEG)), 1e-12);
    CHECK_ABS(d.contact_start * 1e3, 1.97572, 1e-5); /* 11.61914 - 9.64342 */
    /* the operating pitch point: pitch radii r_b / cos(a_w) on both gears */
    CHECK_REL(d.pitch_point, rb1 * tan(aw), 1e-12);
    CHECK_REL(d.pitch_point + d.line_of_action, rb2 * tan(aw), 1e-12);
    CHECK(d.contact_start < d.pitch_point && d.pitch_point < d.contact_end);
    /* tip clearances: 52.9 - (a + 22.6) = (48.4 - a) - 18.1 = 0.50544 mm */
    CHECK_ABS(d.tip_clearance[0] * 1e3, 0.50544, 1e-5);
    CHECK_ABS(d.tip_clearance[1] * 1e3, 0.50544, 1e-5);
    CHECK_ABS(d.trochoid_margin, 0.0123455, 1e-7); /* [KHK] Eq. 5-6 by hand (docs) */
    CHECK(d.trochoid_margin > 0);
}

/* [KHK] Sec. 5.2 (b): "in the meshing of an external gear and a standard internal gear
 * (alpha = 20 deg), trochoid interference is avoided if the difference of the numbers of
 * teeth is larger than 9". */
TEST(trochoid_interference_rule)
{
    int z2s[] = {40, 60, 100};
    for (int k = 0; k < 3; k++) {
        for (int diff = 8; diff <= 11; diff++) {
            gd_gear_pair_geometry g;
            gd_gear_pair_derived d;
            gd_error err;
            gd_gear_pair_geometry_init(&g);
            g.internal = 1;
            g.normal_module = 2e-3;
            g.face_width = 0.02;
            g.gear[1].teeth = z2s[k];
            g.gear[0].teeth = z2s[k] - diff;
            gd_status st = gd_gear_pair_derive(&g, &d, &err);
            if (diff >= 10) CHECK(st == GD_OK && d.trochoid_margin > 0); /* the rule */
            if (diff == 8 && z2s[k] <= 60) {
                /* below it the tips do cut: a located error */
                CHECK(st == GD_EINPUT);
                CHECK_STR(err.field, "driven.teeth");
                CHECK(strstr(err.message, "trochoid interference") != NULL);
            }
        }
    }
}

TEST(interference_errors)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    /* a standard 30-tooth ring has its tip inside its base circle (needs 34 teeth) */
    ring_planet(&g, 0.02, 0);
    g.gear[0].teeth = 14;
    g.gear[0].profile_shift = 0.2; /* not undercut */
    g.gear[0].bore_radius = 0;
    g.gear[1].teeth = 30;
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.profile_shift");
    CHECK(strstr(err.message, "involute interference") != NULL);
    /* ring with fewer teeth than the pinion */
    ring_planet(&g, 0.02, 0);
    g.gear[1].teeth = 28;
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.teeth");
    /* a centre distance above the zero-backlash one jams an internal pair */
    ring_planet(&g, 0.02, 0);
    g.center_distance = 54.01e-3;
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_EINPUT);
    CHECK_STR(err.field, "center_distance");
    CHECK(strstr(err.message, "jam") != NULL);
    g.center_distance = 53.9e-3; /* backlash: accepted, smaller working angle */
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    CHECK_ABS(d.working_pressure_angle, acos(54e-3 * cos(20 * DEG) / 53.9e-3), 1e-12);
    /* the ring's reliefs run from outside its tip inward, located when wrong */
    ring_planet(&g, 0.02, 0);
    g.gear[1].mod.tip_relief = (gd_profile_relief){10e-6, 0.160, 0, GD_RELIEF_LINEAR};
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_EINPUT); /* inside the tip, 164 mm */
    CHECK_STR(err.field, "driven.modifications.tip_relief.start_diameter");
    g.gear[1].mod.tip_relief.start_diameter = 0.170; /* outside the reference, 168 mm */
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "longer than the addendum") != NULL);
    g.gear[1].mod.tip_relief.start_diameter = 0.166;
    g.gear[1].mod.root_relief = (gd_profile_relief){5e-6, 0.167, 0, GD_RELIEF_LINEAR};
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_EINPUT); /* inside the reference */
    CHECK_STR(err.field, "driven.modifications.root_relief.start_diameter");
    g.gear[1].mod.root_relief.start_diameter = 0.169;
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    /* a rim thinner than a module */
    ring_planet(&g, 0.02, 0);
    g.gear[1].bore_radius = 87.5e-3;
    CHECK(gd_gear_pair_derive(&g, &d, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.bore_radius");
}

/* The pressure-angle integral of ring_tooth.c applied to an external tooth (root above
 * its base circle) against tooth_energy.c's tangent-angle integral: the same energies
 * by two parametrisations. */
TEST(radial_integral_matches_external_tooth)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    gd_gear_pair_geometry_init(&g);
    g.normal_module = 2e-3, g.face_width = 0.02;
    g.gear[0].teeth = 60, g.gear[1].teeth = 70;
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    gd_ms_tooth t = {d.base_radius[0],
                     d.half_angle_base[0],
                     d.root_radius[0],
                     d.bore_radius[0],
                     2.06e11,
                     0.3,
                     0};
    REQUIRE(t.rf > t.rb);
    for (int k = 0; k <= 4; k++) {
        double s = d.contact_start + 0.25 * k * d.contact_length;
        double a[3], b[3];
        gd_ms_tooth_beam_terms(&t, s / t.rb, 1e-13, 0, a);
        gd_ms_radial_beam_terms(&t, s / t.rb, 1e-13, b);
        for (int j = 0; j < 3; j++)
            CHECK_REL(b[j], a[j], 1e-9); /* both integrals to 1e-13 */
    }
}

/* A ring and an external gear of very many teeth both tend to the rack: at the
 * reference circle their tooth compliances agree to O(1/z). */
TEST(ring_tooth_tends_to_rack)
{
    double prev = 1;
    for (int z = 500; z <= 8000; z *= 4) {
        gd_ms_tooth e = {0}, r = {0};
        double at = 20 * DEG, rp = 0.5 * z * 1e-3, rb = rp * cos(at);
        e.rb = r.rb = rb;
        e.E = r.E = 2.06e11;
        e.nu = r.nu = 0.3;
        e.alpha2 = (GD_MS_PI / 2) / z + inv(at);
        e.rf = rp - 1.25e-3;
        r.alpha2 = (GD_MS_PI / 2) / z - inv(at);
        r.rf = rp + 1.25e-3;
        r.internal = 1;
        double a[3], b[3];
        gd_ms_radial_beam_terms(&e, tan(at), 1e-12, a);
        gd_ms_radial_beam_terms(&r, tan(at), 1e-12, b);
        double ca = a[0] + a[1] + a[2], cb = b[0] + b[1] + b[2];
        double rel = fabs(cb - ca) / ca;
        fprintf(stderr, "  z %d: external %.6g ring %.6g rel %.3g\n", z, ca, cb, rel);
        CHECK(rel * z > 11 && rel * z < 13); /* O(1/z): rel z = 11.7 measured */
        CHECK(rel < prev);
        prev = rel;
    }
}

TEST(internal_tvms_properties)
{
    gd_gear_pair_geometry g;
    ring_planet(&g, 0.02, 0);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 240;
    o.cycles = 2;
    gd_tvms_result *r = run(&g, &o);
    REQUIRE(r);
    const gd_gear_pair_derived *d = &r->geom;
    fprintf(stderr, "  eps %.5f mean %.6g min %.6g max %.6g iso c'b %.6g cga b %.6g ratio %.4f\n",
            d->contact_ratio_transverse, r->mean, r->min, r->max, r->iso_single_stiffness,
            r->iso_mesh_stiffness_alpha, r->mean / r->iso_mesh_stiffness_alpha);
    /* periodic in the mesh period */
    for (size_t i = 0; i < r->points; i++)
        CHECK_REL(r->stiffness[i + r->points], r->stiffness[i], 1e-12);
    /* 1 or 2 pairs for 1 < eps < 2, pair counts 2 for the fraction eps - 1 of a cycle */
    int two = 0;
    for (size_t i = 0; i < r->points; i++)
        two += r->pairs_in_contact[i] == 2;
    CHECK_ABS((double)two / r->points, d->contact_ratio_transverse - 1, 1.5 / r->points);
    /* the mean over a cycle is the path integral of the pair stiffness over one base
     * pitch (each pair contributes k(s) while it travels s_A..s_E): Gauss-Legendre of
     * the direct pair law, not the tabulated one */
    gd_ms_energy_law e;
    REQUIRE(gd_ms_energy_law_init(&e, &g, d, 1e-10) == 0);
    double integral = 0;
    const int pieces = 16;
    for (int k = 0; k < pieces; k++) {
        double lo = d->contact_start + d->contact_length * k / pieces;
        double hi = d->contact_start + d->contact_length * (k + 1) / pieces;
        /* 8-point rule of the direct law on each piece */
        static const double x8[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                     0.9602898564975363};
        static const double w8[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                     0.1012285362903763};
        double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
        for (int j = 0; j < 4; j++)
            integral += h * w8[j] *
                        (gd_ms_energy_pair_stiffness(&e, c - h * x8[j]) +
                         gd_ms_energy_pair_stiffness(&e, c + h * x8[j]));
    }
    gd_ms_energy_law_free(&e);
    double mean_path = integral * g.face_width / d->base_pitch_transverse;
    /* the samples' mean is a 240-point rectangle rule of a function with two jumps per
     * cycle: O(jump / points) */
    CHECK_REL(r->mean, mean_path, 2 * (r->max - r->min) / r->mean / r->points);
    fprintf(stderr, "  mean %.8g path %.8g rel %.3g\n", r->mean, mean_path,
            fabs(r->mean - mean_path) / mean_path);
    /* the same planet on a 84-tooth external gear */
    gd_gear_pair_geometry x = g;
    x.internal = 0;
    gd_tvms_result *rx = run(&x, &o);
    REQUIRE(rx);
    fprintf(stderr, "  external: eps %.5f mean %.6g iso cga b %.6g ratio %.4f\n",
            rx->geom.contact_ratio_transverse, rx->mean, rx->iso_mesh_stiffness_alpha,
            rx->mean / rx->iso_mesh_stiffness_alpha);
    /* ISO 6336-1 c_gamma_alpha b (internal: zn2 -> infinity): the energy method is 11 %
     * below it for this internal pair and 14 % for the external one (measured; the
     * energy method's usual offset from ISO's empirical fit): within 15 %, and the
     * internal pair relative to ISO within 5 % of the external pair relative to ISO */
    double qi = r->mean / r->iso_mesh_stiffness_alpha, qx = rx->mean / rx->iso_mesh_stiffness_alpha;
    CHECK(fabs(qi - 1) < 0.15);
    CHECK(fabs(qi / qx - 1) < 0.05);
    /* both say an internal mesh is stiffer than the external one with the same teeth */
    CHECK(r->mean > rx->mean);
    CHECK(r->iso_mesh_stiffness_alpha > rx->iso_mesh_stiffness_alpha);
    gd_tvms_free(rx);
    gd_tvms_free(r);
}

/* Spur: k scales exactly with the face width. Helical: one period per mesh cycle, the
 * mean near ISO's c_gamma_beta... and the face contact ratio b sin(beta) / (pi m_n). */
TEST(internal_face_width_and_helix)
{
    gd_gear_pair_geometry g;
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 64;
    ring_planet(&g, 0.02, 0);
    gd_tvms_result *a = run(&g, &o);
    ring_planet(&g, 0.05, 0);
    gd_tvms_result *b = run(&g, &o);
    REQUIRE(a && b);
    for (size_t i = 0; i < a->n; i++)
        CHECK_REL(b->stiffness[i], 2.5 * a->stiffness[i], 1e-12);
    gd_tvms_free(a);
    gd_tvms_free(b);
    ring_planet(&g, 0.03, 15);
    o.slices = 40;
    o.cycles = 2;
    gd_tvms_result *h = run(&g, &o);
    REQUIRE(h);
    CHECK_REL(h->geom.contact_ratio_face, 0.03 * sin(15 * DEG) / (GD_MS_PI * 2e-3), 1e-12);
    for (size_t i = 0; i < h->points; i++)
        CHECK_REL(h->stiffness[i + h->points], h->stiffness[i], 1e-12);
    /* helical contact lines smooth the stiffness: peak-to-peak well below the spur's */
    fprintf(stderr, "  helical: eps_g %.4f mean %.6g ptp %.3g iso cga b %.6g ratio %.4f\n",
            h->geom.contact_ratio_total, h->mean, h->peak_to_peak, h->iso_mesh_stiffness_alpha,
            h->mean / h->iso_mesh_stiffness_alpha);
    CHECK(h->peak_to_peak < 0.1 * h->mean);
    CHECK(fabs(h->mean / h->iso_mesh_stiffness_alpha - 1) < 0.15);
    gd_tvms_free(h);
}

/* Loaded tooth contact analysis of the internal pair (contact_analysis.c through the
 * ring's pair law): aligned, the approach is F / k(theta) and the loaded stiffness the
 * TVMS; with a misalignment f inside full-face contact the face load factor is ISO
 * 6336-1's linear-gap value with N slices at their centres, 1 + f k (1 - 1/N) / (2 F)
 * (the derivation of test_contact_analysis.c's spur test, which holds for any slice
 * law that is the same on every slice of a spur pair). */
TEST(internal_contact_analysis)
{
    gd_gear_pair_geometry g;
    ring_planet(&g, 0.02, 0);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 24, o.slices = 40, o.load_torque = 200;
    gd_ltca_result *r = NULL;
    gd_error err;
    REQUIRE(gd_ltca_compute(&g, &o, &r, &err) == GD_OK);
    gd_tvms_result *t = run(&g, &o);
    REQUIRE(t);
    CHECK_REL(r->force, 200 / (30e-3 * cos(20 * DEG)), 1e-12);
    for (size_t i = 0; i < r->n; i++) {
        CHECK_REL(r->stiffness[i], t->stiffness[i], 1e-9);
        CHECK_REL(r->ste[i], r->force / t->stiffness[i], 1e-9);
        CHECK_REL(r->face_load_factor[i], 1, 1e-9);
    }
    gd_ltca_free(r);
    const double f = 5e-6;
    o.misalignment = f;
    REQUIRE(gd_ltca_compute(&g, &o, &r, &err) == GD_OK);
    for (size_t i = 0; i < r->n; i++) {
        double K = 1 + f * t->stiffness[i] * (1 - 1.0 / o.slices) / (2 * r->force);
        CHECK(K < 2); /* full-face contact */
        CHECK_REL(r->face_load_factor[i], K, 1e-9);
    }
    gd_ltca_free(r);
    gd_tvms_free(t);
}

/* Tooth modifications of an internal pair: a linear tip relief on the ring (start
 * diameter 166 mm, tip 164 mm) adds its amount where the ring's tip meets the planet
 * (s_A) and nothing from its start outward, linearly in the ring's roll length s + N1N2;
 * crowning on the ring is the lead parabola; loaded, the entering pair (at the ring's
 * tip) carries less than without relief. */
TEST(internal_modifications)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    ring_planet(&g, 0.02, 0);
    const double A = 10e-6;
    g.gear[1].mod.tip_relief = (gd_profile_relief){A, 0.166, 0, GD_RELIEF_LINEAR};
    g.gear[1].mod.crowning = 3e-6;
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    gd_ms_mods m;
    gd_ms_mods_init(&m, &g, &d, 0);
    const double rb2 = d.base_radius[1], L = d.line_of_action;
    const double rho_a = sqrt(0.082 * 0.082 - rb2 * rb2), rho_s = sqrt(0.083 * 0.083 - rb2 * rb2);
    const double y0 = 0.01; /* mid face: no crowning */
    CHECK_ABS(gd_ms_mods_separation(&m, d.contact_start, y0), A, 1e-15);
    CHECK_ABS(gd_ms_mods_separation(&m, rho_s - L, y0), 0, 1e-15);
    CHECK_ABS(gd_ms_mods_separation(&m, 0.5 * (rho_a + rho_s) - L, y0), A / 2, 1e-15);
    CHECK_ABS(gd_ms_mods_separation(&m, d.contact_end, y0), 0, 1e-15);
    CHECK_ABS(gd_ms_mods_separation(&m, d.contact_end, 0), 3e-6, 1e-15); /* face end */
    /* loaded: the newest pair (entering at the ring's tip) unloaded by the relief */
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 16, o.slices = 10, o.load_torque = 200;
    gd_ltca_result *r = NULL, *r0 = NULL;
    REQUIRE(gd_ltca_compute(&g, &o, &r, &err) == GD_OK);
    gd_gear_pair_geometry g0;
    ring_planet(&g0, 0.02, 0);
    REQUIRE(gd_ltca_compute(&g0, &o, &r0, &err) == GD_OK);
    CHECK(r->pair_load[0] < 0.8 * r0->pair_load[0]);
    CHECK_REL(r->pair_load[0] + r->pair_load[1], r->force, 1e-9);
    CHECK(r->ste_peak_to_peak != r0->ste_peak_to_peak);
    fprintf(stderr, "  newest pair at entry: %.1f N relieved, %.1f N without\n", r->pair_load[0],
            r0->pair_load[0]);
    gd_ltca_free(r);
    gd_ltca_free(r0);
}

RUN_TESTS(T(hand_calculation_geometry), T(trochoid_interference_rule), T(interference_errors),
          T(radial_integral_matches_external_tooth), T(ring_tooth_tends_to_rack),
          T(internal_tvms_properties), T(internal_face_width_and_helix),
          T(internal_contact_analysis), T(internal_modifications))
