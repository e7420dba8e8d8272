/* Strain energy per shaft and motion type (issue 14, [JMSTHelical] Tables 4 and 7): each
 * bearing goes with the shaft of its node, a mesh half to each of its two shafts;
 * checked against energies computed by hand from the mode shapes, and on the CLI
 * (`geardyn modal --group shaft`). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>

#include "cli_support.h"
#include "geardyn/modal.h"
#include "harness.h"
#include "model_support.h"

/* Two gears on their own lateral/torsional supports, a spur mesh between them. */
static const char PAIR[] = "dofs: [x, y, rz]\n"
                           "shafts:\n"
                           "  - {name: sa, nodes: [{name: ga}]}\n"
                           "  - {name: sb, nodes: [{name: gb}]}\n"
                           "disks: [{node: ga, mass: 2, polar_inertia: 2e-3},\n"
                           "        {node: gb, mass: 5, polar_inertia: 9e-3}]\n"
                           "bearings: [{name: ba, node: ga, k: 1e8, k_torsion: 0},\n"
                           "           {name: bb, node: gb, k: 3e8, k_torsion: 2e4}]\n"
                           "meshes:\n"
                           "  - {name: m, driver: ga, driven: gb, base_radius: [30 mm, 60 mm],\n"
                           "     pressure_angle: 20 deg, stiffness: 2e8}\n";

TEST(shares_by_hand_for_a_gear_pair)
{
    fx f;
    REQUIRE(load(&f, NULL, PAIR));
    int n = f.s->ndof;
    REQUIRE(n == 6);
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.kind = GD_MODAL_UNDAMPED;
    gd_modal_result *r = NULL;
    gd_error e;
    REQUIRE(gd_modal_solve(f.s, &o, &r, &e) == GD_OK);
    double K[36];
    gd_system_dense(f.s, 0, NULL, NULL, K);
    int xa = dof(&f, "ga", GD_X), ya = dof(&f, "ga", GD_Y), xb = dof(&f, "gb", GD_X),
        yb = dof(&f, "gb", GD_Y), rb = dof(&f, "gb", GD_RZ);
    double t[2 * GD_NMOTIONS];
    int checked = 0;
    for (int j = 0; j < r->nmodes; j++) {
        if (r->modes[j].rigid_body) continue;
        const double *u = r->shape_re + (size_t)j * n;
        REQUIRE(gd_modal_energy_by_shaft(f.s, r, j, t, &e) == GD_OK);
        /* by hand: total 1/2 u^T K u; bearing a 1/2 k (x^2 + y^2); bearing b with its
           torsional spring; the mesh is the rest, half to each shaft */
        double total = 0;
        for (int a = 0; a < n; a++)
            for (int b = 0; b < n; b++)
                total += 0.5 * u[a] * K[a + b * n] * u[b];
        double ea = 0.5 * 1e8 * (u[xa] * u[xa] + u[ya] * u[ya]);
        double eb_lat = 0.5 * 3e8 * (u[xb] * u[xb] + u[yb] * u[yb]),
               eb_tor = 0.5 * 2e4 * u[rb] * u[rb];
        double em = total - ea - eb_lat - eb_tor;
        double sa = 0, sb = 0;
        for (int k = 0; k < GD_NMOTIONS; k++) {
            sa += t[k];
            sb += t[GD_NMOTIONS + k];
        }
        /* 1e-10: sums of a few products of the mode shape, rounding only */
        CHECK_ABS(sa, (ea + em / 2) / total, 1e-10);
        CHECK_ABS(sb, (eb_lat + eb_tor + em / 2) / total, 1e-10);
        CHECK_ABS(sa + sb, 1, 1e-12);
        /* shaft b's own split: its bearing's lateral and torsional parts exactly, the
           mesh's half-share by the mesh element's own split */
        CHECK(t[GD_NMOTIONS + GD_MOTION_LATERAL] >= eb_lat / total - 1e-12);
        CHECK(t[GD_NMOTIONS + GD_MOTION_TORSIONAL] >= eb_tor / total - 1e-12);
        CHECK_ABS(t[GD_MOTION_AXIAL] + t[GD_NMOTIONS + GD_MOTION_AXIAL], 0, 1e-15);
        checked++;
    }
    CHECK(checked >= 4);
    CHECK(gd_modal_energy_by_shaft(f.s, r, r->nmodes, t, &e) == GD_EINPUT);
    gd_modal_free(r);
    fx_free(&f);
}

TEST(cli_group_shaft)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    REQUIRE(run(&s, &r, "modal examples/rig2018.yaml --modes 6 --group shaft --json") == 0);
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    const cJSON *modes = cJSON_GetObjectItemCaseSensitive(o, "modes");
    int n = cJSON_GetArraySize(modes);
    CHECK(n == 6);
    for (int i = 0; i < n; i++) {
        const cJSON *m = cJSON_GetArrayItem(modes, i);
        const cJSON *by = cJSON_GetObjectItemCaseSensitive(m, "energy_by_shaft");
        REQUIRE(by && cJSON_GetArraySize(by) == 2);
        double sum = 0;
        for (const cJSON *sh = by->child; sh; sh = sh->next)
            sum += jnum(sh, "share");
        if (cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(m, "rigid_body")))
            CHECK_ABS(sum, 0, 0);
        else
            CHECK_REL(sum, 1, 1e-12);
    }
    /* the first bending pair of the driving shaft: most energy there, lateral */
    const cJSON *m2 = cJSON_GetArrayItem(modes, 2);
    CHECK_STR(jstr(m2, "dominant_shaft"), "driving");
    const cJSON *drv = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(m2, "energy_by_shaft"), "driving");
    CHECK_STR(jstr(drv, "dominant_motion"), "lateral");
    cJSON_Delete(o);
    run_free(&r);
    REQUIRE(run(&s, &r, "modal examples/rig2018.yaml --modes 4 --group shaft") == 0);
    CHECK(contains(r.out, "strain energy by shaft"));
    CHECK(contains(r.out, "shaft driven: its strain energy by motion type"));
    run_free(&r);
    CHECK(run(&s, &r, "modal examples/rig2018.yaml --group gear") == 2);
    CHECK(contains(r.err, "--group") && contains(r.err, "'gear'"));
    CHECK(r.out[0] == '\0');
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(shares_by_hand_for_a_gear_pair), T(cli_group_shaft))
