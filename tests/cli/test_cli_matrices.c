/* geardyn matrices: the Matrix Market files (header, comment, size line, as many entries
 * as it says, values equal to the library's gd_system_matrices bit for bit), dofs.csv,
 * the JSON variant, --set and --coupling, and every error path (exit 2, nothing
 * written). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "geardyn/system.h"
#include "harness.h"

#define CHEN "examples/chen1998_gear_pair.yaml"
#define RIG "examples/rig2018.yaml"

/* The matrix of a model at a speed from the library, for comparison. */
static int library_matrices(const char *path, double speed, gd_csc m[4])
{
    gd_model *model = NULL;
    gd_system *sys = NULL;
    gd_error e;
    int ok = gd_model_load(path, &model, &e) == GD_OK &&
             gd_system_build(model, &sys, &e) == GD_OK &&
             gd_system_matrices(sys, speed, &m[0], &m[1], &m[2], &m[3], &e) == GD_OK;
    gd_system_free(sys);
    gd_model_free(model);
    return ok;
}

/* Parses a Matrix Market file and checks it against a: header, size line, nnz entry
 * lines in column order with the same 1-based indices and values. */
static int mtx_matches(const char *text, const gd_csc *a, const char *model, char *comment,
                       size_t csize)
{
    static const char HEAD[] = "%%MatrixMarket matrix coordinate real general\n";
    if (!text || strncmp(text, HEAD, strlen(HEAD))) return 0;
    const char *p = text + strlen(HEAD), *eol = strchr(p, '\n');
    if (!eol || p[0] != '%' || !strstr(p, model)) return 0;
    snprintf(comment, csize, "%.*s", (int)(eol - p), p);
    int rows, cols, nnz, used;
    if (sscanf(eol + 1, "%d %d %d%n", &rows, &cols, &nnz, &used) != 3) return 0;
    if (rows != a->n || cols != a->n || nnz != a->colptr[a->n]) return 0;
    if (count_lines(text) != 3 + nnz) return 0;
    p = eol + 1 + used;
    for (int j = 0; j < a->n; j++)
        for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++) {
            int i1, j1;
            double v;
            if (sscanf(p, "%d %d %lf%n", &i1, &j1, &v, &used) != 3) return 0;
            if (i1 != a->rowind[k] + 1 || j1 != j + 1 || v != a->values[k]) return 0;
            p += used;
        }
    return 1;
}

static char *read_in(const char *dir, const char *name)
{
    char path[300];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return read_file(path);
}

TEST(help)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "matrices --help");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "usage: geardyn matrices MODEL.yaml --out DIR"));
    CHECK(contains(r.out, "--format F") && contains(r.out, "--speed VALUE"));
    run_free(&r);
    run(&s, &r, "--help");
    CHECK(contains(r.out, "  matrices "));
    run_free(&r);
    scratch_close(&s);
}

TEST(mtx_files_of_the_rig_at_speed)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char dir[256];
    snprintf(dir, sizeof dir, "%s/res", s.dir);
    run_result r;
    run(&s, &r, "matrices " RIG " --speed 3000rpm --out '%s'", dir);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "170 DOFs"));
    run_free(&r);
    CHECK(count_entries(dir) == 5); /* no staging folder left */
    gd_csc m[4];
    REQUIRE(library_matrices(RIG, 3000 * M_PI / 30, m));
    static const char *const FILES[4] = {"M.mtx", "K.mtx", "C.mtx", "G.mtx"};
    static const char *const WHAT[4] = {"M, mass", "K + K_b(W)", "C + C_b(W)", "G, gyroscopic"};
    for (int k = 0; k < 4; k++) {
        char *text = read_in(dir, FILES[k]), comment[600] = "";
        int ok = mtx_matches(text, &m[k], "model examples/rig2018.yaml", comment, sizeof comment);
        if (!ok) fprintf(stderr, "  %s does not match the library\n", FILES[k]);
        CHECK(ok);
        CHECK(strstr(comment, WHAT[k]) && strstr(comment, "W = 314.15926535897933 rad/s") &&
              strstr(comment, "SI units"));
        free(text);
        gd_csc_free(&m[k]);
    }
    char *dofs = read_in(dir, "dofs.csv");
    REQUIRE(dofs);
    CHECK(count_lines(dofs) == 1 + 170);
    CHECK(strncmp(dofs, "index,node,dof,shaft,massless\n1,brg_d1,x,driving,0\n", 51) == 0);
    CHECK(contains(dofs, "\n170,brg_n2,rz,driven,0\n"));
    free(dofs);
    scratch_close(&s);
}

TEST(json_variant)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char dir[256];
    snprintf(dir, sizeof dir, "%s/res", s.dir);
    run_result r;
    run(&s, &r, "matrices " CHEN " --format json --speed 100 --out '%s'", dir);
    CHECK(r.code == 0);
    run_free(&r);
    CHECK(count_entries(dir) == 2);
    char *text = read_in(dir, "matrices.json"), *dofs = read_in(dir, "dofs.csv");
    REQUIRE(text && dofs);
    CHECK(count_lines(dofs) == 1 + 6);
    cJSON *o = cJSON_Parse(text);
    REQUIRE(o);
    CHECK(jnum(o, "speed_rad_s") == 100);
    CHECK(strcmp(jstr(o, "model"), CHEN) == 0);
    const cJSON *d = cJSON_GetObjectItem(o, "dofs");
    CHECK(cJSON_GetArraySize(d) == 6);
    CHECK(strcmp(jstr(cJSON_GetArrayItem(d, 2), "dof"), "rz") == 0);
    CHECK(strcmp(jstr(cJSON_GetArrayItem(d, 5), "node"), "gear_b") == 0);
    gd_csc m[4];
    REQUIRE(library_matrices(CHEN, 100, m));
    static const char *const NAMES[4] = {"M", "K", "C", "G"};
    for (int k = 0; k < 4; k++) {
        const cJSON *a = cJSON_GetObjectItem(o, NAMES[k]);
        const cJSON *rows = cJSON_GetObjectItem(a, "rows"), *cols = cJSON_GetObjectItem(a, "cols"),
                    *vals = cJSON_GetObjectItem(a, "values");
        int nnz = m[k].colptr[m[k].n];
        CHECK(jnum(a, "nnz") == nnz && jnum(a, "size") == 6);
        CHECK(cJSON_GetArraySize(rows) == nnz && cJSON_GetArraySize(cols) == nnz &&
              cJSON_GetArraySize(vals) == nnz);
        int at = 0, same = 1;
        for (int j = 0; j < 6; j++)
            for (int p = m[k].colptr[j]; p < m[k].colptr[j + 1]; p++, at++)
                same = same && cJSON_GetArrayItem(rows, at)->valuedouble == m[k].rowind[p] + 1 &&
                       cJSON_GetArrayItem(cols, at)->valuedouble == j + 1 &&
                       cJSON_GetArrayItem(vals, at)->valuedouble == m[k].values[p];
        CHECK(same);
        gd_csc_free(&m[k]);
    }
    cJSON_Delete(o);
    free(text);
    free(dofs);
    scratch_close(&s);
}

TEST(set_and_coupling_change_the_matrices)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char a[256], b[256], c[256];
    snprintf(a, sizeof a, "%s/a", s.dir);
    snprintf(b, sizeof b, "%s/b", s.dir);
    snprintf(c, sizeof c, "%s/c", s.dir);
    run_result r;
    REQUIRE(run(&s, &r, "matrices " CHEN " --out '%s'", a) == 0);
    run_free(&r);
    REQUIRE(run(&s, &r, "matrices " CHEN " --out '%s' --set meshes.mesh.stiffness=0.5e8", b) == 0);
    run_free(&r);
    REQUIRE(run(&s, &r, "matrices " CHEN " --out '%s' --coupling torsional --dofs rz", c) == 0);
    run_free(&r);
    char *ka = read_in(a, "K.mtx"), *kb = read_in(b, "K.mtx"), *ma = read_in(a, "M.mtx"),
         *mb = read_in(b, "M.mtx"), *dc = read_in(c, "dofs.csv");
    REQUIRE(ka && kb && ma && mb && dc);
    CHECK(strcmp(ka, kb) != 0);
    CHECK(strcmp(ma, mb) == 0);
    CHECK(count_lines(dc) == 1 + 2); /* rz of each gear */
    free(ka), free(kb), free(ma), free(mb), free(dc);
    scratch_close(&s);
}

TEST(errors_write_nothing)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char dir[256], file[256];
    snprintf(dir, sizeof dir, "%s/res", s.dir);
    snprintf(file, sizeof file, "%s/file.txt", s.dir);
    write_file(file, "keep me\n");
    static const struct {
        const char *args, *expect;
    } CASES[] = {
        {CHEN, "--out DIR is required"},
        {"--out '%s'", "give exactly one model file"},
        {CHEN " " CHEN " --out '%s'", "give exactly one model file"},
        {CHEN " --out '%s' --format csv", "--format: 'csv' is not mtx or json"},
        {CHEN " --out '%s' --speed fast", "--speed: 'fast' is not a number"},
        {CHEN " --out '%s' --speed -5", "--speed: give a speed of zero or more"},
        {CHEN " --out '%s' --coupling tight", "unknown coupling level 'tight'"},
        {CHEN " --out '%s' --set disks.0.mass=-1", "--set disks.0.mass=-1: disks[0].mass"},
        {CHEN " --out '%s' --set disk.0.mass=1", "no key 'disk' at the top level"},
        {"examples/no_such.yaml --out '%s'", "cannot open file"},
        {CHEN " --out '%s' --bogus", "unknown option '--bogus'"},
    };
    run_result r;
    for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; i++) {
        char args[600];
        snprintf(args, sizeof args, CASES[i].args, dir);
        run(&s, &r, "matrices %s", args);
        int ok = r.code == 2 && contains(r.err, CASES[i].expect) && !file_exists(dir);
        if (!ok) {
            fprintf(stderr, "  case %zu (%s):\n", i, args);
            show(&r);
            CHECK(0);
        }
        run_free(&r);
    }
    /* --out names a file, or a folder whose parent is missing: checked before computing */
    run(&s, &r, "matrices " CHEN " --out '%s'", file);
    CHECK(r.code == 2 && contains(r.err, "exists and is not a folder"));
    run_free(&r);
    char *kept = read_file(file);
    CHECK(kept && !strcmp(kept, "keep me\n"));
    free(kept);
    run(&s, &r, "matrices " CHEN " --out '%s/missing/res'", s.dir);
    CHECK(r.code == 2 && contains(r.err, "cannot create folder"));
    CHECK(contains(r.err, "/missing' is not a writable folder"));
    run_free(&r);
    run(&s, &r, "matrices " CHEN " --out '%s/sub'", file);
    CHECK(r.code == 2 && contains(r.err, "cannot create folder"));
    run_free(&r);
    CHECK(count_entries(s.dir) == 3); /* file.txt and the captured stdout, stderr */
    scratch_close(&s);
}

RUN_TESTS(T(help), T(mtx_files_of_the_rig_at_speed), T(json_variant),
          T(set_and_coupling_change_the_matrices), T(errors_write_nothing))
