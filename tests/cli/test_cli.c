/* The geardyn command line, run as a program (GD_CLI_PATH) from the source folder:
 * exit codes, text and JSON output, options, output files and every error path.
 * Temporary files live in a mkdtemp folder under /tmp that each test removes. */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cli_support.h"
#include "harness.h"

#define KUMAR_COUPLED "examples/kumar2011_coupled.yaml"
#define KUMAR_TORSIONAL "examples/kumar2011_torsional.yaml"
#define CHEN "examples/chen1998_gear_pair.yaml"
#define RIG "examples/rig2018.yaml"

/* Paper values, Kumar 2011 Table 3.2 (rad/s). */
static const double KUMAR_COUPLED_OMEGA[8] = {0,        122.32,   309.70,   23446.05,
                                              38659.61, 40474.36, 54672.94, 57304.6};

/* ---- running the program ---- */

/* scratch folders, running geardyn, reading output: tests/cli_support.h */

/* ---- help and commands ---- */

TEST(help_lists_commands)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "--help");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "usage: geardyn COMMAND"));
    CHECK(contains(r.out, "check"));
    CHECK(contains(r.out, "modal"));
    CHECK(contains(r.out, "docs/model-format.md"));
    CHECK(r.err[0] == '\0');
    run_free(&r);

    run(&s, &r, "modal --help");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "--speed"));
    CHECK(contains(r.out, "--coupling"));
    CHECK(contains(r.out, "--out DIR"));
    run_free(&r);

    run(&s, &r, "check --help");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "--json"));
    run_free(&r);

    run(&s, &r, "--version");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "geardyn 0."));
    run_free(&r);

    run(&s, &r, "%s", ""); /* no command at all: usage on stderr, exit 2 */
    CHECK(r.code == 2);
    CHECK(contains(r.err, "usage: geardyn COMMAND"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    scratch_close(&s);
}

TEST(unknown_command)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "frobnicate " KUMAR_COUPLED);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "unknown command 'frobnicate'"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    scratch_close(&s);
}

/* ---- check ---- */

TEST(check_every_example)
{
    static const struct {
        const char *file;
        int nodes, dofs, elements;
    } ex[] = {
        {CHEN, 2, 6, 0},
        {KUMAR_COUPLED, 4, 8, 0},
        {KUMAR_TORSIONAL, 4, 4, 0},
        {RIG, 34, 170, 32},
    };
    scratch s;
    REQUIRE(scratch_open(&s));
    for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
        run_result r;
        run(&s, &r, "check %s", ex[i].file);
        char want[128];
        int bad = r.code != 0;
        snprintf(want, sizeof want, "nodes     %d\n", ex[i].nodes);
        bad |= !contains(r.out, want);
        snprintf(want, sizeof want, "DOFs      %d active", ex[i].dofs);
        bad |= !contains(r.out, want);
        snprintf(want, sizeof want, "elements  %d shaft elements", ex[i].elements);
        bad |= !contains(r.out, want);
        bad |= !contains(r.out, ex[i].file);
        if (bad) {
            fprintf(stderr, "  check %s:\n", ex[i].file);
            show(&r);
            gd_ts_->checks_failed++;
        }
        run_free(&r);
    }
    /* the speed ratio of the driven shaft follows from the mesh, reversed */
    run_result r;
    run(&s, &r, "check " KUMAR_COUPLED);
    CHECK(contains(r.out, "-0.94681"));
    CHECK(contains(r.out, "lateral-torsional"));
    run_free(&r);
    run(&s, &r, "check " RIG);
    CHECK(contains(r.out, "-1.5")); /* 48/32 teeth */
    run_free(&r);
    scratch_close(&s);
}

TEST(check_json)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "check " KUMAR_COUPLED " --json");
    CHECK(r.code == 0);
    cJSON *o = cJSON_Parse(r.out);
    if (!o) show(&r);
    REQUIRE(o);
    CHECK_STR(jstr(o, "model"), KUMAR_COUPLED);
    CHECK(jnum(o, "nodes") == 4);
    CHECK(jnum(o, "dofs") == 8);
    CHECK(jnum(o, "massless_dofs") == 0);
    CHECK(jnum(o, "shaft_elements") == 0);
    CHECK(jnum(o, "disks") == 4);
    CHECK(jnum(o, "bearings") == 2);
    CHECK(jnum(o, "springs") == 2);
    CHECK(jnum(o, "speed_rad_s") == 0);
    const cJSON *shafts = cJSON_GetObjectItemCaseSensitive(o, "shafts");
    REQUIRE(cJSON_GetArraySize(shafts) == 2);
    const cJSON *in = cJSON_GetArrayItem(shafts, 0), *outp = cJSON_GetArrayItem(shafts, 1);
    CHECK_STR(jstr(in, "name"), "input");
    CHECK(jnum(in, "nodes") == 2);
    CHECK_REL(jnum(in, "mass_kg"), 1.84, 1e-12);
    CHECK_REL(jnum(in, "polar_inertia_kg_m2"), 0.0115 + 0.001821, 1e-12);
    CHECK_REL(jnum(in, "speed_ratio"), 1.0, 1e-12);
    CHECK_STR(jstr(outp, "name"), "output");
    CHECK_REL(jnum(outp, "speed_ratio"), -0.0445 / 0.047, 1e-12);
    const cJSON *meshes = cJSON_GetObjectItemCaseSensitive(o, "meshes");
    REQUIRE(cJSON_GetArraySize(meshes) == 1);
    const cJSON *m = cJSON_GetArrayItem(meshes, 0);
    CHECK_STR(jstr(m, "driver"), "pinion");
    CHECK_STR(jstr(m, "driven"), "gear");
    CHECK_REL(jnum(m, "stiffness_N_per_m"), 2e8, 1e-12);
    CHECK_STR(jstr(m, "coupling"), "lateral-torsional");
    cJSON_Delete(o);
    run_free(&r);

    /* the rig: shaft mass = steel tube + gear */
    run(&s, &r, "check " RIG " --json");
    CHECK(r.code == 0);
    o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(jnum(o, "nodes") == 34);
    CHECK(jnum(o, "dofs") == 170);
    CHECK(jnum(o, "shaft_elements") == 32);
    const cJSON *d = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "shafts"), 0);
    CHECK_REL(jnum(d, "length_m"), 0.5, 1e-12);
    CHECK_REL(jnum(d, "mass_kg"), 7800 * M_PI / 4 * 0.0254 * 0.0254 * 0.5 + 1.15, 1e-9);
    const cJSON *n = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "shafts"), 1);
    CHECK_REL(jnum(n, "speed_ratio"), -1.5, 1e-12);
    cJSON_Delete(o);
    run_free(&r);

    /* --coupling torsional with --dofs rz: the 4-DOF torsional model */
    run(&s, &r, "check " KUMAR_COUPLED " --json --coupling torsional --dofs rz");
    CHECK(r.code == 0);
    o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(jnum(o, "dofs") == 4);
    CHECK_STR(
        jstr(cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "meshes"), 0), "coupling"),
        "torsional");
    cJSON_Delete(o);
    run_free(&r);
    scratch_close(&s);
}

/* ---- modal ---- */

/* Parses the modal table's rows "N f_n w_n w_d ..." into w_n; returns the row count. */
static int table_omegas(const char *out, double *w, int max)
{
    int n = 0;
    const char *p = out;
    while (p && *p) {
        int mode;
        double f, wn;
        if (sscanf(p, "%d %lf %lf", &mode, &f, &wn) == 3 && mode == n + 1 && n < max) w[n++] = wn;
        p = strchr(p, '\n');
        if (p) p++;
    }
    return n;
}

TEST(modal_table_kumar_coupled)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "modal " KUMAR_COUPLED);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "8 DOFs"));
    CHECK(contains(r.out, "undamped modes"));
    CHECK(contains(r.out, "(rigid body)"));
    double w[16] = {0};
    int n = table_omegas(r.out, w, 16);
    CHECK(n == 8);
    if (n != 8) show(&r);
    CHECK_ABS(w[0], 0.0, 1e-6);
    for (int i = 1; i < n && i < 8; i++)
        CHECK_REL(w[i], KUMAR_COUPLED_OMEGA[i], 0.01);
    run_free(&r);
    scratch_close(&s);
}

TEST(modal_json_kumar_coupled_matches_paper)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "modal " KUMAR_COUPLED " --json");
    CHECK(r.code == 0);
    cJSON *o = cJSON_Parse(r.out);
    if (!o) show(&r);
    REQUIRE(o);
    CHECK(jnum(o, "dofs") == 8);
    CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(o, "damped")));
    const cJSON *modes = cJSON_GetObjectItemCaseSensitive(o, "modes");
    REQUIRE(cJSON_GetArraySize(modes) == 8);
    for (int i = 0; i < 8; i++) {
        const cJSON *m = cJSON_GetArrayItem(modes, i);
        double wn = jnum(m, "omega_n_rad_s");
        CHECK(jnum(m, "mode") == i + 1);
        if (i == 0)
            CHECK_ABS(wn, 0.0, 1e-6);
        else
            CHECK_REL(wn, KUMAR_COUPLED_OMEGA[i], 0.01);
        CHECK_REL(jnum(m, "frequency_hz"), wn / (2 * M_PI), 1e-9);
        CHECK_REL(jnum(m, "omega_d_rad_s"), wn, 1e-9); /* undamped */
        CHECK_ABS(jnum(m, "damping_ratio"), 0.0, 1e-12);
        CHECK_STR(jstr(m, "whirl"), "none"); /* at rest */
        const cJSON *rb = cJSON_GetObjectItemCaseSensitive(m, "rigid_body");
        CHECK(cJSON_IsBool(rb));
        CHECK(cJSON_IsTrue(rb) == (i == 0));
        const cJSON *es = cJSON_GetObjectItemCaseSensitive(m, "energy_share");
        REQUIRE(cJSON_IsObject(es));
        double sum =
            jnum(es, "lateral") + jnum(es, "torsional") + jnum(es, "axial") + jnum(es, "tilt");
        if (i > 0) CHECK_REL(sum, 1.0, 1e-9);
        CHECK_ABS(jnum(es, "axial"), 0.0, 1e-12);
    }
    /* the two slow modes twist the shafts; the x modes (no mesh along x) are lateral */
    CHECK_STR(jstr(cJSON_GetArrayItem(modes, 0), "dominant_motion"), "torsional");
    CHECK_STR(jstr(cJSON_GetArrayItem(modes, 1), "dominant_motion"), "torsional");
    CHECK_STR(jstr(cJSON_GetArrayItem(modes, 1), "dominant_component"), "input_shaft");
    CHECK_STR(jstr(cJSON_GetArrayItem(modes, 3), "dominant_component"), "mesh");
    const cJSON *m5 = cJSON_GetArrayItem(modes, 4);
    CHECK_STR(jstr(m5, "dominant_motion"), "lateral");
    CHECK_REL(jnum(cJSON_GetObjectItemCaseSensitive(m5, "energy_share"), "lateral"), 1.0, 1e-9);
    CHECK_REL(jnum(cJSON_GetArrayItem(modes, 4), "omega_n_rad_s"), sqrt(2.75e9 / 1.84), 1e-9);
    CHECK_REL(jnum(cJSON_GetArrayItem(modes, 6), "omega_n_rad_s"), sqrt(2.75e9 / 0.92), 1e-9);
    cJSON_Delete(o);
    run_free(&r);
    scratch_close(&s);
}

/* Omegas of a modal --json run, or -1 modes on failure. */
static int json_omegas(scratch *s, double *w, int max, const char *args)
{
    run_result r;
    run(s, &r, "%s", args);
    cJSON *o = r.code == 0 ? cJSON_Parse(r.out) : NULL;
    int n = -1;
    if (o) {
        const cJSON *modes = cJSON_GetObjectItemCaseSensitive(o, "modes");
        n = cJSON_GetArraySize(modes);
        for (int i = 0; i < n && i < max; i++)
            w[i] = jnum(cJSON_GetArrayItem(modes, i), "omega_n_rad_s");
        cJSON_Delete(o);
    } else {
        show(&r);
    }
    run_free(&r);
    return n;
}

TEST(modal_speed_with_units)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const char *const speeds[] = {"3000rpm", "'3000 rpm'", "'50 Hz'", "314.1592653589793"};
    for (size_t i = 0; i < sizeof speeds / sizeof speeds[0]; i++) {
        run_result r;
        run(&s, &r, "modal " KUMAR_COUPLED " --json --speed %s", speeds[i]);
        CHECK(r.code == 0);
        cJSON *o = cJSON_Parse(r.out);
        REQUIRE(o);
        CHECK_REL(jnum(o, "speed_rad_s"), 100 * M_PI, 1e-12);
        cJSON_Delete(o);
        run_free(&r);
    }
    /* the rig at 3000 rpm: gyroscopic and damped, so whirl directions appear */
    run_result r;
    run(&s, &r, "modal " RIG " --json --speed '3000 rpm' --modes 8");
    CHECK(r.code == 0);
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(o, "damped")));
    const cJSON *modes = cJSON_GetObjectItemCaseSensitive(o, "modes");
    CHECK(cJSON_GetArraySize(modes) == 8);
    int fwd = 0, bwd = 0;
    for (int i = 0; i < cJSON_GetArraySize(modes); i++) {
        const char *wh = jstr(cJSON_GetArrayItem(modes, i), "whirl");
        fwd += !strcmp(wh, "forward");
        bwd += !strcmp(wh, "backward");
    }
    CHECK(fwd >= 1);
    CHECK(bwd >= 1);
    cJSON_Delete(o);
    run_free(&r);
    /* the table header states the speed */
    run(&s, &r, "modal " KUMAR_COUPLED " --speed 3000rpm");
    CHECK(contains(r.out, "speed 314.159 rad/s (3000 rpm)"));
    run_free(&r);
    scratch_close(&s);
}

TEST(modal_modes_count)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    double all[8], w[200];
    CHECK(json_omegas(&s, all, 8, "modal " KUMAR_COUPLED " --json") == 8);
    int n = json_omegas(&s, w, 200, "modal " KUMAR_COUPLED " --json --modes 3");
    CHECK(n == 3);
    for (int i = 1; i < 3 && n == 3; i++)
        CHECK_REL(w[i], all[i], 1e-9);
    /* more than there are: all of them */
    CHECK(json_omegas(&s, w, 200, "modal " KUMAR_COUPLED " --json --modes 50") == 8);
    /* big model: 20 by default, all on request */
    CHECK(json_omegas(&s, w, 200, "modal " RIG " --json") == 20);
    CHECK(json_omegas(&s, w, 200, "modal " RIG " --json --modes all") == 170);
    for (int i = 1; i < 170; i++)
        CHECK(w[i] >= w[i - 1] * (1 - 1e-9)); /* ascending */
    scratch_close(&s);
}

TEST(modal_undamped_and_damped)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    /* the rig has bearing and mesh damping: damped by default, undamped on request */
    run(&s, &r, "modal " RIG " --json --modes 6 --undamped");
    CHECK(r.code == 0);
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(o, "damped")));
    const cJSON *modes = cJSON_GetObjectItemCaseSensitive(o, "modes");
    CHECK(cJSON_GetArraySize(modes) == 6);
    for (int i = 0; i < cJSON_GetArraySize(modes); i++)
        CHECK_ABS(jnum(cJSON_GetArrayItem(modes, i), "damping_ratio"), 0.0, 1e-12);
    cJSON_Delete(o);
    run_free(&r);

    run(&s, &r, "modal " RIG " --json --modes 6");
    o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(o, "damped")));
    CHECK(jnum(cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "modes"), 1),
               "damping_ratio") > 0);
    cJSON_Delete(o);
    run_free(&r);

    /* Kumar has no damping: undamped by default, the same frequencies when forced damped */
    double wu[8], wd[8];
    CHECK(json_omegas(&s, wu, 8, "modal " KUMAR_COUPLED " --json") == 8);
    run(&s, &r, "modal " KUMAR_COUPLED " --json --damped");
    CHECK(r.code == 0);
    o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(o, "damped")));
    cJSON_Delete(o);
    run_free(&r);
    CHECK(json_omegas(&s, wd, 8, "modal " KUMAR_COUPLED " --json --damped") == 8);
    CHECK_ABS(wd[0], 0.0, 1e-3);
    for (int i = 1; i < 8; i++)
        CHECK_REL(wd[i], wu[i], 1e-6);
    run(&s, &r, "modal " KUMAR_COUPLED " --damped");
    CHECK(contains(r.out, "damped (state space) modes"));
    run_free(&r);
    scratch_close(&s);
}

TEST(modal_coupling_torsional_matches_torsional_model)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    double wc[8], wt[8];
    CHECK(json_omegas(&s, wc, 8, "modal " KUMAR_COUPLED " --json --coupling torsional --dofs rz") ==
          4);
    CHECK(json_omegas(&s, wt, 8, "modal " KUMAR_TORSIONAL " --json") == 4);
    CHECK_ABS(wc[0], 0.0, 1e-6);
    for (int i = 1; i < 4; i++)
        CHECK_REL(wc[i], wt[i], 1e-9);
    /* and the torsional paper values, Table 3.1, within 1% */
    CHECK_REL(wt[1], 122.32, 0.01);
    CHECK_REL(wt[2], 309.7, 0.01);
    CHECK_REL(wt[3], 25727.92, 0.01);
    run_result r;
    run(&s, &r, "modal " KUMAR_COUPLED " --coupling torsional --dofs rz");
    CHECK(contains(r.out, "4 DOFs"));
    run_free(&r);
    scratch_close(&s);
}

/* --coupling sets the meshes' level only ([JMSTHelical]: the shafts keep every DOF, the
 * mesh couples fewer); before, lateral-torsional also dropped z of every node. It
 * gives what the same level written in the file gives. --dofs removes DOFs. */
TEST(coupling_keeps_the_dofs_and_dofs_removes_them)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    const char *six = " --set 'dofs=[x, y, z, rx, ry, rz]' --set bearings.*.kzz=1e8";
    double wc[210], wf[210];
    char args[512];
    snprintf(args, sizeof args, "modal " RIG " --json --modes all --coupling lateral-torsional%s",
             six);
    int n = json_omegas(&s, wc, 210, args);
    CHECK(n == 204); /* 34 nodes x 6 */
    snprintf(args, sizeof args,
             "modal " RIG " --json --modes all --set meshes.*.coupling=lateral-torsional%s", six);
    CHECK(json_omegas(&s, wf, 210, args) == 204);
    for (int i = 0; i < n && i < 204; i++)
        CHECK_REL(wc[i], wf[i], 1e-12); /* the same model: identical up to rounding */
    run_result r;
    run(&s, &r, "check " RIG " --json --coupling torsional%s", six);
    CHECK(r.code == 0);
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(jnum(o, "dofs") == 204);
    cJSON_Delete(o);
    run_free(&r);
    run(&s, &r, "check " RIG " --json --dofs x,y,rz%s", six);
    o = cJSON_Parse(r.out);
    REQUIRE(o);
    CHECK(jnum(o, "dofs") == 102);
    cJSON_Delete(o);
    run_free(&r);
    /* errors: an unknown DOF, none of the model's */
    CHECK(run(&s, &r, "check " KUMAR_COUPLED " --dofs x,q") == 2);
    CHECK(contains(r.err, "unknown DOF 'q'") && contains(r.err, "--dofs"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    CHECK(run(&s, &r, "modal " KUMAR_COUPLED " --dofs z,rx") == 2);
    CHECK(contains(r.err, "none of these DOFs") && contains(r.err, "x,y,rz"));
    run_free(&r);
    CHECK(run(&s, &r, "modal " KUMAR_COUPLED " --dofs ,") == 2);
    CHECK(contains(r.err, "no DOFs listed"));
    run_free(&r);
    scratch_close(&s);
}

TEST(modal_out_writes_csv)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "modal " KUMAR_COUPLED " --out '%s/res'", s.dir);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "8 DOFs")); /* the table is still printed */
    char path[256];
    snprintf(path, sizeof path, "%s/res", s.dir);
    CHECK(count_entries(path) == 2); /* no staging folder left behind */
    snprintf(path, sizeof path, "%s/res/modes.csv", s.dir);
    char *modes = read_file(path);
    REQUIRE(modes);
    CHECK(strncmp(modes,
                  "mode,omega_n_rad_s,frequency_hz,omega_d_rad_s,damping_ratio,log_decrement,"
                  "whirl,dominant_motion,dominant_component,rigid_body,energy_lateral,"
                  "energy_torsional,energy_axial,energy_tilt,residual\n",
                  strlen("mode,omega_n_rad_s,frequency_hz,omega_d_rad_s,damping_ratio,log_"
                         "decrement,whirl,dominant_motion,dominant_component,rigid_body,energy_"
                         "lateral,energy_torsional,energy_axial,energy_tilt,residual\n")) == 0);
    CHECK(count_lines(modes) == 1 + 8);
    const char *row2 = strstr(modes, "\n2,");
    double w2 = row2 ? strtod(row2 + 3, NULL) : 0;
    CHECK_REL(w2, 122.32, 0.01);
    free(modes);
    snprintf(path, sizeof path, "%s/res/mode_shapes.csv", s.dir);
    char *shapes = read_file(path);
    REQUIRE(shapes);
    CHECK(strncmp(shapes, "mode,node,dof,real,imag,magnitude,phase_deg\n", 44) == 0);
    CHECK(count_lines(shapes) == 1 + 8 * 8); /* ndof x nmodes */
    CHECK(contains(shapes, "\n1,pinion,x,"));
    CHECK(contains(shapes, "\n8,load,rz,"));
    free(shapes);
    run_free(&r);

    /* the rig, 4 modes: 170 x 4 shape rows; an existing folder is reused */
    run(&s, &r, "modal " RIG " --modes 4 --out '%s/res'", s.dir);
    CHECK(r.code == 0);
    snprintf(path, sizeof path, "%s/res/mode_shapes.csv", s.dir);
    shapes = read_file(path);
    REQUIRE(shapes);
    CHECK(count_lines(shapes) == 1 + 170 * 4);
    free(shapes);
    snprintf(path, sizeof path, "%s/res/modes.csv", s.dir);
    modes = read_file(path);
    REQUIRE(modes);
    CHECK(count_lines(modes) == 1 + 4);
    free(modes);
    run_free(&r);
    scratch_close(&s);
}

/* ---- errors ---- */

TEST(error_missing_file)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "check examples/no_such_model.yaml");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "examples/no_such_model.yaml"));
    CHECK(contains(r.err, "cannot open"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    run(&s, &r, "modal no_such_model.yaml --json");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "no_such_model.yaml"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    scratch_close(&s);
}

#define BAD_MODEL                                                                                  \
    "shafts:\n"                                                                                    \
    "  - name: a\n"                                                                                \
    "    nodes: [{name: n1}]\n"                                                                    \
    "disks:\n"                                                                                     \
    "  - node: n1\n"                                                                               \
    "    mass: -3\n" /* line 6 */                                                                  \
    "    polar_inertia: 0.1\n"

TEST(error_bad_model_names_file_and_line)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[256], want[300];
    snprintf(path, sizeof path, "%s/bad.yaml", s.dir);
    write_file(path, BAD_MODEL);
    snprintf(want, sizeof want, "%s:6:", path);
    run_result r;
    run(&s, &r, "check '%s'", path);
    CHECK(r.code == 2);
    CHECK(contains(r.err, want));
    CHECK(contains(r.err, "disks[0].mass"));
    CHECK(contains(r.err, "hint:"));
    CHECK(r.out[0] == '\0');
    if (r.code != 2 || !contains(r.err, want)) show(&r);
    run_free(&r);
    run(&s, &r, "modal '%s' --json", path);
    CHECK(r.code == 2);
    CHECK(contains(r.err, want));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    scratch_close(&s);
}

TEST(error_unknown_option_and_missing_argument)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "check " KUMAR_COUPLED " --bogus");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--bogus"));
    CHECK(contains(r.err, "geardyn check --help"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    run(&s, &r, "modal " KUMAR_COUPLED " --frequencies");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--frequencies"));
    run_free(&r);
    run(&s, &r, "modal " KUMAR_COUPLED " --speed"); /* value missing */
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--speed"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    run(&s, &r, "check"); /* no model */
    CHECK(r.code == 2);
    CHECK(contains(r.err, "model file"));
    run_free(&r);
    run(&s, &r, "modal " KUMAR_COUPLED " " KUMAR_TORSIONAL); /* two models */
    CHECK(r.code == 2);
    CHECK(contains(r.err, "exactly one model"));
    run_free(&r);
    scratch_close(&s);
}

TEST(error_bad_speed)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const struct {
        const char *arg, *word;
    } bad[] = {{"fast", "'fast' is not a number"},
               {"-3", "zero or more"},
               {"'-100 rpm'", "zero or more"},
               {"'3 mm'", "'mm'"},
               {"nan", "finite"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        run_result r;
        run(&s, &r, "modal " KUMAR_COUPLED " --speed %s", bad[i].arg);
        int ok = r.code == 2 && contains(r.err, "--speed") && contains(r.err, bad[i].word) &&
                 r.out[0] == '\0';
        if (!ok) {
            fprintf(stderr, "  --speed %s:\n", bad[i].arg);
            show(&r);
            gd_ts_->checks_failed++;
        }
        run_free(&r);
    }
    scratch_close(&s);
}

TEST(error_bad_modes)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const char *const bad[] = {"0", "x", "-2", "3.5", "''"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        run_result r;
        run(&s, &r, "modal " KUMAR_COUPLED " --modes %s", bad[i]);
        int ok = r.code == 2 && contains(r.err, "--modes") && r.out[0] == '\0';
        if (!ok) {
            fprintf(stderr, "  --modes %s:\n", bad[i]);
            show(&r);
            gd_ts_->checks_failed++;
        }
        run_free(&r);
    }
    scratch_close(&s);
}

TEST(error_bad_coupling)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "modal " KUMAR_COUPLED " --coupling weird");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "'weird'"));
    CHECK(contains(r.err, "lateral-torsional"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    run(&s, &r, "check " KUMAR_COUPLED " --coupling Torsional");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--coupling"));
    run_free(&r);
    scratch_close(&s);
}

/* --method: a bad name, and sparse where it cannot serve (all modes), exit 2; sparse
 * and dense give the same frequencies on the rig (to the 6 digits of the table). */
TEST(modal_method_option)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "modal " RIG " --method lanczos");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--method: 'lanczos' is not auto, dense or sparse"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    run(&s, &r, "modal " RIG " --method sparse --modes all");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "lowest modes, not all"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    /* 4 modes of the 8-DOF Kumar pair: the Krylov space would span the whole problem */
    run(&s, &r, "modal examples/kumar2011_coupled.yaml --method sparse --modes 4");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "at most (DOFs - 1) / 2 modes: 4 modes of a 8-DOF model"));
    CHECK(contains(r.err, "ask for at most 3 modes"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    double f[2][6];
    const char *m[2] = {"dense", "sparse"};
    for (int k = 0; k < 2; k++) {
        char cmd[256];
        snprintf(cmd, sizeof cmd, "modal " RIG " --json --modes 6 --speed 3000rpm --method %s",
                 m[k]);
        run(&s, &r, cmd);
        CHECK(r.code == 0);
        cJSON *o = cJSON_Parse(r.out);
        REQUIRE(o);
        CHECK_STR(cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(o, "method")), m[k]);
        const cJSON *modes = cJSON_GetObjectItemCaseSensitive(o, "modes");
        for (int i = 0; i < 6; i++)
            f[k][i] = jnum(cJSON_GetArrayItem(modes, i), "frequency_hz");
        cJSON_Delete(o);
        run_free(&r);
    }
    for (int i = 0; i < 6; i++)
        CHECK_REL(f[1][i], f[0][i], 1e-9);
    scratch_close(&s);
}

TEST(error_undamped_with_damped)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "modal " KUMAR_COUPLED " --undamped --damped");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "exclude each other"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    run(&s, &r, "modal " KUMAR_COUPLED " --damped --undamped");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "exclude each other"));
    run_free(&r);
    scratch_close(&s);
}

TEST(error_out_is_a_file)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[256];
    snprintf(path, sizeof path, "%s/results", s.dir);
    write_file(path, "keep me\n");
    run_result r;
    run(&s, &r, "modal " KUMAR_COUPLED " --out '%s'", path);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "not a folder"));
    CHECK(contains(r.err, path));
    CHECK(r.out[0] == '\0'); /* no table either: the run failed */
    char *kept = read_file(path);
    CHECK(kept && !strcmp(kept, "keep me\n"));
    free(kept);
    run_free(&r);

    /* a folder whose parent does not exist */
    run(&s, &r, "modal " KUMAR_COUPLED " --out '%s/missing/res'", s.dir);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "cannot create folder"));
    run_free(&r);
    scratch_close(&s);
}

TEST(error_run_writes_nothing_into_out)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char bad[256], dir[256], file[300];
    snprintf(bad, sizeof bad, "%s/bad.yaml", s.dir);
    write_file(bad, BAD_MODEL);
    snprintf(dir, sizeof dir, "%s/res", s.dir);
    snprintf(file, sizeof file, "%s/modes.csv", dir);

    /* bad model, folder absent: not created */
    run_result r;
    run(&s, &r, "modal '%s' --out '%s'", bad, dir);
    CHECK(r.code == 2);
    CHECK(!file_exists(file));
    CHECK(!file_exists(dir));
    run_free(&r);

    /* bad model, folder present: left empty */
    mkdir(dir, 0777);
    run(&s, &r, "modal '%s' --out '%s'", bad, dir);
    CHECK(r.code == 2);
    CHECK(count_entries(dir) == 0);
    run_free(&r);

    /* bad option after a good model */
    run(&s, &r, "modal " KUMAR_COUPLED " --speed fast --out '%s'", dir);
    CHECK(r.code == 2);
    CHECK(count_entries(dir) == 0);
    run_free(&r);

    /* the model loads but the modal solve fails (massless DOF with a damper) */
    char mass[256];
    snprintf(mass, sizeof mass, "%s/massless.yaml", s.dir);
    write_file(mass, "dofs: [rz]\n"
                     "shafts:\n"
                     "  - name: a\n"
                     "    nodes: [{name: n1}, {name: n2}]\n"
                     "disks:\n"
                     "  - {node: n1, polar_inertia: 0.1}\n"
                     "springs:\n"
                     "  - {node: n1, to: n2, dof: rz, stiffness: 100}\n"
                     "  - {node: n2, dof: rz, damping: 5}\n");
    run(&s, &r, "modal '%s' --out '%s'", mass, dir);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "n2.rz"));
    CHECK(count_entries(dir) == 0);
    run_free(&r);
    /* check accepts the same model: the problem is the modal analysis' */
    run(&s, &r, "check '%s'", mass);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "1 massless"));
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(help_lists_commands), T(unknown_command), T(check_every_example), T(check_json),
          T(modal_table_kumar_coupled), T(modal_json_kumar_coupled_matches_paper),
          T(modal_speed_with_units), T(modal_modes_count), T(modal_undamped_and_damped),
          T(modal_coupling_torsional_matches_torsional_model),
          T(coupling_keeps_the_dofs_and_dofs_removes_them), T(modal_out_writes_csv),
          T(error_missing_file), T(error_bad_model_names_file_and_line),
          T(error_unknown_option_and_missing_argument), T(error_bad_speed), T(error_bad_modes),
          T(error_bad_coupling), T(modal_method_option), T(error_undamped_with_damped),
          T(error_out_is_a_file), T(error_run_writes_nothing_into_out))
