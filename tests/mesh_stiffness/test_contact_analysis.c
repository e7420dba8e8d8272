/* Loaded tooth contact analysis and micro-geometry (docs/mesh-stiffness.md, "Loaded
 * contact analysis"): the unmodified pair against the TVMS, the Harris map of a
 * linear tip relief sized for a design load, the face load factor under misalignment
 * against ISO 6336-1, edge contact flags and bad input. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/mesh_stiffness.h"
#include "harness.h"
#include "mesh_stiffness/mesh_stiffness_impl.h"

static const double DEG = 3.14159265358979323846 / 180.0;

/* [MMT2018] rig pair: 48/32, module 2 mm, b = 20 mm, E = 2.0e11, bores 12.7 mm. */
static void spur_pair(gd_gear_pair_geometry *g)
{
    gd_gear_pair_geometry_init(g);
    g->gear[0].teeth = 48, g->gear[1].teeth = 32;
    g->normal_module = 2e-3;
    g->face_width = 0.020;
    for (int i = 0; i < 2; i++)
        g->gear[i].E = 2.0e11, g->gear[i].bore_radius = 12.7e-3;
}

/* [JMSTHelical] pair 1 at 20 deg: 52/72, normal module 1.75 mm, b = 20 mm. */
static void helical_pair(gd_gear_pair_geometry *g)
{
    gd_gear_pair_geometry_init(g);
    g->gear[0].teeth = 52, g->gear[1].teeth = 72, g->normal_module = 1.75e-3;
    g->face_width = 0.020, g->helix_angle = 20 * DEG;
    g->gear[0].bore_radius = g->gear[1].bore_radius = 12.7e-3;
}

static void print_err(const gd_error *err)
{
    char buf[1024];
    gd_error_format(err, buf, sizeof buf);
    fprintf(stderr, "  failed: %s\n", buf);
}

static gd_ltca_result *ltca(const gd_gear_pair_geometry *g, const gd_tvms_options *o)
{
    gd_ltca_result *r = NULL;
    gd_error err;
    if (gd_ltca_compute(g, o, &r, &err)) print_err(&err);
    return r;
}

/* Unmodified perfect teeth: every slice touches at once, so the contact analysis is
 * the TVMS: k equal at every position (same slices, same law; only the summation
 * order differs, 1e-12) and delta = F / k. Spur and helical, with and without the
 * gear bodies in series. */
TEST(unmodified_equals_tvms)
{
    for (int c = 0; c < 3; c++) {
        gd_gear_pair_geometry g;
        if (c == 1)
            helical_pair(&g);
        else
            spur_pair(&g);
        gd_tvms_options o;
        gd_tvms_options_init(&o);
        o.points = 90, o.slices = 40, o.cycles = 2;
        if (c == 2) o.body_compliance = 1, g.gear[0].web_thickness = 6e-3;
        o.load_torque = 150;
        gd_tvms_result *t = NULL;
        gd_error err;
        REQUIRE(gd_tvms_compute(&g, &o, &t, &err) == GD_OK);
        gd_ltca_result *r = ltca(&g, &o);
        REQUIRE(r);
        REQUIRE(r->n == t->n && r->max_pairs == t->max_pairs);
        if (c == 2) CHECK(r->body_stiffness > 0);
        double F = 150 / (r->geom.base_radius[0] * cos(r->geom.base_helix_angle));
        CHECK_REL(r->force, F, 1e-15);
        double worst = 0;
        for (size_t i = 0; i < r->n; i++) {
            double e = fabs(r->stiffness[i] - t->stiffness[i]) / t->stiffness[i];
            if (e > worst) worst = e;
            CHECK_REL(r->ste[i], F / t->stiffness[i], 1e-9);
            CHECK_ABS(r->ste_unloaded[i], 0, 0);
            CHECK(r->pairs_in_contact[i] == t->pairs_in_contact[i]);
            CHECK(r->flags[i] == 0);
            for (int j = 0; j < r->max_pairs; j++)
                CHECK_ABS(r->pair_load[i * r->max_pairs + j] / F,
                          t->load_share[i * t->max_pairs + j], 1e-9);
        }
        CHECK(worst <= 1e-9);
        fprintf(stderr, "  case %d: max relative difference of k %.2e\n", c, worst);
        CHECK_REL(r->stiffness_mean, t->mean, 1e-9);
        gd_ltca_free(r);
        gd_tvms_free(t);
    }
}

/* Long linear tip relief on both gears, from the highest (lowest) point of single
 * contact to the tip, of the amount the single pair deflects at the design load
 * (Tavakoli & Houser, J. Mech. Trans. Autom. Des. 108 (1986) 86: with a constant pair
 * stiffness the loaded TE is then flat at that load). With the real, varying pair
 * stiffness the Harris map's minimum of the peak-to-peak TE must still lie within
 * +-15 % of the design load (the acceptance), and the relief must cut the
 * peak-to-peak there well below that of the unmodified pair. */
TEST(harris_map_tip_relief_sized_for_design_load)
{
    gd_gear_pair_geometry g;
    spur_pair(&g);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 128, o.slices = 10;
    gd_tvms_result *t = NULL;
    gd_error err;
    REQUIRE(gd_tvms_compute(&g, &o, &t, &err) == GD_OK);
    const gd_gear_pair_derived *d = &t->geom;
    double ks = 0;
    int ns = 0;
    for (size_t i = 0; i < t->points; i++)
        if (t->pairs_in_contact[i] == 1) ks += t->stiffness[i], ns++;
    REQUIRE(ns > 0);
    ks /= ns;
    const double Td = 100, Fd = Td / d->base_radius[0];
    const double C = Fd / ks; /* single-pair deflection at the design load */
    double hpstc = d->contact_start + d->base_pitch_transverse;
    double lpstc = d->contact_end - d->base_pitch_transverse;
    g.gear[0].mod.tip_relief.amount = C;
    g.gear[0].mod.tip_relief.start_roll_angle = hpstc / d->base_radius[0];
    g.gear[1].mod.tip_relief.amount = C;
    g.gear[1].mod.tip_relief.start_roll_angle = (d->line_of_action - lpstc) / d->base_radius[1];
    enum { NL = 37 };
    double T[NL];
    for (int l = 0; l < NL; l++)
        T[l] = Td * (0.2 + 0.05 * l);
    gd_ltca_map *m = NULL;
    if (gd_ltca_map_compute(&g, &o, T, NL, &m, &err)) print_err(&err);
    REQUIRE(m);
    int best = 0;
    for (int l = 1; l < NL; l++)
        if (m->ste_peak_to_peak[l] < m->ste_peak_to_peak[best]) best = l;
    double ratio = T[best] / Td;
    double unmod_pp = Fd / t->min - Fd / t->max; /* unmodified TE = F / k */
    fprintf(stderr,
            "  relief %.3f um; p-p TE minimum %.4f um at %.2f x design load (unmodified %.3f um)\n",
            C * 1e6, m->ste_peak_to_peak[best] * 1e6, ratio, unmod_pp * 1e6);
    CHECK(fabs(ratio - 1) <= 0.15);
    CHECK(m->ste_peak_to_peak[best] < 0.25 * unmod_pp);
    /* at light load only the unrelieved zone carries load: p-p rises toward the relief */
    CHECK(m->ste_peak_to_peak[0] > 2 * m->ste_peak_to_peak[best]);
    /* the single-load analysis agrees with the map at the design load */
    o.load_torque = Td;
    gd_ltca_result *r = ltca(&g, &o);
    REQUIRE(r);
    CHECK_REL(r->ste_peak_to_peak, m->ste_peak_to_peak[16], 1e-12);
    CHECK_REL(r->ste_mean, m->ste_mean[16], 1e-12);
    gd_ltca_free(r);
    gd_ltca_map_free(m);
    gd_tvms_free(t);
}

/* ISO 6336-1 face load factor for a linear gap F_by across the face with mesh
 * stiffness c_gamma per unit face width (clause 7, Eqs. for K_Hbeta; they follow from
 * a linear load distribution w(y) = c_gamma (delta - F_by y / b)):
 *   whole face in contact:  K = 1 + F_by c_gamma b / (2 F_m)        (K <= 2)
 *   partial contact:        K = sqrt(2 F_by c_gamma b / F_m)        (K >= 2)
 * Spur pair: at every position all slices share one stiffness, so the contact analysis
 * is that linear distribution with c_gamma = k(theta) / b. With N slices evaluated at
 * their centres, the full-contact maximum is 1 + F_by k (1 - 1/N) / (2 F) exactly (1e-9);
 * against the continuous formula the difference is below F_by k / (2 F N). In partial
 * contact the triangle is resolved to about one slice of its base: 3 %. */
TEST(face_load_factor_spur_against_iso6336)
{
    gd_gear_pair_geometry g;
    spur_pair(&g);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 32, o.slices = 100, o.load_torque = 100;
    const int N = o.slices;
    double k0[32]; /* full-contact stiffness: in partial contact k(theta) is the tangent */
    for (int c = 0; c < 2; c++) {
        o.misalignment = c ? 50e-6 : 5e-6;
        gd_ltca_result *r = ltca(&g, &o);
        REQUIRE(r);
        double F = r->force, f = o.misalignment, worst = 0;
        for (size_t i = 0; i < r->n; i++) {
            if (c == 0) k0[i] = r->stiffness[i];
            double k = k0[i], K = r->face_load_factor[i];
            /* loaded at the front face: positive misalignment opens the back face */
            CHECK(r->line_load[i * N] >= r->line_load[i * N + N - 1]);
            if (c == 0) {
                CHECK_REL(K, 1 + f * k * (1 - 1.0 / N) / (2 * F), 1e-9);
                CHECK(fabs(K - (1 + f * k / (2 * F))) <= f * k / (2 * F * N) * (1 + 1e-9));
                CHECK(r->flags[i] == 0);
            } else {
                double iso = sqrt(2 * f * k / F);
                CHECK(iso > 2);
                CHECK_REL(K, iso, 0.03);
                if (fabs(K - iso) / iso > worst) worst = fabs(K - iso) / iso;
                CHECK(r->flags[i] == GD_LTCA_PARTIAL_FACE);
            }
        }
        if (c) fprintf(stderr, "  spur partial contact: K_Hbeta within %.2e of ISO\n", worst);
        gd_ltca_free(r);
    }
}

/* Helical pair: the contact lines cross the face diagonally, so at one instant the
 * slices differ in stiffness; ISO's K_Hbeta refers to the load per unit face width
 * along the face, here the line load averaged over a mesh cycle. Against the ISO
 * full-contact formula with c_gamma = mean mesh stiffness / b. Tolerance 5 % of
 * K_Hbeta - 1: the formula assumes the stiffness uniform over the face at every
 * instant, while delta and the local stiffness vary together over the cycle (their
 * correlation is what is left; the sampling of 64 positions adds about 1 %). */
TEST(face_load_factor_helical_against_iso6336)
{
    gd_gear_pair_geometry g;
    helical_pair(&g);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 64, o.slices = 40, o.load_torque = 100;
    gd_ltca_result *r0 = ltca(&g, &o);
    REQUIRE(r0);
    /* aligned: the cycle-averaged line load is uniform to the sampling */
    CHECK_ABS(r0->face_load_factor_cycle, 1, 0.02);
    o.misalignment = 8e-6;
    gd_ltca_result *r = ltca(&g, &o);
    REQUIRE(r);
    double F = r->force, k = r->stiffness_mean;
    double iso = 1 + o.misalignment * k / (2 * F);
    fprintf(stderr, "  helical: K_Hbeta %.4f, ISO 6336-1 %.4f (aligned %.4f)\n",
            r->face_load_factor_cycle, iso, r0->face_load_factor_cycle);
    CHECK(iso < 2);
    CHECK_ABS(r->face_load_factor_cycle - 1, iso - 1, 0.05 * (iso - 1));
    CHECK(r->flagged == 0);
    gd_ltca_free(r);
    gd_ltca_free(r0);
}

/* A misalignment so large that only the front face edge touches: flagged at every
 * position, every value finite, the load still carried (contact always exists for a
 * positive load). */
TEST(edge_contact_flagged_never_nan)
{
    for (int c = 0; c < 2; c++) {
        gd_gear_pair_geometry g;
        if (c)
            helical_pair(&g);
        else
            spur_pair(&g);
        gd_tvms_options o;
        gd_tvms_options_init(&o);
        o.points = 32, o.slices = 40, o.load_torque = 1, o.misalignment = 1e-3;
        gd_ltca_result *r = ltca(&g, &o);
        REQUIRE(r);
        CHECK(r->flagged == (int)r->points);
        for (size_t i = 0; i < r->n; i++) {
            CHECK(r->flags[i] & GD_LTCA_EDGE_CONTACT);
            CHECK(isfinite(r->ste[i]) && isfinite(r->stiffness[i]) && r->stiffness[i] > 0);
            CHECK(isfinite(r->face_load_factor[i]) && r->face_load_factor[i] > 10);
            double sum = 0;
            for (int j = 0; j < r->max_pairs; j++)
                sum += r->pair_load[i * r->max_pairs + j];
            CHECK_REL(sum, r->force, 1e-9);
        }
        gd_ltca_free(r);
    }
}

/* Crowning alone (spur, full contact): w(y) = c (delta - C_b (2y/b - 1)^2), c = k / b,
 * has the mean w_m = c (delta - C_b / 3) = F / b and the maximum c delta at mid face, so
 * K = 1 + c C_b / (3 w_m) = 1 + k C_b / (3 F), C_b the sum of both gears' crowning. Slice centres
 * change the mean of the parabola by C_b / (3 N^2): 1e-3 with 40 slices. Symmetric about mid face.
 */
TEST(crowning_load_distribution)
{
    gd_gear_pair_geometry g;
    spur_pair(&g);
    g.gear[0].mod.crowning = 2e-6;
    g.gear[1].mod.crowning = 1e-6;
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 16, o.slices = 40, o.load_torque = 100;
    gd_ltca_result *r = ltca(&g, &o);
    REQUIRE(r);
    for (size_t i = 0; i < r->n; i++) {
        double k = r->stiffness[i], K = 1 + k * 3e-6 / (3 * r->force);
        CHECK(K < 2);
        CHECK_REL(r->face_load_factor[i], K, 2e-3);
        for (int j = 0; j < 20; j++)
            CHECK_REL(r->line_load[i * 40 + j], r->line_load[i * 40 + 39 - j], 1e-9);
    }
    gd_ltca_free(r);
}

static int expect_error(const gd_gear_pair_geometry *g, const gd_tvms_options *o, const char *field,
                        const char *words)
{
    gd_ltca_result *r = NULL;
    gd_error err;
    gd_error_clear(&err);
    gd_status st = gd_ltca_compute(g, o, &r, &err);
    if (st != GD_EINPUT || strcmp(err.field, field) || !strstr(err.message, words)) {
        fprintf(stderr, "  expected %s error with '%s', got %d: field '%s' message '%s'\n", field,
                words, (int)st, err.field, err.message);
        gd_ltca_free(r);
        return 0;
    }
    return r == NULL;
}

TEST(bad_input_errors)
{
    gd_gear_pair_geometry g0, g;
    spur_pair(&g0);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 16, o.slices = 10, o.load_torque = 100;
    /* tip relief starting below the reference circle: longer than the addendum */
    g = g0;
    g.gear[0].mod.tip_relief.amount = 10e-6;
    g.gear[0].mod.tip_relief.start_diameter = 95e-3; /* reference 96 mm */
    CHECK(expect_error(&g, &o, "driver.modifications.tip_relief.start_diameter",
                       "longer than the addendum"));
    g.gear[0].mod.tip_relief.start_diameter = 101e-3; /* tip 100 mm */
    CHECK(expect_error(&g, &o, "driver.modifications.tip_relief.start_diameter",
                       "not below the tip"));
    g.gear[0].mod.tip_relief.start_diameter = 0;
    CHECK(expect_error(&g, &o, "driver.modifications.tip_relief.start_diameter",
                       "start diameter or roll"));
    /* a plain number meant as micrometres */
    g = g0;
    g.gear[1].mod.tip_relief.amount = 20;
    g.gear[1].mod.tip_relief.start_diameter = 66e-3;
    CHECK(expect_error(&g, &o, "driven.modifications.tip_relief.amount",
                       "tenth of the normal module"));
    g = g0;
    g.gear[1].mod.root_relief.amount = 5e-6;
    g.gear[1].mod.root_relief.start_diameter = 65e-3; /* reference 64 mm */
    CHECK(expect_error(&g, &o, "driven.modifications.root_relief.start_diameter",
                       "longer than the dedendum"));
    g = g0;
    g.gear[1].mod.crowning = -3e-6;
    CHECK(expect_error(&g, &o, "driven.modifications.crowning", "negative crowning"));
    g = g0;
    g.gear[0].mod.end_relief = 3e-6;
    g.gear[0].mod.end_relief_length = 15e-3;
    CHECK(expect_error(&g, &o, "driver.modifications.end_relief.length", "outside (0, b/2"));
    /* options */
    o.load_torque = 0;
    CHECK(expect_error(&g0, &o, "load", "not positive"));
    o.load_torque = 100, o.method = GD_TVMS_ISO6336;
    CHECK(expect_error(&g0, &o, "method", "needs a stiffness law"));
    o.method = GD_TVMS_ENERGY, o.misalignment = NAN;
    CHECK(expect_error(&g0, &o, "misalignment", "not a number"));
    o.misalignment = 0;
    gd_ltca_map *m = NULL;
    gd_error err;
    double T[2] = {10, -1};
    CHECK(gd_ltca_map_compute(&g0, &o, T, 2, &m, &err) == GD_EINPUT && m == NULL);
    CHECK_STR(err.field, "load");
}

/* The separation of each modification at points where its value is known (exact to
 * rounding, 1e-12): linear and parabolic reliefs at mid zone and at their ends, a root
 * relief at the form circle, start by diameter = start by roll angle, crowning, end
 * relief, helix slope and misalignment signs (docs/mesh-stiffness.md, "Micro-geometry"). */
TEST(separation_of_each_modification)
{
    gd_gear_pair_geometry g;
    spur_pair(&g);
    gd_gear_pair_derived d;
    gd_error err;
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    const double rb1 = d.base_radius[0], rb2 = d.base_radius[1], L = d.line_of_action;
    const double rho_a1 = d.contact_end, rho_a2 = sqrt(pow(d.tip_radius[1], 2) - rb2 * rb2);
    const double b = g.face_width, A = 10e-6;
    /* driver tip relief from roll 17 mm, linear; alone, then a driven root relief from
     * roll 8 mm, parabolic, alone (a driver tip contact meets the driven root) */
    double rs = 17e-3, rr = 8e-3, rf2 = d.form_roll[1];
    gd_gear_pair_geometry gr = g;
    g.gear[0].mod.tip_relief = (gd_profile_relief){A, 2 * sqrt(rb1 * rb1 + rs * rs), 0, 0};
    gr.gear[1].mod.root_relief = (gd_profile_relief){A, 0, rr / rb2, GD_RELIEF_PARABOLIC};
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    REQUIRE(gd_gear_pair_derive(&gr, &d, &err) == GD_OK);
    gd_ms_mods m;
    gd_ms_mods_init(&m, &g, &d, 0);
    double y = 0.5 * b;
    CHECK_ABS(gd_ms_mods_separation(&m, rs, y), 0, 1e-18);
    CHECK_REL(gd_ms_mods_separation(&m, 0.5 * (rs + rho_a1), y), 0.5 * A, 1e-12);
    CHECK_REL(gd_ms_mods_separation(&m, rho_a1, y), A, 1e-12);
    CHECK_ABS(gd_ms_mods_separation(&m, d.contact_start, y), 0, 1e-18);
    /* driven root: roll N1N2 - s; at mid zone (parabolic) A/4, at the form circle A */
    gd_ms_mods mr;
    gd_ms_mods_init(&mr, &gr, &d, 0);
    CHECK_REL(gd_ms_mods_separation(&mr, L - 0.5 * (rr + rf2), y), 0.25 * A, 1e-12);
    CHECK_REL(gd_ms_mods_separation(&mr, L - rf2, y), A, 1e-12);
    CHECK_ABS(gd_ms_mods_separation(&mr, L - rr, y), 0, 1e-18);
    CHECK_ABS(gd_ms_mods_separation(&mr, L - rho_a2, y), 0, 1e-18);
    /* the same tip relief by roll angle */
    gd_gear_pair_geometry h = g;
    h.gear[0].mod.tip_relief.start_diameter = 0;
    h.gear[0].mod.tip_relief.start_roll_angle = rs / rb1;
    gd_ms_mods mh;
    gd_ms_mods_init(&mh, &h, &d, 0);
    CHECK_REL(gd_ms_mods_separation(&mh, 0.5 * (rs + rho_a1), y),
              gd_ms_mods_separation(&m, 0.5 * (rs + rho_a1), y), 1e-12);
    /* lead: crowning 2 + 1 um, end relief 4 um over 2 mm (linear) on the driver, slope
     * +3 um on the driven gear and misalignment -1 um: at a pitch-point contact */
    spur_pair(&g);
    g.gear[0].mod.crowning = 2e-6, g.gear[1].mod.crowning = 1e-6;
    g.gear[0].mod.end_relief = 4e-6, g.gear[0].mod.end_relief_length = 2e-3;
    g.gear[1].mod.helix_slope_deviation = 3e-6;
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    gd_ms_mods_init(&m, &g, &d, -1e-6);
    double sp = rb1 * tan(d.working_pressure_angle);
    CHECK_ABS(gd_ms_mods_separation(&m, sp, 0.5 * b), 0, 1e-18);
    CHECK_REL(gd_ms_mods_separation(&m, sp, 0), 3e-6 + 4e-6 - 1e-6, 1e-12);
    CHECK_REL(gd_ms_mods_separation(&m, sp, b), 3e-6 + 4e-6 + 1e-6, 1e-12);
    CHECK_REL(gd_ms_mods_separation(&m, sp, 1e-3), 3e-6 * 0.81 + 2e-6 + 2e-6 * (0.05 - 0.5), 1e-12);
}

RUN_TESTS(T(separation_of_each_modification), T(unmodified_equals_tvms),
          T(harris_map_tip_relief_sized_for_design_load), T(face_load_factor_spur_against_iso6336),
          T(face_load_factor_helical_against_iso6336), T(edge_contact_flagged_never_nan),
          T(crowning_load_distribution), T(bad_input_errors))
