/* The static start of a transient run on a model whose laws carry the static load
 * (issue 35 item 6): rolling bearings with clearance give the linear stiffness nothing
 * in their directions, so the start is the static analysis's equilibrium (same solver,
 * laws and holds as `geardyn static`) under the run's loads. The transient leaves
 * gravity out, so static is compared with gravity off. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model_file.h"
#include "geardyn/static.h"
#include "geardyn/transient_model.h"
#include "harness.h"

typedef struct fx {
    gd_model *m;
    gd_system *s;
    gd_transient_model *tm;
    gd_transient *tr;
} fx;

/* unbalances 0: without the model's unbalances (their forces at t = 0 are among the
 * run's loads, not among static's mean loads) */
static int load(fx *f, const char *path, int unbalances)
{
    gd_error err;
    memset(f, 0, sizeof *f);
    gd_status st = gd_model_load(path, &f->m, &err);
    if (!st && !unbalances) f->m->nunbalances = 0;
    if (!st) st = gd_system_build(f->m, &f->s, &err);
    if (!st) st = gd_transient_model_build(f->s, &f->tm, &err);
    if (!st) st = gd_transient_new(f->s, &f->tm->spec, f->m->speed, &f->tr, &err);
    if (st) fprintf(stderr, "  %s: %s (%s)\n", path, err.message, err.hint);
    return st == GD_OK;
}

static void unload(fx *f)
{
    gd_transient_free(f->tr);
    gd_transient_model_free(f->tm);
    gd_system_free(f->s);
    gd_model_free(f->m);
}

/* The run's records of every DOF's displacement at t = 0 from the static start (NULL
 * with the error printed when the start fails), nout >= 2 samples over t_end. */
static gd_transient_result *start(fx *f, double t_end, int nrec, gd_tr_record *rec)
{
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = t_end;
    o.record_from = 0;
    o.output_interval = t_end / 2;
    o.init = GD_TR_INIT_STATIC;
    gd_transient_result *r = NULL;
    gd_error err;
    if (gd_transient_run(f->tr, &o, rec, nrec, &r, &err))
        fprintf(stderr, "  %s (%s)\n", err.message, err.hint);
    return r;
}

static gd_static_result *static_without_gravity(const fx *f)
{
    gd_static_options so;
    gd_static_options_init(&so);
    so.gravity = 0;
    gd_static_result *res = NULL;
    gd_error err;
    if (gd_static_run(f->s, &so, &res, &err)) fprintf(stderr, "  static: %s\n", err.message);
    return res;
}

/* The three-stage reducer (rolling_bearing_5dof with 5 um clearance, the motor
 * prescribed, an 800 N m brake): CVODE failed at t = 0 from the old start (its
 * iteration matrix without the bearings is singular laterally). Now every DOF but the
 * train's rotation starts at static's equilibrium (to rounding). */
TEST(reducer_starts_at_static)
{
    fx f;
    REQUIRE(load(&f, "examples/reducer_three_stage.yaml", 0));
    const int n = f.s->ndof;
    gd_tr_record *rec = calloc((size_t)n + 1, sizeof *rec);
    REQUIRE(rec);
    for (int d = 0; d < n; d++)
        rec[d] = (gd_tr_record){GD_REC_DISP, d, 0};
    rec[n] = (gd_tr_record){GD_REC_MESH_FORCE, 3, 0}; /* stage3 */
    gd_static_result *st = static_without_gravity(&f);
    REQUIRE(st);
    gd_transient_result *r = start(&f, 2e-5, n + 1, rec);
    CHECK(r != NULL);
    if (r) {
        double qmax = 0, dmax = 0;
        for (int d = 0; d < n; d++) {
            if (f.s->dof_type[d] == GD_RZ) continue; /* the train turns from t = 0 */
            qmax = fmax(qmax, fabs(st->q[d]));
            dmax = fmax(dmax, fabs(r->values[(size_t)d * r->nout] - st->q[d]));
        }
        CHECK(qmax > 1e-6); /* the brake loads the bearings: micrometres */
        CHECK(dmax <= 1e-9 * qmax);
        /* static's stage3 force, 7993.8 N with gravity (the example's hand check), at the
           mesh stiffness of t = 0 (the TVMS) instead of its mean: within its ripple */
        CHECK_REL(r->values[(size_t)n * r->nout], st->meshes[3].force, 0.03);
        CHECK(st->meshes[3].force > 7000 && st->meshes[3].force < 9000);
    }
    gd_transient_result_free(r);
    gd_static_free(st);
    free(rec);
    unload(&f);
}

/* The rig on 5-DOF ball bearings with clearance and no load in the run (its gravity is
 * the static analysis's only): "a free motion other than the train's rotation" before;
 * now it starts at rest, static's equilibrium without gravity. */
TEST(rig_free_train_starts)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018_geometry.yaml", 1));
    gd_tr_record rec[2] = {{GD_REC_DISP, 1, 0}, {GD_REC_MESH_FORCE, 0, 0}};
    gd_static_result *st = static_without_gravity(&f);
    REQUIRE(st);
    gd_transient_result *r = start(&f, 1e-4, 2, rec);
    CHECK(r != NULL);
    if (r) {
        CHECK_ABS(r->values[0], st->q[1], 1e-12);
        CHECK_ABS(r->values[r->nout], st->meshes[0].force, 1e-6);
    }
    gd_transient_result_free(r);
    gd_static_free(st);
    unload(&f);
}

RUN_TESTS(T(reducer_starts_at_static), T(rig_free_train_starts))
