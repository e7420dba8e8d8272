/* Bad model files: one test per mistake a user can make. Each checks the status, the
 * exact line of the offending text, the field path, and that the message or hint says
 * what to do. The YAML is written one line per string literal; the comments number
 * the lines. Errors found after parsing come from gd_system_build / gd_modal_solve. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/modal.h"
#include "geardyn/model.h"
#include "geardyn/system.h"
#include "harness.h"
#include "model_error_support.h"

/* Common beginnings; the comments give the line numbers they occupy. */
#define STEEL                                                                                      \
    "materials:\n"                                        /* 1 */                                  \
    "  steel: {density: 7850, E: 2.1e11, poisson: 0.3}\n" /* 2 */

#define ONE_NODE                                                                                   \
    "shafts:\n"                 /* 1 */                                                            \
    "  - name: a\n"             /* 2 */                                                            \
    "    nodes: [{name: n1}]\n" /* 3 */

#define TWO_SHAFTS                                                                                 \
    "shafts:\n"                /* 1 */                                                             \
    "  - name: a\n"            /* 2 */                                                             \
    "    nodes: [{name: p}]\n" /* 3 */                                                             \
    "  - name: b\n"            /* 4 */                                                             \
    "    nodes: [{name: g}]\n" /* 5 */

#define MESH_HEAD                                                                                  \
    TWO_SHAFTS "meshes:\n"       /* 6 */                                                           \
               "  - name: m\n"   /* 7 */                                                           \
               "    driver: p\n" /* 8 */                                                           \
               "    driven: g\n" /* 9 */

#define FLEX_HEAD                                                                                  \
    STEEL "shafts:\n"             /* 3 */                                                          \
          "  - name: a\n"         /* 4 */                                                          \
          "    material: steel\n" /* 5 */                                                          \
          "    sections:\n"       /* 6 */

/* ---- the bases the bad cases are edited from are valid ---- */

TEST(valid_bases_load_with_units)
{
    gd_model *m = load_ok(gd_ts_, ONE_NODE "disks:\n"
                                           "  - {node: n1, mass: 1, polar_inertia: 830 kg*mm^2}\n"
                                           "bearings:\n"
                                           "  - {node: n1, k: 5.683 MN/m, k_torsion: 9.483 "
                                           "kN*m/rad}\n"
                                           "speed: 3000 rpm\n");
    REQUIRE(m);
    CHECK_REL(m->disks[0].polar_inertia, 830e-6, 1e-12);
    CHECK_REL(m->disks[0].diametral_inertia, 415e-6, 1e-12); /* polar/2 by default */
    CHECK_REL(m->bearings[0].coeffs.kxx, 5.683e6, 1e-12);
    CHECK_REL(m->bearings[0].coeffs.kyy, 5.683e6, 1e-12);
    CHECK_REL(m->bearings[0].coeffs.ktorsion, 9483.0, 1e-12);
    CHECK_REL(m->speed, 3000 * 2 * M_PI / 60, 1e-12);
    gd_model_free(m);

    m = load_ok(gd_ts_, MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                  "    pressure_angle: 20 deg\n"
                                  "    stiffness: 1e8\n"
                                  "speed: 1 Hz\n");
    REQUIRE(m);
    CHECK_REL(m->meshes[0].pressure_angle, 20 * M_PI / 180, 1e-12);
    CHECK_REL(m->speed, 2 * M_PI, 1e-12);
    CHECK_REL(m->shafts[1].speed_ratio, -0.5, 1e-12); /* external mesh reverses */
    gd_model_free(m);

    m = load_ok(gd_ts_, FLEX_HEAD "      - {length: 0.5, outer_diameter: 25.4 mm}\n");
    REQUIRE(m);
    CHECK_REL(m->shafts[0].sections[0].outer_diameter, 0.0254, 1e-12);
    CHECK(m->nnodes == 2);
    CHECK_STR(m->nodes[0].name, "a@0");
    CHECK_STR(m->nodes[1].name, "a@1");
    gd_model_free(m);
}

/* ---- YAML level ---- */

TEST(yaml_syntax_error)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"         /* 4 */
                               "  - node: n1\n"   /* 5 */
                               "    mass: 1: 2\n" /* 6 */
                               "    polar_inertia: 0.1\n",
                      6, "", "syntax", "indentation");
}

/* libyaml notices the missing ']' only on the next line; the user's mistake is on the
 * line that opened the bracket, so the error should name it (line or message). */
TEST(yaml_unclosed_bracket_names_its_line)
{
    const char *yaml = "shafts:\n"                /* 1 */
                       "  - name: a\n"            /* 2 */
                       "    nodes: [{name: n1}\n" /* 3: no closing ] */
                       "disks: []\n";             /* 4 */
    gd_model *m = NULL;
    gd_error e;
    gd_status st = gd_model_load_string(yaml, "bad.yaml", &m, &e);
    CHECK(st == GD_EINPUT);
    CHECK(strstr(e.message, "syntax") != NULL);
    CHECK(e.line == 3 || strstr(e.message, "line 3") != NULL);
    if (e.line != 3 && !strstr(e.message, "line 3")) show_error(&e, st);
    gd_model_free(m);
}

TEST(yaml_duplicate_key)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"                                    /* 4 */
                               "  - {node: n1, mass: 1, polar_inertia: 1}\n" /* 5 */
                               "shafts: []\n",                               /* 6 */
                      6, "shafts", "duplicate", "remove one");
    /* and the message names the first occurrence */
    gd_model *m = NULL;
    gd_error e;
    gd_model_load_string(ONE_NODE "title: x\ntitle: y\n", "bad.yaml", &m, &e);
    CHECK(e.line == 5);
    CHECK(strstr(e.message, "line 4") != NULL);
    gd_model_free(m);
}

TEST(yaml_alias_rejected)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes: &n [{name: n1}]\n"
                      "  - name: b\n"
                      "    nodes: *n\n",
                      5, NULL, "alias", "full");
}

TEST(yaml_two_documents)
{
    EXPECT_LOAD_ERROR(ONE_NODE "---\n" /* 4 */
                               "title: x\n",
                      4, NULL, "more than one", "one model");
}

TEST(empty_file)
{
    EXPECT_LOAD_ERROR("", 1, NULL, "empty", "model-format");
    EXPECT_LOAD_ERROR("# only a comment\n\n", 1, NULL, "empty", "model-format");
}

/* A file with only the document marker (or a null) is as empty as an empty file. */
TEST(empty_document_marker_is_empty)
{
    gd_model *m = NULL;
    gd_error e;
    gd_status st = gd_model_load_string("---\n", "bad.yaml", &m, &e);
    CHECK(st == GD_EINPUT);
    CHECK(strstr(e.message, "empty") != NULL);
    CHECK(e.hint[0] != '\0');
    if (!strstr(e.message, "empty")) show_error(&e, st);
    gd_model_free(m);
    st = gd_model_load_string("~\n", "bad.yaml", &m, &e);
    CHECK(st == GD_EINPUT);
    CHECK(strstr(e.message, "empty") != NULL);
    gd_model_free(m);
}

TEST(top_level_not_a_map)
{
    EXPECT_LOAD_ERROR("- a\n- b\n", 1, "", "expected a map", NULL);
}

/* ---- unknown keys, at every level, with the nearest key suggested ---- */

TEST(unknown_key_top)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearing:\n" /* 4 */
                               "  - {node: n1, k: 1}\n",
                      4, "bearing", "unknown key 'bearing'", "did you mean 'bearings'?");
}

TEST(unknown_key_top_far_from_any)
{
    /* nothing close: no guess, but the list of keys */
    EXPECT_LOAD_ERROR(ONE_NODE "gearbox_layout: 3\n", 4, "gearbox_layout", "unknown key",
                      "known keys: title");
    gd_model *m = NULL;
    gd_error e;
    gd_model_load_string(ONE_NODE "gearbox_layout: 3\n", "bad.yaml", &m, &e);
    CHECK(strstr(e.hint, "did you mean") == NULL);
    gd_model_free(m);
}

TEST(unknown_key_shaft)
{
    EXPECT_LOAD_ERROR(STEEL "shafts:\n"             /* 3 */
                            "  - name: a\n"         /* 4 */
                            "    materail: steel\n" /* 5 */
                            "    sections:\n"       /* 6 */
                            "      - {length: 0.5, outer_diameter: 0.05}\n",
                      5, "shafts[0].materail", "unknown key", "did you mean 'material'?");
}

TEST(unknown_key_section)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - length: 0.5\n"          /* 7 */
                                "        outer_diamter: 0.05\n", /* 8 */
                      8, "shafts[0].sections[0].outer_diamter", "unknown key",
                      "did you mean 'outer_diameter'?");
}

TEST(unknown_key_node)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes:\n"
                      "      - {name: n1, att: 0}\n", /* 4 */
                      4, "shafts[0].nodes[0].att", "unknown key", "did you mean 'at'?");
}

TEST(unknown_key_disk)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"                  /* 4 */
                               "  - node: n1\n"            /* 5 */
                               "    mass: 1\n"             /* 6 */
                               "    polar_inertai: 0.1\n", /* 7 */
                      7, "disks[0].polar_inertai", "unknown key", "did you mean 'polar_inertia'?");
}

TEST(unknown_key_disk_geometry)
{
    EXPECT_LOAD_ERROR(STEEL "shafts:\n"                   /* 3 */
                            "  - name: a\n"               /* 4 */
                            "    nodes: [{name: n1}]\n"   /* 5 */
                            "disks:\n"                    /* 6 */
                            "  - node: n1\n"              /* 7 */
                            "    geometry:\n"             /* 8 */
                            "      outer_diameter: 0.1\n" /* 9 */
                            "      widht: 0.02\n"         /* 10 */
                            "      material: steel\n",
                      10, "disks[0].geometry.widht", "unknown key", "did you mean 'width'?");
}

TEST(unknown_key_bearing)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"    /* 4 */
                               "  - node: n1\n" /* 5 */
                               "    kx: 1e6\n", /* 6 */
                      6, "bearings[0].kx", "unknown key", "did you mean 'k'?");
}

TEST(unknown_key_bearing_table_row)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"                      /* 4 */
                               "  - node: n1\n"                   /* 5 */
                               "    table:\n"                     /* 6 */
                               "      - {speed: 0, kxx: 1e6}\n"   /* 7 */
                               "      - {sped: 100, kxx: 2e6}\n", /* 8 */
                      8, "bearings[0].table[1].sped", "unknown key", "did you mean 'speed'?");
}

TEST(unknown_key_spring)
{
    EXPECT_LOAD_ERROR(ONE_NODE "springs:\n"           /* 4 */
                               "  - node: n1\n"       /* 5 */
                               "    dof: rz\n"        /* 6 */
                               "    stifness: 100\n", /* 7 */
                      7, "springs[0].stifness", "unknown key", "did you mean 'stiffness'?");
}

TEST(unknown_key_mesh)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n" /* 10 */
                                "    stiffness: 1e8\n"           /* 11 */
                                "    pressure_angel: 20 deg\n",  /* 12 */
                      12, "meshes[0].pressure_angel", "unknown key",
                      "did you mean 'pressure_angle'?");
}

TEST(unknown_key_material)
{
    EXPECT_LOAD_ERROR("materials:\n"
                      "  steel: {densty: 7850, E: 2.1e11, poisson: 0.3}\n" /* 2 */
                      ONE_NODE,
                      2, "materials.steel.densty", "unknown key", "did you mean 'density'?");
}

/* ---- missing required fields ---- */

TEST(missing_shafts)
{
    EXPECT_LOAD_ERROR("title: gearbox\n"
                      "disks: []\n",
                      1, "shafts", "'shafts'", NULL);
}

TEST(empty_shafts_list)
{
    EXPECT_LOAD_ERROR("shafts: []\n", 1, "shafts", "no shafts", "at least one shaft");
}

TEST(shaft_without_sections_or_nodes)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n", /* 2 */
                      2, "shafts[0]", "neither sections nor nodes", "nodes:");
}

TEST(missing_section_length)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {outer_diameter: 0.05}\n", /* 7 */
                      7, "shafts[0].sections[0].length", "'length'", NULL);
}

TEST(missing_section_material)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    sections:\n"
                      "      - {length: 0.5, outer_diameter: 0.05}\n", /* 4 */
                      4, "shafts[0].sections[0]", "no material", "material:");
}

TEST(missing_mesh_stiffness)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n", 7, "meshes[0].stiffness",
                      "'stiffness'", NULL);
}

TEST(missing_mesh_name)
{
    EXPECT_LOAD_ERROR(TWO_SHAFTS "meshes:\n"       /* 6 */
                                 "  - driver: p\n" /* 7 */
                                 "    driven: g\n"
                                 "    base_radius: [0.05, 0.1]\n"
                                 "    stiffness: 1e8\n",
                      7, "meshes[0].name", "'name'", NULL);
}

TEST(missing_mesh_driver)
{
    EXPECT_LOAD_ERROR(TWO_SHAFTS "meshes:\n"     /* 6 */
                                 "  - name: m\n" /* 7 */
                                 "    driven: g\n"
                                 "    base_radius: [0.05, 0.1]\n"
                                 "    stiffness: 1e8\n",
                      7, "meshes[0].driver", "'driver'", NULL);
}

TEST(missing_node_name)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes:\n"
                      "      - {at: 0}\n", /* 4 */
                      4, "shafts[0].nodes[0].name", "'name'", NULL);
}

TEST(missing_node_position_on_flexible_shaft)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05}\n" /* 7 */
                                "    nodes:\n"                                  /* 8 */
                                "      - {name: brg}\n",                        /* 9 */
                      9, "shafts[0].nodes[0]", "needs `at`", "at: 0.25 m");
}

TEST(missing_disk_node)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - {mass: 1, polar_inertia: 0.1}\n", /* 5 */
                      5, "disks[0].node", "'node'", NULL);
}

TEST(missing_spring_dof)
{
    EXPECT_LOAD_ERROR(ONE_NODE "springs:\n"
                               "  - {node: n1, stiffness: 100}\n", /* 5 */
                      5, "springs[0].dof", "'dof'", NULL);
}

TEST(missing_material_modulus)
{
    EXPECT_LOAD_ERROR("materials:\n"
                      "  steel: {density: 7850, poisson: 0.3}\n" /* 2 */
                      ONE_NODE,
                      2, "materials.steel.E", "'E'", NULL);
}

TEST(material_needs_poisson_or_g)
{
    EXPECT_LOAD_ERROR("materials:\n"
                      "  steel: {density: 7850, E: 2.1e11}\n" /* 2 */
                      ONE_NODE,
                      2, "materials.steel", "poisson or G", "poisson");
}

TEST(disk_without_mass_or_inertia)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - {name: d, node: n1}\n", /* 5 */
                      5, "disks[0]", "no mass or inertia", "polar_inertia");
}

/* Every error should say what to do: missing keys and wrong kinds of value too. */
TEST(missing_key_and_wrong_kind_errors_have_a_hint)
{
    static const char *const cases[] = {
        FLEX_HEAD "      - {outer_diameter: 0.05}\n",        /* missing length */
        MESH_HEAD "    base_radius: [0.05, 0.1]\n",          /* missing stiffness */
        "title: gearbox\n",                                  /* missing shafts */
        "shafts: 3\n",                                       /* value, not a list */
        ONE_NODE "disks:\n  - node: n1\n    mass: [1, 2]\n", /* list, not a value */
        TWO_SHAFTS "meshes:\n  - m1\n",                      /* value, not a map */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        gd_model *m = NULL;
        gd_error e;
        gd_error_clear(&e);
        gd_status st = gd_model_load_string(cases[i], "bad.yaml", &m, &e);
        CHECK(st == GD_EINPUT);
        if (e.hint[0] == '\0') {
            fprintf(stderr, "  case %zu has no hint:\n", i);
            show_error(&e, st);
            gd_ts_->checks_failed++;
        }
        gd_model_free(m);
    }
}

/* ---- wrong types ---- */

TEST(list_where_value_expected)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: [1, 2]\n" /* 6 */
                               "    polar_inertia: 0.1\n",
                      6, "disks[0].mass", "found a list", NULL);
}

TEST(string_where_number_expected)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: heavy\n" /* 6 */
                               "    polar_inertia: 0.1\n",
                      6, "disks[0].mass", "'heavy' is not a number", "SI (kg)");
}

TEST(value_where_list_expected)
{
    EXPECT_LOAD_ERROR("shafts: 3\n", 1, "shafts", "expected a list", NULL);
    EXPECT_LOAD_ERROR(ONE_NODE "disks: {node: n1, mass: 1}\n", 4, "disks", "expected a list", NULL);
}

TEST(value_where_map_expected)
{
    EXPECT_LOAD_ERROR(TWO_SHAFTS "meshes:\n"
                                 "  - m1\n", /* 7 */
                      7, "meshes[0]", "expected a map", NULL);
}

TEST(whole_number_expected)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05, elements: 2.5}\n", 7,
                      "shafts[0].sections[0].elements", "not a whole number", "whole number");
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05, elements: 0}\n", 7,
                      "shafts[0].sections[0].elements", "out of range", "from 1 to 10000");
}

TEST(pair_expected)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: 0.05\n" /* 10 */
                                "    stiffness: 1e8\n",
                      10, "meshes[0].base_radius", "list of two", "[driver, driven]");
}

TEST(unknown_choice_values)
{
    EXPECT_LOAD_ERROR(ONE_NODE "springs:\n"
                               "  - {node: n1, dof: theta, stiffness: 1}\n", /* 5 */
                      5, "springs[0].dof", "unknown value 'theta'", "x, y, z, rx, ry, rz");
    EXPECT_LOAD_ERROR("dofs: [x, y, theta]\n" ONE_NODE, 1, "dofs[2]", "unknown DOF 'theta'",
                      "x, y, z, rx, ry, rz");
    EXPECT_LOAD_ERROR("rotation: clockwise\n" ONE_NODE, 1, "rotation", "unknown value", "ccw, cw");
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                "    stiffness: 1e8\n"
                                "    hand: rigth\n", /* 12 */
                      12, "meshes[0].hand", "unknown value 'rigth'", "right, left");
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                "    stiffness: 1e8\n"
                                "    coupling: lateral\n", /* 12 */
                      12, "meshes[0].coupling", "unknown value", "lateral-torsional");
}

TEST(no_dofs)
{
    EXPECT_LOAD_ERROR("dofs: []\n" ONE_NODE, 1, "dofs", "no DOFs", "[rz]");
}

/* ---- values out of range ---- */

TEST(negative_mass)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: -2\n" /* 6 */
                               "    polar_inertia: 0.1\n",
                      6, "disks[0].mass", "positive", "greater than zero");
}

TEST(zero_mass)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: 0 kg\n" /* 6 */
                               "    polar_inertia: 0.1\n",
                      6, "disks[0].mass", "positive", "greater than zero");
}

TEST(negative_inertia)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - {node: n1, mass: 1, polar_inertia: -0.1}\n", /* 5 */
                      5, "disks[0].polar_inertia", "negative", "zero or more");
}

TEST(zero_length)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0, outer_diameter: 0.05}\n", 7,
                      "shafts[0].sections[0].length", "positive", "greater than zero");
}

TEST(negative_length)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - outer_diameter: 0.05\n" /* 7 */
                                "        length: -0.5 m\n",      /* 8 */
                      8, "shafts[0].sections[0].length", "positive", "greater than zero");
}

TEST(inner_diameter_not_below_outer)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - length: 0.5\n"            /* 7 */
                                "        outer_diameter: 50 mm\n"  /* 8 */
                                "        inner_diameter: 50 mm\n", /* 9 */
                      9, "shafts[0].sections[0].inner_diameter", "not less than outer", "bore");
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - length: 0.5\n"
                                "        outer_diameter: 50 mm\n"
                                "        inner_diameter: 60 mm\n",
                      9, "shafts[0].sections[0].inner_diameter", "not less than outer", "bore");
}

/* Like the section check, the error should point at inner_diameter itself. */
TEST(disk_geometry_inner_diameter_not_below_outer)
{
    EXPECT_LOAD_ERROR(STEEL "shafts:\n"                   /* 3 */
                            "  - name: a\n"               /* 4 */
                            "    nodes: [{name: n1}]\n"   /* 5 */
                            "disks:\n"                    /* 6 */
                            "  - node: n1\n"              /* 7 */
                            "    geometry:\n"             /* 8 */
                            "      outer_diameter: 0.1\n" /* 9 */
                            "      inner_diameter: 0.2\n" /* 10 */
                            "      width: 0.02\n"
                            "      material: steel\n",
                      10, "disks[0].geometry.inner_diameter", "not less than outer", "bore");
}

TEST(disk_geometry_and_mass)
{
    EXPECT_LOAD_ERROR(STEEL "shafts:\n"
                            "  - name: a\n"
                            "    nodes: [{name: n1}]\n"
                            "disks:\n"
                            "  - node: n1\n" /* 7 */
                            "    mass: 1\n"
                            "    geometry: {outer_diameter: 0.1, width: 0.02, material: steel}\n",
                      7, "disks[0]", "both geometry and mass", "either");
}

TEST(nan_value)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: nan\n" /* 6 */
                               "    polar_inertia: 0.1\n",
                      6, "disks[0].mass", "not a finite number", NULL);
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: .nan\n" /* YAML's spelling */
                               "    polar_inertia: 0.1\n",
                      6, "disks[0].mass", "not a number", NULL);
}

TEST(inf_value)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: 1\n"
                               "    polar_inertia: inf\n", /* 7 */
                      7, "disks[0].polar_inertia", "not a finite number", NULL);
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: 1\n"
                               "    polar_inertia: 1e999\n", /* overflows to inf */
                      7, "disks[0].polar_inertia", "not a finite number", NULL);
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - {node: n1, k: -inf N/m}\n", /* 5 */
                      5, "bearings[0].k", "not a finite number", NULL);
}

TEST(negative_speed)
{
    EXPECT_LOAD_ERROR("speed: -100 rpm\n" ONE_NODE, 1, "speed", "negative", "zero or more");
}

TEST(poisson_out_of_range)
{
    EXPECT_LOAD_ERROR("materials:\n"
                      "  steel: {density: 7850, E: 2.1e11, poisson: 0.7}\n" /* 2 */
                      ONE_NODE,
                      2, "materials.steel.poisson", "not physical", "0.5");
    EXPECT_LOAD_ERROR("materials:\n"
                      "  steel:\n"
                      "    density: 7850\n"
                      "    E: 2.1e11\n"
                      "    poisson: -1\n" /* 5 */
                      ONE_NODE,
                      5, "materials.steel.poisson", "not physical", "-1");
}

TEST(g_and_poisson_both)
{
    EXPECT_LOAD_ERROR("materials:\n"
                      "  steel:\n"
                      "    density: 7850\n"
                      "    E: 2.1e11\n"
                      "    G: 80 GPa\n" /* 5 */
                      "    poisson: 0.3\n" ONE_NODE,
                      5, "materials.steel.G", "both", "either G or poisson");
}

TEST(teeth_not_whole)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    teeth: [20.5, 30]\n" /* 10 */
                                "    module: 2 mm\n"
                                "    stiffness: 1e8\n",
                      10, "meshes[0].teeth", "invalid teeth number 20.5", "whole numbers");
}

/* ---- units ---- */

TEST(bad_unit)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - node: n1\n"
                               "    mass: 1 kilo\n" /* 6 */
                               "    polar_inertia: 1\n",
                      6, "disks[0].mass", "unknown unit 'kilo'", "SI (kg)");
}

TEST(wrong_dimension_length_as_angle)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                "    pressure_angle: 20 mm\n" /* 11 */
                                "    stiffness: 1e8\n",
                      11, "meshes[0].pressure_angle", "'mm'", "20 deg");
}

TEST(wrong_dimension_linear_stiffness_on_rotation)
{
    EXPECT_LOAD_ERROR(ONE_NODE "springs:\n"
                               "  - {node: n1, dof: rz, stiffness: 100 N/m}\n", /* 5 */
                      5, "springs[0].stiffness", "'N/m'", "N*m/rad");
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                "    stiffness: 2e8 N*m/rad\n", /* 11 */
                      11, "meshes[0].stiffness", "'N*m/rad'", "N/m");
}

TEST(pressure_angle_plain_number_is_radians)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                "    pressure_angle: 20\n" /* 11 */
                                "    stiffness: 1e8\n",
                      11, "meshes[0].pressure_angle", "radians", "did you mean '20 deg'?");
}

TEST(helix_angle_plain_number_is_radians)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                "    helix_angle: 15\n" /* 11 */
                                "    stiffness: 1e8\n",
                      11, "meshes[0].helix_angle", "radians", "did you mean '15 deg'?");
}

/* ---- references by name ---- */

TEST(unknown_material)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05, material: steal}\n", 7,
                      "shafts[0].sections[0].material", "unknown material 'steal'", "materials:");
}

/* Like unknown nodes (which list the named ones), an unknown material should point at
 * the materials that exist. */
TEST(unknown_material_suggests_defined_ones)
{
    gd_model *m = NULL;
    gd_error e;
    gd_status st = gd_model_load_string(
        FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05, material: steal}\n", "bad.yaml", &m,
        &e);
    CHECK(st == GD_EINPUT);
    CHECK(strstr(e.hint, "steel") != NULL);
    if (!strstr(e.hint, "steel")) show_error(&e, st);
    gd_model_free(m);
}

TEST(unknown_node)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes: [{name: n1}, {name: n2}]\n"
                      "bearings:\n"
                      "  - {node: n3, k: 1e6}\n", /* 5 */
                      5, "bearings[0].node", "unknown node 'n3'", "named nodes: n1 n2");
}

TEST(unknown_mesh_node_and_shaft)
{
    EXPECT_LOAD_ERROR(TWO_SHAFTS "meshes:\n"
                                 "  - name: m\n"
                                 "    driver: pinion\n" /* 8 */
                                 "    driven: g\n"
                                 "    base_radius: [0.05, 0.1]\n"
                                 "    stiffness: 1e8\n",
                      8, "meshes[0].driver", "unknown node 'pinion'", "SHAFT@INDEX");
    EXPECT_LOAD_ERROR("reference_shaft: c\n" TWO_SHAFTS, 1, "reference_shaft", "unknown shaft 'c'",
                      "one of the shafts");
}

TEST(node_position_outside_shaft)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05}\n"
                                "    nodes:\n"
                                "      - {name: brg, at: 0.6}\n", /* 9 */
                      9, "shafts[0].nodes[0].at", "outside the shaft", "0.5 m");
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05}\n"
                                "    nodes:\n"
                                "      - name: brg\n"
                                "        at: -10 mm\n", /* 10 */
                      10, "shafts[0].nodes[0].at", "outside the shaft", "from 0");
}

TEST(coincident_named_nodes)
{
    EXPECT_LOAD_ERROR(FLEX_HEAD "      - {length: 0.5, outer_diameter: 0.05}\n"
                                "    nodes:\n"
                                "      - {name: n1, at: 0.25}\n"
                                "      - {name: n2, at: 250 mm}\n", /* 10 */
                      10, NULL, "same position", "move one");
}

/* ---- duplicates ---- */

TEST(duplicate_shaft_name)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes: [{name: n1}]\n"
                      "  - name: a\n" /* 4 */
                      "    nodes: [{name: n2}]\n",
                      4, "shafts[1].name", "duplicate shaft name 'a'", "own name");
}

/* The field should be the path of the second name, like every other error's. */
TEST(duplicate_node_name)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes: [{name: n1}]\n"
                      "  - name: b\n"
                      "    nodes:\n"
                      "      - {name: n1}\n", /* 6 */
                      6, "shafts[1].nodes[0].name", "used twice", "own name");
}

TEST(duplicate_mesh_name)
{
    gd_model *m = NULL;
    gd_error e;
    const char *yaml = TWO_SHAFTS "  - name: c\n"            /* 6 */
                                  "    nodes: [{name: h}]\n" /* 7 */
                                  "meshes:\n"                /* 8 */
                                  "  - {name: m, driver: p, driven: g, base_radius: [0.05, "
                                  "0.1], stiffness: 1e8}\n" /* 9 */
                                  "  - name: m\n"           /* 10 */
                                  "    driver: g\n"
                                  "    driven: h\n"
                                  "    base_radius: [0.1, 0.05]\n"
                                  "    stiffness: 1e8\n";
    gd_status st = gd_model_load_string(yaml, "bad.yaml", &m, &e);
    check_error(gd_ts_, __LINE__, st, &e, GD_EINPUT, 10, NULL, "duplicate mesh name 'm'",
                "own name");
    CHECK(strncmp(e.field, "meshes[1]", 9) == 0);
    gd_model_free(m);
}

/* Component names label the modal energy table and are keys of the JSON object
 * energy_by_component, so two bearings (or springs) must not share a name. */
TEST(duplicate_bearing_name)
{
    EXPECT_LOAD_ERROR(ONE_NODE "disks:\n"
                               "  - {node: n1, mass: 1, polar_inertia: 0.1}\n"
                               "bearings:\n"
                               "  - {name: b, node: n1, k: 1e6}\n"
                               "  - {name: b, node: n1, k_torsion: 1e3}\n", /* 8 */
                      8, "bearings[1].name", "duplicate", "own name");
}

/* Generated names "<shaft>@<index>" must stay distinct for distinct shaft names of
 * allowed length (63 characters). */
TEST(long_shaft_names_give_distinct_generated_nodes)
{
    const char *yaml = STEEL "shafts:\n"
                             "  - name: aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa_x\n"
                             "    material: steel\n"
                             "    sections: [{length: 1, outer_diameter: 0.05}]\n"
                             "  - name: aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa_y\n"
                             "    material: steel\n"
                             "    sections: [{length: 1, outer_diameter: 0.05}]\n";
    gd_model *m = load_ok(gd_ts_, yaml);
    REQUIRE(m);
    CHECK(m->nnodes == 4);
    for (int i = 0; i < m->nnodes; i++)
        for (int j = 0; j < i; j++)
            CHECK(strcmp(m->nodes[i].name, m->nodes[j].name) != 0);
    gd_model_free(m);
}

/* ---- meshes ---- */

TEST(mesh_on_one_shaft)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes: [{name: p}, {name: g}]\n"
                      "meshes:\n"
                      "  - name: m\n"
                      "    driver: p\n"
                      "    driven: g\n" /* 7 */
                      "    base_radius: [0.05, 0.1]\n"
                      "    stiffness: 1e8\n",
                      7, "meshes[0].driven", "same shaft 'a'", "two different shafts");
}

TEST(teeth_inconsistent_with_radii)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    teeth: [20, 30]\n" /* 10 */
                                "    base_radius: [0.05, 0.1]\n"
                                "    stiffness: 1e8\n",
                      10, "meshes[0].teeth", "differs from teeth ratio", "same gear ratio");
}

TEST(gear_size_missing_or_twice)
{
    EXPECT_LOAD_ERROR(MESH_HEAD "    teeth: [20, 30]\n"
                                "    stiffness: 1e8\n",
                      7, "meshes[0]", "gear size missing", "exactly one of");
    EXPECT_LOAD_ERROR(MESH_HEAD "    base_radius: [0.05, 0.1]\n"
                                "    pitch_radius: [0.05, 0.1]\n"
                                "    stiffness: 1e8\n",
                      7, "meshes[0]", "more than once", "exactly one of");
    EXPECT_LOAD_ERROR(MESH_HEAD "    module: 2 mm\n" /* 10 */
                                "    stiffness: 1e8\n",
                      10, NULL, "needs the teeth", "teeth: [z1, z2]");
}

/* Four external meshes around a loop a-b-c-d-a; consistent when the radii agree. */
#define LOOP_SHAFTS                                                                                \
    "shafts:\n"                                                                          /* 1 */   \
    "  - name: a\n"                                                                      /* 2 */   \
    "    nodes: [{name: a1}, {name: a2}]\n"                                              /* 3 */   \
    "  - name: b\n"                                                                      /* 4 */   \
    "    nodes: [{name: b1}, {name: b2}]\n"                                              /* 5 */   \
    "  - name: c\n"                                                                      /* 6 */   \
    "    nodes: [{name: c1}, {name: c2}]\n"                                              /* 7 */   \
    "  - name: d\n"                                                                      /* 8 */   \
    "    nodes: [{name: d1}, {name: d2}]\n"                                              /* 9 */   \
    "meshes:\n"                                                                          /* 10 */  \
    "  - {name: m1, driver: a1, driven: b1, base_radius: [0.05, 0.1], stiffness: 1e8}\n" /* 11 */  \
    "  - {name: m2, driver: b2, driven: c1, base_radius: [0.1, 0.05], stiffness: 1e8}\n" /* 12 */

/* The loop error names the mesh that closes it: its field should be that mesh's path. */
TEST(gear_ratio_loop_inconsistent)
{
    /* from a, the search reaches b (m1) and d (m4), then c from b (m2); m3 closes */
    const char *yaml = LOOP_SHAFTS
        "  - {name: m3, driver: c2, driven: d1, base_radius: [0.05, 0.06], stiffness: 1e8}\n"
        "  - {name: m4, driver: d2, driven: a2, base_radius: [0.05, 0.05], stiffness: 1e8}\n";
    gd_model *m = NULL;
    gd_error e;
    gd_status st = gd_model_load_string(yaml, "bad.yaml", &m, &e);
    check_error(gd_ts_, __LINE__, st, &e, GD_EINPUT, 13, "meshes[2]", "inconsistent gear ratios",
                "radii or teeth");
    CHECK(strstr(e.message, "'m3'") != NULL);
    gd_model_free(m);
    /* three external gears in a ring cannot turn at all: any radii are inconsistent */
    st = gd_model_load_string(
        "shafts:\n"
        "  - name: a\n"
        "    nodes: [{name: p}]\n"
        "  - name: b\n"
        "    nodes: [{name: g}, {name: g2}]\n"
        "  - name: c\n"
        "    nodes: [{name: h}, {name: h2}]\n"
        "meshes:\n"
        "  - {name: m1, driver: p, driven: g, base_radius: [0.05, 0.05], stiffness: 1e8}\n"
        "  - {name: m2, driver: g2, driven: h, base_radius: [0.05, 0.05], stiffness: 1e8}\n"
        "  - {name: m3, driver: h2, driven: p, base_radius: [0.05, 0.05], stiffness: 1e8}\n",
        "bad.yaml", &m, &e);
    CHECK(st == GD_EINPUT);
    CHECK(strstr(e.message, "inconsistent gear ratios") != NULL);
    gd_model_free(m);
}

TEST(gear_loop_consistent_is_accepted)
{
    gd_model *m = load_ok(
        gd_ts_, LOOP_SHAFTS
        "  - {name: m3, driver: c2, driven: d1, base_radius: [0.05, 0.05], stiffness: 1e8}\n"
        "  - {name: m4, driver: d2, driven: a2, base_radius: [0.05, 0.05], stiffness: 1e8}\n");
    REQUIRE(m);
    CHECK_REL(m->shafts[0].speed_ratio, 1.0, 1e-12);
    CHECK_REL(m->shafts[1].speed_ratio, -0.5, 1e-12);
    CHECK_REL(m->shafts[2].speed_ratio, 1.0, 1e-12);
    CHECK_REL(m->shafts[3].speed_ratio, -1.0, 1e-12);
    CHECK(m->meshes[1].driver_sense == -1); /* b turns cw */
    gd_model_free(m);
}

TEST(driver_rotation_contradicts_train)
{
    EXPECT_LOAD_ERROR("rotation: ccw\n" /* 1 */
                      "shafts:\n"
                      "  - name: a\n"
                      "    nodes: [{name: p}]\n"
                      "  - name: b\n"
                      "    nodes: [{name: g}]\n"
                      "meshes:\n"
                      "  - name: m\n"
                      "    driver: g\n" /* on shaft b, which turns cw */
                      "    driven: p\n"
                      "    base_radius: [0.1, 0.05]\n"
                      "    stiffness: 1e8\n"
                      "    driver_rotation: ccw\n", /* 13 */
                      13, "meshes[0].driver_rotation", "gear train makes it turn cw", "rotation:");
}

/* speed_ratio errors should point at the speed_ratio key, with its full path. */
TEST(speed_ratio_errors_point_at_the_key)
{
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    nodes: [{name: p}]\n"
                      "  - name: b\n"
                      "    speed_ratio: 2\n" /* 5 */
                      "    nodes: [{name: g}]\n"
                      "meshes:\n"
                      "  - {name: m, driver: p, driven: g, base_radius: [0.05, 0.1], "
                      "stiffness: 1e8}\n",
                      5, "shafts[1].speed_ratio", "meshes give -0.5", "remove speed_ratio");
    EXPECT_LOAD_ERROR("shafts:\n"
                      "  - name: a\n"
                      "    speed_ratio: 2\n" /* 3 */
                      "    nodes: [{name: p}]\n",
                      3, "shafts[0].speed_ratio", "reference shaft 'a'", "reference speed");
}

/* ---- bearings and springs ---- */

TEST(bearing_without_coefficients)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - name: b1\n" /* 5 */
                               "    node: n1\n",
                      5, "bearings[0]", "no stiffness or damping", "kxx");
}

TEST(bearing_to_itself)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - name: b1\n"
                               "    node: n1\n"
                               "    to: n1\n" /* 7 */
                               "    k: 1e6\n",
                      7, "bearings[0].to", "to itself", "omit `to`");
}

TEST(spring_to_itself)
{
    EXPECT_LOAD_ERROR(ONE_NODE "springs:\n"
                               "  - name: s1\n"
                               "    node: n1\n"
                               "    to: n1\n" /* 7 */
                               "    dof: rz\n"
                               "    stiffness: 10\n",
                      7, "springs[0].to", "to itself", "omit `to`");
}

TEST(spring_without_stiffness_or_damping)
{
    EXPECT_LOAD_ERROR(ONE_NODE "springs:\n"
                               "  - {node: n1, dof: x, stiffness: 0}\n", /* 5 */
                      5, "springs[0]", "neither stiffness nor damping", "positive");
}

TEST(bearing_k_and_kxx)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - name: b1\n"
                               "    node: n1\n"
                               "    k: 1e6\n"
                               "    kxx: 2e6\n", /* 8 */
                      8, "bearings[0].kxx", "'kxx' given together with 'k'", "not both");
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - {name: b1, node: n1, cyy: 3, c: 1}\n", /* 5 */
                      5, "bearings[0].cyy", "'cyy' given together with 'c'", "not both");
}

TEST(bearing_speed_table_not_increasing)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - name: b1\n"
                               "    node: n1\n"
                               "    table:\n"
                               "      - {speed: 0, k: 1e6}\n"
                               "      - {speed: 1000 rpm, k: 2e6}\n"
                               "      - {speed: 50, k: 3e6}\n", /* 10 */
                      10, NULL, "must increase", "increasing speed");
    gd_model *m = NULL;
    gd_error e;
    gd_model_load_string(ONE_NODE "bearings:\n"
                                  "  - name: b1\n"
                                  "    node: n1\n"
                                  "    table:\n"
                                  "      - {speed: 0, k: 1e6}\n"
                                  "      - {speed: 0, k: 2e6}\n",
                         "bad.yaml", &m, &e);
    CHECK(e.status == GD_EINPUT && e.line == 9); /* equal speeds do not increase */
    CHECK(strncmp(e.field, "bearings[0].table[1]", 20) == 0);
    gd_model_free(m);
}

TEST(bearing_table_rules)
{
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - name: b1\n"
                               "    node: n1\n"
                               "    table:\n" /* 7 */
                               "      - {speed: 0, k: 1e6}\n",
                      8, "bearings[0].table", "two or more rows", "at least two rows");
    EXPECT_LOAD_ERROR(ONE_NODE "bearings:\n"
                               "  - name: b1\n"
                               "    node: n1\n"
                               "    k: 1e6\n"
                               "    table:\n"
                               "      - {speed: 0, k: 1e6}\n" /* 9 */
                               "      - {speed: 100, k: 2e6}\n",
                      9, "bearings[0].table", "together with a speed table", "table rows");
}

/* ---- shafts ---- */

TEST(elements_per_section_and_max_length_both)
{
    EXPECT_LOAD_ERROR(STEEL "shafts:\n"
                            "  - name: a\n" /* 4 */
                            "    material: steel\n"
                            "    elements_per_section: 4\n"
                            "    max_element_length: 0.1\n"
                            "    sections: [{length: 0.5, outer_diameter: 0.05}]\n",
                      4, "shafts[0]", "both elements_per_section and max_element_length",
                      "one of the two");
}

/* max_element_length is an upper bound on every element, also next to a named node. */
TEST(max_element_length_respected_next_to_named_node)
{
    gd_model *m = load_ok(gd_ts_, STEEL "shafts:\n"
                                        "  - name: a\n"
                                        "    material: steel\n"
                                        "    max_element_length: 0.5\n"
                                        "    sections: [{length: 1, outer_diameter: 0.05}]\n"
                                        "    nodes: [{name: d, at: 0.3}]\n");
    REQUIRE(m);
    double total = 0;
    for (int i = 0; i < m->nelements; i++) {
        CHECK(m->elements[i].length <= 0.5 + 1e-12);
        total += m->elements[i].length;
    }
    CHECK_REL(total, 1.0, 1e-12);
    CHECK(gd_model_find_node(m, "d") >= 0);
    gd_model_free(m);
}

TEST(name_too_long)
{
    EXPECT_LOAD_ERROR(
        "shafts:\n"
        "  - name: aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\n"
        "    nodes: [{name: n1}]\n",
        2, "shafts[0].name", "longer than 63", "shorter name");
}

/* ---- errors found after parsing ---- */

static gd_system *build_ok(gd_test_state *gd_ts_, const gd_model *m)
{
    gd_system *s = NULL;
    gd_error e;
    gd_error_clear(&e);
    gd_status st = gd_system_build(m, &s, &e);
    if (st) {
        show_error(&e, st);
        gd_ts_->checks_failed++;
    }
    return s;
}

TEST(no_active_dof)
{
    gd_model *m = load_ok(gd_ts_, "dofs: [z]\n" ONE_NODE "disks:\n"
                                  "  - {node: n1, polar_inertia: 0.1}\n");
    REQUIRE(m);
    gd_system *s = NULL;
    gd_error e;
    gd_status st = gd_system_build(m, &s, &e);
    check_error(gd_ts_, __LINE__, st, &e, GD_EINPUT, 0, "dofs", "no active degree of freedom",
                "active DOFs");
    CHECK(s == NULL);
    CHECK_STR(e.file, "good.yaml");
    gd_system_free(s);
    gd_model_free(m);
}

#define MASSLESS_DAMPER                                                                            \
    "dofs: [rz]\n"                                      /* 1 */                                    \
    "shafts:\n"                                         /* 2 */                                    \
    "  - name: a\n"                                     /* 3 */                                    \
    "    nodes:\n"                                      /* 4 */                                    \
    "      - {name: n1}\n"                              /* 5 */                                    \
    "      - {name: n2}\n"                              /* 6 */                                    \
    "disks:\n"                                          /* 7 */                                    \
    "  - {node: n1, polar_inertia: 0.1}\n"              /* 8 */                                    \
    "springs:\n"                                        /* 9 */                                    \
    "  - {node: n1, to: n2, dof: rz, stiffness: 100}\n" /* 10 */                                   \
    "  - {node: n2, dof: rz, damping: 5}\n"             /* 11 */

#define MASSLESS_FLOATING                                                                          \
    "dofs: [rz]\n"                                      /* 1 */                                    \
    "shafts:\n"                                         /* 2 */                                    \
    "  - name: a\n"                                     /* 3 */                                    \
    "    nodes:\n"                                      /* 4 */                                    \
    "      - {name: n1}\n"                              /* 5 */                                    \
    "      - {name: n2}\n"                              /* 6 */                                    \
    "      - {name: n3}\n"                              /* 7 */                                    \
    "disks:\n"                                          /* 8 */                                    \
    "  - {node: n1, polar_inertia: 0.1}\n"              /* 9 */                                    \
    "springs:\n"                                        /* 10 */                                   \
    "  - {node: n1, dof: rz, stiffness: 100}\n"         /* 11 */                                   \
    "  - {node: n2, to: n3, dof: rz, stiffness: 100}\n" /* 12 */

#define MASSLESS_DAMPER_ONLY                                                                       \
    "dofs: [rz]\n"                                                                                 \
    "shafts:\n"                                                                                    \
    "  - name: a\n"                                                                                \
    "    nodes: [{name: n1}, {name: n2}]\n"                                                        \
    "disks:\n"                                                                                     \
    "  - {node: n1, polar_inertia: 0.1}\n"                                                         \
    "springs:\n"                                                                                   \
    "  - {node: n1, dof: rz, stiffness: 100}\n"                                                    \
    "  - {node: n2, dof: rz, damping: 5}\n"

/* Runs modal on yaml (which must load and build) and returns the status; err filled. */
static gd_status modal_status(gd_test_state *gd_ts_, const char *yaml, gd_modal_kind kind,
                              gd_error *e, int *nmassless)
{
    gd_model *m = load_ok(gd_ts_, yaml);
    if (!m) return GD_OK;
    gd_system *s = build_ok(gd_ts_, m);
    gd_status st = GD_OK;
    if (s) {
        *nmassless = s->nmassless;
        gd_modal_options o;
        gd_modal_options_init(&o);
        o.kind = kind;
        gd_modal_result *r = NULL;
        gd_error_clear(e);
        st = gd_modal_solve(s, &o, &r, e);
        if (st == GD_OK) CHECK(r != NULL);
        if (st != GD_OK) CHECK(r == NULL);
        gd_modal_free(r);
        gd_system_free(s);
    }
    gd_model_free(m);
    return st;
}

TEST(massless_dof_with_damper)
{
    gd_error e;
    int nml = -1;
    gd_status st = modal_status(gd_ts_, MASSLESS_DAMPER, GD_MODAL_AUTO, &e, &nml);
    CHECK(nml == 1);
    check_error(gd_ts_, __LINE__, st, &e, GD_EINPUT, 0, "n2.rz", "no mass", "damper");
    CHECK_STR(e.file, "good.yaml");
}

TEST(massless_dof_held_by_nothing)
{
    gd_error e;
    int nml = -1;
    gd_status st = modal_status(gd_ts_, MASSLESS_FLOATING, GD_MODAL_AUTO, &e, &nml);
    CHECK(nml == 2);
    check_error(gd_ts_, __LINE__, st, &e, GD_EINPUT, 0, NULL, "not held by any stiffness",
                "spring that holds it");
    CHECK(!strcmp(e.field, "n2.rz") || !strcmp(e.field, "n3.rz"));
    /* a DOF with only a damper: an error in any case (damped: no mass; undamped: the
     * damper is dropped and nothing holds it) */
    st = modal_status(gd_ts_, MASSLESS_DAMPER_ONLY, GD_MODAL_AUTO, &e, &nml);
    check_error(gd_ts_, __LINE__, st, &e, GD_EINPUT, 0, "n2.rz", "no mass", "damper");
    st = modal_status(gd_ts_, MASSLESS_DAMPER_ONLY, GD_MODAL_UNDAMPED, &e, &nml);
    check_error(gd_ts_, __LINE__, st, &e, GD_EINPUT, 0, "n2.rz", "not held", "spring");
}

/* The massless DOF is condensed when it is held by a stiffness and not damped. */
TEST(massless_dof_held_by_spring_is_condensed)
{
    gd_error e;
    int nml = -1;
    gd_status st = modal_status(gd_ts_,
                                "dofs: [rz]\n"
                                "shafts:\n"
                                "  - name: a\n"
                                "    nodes: [{name: n1}, {name: n2}]\n"
                                "disks:\n"
                                "  - {node: n1, polar_inertia: 0.1}\n"
                                "springs:\n"
                                "  - {node: n1, to: n2, dof: rz, stiffness: 100}\n"
                                "  - {node: n2, dof: rz, stiffness: 300}\n",
                                GD_MODAL_AUTO, &e, &nml);
    CHECK(st == GD_OK);
    CHECK(nml == 1);
}

/* Errors from the modal solve should still point into the model file: the massless
 * node's line (or the damper's). */
TEST(modal_errors_name_a_line)
{
    gd_error e;
    int nml;
    modal_status(gd_ts_, MASSLESS_DAMPER, GD_MODAL_AUTO, &e, &nml);
    CHECK(e.line == 6 || e.line == 11);
    if (e.line != 6 && e.line != 11) show_error(&e, e.status);
    modal_status(gd_ts_, MASSLESS_FLOATING, GD_MODAL_AUTO, &e, &nml);
    CHECK(e.line == 6 || e.line == 7 || e.line == 12);
    if (e.line <= 0) show_error(&e, e.status);
}

/* A torsion-only body (no diametral inertia) on a lumped node of a model that keeps the
 * tilts: its tilt DOFs carry only the gyroscopic term, which has nothing to act on.
 * At rest that term is zero, so the modal analysis should succeed rather than report
 * the tilts as massless DOFs held by nothing. */
TEST(torsion_only_disk_in_model_with_tilts)
{
    gd_error e;
    int nml = -1;
    gd_status st = modal_status(gd_ts_,
                                "dofs: [x, y, rx, ry, rz]\n"
                                "shafts:\n"
                                "  - name: a\n"
                                "    nodes: [{name: n1}, {name: n2}]\n"
                                "disks:\n"
                                "  - {node: n1, polar_inertia: 0.1, diametral_inertia: 0}\n"
                                "  - {node: n2, polar_inertia: 0.1, diametral_inertia: 0}\n"
                                "springs:\n"
                                "  - {node: n1, to: n2, dof: rz, stiffness: 100}\n",
                                GD_MODAL_AUTO, &e, &nml);
    CHECK(st == GD_OK);
    if (st != GD_OK) show_error(&e, st);
}

/* ---- unbalances ---- */

TEST(unbalance_amount_or_mass_and_eccentricity)
{
    gd_model *m =
        load_ok(gd_ts_, ONE_NODE "unbalances:\n"
                                 "  - {node: n1, mass: 2, eccentricity: 10 um, phase: 90 deg}\n"
                                 "  - {name: u2, node: n1, amount: 3 g*mm}\n");
    REQUIRE(m);
    REQUIRE(m->nunbalances == 2);
    CHECK_REL(m->unbalances[0].amount, 2e-5, 1e-12);
    CHECK_REL(m->unbalances[0].phase, M_PI / 2, 1e-12);
    CHECK_REL(m->unbalances[1].amount, 3e-6, 1e-12);
    CHECK_STR(m->unbalances[0].name, "unbalance1");
    gd_model_free(m);
}

TEST(unbalance_errors)
{
    EXPECT_LOAD_ERROR(ONE_NODE "unbalances:\n"
                               "  - {node: n1, phase: 0}\n", /* 5 */
                      5, "unbalances[0]", "missing", "amount");
    EXPECT_LOAD_ERROR(ONE_NODE "unbalances:\n"
                               "  - {node: n1, amount: 1e-4, mass: 1}\n",
                      5, "unbalances[0]", "together", "both");
    EXPECT_LOAD_ERROR(ONE_NODE "unbalances:\n"
                               "  - {node: n1, mass: 1}\n",
                      5, "unbalances[0]", "missing", "eccentricity");
    EXPECT_LOAD_ERROR(ONE_NODE "unbalances:\n"
                               "  - {node: n1, amount: -1e-4}\n",
                      5, "unbalances[0].amount", "positive", "greater than zero");
    EXPECT_LOAD_ERROR(ONE_NODE "unbalances:\n"
                               "  - {node: nx, amount: 1e-4}\n",
                      5, "unbalances[0].node", "unknown node", "n1");
    EXPECT_LOAD_ERROR(ONE_NODE "unbalances:\n"
                               "  - {node: n1, amount: 1e-4, ecc: 2}\n",
                      5, "unbalances[0].ecc", "unknown key", "eccentricity");
}

RUN_TESTS(T(unbalance_amount_or_mass_and_eccentricity), T(unbalance_errors),
          T(valid_bases_load_with_units), T(yaml_syntax_error),
          T(yaml_unclosed_bracket_names_its_line), T(yaml_duplicate_key), T(yaml_alias_rejected),
          T(yaml_two_documents), T(empty_file), T(empty_document_marker_is_empty),
          T(top_level_not_a_map), T(unknown_key_top), T(unknown_key_top_far_from_any),
          T(unknown_key_shaft), T(unknown_key_section), T(unknown_key_node), T(unknown_key_disk),
          T(unknown_key_disk_geometry), T(unknown_key_bearing), T(unknown_key_bearing_table_row),
          T(unknown_key_spring), T(unknown_key_mesh), T(unknown_key_material), T(missing_shafts),
          T(empty_shafts_list), T(shaft_without_sections_or_nodes), T(missing_section_length),
          T(missing_section_material), T(missing_mesh_stiffness), T(missing_mesh_name),
          T(missing_mesh_driver), T(missing_node_name), T(missing_node_position_on_flexible_shaft),
          T(missing_disk_node), T(missing_spring_dof), T(missing_material_modulus),
          T(material_needs_poisson_or_g), T(disk_without_mass_or_inertia),
          T(missing_key_and_wrong_kind_errors_have_a_hint), T(list_where_value_expected),
          T(string_where_number_expected), T(value_where_list_expected),
          T(value_where_map_expected), T(whole_number_expected), T(pair_expected),
          T(unknown_choice_values), T(no_dofs), T(negative_mass), T(zero_mass), T(negative_inertia),
          T(zero_length), T(negative_length), T(inner_diameter_not_below_outer),
          T(disk_geometry_inner_diameter_not_below_outer), T(disk_geometry_and_mass), T(nan_value),
          T(inf_value), T(negative_speed), T(poisson_out_of_range), T(g_and_poisson_both),
          T(teeth_not_whole), T(bad_unit), T(wrong_dimension_length_as_angle),
          T(wrong_dimension_linear_stiffness_on_rotation),
          T(pressure_angle_plain_number_is_radians), T(helix_angle_plain_number_is_radians),
          T(unknown_material), T(unknown_material_suggests_defined_ones), T(unknown_node),
          T(unknown_mesh_node_and_shaft), T(node_position_outside_shaft), T(coincident_named_nodes),
          T(duplicate_shaft_name), T(duplicate_node_name), T(duplicate_mesh_name),
          T(duplicate_bearing_name), T(long_shaft_names_give_distinct_generated_nodes),
          T(mesh_on_one_shaft), T(teeth_inconsistent_with_radii), T(gear_size_missing_or_twice),
          T(gear_ratio_loop_inconsistent), T(gear_loop_consistent_is_accepted),
          T(driver_rotation_contradicts_train), T(speed_ratio_errors_point_at_the_key),
          T(bearing_without_coefficients), T(bearing_to_itself), T(spring_to_itself),
          T(spring_without_stiffness_or_damping), T(bearing_k_and_kxx),
          T(bearing_speed_table_not_increasing), T(bearing_table_rules),
          T(elements_per_section_and_max_length_both),
          T(max_element_length_respected_next_to_named_node), T(name_too_long), T(no_active_dof),
          T(massless_dof_with_damper), T(massless_dof_held_by_nothing),
          T(massless_dof_held_by_spring_is_condensed), T(modal_errors_name_a_line),
          T(torsion_only_disk_in_model_with_tilts))
