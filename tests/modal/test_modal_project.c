/* The sparse modes by projection (src/modal/sparse_project.c, issue 35): block shift-invert
 * Lanczos on the undamped problem, the damped one projected on its Ritz vectors, refined and
 * checked for completeness by the continuation. On the 366-DOF MMT rig
 * (bench/models/rig366.yaml): at rest its lateral modes are exact x-y doubles (isotropic
 * bearings, no gyroscopic split), which a single Lanczos start vector finds once; at 3000
 * rpm they split. Both give every mode LAPACK gives, to the tolerance. And the fallback rule:
 * an undamped solve and overdamped wanted modes are declined (NULL), and gd_modal_solve then
 * still gives LAPACK's modes by Krylov-Schur. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/modal.h"
#include "geardyn/model_file.h"
#include "harness.h"
#include "modal/modal_impl.h"

typedef struct fx {
    gd_model *m;
    gd_system *s;
} fx;

static int load(fx *f, const char *set)
{
    const char *sets[] = {set};
    gd_load_options lo = {set ? 1 : 0, sets};
    gd_error err;
    if (gd_model_load_opts("bench/models/rig366.yaml", &lo, &f->m, &err) ||
        gd_system_build(f->m, &f->s, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        return 0;
    }
    return 1;
}

static void unload(fx *f)
{
    gd_system_free(f->s);
    gd_model_free(f->m);
}

static gd_modal_options options(double speed, int nmodes, gd_modal_kind kind, gd_eig_method m)
{
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = speed;
    o.nmodes = nmodes;
    o.want_left = 0;
    o.kind = kind;
    o.method = m;
    return o;
}

/* gd_sparse_modes_projected alone on sys: its result (NULL when it declines), residuals
 * filled */
static gd_modal_result *projected(const gd_system *sys, const gd_modal_options *o)
{
    gd_dynmat a;
    gd_splu_symbolic sym;
    gd_sparse_ws ws;
    gd_modal_result *r = NULL;
    gd_error err;
    if (gd_dynmat_build(sys, &a, &err)) return NULL;
    if (!gd_splu_analyze(&a.pat, &sym, &err)) {
        if (!gd_sparse_ws_init(&ws, &a, o->nmodes)) {
            if (!gd_sparse_modes_projected(&a, &sym, o, &ws, &r, &err) && r &&
                gd_modal_residuals_on(&a, ws.k, r->damped ? ws.d : NULL, r, NULL, NULL)) {
                gd_modal_free(r);
                r = NULL;
            }
            gd_sparse_ws_free(&ws);
        }
        gd_splu_symbolic_free(&sym);
    }
    gd_dynmat_free(&a);
    return r;
}

/* r against LAPACK's modes of the same problem: the same count and rigid-body modes,
 * frequencies and damping ratios within 1e-8 (10 times the default residual 1e-9: an
 * eigenvalue's error is its residual times a condition number below 10 here) */
static void against_dense(gd_test_state *gd_ts_, const fx *f, const gd_modal_result *r,
                          const gd_modal_options *o, const char *what)
{
    gd_modal_options od = *o;
    od.method = GD_EIG_DENSE;
    gd_modal_result *de = NULL;
    gd_error err;
    REQUIRE(gd_modal_solve(f->s, &od, &de, &err) == GD_OK);
    CHECK(r->nmodes == o->nmodes && de->nmodes == o->nmodes);
    double worst = 0, worst_res = 0;
    for (int j = 0; j < r->nmodes && j < de->nmodes; j++) {
        const gd_mode *a = &r->modes[j], *b = &de->modes[j];
        CHECK(a->rigid_body == b->rigid_body);
        if (a->rigid_body || b->rigid_body) continue;
        double d = fabs(a->omega_n - b->omega_n) / b->omega_n;
        CHECK(d <= 1e-8);
        CHECK(fabs(a->damping_ratio - b->damping_ratio) <= 1e-8);
        CHECK(a->residual <= fmax(GD_MODAL_TOL_DEFAULT, 100 * a->residual_floor));
        if (d > 1e-8) printf("    mode %d: %.15g against %.15g\n", j + 1, a->omega_n, b->omega_n);
        worst = fmax(worst, d);
        worst_res = fmax(worst_res, a->residual);
    }
    printf("  %s: frequencies within %.1e of LAPACK's, largest residual %.1e\n", what, worst,
           worst_res);
    gd_modal_free(de);
}

TEST(projection_finds_every_copy_of_double_modes)
{
    fx f;
    REQUIRE(load(&f, NULL));
    const double speeds[] = {0, 314.159265358979 /* 3000 rpm */};
    for (int i = 0; i < 2; i++) {
        gd_modal_options o = options(speeds[i], 12, GD_MODAL_AUTO, GD_EIG_AUTO);
        gd_modal_result *r = projected(f.s, &o);
        /* the projection vouched for its modes (a missed copy fails the completeness check) */
        REQUIRE(r != NULL);
        CHECK(r->sparse && r->damped);
        against_dense(gd_ts_, &f, r, &o, i ? "3000 rpm" : "at rest (x-y doubles)");
        /* the library's entry takes the same path */
        gd_modal_result *s = NULL;
        gd_error err;
        o.method = GD_EIG_SPARSE;
        REQUIRE(gd_modal_solve(f.s, &o, &s, &err) == GD_OK);
        for (int j = 0; j < s->nmodes; j++)
            CHECK(s->modes[j].lambda_im == r->modes[j].lambda_im);
        gd_modal_free(s);
        gd_modal_free(r);
    }
    unload(&f);
}

TEST(projection_declines_what_it_cannot_vouch_for)
{
    fx f;
    REQUIRE(load(&f, NULL));
    /* undamped: declined (Krylov-Schur's conservative problem) */
    gd_modal_options o = options(0, 12, GD_MODAL_UNDAMPED, GD_EIG_SPARSE);
    CHECK(projected(f.s, &o) == NULL);
    unload(&f);
    /* bearings damped at 1e6 N s/m: the axial modes on their kzz springs (mass ~ 1 kg per
     * node, kzz 5e7 N/m) are overdamped, real pairs in the projection */
    REQUIRE(load(&f, "bearings.*.czz=1e6"));
    o = options(0, 12, GD_MODAL_AUTO, GD_EIG_SPARSE);
    gd_modal_result *r = projected(f.s, &o);
    CHECK(r == NULL);
    gd_modal_free(r);
    gd_modal_result *s = NULL;
    gd_error err;
    REQUIRE(gd_modal_solve(f.s, &o, &s, &err) == GD_OK);
    int over = 0;
    for (int j = 0; j < s->nmodes; j++)
        over += s->modes[j].overdamped;
    CHECK(over > 0);
    /* each underdamped elastic mode is one of LAPACK's (the two solvers order the real
     * eigenvalues of the overdamped pairs differently: their members are modes each) */
    gd_modal_options od = o;
    od.method = GD_EIG_DENSE;
    od.nmodes = 40;
    gd_modal_result *de = NULL;
    REQUIRE(gd_modal_solve(f.s, &od, &de, &err) == GD_OK);
    for (int j = 0; j < s->nmodes; j++) {
        const gd_mode *a = &s->modes[j];
        if (a->rigid_body || a->overdamped) continue;
        double best = INFINITY;
        for (int i = 0; i < de->nmodes; i++)
            best = fmin(best, fabs(de->modes[i].omega_n - a->omega_n) / a->omega_n);
        CHECK(best <= 1e-8);
    }
    gd_modal_free(de);
    gd_modal_free(s);
    unload(&f);
}

RUN_TESTS(T(projection_finds_every_copy_of_double_modes),
          T(projection_declines_what_it_cannot_vouch_for))
