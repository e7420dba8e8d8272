/* Model keys read only by time integration: mesh TVMS tables, damping laws,
 * transmission error and backlash; squeeze film dampers; loads, prescribed motion and
 * cam torques (docs/model-format.md, "Time integration"). */
#include "geardyn/model.h"
#include "harness.h"

#define PAIR                                                                                       \
    "dofs: [rz]\n"                                           /* 1 */                               \
    "shafts:\n"                                              /* 2 */                               \
    "  - {name: a, nodes: [{name: p}, {name: m}]}\n"         /* 3 */                               \
    "  - {name: b, nodes: [{name: g}]}\n"                    /* 4 */                               \
    "disks:\n"                                               /* 5 */                               \
    "  - {node: p, polar_inertia: 1e-3}\n"                   /* 6 */                               \
    "  - {node: m, polar_inertia: 1e-2}\n"                   /* 7 */                               \
    "  - {node: g, polar_inertia: 2e-3}\n"                   /* 8 */                               \
    "springs: [{node: m, to: p, dof: rz, stiffness: 1e4}]\n" /* 9 */                               \
    "meshes:\n"                                              /* 10 */                              \
    "  - name: mesh\n"                                       /* 11 */                              \
    "    driver: p\n"                                        /* 12 */                              \
    "    driven: g\n"                                        /* 13 */                              \
    "    teeth: [20, 40]\n"                                  /* 14 */                              \
    "    base_radius: [0.02, 0.04]\n"                        /* 15 */

static gd_model *load(gd_test_state *gd_ts_, const char *yaml, gd_error *err)
{
    gd_model *m = NULL;
    gd_error_clear(err);
    gd_status st = gd_model_load_string(yaml, "dyn.yaml", &m, err);
    if (st) fprintf(stderr, "    %d %s: %s | %s\n", err->line, err->field, err->message, err->hint);
    CHECK(st == GD_OK);
    return m;
}

static void expect(gd_test_state *gd_ts_, int line, const char *yaml, int want_line,
                   const char *field, const char *word)
{
    gd_error err;
    gd_model *m = NULL;
    gd_error_clear(&err);
    gd_status st = gd_model_load_string(yaml, "dyn.yaml", &m, &err);
    int ok = st == GD_EINPUT && m == NULL && err.line == want_line && !strcmp(err.field, field) &&
             (strstr(err.message, word) || strstr(err.hint, word)) && err.hint[0];
    if (!ok) {
        fprintf(stderr, "  test line %d: got %d %d:%s: %s | %s\n", line, st, err.line, err.field,
                err.message, err.hint);
        gd_ts_->checks_failed++;
    }
    gd_model_free(m);
}
#define EXPECT(yaml, l, f, w) expect(gd_ts_, __LINE__, yaml, l, f, w)

TEST(mesh_tvms_table_damping_backlash_and_ste)
{
    gd_error err;
    gd_model *m = load(gd_ts_,
                       PAIR "    tvms: {angle: [0, 3 deg, 9 deg, 15 deg], stiffness: [3e8, 4e8, "
                            "4e8, 2e8], phase: 1 deg}\n"
                            "    damping: {constant: 100, per_stiffness: 1e-6 s, separated: 5}\n"
                            "    backlash: {gap: 25 um, coast_stiffness_ratio: 0.8}\n"
                            "    transmission_error: {angle: [0, 9 deg], error: [0, 2 um]}\n",
                       &err);
    REQUIRE(m);
    const gd_mesh *g = &m->meshes[0];
    REQUIRE(g->dyn.tvms && g->dyn.ste);
    CHECK_REL(g->dyn.tvms->period, 2 * M_PI / 20, 1e-14);
    CHECK_REL(gd_table_eval(g->dyn.tvms, 3 * M_PI / 180, NULL, NULL), 4e8, 1e-12);
    /* periodic closure: halfway from 15 deg (2e8) to 18 deg = 0 (3e8) */
    CHECK_REL(gd_table_eval(g->dyn.tvms, 16.5 * M_PI / 180, NULL, NULL), 2.5e8, 1e-9);
    /* mean of the piecewise-linear loop over the 18 deg period:
     * (3.5*3 + 4*6 + 3*6 + 2.5*3) / 18 = 3.333e8 */
    CHECK_REL(g->stiffness, 60.0 / 18.0 * 1e8, 1e-5);
    CHECK_REL(g->dyn.tvms_phase, M_PI / 180, 1e-14);
    CHECK_REL(g->damping, 100, 1e-15);
    CHECK_REL(g->dyn.damping_per_stiffness, 1e-6, 1e-15);
    CHECK_REL(g->dyn.damping_separated, 5, 1e-15);
    CHECK_REL(gd_mesh_linear_damping(g), 100 + 1e-6 * g->stiffness, 1e-14);
    CHECK(g->dyn.backlash == 1);
    CHECK_REL(g->dyn.gap, 25e-6, 1e-14);
    CHECK_REL(g->dyn.coast_stiffness_ratio, 0.8, 1e-15);
    CHECK_REL(gd_table_eval(g->dyn.ste, 4.5 * M_PI / 180, NULL, NULL), 1e-6, 1e-9);
    gd_model_free(m);
}

TEST(mesh_dynamics_errors)
{
    EXPECT(PAIR "    tvms: {angle: [0, 20 deg], stiffness: [3e8, 4e8]}\n", 16,
           "meshes[0].tvms.angle", "period");
    EXPECT(PAIR "    tvms: {angle: [0, 5 deg, 3 deg], stiffness: [3e8, 4e8, 1e8]}\n", 16,
           "meshes[0].tvms.angle", "increase");
    EXPECT(PAIR "    tvms: {angle: [0, 5 deg], stiffness: [3e8]}\n", 16, "meshes[0].tvms.stiffness",
           "values for");
    EXPECT(PAIR "    tvms: {angle: [0, 5 deg], stiffness: [3e8, -1]}\n", 16, "meshes[0].tvms",
           "positive");
    EXPECT(PAIR "    tvms: {angle: [0, 5 deg], stiffness: [3e8, 4e8], interpolation: cubic}\n", 16,
           "meshes[0].tvms.interpolation", "linear");
    EXPECT(PAIR "    stiffness: 3e8\n    backlash: {coast_stiffness_ratio: 1}\n", 17,
           "meshes[0].backlash.gap", "missing");
    EXPECT(PAIR "    stiffness: 3e8\n    backlash: {gap: -1 um}\n", 17, "meshes[0].backlash.gap",
           "negative");
    EXPECT(PAIR "    stiffness: 3e8\n    damping: {constant: 1, per_k: 2}\n", 17,
           "meshes[0].damping.per_k", "per_stiffness");
    /* no stiffness and no table */
    EXPECT(PAIR "    damping: 3\n", 11, "meshes[0].stiffness", "missing");
    /* a table over the mesh period needs the teeth */
    EXPECT("dofs: [rz]\nshafts:\n  - {name: a, nodes: [{name: p}]}\n  - {name: b, nodes: "
           "[{name: g}]}\nmeshes:\n  - {name: m, driver: p, driven: g, base_radius: [0.02, 0.04],\n"
           "     tvms: {angle: [0, 1 deg], stiffness: [1e8, 2e8]}}\n",
           7, "meshes[0].tvms", "teeth");
}

TEST(squeeze_film_damper)
{
    gd_error err;
    gd_model *m =
        load(gd_ts_,
             PAIR "    stiffness: 3e8\n"
                  "bearings:\n"
                  "  - {name: s, node: g, sfd: {viscosity: 6.895e-3 Pa*s, diameter: 35.56 "
                  "mm, length: 17.145 mm, clearance: 76.2 um}}\n"
                  "  - {name: t, node: p, k: 1e6, sfd: {viscosity: 1e-2, diameter: 0.04, "
                  "length: 0.01, clearance: 1e-4, film: 2pi, correction: none}}\n",
             &err);
    REQUIRE(m);
    const gd_bearing *s = &m->bearings[0], *t = &m->bearings[1];
    CHECK(s->has_sfd && t->has_sfd);
    CHECK_REL(s->sfd.radius, 17.78e-3, 1e-12);
    CHECK_REL(s->sfd.length, 17.145e-3, 1e-12);
    CHECK_REL(s->sfd.clearance, 76.2e-6, 1e-12);
    CHECK(s->sfd.film == GD_SFD_PI_FILM && s->sfd.correction == 0);
    CHECK(t->sfd.film == GD_SFD_2PI_FILM && t->sfd.correction < 0);
    CHECK_REL(t->coeffs.kxx, 1e6, 1e-15);
    gd_model_free(m);
    EXPECT(PAIR "    stiffness: 3e8\nbearings:\n  - {node: g, sfd: {viscosity: 1e-2, diameter: "
                "0.04, length: 0.01}}\n",
           18, "bearings[0].sfd.clearance", "missing");
    EXPECT(PAIR "    stiffness: 3e8\nbearings:\n  - {node: g, sfd: {viscosity: 1e-2, diameter: "
                "0.04, length: 0.01, clearance: 0.03}}\n",
           18, "bearings[0].sfd.clearance", "radius");
    EXPECT(PAIR "    stiffness: 3e8\nbearings:\n  - {node: g, sfd: {viscosity: 1e-2, diameter: "
                "0.04, length: 0.01, clearance: 1e-4, film: half}}\n",
           18, "bearings[0].sfd.film", "2pi");
    EXPECT(PAIR "    stiffness: 3e8\nbearings:\n  - {node: g, sfd: {viscosity: 1e-2, diameter: "
                "0.04, length: 0.01, clearance: 1e-4, correction: maybe}}\n",
           18, "bearings[0].sfd.correction", "auto");
}

TEST(loads_prescribed_and_cams)
{
    gd_error err;
    gd_model *m =
        load(gd_ts_,
             PAIR "    stiffness: 3e8\n"
                  "excitations:\n"
                  "  unbalances: false\n"
                  "  loads:\n"
                  "    - {name: brake, node: g, value: -12 N*m}\n"
                  "    - {node: g, mean: 5, amplitude: 2, frequency: 50 Hz, phase: 90 deg}\n"
                  "    - {node: g, amplitude: 3, order: 2}\n"
                  "    - {node: g, table: {angle: [0, 180 deg], value: [1, 3]}}\n"
                  "prescribed:\n"
                  "  - {node: m, motion: nominal}\n"
                  "  - {node: p, dof: rz, speed: 600 rpm}\n"
                  "cam_torques:\n"
                  "  - name: intake\n"
                  "    camshaft: g\n"
                  "    lift: {angle: [0, 90 deg, 180 deg, 270 deg], lift: [0, 5 mm, 8 mm, 5 mm]}\n"
                  "    valves: [{mass: 0.1 kg, phase: 0}, {mass: 0.12, phase: 90 deg}]\n"
                  "  - camshaft: g\n"
                  "    include_acceleration: false\n"
                  "    lift: {harmonics: {mean: 4 mm, cos: [-4 mm, 0.5 mm]}}\n"
                  "    valves: [{mass: 0.1}]\n",
             &err);
    REQUIRE(m);
    CHECK(m->excite_unbalances == 0);
    REQUIRE(m->nexcitations == 4);
    CHECK(m->excitations[0].law.kind == GD_LOAD_CONSTANT && m->excitations[0].dof == GD_RZ);
    CHECK_REL(m->excitations[0].law.mean, -12, 1e-15);
    CHECK(m->excitations[1].law.kind == GD_LOAD_HARMONIC_TIME);
    CHECK_REL(m->excitations[1].law.frequency, 100 * M_PI, 1e-14);
    CHECK_REL(m->excitations[1].law.phase, M_PI / 2, 1e-14);
    CHECK(m->excitations[2].law.kind == GD_LOAD_HARMONIC_ANGLE);
    CHECK_REL(m->excitations[2].law.frequency, 2, 1e-15);
    CHECK(m->excitations[3].law.kind == GD_LOAD_TABLE_ANGLE);
    CHECK_REL(gd_load_eval(&m->excitations[3].law, 0, M_PI / 2), 2, 1e-12);
    REQUIRE(m->nprescribed == 2);
    CHECK(m->prescribed[0].law.kind == GD_PRESCRIBED_NOMINAL);
    CHECK(m->prescribed[1].law.kind == GD_PRESCRIBED_SPEED);
    CHECK_REL(m->prescribed[1].law.speed, 20 * M_PI, 1e-14);
    REQUIRE(m->ncams == 2);
    CHECK(m->cams[0].nvalves == 2 && m->cams[0].include_acceleration == 1);
    CHECK_REL(m->cams[0].valve_phase[1], M_PI / 2, 1e-14);
    CHECK_REL(gd_lift_eval(&m->cams[0].lift, M_PI, NULL, NULL), 8e-3, 1e-12);
    CHECK(m->cams[1].lift.kind == GD_LIFT_HARMONIC && m->cams[1].include_acceleration == 0);
    CHECK_REL(gd_lift_eval(&m->cams[1].lift, 0, NULL, NULL), 0.5e-3, 1e-12);
    gd_model_free(m);
}

#define PAIR_K PAIR "    stiffness: 3e8\n"

TEST(load_prescribed_and_cam_errors)
{
    EXPECT(PAIR_K "excitations:\n  loads:\n    - {node: g, value: 1, amplitude: 2}\n", 19,
           "excitations.loads[0]", "constant");
    EXPECT(PAIR_K "excitations:\n  loads:\n    - {node: g, amplitude: 2}\n", 19,
           "excitations.loads[0]", "frequency");
    EXPECT(PAIR_K "excitations:\n  loads:\n    - {node: g}\n", 19, "excitations.loads[0]",
           "no value");
    EXPECT(PAIR_K "excitations:\n  loads:\n    - {node: g, value: 3 m}\n", 19,
           "excitations.loads[0].value", "N*m");
    EXPECT(PAIR_K "excitations:\n  loads:\n    - {node: zz, value: 3}\n", 19,
           "excitations.loads[0].node", "unknown node");
    EXPECT(PAIR_K "excitations:\n  unbalance: true\n", 18, "excitations.unbalance", "unbalances");
    EXPECT(PAIR_K "prescribed:\n  - {node: m}\n", 18, "prescribed[0]", "missing");
    EXPECT(PAIR_K "prescribed:\n  - {node: m, motion: nominal, speed: 3}\n", 18, "prescribed[0]",
           "twice");
    EXPECT(PAIR_K "prescribed:\n  - {node: m, motion: nominal}\n  - {node: m, speed: 1}\n", 19,
           "prescribed[1]", "already");
    EXPECT(PAIR_K "prescribed:\n  - {node: m, motion: fixed}\n", 18, "prescribed[0].motion",
           "nominal");
    /* the "missing cam table" */
    EXPECT(PAIR_K "cam_torques:\n  - {camshaft: g, valves: [{mass: 0.1}]}\n", 18,
           "cam_torques[0].lift", "lift");
    EXPECT(PAIR_K "cam_torques:\n  - {camshaft: g, lift: {angle: [0, 1], lift: [0, 1e-3]}, "
                  "valves: [{mass: 0.1}]}\n",
           18, "cam_torques[0].lift.angle", "three");
    EXPECT(PAIR_K "cam_torques:\n  - {camshaft: g, lift: {angle: [0, 1, 2], lift: [0, 1e-3, "
                  "0]}, valves: []}\n",
           18, "cam_torques[0].valves", "no valves");
    EXPECT(PAIR_K "cam_torques:\n  - {camshaft: g, lift: {angle: [0, 1, 2], lift: [0, 1e-3, "
                  "0]}, valves: [{mass: -1}]}\n",
           18, "cam_torques[0].valves[0].mass", "positive");
}

RUN_TESTS(T(mesh_tvms_table_damping_backlash_and_ste), T(mesh_dynamics_errors),
          T(squeeze_film_damper), T(loads_prescribed_and_cams), T(load_prescribed_and_cam_errors))
