/* The transient on the condensed structure (src/transient/condensed.c, docs/transient.md
 * "Condensed transient") against the full problem:
 *  - every mode kept (exact condensation): a rattling input gear and idler
 *    (tests/transient/condensed_pair.yaml: backlash mesh, churning drag, firing torque)
 *    over 0.1 s with about a hundred located contact changes, both at rtol 1e-11: the same
 *    contact events at the same times and the same mesh force and idler speed records,
 *    to 1e-8 of their peaks;
 *  - the recovered DOFs at the end (q_end, v_end) of both;
 *  - refusals: a prescribed DOF, generalized-alpha. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct fx {
    gd_model *m;
    gd_system *s;
    gd_transient_model *tm;
} fx;

static int load(fx *f, const char *path)
{
    gd_error err;
    memset(f, 0, sizeof *f);
    gd_status st = gd_model_load(path, &f->m, &err);
    if (!st) st = gd_system_build(f->m, &f->s, &err);
    if (!st) st = gd_transient_model_build(f->s, &f->tm, &err);
    if (st) fprintf(stderr, "  %s: %s (%s)\n", path, err.message, err.field);
    return st == GD_OK;
}

static void unload(fx *f)
{
    gd_transient_model_free(f->tm);
    gd_system_free(f->s);
    gd_model_free(f->m);
}

static double peak_diff(const gd_transient_result *a, const gd_transient_result *b, int r,
                        double *peak)
{
    double p = 0, e = 0;
    for (int k = 0; k < a->nout; k++) {
        p = fmax(p, fabs(a->values[(size_t)r * a->nout + k]));
        e = fmax(e, fabs(a->values[(size_t)r * a->nout + k] - b->values[(size_t)r * b->nout + k]));
    }
    *peak = p;
    return e;
}

TEST(every_mode_kept_equals_the_full_problem_through_impacts)
{
    fx f;
    REQUIRE(load(&f, "tests/transient/condensed_pair.yaml"));
    const double W = 800 * M_PI / 30;
    gd_transient *full = NULL, *cond = NULL;
    gd_error err;
    REQUIRE(gd_transient_new(f.s, &f.tm->spec, W, &full, &err) == GD_OK);
    if (gd_transient_new_condensed(f.s, &f.tm->spec, W, 0.0, &cond, &err))
        fprintf(stderr, "  %s (%s)\n", err.message, err.field);
    REQUIRE(cond);
    gd_tr_condensed_info ci;
    CHECK(gd_transient_condensed_info(cond, &ci) == 1);
    CHECK(ci.ncoords == 2); /* g1 (mesh, load) and g2 (mesh, drag) */
    CHECK(ci.ndiscarded == 0);
    CHECK(gd_transient_nstates(cond) == 6); /* three elastic modes, no rigid one */
    const int g2 = gd_system_dof(f.s, gd_model_find_node(f.m, "g2"), GD_RZ);
    gd_tr_record rec[3] = {{GD_REC_MESH_FORCE, 0, 0},
                           {GD_REC_VEL, g2, 0},
                           {GD_REC_MESH_DEFLECTION, 0, 0}};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.1;
    o.output_interval = 1e-4;
    o.rtol = 1e-11;
    o.atol_q = 1e-16;
    o.atol_v = 1e-13;
    gd_transient_result *a = NULL, *b = NULL;
    REQUIRE(gd_transient_run(full, &o, rec, 3, &a, NULL) == GD_OK);
    REQUIRE(gd_transient_run(cond, &o, rec, 3, &b, &err) == GD_OK);
    /* a non-smooth run: many located contact changes, the same in both */
    CHECK(a->ncontact_events > 20);
    CHECK(a->ncontact_events == b->ncontact_events);
    double et = 0;
    int same_state = 1;
    for (int i = 0; i < a->ncontact_events && i < b->ncontact_events; i++) {
        et = fmax(et, fabs(a->contact_events[i].t - b->contact_events[i].t));
        same_state &= a->contact_events[i].to == b->contact_events[i].to;
    }
    CHECK(same_state);
    CHECK_ABS(et, 0.0, 1e-9); /* s */
    for (int r = 0; r < 3; r++) {
        double peak, e = peak_diff(a, b, r, &peak);
        CHECK(peak > 0);
        fprintf(stderr, "  record %d: peak %.4g, difference %.3g (%.2g of the peak)\n", r, peak, e,
                e / peak);
        CHECK_ABS(e / peak, 0.0, 1e-8);
    }
    double qmax = 0, eq = 0, vmax = 0, ev = 0;
    for (int i = 0; i < a->ndof; i++) {
        qmax = fmax(qmax, fabs(a->q_end[i]));
        vmax = fmax(vmax, fabs(a->v_end[i]));
        eq = fmax(eq, fabs(a->q_end[i] - b->q_end[i]));
        ev = fmax(ev, fabs(a->v_end[i] - b->v_end[i]));
    }
    CHECK_ABS(eq / qmax, 0.0, 1e-8);
    CHECK_ABS(ev / vmax, 0.0, 1e-8);
    CHECK(strstr(b->method_note, "condensed") != NULL);
    gd_transient_result_free(a);
    gd_transient_result_free(b);
    gd_transient_free(full);
    gd_transient_free(cond);
    unload(&f);
}

TEST(refusals_name_the_field)
{
    fx f;
    REQUIRE(load(&f, "examples/rattle_idle.yaml")); /* a prescribed flywheel */
    gd_transient *tr = NULL;
    gd_error err;
    CHECK(gd_transient_new_condensed(f.s, &f.tm->spec, 83.8, 0.0, &tr, &err) == GD_EINPUT);
    CHECK(!tr);
    CHECK_STR(err.field, "prescribed");
    unload(&f);
    REQUIRE(load(&f, "tests/transient/condensed_pair.yaml"));
    REQUIRE(gd_transient_new_condensed(f.s, &f.tm->spec, 83.8, 0.0, &tr, &err) == GD_OK);
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.01;
    o.method = GD_TR_GEN_ALPHA;
    gd_transient_result *r = NULL;
    CHECK(gd_transient_run(tr, &o, NULL, 0, &r, &err) == GD_EINPUT);
    CHECK_STR(err.field, "method");
    o.method = GD_TR_BDF;
    o.init = GD_TR_INIT_STATIC;
    CHECK(gd_transient_run(tr, &o, NULL, 0, &r, &err) == GD_EINPUT);
    CHECK_STR(err.field, "start");
    CHECK(!r);
    gd_transient_free(tr);
    unload(&f);
}

RUN_TESTS(T(every_mode_kept_equals_the_full_problem_through_impacts), T(refusals_name_the_field))
