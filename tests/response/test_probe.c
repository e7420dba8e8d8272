/* The probe vocabulary of the element registry (gd_element_type.probe): the prefixes the
 * kinds own, the instance found by its component name, the default force probes, and
 * the invariants a kind with a probe keeps (a force row, one component per instance). */
#include <string.h>

#include "geardyn/probe.h"
#include "harness.h"
#include "model_support.h"

TEST(kinds_own_their_probe_prefix)
{
    const char *rest = NULL;
    CHECK(gd_probe_element("mesh:mesh", &rest) == &gd_element_mesh);
    CHECK_STR(rest, "mesh");
    CHECK(gd_probe_element("bearing:support_b.y", &rest) == &gd_element_bearing);
    CHECK_STR(rest, "support_b.y");
    /* a prefix is a whole word before the colon; a node name is no probe */
    CHECK(gd_probe_element("meshes:a", NULL) == NULL);
    CHECK(gd_probe_element("mesh", NULL) == NULL);
    CHECK(gd_probe_element("gear_a.x", NULL) == NULL);
    CHECK(gd_probe_element("spring:coupling.rz", NULL) == NULL); /* no spring probe (yet) */
    /* the table's invariants: every probe has its force row and a one-component-per-
     * instance numbering (gd_probe_instance returns the component index) */
    int nprobe = 0;
    for (int k = 0; k < gd_nelement_types; k++) {
        const gd_element_type *t = gd_element_types[k];
        if (!t->probe) continue;
        nprobe++;
        CHECK(t->force_row != NULL && t->component != NULL && t->probe_help != NULL);
    }
    CHECK(nprobe == 2);
}

TEST(instances_and_defaults_from_the_table)
{
    fx f;
    REQUIRE(load(&f, "examples/chen1998_gear_pair.yaml", NULL));
    CHECK(gd_probe_instance(f.s, &gd_element_bearing, "support_b") == 1);
    CHECK(gd_probe_instance(f.s, &gd_element_bearing, "mesh") == -1);
    CHECK(gd_probe_instance(f.s, &gd_element_mesh, "mesh") == 0);
    /* the one-force kinds first, then x and y of each bearing: the CLI's unbalance
     * defaults and the report's force probes, as they were written by hand */
    gd_probe p[8];
    int n = gd_probe_defaults(f.s, p, 8);
    REQUIRE(n == 5);
    const char *want[5] = {"mesh:mesh", "bearing:support_a.x", "bearing:support_a.y",
                           "bearing:support_b.x", "bearing:support_b.y"};
    for (int k = 0; k < n; k++)
        CHECK_STR(p[k].name, want[k]);
    CHECK(p[0].element == &gd_element_mesh && p[0].index == 0);
    CHECK(p[4].element == &gd_element_bearing && p[4].index == 1 && p[4].dir == GD_Y);
    /* the cap holds */
    CHECK(gd_probe_defaults(f.s, p, 2) == 2);
    fx_free(&f);
}

RUN_TESTS(T(kinds_own_their_probe_prefix), T(instances_and_defaults_from_the_table))
