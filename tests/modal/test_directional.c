/* Directional modes (issue 14, [Kumar2011] complex variable approach): the eigenvalues of
 * the equation written for r = x + i y and its conjugate, one per mode, Im > 0 forward
 * and Im < 0 backward. They are computed from the complex-coordinate matrices by their
 * own (complex) eigensolver, so pairing them with the real-coordinate damped modes
 * checks both. */
#include <math.h>
#include <stdlib.h>

#include "cli_support.h"
#include "geardyn/modal.h"
#include "harness.h"
#include "model_support.h"

/* Every directional root has a real-coordinate mode with the same eigenvalue up to the
 * sign of Im (1e-9 relative: two eigensolvers on the same matrices) and the same
 * whirl; the counts agree (rigid-body modes left out). Returns the number paired. */
static int pair_with_real(gd_test_state *gd_ts_, const fx *f, double speed)
{
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = speed;
    o.kind = GD_MODAL_DAMPED;
    gd_modal_result *r = NULL;
    gd_directional_result *d = NULL;
    gd_error e;
    if (gd_modal_solve(f->s, &o, &r, &e) || gd_modal_directional(f->s, &o, &d, &e)) {
        fprintf(stderr, "  %s\n", e.message);
        gd_ts_->checks_failed++;
        gd_modal_free(r);
        return 0;
    }
    int nreal = 0, paired = 0;
    int *used = calloc((size_t)r->nmodes, sizeof *used);
    for (int k = 0; k < r->nmodes; k++)
        nreal += !r->modes[k].rigid_body;
    for (int j = 0; j < d->nmodes; j++) {
        const gd_directional_mode *dm = &d->modes[j];
        int best = -1;
        double bd = INFINITY;
        for (int k = 0; k < r->nmodes; k++) {
            const gd_mode *md = &r->modes[k];
            if (md->rigid_body || used[k]) continue;
            double dist = hypot(dm->lambda_re - md->lambda_re, fabs(dm->lambda_im) - md->lambda_im);
            if (dist < bd) {
                bd = dist;
                best = k;
            }
        }
        if (best < 0) {
            CHECK(best >= 0);
            break;
        }
        const gd_mode *md = &r->modes[best];
        used[best] = 1;
        int ok = bd <= 1e-9 * md->omega_n &&
                 (speed == 0 || dm->whirl == md->whirl || dm->whirl == GD_WHIRL_NONE);
        CHECK(ok);
        if (!ok)
            fprintf(stderr, "    root %d: %.12g%+.12gi (%s) vs mode %d %.12g%+.12gi (%s)\n", j,
                    dm->lambda_re, dm->lambda_im, gd_whirl_names[dm->whirl], best, md->lambda_re,
                    md->lambda_im, gd_whirl_names[md->whirl]);
        /* the sign of Im is the whirl */
        if (dm->whirl == GD_WHIRL_BACKWARD) CHECK(dm->lambda_im < 0);
        if (dm->whirl != GD_WHIRL_BACKWARD) CHECK(dm->lambda_im >= 0);
        paired++;
    }
    CHECK(d->nmodes == nreal);
    free(used);
    gd_modal_free(r);
    gd_directional_free(d);
    return paired;
}

TEST(kumar_coupled_roots_pair_with_the_real_modes)
{
    fx f;
    REQUIRE(load(&f, "examples/kumar2011_coupled.yaml", NULL));
    /* 8 DOFs, one rigid (the free gear train turns): 7 modes, all straight-line orbits
       (the bearings are isotropic but the mesh acts along y) */
    CHECK(pair_with_real(gd_ts_, &f, 0) == 7);
    fx_free(&f);
}

/* A Jeffcott-like rotor with an overhung-ish disk on isotropic damped bearings: at
 * rest each lateral mode is a double root, split into a forward (+w) and a backward
 * (-w) circle; with speed the gyroscopic moment of the disk lifts the forward and
 * lowers the backward frequency. */
static const char ISO[] =
    "materials: {steel: {E: 2.1e11, density: 7850, poisson: 0.3}}\n"
    "dofs: [x, y, rx, ry]\n"
    "shafts:\n"
    "  - name: s\n"
    "    material: steel\n"
    "    elements_per_section: 4\n"
    "    sections: [{length: 0.6, outer_diameter: 30 mm}]\n"
    "    nodes: [{name: b1, at: 0}, {name: mid, at: 0.2}, {name: b2, at: 0.6}]\n"
    "disks: [{node: mid, mass: 10, polar_inertia: 0.15, diametral_inertia: 0.08}]\n"
    "bearings: [{node: b1, k: 2e7, c: 100}, {node: b2, k: 2e7, c: 100}]\n";

TEST(isotropic_rotor_splits_forward_and_backward_with_speed)
{
    fx f;
    REQUIRE(load(&f, NULL, ISO));
    CHECK(pair_with_real(gd_ts_, &f, 0) > 0);
    CHECK(pair_with_real(gd_ts_, &f, 500) > 0);
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.nmodes = 4;
    double fw[2], bw[2];
    for (int si = 0; si < 2; si++) {
        o.speed = si ? 500 : 0;
        gd_directional_result *d = NULL;
        gd_error e;
        REQUIRE(gd_modal_directional(f.s, &o, &d, &e) == GD_OK);
        REQUIRE(d->nmodes == 4);
        /* the lowest pair: one forward, one backward */
        const gd_directional_mode *a = &d->modes[0], *b = &d->modes[1];
        const gd_directional_mode *pf = a->lambda_im > 0 ? a : b, *pb = a->lambda_im > 0 ? b : a;
        CHECK(pf->whirl == GD_WHIRL_FORWARD && pb->whirl == GD_WHIRL_BACKWARD);
        /* circular orbits (isotropic): all forward, all backward */
        CHECK_ABS(pf->forward_fraction, 1, 1e-9);
        CHECK_ABS(pb->forward_fraction, 0, 1e-9);
        fw[si] = pf->lambda_im;
        bw[si] = -pb->lambda_im;
        gd_directional_free(d);
    }
    /* at rest the two circles have one frequency (1e-9: a double root) */
    CHECK_REL(fw[0], bw[0], 1e-9);
    /* at 500 rad/s they split: forward up, backward down, by more than 1% here */
    CHECK(fw[1] > 1.01 * fw[0]);
    CHECK(bw[1] < 0.99 * bw[0]);
    fx_free(&f);
}

TEST(cli_directional)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    REQUIRE(run(&s, &r, "modal examples/kumar2011_coupled.yaml --damped --directional --json") ==
            0);
    cJSON *o = cJSON_Parse(r.out);
    REQUIRE(o);
    const cJSON *d = cJSON_GetObjectItemCaseSensitive(o, "directional");
    CHECK(cJSON_GetArraySize(d) == 7);
    const cJSON *d0 = cJSON_GetArrayItem(d, 0);
    CHECK_REL(jnum(d0, "eigenvalue_imag"), 122.3014, 1e-6); /* the table's 122.301 rad/s */
    CHECK_STR(jstr(d0, "whirl"), "none");
    cJSON_Delete(o);
    run_free(&r);
    REQUIRE(run(&s, &r, "modal examples/kumar2011_coupled.yaml --directional") == 0);
    CHECK(contains(r.out, "directional modes"));
    run_free(&r);
    scratch_close(&s);
}

RUN_TESTS(T(kumar_coupled_roots_pair_with_the_real_modes), T(cli_directional),
          T(isotropic_rotor_splits_forward_and_backward_with_speed))
