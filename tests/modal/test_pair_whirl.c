/* The whirl of a repeated pair (src/modal/mode_properties.c, pair_whirl): an isotropic
 * rotor whose x/y pairs nothing splits (no gyroscopic term: `--undamped` at speed, or a
 * model without tilts) has any basis of each pair's space as eigenvectors. LAPACK
 * returned two straight-line orbits ("none"), Krylov-Schur complex mixtures (forward,
 * backward or mixed, whatever the Krylov start): the label depended on the solver. It is
 * now read from the pair turned to circular orbits: mode j forward, mode j + 1 backward,
 * by either solver, at every speed; at rest no whirl. */
#include <math.h>

#include "geardyn/modal.h"
#include "harness.h"
#include "model_support.h"

#define ROTOR(DOFS)                                                                                \
    "dofs: " DOFS "\n"                                                                             \
    "materials:\n  steel: {density: 7800, E: 2.1e11, poisson: 0.3}\n"                              \
    "shafts:\n  - name: rotor\n    material: steel\n    elements_per_section: 12\n"                \
    "    sections: [{length: 0.6, outer_diameter: 0.03}]\n"                                        \
    "    nodes: [{name: b1, at: 0}, {name: disk, at: 0.45}, {name: b2, at: 0.6}]\n"                \
    "disks:\n  - {name: disk, node: disk, mass: 8, polar_inertia: 0.12, diametral_inertia: "       \
    "0.06}\n"                                                                                      \
    "bearings:\n  - {name: B1, node: b1, k: 2e6, c: 30}\n  - {name: B2, node: b2, k: 2e6, c: "     \
    "30}\n"

/* Both solvers' labels of the lowest 6 modes; returns the number of pairs seen. */
static int pairs(gd_test_state *gd_ts_, const char *yaml, gd_modal_kind kind, double speed)
{
    fx f;
    if (!load(&f, NULL, yaml)) {
        gd_ts_->checks_failed++;
        return 0;
    }
    gd_modal_result *r[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
        gd_modal_options o;
        gd_modal_options_init(&o);
        o.speed = speed;
        o.nmodes = 6;
        o.want_left = 0;
        o.kind = kind;
        o.method = k ? GD_EIG_SPARSE : GD_EIG_DENSE;
        gd_error err;
        CHECK(gd_modal_solve(f.s, &o, &r[k], &err) == GD_OK);
    }
    int npairs = 0;
    if (r[0] && r[1]) {
        CHECK(r[0]->nmodes == 6 && r[1]->nmodes == 6 && !r[1]->modes[0].rigid_body);
        for (int j = 0; j < 6; j++) {
            const gd_mode *d = &r[0]->modes[j], *s = &r[1]->modes[j];
            CHECK_REL(s->omega_n, d->omega_n, 1e-8);
            if (s->whirl != d->whirl)
                fprintf(stderr, "  mode %d (%.6g Hz): dense %s, sparse %s\n", j + 1,
                        d->frequency_hz, gd_whirl_names[d->whirl], gd_whirl_names[s->whirl]);
            CHECK(s->whirl == d->whirl);
        }
        for (int j = 0; j + 1 < 6; j++) {
            const gd_mode *a = &r[0]->modes[j], *b = &r[0]->modes[j + 1];
            if (fabs(a->omega_n - b->omega_n) > 1e-6 * a->omega_n) continue; /* pair_whirl's rule */
            npairs++;
            /* a lateral pair: one forward and one backward circle, the forward one first */
            CHECK(a->whirl == (speed != 0 ? GD_WHIRL_FORWARD : GD_WHIRL_NONE));
            CHECK(b->whirl == (speed != 0 ? GD_WHIRL_BACKWARD : GD_WHIRL_NONE));
            j++;
        }
    }
    gd_modal_free(r[0]);
    gd_modal_free(r[1]);
    fx_free(&f);
    return npairs;
}

/* --undamped at 3000 rpm: the gyroscopic term dropped, every lateral mode a repeated pair */
TEST(undamped_pairs_label_alike_by_both_solvers)
{
    CHECK(pairs(gd_ts_, ROTOR("[x, y, rx, ry]"), GD_MODAL_UNDAMPED, 314.159) == 3);
    /* at rest: no direction to whirl in, whatever the basis */
    CHECK(pairs(gd_ts_, ROTOR("[x, y, rx, ry]"), GD_MODAL_UNDAMPED, 0) == 3);
}

/* damped (the bearings' c) without tilts, hence without gyroscopic coupling: repeated
   complex pairs at speed */
TEST(damped_pairs_without_gyroscopics_label_alike)
{
    int np = pairs(gd_ts_, ROTOR("[x, y]"), GD_MODAL_DAMPED, 314.159);
    CHECK(np == 1);
}

/* a gyroscopic rotor at speed has no repeated pair: its labels are its own vectors' (the
   forward mode above its backward twin), unchanged */
TEST(split_pairs_keep_their_own_labels)
{
    fx f;
    REQUIRE(load(&f, NULL, ROTOR("[x, y, rx, ry]")));
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = 314.159;
    o.nmodes = 4;
    o.want_left = 0;
    gd_modal_result *r = NULL;
    gd_error err;
    REQUIRE(gd_modal_solve(f.s, &o, &r, &err) == GD_OK);
    CHECK(r->modes[0].omega_n < r->modes[1].omega_n * (1 - 1e-6));
    CHECK(r->modes[0].whirl == GD_WHIRL_BACKWARD && r->modes[1].whirl == GD_WHIRL_FORWARD);
    gd_modal_free(r);
    fx_free(&f);
}

RUN_TESTS(T(undamped_pairs_label_alike_by_both_solvers),
          T(damped_pairs_without_gyroscopics_label_alike), T(split_pairs_keep_their_own_labels))
