/* Gear mesh element invariants (DESIGN.md): rigid rotation in the gear ratio and
 * common translation give no deformation, helical at 0 deg equals spur, torsional
 * level is k [rb1^2, rb1 rb2; rb1 rb2, rb2^2]. */
#include "elements/elements_impl.h"
#include "geardyn/system.h"
#include "harness.h"

static gd_mesh make_mesh(double gamma, double alpha, double beta, int hand, int sense,
                         gd_coupling level)
{
    gd_mesh g;
    memset(&g, 0, sizeof g);
    g.base_radius[0] = 0.031;
    g.base_radius[1] = 0.077;
    g.pressure_angle = alpha;
    g.helix_angle = beta;
    g.base_helix_angle = atan(tan(beta) * cos(alpha));
    g.hand = hand;
    g.line_of_centres = gamma;
    g.driver_sense = sense;
    g.stiffness = 1e8;
    g.coupling = level;
    return g;
}

static double dot12(const double *a, const double *q)
{
    double s = 0;
    for (int i = 0; i < 12; i++)
        s += a[i] * q[i];
    return s;
}

/* Sweeps geometry, hand, sense and coupling level. */
#define FOR_ALL_MESHES(body)                                                                       \
    for (int gi = 0; gi < 4; gi++)                                                                 \
        for (int bi = 0; bi < 3; bi++)                                                             \
            for (int hand = -1; hand <= 1; hand += 2)                                              \
                for (int sense = -1; sense <= 1; sense += 2)                                       \
                    for (int lv = 0; lv < 3; lv++) {                                               \
                        gd_mesh g = make_mesh(gi * 1.1 - 0.7, 0.349 + 0.05 * gi, bi * 0.2, hand,   \
                                              sense, (gd_coupling)lv);                             \
                        double a[12];                                                              \
                        gd_mesh_vector_local(&g, a);                                               \
                        body                                                                       \
                    }

TEST(rigid_rotation_in_gear_ratio_gives_no_deformation){FOR_ALL_MESHES({
    double q[12] = {0};
    q[GD_RZ] = 1e-3;
    q[6 + GD_RZ] = -1e-3 * g.base_radius[0] / g.base_radius[1];
    CHECK_ABS(dot12(a, q), 0, 1e-18);
})}

TEST(common_translation_gives_no_deformation){FOR_ALL_MESHES({
    for (int d = GD_X; d <= GD_Z; d++) {
        double q[12] = {0};
        q[d] = q[6 + d] = 1e-4;
        CHECK_ABS(dot12(a, q), 0, 1e-18);
    }
})}

TEST(contact_normal_is_unit_and_torque_resists_the_driver){FOR_ALL_MESHES({
    if (lv != GD_COUPLING_FULL) continue;
    CHECK_REL(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 1.0, 1e-14);
    /* moment arm of the normal force about each centre: rb cos(bb) in the plane */
    CHECK_REL(fabs(a[GD_RZ]), g.base_radius[0] * cos(g.base_helix_angle), 1e-14);
    CHECK_REL(fabs(a[6 + GD_RZ]), g.base_radius[1] * cos(g.base_helix_angle), 1e-14);
    /* compression pushes the driver against its rotation: torque -k d a_rz opposes s */
    CHECK(a[GD_RZ] * sense > 0);
    /* the normal force on each gear is equal and opposite */
    for (int d = 0; d < 3; d++)
        CHECK_ABS(a[d] + a[6 + d], 0, 1e-15);
})}

TEST(helical_at_zero_helix_equals_spur)
{
    for (int lv = 0; lv < 3; lv++)
        for (int hand = -1; hand <= 1; hand += 2) {
            gd_mesh h = make_mesh(0.3, 0.349, 0.0, hand, 1, (gd_coupling)lv);
            gd_mesh s = make_mesh(0.3, 0.349, 0.0, 1, 1, (gd_coupling)lv);
            double ah[12], as[12];
            gd_mesh_vector_local(&h, ah);
            gd_mesh_vector_local(&s, as);
            for (int i = 0; i < 12; i++)
                CHECK_ABS(ah[i], as[i], 1e-16);
            /* spur: no axial or tilt coupling at all */
            for (int k = 0; k < 2; k++)
                for (int d = GD_Z; d <= GD_RY; d++)
                    CHECK_ABS(ah[6 * k + d], 0, 1e-16);
        }
    /* and a small helix angle tends to it continuously */
    gd_mesh h = make_mesh(0.3, 0.349, 1e-7, 1, 1, GD_COUPLING_FULL);
    gd_mesh s = make_mesh(0.3, 0.349, 0.0, 1, 1, GD_COUPLING_FULL);
    double ah[12], as[12];
    gd_mesh_vector_local(&h, ah);
    gd_mesh_vector_local(&s, as);
    for (int i = 0; i < 12; i++)
        CHECK_ABS(ah[i], as[i], 1e-7);
}

TEST(helical_hand_and_sense_flip_axial_thrust)
{
    gd_mesh r = make_mesh(0, 0.349, 0.35, 1, 1, GD_COUPLING_FULL);
    gd_mesh l = make_mesh(0, 0.349, 0.35, -1, 1, GD_COUPLING_FULL);
    gd_mesh rc = make_mesh(0, 0.349, 0.35, 1, -1, GD_COUPLING_FULL);
    double ar[12], al[12], arc[12];
    gd_mesh_vector_local(&r, ar);
    gd_mesh_vector_local(&l, al);
    gd_mesh_vector_local(&rc, arc);
    CHECK_REL(fabs(ar[GD_Z]), sin(r.base_helix_angle), 1e-14);
    CHECK_ABS(ar[GD_Z] + al[GD_Z], 0, 1e-16);
    CHECK_ABS(ar[GD_Z] + arc[GD_Z], 0, 1e-16);
    /* the axial force at the base radius tilts the gear: moment arm rb sin(bb) */
    CHECK_REL(hypot(ar[GD_RX], ar[GD_RY]), r.base_radius[0] * sin(r.base_helix_angle), 1e-13);
}

TEST(torsional_level_is_k_rb_rb)
{
    for (int sense = -1; sense <= 1; sense += 2) {
        gd_mesh g = make_mesh(0.9, 0.349, 0.0, 1, sense, GD_COUPLING_TORSIONAL);
        double a[12];
        gd_mesh_vector_local(&g, a);
        for (int i = 0; i < 12; i++)
            if (i % 6 != GD_RZ) CHECK(a[i] == 0.0);
        double rb1 = g.base_radius[0], rb2 = g.base_radius[1];
        CHECK_REL(g.stiffness * a[GD_RZ] * a[GD_RZ], g.stiffness * rb1 * rb1, 1e-14);
        CHECK_REL(g.stiffness * a[6 + GD_RZ] * a[6 + GD_RZ], g.stiffness * rb2 * rb2, 1e-14);
        CHECK_REL(g.stiffness * a[GD_RZ] * a[6 + GD_RZ], g.stiffness * rb1 * rb2, 1e-14);
    }
}

/* Kumar 2011 ([Kumar2011]) Eq. 3.1: with the line of action along y the mesh deformation is
 * y_p - y_g + r_p th_p + r_g th_g. */
TEST(kumar_mesh_vector)
{
    gd_mesh g = make_mesh(0, 0, 0, 1, 1, GD_COUPLING_LATERAL_TORSIONAL);
    g.base_radius[0] = 0.0445;
    g.base_radius[1] = 0.047;
    double a[12];
    gd_mesh_vector_local(&g, a);
    const double want[12] = {0, 1, 0, 0, 0, 0.0445, 0, -1, 0, 0, 0, 0.047};
    for (int i = 0; i < 12; i++)
        CHECK_ABS(a[i], want[i], 1e-16);
}

RUN_TESTS(T(rigid_rotation_in_gear_ratio_gives_no_deformation),
          T(common_translation_gives_no_deformation),
          T(contact_normal_is_unit_and_torque_resists_the_driver),
          T(helical_at_zero_helix_equals_spur), T(helical_hand_and_sense_flip_axial_thrust),
          T(torsional_level_is_k_rb_rb), T(kumar_mesh_vector))
