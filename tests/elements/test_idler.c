/* Idling gears, synchronisers and gear selection (docs/model-format.md, "idlers"):
 *  - an idler on a hub: free in rotation in neutral (a rigid-body mode), locked when
 *    engaged: the 2-DOF frequencies of J_hub, J_idler, the lock k and the hub's support;
 *  - examples/manual_5speed.yaml: the gear train's speeds with gear 3 and with gear 4
 *    selected (the output shaft follows the engaged idler; the idlers follow the input
 *    pinions), the idlers' order labels named from their meshes, the lock springs;
 *  - the errors: two gears on one synchroniser, a gear that does not exist, a fixed gear
 *    on a synchroniser, an idler on two synchronisers, a shift without a cone. */
#include <math.h>
#include <string.h>

#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/modal.h"
#include "geardyn/system.h"
#include "harness.h"

#define PI 3.14159265358979323846

/* a hub (J_h = 0.01) on a torsional support k0 = 1e4 to ground, an idler (J_i = 1e-3) on
   it through its needle bearing, a synchroniser with lock k = 1e6 */
static const char *HUB = "dofs: [rz]\n"
                         "shafts:\n  - {name: shaft, nodes: [{name: hub}]}\n"
                         "disks:\n  - {name: hub, node: hub, mass: 2, polar_inertia: 0.01}\n"
                         "springs:\n  - {name: support, node: hub, dof: rz, stiffness: 1e4}\n"
                         "idlers:\n  - {name: idl, on: hub, mass: 0.5, polar_inertia: 1e-3,\n"
                         "     radial_stiffness: 1e8}\n"
                         "synchronisers:\n  - {name: sy, node: hub, idlers: [idl],"
                         " stiffness: 1e6}\n"
                         "gears: {1: idl}\n";

static gd_model *load(const char *yaml, const char *set0, const char *set1, gd_error *err)
{
    const char *sets[2] = {set0, set1};
    gd_load_options opt;
    gd_load_options_init(&opt);
    opt.nset = set0 ? (set1 ? 2 : 1) : 0;
    opt.set = sets;
    gd_model *m = NULL;
    gd_error_clear(err);
    if (gd_model_load_string_opts(yaml, "idler.yaml", &opt, &m, err)) return NULL;
    return m;
}

static int frequencies(const gd_model *m, double *f, int *rigid)
{
    gd_modal_options opt;
    gd_modal_options_init(&opt);
    opt.kind = GD_MODAL_UNDAMPED;
    gd_system *sys = NULL;
    gd_modal_result *r = NULL;
    if (gd_system_build(m, &sys, NULL) || gd_modal_solve(sys, &opt, &r, NULL)) {
        gd_system_free(sys);
        return -1;
    }
    int n = 0;
    *rigid = 0;
    for (int i = 0; i < r->nmodes; i++) {
        if (r->modes[i].rigid_body)
            (*rigid)++;
        else
            f[n++] = r->modes[i].frequency_hz;
    }
    gd_modal_free(r);
    gd_system_free(sys);
    return n;
}

TEST(idler_free_in_neutral_locked_when_engaged)
{
    gd_error err;
    gd_model *m = load(HUB, NULL, NULL, &err);
    REQUIRE(m);
    CHECK(m->nidlers == 1 && m->nsynchronisers == 1);
    CHECK(m->synchronisers[0].engaged == -1 && m->synchronisers[0].spring == -1);
    CHECK(m->idlers[0].carrier == gd_model_find_node(m, "hub"));
    double f[8];
    int rigid;
    /* neutral: the hub on its support, the idler free (a rigid-body mode) */
    int n = frequencies(m, f, &rigid);
    CHECK(n == 1 && rigid == 1);
    CHECK_REL(f[0], sqrt(1e4 / 0.01) / (2 * PI), 1e-9);
    gd_model_free(m);

    m = load(HUB, "gear=1", NULL, &err);
    REQUIRE(m);
    CHECK(m->gear == 1 && m->synchronisers[0].engaged == 0 && m->idlers[0].engaged);
    int sp = m->synchronisers[0].spring;
    REQUIRE(sp >= 0);
    CHECK(!strcmp(m->springs[sp].name, "sy.lock") && m->springs[sp].stiffness == 1e6);
    /* engaged: det(K - w^2 M) = 0 for K = [k0 + k, -k; -k, k], M = diag(J_h, J_i) */
    double k0 = 1e4, k = 1e6, Jh = 0.01, Ji = 1e-3;
    double a = Jh * Ji, b = -(Jh * k + Ji * (k0 + k)), c = k0 * k;
    double disc = sqrt(b * b - 4 * a * c);
    double w1 = sqrt((-b - disc) / (2 * a)), w2 = sqrt((-b + disc) / (2 * a));
    n = frequencies(m, f, &rigid);
    CHECK(n == 2 && rigid == 0);
    CHECK_REL(f[0], w1 / (2 * PI), 1e-9);
    CHECK_REL(f[1], w2 / (2 * PI), 1e-9);
    /* the per-synchroniser key does the same */
    gd_model_free(m);
    m = load(HUB, "synchronisers.0.engaged=idl", NULL, &err);
    REQUIRE(m);
    CHECK(m->gear == 0 && m->synchronisers[0].engaged == 0);
    gd_model_free(m);
}

TEST(manual_5speed_train_speeds_follow_the_selection)
{
    gd_error err;
    gd_model *m = NULL;
    REQUIRE(gd_model_load_opts("examples/manual_5speed.yaml", NULL, &m, &err) == GD_OK);
    CHECK(m->nidlers == 5 && m->nsynchronisers == 3 && m->ngears == 5 && m->gear == 3);
    /* base radii of the input pinions and of the idlers (the example's meshes) */
    const double rp[5] = {12.921, 19.968, 24.667, 39.937, 44.635};
    const double ri[5] = {44.635, 42.286, 35.238, 41.112, 36.413};
    int out = gd_model_find_shaft(m, "output"), diff = gd_model_find_shaft(m, "differential");
    for (int i = 0; i < 5; i++) {
        char name[16];
        snprintf(name, sizeof name, "idler%d", i + 1);
        int s = gd_model_find_shaft(m, name);
        REQUIRE(s >= 0);
        /* each idler turns with its input pinion, the engaged one with the output too */
        CHECK_REL(m->shafts[s].speed_ratio, -rp[i] / ri[i], 1e-12);
        CHECK(m->idlers[i].engaged == (i == 2));
        char label[128];
        gd_model_shaft_order_label(m, s, label, (int)sizeof label);
        char want[32];
        snprintf(want, sizeof want, "1x idler gear%d", i + 1);
        CHECK(!strcmp(label, want));
    }
    CHECK_REL(m->shafts[out].speed_ratio, -rp[2] / ri[2], 1e-12);
    CHECK_REL(m->shafts[diff].speed_ratio, rp[2] / ri[2] * 21.965 / 83.985, 1e-12);
    char label[128];
    gd_model_shaft_order_label(m, out, label, (int)sizeof label);
    CHECK(!strcmp(label, "1x output"));
    gd_model_free(m);

    /* 4th gear: the output follows idler 4 */
    const char *sets[1] = {"gear=4"};
    gd_load_options opt;
    gd_load_options_init(&opt);
    opt.nset = 1;
    opt.set = sets;
    REQUIRE(gd_model_load_opts("examples/manual_5speed.yaml", &opt, &m, &err) == GD_OK);
    out = gd_model_find_shaft(m, "output");
    CHECK_REL(m->shafts[out].speed_ratio, -rp[3] / ri[3], 1e-12);
    CHECK(m->idlers[3].engaged && !m->idlers[2].engaged);
    int sp = m->synchronisers[1].spring;
    REQUIRE(sp >= 0);
    CHECK(m->springs[sp].node1 == m->idlers[3].node &&
          m->springs[sp].node2 == m->idlers[3].carrier);
    gd_model_free(m);
}

/* A load that fails with msg1 (and msg2) in the message or hint, at field. */
static int refused(const char *yaml, const char *set, const char *field, const char *w1,
                   const char *w2)
{
    gd_error err;
    gd_model *m = load(yaml, set, NULL, &err);
    if (m) {
        gd_model_free(m);
        fprintf(stderr, "  accepted: %s\n", set ? set : "");
        return 0;
    }
    char all[2048];
    snprintf(all, sizeof all, "%s | %s | %s", err.field, err.message, err.hint);
    int ok = err.status == GD_EINPUT && strstr(err.field, field) && strstr(all, w1) &&
             (!w2 || strstr(all, w2));
    if (!ok) fprintf(stderr, "  %s: %s\n", set ? set : "", all);
    return ok;
}

TEST(selection_errors_are_located)
{
    static const char *TWO =
        "dofs: [rz]\n"
        "shafts:\n  - {name: shaft, nodes: [{name: hub}]}\n"
        "disks:\n  - {name: hub, node: hub, mass: 2, polar_inertia: 0.01}\n"
        "  - {name: fixed, node: hub, mass: 1, polar_inertia: 1e-3}\n"
        "springs:\n  - {name: support, node: hub, dof: rz, stiffness: 1e4}\n"
        "idlers:\n  - {name: a, on: hub, mass: 0.5, polar_inertia: 1e-3, radial_stiffness: 1e8}\n"
        "  - {name: b, on: hub, mass: 0.5, polar_inertia: 1e-3, radial_stiffness: 1e8}\n"
        "synchronisers:\n  - {name: sy, node: hub, idlers: [a, b]}\n"
        "gears: {1: a, 2: b}\n";
    CHECK(refused(TWO, "gear=7", "gear", "gear 7 does not exist", "1 2"));
    gd_error err;
    gd_model *m = load(TWO, "synchronisers.0.engaged=a", NULL, &err);
    CHECK(m && m->idlers[0].engaged); /* engaged alone is a selection */
    if (m) gd_model_free(m);
    char both[2048];
    snprintf(both, sizeof both, "%sgear: 2\n", TWO);
    CHECK(refused(both, "synchronisers.0.engaged=a", "synchronisers[0].engaged",
                  "two gears engaged on synchroniser 'sy'", NULL));
    CHECK(refused(TWO, "synchronisers.0.engaged=[a, b]", "synchronisers[0].engaged",
                  "two gears engaged", NULL));
    CHECK(refused(TWO, "synchronisers.0.idlers=[a, fixed]", "synchronisers[0].idlers[1]",
                  "'fixed' is not an idler", "fixed on its shaft"));
    CHECK(refused(TWO, "gears={1: a, 2: fixed}", "gears.2", "'fixed' is not an idler", NULL));
    CHECK(refused(TWO,
                  "synchronisers=[{name: sy, node: hub, idlers: [a, b]}, {name: sz, "
                  "node: hub, idlers: [b]}]",
                  "synchronisers[1].idlers[0]", "on synchronisers 'sy' and 'sz'", NULL));
    CHECK(refused(TWO, "shift={from: 1, to: 2, at: 0.1}", "shift.from", "not engaged", NULL));
    snprintf(both, sizeof both, "%sgear: 1\n", TWO);
    CHECK(refused(both, "shift={from: 1, to: 2, at: 0.1}", "shift.to", "has no cone", NULL));
    CHECK(refused(both, "shift={from: 1, to: 3, at: 0.1}", "shift.to", "gear 3 does not exist",
                  NULL));
}

RUN_TESTS(T(idler_free_in_neutral_locked_when_engaged),
          T(manual_5speed_train_speeds_follow_the_selection), T(selection_errors_are_located))
