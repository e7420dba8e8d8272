/* Models built in code (geardyn/builder.h): the two-shaft rig of examples/rig2018.yaml
 * and the gear pair of examples/chen1998_gear_pair.yaml transcribed into specs give
 * the same system and natural frequencies as the files; errors from code are located
 * by field path with line 0; the specs' defaults. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/builder.h"
#include "geardyn/modal.h"
#include "geardyn/model.h"
#include "geardyn/system.h"
#include "harness.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* ---- helpers ---- */

/* The model's system and modes at default options; 0 on failure. */
static int solve(gd_test_state *gd_ts_, const gd_model *m, gd_system **sys, gd_modal_result **res)
{
    gd_error err;
    gd_modal_options opt;
    gd_modal_options_init(&opt);
    *sys = NULL;
    *res = NULL;
    gd_status st = gd_system_build(m, sys, &err);
    if (!st) st = gd_modal_solve(*sys, &opt, res, &err);
    if (st) fprintf(stderr, "  solve: %s\n", err.message);
    CHECK(st == GD_OK);
    return st == GD_OK;
}

/* The file's model and the code's model have the same DOFs and natural frequencies. */
static void check_same_modes(gd_test_state *gd_ts_, const char *path, const gd_model *built)
{
    gd_error err;
    gd_model *loaded = NULL;
    gd_status st = gd_model_load(path, &loaded, &err);
    if (st) fprintf(stderr, "  load %s: %s\n", path, err.message);
    REQUIRE(st == GD_OK);
    gd_system *sa, *sb;
    gd_modal_result *ra, *rb;
    if (solve(gd_ts_, loaded, &sa, &ra) && solve(gd_ts_, built, &sb, &rb)) {
        CHECK(sa->ndof == sb->ndof);
        CHECK(ra->nmodes == rb->nmodes);
        CHECK(ra->nmodes > 0);
        for (int i = 0; i < ra->nmodes && i < rb->nmodes; i++) {
            CHECK_REL(rb->modes[i].omega_n, ra->modes[i].omega_n, 1e-12);
            CHECK_REL(rb->modes[i].damping_ratio, ra->modes[i].damping_ratio, 1e-9);
        }
        gd_modal_free(rb);
        gd_system_free(sb);
    }
    CHECK(loaded->nnodes == built->nnodes);
    CHECK(loaded->nelements == built->nelements);
    for (int i = 0; i < loaded->nnodes && i < built->nnodes; i++)
        CHECK_STR(built->nodes[i].name, loaded->nodes[i].name);
    for (int s = 0; s < loaded->nshafts && s < built->nshafts; s++)
        CHECK_REL(built->shafts[s].speed_ratio, loaded->shafts[s].speed_ratio, 1e-15);
    gd_modal_free(ra);
    gd_system_free(sa);
    gd_model_free(loaded);
}

#define OK(call)                                                                                   \
    do {                                                                                           \
        gd_status st_ = (call);                                                                    \
        if (st_) fprintf(stderr, "  %s:%d: %s: %s\n", __FILE__, __LINE__, #call, err.message);     \
        REQUIRE(st_ == GD_OK);                                                                     \
    } while (0)

/* ---- examples/rig2018.yaml in code ---- */

/* One shaft of the rig: two sections of 0.25 m, 25.4 mm, eight elements each; named
 * nodes at the ends and mid-span. */
static gd_status rig_shaft(gd_model *m, const char *name, const char *const nodes[3], gd_error *err)
{
    gd_section_spec sec[2];
    gd_station_spec st[3];
    for (int i = 0; i < 2; i++) {
        gd_section_spec_init(&sec[i]);
        sec[i].length = 0.25;
        sec[i].outer_diameter = 25.4e-3;
    }
    for (int i = 0; i < 3; i++) {
        gd_station_spec_init(&st[i]);
        st[i].name = nodes[i];
        st[i].at = 0.25 * i;
    }
    gd_shaft_spec s;
    gd_shaft_spec_init(&s);
    s.name = name;
    s.material = "steel";
    s.elements_per_section = 8;
    s.nsections = 2;
    s.sections = sec;
    s.nstations = 3;
    s.stations = st;
    return gd_model_add_shaft(m, &s, NULL, err);
}

static gd_status rig_disk(gd_model *m, const char *name, double mass, double ip, gd_error *err)
{
    gd_disk_spec d;
    gd_disk_spec_init(&d);
    d.name = name;
    d.node = name;
    d.mass = mass;
    d.polar_inertia = ip;
    return gd_model_add_disk(m, &d, NULL, err);
}

static gd_status rig_bearing(gd_model *m, const char *name, const char *node, gd_error *err)
{
    gd_bearing_spec b;
    gd_bearing_spec_init(&b);
    b.name = name;
    b.node = node;
    b.coeffs.kxx = b.coeffs.kyy = 1e8;
    b.coeffs.cxx = b.coeffs.cyy = 200;
    return gd_model_add_bearing(m, &b, NULL, err);
}

TEST(rig2018_built_in_code_matches_the_file)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("rig2018.c", &m, &err));
    CHECK(!gd_model_is_finished(m));
    OK(gd_model_set_dofs(m,
                         GD_DOF_BIT(GD_X) | GD_DOF_BIT(GD_Y) | GD_DOF_BIT(GD_RX) |
                             GD_DOF_BIT(GD_RY) | GD_DOF_BIT(GD_RZ),
                         &err));
    gd_material_spec steel;
    gd_material_spec_init(&steel);
    steel.name = "steel";
    steel.density = 7800;
    steel.E = 2.0e11;
    steel.poisson = 0.3;
    OK(gd_model_add_material(m, &steel, NULL, &err));
    static const char *const driving[3] = {"brg_d1", "gear48", "brg_d2"};
    static const char *const driven[3] = {"brg_n1", "gear32", "brg_n2"};
    OK(rig_shaft(m, "driving", driving, &err));
    OK(rig_shaft(m, "driven", driven, &err));
    OK(rig_disk(m, "gear48", 1.15, 1.3e-3, &err));
    OK(rig_disk(m, "gear32", 0.522, 2.5e-4, &err));
    OK(rig_bearing(m, "A1", "brg_d1", &err));
    OK(rig_bearing(m, "A2", "brg_d2", &err));
    OK(rig_bearing(m, "B1", "brg_n1", &err));
    OK(rig_bearing(m, "B2", "brg_n2", &err));
    gd_mesh_spec g;
    gd_mesh_spec_init(&g);
    g.name = "mesh";
    g.driver = "gear48";
    g.driven = "gear32";
    g.teeth[0] = 48;
    g.teeth[1] = 32;
    g.base_radius[0] = 0.048;
    g.base_radius[1] = 0.032;
    g.pressure_angle = 20 * DEG;
    g.stiffness = 3.9e8;
    g.damping = 1.8e3;
    g.coupling = GD_COUPLING_LATERAL_TORSIONAL;
    int index = -1;
    OK(gd_model_add_mesh(m, &g, &index, &err));
    CHECK(index == 0);
    OK(gd_model_finish(m, &err));
    CHECK(gd_model_is_finished(m));
    CHECK(m->nnodes == 34);
    CHECK(m->nelements == 32);
    CHECK_REL(m->shafts[1].speed_ratio, -1.5, 1e-15);
    check_same_modes(gd_ts_, "examples/rig2018.yaml", m);
    gd_model_free(m);
}

/* ---- examples/chen1998_gear_pair.yaml in code ---- */

static gd_status lumped_shaft(gd_model *m, const char *name, const char *node, gd_error *err)
{
    gd_station_spec st;
    gd_station_spec_init(&st);
    st.name = node;
    gd_shaft_spec s;
    gd_shaft_spec_init(&s);
    s.name = name;
    s.nstations = 1;
    s.stations = &st;
    return gd_model_add_shaft(m, &s, NULL, err);
}

static gd_status support(gd_model *m, const char *name, const char *node, double k, double c,
                         double kt, double ct, gd_error *err)
{
    gd_bearing_spec b;
    gd_bearing_spec_init(&b);
    b.name = name;
    b.node = node;
    b.coeffs.kxx = b.coeffs.kyy = k;
    b.coeffs.cxx = b.coeffs.cyy = c;
    b.coeffs.ktorsion = kt;
    b.coeffs.ctorsion = ct;
    return gd_model_add_bearing(m, &b, NULL, err);
}

/* The Chen et al. gear pair; with_sfd adds gear a's squeeze film damper. */
static gd_status chen_pair(gd_model *m, gd_error *err)
{
    gd_status st;
    if ((st = gd_model_set_dofs(m, GD_DOF_BIT(GD_X) | GD_DOF_BIT(GD_Y) | GD_DOF_BIT(GD_RZ), err)) ||
        (st = lumped_shaft(m, "shaft_a", "gear_a", err)) ||
        (st = lumped_shaft(m, "shaft_b", "gear_b", err)) ||
        (st = rig_disk(m, "gear_a", 8.975, 21.45e-3, err)) ||
        (st = rig_disk(m, "gear_b", 9.124, 5.097e-3, err)))
        return st;
    gd_bearing_spec b;
    gd_bearing_spec_init(&b);
    b.name = "support_a";
    b.node = "gear_a";
    b.coeffs.kxx = b.coeffs.kyy = 5.683e6;
    b.coeffs.cxx = b.coeffs.cyy = 714.18;
    b.coeffs.ktorsion = 9.483e3;
    b.coeffs.ctorsion = 0.7131;
    b.has_sfd = 1;
    b.sfd.viscosity = 6.895e-3;
    b.sfd.radius = 0.5 * 35.56e-3;
    b.sfd.length = 17.145e-3;
    b.sfd.clearance = 76.2e-6;
    b.sfd.film = GD_SFD_PI_FILM;
    if ((st = gd_model_add_bearing(m, &b, NULL, err)) ||
        (st = support(m, "support_b", "gear_b", 25.5735e6, 1527.5, 28.68e3, 0.6045, err)))
        return st;
    gd_mesh_spec g;
    gd_mesh_spec_init(&g);
    g.name = "mesh";
    g.driver = "gear_a";
    g.driven = "gear_b";
    g.base_radius[0] = 10.29e-3;
    g.base_radius[1] = 54.00e-3;
    g.pressure_angle = 20 * DEG;
    g.line_of_centres = 0;
    g.stiffness = 34.098e6;
    g.damping = 384.35;
    g.coupling = GD_COUPLING_LATERAL_TORSIONAL;
    if ((st = gd_model_add_mesh(m, &g, NULL, err))) return st;
    gd_unbalance_spec u;
    gd_unbalance_spec_init(&u);
    u.name = "gear_a_unbalance";
    u.node = "gear_a";
    u.amount = 8.975 * 12.7e-6;
    return gd_model_add_unbalance(m, &u, NULL, err);
}

TEST(gear_pair_built_in_code_matches_the_file)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("pair.c", &m, &err));
    OK(chen_pair(m, &err));
    OK(gd_model_finish(m, &err));
    CHECK(m->nnodes == 2);
    CHECK(m->bearings[0].has_sfd);
    CHECK_REL(m->unbalances[0].amount, 8.975 * 12.7e-6, 1e-15);
    check_same_modes(gd_ts_, "examples/chen1998_gear_pair.yaml", m);
    gd_model_free(m);
}

/* ---- errors from code ---- */

static void check_code_error(gd_test_state *gd_ts_, int at, gd_status st, const gd_error *e,
                             const char *field, const char *word)
{
    int bad = !(st == GD_EINPUT && e->status == GD_EINPUT && e->line == 0 && e->column == 0 &&
                !strcmp(e->field, field) && strstr(e->message, word) && e->hint[0] &&
                !strcmp(e->file, "code.c"));
    if (bad) {
        fprintf(stderr, "  %s:%d: got %d %s:%d:%d '%s': %s | %s\n", __FILE__, at, (int)st, e->file,
                e->line, e->column, e->field, e->message, e->hint);
        gd_ts_->checks_failed++;
    }
}
#define CHECK_CODE_ERROR(st, e, field, word) check_code_error(gd_ts_, __LINE__, st, e, field, word)

TEST(negative_mass_names_the_field_at_line_0)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("code.c", &m, &err));
    OK(lumped_shaft(m, "a", "n1", &err));
    gd_disk_spec d;
    gd_disk_spec_init(&d);
    d.node = "n1";
    d.mass = -1;
    d.polar_inertia = 1e-3;
    int index = 7;
    CHECK_CODE_ERROR(gd_model_add_disk(m, &d, &index, &err), &err, "disks[0].mass", "negative");
    CHECK(index == 7); /* a failed add leaves everything as it was */
    CHECK(m->ndisks == 0);
    /* the model can still be added to and finished */
    d.mass = 1;
    OK(gd_model_add_disk(m, &d, &index, &err));
    CHECK(index == 0);
    OK(gd_model_finish(m, &err));
    CHECK_STR(m->disks[0].name, "disk1");
    CHECK_REL(m->disks[0].diametral_inertia, 0.5e-3, 1e-15);
    gd_model_free(m);
}

TEST(unknown_node_is_reported_by_finish)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("code.c", &m, &err));
    OK(lumped_shaft(m, "a", "n1", &err));
    OK(support(m, "b1", "n1", 1e6, 0, 0, 0, &err));
    OK(support(m, "b2", "n2", 1e6, 0, 0, 0, &err));
    gd_system *sys = NULL;
    CHECK(gd_system_build(m, &sys, &err) == GD_EINPUT); /* not finished */
    CHECK(sys == NULL);
    CHECK(strstr(err.message, "not finished") != NULL);
    CHECK_CODE_ERROR(gd_model_finish(m, &err), &err, "bearings[1].node", "unknown node 'n2'");
    CHECK(strstr(err.hint, "n1") != NULL);
    CHECK(!gd_model_is_finished(m));
    /* a failed finish cannot be retried: the model can only be freed */
    CHECK(gd_model_finish(m, &err) == GD_EINPUT);
    gd_model_free(m);
}

TEST(generated_nodes_and_added_stations)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("code.c", &m, &err));
    gd_material_spec mat;
    gd_material_spec_init(&mat);
    mat.name = "steel";
    mat.density = 7850;
    mat.E = 2.1e11;
    mat.G = 8.1e10;
    OK(gd_model_add_material(m, &mat, NULL, &err));
    CHECK_REL(m->materials[0].poisson, 2.1e11 / (2 * 8.1e10) - 1, 1e-15);
    gd_section_spec sec;
    gd_section_spec_init(&sec);
    sec.length = 1.0;
    sec.outer_diameter = 0.05;
    gd_shaft_spec s;
    gd_shaft_spec_init(&s);
    s.name = "a";
    s.material = "steel";
    s.nsections = 1;
    s.sections = &sec;
    s.max_element_length = 0.25;
    OK(gd_model_add_shaft(m, &s, NULL, &err));
    gd_node_spec n;
    gd_node_spec_init(&n);
    n.shaft = "a";
    n.name = "mid";
    n.at = 0.5;
    int index = -1;
    OK(gd_model_add_node(m, &n, &index, &err));
    CHECK(index == 0);
    n.name = "out";
    n.at = 1.5;
    CHECK_CODE_ERROR(gd_model_add_node(m, &n, NULL, &err), &err, "shafts[0].nodes[1].at",
                     "outside the shaft");
    n.shaft = "nowhere";
    CHECK(gd_model_add_node(m, &n, NULL, &err) == GD_EINPUT);
    OK(support(m, "left", "a@0", 1e7, 0, 0, 0, &err));
    OK(support(m, "right", "a@4", 1e7, 0, 0, 0, &err));
    OK(gd_model_finish(m, &err));
    CHECK(m->nnodes == 5);
    CHECK(m->nelements == 4);
    CHECK(gd_model_find_node(m, "mid") == 2);
    CHECK(m->bearings[1].node == 4);
    gd_model_free(m);
}

TEST(add_after_finish_is_refused)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("code.c", &m, &err));
    OK(lumped_shaft(m, "a", "n1", &err));
    OK(rig_disk(m, "n1", 1, 1e-3, &err));
    OK(gd_model_finish(m, &err));
    gd_disk_spec d;
    gd_disk_spec_init(&d);
    d.node = "n1";
    d.mass = 1;
    gd_status st = gd_model_add_disk(m, &d, NULL, &err);
    CHECK(st == GD_EINPUT);
    CHECK(strstr(err.message, "finished") != NULL);
    CHECK(m->ndisks == 1);
    CHECK(gd_model_set_speed(m, 10, &err) == GD_EINPUT);
    CHECK(gd_model_finish(m, &err) == GD_EINPUT);
    gd_model_free(m);
}

/* Four lumped shafts a-b-c-d geared in a loop by meshes m0..m3; the driven radius of
 * m3 (d-a) is consistent at 0.1. ratio_b != 0: shaft b's speed_ratio given. */
static gd_status gear_loop(gd_model *m, double rb_da, double ratio_b, gd_error *err)
{
    static const char *const shafts[4] = {"a", "b", "c", "d"};
    static const char *const nodes[4] = {"ga", "gb", "gc", "gd"};
    gd_status st;
    for (int i = 0; i < 4; i++) {
        gd_station_spec n;
        gd_station_spec_init(&n);
        n.name = nodes[i];
        gd_shaft_spec s;
        gd_shaft_spec_init(&s);
        s.name = shafts[i];
        s.nstations = 1;
        s.stations = &n;
        if (i == 1 && ratio_b != 0) {
            s.has_speed_ratio = 1;
            s.speed_ratio = ratio_b;
        }
        if ((st = gd_model_add_shaft(m, &s, NULL, err)) ||
            (st = rig_disk(m, nodes[i], 1, 1e-3, err)))
            return st;
    }
    const double rb[4][2] = {{0.1, 0.2}, {0.1, 0.1}, {0.2, 0.1}, {0.1, rb_da}};
    for (int i = 0; i < 4; i++) {
        char name[8];
        snprintf(name, sizeof name, "m%d", i);
        gd_mesh_spec g;
        gd_mesh_spec_init(&g);
        g.name = name;
        g.driver = nodes[i];
        g.driven = nodes[(i + 1) % 4];
        g.base_radius[0] = rb[i][0];
        g.base_radius[1] = rb[i][1];
        g.stiffness = 1e8;
        g.coupling = GD_COUPLING_TORSIONAL;
        if ((st = gd_model_add_mesh(m, &g, NULL, err))) return st;
    }
    return GD_OK;
}

TEST(gear_loop_speed_ratios)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("code.c", &m, &err));
    OK(gear_loop(m, 0.1, 0, &err));
    OK(gd_model_finish(m, &err));
    CHECK_REL(m->shafts[1].speed_ratio, -0.5, 1e-15);
    CHECK_REL(m->shafts[2].speed_ratio, 0.5, 1e-15);
    CHECK_REL(m->shafts[3].speed_ratio, -1.0, 1e-15);
    gd_model_free(m);

    OK(gd_model_new("code.c", &m, &err));
    OK(gear_loop(m, 0.3, 0, &err));
    /* from a, d turns at -3 through m3 and c at 0.5 through b: m2 (c-d) closes the loop */
    CHECK_CODE_ERROR(gd_model_finish(m, &err), &err, "meshes[2]", "inconsistent gear ratios");
    gd_model_free(m);

    OK(gd_model_new("code.c", &m, &err));
    OK(gear_loop(m, 0.1, 2.0, &err));
    CHECK_CODE_ERROR(gd_model_finish(m, &err), &err, "shafts[1].speed_ratio",
                     "its meshes give -0.5");
    gd_model_free(m);
}

TEST(value_and_name_errors_from_code)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new("code.c", &m, &err));
    gd_section_spec sec;
    gd_section_spec_init(&sec);
    sec.length = 0.5;
    sec.outer_diameter = 0.02;
    sec.inner_diameter = 0.03;
    gd_shaft_spec s;
    gd_shaft_spec_init(&s);
    s.material = "steel";
    s.nsections = 1;
    s.sections = &sec;
    CHECK_CODE_ERROR(gd_model_add_shaft(m, &s, NULL, &err), &err,
                     "shafts[0].sections[0].inner_diameter", "not less than outer");
    sec.inner_diameter = 0;
    s.path = "rotor"; /* a caller's own path prefix */
    OK(gd_model_add_shaft(m, &s, NULL, &err));
    CHECK_STR(m->shafts[0].name, "shaft1");
    gd_spring_spec sp;
    gd_spring_spec_init(&sp);
    sp.node = "shaft1@0";
    CHECK_CODE_ERROR(gd_model_add_spring(m, &sp, NULL, &err), &err, "springs[0]",
                     "neither stiffness nor damping");
    gd_mesh_spec g;
    gd_mesh_spec_init(&g);
    g.name = "g";
    g.driver = "shaft1@0";
    g.driven = "shaft1@1";
    g.stiffness = 1e8;
    CHECK_CODE_ERROR(gd_model_add_mesh(m, &g, NULL, &err), &err, "meshes[0]", "gear size missing");
    g.pressure_angle = 20; /* degrees by mistake */
    g.module = 2e-3;
    CHECK_CODE_ERROR(gd_model_add_mesh(m, &g, NULL, &err), &err, "meshes[0].pressure_angle",
                     "not below 60 deg");
    g.pressure_angle = 20 * DEG;
    CHECK_CODE_ERROR(gd_model_add_mesh(m, &g, NULL, &err), &err, "meshes[0]",
                     "module needs the teeth");
    g.teeth[0] = 20;
    g.teeth[1] = 40;
    OK(gd_model_add_mesh(m, &g, NULL, &err));
    /* finish: the unknown material, at the section's path under the caller's prefix */
    CHECK_CODE_ERROR(gd_model_finish(m, &err), &err, "rotor.sections[0].material",
                     "unknown material 'steel'");
    gd_model_free(m);

    /* a mesh within one shaft, found by finish */
    OK(gd_model_new("code.c", &m, &err));
    gd_material_spec mat;
    gd_material_spec_init(&mat);
    mat.name = "steel";
    mat.density = 7800;
    mat.E = 2e11;
    mat.poisson = 0.3;
    OK(gd_model_add_material(m, &mat, NULL, &err));
    CHECK_CODE_ERROR(gd_model_add_material(m, &mat, NULL, &err), &err, "materials.steel",
                     "duplicate material");
    s.path = NULL;
    OK(gd_model_add_shaft(m, &s, NULL, &err));
    OK(gd_model_add_mesh(m, &g, NULL, &err));
    CHECK_CODE_ERROR(gd_model_finish(m, &err), &err, "meshes[0].driven", "same shaft");
    gd_model_free(m);

    /* duplicate component names across kinds */
    OK(gd_model_new("code.c", &m, &err));
    OK(lumped_shaft(m, "a", "n1", &err));
    OK(support(m, "a", "n1", 1e6, 0, 0, 0, &err));
    CHECK_CODE_ERROR(gd_model_finish(m, &err), &err, "bearings[0].name",
                     "already used by the shaft");
    gd_model_free(m);
}

/* Unfinished models with every kind of item are freed whole (valgrind checks). */
TEST(unfinished_model_is_freed)
{
    gd_error err;
    gd_model *m = NULL;
    OK(gd_model_new(NULL, &m, &err));
    OK(chen_pair(m, &err));
    double x[3] = {0, 2, 4}, y[3] = {1, 2, 1};
    gd_excitation_spec e;
    gd_excitation_spec_init(&e);
    e.node = "gear_a";
    e.law.kind = GD_LOAD_TABLE_ANGLE;
    e.table.n = 3;
    e.table.x = x;
    e.table.y = y;
    OK(gd_model_add_excitation(m, &e, NULL, &err));
    gd_prescribed_spec p;
    gd_prescribed_spec_init(&p);
    p.node = "gear_b";
    p.law.kind = GD_PRESCRIBED_SPEED;
    p.law.speed = 10;
    OK(gd_model_add_prescribed(m, &p, NULL, &err));
    double mass[2] = {0.1, 0.1}, phase[2] = {0, PI};
    gd_cam_spec c;
    gd_cam_spec_init(&c);
    c.camshaft = "gear_b";
    c.lift_table.n = 3;
    c.lift_table.x = x;
    c.lift_table.y = y;
    c.nvalves = 2;
    c.valve_mass = mass;
    c.valve_phase = phase;
    OK(gd_model_add_cam(m, &c, NULL, &err));
    OK(gd_model_set_reference_shaft(m, "shaft_b", -1, (gd_loc){0, 0}, &err));
    gd_model_free(m);

    /* and finished, with their tables made */
    OK(gd_model_new(NULL, &m, &err));
    OK(chen_pair(m, &err));
    OK(gd_model_add_excitation(m, &e, NULL, &err));
    OK(gd_model_add_prescribed(m, &p, NULL, &err));
    OK(gd_model_add_cam(m, &c, NULL, &err));
    OK(gd_model_set_reference_shaft(m, "shaft_b", -1, (gd_loc){0, 0}, &err));
    OK(gd_model_finish(m, &err));
    CHECK(m->excitations[0].law.table != NULL);
    CHECK(m->cams[0].lift.table != NULL);
    CHECK_STR(m->cams[0].name, "cam1");
    CHECK(m->reference_shaft == 1);
    CHECK_REL(m->shafts[1].speed_ratio, -1.0, 1e-15);
    CHECK_REL(m->shafts[0].speed_ratio, 54.00 / 10.29, 1e-12);
    gd_model_free(m);
}

/* ---- a mesh stiffened from its geometry ---- */

static const char *const GEOMETRY_PAIR =
    "dofs: [rz]\n"
    "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"
    "shafts:\n"
    "  - {name: a, nodes: [{name: p}]}\n"
    "  - {name: b, nodes: [{name: g}]}\n"
    "disks:\n"
    "  - {node: p, polar_inertia: 1.3e-3}\n"
    "  - {node: g, polar_inertia: 2.5e-4}\n"
    "meshes:\n"
    "  - name: m\n"
    "    driver: p\n"
    "    driven: g\n"
    "    coupling: torsional\n"
    "    geometry:\n"
    "      normal_module: 2 mm\n"
    "      normal_pressure_angle: 20 deg\n"
    "      face_width: 20 mm\n"
    "      driver: {teeth: 48, material: steel, bore_radius: 12.7 mm}\n"
    "      driven: {teeth: 32, material: steel, bore_radius: 12.7 mm}\n"
    "    stiffness: {from: geometry}\n";

static gd_status geometry_pair(gd_model *m, int teeth, gd_error *err)
{
    gd_status st;
    gd_disk_spec d;
    gd_disk_spec_init(&d);
    if ((st = gd_model_set_dofs(m, GD_DOF_BIT(GD_RZ), err)) ||
        (st = lumped_shaft(m, "a", "p", err)) || (st = lumped_shaft(m, "b", "g", err)))
        return st;
    const char *nodes[2] = {"p", "g"};
    const double ip[2] = {1.3e-3, 2.5e-4};
    for (int i = 0; i < 2; i++) {
        d.node = nodes[i];
        d.polar_inertia = ip[i];
        if ((st = gd_model_add_disk(m, &d, NULL, err))) return st;
    }
    gd_gear_pair_geometry geom;
    gd_gear_pair_geometry_init(&geom);
    geom.normal_module = 2e-3;
    geom.normal_pressure_angle = 20 * DEG;
    geom.face_width = 20e-3;
    const int z[2] = {teeth, 32};
    for (int i = 0; i < 2; i++) {
        geom.gear[i].teeth = z[i];
        geom.gear[i].E = 2.0e11;
        geom.gear[i].poisson = 0.3;
        geom.gear[i].bore_radius = 12.7e-3;
    }
    gd_mesh_spec g;
    gd_mesh_spec_init(&g);
    g.name = "m";
    g.driver = "p";
    g.driven = "g";
    g.coupling = GD_COUPLING_TORSIONAL;
    g.geometry = &geom; /* copied by the add */
    g.stiffness_from_geometry = 1;
    return gd_model_add_mesh(m, &g, NULL, err);
}

TEST(mesh_from_geometry_in_code_matches_the_file)
{
    gd_error err;
    gd_model *m = NULL, *f = NULL;
    OK(gd_model_new("code.c", &m, &err));
    OK(geometry_pair(m, 48, &err));
    OK(gd_model_finish(m, &err));
    OK(gd_model_load_string(GEOMETRY_PAIR, "g.yaml", &f, &err));
    const gd_mesh *a = &m->meshes[0], *b = &f->meshes[0];
    REQUIRE(a->tvms != NULL && b->tvms != NULL);
    CHECK(a->teeth[0] == 48 && a->teeth[1] == 32);
    CHECK_REL(a->stiffness, b->stiffness, 1e-14);
    CHECK_REL(a->base_radius[0], b->base_radius[0], 1e-15);
    CHECK_REL(a->pressure_angle, b->pressure_angle, 1e-15);
    CHECK_REL(m->shafts[1].speed_ratio, -1.5, 1e-12);
    gd_model_free(f);
    gd_model_free(m);

    /* an invalid geometry, found by finish, named under the mesh's geometry */
    OK(gd_model_new("code.c", &m, &err));
    OK(geometry_pair(m, 2, &err));
    CHECK(gd_model_finish(m, &err) == GD_EINPUT);
    CHECK(strncmp(err.field, "meshes[0].geometry", 18) == 0);
    CHECK(err.line == 0);
    gd_model_free(m);
}

/* ---- spec defaults ---- */

TEST(spec_init_defaults)
{
    gd_material_spec mat;
    gd_material_spec_init(&mat);
    CHECK(mat.name == NULL && mat.density == 0 && mat.E == 0 && mat.G == 0 && mat.path == NULL);
    gd_section_spec sec;
    gd_section_spec_init(&sec);
    CHECK(sec.inner_diameter == 0 && sec.material == NULL && sec.elements == 0);
    gd_shaft_spec s;
    gd_shaft_spec_init(&s);
    CHECK(s.name == NULL && s.nsections == 0 && s.nstations == 0);
    CHECK(s.elements_per_section == 0 && s.max_element_length == 0);
    CHECK(!s.has_speed_ratio && s.speed_ratio == 1.0);
    CHECK(s.loc.line == 0 && s.loc.column == 0);
    gd_node_spec n;
    gd_node_spec_init(&n);
    CHECK(n.shaft == NULL && n.name == NULL && n.at == 0);
    gd_disk_spec d;
    gd_disk_spec_init(&d);
    CHECK(d.mass == 0 && d.polar_inertia == 0 && d.diametral_inertia < 0 && !d.from_geometry);
    gd_bearing_spec b;
    gd_bearing_spec_init(&b);
    CHECK(b.to == NULL && b.ntable == 0 && !b.has_sfd && b.coeffs.kxx == 0);
    gd_spring_spec sp;
    gd_spring_spec_init(&sp);
    CHECK(sp.dof == GD_RZ && sp.to == NULL && sp.stiffness == 0);
    gd_mesh_spec g;
    gd_mesh_spec_init(&g);
    CHECK_REL(g.pressure_angle, 20 * DEG, 1e-15);
    CHECK(g.helix_angle == 0 && g.hand == 1 && g.coupling == GD_COUPLING_FULL);
    CHECK(g.teeth[0] == 0 && g.base_radius[0] == 0 && g.module == 0 && g.geometry == NULL);
    CHECK(!g.stiffness_from_geometry && g.driver_rotation == 0);
    CHECK(g.tvms.n == 0 && g.transmission_error.n == 0 && !g.backlash);
    CHECK(g.coast_stiffness_ratio == 1.0);
    gd_tvms_options opt;
    gd_tvms_options_init(&opt);
    CHECK(memcmp(&opt, &g.tvms_options, sizeof opt) == 0);
    gd_unbalance_spec u;
    gd_unbalance_spec_init(&u);
    CHECK(u.amount == 0 && u.phase == 0);
    gd_excitation_spec e;
    gd_excitation_spec_init(&e);
    CHECK(e.dof == GD_RZ && e.law.kind == GD_LOAD_CONSTANT && e.table.interp == GD_INTERP_LINEAR);
    gd_prescribed_spec p;
    gd_prescribed_spec_init(&p);
    CHECK(p.dof == GD_RZ && p.law.kind == GD_PRESCRIBED_NOMINAL);
    CHECK(p.table.interp == GD_INTERP_SPLINE);
    gd_cam_spec c;
    gd_cam_spec_init(&c);
    CHECK(c.lift.kind == GD_LIFT_TABLE && c.lift_table.interp == GD_INTERP_SPLINE);
    CHECK(c.include_acceleration == 1 && c.nvalves == 0);

    /* a new model's globals */
    gd_error err;
    gd_model *m = NULL;
    CHECK(gd_model_new("x", &m, &err) == GD_OK);
    REQUIRE(m);
    CHECK(m->dof_mask == GD_DOFS_ALL && m->speed == 0 && m->excite_unbalances == 1);
    CHECK_STR(m->file, "x");
    gd_model_free(m);
}

RUN_TESTS(T(rig2018_built_in_code_matches_the_file), T(gear_pair_built_in_code_matches_the_file),
          T(negative_mass_names_the_field_at_line_0), T(unknown_node_is_reported_by_finish),
          T(generated_nodes_and_added_stations), T(add_after_finish_is_refused),
          T(gear_loop_speed_ratios), T(value_and_name_errors_from_code),
          T(unfinished_model_is_freed), T(mesh_from_geometry_in_code_matches_the_file),
          T(spec_init_defaults))
