/* Static analysis (geardyn/static.h): a shaft on two bearings against the Timoshenko
 * beam closed form under a gear's mesh force and under its own weight, the force and
 * moment balance of every example, helical at 0 deg against spur, and the errors. */
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/static.h"
#include "harness.h"
#include "model_support.h"

#define PI 3.14159265358979323846

/* Driver shaft: L = 0.5 m, d = 30 mm on two radial bearings (no tilt stiffness, so the
 * reactions are statically determinate) at 0 and L, the gear at a = 0.2 m; the driven
 * shaft alike. The input torque acts at the driver gear itself, so the driver shaft is
 * loaded by the mesh force only. */
static const char PAIR[] =
    "dofs: [x, y, %s rx, ry, rz]\n"
    "materials: {steel: {density: 7800, E: 2.1e11, poisson: 0.3}}\n"
    "shafts:\n"
    "  - name: s1\n"
    "    material: steel\n"
    "    sections:\n"
    "      - {length: 0.2, outer_diameter: 30 mm, elements: 4}\n"
    "      - {length: 0.3, outer_diameter: 30 mm, elements: 6}\n"
    "    nodes: [{name: a1, at: 0}, {name: g1, at: 0.2}, {name: a2, at: 0.5}]\n"
    "  - name: s2\n"
    "    material: steel\n"
    "    sections:\n"
    "      - {length: 0.2, outer_diameter: 30 mm, elements: 4}\n"
    "      - {length: 0.3, outer_diameter: 30 mm, elements: 6}\n"
    "    nodes: [{name: b1, at: 0}, {name: g2, at: 0.2}, {name: b2, at: 0.5}]\n"
    "bearings:\n"
    "  - {name: A1, node: a1, k: 2e8%s}\n"
    "  - {name: A2, node: a2, k: 2e8%s}\n"
    "  - {name: B1, node: b1, k: 2e8%s}\n"
    "  - {name: B2, node: b2, k: 2e8%s}\n"
    "meshes:\n"
    "  - {name: m, driver: g1, driven: g2, base_radius: [0.05, 0.08],\n"
    "     pressure_angle: 20 deg, line_of_centres: 30 deg, stiffness: 4e8,\n"
    "     face_width: 20 mm, coupling: %s%s}\n";

static int load_pair(fx *f, const char *zdof, const char *kzz, const char *coupling,
                     const char *helix)
{
    char y[4096];
    snprintf(y, sizeof y, PAIR, zdof, kzz, kzz, kzz, kzz, coupling, helix);
    return load(f, NULL, y);
}

static gd_static_result *run(const fx *f, double torque, const char *input, gd_error *err)
{
    gd_static_options o;
    gd_static_options_init(&o);
    o.input_torque = torque;
    if (input) o.input_node = gd_model_find_node(f->m, input);
    gd_static_result *r = NULL;
    if (gd_static_run(f->s, &o, &r, err)) return NULL;
    return r;
}

static double node_u(const fx *f, const gd_static_result *r, const char *node, gd_dof d)
{
    return r->u[(size_t)gd_model_find_node(f->m, node) * GD_NODE_DOFS + d];
}

/* Timoshenko beam on two elastic supports k, point load P at a (b = L - a): the
 * deflection under the load per unit P, and the section rotation (bending only: the
 * shear strain integrates to zero between the supports) per unit P. */
static void beam(double L, double a, double d, double E, double nu, double k, double *cw,
                 double *ct)
{
    double b = L - a, I = PI * pow(d, 4) / 64, A = PI * d * d / 4, G = E / (2 * (1 + nu));
    double kappa = 6 * (1 + nu) / (7 + 6 * nu); /* Cowper, solid circle */
    double r1 = b / L, r2 = a / L;              /* reactions per unit load */
    *cw = a * a * b * b / (3 * E * I * L) + a * b / (kappa * G * A * L) + (r1 / k) * (1 - a / L) +
          (r2 / k) * (a / L);
    *ct = a * b * (b - a) / (3 * E * I * L) + (r2 / k - r1 / k) / L;
}

TEST(spur_shaft_against_timoshenko)
{
    fx f;
    REQUIRE(load_pair(&f, "", "", "full", ""));
    gd_error err;
    gd_static_result *r = run(&f, 100.0, "g1", &err);
    REQUIRE(r);
    const gd_static_mesh *m = &r->meshes[0];
    /* the driver's torque balance alone gives F = T / rb1 (the output is held) */
    CHECK_REL(m->force, 100.0 / 0.05, 1e-12);
    CHECK_REL(m->tangential, 2000 * cos(20 * PI / 180), 1e-12);
    CHECK_REL(m->radial, 2000 * sin(20 * PI / 180), 1e-12);
    double Px = m->on_driver[GD_X], Py = m->on_driver[GD_Y];
    CHECK_REL(hypot(Px, Py), 2000.0, 1e-12);
    double cw, ct;
    beam(0.5, 0.2, 0.03, 2.1e11, 0.3, 2e8, &cw, &ct);
    /* nodal values of the Timoshenko element are exact for nodal loads: 1e-6 is the
       issue's tolerance; the agreement is ~1e-10 (the solve's rounding) */
    CHECK_REL(node_u(&f, r, "g1", GD_X), cw * Px, 1e-6);
    CHECK_REL(node_u(&f, r, "g1", GD_Y), cw * Py, 1e-6);
    /* ry = dx/dz, rx = -dy/dz (src/elements/shaft.c) */
    CHECK_REL(node_u(&f, r, "g1", GD_RY), ct * Px, 1e-6);
    CHECK_REL(node_u(&f, r, "g1", GD_RX), -ct * Py, 1e-6);
    printf("  closed form: deflection rel err %.2g, slope rel err %.2g\n",
           fabs(node_u(&f, r, "g1", GD_X) / (cw * Px) - 1),
           fabs(node_u(&f, r, "g1", GD_RY) / (ct * Px) - 1));
    /* reactions: -P b / L and -P a / L */
    CHECK_REL(r->bearings[0].force[0], -Px * 0.3 / 0.5, 1e-9);
    CHECK_REL(r->bearings[0].force[1], -Py * 0.3 / 0.5, 1e-9);
    CHECK_REL(r->bearings[1].force[0], -Px * 0.2 / 0.5, 1e-9);
    CHECK_REL(r->bearings[1].force[1], -Py * 0.2 / 0.5, 1e-9);
    /* the torque hold: the driven shaft's last node, reacting T rb2 / rb1 */
    REQUIRE(r->nholds == 1);
    CHECK(r->holds[0].node == gd_model_find_node(f.m, "b2"));
    CHECK(!r->holds[0].prescribed);
    CHECK_REL(fabs(r->holds[0].reaction), 100.0 * 0.08 / 0.05, 1e-9);
    /* misalignment: the relative tilt in the plane of action times the face width */
    double n[2] = {-Px / 2000, -Py / 2000}; /* force on the driver is -F n */
    double tx = node_u(&f, r, "g1", GD_RX) - node_u(&f, r, "g2", GD_RX);
    double ty = node_u(&f, r, "g1", GD_RY) - node_u(&f, r, "g2", GD_RY);
    CHECK_REL(m->tilt_in_plane, -tx * n[1] + ty * n[0], 1e-12);
    CHECK_ABS(m->tilt_out_of_plane, tx * n[0] + ty * n[1], 1e-12 * fabs(m->tilt_in_plane));
    CHECK_REL(m->f_sh, 0.02 * m->tilt_in_plane, 1e-12);
    CHECK(fabs(m->tilt_out_of_plane) < 1e-6 * fabs(m->tilt_in_plane));
    /* both shafts bend the same way in the plane of action: the driven one carries the
       opposite force at the same place on the same shaft, so the tilts cancel
       and only the gear sizes (none here) could differ: check against the closed form */
    CHECK_REL(m->tilt_in_plane, 2 * ct * 2000 * (-1), 1e-6);
    gd_static_free(r);
    fx_free(&f);
}

TEST(gravity_against_uniform_load)
{
    static const char Y[] =
        "dofs: [x, y, rx, ry]\n"
        "materials: {steel: {density: 7800, E: 2.1e11, poisson: 0.3}}\n"
        "gravity: {direction: [0, -2, 0], g: 9.81}\n"
        "shafts:\n"
        "  - name: s\n"
        "    material: steel\n"
        "    sections: [{length: 0.8, outer_diameter: 40 mm, elements: 16}]\n"
        "    nodes: [{name: l, at: 0}, {name: mid, at: 0.4}, {name: r, at: 0.8}]\n"
        "bearings:\n"
        "  - {name: L, node: l, k: 5e7}\n"
        "  - {name: R, node: r, k: 5e7}\n";
    fx f;
    REQUIRE(load(&f, NULL, Y));
    CHECK_REL(f.m->gravity[1], -9.81, 1e-15);
    gd_error err;
    gd_static_result *r = run(&f, 0, NULL, &err);
    REQUIRE(r);
    double L = 0.8, d = 0.04, E = 2.1e11, nu = 0.3, I = PI * pow(d, 4) / 64, A = PI * d * d / 4;
    double G = E / (2 * (1 + nu)), kappa = 6 * (1 + nu) / (7 + 6 * nu), w = 7800 * A * 9.81;
    /* reactions w L / 2 up: exact (statically determinate) */
    CHECK_REL(r->bearings[0].force[1], w * L / 2, 1e-9);
    CHECK_REL(r->bearings[1].force[1], w * L / 2, 1e-9);
    /* midspan: 5 w L^4 / (384 E I) + w L^2 / (8 kappa G A) + the bearings' w L / (2 k);
       end slope w L^3 / (24 E I) plus the rigid tilt 0; consistent loads on elements
       with exact homogeneous shape functions give exact nodal values */
    double mid =
        5 * w * pow(L, 4) / (384 * E * I) + w * L * L / (8 * kappa * G * A) + w * L / (2 * 5e7);
    CHECK_REL(node_u(&f, r, "mid", GD_Y), -mid, 1e-6);
    printf("  weight: midspan rel err %.2g, end slope rel err %.2g\n",
           fabs(node_u(&f, r, "mid", GD_Y) / -mid - 1),
           fabs(node_u(&f, r, "l", GD_RX) / (w * pow(L, 3) / (24 * E * I)) - 1));
    CHECK_REL(node_u(&f, r, "l", GD_RX), w * pow(L, 3) / (24 * E * I), 1e-6);
    CHECK_ABS(node_u(&f, r, "mid", GD_RX), 0, 1e-15);
    CHECK_ABS(node_u(&f, r, "mid", GD_X), 0, 1e-18);
    gd_static_free(r);
    fx_free(&f);
}

/* Sum over shaft s of every force on its nodes (applied, supports, meshes, holds):
 * forces and moments about the shaft's origin; scale collects the magnitudes. */
static void shaft_balance(const fx *f, const gd_static_result *r, int s, double out[6],
                          double *scale)
{
    const gd_model *m = f->m;
    double F[64][6];
    memset(out, 0, 6 * sizeof *out);
    *scale = 0;
    for (int p = m->shafts[s].first_node; p < m->shafts[s].first_node + m->shafts[s].nnodes; p++) {
        /* the loads and the laws' forces as two terms, so the scale is the load's even
           where the laws alone carry it */
        double t[6] = {0}, tl[6] = {0};
        int nt = 0;
        for (int i = 0; i < r->ndof; i++)
            if (f->s->dof_node[i] == p) {
                t[f->s->dof_type[i]] += r->f[i];
                tl[f->s->dof_type[i]] += r->law_forces[i];
            }
        memcpy(F[nt++], t, sizeof t);
        memcpy(F[nt++], tl, sizeof tl);
        for (int b = 0; b < m->nbearings && nt < 60; b++) {
            double sg = m->bearings[b].node == p ? 1 : m->bearings[b].node2 == p ? -1 : 0;
            if (sg == 0) continue;
            for (int k = 0; k < 3; k++) {
                F[nt][k] = sg * r->bearings[b].force[k];
                F[nt][3 + k] = sg * r->bearings[b].moment[k];
            }
            nt++;
        }
        for (int k = 0; k < m->nsprings && nt < 60; k++) {
            double sg = m->springs[k].node1 == p ? 1 : m->springs[k].node2 == p ? -1 : 0;
            if (sg == 0) continue;
            memset(F[nt], 0, sizeof F[nt]);
            F[nt++][m->springs[k].dof] = sg * r->springs[k];
        }
        for (int k = 0; k < m->nmeshes && nt < 60; k++) {
            if (m->meshes[k].driver == p) memcpy(F[nt++], r->meshes[k].on_driver, sizeof F[0]);
            if (m->meshes[k].driven == p) memcpy(F[nt++], r->meshes[k].on_driven, sizeof F[0]);
        }
        /* a planetary set's springs on the node (its sun, ring or carrier, or a planet):
           -K u of each instance, summed into one entry */
        double ps[6] = {0};
        for (int e = 0; e < f->s->ninstances; e++) {
            const gd_element_instance *in = &f->s->instances[e];
            int nodes[2];
            if (in->type != &gd_element_planetary) continue;
            int nn = in->type->nodes(m, in->index, nodes);
            for (int side = 0; side < nn; side++) {
                if (nodes[side] != p) continue;
                double K[144], u[12];
                in->type->matrices(m, in->index, r->speed, NULL, K, NULL, NULL);
                for (int a = 0; a < in->nlocal; a++)
                    u[a] = in->dof[a] >= 0 ? r->q[in->dof[a]] : 0;
                for (int k = 0; k < 6; k++)
                    for (int a = 0; a < in->nlocal; a++)
                        ps[k] -= K[(6 * side + k) * in->nlocal + a] * u[a];
            }
        }
        if (nt < 60) memcpy(F[nt++], ps, sizeof ps);
        for (int h = 0; h < r->nholds && nt < 60; h++)
            if (r->holds[h].node == p) {
                memset(F[nt], 0, sizeof F[nt]);
                F[nt++][r->holds[h].dof] = r->holds[h].reaction;
            }
        double z = m->nodes[p].position;
        for (int j = 0; j < nt; j++) {
            double g[6] = {F[j][0], F[j][1], F[j][2], F[j][3] - z * F[j][1], F[j][4] + z * F[j][0],
                           F[j][5]};
            for (int k = 0; k < 6; k++) {
                out[k] += g[k];
                *scale = fmax(*scale, fabs(g[k]));
            }
        }
    }
}

TEST(examples_balance)
{
    glob_t g;
    REQUIRE(glob("examples/*.yaml", 0, NULL, &g) == 0);
    int checked = 0;
    double worst = 0;
    for (size_t e = 0; e < g.gl_pathc; e++) {
        /* the gear-pair files (mesh-stiffness input) are not models */
        FILE *fp = fopen(g.gl_pathv[e], "r");
        char line[512];
        int model = 0;
        while (fp && fgets(line, sizeof line, fp))
            if (!strncmp(line, "shafts:", 7)) model = 1;
        if (fp) fclose(fp);
        if (!model) continue;
        fx f;
        if (!load(&f, g.gl_pathv[e], NULL)) {
            fprintf(stderr, "  %s did not load\n", g.gl_pathv[e]);
            CHECK(0);
            continue;
        }
        /* gravity across the shafts and an input torque on top of the model's loads */
        f.m->gravity[1] = -9.81;
        /* a model without torsion (a lateral oscillator) gets no torque, and its weight
         * along x */
        int has_rz = 0;
        for (int i = 0; i < f.s->ndof; i++)
            has_rz |= f.s->dof_type[i] == GD_RZ;
        if (!has_rz) f.m->gravity[0] = -9.81;
        gd_error err;
        gd_static_result *r = run(&f, has_rz ? 10.0 : 0.0, NULL, &err);
        if (!r && f.m->nlaws && err.status == GD_EINPUT && strstr(err.message, "no static")) {
            /* held by journal bearings alone at the model's speed 0: no equilibrium, said
             * so (journal_rotor_settles_at_the_laws_state runs it at speed) */
            fx_free(&f);
            continue;
        }
        if (!r) {
            fprintf(stderr, "  %s: %s\n", g.gl_pathv[e], err.message);
            CHECK(0);
            fx_free(&f);
            continue;
        }
        double total = 0;
        for (int i = 0; i < r->ndof; i++)
            total += fabs(r->f[i]);
        CHECK(total > 0);
        for (int s = 0; s < f.m->nshafts; s++) {
            double b[6], scale;
            shaft_balance(&f, r, s, b, &scale);
            for (int k = 0; k < 6; k++)
                worst = fmax(worst, fabs(b[k]) / fmax(scale, 1e-300));
            for (int k = 0; k < 6; k++)
                if (!(fabs(b[k]) <= 1e-9 * fmax(scale, 1e-300))) {
                    fprintf(stderr, "  %s shaft %s component %d: residual %.3g of %.3g\n",
                            g.gl_pathv[e], f.m->shafts[s].name, k, b[k], scale);
                    CHECK(0);
                }
        }
        checked++;
        gd_static_free(r);
        fx_free(&f);
    }
    CHECK(checked >= 6);
    printf("  %d examples: worst residual %.2g of the largest term\n", checked, worst);
    globfree(&g);
}

TEST(helical_at_zero_equals_spur)
{
    fx sp, he;
    REQUIRE(load_pair(&sp, "", "", "lateral-torsional", ""));
    REQUIRE(load_pair(&he, "z,", ", kzz: 1e8", "full", ", helix_angle: 0 deg, hand: left"));
    gd_error err;
    gd_static_result *a = run(&sp, 50.0, NULL, &err), *b = run(&he, 50.0, NULL, &err);
    REQUIRE(a && b);
    CHECK_REL(b->meshes[0].force, a->meshes[0].force, 1e-12);
    CHECK_ABS(b->meshes[0].axial, 0, 1e-12);
    double umax = 0;
    for (int i = 0; i < sp.m->nnodes * GD_NODE_DOFS; i++)
        umax = fmax(umax, fabs(a->u[i]));
    for (int i = 0; i < sp.m->nnodes * GD_NODE_DOFS; i++)
        CHECK_ABS(b->u[i], a->u[i], 1e-12 * umax);
    gd_static_free(a);
    gd_static_free(b);
    /* 15 deg: the axial force F sin(bb) is reacted axially by the driver's bearings */
    fx h15;
    REQUIRE(load_pair(&h15, "z,", ", kzz: 1e8", "full", ", helix_angle: 15 deg, hand: right"));
    gd_static_result *c = run(&h15, 50.0, "g1", &err);
    REQUIRE(c);
    double bb = h15.m->meshes[0].base_helix_angle;
    CHECK_REL(c->meshes[0].force, 50.0 / (0.05 * cos(bb)), 1e-12);
    CHECK_REL(fabs(c->meshes[0].on_driver[GD_Z]), c->meshes[0].force * sin(bb), 1e-12);
    CHECK_REL(c->bearings[0].force[2] + c->bearings[1].force[2], -c->meshes[0].on_driver[GD_Z],
              1e-9);
    /* the axial force at the base radius tilts the gear: |M| = rb1 F sin(bb) */
    CHECK_REL(hypot(c->meshes[0].on_driver[GD_RX], c->meshes[0].on_driver[GD_RY]),
              0.05 * c->meshes[0].force * sin(bb), 1e-12);
    gd_static_free(c);
    fx_free(&sp);
    fx_free(&he);
    fx_free(&h15);
}

/* Cross-coupled bearings (kxy != kyx) make K unsymmetric: the free train is found by
 * the SVD path, and the torque and force balances still hold. */
TEST(cross_coupled_bearings)
{
    fx f;
    REQUIRE(load_pair(&f, "", ", kxy: 3e7, kyx: -3e7", "full", ""));
    gd_error err;
    gd_static_result *r = run(&f, 100.0, "g1", &err);
    REQUIRE(r);
    CHECK_REL(r->meshes[0].force, 100.0 / 0.05, 1e-12);
    REQUIRE(r->nholds == 1);
    CHECK(r->holds[0].node == gd_model_find_node(f.m, "b2"));
    for (int s = 0; s < 2; s++) {
        double b[6], scale;
        shaft_balance(&f, r, s, b, &scale);
        for (int k = 0; k < 6; k++)
            CHECK(fabs(b[k]) <= 1e-9 * scale);
    }
    /* the reactions are statically determinate (P b / L), but the cross terms turn the
       bearing's displacement away from its force: R = -K u with K = [[kxx, kxy], [kyx,
       kyy]] */
    double Px = r->meshes[0].on_driver[GD_X], Py = r->meshes[0].on_driver[GD_Y];
    CHECK_REL(r->bearings[0].force[0], -Px * 0.6, 1e-9);
    CHECK_REL(r->bearings[0].force[1], -Py * 0.6, 1e-9);
    double ux = node_u(&f, r, "a1", GD_X), uy = node_u(&f, r, "a1", GD_Y);
    CHECK_REL(r->bearings[0].force[0], -(2e8 * ux + 3e7 * uy), 1e-9);
    CHECK_REL(r->bearings[0].force[1], -(-3e7 * ux + 2e8 * uy), 1e-9);
    gd_static_free(r);
    fx_free(&f);
}

TEST(free_shaft_is_named)
{
    /* no axial bearing stiffness with z active: the driven shaft floats axially */
    fx f;
    REQUIRE(load_pair(&f, "z,", "", "lateral-torsional", ""));
    gd_error err;
    CHECK(run(&f, 10.0, NULL, &err) == NULL);
    CHECK(err.status == GD_EINPUT);
    CHECK(strstr(err.message, "axial translation z") != NULL);
    CHECK(strstr(err.message, "shaft 's") != NULL);
    CHECK(err.line > 0);
    fx_free(&f);
}

TEST(gravity_key_errors)
{
    static const char *const BAD[][2] = {
        {"gravity: {direction: [0, 0, 0]}", "gravity direction is zero"},
        {"gravity: {direction: [0, -1]}", "expected a list of three values"},
        {"gravity: {g: 9.81}", "gravity without a direction"},
        {"gravity: {direction: [0, -1, 0], g: -1}", "g"},
        {"gravity: {direction: [0, -1, 0], gee: 1}", "gee"},
    };
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++) {
        char y[512];
        snprintf(y, sizeof y,
                 "shafts: [{name: s, nodes: [{name: a}]}]\ndisks: [{node: a, mass: 1}]\n%s\n",
                 BAD[i][0]);
        gd_model *m = NULL;
        gd_error err;
        CHECK(gd_model_load_string(y, "bad.yaml", &m, &err) == GD_EINPUT);
        CHECK(m == NULL);
        CHECK(err.line == 3);
        if (!strstr(err.message, BAD[i][1]) && !strstr(err.field, BAD[i][1])) {
            fprintf(stderr, "  %s: %s (%s)\n", BAD[i][0], err.message, err.field);
            CHECK(0);
        }
    }
}

/* A rigid rotor on two journal bearings (examples/journal_rotor.yaml) under its weight:
 * held by its laws alone, it settles where the bearings carry the weight. The static
 * analysis and the state the linear analyses linearise about (gd_system_law_state,
 * checked against Ocvirk's load capacity in tests/system/test_system_laws.c) solve one
 * equation with one Newton iteration, so they agree to its tolerance (1e-10 of the
 * load); the bearings' vertical forces add up to the weight 40 x 9.81 N. At rest the
 * bearings carry nothing: an input error that says so. */
TEST(journal_rotor_settles_at_the_laws_state)
{
    fx f;
    REQUIRE(load(&f, "examples/journal_rotor.yaml", NULL));
    gd_static_options o;
    gd_static_options_init(&o);
    o.speed = 1000.0;
    gd_static_result *r = NULL;
    gd_error err;
    REQUIRE(gd_static_run(f.s, &o, &r, &err) == GD_OK);
    double *q = calloc((size_t)f.s->ndof, sizeof *q);
    REQUIRE(q);
    CHECK(gd_system_law_state(f.s, 1000.0, q) == 1);
    double qmax = 0, dmax = 0, fy = 0;
    for (int i = 0; i < f.s->ndof; i++) {
        qmax = fmax(qmax, fabs(q[i]));
        dmax = fmax(dmax, fabs(q[i] - r->q[i]));
        if (f.s->dof_type[i] == GD_Y) fy += r->law_forces[i];
    }
    printf("  1000 rad/s: |q| %.4g m, static vs law state %.2g, bearings carry %.10g N\n", qmax,
           dmax, fy);
    CHECK(qmax > 1e-6 && qmax < 50e-6); /* inside the 50 um clearance */
    CHECK(dmax <= 1e-9 * qmax);
    CHECK_REL(fy, 40 * 9.81, 1e-9);
    CHECK(r->nholds == 0);
    REQUIRE(r->nlaws == 2);
    CHECK_STR(r->laws[0].type, "journal_bearing");
    CHECK_STR(r->laws[0].record_names[2], "ecc");
    int x = gd_system_dof(f.s, 0, GD_X), y = gd_system_dof(f.s, 0, GD_Y);
    CHECK_REL(r->laws[0].records[2], hypot(r->q[x], r->q[y]) / 50e-6, 1e-12);
    CHECK_REL(r->laws[0].records[1], fy / 2, 1e-9); /* fy: the load on each, symmetric */
    gd_static_free(r);
    o.speed = 0;
    r = NULL;
    CHECK(gd_static_run(f.s, &o, &r, &err) == GD_EINPUT);
    CHECK(r == NULL && strstr(err.message, "no static") != NULL);
    CHECK(strstr(err.message, "carries nothing at 0 rad/s") != NULL);
    CHECK_STR(err.field, "laws[0]"); /* located at the first journal bearing */
    CHECK(err.line == 24);
    free(q);
    fx_free(&f);
}

RUN_TESTS(T(spur_shaft_against_timoshenko), T(gravity_against_uniform_load), T(examples_balance),
          T(helical_at_zero_equals_spur), T(cross_coupled_bearings), T(free_shaft_is_named),
          T(gravity_key_errors), T(journal_rotor_settles_at_the_laws_state))
