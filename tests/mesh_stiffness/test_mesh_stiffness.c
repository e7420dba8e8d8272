/* Gear mesh stiffness from geometry: paper values ([JMSTHelical] Table 1 and Sec. 5.1,
 * [MMT2018] Sec. 5.1), properties of k(angle), quadrature convergence, and bad input. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/mesh_stiffness.h"
#include "harness.h"
#include "tvms_support.h"
#include "model_file/mesh_geometry_read_impl.h"
#include "mesh_stiffness/mesh_stiffness_impl.h"
#include "model_file/yaml_doc_impl.h"

static const double DEG = GD_MS_PI / 180.0;

/* [JMSTHelical] pairs: module 1.75 mm (52/72) or 2.5 mm (22/79), b = 20 mm, steel 2.06e11. */
static void pair_002(gd_gear_pair_geometry *g, int which, double beta_deg)
{
    gd_gear_pair_geometry_init(g);
    g->face_width = 0.020;
    g->helix_angle = beta_deg * DEG;
    if (which == 1) {
        g->gear[0].teeth = 52, g->gear[1].teeth = 72, g->normal_module = 1.75e-3;
        g->gear[0].bore_radius = g->gear[1].bore_radius = 12.7e-3;
    } else {
        g->gear[0].teeth = 22, g->gear[1].teeth = 79, g->normal_module = 2.5e-3;
        g->gear[0].bore_radius = 12.7e-3, g->gear[1].bore_radius = 25e-3;
    }
}

/* [MMT2018] rig: 48/32, module 2 mm, b = 20 mm, E = 2.0e11, bores on 25.4 mm shafts. */
static void pair_004(gd_gear_pair_geometry *g)
{
    gd_gear_pair_geometry_init(g);
    g->gear[0].teeth = 48, g->gear[1].teeth = 32;
    g->normal_module = 2e-3;
    g->face_width = 0.020;
    for (int i = 0; i < 2; i++)
        g->gear[i].E = 2.0e11, g->gear[i].bore_radius = 12.7e-3;
}

TEST(table1_contact_ratios_002)
{
    /* [JMSTHelical] Table 1, all printed values (rows 5 and 15 lost their labels in OCR) */
    static const double beta[5] = {0, 5, 10, 15, 20};
    static const double ea[2][5] = {{1.7865, 1.7763, 1.7459, 1.6957, 1.6268},
                                    {1.7024, 1.6932, 1.6658, 1.6205, 1.5580}};
    static const double eb[2][5] = {{0, 0.3171, 0.6317, 0.9415, 1.2442},
                                    {0, 0.2219, 0.4422, 0.6591, 0.8709}};
    for (int p = 0; p < 2; p++)
        for (int i = 0; i < 5; i++) {
            gd_gear_pair_geometry g;
            gd_gear_pair_derived d;
            gd_error err;
            pair_002(&g, p + 1, beta[i]);
            REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
            CHECK_ABS(d.contact_ratio_transverse, ea[p][i], 0.5e-4);
            CHECK_ABS(d.contact_ratio_face, eb[p][i], 0.5e-4);
            CHECK_ABS(d.contact_ratio_total, ea[p][i] + eb[p][i], 1e-4);
        }
}

TEST(derived_geometry_standard_spur)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    pair_004(&g);
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    CHECK_REL(d.center_distance, 0.080, 1e-12);
    CHECK_REL(d.base_radius[0], 0.048 * cos(20 * DEG), 1e-12);
    CHECK_REL(d.tip_radius[1], 0.034, 1e-12);
    CHECK_REL(d.root_radius[0], 0.0455, 1e-12);
    CHECK_REL(d.base_pitch_transverse, GD_MS_PI * 2e-3 * cos(20 * DEG), 1e-12);
    CHECK_REL(d.mesh_period, 2 * GD_MS_PI / 48, 1e-14);
    CHECK_REL(d.tip_clearance[0], 0.25 * 2e-3, 1e-9);
    /* textbook: eps = [sqrt(ra1^2-rb1^2) + sqrt(ra2^2-rb2^2) - a sin(alpha)] / pb */
    double rb1 = d.base_radius[0], rb2 = d.base_radius[1];
    double e =
        (sqrt(0.050 * 0.050 - rb1 * rb1) + sqrt(0.034 * 0.034 - rb2 * rb2) - 0.08 * sin(20 * DEG)) /
        d.base_pitch_transverse;
    CHECK_REL(d.contact_ratio_transverse, e, 1e-12);
    /* profile shift: working pressure angle from inv(aw) = inv(a) + 2 tan(a)(x1+x2)/(z1+z2) */
    g.gear[0].profile_shift = 0.3, g.gear[1].profile_shift = 0.2;
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    double inv = tan(20 * DEG) - 20 * DEG + 2 * tan(20 * DEG) * 0.5 / 80;
    CHECK_REL(tan(d.working_pressure_angle) - d.working_pressure_angle, inv, 1e-10);
    CHECK(d.center_distance > 0.080 && d.center_distance < 0.080 + 0.5 * 2e-3);
    CHECK(d.tip_shortening > 0 && d.tip_shortening < 0.05);
}

TEST(mean_stiffness_002_sec51)
{
    /* [JMSTHelical] Sec. 5.1: averaged TVMS at 20 deg: 3.13e8 (pair 1), 3.69e8 N/m (pair 2) */
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    gd_gear_pair_geometry g;
    pair_002(&g, 1, 20);
    gd_tvms_result *r = run(&g, &o);
    REQUIRE(r);
    CHECK_REL(r->mean, 3.13e8, 0.10);
    CHECK_REL(r->mean, 3.302e8, 0.005); /* regression of this implementation */
    CHECK(r->slices == 50);
    gd_tvms_free(r);
    pair_002(&g, 2, 20);
    r = run(&g, &o);
    REQUIRE(r);
    CHECK_REL(r->mean, 3.69e8, 0.10);
    CHECK_REL(r->mean, 3.658e8, 0.005);
    gd_tvms_free(r);
}

TEST(fluctuation_trend_002_fig4)
{
    /* Fig. 4: pair 1 fluctuates least at 15 deg (eps_beta 0.94 ~ 1), more at 20 deg
     * (1.24); pair 2's fluctuation falls steadily as eps_beta grows to 0.87. */
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    double p2p[2][5];
    for (int p = 0; p < 2; p++)
        for (int i = 0; i < 5; i++) {
            gd_gear_pair_geometry g;
            pair_002(&g, p + 1, 5.0 * i);
            gd_tvms_result *r = run(&g, &o);
            REQUIRE(r);
            p2p[p][i] = r->peak_to_peak;
            gd_tvms_free(r);
        }
    for (int i = 0; i < 5; i++)
        if (i != 3) CHECK(p2p[0][3] < 0.5 * p2p[0][i]);
    CHECK(p2p[0][4] < p2p[0][2]);
    for (int i = 1; i < 5; i++)
        CHECK(p2p[1][i] < p2p[1][i - 1]);
}

TEST(rig_004_fig8)
{
    /* [MMT2018] Sec. 5.1 / Table 3: max 3.9e8, mean 3.3e8, min 1.9e8 N/m (15%) */
    gd_gear_pair_geometry g;
    pair_004(&g);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.cycles = 2;
    gd_tvms_result *r = run(&g, &o);
    REQUIRE(r);
    CHECK_REL(r->max, 3.9e8, 0.15);
    CHECK_REL(r->mean, 3.3e8, 0.15);
    CHECK_REL(r->min, 1.9e8, 0.15);
    /* one tooth pair entering at theta = 0 meshes double - single - double over
     * [0, eps T): two pairs before (eps - 1) T and after T, one in between */
    double eps = r->geom.contact_ratio_transverse, T = r->mesh_period_rad;
    int bad = 0;
    double kmax_single = 0, kmin_double = 1e300;
    for (size_t i = 0; i < r->n; i++) {
        double ph = fmod(r->angle_rad[i] / T, 1.0);
        int want = ph < eps - 1 - 1e-9 ? 2 : ph > eps - 1 + 1e-9 ? 1 : -1;
        if (want > 0 && r->pairs_in_contact[i] != want) bad++;
        if (want == 1 && r->stiffness[i] > kmax_single) kmax_single = r->stiffness[i];
        if (want == 2 && r->stiffness[i] < kmin_double) kmin_double = r->stiffness[i];
    }
    CHECK(bad == 0);
    CHECK(kmax_single < kmin_double); /* max in double, min in single contact */
    /* the pair that entered at 0 carries load through [0, eps T) and none after */
    size_t i_mid = (size_t)(0.5 * (eps - 1 + 1) * r->points); /* mid single zone */
    CHECK_REL(r->load_share[i_mid * r->max_pairs + 0], 1.0, 1e-12);
    size_t i_late = r->points + (size_t)(0.5 * (eps - 1) * r->points); /* 2nd cycle, double */
    CHECK(r->load_share[i_late * r->max_pairs + 1] > 0.2);
    gd_tvms_free(r);
}

TEST(periodic_with_base_pitch)
{
    for (int p = 1; p <= 2; p++) {
        gd_gear_pair_geometry g;
        pair_002(&g, p, p == 1 ? 17 : 0);
        gd_tvms_options o;
        gd_tvms_options_init(&o);
        o.points = 97;
        o.cycles = 3;
        gd_tvms_result *r = run(&g, &o);
        REQUIRE(r);
        CHECK_REL(r->mesh_period_rad * r->geom.base_radius[0], r->geom.base_pitch_transverse,
                  1e-12);
        double worst = 0;
        for (size_t i = 0; i + r->points < r->n; i++) {
            double e = fabs(r->stiffness[i + r->points] - r->stiffness[i]) / r->mean;
            if (e > worst) worst = e;
            CHECK(r->pairs_in_contact[i + r->points] == r->pairs_in_contact[i]);
        }
        CHECK(worst < 1e-9);
        gd_tvms_free(r);
    }
}

/* k at any angle through the slicing sum, for continuity tests */
static double k_at(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d,
                   const gd_ms_energy_law *e, int slices, double theta)
{
    gd_ms_slicing sl = {d, g->face_width, slices, gd_ms_energy_law_eval, e, 4};
    return gd_ms_slicing_eval(&sl, theta, NULL, NULL);
}

TEST(continuity_where_slices_enter_and_leave)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    pair_002(&g, 1, 20);
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    gd_ms_energy_law e;
    REQUIRE(gd_ms_energy_law_init(&e, &g, &d, 1e-10) == 0);
    const int N = 50;
    double tb = d.overlap_length / g.face_width, T = d.mesh_period, p = d.base_pitch_transverse;
    double worst = 0, kref = k_at(&g, &d, &e, N, 0.3 * T);
    /* slice boundary y_i enters where s_A + q p - y_i tb = s_A, and leaves at s_E */
    for (int i = 0; i <= N; i += 7) {
        double y = g.face_width * i / N;
        double q_in = y * tb / p, q_out = (d.contact_length + y * tb) / p;
        double qs[2] = {q_in, q_out};
        for (int k = 0; k < 2; k++) {
            double th = qs[k] * T, h = 1e-9 * T;
            double jump = fabs(k_at(&g, &d, &e, N, th + h) - k_at(&g, &d, &e, N, th - h));
            if (jump > worst) worst = jump;
        }
    }
    CHECK(worst < 1e-5 * kref);
    /* and no jumps anywhere: steps between 20000 samples are O(1/20000) */
    double step = 0;
    for (int i = 0; i < 20000; i++) {
        double a = k_at(&g, &d, &e, N, T * i / 20000.0),
               b = k_at(&g, &d, &e, N, T * (i + 1) / 20000.0);
        if (fabs(b - a) > step) step = fabs(b - a);
    }
    CHECK(step < 2e-3 * kref);
    /* a spur pair, by contrast, jumps by a whole tooth pair where one enters */
    gd_gear_pair_geometry gs;
    gd_gear_pair_derived ds;
    pair_002(&gs, 1, 0);
    REQUIRE(gd_gear_pair_derive(&gs, &ds, &err) == GD_OK);
    gd_ms_energy_law es;
    REQUIRE(gd_ms_energy_law_init(&es, &gs, &ds, 1e-10) == 0);
    double h = 1e-9 * ds.mesh_period;
    double sj = k_at(&gs, &ds, &es, 1, h) - k_at(&gs, &ds, &es, 1, -h);
    CHECK(sj > 0.2 * kref);
    gd_ms_energy_law_free(&es);
    gd_ms_energy_law_free(&e);
}

TEST(helical_at_zero_helix_equals_spur)
{
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 180;
    gd_gear_pair_geometry g;
    pair_002(&g, 2, 0);
    gd_tvms_result *spur = run(&g, &o);
    g.helix_angle = 1e-10; /* helical code path, vanishing helix */
    gd_tvms_result *hel = run(&g, &o);
    REQUIRE(spur && hel);
    CHECK(hel->slices == 50 && spur->slices == 1);
    CHECK_REL(hel->geom.contact_ratio_transverse, spur->geom.contact_ratio_transverse, 1e-12);
    double worst = 0;
    for (size_t i = 1; i < spur->n; i++) { /* sample 0 is the instant a pair enters */
        double e = fabs(hel->stiffness[i] - spur->stiffness[i]) / spur->mean;
        if (e > worst) worst = e;
    }
    CHECK(worst < 1e-7);
    CHECK_REL(hel->mean, spur->mean, 1e-2);
    gd_tvms_free(spur);
    gd_tvms_free(hel);
}

TEST(linear_in_face_width)
{
    for (int m = 0; m < GD_TVMS_METHOD_COUNT_; m++) {
        gd_tvms_options o;
        gd_tvms_options_init(&o);
        o.method = (gd_tvms_method)m;
        gd_gear_pair_geometry g;
        pair_004(&g);
        gd_tvms_result *a = run(&g, &o);
        g.face_width *= 2.5;
        gd_tvms_result *b = run(&g, &o);
        REQUIRE(a && b);
        for (size_t i = 0; i < a->n; i++)
            CHECK_REL(b->stiffness[i], 2.5 * a->stiffness[i], 1e-9);
        gd_tvms_free(a);
        gd_tvms_free(b);
    }
    /* helical: the contact lines change shape, but the mean follows b exactly */
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 720;
    gd_gear_pair_geometry g;
    pair_002(&g, 1, 20);
    gd_tvms_result *a = run(&g, &o);
    g.face_width *= 2;
    gd_tvms_result *b = run(&g, &o);
    REQUIRE(a && b);
    CHECK_REL(b->mean, 2 * a->mean, 2e-3);
    gd_tvms_free(a);
    gd_tvms_free(b);
}

TEST(load_shares_sum_to_one)
{
    for (int m = 0; m < GD_TVMS_METHOD_COUNT_; m++)
        for (int p = 1; p <= 2; p++) {
            gd_tvms_options o;
            gd_tvms_options_init(&o);
            o.method = (gd_tvms_method)m;
            o.cycles = 2;
            gd_gear_pair_geometry g;
            pair_002(&g, p, 15);
            gd_tvms_result *r = run(&g, &o);
            REQUIRE(r);
            for (size_t i = 0; i < r->n; i++) {
                double s = 0;
                int nz = 0;
                for (int j = 0; j < r->max_pairs; j++) {
                    double v = r->load_share[i * r->max_pairs + j];
                    CHECK(v >= 0 && v <= 1);
                    s += v;
                    nz += v > 0;
                }
                CHECK_ABS(s, 1.0, 1e-12);
                CHECK(nz == r->pairs_in_contact[i]);
            }
            gd_tvms_free(r);
        }
}

typedef struct sin_ctx {
    int calls;
} sin_ctx;
static double f_sin(double x, void *c)
{
    ((sin_ctx *)c)->calls++;
    return sin(x);
}
static double f_peak(double x, void *c)
{
    (void)c;
    return 1.0 / (1e-4 + (x - 0.3) * (x - 0.3));
}

TEST(quadrature_converges)
{
    sin_ctx c = {0};
    CHECK_ABS(gd_ms_integrate(f_sin, &c, 0, GD_MS_PI, 1e-13, NULL), 2.0, 1e-13);
    double exact = (atan(0.7 / 1e-2) + atan(0.3 / 1e-2)) / 1e-2;
    int ne = 0;
    double v = gd_ms_integrate(f_peak, NULL, 0, 1, 1e-10, &ne);
    CHECK_REL(v, exact, 1e-9);
    CHECK(ne > 15); /* it had to adapt */
    ne = 0;         /* a tolerance rounding cannot reach stops on its budget, still accurate */
    CHECK_REL(gd_ms_integrate(f_peak, NULL, 0, 1, 1e-300, &ne), exact, 1e-12);
    CHECK(ne < 70000);
    /* Gauss-Legendre n = 4, 8, 16, 32 on the tooth bending integral converge fast */
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    pair_002(&g, 2, 0);
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    for (int i = 0; i < 2; i++) {
        gd_ms_tooth t = {d.base_radius[i],
                         d.half_angle_base[i],
                         d.root_radius[i],
                         d.bore_radius[i],
                         2.06e11,
                         0.3,
                         0};
        double tc = (i == 0 ? d.contact_start : d.line_of_action - d.contact_end) / t.rb;
        double ref[3], prev_err = 1e300;
        gd_ms_tooth_beam_terms(&t, tc, 1e-14, 0, ref);
        for (int n = 4; n <= 32; n *= 2) {
            double v3[3];
            gd_ms_tooth_beam_terms(&t, tc, 0, n, v3);
            double e = 0;
            for (int k = 0; k < 3; k++)
                e = fmax(e, fabs(v3[k] - ref[k]) / ref[k]);
            CHECK(e < prev_err || e < 1e-13);
            prev_err = e;
        }
        CHECK(prev_err < 1e-11);
        /* the adaptive rule meets its tolerance */
        double c6 = gd_ms_tooth_beam_compliance(&t, tc, 1e-6, NULL);
        CHECK_REL(c6, ref[0] + ref[1] + ref[2], 1e-6);
        CHECK(ref[0] > 0 && ref[1] > 0 && ref[2] > 0);
    }
}

/* Bending and axial energy of the involute tooth integrated in Cartesian form, with
 * the profile from the polar involute r -> (r sin th, r cos th), th = a2 - inv(acos(rb/r)):
 * an independent check of the angle parametrisation of [JMSTHelical] Eqs. 7 and 9. */
TEST(tooth_energy_matches_cartesian_integral)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    pair_004(&g);
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    gd_ms_tooth t = {
        d.base_radius[0], d.half_angle_base[0], d.root_radius[0], d.bore_radius[0], 2e11, 0.3, 0};
    REQUIRE(t.rf > t.rb); /* involute all the way to the root circle */
    double rc = 0.5 * (d.pitch_radius[0] + d.tip_radius[0]);
    double ac = acos(t.rb / rc), thc = t.alpha2 - (tan(ac) - ac);
    double a1 = ac - thc, xc = rc * sin(thc), yc = rc * cos(thc);
    double cb = 0, ca = 0;
    const int n = 200000;
    for (int i = 0; i < n; i++) {
        double r0 = t.rf + (rc - t.rf) * i / n, r1 = t.rf + (rc - t.rf) * (i + 1) / n;
        double y[2], x[2], rr[2] = {r0, r1};
        for (int k = 0; k < 2; k++) {
            double a = acos(t.rb / rr[k]), th = t.alpha2 - (tan(a) - a);
            x[k] = rr[k] * sin(th), y[k] = rr[k] * cos(th);
        }
        double h = 0.5 * (x[0] + x[1]), ym = 0.5 * (y[0] + y[1]), dy = y[1] - y[0];
        double M = cos(a1) * (yc - ym) - sin(a1) * xc; /* per unit load */
        cb += M * M / (2e11 * 2 * h * h * h / 3) * dy;
        ca += sin(a1) * sin(a1) / (2e11 * 2 * h) * dy;
    }
    double v[3];
    gd_ms_tooth_beam_terms(&t, tan(ac), 1e-12, 0, v);
    CHECK_REL(v[0], cb, 1e-6);
    CHECK_REL(v[2], ca, 1e-6);
}

TEST(energy_table_matches_direct)
{
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    pair_004(&g);
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    gd_ms_energy_law e;
    REQUIRE(gd_ms_energy_law_init(&e, &g, &d, 1e-10) == 0);
    double worst = 0;
    for (int i = 0; i <= 37; i++) {
        double s = d.contact_start + d.contact_length * (i + 0.31) / 38.0;
        if (s > d.contact_end) s = d.contact_end;
        double a = gd_ms_energy_law_eval(s, &e), b = gd_ms_energy_pair_stiffness(&e, s);
        worst = fmax(worst, fabs(a - b) / b);
    }
    CHECK(worst < 1e-8);
    CHECK(e.table.n <= 257);
    /* Hertz of Yang & Lin: k_h = pi E L / (4 (1 - nu^2)) */
    CHECK_REL(1 / gd_ms_hertz_compliance(2e11, 0.3, 2e11, 0.3), GD_MS_PI * 2e11 / (4 * 0.91),
              1e-14);
    gd_ms_energy_law_free(&e);
}

TEST(iso6336_values)
{
    /* spur z 20/40, x = 0, standard rack: q' = C1 + C2/20 + C3/40 */
    gd_gear_pair_geometry g;
    gd_gear_pair_derived d;
    gd_error err;
    gd_gear_pair_geometry_init(&g);
    g.gear[0].teeth = 20, g.gear[1].teeth = 40, g.normal_module = 3e-3, g.face_width = 0.03;
    REQUIRE(gd_gear_pair_derive(&g, &d, &err) == GD_OK);
    gd_ms_iso iso;
    gd_ms_iso6336(&g, &d, &iso);
    double q = 0.04723 + 0.15551 / 20 + 0.25791 / 40;
    CHECK_REL(iso.c_th, 1 / q, 1e-12);
    CHECK_REL(iso.C_B, 0.975, 1e-12); /* h_fP = 1.25 m_n */
    CHECK_REL(iso.c_single, 1e9 * 0.8 * 0.975 / q, 1e-12);
    CHECK_REL(iso.c_gamma_alpha, iso.c_single * (0.75 * d.contact_ratio_transverse + 0.25), 1e-12);
    CHECK_REL(iso.c_gamma_beta, 0.85 * iso.c_gamma_alpha, 1e-12);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.method = GD_TVMS_ISO6336;
    gd_tvms_result *r = run(&g, &o);
    REQUIRE(r);
    CHECK_REL(r->mean, iso.c_gamma_alpha * 0.03, 1e-12);
    CHECK(r->peak_to_peak == 0);
    gd_tvms_free(r);
}

TEST(single_pair_law_and_square)
{
    CHECK_REL(gd_ms_cai_factor(0), 0.55, 1e-15);
    CHECK_REL(gd_ms_cai_factor(0.5), 1.0, 1e-15);
    CHECK_REL(gd_ms_cai_factor(1), 0.55, 1e-15);
    gd_gear_pair_geometry g;
    pair_004(&g);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 1000;
    o.method = GD_TVMS_SINGLE_PAIR;
    gd_tvms_result *r = run(&g, &o);
    REQUIRE(r);
    double eps = r->geom.contact_ratio_transverse;
    /* mid single contact: the pair is mid-arc, so k = K_m = c' b */
    size_t i = (size_t)(0.5 * eps * 1000);
    CHECK(r->pairs_in_contact[i] == 1);
    CHECK_REL(r->stiffness[i], r->iso_single_stiffness, 1e-5);
    /* entering pair contributes 0.55 K_m at theta = 0, plus the leaving one */
    CHECK_REL(r->stiffness[0], r->iso_single_stiffness * (0.55 + gd_ms_cai_factor(1 / eps)), 1e-9);
    gd_tvms_free(r);
    o.method = GD_TVMS_SQUARE;
    r = run(&g, &o);
    REQUIRE(r);
    int ndouble = 0;
    for (size_t k = 0; k < r->n; k++) {
        double v = r->stiffness[k] / r->iso_single_stiffness;
        CHECK(fabs(v - 1) < 1e-12 || fabs(v - 2) < 1e-12);
        ndouble += v > 1.5;
    }
    CHECK_ABS(ndouble / 1000.0, eps - 1, 1.5e-3);
    CHECK_REL(r->mean, r->iso_single_stiffness * eps, 2e-3);
    gd_tvms_free(r);
}

TEST(body_compliance_in_series)
{
    gd_gear_pair_geometry g;
    pair_002(&g, 1, 20);
    g.gear[0].body_torsional_stiffness = 2e6;
    g.gear[1].web_thickness = 8e-3; /* web from the bore to root - 2 m_n */
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.points = 90;
    gd_tvms_result *a = run(&g, &o);
    o.body_compliance = 1;
    gd_tvms_result *b = run(&g, &o);
    REQUIRE(a && b);
    double cb = cos(a->geom.base_helix_angle);
    double r1 = a->geom.base_radius[0] * cb, r2 = a->geom.base_radius[1] * cb;
    double ro = a->geom.root_radius[1] - 2 * 1.75e-3, ri = 12.7e-3;
    double kt2 = 4 * GD_MS_PI * 2.06e11 / 2.6 * 8e-3 / (1 / (ri * ri) - 1 / (ro * ro));
    double kbody = 1 / (r1 * r1 / 2e6 + r2 * r2 / kt2);
    CHECK_REL(b->body_stiffness, kbody, 1e-12);
    for (size_t i = 0; i < a->n; i++)
        CHECK_REL(b->stiffness[i], 1 / (1 / a->stiffness[i] + 1 / kbody), 1e-12);
    CHECK(b->mean < a->mean);
    gd_tvms_free(a);
    gd_tvms_free(b);
}

TEST(eval_and_fourier)
{
    gd_gear_pair_geometry g;
    pair_002(&g, 2, 10);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.harmonics = 3;
    gd_tvms_result *r = run(&g, &o);
    REQUIRE(r);
    double T = r->mesh_period_rad;
    for (size_t i = 0; i < r->points; i += 37) {
        CHECK_REL(gd_tvms_eval(r, r->angle_rad[i]), r->stiffness[i], 1e-9);
        CHECK_REL(gd_tvms_eval(r, r->angle_rad[i] + 7 * T), r->stiffness[i], 1e-9);
        CHECK_REL(gd_tvms_eval(r, r->angle_rad[i] - 3 * T), r->stiffness[i], 1e-9);
    }
    double mid = gd_tvms_eval(r, 0.5 * (r->angle_rad[10] + r->angle_rad[11]));
    CHECK_REL(mid, 0.5 * (r->stiffness[10] + r->stiffness[11]), 1e-12);
    /* rebuilding from the harmonics approximates the samples */
    double rms = 0;
    for (size_t i = 0; i < r->points; i++) {
        double v = r->mean;
        for (int h = 1; h <= 3; h++)
            v += r->harmonic_amplitude[h - 1] *
                 cos(h * 22 * r->angle_rad[i] + r->harmonic_phase[h - 1]);
        rms += (v - r->stiffness[i]) * (v - r->stiffness[i]);
    }
    CHECK(sqrt(rms / r->points) < 0.25 * r->peak_to_peak);
    gd_tvms_free(r);
    /* exact on a pure harmonic */
    double x[64], amp[3], ph[3];
    for (int i = 0; i < 64; i++)
        x[i] = 5 + 2 * cos(2 * 2 * GD_MS_PI * i / 64 + 0.3);
    gd_ms_fourier(x, 64, 3, amp, ph);
    CHECK_ABS(amp[0], 0, 1e-12);
    CHECK_REL(amp[1], 2, 1e-12);
    CHECK_REL(ph[1], 0.3, 1e-12);
}

static gd_status derive_err(const gd_gear_pair_geometry *g, gd_error *err)
{
    gd_gear_pair_derived d;
    gd_error_clear(err);
    return gd_gear_pair_derive(g, &d, err);
}

TEST(bad_geometry_errors)
{
    gd_gear_pair_geometry g;
    gd_error err;
    /* undercut: 12 teeth without profile shift (limit x >= 1 - 12 sin^2(20)/2 = 0.298) */
    pair_004(&g);
    g.gear[0].teeth = 12, g.gear[0].bore_radius = 0;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driver.profile_shift");
    CHECK(strstr(err.message, "undercut") && strstr(err.message, "0.298"));
    g.gear[0].profile_shift = 0.3; /* enough shift cures it */
    CHECK(derive_err(&g, &err) == GD_OK);
    /* contact ratio below 1 */
    pair_004(&g);
    g.gear[0].addendum_coef = g.gear[1].addendum_coef = 0.45;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "below the limit 1") != NULL);
    /* negative clearance: driven tip 1.3 m_n above pitch vs 1.25 m_n dedendum */
    pair_004(&g);
    g.gear[1].tip_radius = 0.032 + 1.3 * 2e-3;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.tip_radius");
    CHECK(strstr(err.message, "negative tip clearance") != NULL);
    /* tip interference: driven tip 1.2 m_n meets the 20-tooth driver below its form
     * circle (clearance kept by a deeper driver root) */
    gd_gear_pair_geometry_init(&g);
    g.normal_module = 2e-3, g.face_width = 0.02;
    g.gear[0].teeth = 20, g.gear[1].teeth = 60;
    g.gear[1].tip_radius = (30 + 1.2) * 2e-3;
    g.gear[0].root_radius = (10 - 1.3) * 2e-3;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.tip_radius");
    CHECK(strstr(err.message, "interference") != NULL);
    /* pressure angle in rad by mistake */
    pair_004(&g);
    g.normal_pressure_angle = 20;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "normal_pressure_angle");
    CHECK(strstr(err.hint, "did you mean '20 deg'") != NULL);
    /* bore too large, pointed tip, jammed centre distance, teeth */
    pair_004(&g);
    g.gear[1].bore_radius = 0.029;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.bore_radius");
    /* bore far below the fillet-foundation fit (issue 38 M7: through the C API a bore
     * of 1e-300 m reached the TVMS and was reported as "a bug") */
    pair_004(&g);
    g.gear[0].bore_radius = 1e-300;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driver.bore_radius");
    CHECK(strstr(err.message, "tenth of the root radius") != NULL);
    gd_tvms_options o0;
    gd_tvms_options_init(&o0);
    gd_tvms_result *r0 = NULL;
    CHECK(gd_tvms_compute(&g, &o0, &r0, &err) == GD_EINPUT && r0 == NULL);
    CHECK_STR(err.field, "driver.bore_radius");
    CHECK(strstr(err.hint, "bug") == NULL);
    pair_004(&g);
    g.gear[1].teeth = 8, g.gear[1].profile_shift = 1.2;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.tip_radius");
    CHECK(strstr(err.message, "point") != NULL);
    pair_004(&g);
    g.gear[0].profile_shift = 0.5, g.center_distance = 0.080;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "center_distance");
    pair_004(&g);
    g.gear[1].teeth = 3;
    CHECK(derive_err(&g, &err) == GD_EINPUT);
    CHECK_STR(err.field, "driven.teeth");
    /* unknown method */
    gd_tvms_method m;
    gd_error e;
    CHECK(gd_tvms_method_parse("fem", &m, &e) == GD_EINPUT);
    CHECK_STR(e.message, "unknown method 'fem'");
    CHECK(gd_tvms_method_parse("single-pair-law", &m, NULL) == GD_OK && m == GD_TVMS_SINGLE_PAIR);
    pair_004(&g);
    gd_tvms_options o;
    gd_tvms_options_init(&o);
    o.method = (gd_tvms_method)17;
    gd_tvms_result *r = (gd_tvms_result *)&o; /* must be reset to NULL */
    CHECK(gd_tvms_compute(&g, &o, &r, &err) == GD_EINPUT);
    CHECK(r == NULL);
    CHECK_STR(err.field, "method");
    gd_tvms_options_init(&o);
    o.points = 2;
    CHECK(gd_tvms_compute(&g, &o, &r, &err) == GD_EINPUT);
    CHECK_STR(err.field, "points");
}

static const char MODEL[] =
    "materials:\n"
    "  steel: {density: 7800, E: 2.0e11, poisson: 0.3}\n"
    "shafts: []\n"
    "meshes:\n"
    "  - name: m1\n"
    "    driver: gear48\n"
    "    driven: gear32\n"
    "    teeth: [48, 32]\n"
    "    base_radius: [0.048, 0.032]\n"
    "    damping: 1.8e3\n"
    "    coupling: lateral-torsional\n"
    "    geometry:\n"
    "      normal_module: 2 mm\n"
    "      face_width: 20 mm\n"
    "      driver: {teeth: 48, material: steel, bore_radius: 12.7 mm}\n"
    "      driven: {teeth: 32, material: {E: 2.0e11, poisson: 0.3}, bore_radius: 12.7 mm}\n"
    "    stiffness: {from: geometry, method: square, points: 120, cycles: 2, slices: 7, "
    "body_compliance: false}\n";

static gd_status read_text(const char *text, gd_gear_pair_geometry *g, gd_tvms_options *o,
                           gd_error *err)
{
    gd_ydoc *doc = NULL;
    gd_error_clear(err);
    gd_status st = gd_ydoc_load_string(text, "t.yaml", &doc, err);
    if (st) return st;
    gd_yreader r = {"t.yaml", err};
    const gd_ynode *mesh = gd_ymap_get(doc->root, "meshes")->items[0];
    gd_tvms_options_init(o);
    st = gd_gear_pair_read(&r, doc->root, mesh, "meshes[0]", g, o);
    gd_ydoc_free(doc);
    return st;
}

static char *replace(const char *s, const char *from, const char *to)
{
    const char *p = strstr(s, from);
    if (!p) return NULL;
    size_t n = strlen(s) - strlen(from) + strlen(to) + 1;
    char *out = malloc(n);
    if (!out) return NULL;
    snprintf(out, n, "%.*s%s%s", (int)(p - s), s, to, p + strlen(from));
    return out;
}

TEST(reader)
{
    gd_gear_pair_geometry g;
    gd_tvms_options o;
    gd_error err;
    REQUIRE(read_text(MODEL, &g, &o, &err) == GD_OK); /* the model's own keys are let be */
    CHECK(g.gear[0].teeth == 48 && g.gear[1].teeth == 32);
    CHECK_REL(g.normal_module, 2e-3, 1e-15);
    CHECK_REL(g.normal_pressure_angle, 20 * DEG, 1e-15); /* default */
    CHECK_REL(g.gear[1].E, 2e11, 1e-15);
    CHECK_REL(g.gear[0].bore_radius, 12.7e-3, 1e-15);
    CHECK(o.method == GD_TVMS_SQUARE && o.points == 120 && o.cycles == 2 && o.slices == 7);
    CHECK(g.hand == 1);
    char *t = replace(MODEL, "damping: 1.8e3", "damping: 1.8e3\n    hand: left");
    REQUIRE(t);
    CHECK(read_text(t, &g, &o, &err) == GD_OK);
    free(t);
    CHECK(g.hand == -1); /* from the mesh's own key */
    static const struct {
        const char *from, *to, *field, *text;
        int line;
    } cases[] = {
        {"face_width: 20 mm", "face_widht: 20 mm", "meshes[0].geometry.face_widht",
         "did you mean 'face_width'", 14},
        {"method: square", "method: fem", "meshes[0].stiffness.method", "energy, iso6336", 17},
        {"from: geometry", "from: table", "meshes[0].stiffness.from", "geometry", 17},
        {"normal_module: 2 mm", "normal_module: 2 mm\n      normal_pressure_angle: 20",
         "meshes[0].geometry.normal_pressure_angle", "did you mean '20 deg'", 14},
        {"teeth: 48, material", "teeth: 12, material", "meshes[0].geometry.driver.profile_shift",
         "undercut", 15},
        {"material: steel", "material: brass", "meshes[0].geometry.driver.material",
         "unknown material", 15},
        {"bore_radius: 12.7 mm}\n      driven", "bore_radius: 44 mm}\n      driven",
         "meshes[0].geometry.driver.bore_radius", "rim below one module", 15},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *bad = replace(MODEL, cases[i].from, cases[i].to);
        REQUIRE(bad);
        gd_status st = read_text(bad, &g, &o, &err);
        free(bad);
        CHECK(st == GD_EINPUT);
        CHECK_STR(err.field, cases[i].field);
        char all[1200];
        snprintf(all, sizeof all, "%s | %s", err.message, err.hint);
        if (!strstr(all, cases[i].text)) {
            fprintf(stderr, "  case %zu: '%s' not in '%s'\n", i, cases[i].text, all);
            CHECK(0);
        }
        CHECK(err.line == cases[i].line);
        CHECK_STR(err.file, "t.yaml");
    }
}

TEST(reads_the_examples)
{
    static const char *const files[3] = {
        "examples/helical_pair1.yaml", "examples/helical_pair2.yaml", "examples/rig2018_pair.yaml"};
    static const double mean[3] = {3.13e8, 3.69e8, 3.3e8};
    for (int i = 0; i < 3; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", GD_SOURCE_DIR, files[i]);
        gd_ydoc *doc = NULL;
        gd_error err;
        REQUIRE(gd_ydoc_load_file(path, &doc, &err) == GD_OK);
        gd_yreader r = {path, &err};
        gd_gear_pair_geometry g;
        gd_tvms_options o;
        gd_tvms_options_init(&o);
        gd_status st = gd_gear_pair_read(&r, doc->root, gd_ymap_get(doc->root, "meshes")->items[0],
                                         "meshes[0]", &g, &o);
        gd_ydoc_free(doc);
        REQUIRE(st == GD_OK);
        gd_tvms_result *res = run(&g, &o);
        REQUIRE(res);
        CHECK_REL(res->mean, mean[i], i == 2 ? 0.15 : 0.10);
        gd_tvms_free(res);
    }
}

RUN_TESTS(T(table1_contact_ratios_002), T(derived_geometry_standard_spur),
          T(mean_stiffness_002_sec51), T(fluctuation_trend_002_fig4), T(rig_004_fig8),
          T(periodic_with_base_pitch), T(continuity_where_slices_enter_and_leave),
          T(helical_at_zero_helix_equals_spur), T(linear_in_face_width), T(load_shares_sum_to_one),
          T(quadrature_converges), T(tooth_energy_matches_cartesian_integral),
          T(energy_table_matches_direct), T(iso6336_values), T(single_pair_law_and_square),
          T(body_compliance_in_series), T(eval_and_fourier), T(bad_geometry_errors), T(reader),
          T(reads_the_examples))
