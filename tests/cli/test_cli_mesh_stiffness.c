/* geardyn mesh-stiffness: every option and error path, exit codes, and that nothing
 * is written on error. */
#include <cjson/cJSON.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "harness.h"

static char tmpdir[256];
static char out_text[1 << 20], err_text[1 << 16];

static void slurp(const char *path, char *buf, size_t size)
{
    buf[0] = '\0';
    FILE *f = fopen(path, "r");
    if (!f) return;
    size_t n = fread(buf, 1, size - 1, f);
    buf[n] = '\0';
    fclose(f);
}

/* Runs "geardyn mesh-stiffness ARGS" from the source folder; returns the exit code. */
static int run(const char *args)
{
    if (!tmpdir[0]) {
        snprintf(tmpdir, sizeof tmpdir, "/tmp/gd-cli-ms-XXXXXX");
        if (!mkdtemp(tmpdir)) return -1;
    }
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' mesh-stiffness %s >'%s/out' 2>'%s/err'",
             GD_SOURCE_DIR, GD_CLI_PATH, args, tmpdir, tmpdir);
    int st = system(cmd);
    char p[400];
    snprintf(p, sizeof p, "%s/out", tmpdir);
    slurp(p, out_text, sizeof out_text);
    snprintf(p, sizeof p, "%s/err", tmpdir);
    slurp(p, err_text, sizeof err_text);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static const char *write_file(const char *name, const char *text)
{
    static char path[400];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return path;
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

static double num(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

TEST(help_and_usage)
{
    CHECK(run("--help") == 0);
    CHECK(strstr(out_text, "usage: geardyn mesh-stiffness FILE") != NULL);
    CHECK(strstr(out_text, "--helix-angle") != NULL);
    CHECK(run("") == 2);
    CHECK(strstr(err_text, "give exactly one FILE") != NULL);
    CHECK(run("a.yaml b.yaml") == 2);
    CHECK(run("examples/rig2018_pair.yaml --bogus") == 2);
    CHECK(strstr(err_text, "unknown option '--bogus'") != NULL);
    CHECK(run("examples/rig2018_pair.yaml --points") == 2);
}

TEST(json_pair1_table1_and_mean)
{
    REQUIRE(run("examples/helical_pair1.yaml --json") == 0);
    cJSON *o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_ABS(num(o, "contact_ratio_transverse"), 1.6268, 0.5e-4);
    CHECK_ABS(num(o, "contact_ratio_face"), 1.2442, 0.5e-4);
    CHECK_ABS(num(o, "contact_ratio_total"), 1.6268 + 1.2442, 1e-4);
    CHECK_REL(num(o, "stiffness_mean"), 3.13e8, 0.10);
    CHECK(num(o, "stiffness_max") >= num(o, "stiffness_mean"));
    CHECK(num(o, "stiffness_min") <= num(o, "stiffness_mean"));
    CHECK_REL(num(o, "mesh_period_rad"), 2 * M_PI / 52, 1e-12);
    const cJSON *a = cJSON_GetObjectItem(o, "angle_rad"), *k = cJSON_GetObjectItem(o, "stiffness"),
                *p = cJSON_GetObjectItem(o, "pairs_in_contact"),
                *ls = cJSON_GetObjectItem(o, "load_share");
    CHECK(cJSON_GetArraySize(a) == 360 && cJSON_GetArraySize(k) == 360 &&
          cJSON_GetArraySize(p) == 360);
    CHECK(cJSON_GetArraySize(ls) == 360);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(o, "harmonics")) == 5);
    cJSON_Delete(o);
}

TEST(helix_angle_override)
{
    REQUIRE(run("examples/helical_pair2.yaml --json --helix-angle '15 deg'") == 0);
    cJSON *o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_ABS(num(o, "contact_ratio_transverse"), 1.6205, 0.5e-4);
    CHECK_ABS(num(o, "contact_ratio_face"), 0.6591, 0.5e-4);
    cJSON_Delete(o);
    REQUIRE(run("examples/helical_pair1.yaml --json --helix-angle 0") == 0);
    o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_ABS(num(o, "contact_ratio_transverse"), 1.7865, 0.5e-4);
    CHECK(num(o, "slices") == 1);
    cJSON_Delete(o);
    CHECK(run("examples/helical_pair1.yaml --helix-angle 15") == 2); /* 15 rad */
    CHECK(strstr(err_text, "--helix-angle") && strstr(err_text, "did you mean '15 deg'"));
    CHECK(run("examples/helical_pair1.yaml --helix-angle 'ten deg'") == 2);
    CHECK(strstr(err_text, "--helix-angle") != NULL);
    CHECK(run("examples/helical_pair1.yaml --helix-angle '5 mm'") == 2);
}

TEST(methods_points_cycles_slices)
{
    REQUIRE(run("examples/rig2018_pair.yaml --json --method iso6336 --points 50 --cycles 3") == 0);
    cJSON *o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK(num(o, "stiffness_max") == num(o, "stiffness_min"));
    CHECK_REL(num(o, "stiffness_mean"), num(o, "iso6336_mesh_stiffness_alpha"), 1e-12);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(o, "stiffness")) == 150);
    cJSON_Delete(o);
    REQUIRE(run("examples/rig2018_pair.yaml --json --method single-pair-law") == 0);
    o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK(strcmp(cJSON_GetObjectItem(o, "method")->valuestring, "single-pair-law") == 0);
    CHECK(num(o, "stiffness_max") > 1.5 * num(o, "stiffness_min"));
    cJSON_Delete(o);
    REQUIRE(run("examples/rig2018_pair.yaml --json --method square --points 1000") == 0);
    o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_REL(num(o, "stiffness_max"), 2 * num(o, "stiffness_min"), 1e-12);
    cJSON_Delete(o);
    REQUIRE(run("examples/helical_pair1.yaml --json --slices 7") == 0);
    o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK(num(o, "slices") == 7);
    cJSON_Delete(o);
    /* [MMT2018] rig, default energy method: Fig. 8 values within 15% */
    REQUIRE(run("examples/rig2018_pair.yaml --json") == 0);
    o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_REL(num(o, "stiffness_max"), 3.9e8, 0.15);
    CHECK_REL(num(o, "stiffness_mean"), 3.3e8, 0.15);
    CHECK_REL(num(o, "stiffness_min"), 1.9e8, 0.15);
    cJSON_Delete(o);
    /* text output: summary then the CSV */
    REQUIRE(run("examples/helical_pair2.yaml --points 20") == 0);
    CHECK(strstr(out_text, "contact ratio    transverse 1.5580  face 0.8709  total 2.4289") !=
          NULL);
    CHECK(strstr(out_text, "angle_rad,stiffness_N_per_m,pairs_in_contact,load_share_0") != NULL);
}

TEST(bad_options)
{
    CHECK(run("examples/rig2018_pair.yaml --method fem") == 2);
    CHECK(strstr(err_text, "unknown method 'fem'") != NULL);
    CHECK(run("examples/rig2018_pair.yaml --points abc") == 2);
    CHECK(strstr(err_text, "--points") != NULL);
    CHECK(run("examples/rig2018_pair.yaml --points 3") == 2);
    CHECK(run("examples/rig2018_pair.yaml --cycles 0") == 2);
    CHECK(strstr(err_text, "--cycles") != NULL);
    CHECK(run("examples/rig2018_pair.yaml --slices -4") == 2);
    CHECK(strstr(err_text, "--slices") != NULL);
    CHECK(run("examples/helical_pair1.yaml --mesh nope") == 2);
    CHECK(strstr(err_text, "no mesh named 'nope'") && strstr(err_text, "'pair1'"));
    CHECK(run("no/such/file.yaml") == 2);
    CHECK(strstr(err_text, "no/such/file.yaml") != NULL);
}

static const char GOOD[] = "units: SI\n"
                           "shafts: [{name: a}]\n"
                           "materials:\n"
                           "  steel: {density: 7800, E: 2.06e11, poisson: 0.3}\n"
                           "meshes:\n"
                           "  - name: plain\n"
                           "    stiffness: 2e8\n"
                           "  - name: geo\n"
                           "    driver: n1\n"
                           "    driven: n2\n"
                           "    damping: 100\n"
                           "    geometry:\n"
                           "      normal_module: 3 mm\n"
                           "      face_width: 25 mm\n"
                           "      driver: {teeth: 25, material: steel}\n"
                           "      driven: {teeth: 40, material: steel}\n";

static char *with(const char *from, const char *to)
{
    static char buf[4096];
    const char *p = strstr(GOOD, from);
    if (!p) return NULL;
    snprintf(buf, sizeof buf, "%.*s%s%s", (int)(p - GOOD), GOOD, to, p + strlen(from));
    return buf;
}

TEST(model_file_and_mesh_pick)
{
    REQUIRE(run("--help") == 0); /* makes tmpdir */
    const char *f = write_file("good.yaml", GOOD);
    char args[600];
    snprintf(args, sizeof args, "'%s' --json --points 40", f);
    REQUIRE(run(args) == 0); /* first mesh with a geometry */
    cJSON *o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK(strcmp(cJSON_GetObjectItem(o, "mesh")->valuestring, "geo") == 0);
    cJSON_Delete(o);
    snprintf(args, sizeof args, "'%s' --mesh plain", f);
    CHECK(run(args) == 2);
    CHECK(strstr(err_text, "meshes[0].geometry") && strstr(err_text, "no geometry"));
    f = write_file("nogeo.yaml", "meshes:\n  - {name: a, stiffness: 1e8}\n");
    snprintf(args, sizeof args, "'%s'", f);
    CHECK(run(args) == 2);
    CHECK(strstr(err_text, "no mesh has a geometry") != NULL);
    f = write_file("nomesh.yaml", "shafts: []\n");
    snprintf(args, sizeof args, "'%s'", f);
    CHECK(run(args) == 2);
    CHECK(strstr(err_text, "no list of meshes") != NULL);
}

TEST(non_physical_geometry_writes_nothing)
{
    REQUIRE(run("--help") == 0);
    static const struct {
        const char *from, *to, *expect;
    } cases[] = {
        {"teeth: 25,", "teeth: 12,", "meshes[1].geometry.driver.profile_shift"},
        {"teeth: 25, material: steel}\n      driven: {teeth: 40,",
         "teeth: 25, addendum_coef: 0.45, material: steel}\n      driven: {teeth: 40, "
         "addendum_coef: 0.45,",
         "contact ratio"},
        {"teeth: 40,", "teeth: 40, tip_radius: 64 mm,", "negative tip clearance"},
        {"teeth: 25,", "teeth: 25, tip_radius: 50 mm,", "driver.tip_radius"},
        {"driver: {teeth: 25, material: steel}\n      driven: {teeth: 40, material: steel}",
         "driver: {teeth: 20, root_radius: 26.1 mm, material: steel}\n      driven: {teeth: 60, "
         "tip_radius: 93.6 mm, material: steel}",
         "tip interference"},
        {"face_width: 25 mm", "face_width: 25 mm\n      normal_pressure_angle: 20",
         "did you mean '20 deg'"},
        {"face_width: 25 mm", "face_width: 25 mm\n      helix: 10 deg", "unknown key 'helix'"},
        {"face_width: 25 mm", "face_width: -25 mm", "face_width"},
        {"geometry:\n", "stiffness: {from: geometry, method: fem}\n    geometry:\n",
         "unknown value 'fem'"},
        {"geometry:\n", "stiffness: {from: geometry, points: 2}\n    geometry:\n", "points"},
        {"material: steel}\n", "material: unobtainium}\n", "unknown material 'unobtainium'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *text = with(cases[i].from, cases[i].to);
        REQUIRE(text);
        const char *f = write_file("bad.yaml", text);
        char out[400], args[900];
        snprintf(out, sizeof out, "%s/out_bad", tmpdir);
        snprintf(args, sizeof args, "'%s' --out '%s'", f, out);
        int rc = run(args);
        CHECK(rc == 2);
        if (!strstr(err_text, cases[i].expect)) {
            fprintf(stderr, "  case %zu: '%s' not in: %s\n", i, cases[i].expect, err_text);
            CHECK(0);
        }
        CHECK(strstr(err_text, "bad.yaml:") != NULL); /* located in the file */
        CHECK(!exists(out));
    }
}

TEST(out_dir)
{
    REQUIRE(run("--help") == 0);
    char args[600], p[500];
    snprintf(args, sizeof args, "examples/rig2018_pair.yaml --points 90 --cycles 2 --out '%s/res'",
             tmpdir);
    REQUIRE(run(args) == 0);
    CHECK(strstr(out_text, "stiffness (N/m)") != NULL);
    CHECK(strstr(out_text, "angle_rad,") == NULL); /* CSV went to the file */
    snprintf(p, sizeof p, "%s/res/mesh_stiffness.csv", tmpdir);
    slurp(p, out_text, sizeof out_text);
    int lines = 0;
    for (char *c = out_text; *c; c++)
        lines += *c == '\n';
    CHECK(lines == 181);
    static const char HEAD[] =
        "angle_rad,stiffness_N_per_m,pairs_in_contact,load_share_0,load_share_1\n";
    CHECK(strncmp(out_text, HEAD, strlen(HEAD)) == 0);
    snprintf(p, sizeof p, "%s/res/summary.json", tmpdir);
    slurp(p, out_text, sizeof out_text);
    cJSON *o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_REL(num(o, "stiffness_mean"), 3.3e8, 0.15);
    CHECK(cJSON_GetObjectItem(o, "stiffness") == NULL);
    cJSON_Delete(o);
    /* --out onto a file: error, exit 2 */
    snprintf(args, sizeof args, "examples/rig2018_pair.yaml --out '%s/res/summary.json'", tmpdir);
    CHECK(run(args) == 2);
    CHECK(strstr(err_text, "not a folder") != NULL);
}

static cJSON *item(const cJSON *o, const char *key, int i)
{
    return cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, key), i);
}

/* --load: the unmodified pair's loaded stiffness is the TVMS (1e-9) and its loaded TE
 * F / k; --load-range: TE linear in the load for unmodified teeth, so the peak-to-peak
 * grows with the load exactly (1e-9); --misalignment raises the face load factor. */
TEST(contact_analysis_load_and_harris_map)
{
    REQUIRE(run("examples/rig2018_pair.yaml --points 16 --json") == 0);
    cJSON *t = cJSON_Parse(out_text);
    REQUIRE(t);
    REQUIRE(run("examples/rig2018_pair.yaml --points 16 --slices 10 --load 100Nm --json") == 0);
    cJSON *o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_REL(num(o, "stiffness_mean"), num(t, "stiffness_mean"), 1e-9);
    double F = num(o, "normal_force_N");
    CHECK_REL(F, 100 / 0.048 / cos(20 * M_PI / 180), 1e-12);
    for (int i = 0; i < 16; i++) {
        double k = item(t, "stiffness", i)->valuedouble;
        CHECK_REL(item(o, "stiffness", i)->valuedouble, k, 1e-9);
        CHECK_REL(item(o, "ste", i)->valuedouble, F / k, 1e-9);
    }
    CHECK_REL(num(o, "face_load_factor"), 1, 1e-9);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItem(o, "line_load_mean")) == 10);
    cJSON_Delete(o);
    cJSON_Delete(t);
    REQUIRE(run("examples/rig2018_pair.yaml --points 16 --slices 10 --load-range "
                "'50 N m:150 N m:3' --json") == 0);
    o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_REL(item(o, "torque_N_m", 1)->valuedouble, 100, 1e-12);
    CHECK_REL(item(o, "ste_peak_to_peak", 2)->valuedouble,
              3 * item(o, "ste_peak_to_peak", 0)->valuedouble, 1e-9);
    cJSON_Delete(o);
    REQUIRE(run("examples/rig2018_pair.yaml --points 16 --slices 10 --load 100Nm "
                "--misalignment 5um") == 0);
    CHECK(strstr(out_text, "misalignment     5 um") != NULL);
    CHECK(strstr(out_text, "face load factor K_Hbeta 1.") != NULL);
    CHECK(strstr(out_text, "K_Hbeta 1.0000") == NULL);
    CHECK(strstr(out_text, "angle_rad,ste_m,ste_unloaded_m,stiffness_N_per_m") != NULL);
    /* the file's own load: a stand-alone file with tip relief */
    const char *path = write_file(
        "relief.yaml",
        "materials: {steel: {E: 2.0e11, poisson: 0.3}}\n"
        "meshes:\n"
        "  - name: pair\n"
        "    geometry:\n"
        "      normal_module: 2 mm\n"
        "      face_width: 20 mm\n"
        "      driver: {teeth: 48, material: steel, bore_radius: 12.7 mm,\n"
        "               modifications: {tip_relief: {amount: 10 um, start_roll_angle: 21.5 deg}}}\n"
        "      driven: {teeth: 32, material: steel, bore_radius: 12.7 mm}\n"
        "    stiffness: {from: contact_analysis, load: 100 N m, points: 32, slices: 10}\n");
    char args[700];
    snprintf(args, sizeof args, "'%s' --json", path);
    REQUIRE(run(args) == 0);
    o = cJSON_Parse(out_text);
    REQUIRE(o);
    CHECK_REL(num(o, "torque_N_m"), 100, 1e-15);
    CHECK(num(o, "ste_peak_to_peak") > 0);
    /* single contact near the highest point is on the relief (roll 16.9 mm < 17.4 mm) */
    CHECK(item(o, "ste_unloaded", 31)->valuedouble > 0);
    cJSON_Delete(o);
}

/* The example with tip relief sized for 100 N m: the Harris map's smallest
 * peak-to-peak TE lies within +-15 % of the design load (110 N m on this grid). */
TEST(harris_map_of_the_relief_example)
{
    REQUIRE(run("examples/rig2018_pair_relief.yaml --load-range 20Nm:200Nm:19 --json") == 0);
    cJSON *o = cJSON_Parse(out_text);
    REQUIRE(o);
    int best = 0;
    for (int l = 1; l < 19; l++)
        if (item(o, "ste_peak_to_peak", l)->valuedouble <
            item(o, "ste_peak_to_peak", best)->valuedouble)
            best = l;
    double T = item(o, "torque_N_m", best)->valuedouble;
    CHECK(T >= 85 && T <= 115);
    CHECK(item(o, "ste_peak_to_peak", best)->valuedouble < 0.8e-6);
    cJSON_Delete(o);
    REQUIRE(run("examples/rig2018_pair_relief.yaml --load-range 20Nm:200Nm:19") == 0);
    CHECK(strstr(out_text, "smallest p-p TE  0.58778 um at 110 N m") != NULL);
}

TEST(contact_analysis_out_and_errors)
{
    REQUIRE(run("--help") == 0);
    CHECK(strstr(out_text, "--load-range") != NULL);
    char args[700], p[500];
    snprintf(args, sizeof args,
             "examples/helical_pair1.yaml --points 16 --slices 10 --load 50Nm --out '%s/ca'",
             tmpdir);
    REQUIRE(run(args) == 0);
    CHECK(strstr(out_text, "angle_rad,") == NULL);
    snprintf(p, sizeof p, "%s/ca/contact_analysis.csv", tmpdir);
    slurp(p, out_text, sizeof out_text);
    CHECK(strncmp(out_text, "angle_rad,ste_m,ste_unloaded_m,stiffness_N_per_m,pairs_in_contact,",
                  66) == 0);
    snprintf(p, sizeof p, "%s/ca/line_load.csv", tmpdir);
    CHECK(exists(p));
    snprintf(p, sizeof p, "%s/ca/summary.json", tmpdir);
    CHECK(exists(p));
    snprintf(args, sizeof args,
             "examples/helical_pair1.yaml --points 16 --slices 10 --load-range 10:100:4 --out "
             "'%s/map'",
             tmpdir);
    REQUIRE(run(args) == 0);
    snprintf(p, sizeof p, "%s/map/harris_map.csv", tmpdir);
    slurp(p, out_text, sizeof out_text);
    int lines = 0;
    for (char *c = out_text; *c; c++)
        lines += *c == '\n';
    CHECK(lines == 5);
    /* errors: exit 2, nothing written */
    static const char *const BAD[][2] = {
        {"--load -5Nm", "must be positive"},
        {"--load 5kg", "--load"},
        {"--load 5Nm --load-range 1:2:3", "not both"},
        {"--load-range 5:1:3", "FROM < TO"},
        {"--load-range 1:5", "FROM:TO:COUNT"},
        {"--load-range 1:5:1", "from 2 to 1000"},
        {"--misalignment 3deg", "--misalignment"},
        {"--load 5Nm --method iso6336", "stiffness law"},
        {"--load 5Nm --plot x.svg", "--plot"},
        {"--misalignment 5um", "goes with --load"},
    };
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++) {
        snprintf(args, sizeof args, "examples/rig2018_pair.yaml %s --out '%s/bad'", BAD[i][0],
                 tmpdir);
        CHECK(run(args) == 2);
        CHECK(strstr(err_text, BAD[i][1]) != NULL);
        if (!strstr(err_text, BAD[i][1])) fprintf(stderr, "  %s: %s", BAD[i][0], err_text);
        snprintf(p, sizeof p, "%s/bad", tmpdir);
        CHECK(!exists(p));
    }
}

static void cleanup(void)
{
    if (tmpdir[0]) {
        char cmd[400];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
        if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    }
}

static gd_test_case CASES[] = {T(help_and_usage),
                               T(json_pair1_table1_and_mean),
                               T(helix_angle_override),
                               T(methods_points_cycles_slices),
                               T(bad_options),
                               T(model_file_and_mesh_pick),
                               T(non_physical_geometry_writes_nothing),
                               T(out_dir),
                               T(contact_analysis_load_and_harris_map),
                               T(harris_map_of_the_relief_example),
                               T(contact_analysis_out_and_errors)};

int main(int argc, char **argv)
{
    int rc = gd_test_run(CASES, (int)(sizeof CASES / sizeof CASES[0]), argc, argv);
    cleanup();
    return rc;
}
