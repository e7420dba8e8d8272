/* The eigensolver choice (src/modal/method.c): AUTO picks the dense solver where the
 * cost model says it is cheaper and the sparse one elsewhere, and both give the same
 * modes. Models: the MMT rig at several refinements, damped and undamped. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/model_file.h"
#include "geardyn/modal.h"
#include "harness.h"

typedef struct fx {
    gd_model *m;
    gd_system *s;
} fx;

/* The rig with `per` elements per section; undamped: bearing and mesh damping zero. */
static int load_rig(fx *f, int per, int undamped)
{
    char a[64];
    snprintf(a, sizeof a, "shafts.*.elements_per_section=%d", per);
    const char *sets[] = {a, "bearings.*.c=0", "meshes.mesh.damping=0"};
    gd_load_options lo = {undamped ? 3 : 1, sets};
    gd_error err;
    if (gd_model_load_opts("examples/rig2018.yaml", &lo, &f->m, &err) ||
        gd_system_build(f->m, &f->s, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        return 0;
    }
    return 1;
}

static void fx_free(fx *f)
{
    gd_system_free(f->s);
    gd_model_free(f->m);
}

static gd_modal_result *solve(const fx *f, double speed, int nmodes, gd_eig_method m)
{
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = speed;
    o.nmodes = nmodes;
    o.want_left = 0;
    o.method = m;
    gd_modal_result *r = NULL;
    gd_error err;
    if (gd_modal_solve(f->s, &o, &r, &err)) fprintf(stderr, "  %s\n", err.message);
    return r;
}

/* Largest |lambda_a - lambda_b| / max(omega_n, 1) over the modes, and the energy shares'
 * largest difference (lateral, torsional, axial, tilt). */
static double deviation(const gd_modal_result *a, const gd_modal_result *b, double *share)
{
    double dev = 0;
    *share = 0;
    for (int j = 0; j < a->nmodes && j < b->nmodes; j++) {
        const gd_mode *x = &a->modes[j], *y = &b->modes[j];
        dev = fmax(dev, hypot(x->lambda_re - y->lambda_re, x->lambda_im - y->lambda_im) /
                            fmax(y->omega_n, 1.0));
        if (!x->rigid_body)
            for (int k = 0; k < GD_NMOTIONS; k++)
                *share = fmax(*share, fabs(x->energy_share[k] - y->energy_share[k]));
    }
    return dev;
}

/* Sparse and dense agree, and AUTO picks `expect_sparse`. Eigenvalues to 1e-8 relative:
 * the Krylov-Schur residual tolerance is 1e-9 of the shifted operator (measured
 * deviations 1e-11 to 5e-10); energy shares to 1e-6 (they depend on the shapes, whose
 * error is the square root of the eigenvalues' for close pairs at most). */
static void check_model(gd_test_state *gd_ts_, int per, int undamped, double speed, int nmodes,
                        int expect_sparse)
{
    fx f;
    REQUIRE(load_rig(&f, per, undamped));
    gd_modal_result *d = solve(&f, speed, nmodes, GD_EIG_DENSE),
                    *s = solve(&f, speed, nmodes, GD_EIG_SPARSE),
                    *a = solve(&f, speed, nmodes, GD_EIG_AUTO);
    REQUIRE(d && s && a);
    CHECK(!d->sparse && s->sparse);
    CHECK(a->sparse == expect_sparse);
    CHECK(d->nmodes == nmodes && s->nmodes == nmodes && a->nmodes == nmodes);
    CHECK(d->damped == s->damped);
    double share, dev = deviation(s, d, &share);
    CHECK_ABS(dev, 0.0, 1e-8);
    CHECK_ABS(share, 0.0, 1e-6);
    for (int j = 0; j < nmodes; j++) {
        CHECK(s->modes[j].rigid_body == d->modes[j].rigid_body);
        CHECK(s->modes[j].whirl == d->modes[j].whirl);
    }
    gd_modal_free(d);
    gd_modal_free(s);
    gd_modal_free(a);
    fx_free(&f);
}

/* 30 DOFs, undamped at rest: dsygvx on 30 x 30 (measured 0.17 ms) beats the sparse
 * set-up (0.22 ms): dense. */
TEST(auto_picks_dense_for_a_small_undamped_model)
{
    check_model(gd_ts_, 1, 1, 0.0, 6, 0);
}

/* 30 DOFs, damped at 3000 rpm: the 60-state dgeev (0.59 ms) loses to sparse (0.24 ms). */
TEST(auto_picks_sparse_for_a_small_damped_model)
{
    check_model(gd_ts_, 1, 0, 314.159, 6, 1);
}

/* 170 DOFs (the example rig) at 3000 rpm, 12 modes; and at rest, undamped. */
TEST(auto_picks_sparse_for_the_rig)
{
    check_model(gd_ts_, 8, 0, 314.159, 12, 1);
    check_model(gd_ts_, 8, 1, 0.0, 12, 1);
}

/* Too many modes for a Krylov basis smaller than the state, or all modes, or left
 * vectors: dense whatever the cost. */
TEST(auto_is_dense_where_sparse_cannot_serve)
{
    fx f;
    REQUIRE(load_rig(&f, 1, 0));
    gd_modal_result *r = solve(&f, 314.159, 8, GD_EIG_AUTO); /* 2 x 8 + 16 > 30 */
    REQUIRE(r);
    CHECK(!r->sparse);
    gd_modal_free(r);
    r = solve(&f, 314.159, 0, GD_EIG_AUTO);
    REQUIRE(r);
    CHECK(!r->sparse && r->nmodes == 30);
    gd_modal_free(r);
    gd_modal_options o;
    gd_modal_options_init(&o); /* want_left */
    o.nmodes = 6;
    o.speed = 314.159;
    REQUIRE(gd_modal_solve(f.s, &o, &r, NULL) == GD_OK);
    CHECK(!r->sparse && r->left_re);
    gd_modal_free(r);
    gd_error err;
    o.method = GD_EIG_SPARSE;
    CHECK(gd_modal_solve(f.s, &o, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "right eigenvectors only") != NULL);
    o.want_left = 0;
    o.nmodes = 0;
    CHECK(gd_modal_solve(f.s, &o, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "lowest modes") != NULL);
    fx_free(&f);
}

/* Sparse and dense on a loaded model at rest: the same modes, the same eigenvalues to
 * 1e-8 relative (as check_model), and `copies` of them within 0.01 Hz of f_rep (the
 * next distinct mode is 30 Hz or more away). */
static void check_repeated(gd_test_state *gd_ts_, gd_model *m, gd_system *s, int nmodes,
                           double f_rep, int copies)
{
    fx f = {m, s};
    gd_modal_result *d = solve(&f, 0.0, nmodes, GD_EIG_DENSE),
                    *sp = solve(&f, 0.0, nmodes, GD_EIG_SPARSE);
    REQUIRE(d && sp);
    CHECK(sp->sparse && sp->nmodes == nmodes && d->nmodes == nmodes);
    double share, dev = deviation(sp, d, &share);
    CHECK_ABS(dev, 0.0, 1e-8);
    int nd = 0, ns = 0;
    for (int j = 0; j < nmodes; j++) {
        nd += fabs(d->modes[j].frequency_hz - f_rep) < 0.01;
        ns += fabs(sp->modes[j].frequency_hz - f_rep) < 0.01;
    }
    CHECK(nd == copies);
    CHECK(ns == copies);
    gd_modal_free(d);
    gd_modal_free(sp);
}

/* An isotropic rotor at rest has exact double lateral pairs; a single Krylov start
 * vector meets each double eigenspace in one direction only, and the sparse solver
 * used to return one copy of 745.32 Hz and the next mode in the other's place. */
TEST(sparse_finds_the_double_pairs_of_a_rotor_at_rest)
{
    fx f;
    gd_error err;
    REQUIRE(gd_model_load("tests/plot/study.yaml", &f.m, &err) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    check_repeated(gd_ts_, f.m, f.s, 7, 745.32, 2); /* modes 6 and 7 (1: rigid body) */
    fx_free(&f);
}

/* Three identical decoupled torsional oscillators (a triple eigenvalue: 3000 N m/rad on
 * 0.02 kg m^2, omega_n / 2 pi = 61.64 Hz) below ten stiffer distinct ones; damped, so
 * the state-space form is used. */
TEST(sparse_finds_a_triple_eigenvalue)
{
    char yaml[4096];
    int len = snprintf(yaml, sizeof yaml, "dofs: [rz]\nshafts: [{name: s, nodes: [");
    for (int i = 0; i < 13; i++)
        len += snprintf(yaml + len, sizeof yaml - len, "%s{name: n%d}", i ? ", " : "", i);
    len += snprintf(yaml + len, sizeof yaml - len, "]}]\ndisks:\n");
    for (int i = 0; i < 13; i++)
        len += snprintf(yaml + len, sizeof yaml - len, "  - {node: n%d, polar_inertia: 0.02}\n", i);
    len += snprintf(yaml + len, sizeof yaml - len, "springs:\n");
    for (int i = 0; i < 13; i++)
        len += snprintf(yaml + len, sizeof yaml - len,
                        "  - {node: n%d, dof: rz, stiffness: %g, damping: 0.01}\n", i,
                        i < 3 ? 3000.0 : 3000.0 * (1.5 + 0.25 * i));
    REQUIRE(len < (int)sizeof yaml);
    fx f;
    gd_error err;
    REQUIRE(gd_model_load_string(yaml, "triple.yaml", &f.m, &err) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    check_repeated(gd_ts_, f.m, f.s, 6, sqrt(3000 / 0.02) / (2 * 3.14159265358979), 3);
    fx_free(&f);
}

/* A finely meshed shaft (issue 23): 333 Timoshenko elements of 1 mm on a 50 mm shaft,
 * 2004 DOFs, undamped at rest. The element frequencies are 1e4 times the lowest mode's,
 * which once put the automatic shift far above every wanted mode (sparse_modes.c).
 * Sparse and dense agree to 1e-8 relative (measured 5.6e-10), the double lateral pairs
 * included, and AUTO picks sparse (measured 0.02 s against 1.8 s). */
TEST(sparse_matches_dense_on_a_fine_mesh)
{
    static const char yaml[] = "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"
                               "shafts:\n"
                               "  - {name: shaft, material: steel, elements_per_section: 333,\n"
                               "     sections: [{length: 0.333, outer_diameter: 0.05}],\n"
                               "     nodes: [{name: left, at: 0}, {name: right, at: 0.333}]}\n"
                               "bearings:\n"
                               "  - {node: left, k: 1e8, kzz: 1e8}\n"
                               "  - {node: right, k: 1e8, kzz: 1e8}\n";
    fx f;
    gd_error err;
    REQUIRE(gd_model_load_string(yaml, "fine.yaml", &f.m, &err) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    REQUIRE(f.s->ndof == 2004);
    gd_modal_result *d = solve(&f, 0.0, 10, GD_EIG_DENSE), *sp = solve(&f, 0.0, 10, GD_EIG_SPARSE),
                    *a = solve(&f, 0.0, 10, GD_EIG_AUTO);
    REQUIRE(d && sp && a);
    CHECK(sp->sparse && a->sparse && !d->sparse);
    REQUIRE(sp->nmodes == 10 && d->nmodes == 10);
    double share, dev = deviation(sp, d, &share);
    CHECK_ABS(dev, 0.0, 1e-8);
    printf("  fine mesh: sparse vs dense %.2e\n", dev);
    CHECK(sp->modes[0].rigid_body && d->modes[0].rigid_body);
    for (int j = 1; j < 10; j++)
        CHECK(!sp->modes[j].rigid_body);
    gd_modal_free(d);
    gd_modal_free(sp);
    gd_modal_free(a);
    fx_free(&f);
}

/* The 10 m shaft of issue 23 at 10,002 DOFs (1,666 elements of 6 mm on a 0.2 m shaft),
 * damped by its bearings, sparse only (the dense state space would take minutes). The
 * old automatic shift, 10^-3 of an element's frequency (852 rad/s, 34 times the lowest
 * mode), left the x/y pair of the lowest mode with damping ratios 2 % apart (7.764e-7
 * and 7.616e-7) and at 100k DOFs made one of them unstable; an isotropic shaft's pair
 * has equal ones. Now 6e-6 apart: asserted at 1e-3. The pair's frequencies agree to
 * 1e-8, and the lowest lies within 1e-7 of 3.96281905 Hz (scipy's ARPACK and Lanczos
 * on the exported matrices at several shifts: 3.9628190 to 3.9628192, the rounding of
 * this mesh, docs/analyses.md). */
TEST(sparse_keeps_the_damping_of_a_fine_mesh)
{
    static const char yaml[] =
        "materials: {steel: {density: 7800, E: 2.0e11, poisson: 0.3}}\n"
        "shafts:\n"
        "  - {name: shaft, material: steel, elements_per_section: 833,\n"
        "     sections: [{length: 5, outer_diameter: 0.2}, {length: 5, outer_diameter: 0.2}],\n"
        "     nodes: [{name: left, at: 0}, {name: right, at: 10}]}\n"
        "bearings:\n"
        "  - {node: left, k: 1e8, c: 1e3, kzz: 1e8, czz: 1e3}\n"
        "  - {node: right, k: 1e8, c: 1e3, kzz: 1e8, czz: 1e3}\n";
    fx f;
    gd_error err;
    REQUIRE(gd_model_load_string(yaml, "shaft10k.yaml", &f.m, &err) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    REQUIRE(f.s->ndof == 10002);
    gd_modal_result *r = solve(&f, 0.0, 10, GD_EIG_SPARSE);
    REQUIRE(r && r->sparse && r->damped && r->nmodes == 10);
    CHECK(r->modes[0].rigid_body);
    const gd_mode *a = &r->modes[1], *b = &r->modes[2];
    CHECK_REL(b->frequency_hz, a->frequency_hz, 1e-8);
    CHECK_REL(b->damping_ratio, a->damping_ratio, 1e-3);
    CHECK_REL(a->frequency_hz, 3.96281905, 1e-7);
    printf("  fine shaft: pair %.10g / %.10g Hz, damping %.6g / %.6g\n", a->frequency_hz,
           b->frequency_hz, a->damping_ratio, b->damping_ratio);
    for (int j = 0; j < 10; j++)
        CHECK(!r->modes[j].unstable);
    gd_modal_free(r);
    fx_free(&f);
}

RUN_TESTS(T(auto_picks_dense_for_a_small_undamped_model),
          T(auto_picks_sparse_for_a_small_damped_model), T(auto_picks_sparse_for_the_rig),
          T(auto_is_dense_where_sparse_cannot_serve),
          T(sparse_finds_the_double_pairs_of_a_rotor_at_rest), T(sparse_finds_a_triple_eigenvalue),
          T(sparse_matches_dense_on_a_fine_mesh), T(sparse_keeps_the_damping_of_a_fine_mesh))
