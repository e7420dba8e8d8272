/* Model files written by a hostile user (issue 14, "Hostile input"): numbers whose
 * conversion to a count would overflow, models too big to allocate, non-finite and
 * denormal values in every numeric field kind, YAML alias bombs and deep nesting,
 * BOM/CRLF/tab files, duplicate keys, unknown units, a folder as the model. Each must
 * load or fail with a located error, never crash, hang or exhaust memory. The inputs
 * the fuzzer starts from (tests/model_file/hostile/, fuzz/fuzz_model.c) are replayed
 * here too, so each crash it found stays fixed. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "geardyn/builder.h"
#include "geardyn/mesh_stiffness.h"
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "harness.h"
#include "model_error_support.h"

#define STEEL "materials: {steel: {E: 2.1e11, density: 7850, poisson: 0.3}}\n" /* 1 */

/* `teeth: [1e20, 37]` was converted to int unchecked (undefined behaviour; the message
 * said "invalid teeth number -2.14748e+09"). */
TEST(teeth_beyond_int_is_a_located_error)
{
    EXPECT_LOAD_ERROR("shafts:\n"                                                  /* 1 */
                      "  - {name: a, nodes: [{name: ga}]}\n"                       /* 2 */
                      "  - {name: b, nodes: [{name: gb}]}\n"                       /* 3 */
                      "disks: [{node: ga, mass: 1, polar_inertia: 1},\n"           /* 4 */
                      "        {node: gb, mass: 1, polar_inertia: 1}]\n"           /* 5 */
                      "meshes:\n"                                                  /* 6 */
                      "  - {name: m, driver: ga, driven: gb, teeth: [1e20, 37],\n" /* 7 */
                      "     module: 2 mm, stiffness: 1e8}\n",                      /* 8 */
                      7, "meshes[0].teeth", "1e+20", "100000");
    EXPECT_LOAD_ERROR("shafts:\n"                                                  /* 1 */
                      "  - {name: a, nodes: [{name: ga}]}\n"                       /* 2 */
                      "  - {name: b, nodes: [{name: gb}]}\n"                       /* 3 */
                      "meshes:\n"                                                  /* 4 */
                      "  - {name: m, driver: ga, driven: gb, teeth: [17, 3e9]}\n", /* 5 */
                      5, "meshes[0].teeth", "3e+09", "3 to 100000");
}

/* `length: 1e72` with `max_element_length: 1 mm` overflowed the element count. */
TEST(element_count_beyond_int_is_a_located_error)
{
    EXPECT_LOAD_ERROR(STEEL                                              /* 1 */
                      "shafts:\n"                                        /* 2 */
                      "  - name: s\n"                                    /* 3 */
                      "    material: steel\n"                            /* 4 */
                      "    max_element_length: 1 mm\n"                   /* 5 */
                      "    sections:\n"                                  /* 6 */
                      "      - {length: 1e72, outer_diameter: 50 mm}\n", /* 7 */
                      7, "shafts[0].sections[0]", "limit of 10000 per section",
                      "max_element_length");
}

/* 1e-9 m elements on a 1 m section asked for 1e9 elements (memory exhaustion). */
TEST(too_fine_elements_fail_before_allocation)
{
    EXPECT_LOAD_ERROR(STEEL                                           /* 1 */
                      "shafts:\n"                                     /* 2 */
                      "  - name: s\n"                                 /* 3 */
                      "    material: steel\n"                         /* 4 */
                      "    max_element_length: 1e-9\n"                /* 5 */
                      "    sections:\n"                               /* 6 */
                      "      - {length: 1, outer_diameter: 50 mm}\n", /* 7 */
                      7, "shafts[0].sections[0]", "1e+09 elements", "longer max_element_length");
}

/* Shafts of n sections of `elements_per_section` each, and a `limits:` block. */
static char *sections_model(int n, int per_section, const char *limits)
{
    size_t size = 512 + (size_t)n * 48;
    char *y = malloc(size);
    if (!y) return NULL;
    int k = snprintf(y, size,
                     STEEL "%sshafts:\n  - name: s\n    material: steel\n"
                           "    elements_per_section: %d\n    sections:\n",
                     limits, per_section);
    for (int i = 0; i < n; i++)
        k += snprintf(y + k, size - (size_t)k, "      - {length: 0.1, outer_diameter: 0.05}\n");
    return y;
}

/* 10 000 sections x 10 000 elements (1e8 nodes) exhausted memory; the bound names
 * itself and the key that raises it, and holds before anything is allocated. */
TEST(model_size_is_bounded_with_the_limit_named)
{
    char *y = sections_model(10000, 10000, "");
    REQUIRE(y);
    EXPECT_LOAD_ERROR(y, 3, "shafts[0]", "limit of 100000 nodes", "limits: {max_nodes: N}");
    free(y);
    /* raised or lowered from the file: 3 sections x 4 elements = 13 nodes */
    y = sections_model(3, 4, "limits: {max_nodes: 12}\n");
    REQUIRE(y);
    EXPECT_LOAD_ERROR(y, 4, "shafts[0]", "13 nodes (78 DOFs)", "max_nodes");
    free(y);
    y = sections_model(3, 4, "limits: {max_nodes: 13}\n");
    REQUIRE(y);
    gd_model *m = load_ok(gd_ts_, y);
    if (m) CHECK(m->nnodes == 13);
    gd_model_free(m);
    free(y);
    EXPECT_LOAD_ERROR(STEEL "limits: {max_nodes: 0}\n"
                            "shafts: [{name: s, nodes: [{name: a}]}]\n",
                      2, "limits.max_nodes", "out of range", "whole number");
}

/* A stiffness table of points x cycles (each bounded alone) could ask for 1e10 samples
 * (hundreds of GB), and points x slices for 1e11 contact evaluations (hours): both
 * are bounded, located in the file, and in gd_tvms_compute for callers of the API. */
TEST(stiffness_table_work_is_bounded)
{
    static const char *const sets[][2] = {
        {"meshes.0.stiffness.points=1000000", "meshes.0.stiffness.cycles=10000"},
        {"meshes.0.stiffness.points=100000", "meshes.0.stiffness.slices=1000"}};
    static const char *const words[] = {"points x cycles = 1e+10", "points x slices = 1e+08"};
    gd_gear_pair_geometry g;
    gd_tvms_options o;
    gd_error e;
    for (int k = 0; k < 2; k++) {
        gd_load_options lo;
        gd_load_options_init(&lo);
        lo.nset = 2;
        lo.set = sets[k];
        gd_error_clear(&e);
        gd_status st = gd_gear_pair_load(GD_SOURCE_DIR "/examples/helical_pair1.yaml", NULL, &lo,
                                         &g, &o, NULL, 0, &e);
        CHECK(st == GD_EINPUT);
        CHECK(e.line == 24 && strstr(e.message, words[k]) && strstr(e.hint, "lower points"));
        if (st != GD_EINPUT || e.line != 24) show_error(&e, st);
    }
    REQUIRE(gd_gear_pair_load(GD_SOURCE_DIR "/examples/helical_pair1.yaml", NULL, NULL, &g, &o,
                              NULL, 0, &e) == GD_OK);
    o.points = 1000000;
    o.cycles = 10000;
    gd_tvms_result *r = NULL;
    CHECK(gd_tvms_compute(&g, &o, &r, &e) == GD_EINPUT && r == NULL);
    CHECK(strstr(e.message, "1e+07") != NULL);
}

/* Overrides of one field of a model that loads; bad values in every kind of numeric
 * field: a quantity, a whole number, a pair, a list (table), a global. */
static const char BASE[] = STEEL "shafts:\n"
                                 "  - name: a\n"
                                 "    material: steel\n"
                                 "    elements_per_section: 2\n"
                                 "    sections: [{length: 0.3, outer_diameter: 30 mm}]\n"
                                 "    nodes: [{name: ga, at: 0.15}]\n"
                                 "  - {name: b, nodes: [{name: gb}]}\n"
                                 "disks: [{node: ga, mass: 1, polar_inertia: 1e-3},\n"
                                 "        {node: gb, mass: 1, polar_inertia: 1e-3}]\n"
                                 "bearings: [{node: a@0, k: 1e8}, {node: gb, k: 1e8, "
                                 "k_torsion: 1e4}]\n"
                                 "meshes:\n"
                                 "  - name: m\n"
                                 "    driver: ga\n"
                                 "    driven: gb\n"
                                 "    teeth: [20, 40]\n"
                                 "    base_radius: [20 mm, 40 mm]\n"
                                 "    tvms: {angle: [0, 9 deg], stiffness: [1e8, 2e8]}\n"
                                 "speed: 100\n";

TEST(non_finite_and_denormal_values_are_refused_in_every_field_kind)
{
    gd_model *m = load_ok(gd_ts_, BASE);
    REQUIRE(m);
    gd_model_free(m);
    static const char *const fields[] = {"disks.0.mass=%s",
                                         "shafts.a.elements_per_section=%s",
                                         "meshes.m.teeth=[%s, 40]",
                                         "meshes.m.base_radius=[20 mm, %s]",
                                         "meshes.m.tvms.angle=[0, %s]",
                                         "speed=%s",
                                         "shafts.a.sections.0.length=%s m"};
    static const char *const values[] = {"nan",    "NaN",    "inf",    "-inf",    "1e400",
                                         "-1e400", "1e-400", "1e-310", "4.9e-324"};
    for (size_t f = 0; f < sizeof fields / sizeof *fields; f++)
        for (size_t v = 0; v < sizeof values / sizeof *values; v++) {
            char set[128];
            snprintf(set, sizeof set, fields[f], values[v]);
            const char *sets[] = {set};
            gd_load_options opt;
            gd_load_options_init(&opt);
            opt.nset = 1;
            opt.set = sets;
            gd_error e;
            gd_error_clear(&e);
            m = NULL;
            gd_status st = gd_model_load_string_opts(BASE, "base.yaml", &opt, &m, &e);
            /* the last three underflow: refused as too small, not as "not finite" */
            const char *why = v >= 6 ? "too small" : "not a finite number";
            int ok = st == GD_EINPUT && !m && strstr(e.file, "--set") &&
                     (strstr(e.message, why) || strstr(e.message, "whole number"));
            CHECK(ok);
            if (!ok) {
                fprintf(stderr, "    --set %s\n", set);
                show_error(&e, st);
            }
            gd_model_free(m);
        }
}

TEST(unknown_units_name_the_unit)
{
    EXPECT_LOAD_ERROR(STEEL                                                       /* 1 */
                      "shafts:\n"                                                 /* 2 */
                      "  - name: s\n"                                             /* 3 */
                      "    material: steel\n"                                     /* 4 */
                      "    sections: [{length: 3 furlong, outer_diameter: 1}]\n", /* 5 */
                      5, "shafts[0].sections[0].length", "furlong", "1.5 mm");
}

/* Aliases are refused at the first one, so a billion-laughs document is never
 * expanded: it fails at once with the alias located. */
TEST(alias_bomb_fails_at_the_first_alias)
{
    EXPECT_LOAD_ERROR("a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]\n" /* 1 */
                      "a1: &a1 [*a0, *a0, *a0, *a0, *a0, *a0, *a0, *a0, *a0]\n" /* 2 */
                      "a2: &a2 [*a1, *a1, *a1, *a1, *a1, *a1, *a1, *a1, *a1]\n" /* 3 */
                      "shafts: *a2\n",                                          /* 4 */
                      2, NULL, "aliases", "in full");
}

/* 100 000 nested lists or maps: bounded at 64 levels, before libyaml's or our stack
 * could overflow. */
TEST(deep_nesting_is_bounded)
{
    enum { DEPTH = 100000 };
    char *y = malloc(2 * DEPTH + 16);
    REQUIRE(y);
    strcpy(y, "shafts: ");
    memset(y + 8, '[', DEPTH);
    memset(y + 8 + DEPTH, ']', DEPTH);
    y[8 + 2 * DEPTH] = '\0';
    EXPECT_LOAD_ERROR(y, 1, NULL, "deeper than 64", "flatten");
    free(y);
}

/* A file saved on Windows (byte-order mark, CRLF) loads as the same model. */
TEST(bom_and_crlf_files_load)
{
    gd_model *m = load_ok(gd_ts_, BASE);
    REQUIRE(m);
    size_t n = strlen(BASE);
    char *y = malloc(2 * n + 4);
    REQUIRE(y);
    size_t k = 0;
    memcpy(y, "\xef\xbb\xbf", 3);
    k = 3;
    for (size_t i = 0; i < n; i++) {
        if (BASE[i] == '\n') y[k++] = '\r';
        y[k++] = BASE[i];
    }
    y[k] = '\0';
    gd_model *w = load_ok(gd_ts_, y);
    if (w) {
        CHECK(w->nnodes == m->nnodes);
        CHECK(w->nelements == m->nelements);
        CHECK_STR(w->nodes[1].name, m->nodes[1].name);
        CHECK(w->meshes[0].stiffness == m->meshes[0].stiffness);
    }
    gd_model_free(w);
    gd_model_free(m);
    free(y);
}

TEST(tab_indentation_is_located_with_a_hint)
{
    EXPECT_LOAD_ERROR("shafts:\n"      /* 1 */
                      "\t- name: a\n", /* 2 */
                      2, NULL, "syntax", "never tabs");
}

TEST(duplicate_keys_name_both_lines)
{
    EXPECT_LOAD_ERROR("shafts:\n"                 /* 1 */
                      "  - name: a\n"             /* 2 */
                      "    nodes: [{name: n1}]\n" /* 3 */
                      "    name: b\n",            /* 4 */
                      4, "name", "first given on line 2", "remove one");
}

/* A folder given as the model: fopen opens it and libyaml said "input error". */
TEST(folder_as_model_path)
{
    gd_model *m = NULL;
    gd_error e;
    gd_error_clear(&e);
    gd_status st = gd_model_load(GD_SOURCE_DIR "/examples", &m, &e);
    CHECK(st == GD_EIO);
    CHECK(m == NULL);
    CHECK(strstr(e.message, "is a folder") != NULL);
    gd_model_free(m);
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    CHECK(run(&s, &r, "check examples") == 2);
    CHECK(contains(r.err, "is a folder, not a model file"));
    run_free(&r);
    scratch_close(&s);
}

/* --out a file, under a file, or where nothing can be created: exit 2, nothing
 * written. */
TEST(unusable_out_fails_before_writing)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char file[600];
    snprintf(file, sizeof file, "%s/plain", s.dir);
    write_file(file, "x");
    char under[620];
    snprintf(under, sizeof under, "%s/sub", file);
    const char *outs[] = {file, under, "/proc/geardyn_out"};
    const char *cmds[] = {"modal", "matrices", "campbell", "transient"};
    for (size_t c = 0; c < sizeof cmds / sizeof *cmds; c++)
        for (size_t o = 0; o < sizeof outs / sizeof *outs; o++) {
            run_result r;
            int code = run(&s, &r, "%s examples/chen1998_gear_pair.yaml %s --out '%s'", cmds[c],
                           !strcmp(cmds[c], "campbell")    ? "--speeds 0:100:2"
                           : !strcmp(cmds[c], "transient") ? "--duration 1e-4"
                                                           : "",
                           outs[o]);
            /* the scratch folder holds only the file and the captured stdout/stderr */
            int ok = code == 2 && contains(r.err, "--out") && count_entries(s.dir) == 3;
            CHECK(ok);
            if (!ok) {
                fprintf(stderr, "    %s --out %s\n", cmds[c], outs[o]);
                show(&r);
            }
            run_free(&r);
        }
    char *text = read_file(file);
    CHECK(text && !strcmp(text, "x"));
    free(text);
    scratch_close(&s);
}

/* Every input under tests/model_file/hostile (the fuzzer's seeds and the crashes it
 * found) loads or fails with GD_EINPUT located in the file; a model that loads builds. */
TEST(hostile_inputs_replay)
{
    const char *dir = GD_SOURCE_DIR "/tests/model_file/hostile";
    DIR *d = opendir(dir);
    REQUIRE(d);
    struct dirent *de;
    int files = 0;
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.') continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        gd_model *m = NULL;
        gd_error e;
        gd_error_clear(&e);
        gd_status st = gd_model_load(path, &m, &e);
        files++;
        if (st == GD_OK) {
            gd_system *sys = NULL;
            st = gd_system_build(m, &sys, &e);
            gd_system_free(sys);
            gd_model_free(m);
        }
        int ok = st == GD_OK || (st == GD_EINPUT && e.message[0] && e.hint[0]);
        CHECK(ok);
        if (!ok) {
            fprintf(stderr, "    %s\n", de->d_name);
            show_error(&e, st);
        }
    }
    closedir(d);
    CHECK(files >= 6);
}

RUN_TESTS(T(teeth_beyond_int_is_a_located_error), T(element_count_beyond_int_is_a_located_error),
          T(too_fine_elements_fail_before_allocation), T(stiffness_table_work_is_bounded),
          T(model_size_is_bounded_with_the_limit_named),
          T(non_finite_and_denormal_values_are_refused_in_every_field_kind),
          T(unknown_units_name_the_unit), T(alias_bomb_fails_at_the_first_alias),
          T(deep_nesting_is_bounded), T(bom_and_crlf_files_load),
          T(tab_indentation_is_located_with_a_hint), T(duplicate_keys_name_both_lines),
          T(folder_as_model_path), T(unusable_out_fails_before_writing), T(hostile_inputs_replay))
