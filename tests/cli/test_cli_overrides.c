/* `--set PATH=VALUE` on the command line: every subcommand lists and applies it, the
 * result equals that of an edited copy of the file, and every error (nothing matched,
 * malformed, a value the model rejects, too many) exits 2, names the --set argument and
 * writes nothing. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "harness.h"

#define CHEN "examples/chen1998_gear_pair.yaml"
#define PAIR1 "examples/helical_pair1.yaml"

/* The arguments each subcommand needs besides its file, %s being an output folder. */
static const struct {
    const char *cmd, *file, *args;
} COMMANDS[] = {
    {"check", CHEN, ""},
    {"modal", CHEN, "--out '%s'"},
    {"campbell", CHEN, "--speeds 0:100:2 --out '%s'"},
    {"frf", CHEN, "--input gear_a.x --output gear_b.x --freq 1:10:2 --out '%s'"},
    {"unbalance", CHEN, "--speeds 1:10:2 --out '%s'"},
    {"transient", CHEN, "--duration 1ms --quiet --out '%s'"},
    {"matrices", CHEN, "--out '%s'"},
    {"mesh-stiffness", PAIR1, "--out '%s'"},
};
#define NCOMMANDS (sizeof COMMANDS / sizeof COMMANDS[0])

TEST(every_command_lists_set)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    for (size_t i = 0; i < NCOMMANDS; i++) {
        run(&s, &r, "%s --help", COMMANDS[i].cmd);
        CHECK(r.code == 0);
        if (!contains(r.out, "[--set PATH=VALUE]...") || !contains(r.out, "  --set PATH=VALUE")) {
            fprintf(stderr, "  %s --help does not list --set\n", COMMANDS[i].cmd);
            CHECK(0);
        }
        run_free(&r);
    }
    scratch_close(&s);
}

TEST(every_command_applies_set_and_writes_nothing_on_error)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char out[256], args[512];
    snprintf(out, sizeof out, "%s/res", s.dir);
    run_result r;
    for (size_t i = 0; i < NCOMMANDS; i++) {
        snprintf(args, sizeof args, COMMANDS[i].args, out);
        run(&s, &r, "%s %s %s --set meshes.msh.stiffness=1 --set meshes.0.damping=1",
            COMMANDS[i].cmd, COMMANDS[i].file, args);
        int ok = r.code == 2 &&
                 contains(r.err, "geardyn: error: --set meshes.msh.stiffness=1: meshes.msh: "
                                 "no mesh named 'msh' in 'meshes'\n  hint: have: ") &&
                 !file_exists(out);
        if (!ok) {
            fprintf(stderr, "  %s did not apply --set:\n", COMMANDS[i].cmd);
            show(&r);
            CHECK(0);
        }
        run_free(&r);
    }
    scratch_close(&s);
}

/* Each mode's frequency and damping from `modal --json` output. */
static int modes_of(const char *json, double *f, double *z, int max)
{
    cJSON *o = cJSON_Parse(json);
    const cJSON *modes = cJSON_GetObjectItem(o, "modes"), *md;
    int n = 0;
    cJSON_ArrayForEach(md, modes)
    {
        if (n == max) break;
        f[n] = jnum(md, "frequency_hz");
        z[n++] = jnum(md, "damping_ratio");
    }
    cJSON_Delete(o);
    return n;
}

TEST(modal_equals_an_edited_copy)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char *text = read_file(CHEN), copy[256];
    REQUIRE(text);
    const char *line = "stiffness: 34.098 MN/m", *at = strstr(text, line);
    REQUIRE(at);
    char *edited = malloc(strlen(text) + 32);
    REQUIRE(edited);
    sprintf(edited, "%.*sstiffness: 5e7%s", (int)(at - text), text, at + strlen(line));
    snprintf(copy, sizeof copy, "%s/chen_edited.yaml", s.dir);
    write_file(copy, edited);
    free(edited);
    free(text);

    double f0[8], z0[8], f1[8], z1[8], f2[8], z2[8];
    run_result r;
    REQUIRE(run(&s, &r, "modal '%s' --json", copy) == 0);
    int n0 = modes_of(r.out, f0, z0, 8);
    run_free(&r);
    REQUIRE(run(&s, &r, "modal " CHEN " --json --set 'meshes.*.stiffness=5e7'") == 0);
    int n1 = modes_of(r.out, f1, z1, 8);
    run_free(&r);
    REQUIRE(run(&s, &r, "modal " CHEN " --json") == 0);
    int n2 = modes_of(r.out, f2, z2, 8);
    run_free(&r);
    REQUIRE(n0 == 6 && n1 == 6 && n2 == 6);
    for (int j = 0; j < 6; j++) {
        CHECK_REL(f1[j], f0[j], 1e-12);
        CHECK_REL(z1[j], z0[j], 1e-12);
    }
    CHECK(fabs(f2[5] - f0[5]) > 1e-3 * f0[5]); /* the stiffest mode moved */
    scratch_close(&s);
}

TEST(check_shows_the_new_values)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r,
        "check " CHEN " --json --set meshes.mesh.stiffness=3e8N/m --set 'meshes.mesh.damping=1 "
        "kN*s/m' --set speed=3000rpm");
    CHECK(r.code == 0);
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    const cJSON *mesh = cJSON_GetArrayItem(cJSON_GetObjectItem(o, "meshes"), 0);
    CHECK(jnum(mesh, "stiffness_N_per_m") == 3e8);
    CHECK(jnum(mesh, "damping_N_s_per_m") == 1000);
    CHECK_REL(jnum(o, "speed_rad_s"), 100 * M_PI, 1e-15);
    cJSON_Delete(o);
    run_free(&r);
    /* a flow list from the shell */
    run(&s, &r, "check " CHEN " --set 'meshes.mesh.base_radius=[12 mm, 54 mm]'");
    CHECK(r.code == 0);
    CHECK(contains(r.out, " 4.5 ") && contains(r.out, " 0.012 "));
    run_free(&r);
    scratch_close(&s);
}

TEST(errors_name_the_set_argument)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "check " CHEN " --set disks.0.mass=-2");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "geardyn: error: --set disks.0.mass=-2: disks[0].mass: must be "
                          "positive (got -2)\n  hint: give a value greater than zero"));
    run_free(&r);
    run(&s, &r, "modal " CHEN " --set meshes.mesh.dampng=5");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--set meshes.mesh.dampng=5: meshes[0].dampng: unknown key 'dampng'"));
    CHECK(contains(r.err, "did you mean 'damping'?"));
    run_free(&r);
    run(&s, &r, "check " CHEN " --set meshes.mesh.stiffness");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--set meshes.mesh.stiffness: no '=' between the path and the value"));
    run_free(&r);
    run(&s, &r, "check " CHEN " --set 'bearings..k=1'");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "empty segment 2 in the path"));
    run_free(&r);
    run(&s, &r, "check " CHEN " --set");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "option '--set' needs a value"));
    run_free(&r);
    char many[64 * 32 + 1] = "";
    for (int i = 0; i < 65; i++)
        strcat(many, " --set speed=1");
    run(&s, &r, "check " CHEN "%s", many);
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--set: at most 64 options"));
    run_free(&r);
    scratch_close(&s);
}

TEST(mesh_stiffness_set)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    REQUIRE(run(&s, &r, "mesh-stiffness " PAIR1 " --json --helix-angle 0") == 0);
    cJSON *a = cJSON_Parse(r.out);
    run_free(&r);
    REQUIRE(run(&s, &r,
                "mesh-stiffness " PAIR1
                " --json --set meshes.pair1.geometry.helix_angle=0deg") == 0);
    cJSON *b = cJSON_Parse(r.out);
    run_free(&r);
    REQUIRE(a && b);
    CHECK_ABS(jnum(b, "contact_ratio_transverse"), 1.7865, 0.5e-4);
    CHECK(jnum(b, "stiffness_mean") == jnum(a, "stiffness_mean"));
    CHECK(jnum(b, "slices") == 1);
    cJSON_Delete(a);
    cJSON_Delete(b);
    run(&s, &r, "mesh-stiffness " PAIR1 " --set meshes.pair1.geometry.face_width=-1mm");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "geardyn: error: --set meshes.pair1.geometry.face_width=-1mm: "
                          "meshes[0].geometry.face_width: must be positive"));
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(every_command_lists_set), T(every_command_applies_set_and_writes_nothing_on_error),
          T(modal_equals_an_edited_copy), T(check_shows_the_new_values),
          T(errors_name_the_set_argument), T(mesh_stiffness_set))
