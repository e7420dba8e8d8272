/* Modal reduction of the transient problem (src/transient/reduce.c): the reduced
 * model's frequencies below the cutoff against the full model's, and an unbalance
 * run-up of the reduced model against the full one, on the MMT rig (170 DOFs). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>

#include "geardyn/modal.h"
#include "geardyn/model_file.h"
#include "geardyn/transient.h"
#include "harness.h"
#include "transient/transient_impl.h"

#define TWO_PI 6.28318530717958647692

typedef struct fixture {
    gd_model *m;
    gd_system *s;
} fixture;

static const char *sets[] = {("unbalances=[{node: gear48, amount: 1e-5}, {node: gear32, amount: "
                              "5e-6, phase: 90 deg}]"),
                             "bearings.*.c=0", "meshes.mesh.damping=0"};

static int fx_load(fixture *f, int nset)
{
    gd_error err;
    gd_load_options lo = {nset, sets};
    memset(f, 0, sizeof *f);
    if (gd_model_load_opts("examples/rig2018.yaml", &lo, &f->m, &err) ||
        gd_system_build(f->m, &f->s, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        return 0;
    }
    return 1;
}

static void fx_free(fixture *f)
{
    gd_system_free(f->s);
    gd_model_free(f->m);
}

static gd_transient *problem(const fixture *f, double cutoff)
{
    gd_transient_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.unbalances = 1;
    gd_transient *tr = NULL;
    gd_error err;
    gd_status st = cutoff > 0 ? gd_transient_new_reduced(f->s, &spec, 314.159265, cutoff, &tr, &err)
                              : gd_transient_new(f->s, &spec, 314.159265, &tr, &err);
    if (st) fprintf(stderr, "  %s\n", err.message);
    return tr;
}

/* Undamped frequencies of the reduced M, K (at rest: no gyroscopics) against the full
 * model's, cutoff 5 kHz: Craig-Bampton bounds them from above; measured errors 1e-5 to
 * 3e-5 below a fifth of the cutoff (bound 1e-4), up to 1.1e-3 below half of it (bound
 * 2e-3): the truncation error grows with (omega / cutoff)^2 and more. */
TEST(reduced_frequencies_below_the_cutoff)
{
    fixture f;
    REQUIRE(fx_load(&f, 3));
    gd_transient_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.unbalances = 1;
    gd_transient *tr = NULL;
    double cutoff = TWO_PI * 5000;
    REQUIRE(gd_transient_new_reduced(f.s, &spec, 0.0, cutoff, &tr, NULL) == GD_OK);
    int nkept, nmodes, nr = gd_transient_reduced_size(tr, &nkept, &nmodes);
    CHECK(nr == nkept + nmodes && nr < f.s->ndof / 3);
    double *M = calloc((size_t)nr * nr, sizeof *M), *K = calloc((size_t)nr * nr, sizeof *K),
           *w = malloc((size_t)nr * sizeof *w);
    REQUIRE(M && K && w);
    for (int j = 0; j < nr; j++) {
        for (int p = tr->M->p[j]; p < tr->M->p[j + 1]; p++)
            M[tr->M->i[p] + (size_t)j * nr] = tr->M->x[p];
        for (int p = tr->K->p[j]; p < tr->K->p[j + 1]; p++)
            K[tr->K->i[p] + (size_t)j * nr] = tr->K->x[p];
    }
    REQUIRE(LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, 'N', 'U', nr, K, nr, M, nr, w) == 0);
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.kind = GD_MODAL_UNDAMPED;
    o.want_left = 0;
    o.nmodes = 24; /* the lowest, by the sparse solver: cheap under valgrind */
    gd_modal_result *r = NULL;
    REQUIRE(gd_modal_solve(f.s, &o, &r, NULL) == GD_OK);
    int checked = 0;
    for (int k = 0; k < nr && k < r->nmodes; k++) {
        double full = r->modes[k].omega_n, red = sqrt(fmax(w[k], 0.0));
        if (full > cutoff / 2) break;
        if (r->modes[k].rigid_body) { /* zero to round-off (valgrind's: 4e-4 rad/s) */
            CHECK_ABS(red, 0.0, 1e-2);
            continue;
        }
        CHECK(red >= full * (1 - 1e-9));
        CHECK_REL(red, full, full < cutoff / 5 ? 1e-4 : 2e-3);
        checked++;
    }
    CHECK(checked >= 10);
    gd_modal_free(r);
    free(M);
    free(K);
    free(w);
    gd_transient_free(tr);
    fx_free(&f);
}

/* Unbalance switched on from rest (3000 rpm, damped rig), gen-alpha h = 1e-5 s over
 * 0.02 s: the reduced model (cutoff 5 kHz) against the full one on a kept DOF (gear x)
 * and an expanded interior one (bearing y). Measured 1.5e-4 and 2.0e-2 of the peaks
 * (the bearing's small motion, 1 % of the gear's, carries more of the modes near and
 * above the cutoff); bounds 3e-4 and 4e-2. */
TEST(reduced_unbalance_response_matches_the_full_model)
{
    fixture f;
    REQUIRE(fx_load(&f, 1));
    gd_transient *full = problem(&f, 0), *red = problem(&f, TWO_PI * 5000);
    REQUIRE(full && red);
    gd_tr_record rec[2] = {
        {GD_REC_DISP, gd_system_dof(f.s, gd_model_find_node(f.m, "gear48"), GD_X), 0},
        {GD_REC_DISP, gd_system_dof(f.s, gd_model_find_node(f.m, "brg_d1"), GD_Y), 0}};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.method = GD_TR_GEN_ALPHA;
    o.step = 1e-5;
    o.t_end = 0.02;
    o.output_interval = 1e-4;
    gd_transient_result *a = NULL, *b = NULL;
    REQUIRE(gd_transient_run(full, &o, rec, 2, &a, NULL) == GD_OK);
    REQUIRE(gd_transient_run(red, &o, rec, 2, &b, NULL) == GD_OK);
    double tol[2] = {3e-4, 4e-2};
    for (int r = 0; r < 2; r++) {
        double peak = 0, e = 0;
        for (int k = 0; k < a->nout; k++) {
            peak = fmax(peak, fabs(a->values[r * a->nout + k]));
            e = fmax(e, fabs(a->values[r * a->nout + k] - b->values[r * a->nout + k]));
        }
        CHECK(peak > 0);
        CHECK_ABS(e / peak, 0.0, tol[r]);
    }
    CHECK(b->ndof == f.s->ndof);
    gd_transient_result_free(a);
    gd_transient_result_free(b);
    gd_transient_free(full);
    gd_transient_free(red);
    fx_free(&f);
}

RUN_TESTS(T(reduced_frequencies_below_the_cutoff),
          T(reduced_unbalance_response_matches_the_full_model))
