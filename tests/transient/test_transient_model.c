/* The transient spec made from a model (src/transient_model.c): mesh laws (TVMS table,
 * geometry TVMS, STE, backlash, damping laws), squeeze film dampers, loads, prescribed
 * motion, cams, the unbalance flag; errors naming the model line; and runs of the spec:
 * static mesh force under a brake torque with backlash, the TVMS seen by the run, the
 * cam torque on a prescribed camshaft, the SFD force. Models are loaded from YAML with
 * the linear keys and given their time-integration data in C. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/transient_model.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define PAIR                                                                                       \
    "dofs: [rz]\n"                                                          /* 1 */                \
    "speed: 300\n"                                                          /* 2 */                \
    "shafts:\n"                                                             /* 3 */                \
    "  - {name: a, nodes: [{name: p}]}\n"                                   /* 4 */                \
    "  - {name: b, nodes: [{name: g}, {name: load}]}\n"                     /* 5 */                \
    "disks:\n"                                                              /* 6 */                \
    "  - {node: p, polar_inertia: 1e-3}\n"                                  /* 7 */                \
    "  - {node: g, polar_inertia: 2e-3}\n"                                  /* 8 */                \
    "  - {node: load, polar_inertia: 5e-3}\n"                               /* 9 */                \
    "springs: [{node: g, to: load, dof: rz, stiffness: 2e4, damping: 2}]\n" /* 10 */               \
    "meshes:\n"                                                             /* 11 */               \
    "  - {name: m1, driver: p, driven: g, teeth: [20, 40], base_radius: [0.02, 0.04],\n"           \
    "     pressure_angle: 20 deg, stiffness: 2e8, damping: 50, coupling: torsional}\n"

typedef struct fx {
    gd_model *m;
    gd_system *s;
} fx;

static int load(fx *f, const char *yaml)
{
    gd_error err;
    f->m = NULL;
    f->s = NULL;
    gd_status st = gd_model_load_string(yaml, "tm.yaml", &f->m, &err);
    if (!st) st = gd_system_build(f->m, &f->s, &err);
    if (st) fprintf(stderr, "  model: %s (%s)\n", err.message, err.field);
    return st == GD_OK;
}

static void unload(fx *f)
{
    gd_system_free(f->s);
    gd_model_free(f->m);
}

static gd_table *table(int n, const double *x, const double *y, double period, gd_interp ip)
{
    gd_table *t = NULL;
    gd_error err;
    if (gd_table_new(n, x, y, period, ip, &t, &err)) fprintf(stderr, "  %s\n", err.message);
    return t;
}

/* TVMS 2e8 +- 20 % over one mesh period of the 20-tooth driver (owned by the model). */
static gd_table *tvms20(void)
{
    double x[8], y[8], per = 2 * M_PI / 20;
    for (int i = 0; i < 8; i++) {
        x[i] = i * per / 8;
        y[i] = 2e8 * (1 + 0.2 * cos(2 * M_PI * i / 8));
    }
    return table(8, x, y, per, GD_INTERP_LINEAR);
}

static void add_load(gd_model *m, const char *name, const char *node, gd_dof d, double value)
{
    int i = m->nexcitations++;
    m->excitations = realloc(m->excitations, (size_t)m->nexcitations * sizeof *m->excitations);
    gd_excitation *e = &m->excitations[i];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%s", name);
    e->node = gd_model_find_node(m, node);
    e->dof = d;
    e->law.kind = GD_LOAD_CONSTANT;
    e->law.mean = value;
    e->loc.line = 42;
    e->loc.column = 7;
}

static void add_prescribed(gd_model *m, const char *node, gd_dof d)
{
    int i = m->nprescribed++;
    m->prescribed = realloc(m->prescribed, (size_t)m->nprescribed * sizeof *m->prescribed);
    gd_prescription *p = &m->prescribed[i];
    memset(p, 0, sizeof *p);
    p->node = gd_model_find_node(m, node);
    p->dof = d;
    p->law.kind = GD_PRESCRIBED_NOMINAL;
    p->loc.line = 50;
}

/* A cam with a harmonic lift s = 4 mm (1 - cos theta) and nv valves. */
static void add_cam(gd_model *m, const char *node, int nv, int with_table)
{
    int i = m->ncams++;
    m->cams = realloc(m->cams, (size_t)m->ncams * sizeof *m->cams);
    gd_cam *c = &m->cams[i];
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "cam%d", i);
    c->node = gd_model_find_node(m, node);
    c->lift.kind = with_table ? GD_LIFT_TABLE : GD_LIFT_HARMONIC;
    c->lift.harmonic.order = 1;
    c->lift.harmonic.mean = 4e-3;
    c->lift.harmonic.n = 1;
    c->lift.harmonic.cos_amp[0] = -4e-3;
    c->include_acceleration = 1;
    c->nvalves = nv;
    c->valve_mass = malloc((size_t)nv * sizeof *c->valve_mass);
    c->valve_phase = malloc((size_t)nv * sizeof *c->valve_phase);
    for (int v = 0; v < nv; v++) {
        c->valve_mass[v] = 0.1 + 0.01 * v;
        c->valve_phase[v] = v * M_PI / 2;
    }
    c->loc.line = 60;
}

TEST(mesh_laws)
{
    fx f;
    REQUIRE(load(&f, PAIR));
    gd_mesh *g = &f.m->meshes[0];
    gd_error err;
    gd_transient_model *tm = NULL;
    /* no law: the mesh stays linear */
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    CHECK(tm->spec.nmeshes == 0);
    CHECK(gd_transient_model_mesh_index(tm, 0) == -1);
    CHECK(tm->spec.unbalances == 1);
    gd_transient_model_free(tm);
    g->dyn.tvms = tvms20();
    g->dyn.tvms_phase = 0.01;
    g->dyn.damping_per_stiffness = 1e-6;
    g->dyn.damping_separated = 5;
    g->dyn.backlash = 1;
    g->dyn.gap = 20e-6;
    g->dyn.coast_stiffness_ratio = 0.8;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    REQUIRE(tm->spec.nmeshes == 1);
    const gd_tr_mesh *t = &tm->spec.meshes[0];
    CHECK(t->mesh == 0);
    CHECK(t->tvms == g->dyn.tvms); /* borrowed from the model */
    CHECK(t->ste == NULL);
    CHECK_REL(t->stiffness, 2e8, 1e-15);
    CHECK_REL(t->damping, 50, 1e-15);
    CHECK_REL(t->damping_per_k, 1e-6, 1e-15);
    CHECK_REL(t->damping_free, 5, 1e-15);
    CHECK(t->backlash == 1);
    CHECK_REL(t->gap, 20e-6, 1e-15);
    CHECK_REL(t->coast_scale, 0.8, 1e-15);
    CHECK_REL(t->angle_offset, 0.01, 1e-15);
    CHECK(tm->nowned == 0);
    CHECK(gd_transient_model_mesh_index(tm, 0) == 0);
    gd_transient_model_free(tm);
    /* coast ratio 0 means 1; STE alone makes the mesh nonlinear */
    g->dyn.coast_stiffness_ratio = 0;
    g->dyn.backlash = 0;
    g->dyn.damping_per_stiffness = 0;
    g->dyn.damping_separated = 0;
    gd_table_free(g->dyn.tvms);
    g->dyn.tvms = NULL;
    double x[2] = {0, 0.1}, e[2] = {1e-6, -1e-6};
    g->dyn.ste = table(2, x, e, 2 * M_PI / 20, GD_INTERP_LINEAR);
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    REQUIRE(tm->spec.nmeshes == 1);
    CHECK(tm->spec.meshes[0].ste == g->dyn.ste);
    CHECK(tm->spec.meshes[0].tvms == NULL);
    CHECK_REL(tm->spec.meshes[0].coast_scale, 1.0, 0);
    gd_transient_model_free(tm);
    unload(&f);
}

/* stiffness: {from: geometry}: the spec owns a periodic table of the TVMS result. */
TEST(geometry_tvms)
{
    fx f;
    REQUIRE(load(&f, "dofs: [rz]\n"
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
                     "      face_width: 20 mm\n"
                     "      driver: {teeth: 48, material: steel, bore_radius: 12.7 mm}\n"
                     "      driven: {teeth: 32, material: steel, bore_radius: 12.7 mm}\n"
                     "    stiffness: {from: geometry, method: single-pair-law, points: 90}\n"));
    const gd_mesh *g = &f.m->meshes[0];
    REQUIRE(g->tvms != NULL);
    gd_error err;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    REQUIRE(tm->spec.nmeshes == 1);
    CHECK(tm->nowned == 1);
    const gd_table *t = tm->spec.meshes[0].tvms;
    REQUIRE(t != NULL);
    CHECK(t->n == 90);
    CHECK_REL(t->period, 2 * M_PI / 48, 1e-12);
    double sum = 0, mx = 0, mn = 1e300;
    for (int i = 0; i < t->n; i++) {
        sum += t->y[i];
        mx = fmax(mx, t->y[i]);
        mn = fmin(mn, t->y[i]);
    }
    CHECK_REL(sum / t->n, g->tvms->mean, 1e-9);
    CHECK_REL(mx, g->tvms->max, 1e-12);
    CHECK_REL(mn, g->tvms->min, 1e-12);
    CHECK(mx > 1.2 * mn); /* single and double pair zones */
    /* at a sample angle the table is the result's value */
    CHECK_REL(gd_table_eval(t, t->x[17] + 3 * t->period, NULL, NULL),
              gd_tvms_eval(g->tvms, t->x[17]), 1e-12);
    gd_transient_model_free(tm);
    unload(&f);
}

TEST(loads_prescribed_cams)
{
    fx f;
    REQUIRE(load(&f, PAIR));
    gd_model *m = f.m;
    add_load(m, "brake", "load", GD_RZ, -12.0);
    add_prescribed(m, "p", GD_RZ);
    add_cam(m, "load", 3, 0);
    m->excite_unbalances = 0;
    gd_error err;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const gd_transient_spec *sp = &tm->spec;
    int dload = gd_system_dof(f.s, gd_model_find_node(m, "load"), GD_RZ);
    int dp = gd_system_dof(f.s, gd_model_find_node(m, "p"), GD_RZ);
    REQUIRE(sp->nloads == 1);
    CHECK(sp->loads[0].dof == dload);
    CHECK(sp->loads[0].law.kind == GD_LOAD_CONSTANT);
    CHECK_REL(sp->loads[0].law.mean, -12.0, 0);
    REQUIRE(sp->nprescribed == 1);
    CHECK(sp->prescribed[0].dof == dp);
    CHECK(sp->prescribed[0].law.kind == GD_PRESCRIBED_NOMINAL);
    REQUIRE(sp->ncams == 3);
    for (int v = 0; v < 3; v++) {
        CHECK(sp->cams[v].dof == dload);
        CHECK(sp->cams[v].law == &m->cams[0].lift);
        CHECK_REL(sp->cams[v].mass, 0.1 + 0.01 * v, 1e-15);
        CHECK_REL(sp->cams[v].phase, v * M_PI / 2, 1e-15);
        CHECK(tm->cam_of[v] == 0);
    }
    CHECK(sp->cam_acceleration == 1);
    CHECK(sp->unbalances == 0);
    CHECK(sp->nsfds == 0);
    gd_transient_model_free(tm);
    unload(&f);
}

static void expect_error(gd_test_state *gd_ts_, fx *f, int line, const char *field, const char *w1,
                         const char *w2)
{
    gd_error err;
    gd_error_clear(&err);
    gd_transient_model *tm = (gd_transient_model *)1;
    CHECK(gd_transient_model_build(f->s, &tm, &err) == GD_EINPUT);
    CHECK(tm == NULL);
    CHECK_STR(err.file, "tm.yaml");
    CHECK(err.line == line);
    CHECK_STR(err.field, field);
    CHECK(strstr(err.message, w1) != NULL);
    if (w2) CHECK(strstr(err.message, w2) != NULL);
    CHECK(err.hint[0] != 0);
    if (err.line != line || strcmp(err.field, field) || !strstr(err.message, w1))
        fprintf(stderr, "    got %d %s: %s\n", err.line, err.field, err.message);
}

TEST(errors)
{
    fx f;
    /* a load on x of a torsional model */
    REQUIRE(load(&f, PAIR));
    add_load(f.m, "push", "g", GD_X, 10.0);
    expect_error(gd_ts_, &f, 42, "excitations.loads[0]", "g.x", "not an active DOF");
    unload(&f);
    /* a table load without its table */
    REQUIRE(load(&f, PAIR));
    add_load(f.m, "tab", "g", GD_RZ, 1.0);
    f.m->excitations[0].law.kind = GD_LOAD_TABLE_ANGLE;
    expect_error(gd_ts_, &f, 42, "excitations.loads[0]", "without a table", NULL);
    unload(&f);
    /* prescribed on an inactive DOF; prescribed twice */
    REQUIRE(load(&f, PAIR));
    add_prescribed(f.m, "p", GD_Y);
    expect_error(gd_ts_, &f, 50, "prescribed[0]", "p.y", "not an active DOF");
    unload(&f);
    REQUIRE(load(&f, PAIR));
    add_prescribed(f.m, "p", GD_RZ);
    add_prescribed(f.m, "p", GD_RZ);
    expect_error(gd_ts_, &f, 50, "prescribed[1]", "twice", NULL);
    unload(&f);
    /* a cam without its lift table, a cam without valves */
    REQUIRE(load(&f, PAIR));
    add_cam(f.m, "g", 2, 1);
    expect_error(gd_ts_, &f, 60, "cam_torques[0]", "cam0", "no lift table");
    unload(&f);
    REQUIRE(load(&f, PAIR));
    add_cam(f.m, "g", 0, 0);
    expect_error(gd_ts_, &f, 60, "cam_torques[0]", "no valve", NULL);
    unload(&f);
    /* a damper on a torsional model */
    REQUIRE(load(&f, PAIR "bearings: [{name: b1, node: g, k_torsion: 1e3}]\n"));
    f.m->bearings[0].has_sfd = 1;
    f.m->bearings[0].sfd = (gd_sfd_params){1e-2, 0.02, 0.01, 1e-4, GD_SFD_PI_FILM, 0, 0};
    expect_error(gd_ts_, &f, 14, "bearings[0].sfd", "b1", "x and y");
    unload(&f);
}

/* Crank prescribed at nominal speed, brake torque on the load, backlash mesh with TVMS:
 * from the static state the mesh force is T / rb_g and the deformation b + F / k(theta);
 * the recorded stiffness follows the table at the driver angle W t. */
TEST(run_static_brake)
{
    fx f;
    REQUIRE(load(&f, PAIR));
    gd_model *m = f.m;
    gd_mesh *g = &m->meshes[0];
    g->dyn.tvms = tvms20();
    g->dyn.backlash = 1;
    g->dyn.gap = 20e-6;
    g->dyn.damping_per_stiffness = 1e-6;
    add_load(m, "brake", "load", GD_RZ, 12.0); /* g turns about -z: +z opposes it */
    add_prescribed(m, "p", GD_RZ);
    gd_error err;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_transient *tr = NULL;
    double W = 0.05; /* slow: quasi-static */
    REQUIRE(gd_transient_new(f.s, &tm->spec, W, &tr, &err) == GD_OK);
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.2;
    o.record_from = 0.0;
    o.output_interval = 0.01;
    o.init = GD_TR_INIT_STATIC;
    o.rtol = 1e-9;
    o.atol_q = 1e-15;
    o.atol_v = 1e-12;
    gd_tr_record rec[3] = {
        {GD_REC_MESH_FORCE, 0, 0}, {GD_REC_MESH_DEFLECTION, 0, 0}, {GD_REC_MESH_STIFFNESS, 0, 0}};
    gd_transient_result *r = NULL;
    if (gd_transient_run(tr, &o, rec, 3, &r, &err)) fprintf(stderr, "  %s\n", err.message);
    REQUIRE(r != NULL);
    double F = 12.0 / 0.04;
    CHECK_REL(r->stats[0].mean, F, 1e-4); /* drive flank */
    CHECK(r->stats[0].peak_to_peak < 1e-3 * F);
    for (int k = 0; k < r->nout; k += 5) {
        double th = W * r->t[k];
        double kk = gd_table_eval(g->dyn.tvms, th, NULL, NULL);
        CHECK_REL(r->values[2 * r->nout + k], kk, 1e-9);
        CHECK_REL(r->values[r->nout + k], 20e-6 + F / kk, 1e-4);
    }
    CHECK(r->contacts[0].contact_losses == 0);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    unload(&f);
}

/* A cam on the prescribed driver: the cam torque is reacted by the mesh; with the driver
 * prescribed at nominal speed the driven side sees it only through the mesh. Here the
 * cam sits on the free load shaft and the run's mean mesh force equals the brake torque
 * plus the cam's mean torque (zero over a revolution: m s' s'' W^2 integrates to 0). */
TEST(run_cam)
{
    fx f;
    REQUIRE(load(&f, PAIR));
    gd_model *m = f.m;
    add_prescribed(m, "p", GD_RZ);
    add_load(m, "brake", "load", GD_RZ, 12.0);
    add_cam(m, "load", 1, 0);
    m->cams[0].include_acceleration = 0;
    gd_error err;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_transient *tr = NULL;
    double W = 300; /* load turns at -150 rad/s */
    REQUIRE(gd_transient_new(f.s, &tm->spec, W, &tr, &err) == GD_OK);
    gd_transient_options o;
    gd_transient_options_init(&o);
    double rev = 2 * M_PI / 150;
    o.t_end = 6 * rev;
    o.record_from = 2 * rev;
    o.output_interval = rev / 400;
    o.init = GD_TR_INIT_STATIC;
    gd_tr_record rec[1] = {{GD_REC_MESH_FORCE, 0, 0}};
    gd_transient_result *r = NULL;
    if (gd_transient_run(tr, &o, rec, 1, &r, &err)) fprintf(stderr, "  %s\n", err.message);
    REQUIRE(r != NULL);
    /* cam torque amplitude m s' s'' W^2 = 0.1 (4e-3)^2 / 2 150^2 = 0.018 N m: small
     * fluctuation around the brake's 300 N */
    CHECK_REL(r->stats[0].mean, 300.0, 2e-3);
    CHECK(r->stats[0].peak_to_peak > 0.1);
    CHECK(r->stats[0].peak_to_peak < 10);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    unload(&f);
}

/* A journal on a centring spring and a 2pi-film damper under unbalance: the spec holds
 * the damper; the circular orbit's radius balances U w^2 against the spring, mass and
 * the damper's tangential force (F_t = -pi mu R L^3 eps w / (c^2 s^3), F_r = 0). */
TEST(sfd_bearing)
{
    fx f;
    REQUIRE(load(&f, "dofs: [x, y]\n"
                     "speed: 500\n"
                     "shafts: [{name: a, nodes: [{name: j}]}]\n"
                     "disks: [{node: j, mass: 5}]\n"
                     "bearings: [{name: sq, node: j, k: 1e6}]\n"
                     "unbalances: [{node: j, mass: 5, eccentricity: 20 um}]\n"));
    gd_model *m = f.m;
    gd_sfd_params p = {5e-3, 0.02, 0.01, 100e-6, GD_SFD_2PI_FILM, -1, 0};
    m->bearings[0].has_sfd = 1;
    m->bearings[0].sfd = p;
    gd_error err;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    REQUIRE(tm->spec.nsfds == 1);
    CHECK(tm->spec.sfds[0].node == 0);
    CHECK(tm->spec.sfds[0].node2 == -1);
    CHECK_REL(tm->spec.sfds[0].params.clearance, 100e-6, 0);
    CHECK(gd_transient_model_sfd_index(tm, 0) == 0);
    CHECK(tm->spec.unbalances == 1);
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(f.s, &tm->spec, 500, &tr, &err) == GD_OK);
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.4;
    o.record_from = 0.35;
    o.output_interval = 1e-4;
    o.rtol = 1e-8;
    o.atol_q = 1e-13;
    o.atol_v = 1e-10;
    gd_tr_record rec[1] = {{GD_REC_SFD_ECCENTRICITY, 0, 0}};
    gd_transient_result *r = NULL;
    if (gd_transient_run(tr, &o, rec, 1, &r, &err)) fprintf(stderr, "  %s\n", err.message);
    REQUIRE(r != NULL);
    double eps = r->stats[0].mean;
    CHECK(r->stats[0].peak_to_peak < 1e-3 * eps); /* circular orbit */
    /* balance: (k - m w^2) e = U w^2 cos(phi), c_t w e = U w^2 sin(phi) */
    double w = 500, c = 100e-6, e = eps * c, s = sqrt(1 - eps * eps);
    double ct = M_PI * p.viscosity * p.radius * pow(p.length, 3) / (c * c * c * s * s * s);
    double lhs = hypot((1e6 - 5 * w * w) * e, ct * w * e);
    CHECK_REL(lhs, 5 * 20e-6 * w * w, 1e-4);
    gd_transient_result_free(r);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    unload(&f);
}

/* gd_transient_record_dofs: the free DOFs a record reads (what harmonic balance samples
 * for --record); gd_transient_record_values: every record from one state, the values
 * gd_transient_record_value gives one at a time. */
TEST(record_dofs_and_values)
{
    fx f;
    REQUIRE(load(&f, PAIR));
    f.m->meshes[0].dyn.tvms = tvms20(); /* a law: the mesh also reads its driver's angle */
    gd_error err;
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(f.s, &tm->spec, 300, &tr, &err) == GD_OK);
    /* nothing prescribed: the free index of a DOF is the DOF */
    const int p = gd_system_dof(f.s, 0, GD_RZ), g = gd_system_dof(f.s, 1, GD_RZ),
              l = gd_system_dof(f.s, 2, GD_RZ);
    gd_tr_record rec[3] = {
        {GD_REC_DISP, l, 0}, {GD_REC_MESH_FORCE, 0, 0}, {GD_REC_SPEED_RATIO, g, p}};
    int idx[8];
    int n = gd_transient_record_dofs(tr, &rec[0], idx, 8);
    CHECK(n == 1 && idx[0] == l);
    n = gd_transient_record_dofs(tr, &rec[1], idx, 8);
    int np = 0, ng = 0, other = 0;
    for (int i = 0; i < n; i++) {
        np += idx[i] == p;
        ng += idx[i] == g;
        other += idx[i] != p && idx[i] != g;
    }
    CHECK(n == 3 && np == 2 && ng == 1 && other == 0);          /* p as a mesh DOF and as driver */
    CHECK(gd_transient_record_dofs(tr, &rec[1], idx, 2) == -1); /* more than cap */
    n = gd_transient_record_dofs(tr, &rec[2], idx, 8);
    CHECK(n == 2 && ((idx[0] == p && idx[1] == g) || (idx[0] == g && idx[1] == p)));
    const int ns = gd_transient_nstates(tr), nf = ns / 2;
    REQUIRE(ns == 6);
    double y[6], v[3];
    for (int i = 0; i < ns; i++)
        y[i] = (i + 1) * (i < nf ? 1e-6 : 1e-3);
    gd_transient_record_values(tr, rec, 3, 0.01, y, v);
    for (int r = 0; r < 3; r++)
        CHECK(v[r] == gd_transient_record_value(tr, &rec[r], 0.01, y));
    CHECK(v[0] == y[l]);
    /* the speed ratio (W_g + q_g') / (W_p + q_p') at 300 rad/s on the pinion, 20:40 */
    CHECK_REL(v[2], (-150 + y[nf + g]) / (300 + y[nf + p]), 1e-12);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    unload(&f);
}

RUN_TESTS(T(mesh_laws), T(geometry_tvms), T(loads_prescribed_cams), T(errors), T(run_static_brake),
          T(run_cam), T(sfd_bearing), T(record_dofs_and_values))
