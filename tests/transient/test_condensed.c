/* The transient on the condensed structure (src/transient/condensed.c, docs/transient.md
 * "Condensed transient") against the full problem:
 *  - every mode kept (exact condensation), tests/transient/condensed_pair.yaml (a rattling
 *    input gear and idler: backlash mesh, churning drag, firing torque, flywheel on a
 *    governor spring): at 30 states in each of the mesh's three contact modes, the
 *    accelerations of every DOF recovered from the condensed state's rate against the full
 *    problem's right-hand side at the recovered state, and the contact switch functions
 *    of both: equal to 1e-8 (the vector fields are the same);
 *  - the same over a 0.1 s run with 47 located contact changes, both at rtol 1e-12: the
 *    same contact events (count, flanks) at the same times and the records within 10 x what
 *    the integrators' own error leaves (the full problem at rtol 1e-12 against 1e-13:
 *    impacts amplify the step errors, so trajectories agree to 1e-3..1e-5, not 1e-8);
 *  - below a cut-off (condensed_shaft.yaml, 103 DOFs): Adams with the coordinates' error
 *    weights against 8 modes at rtol 1e-9; the default rule on both models;
 *  - a prescribed DOF (condensed_prescribed.yaml): the vector field, and runs smooth and
 *    rattling;
 *  - refusals: generalized-alpha, a static start. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "transient/transient_impl.h"

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

/* At 30 random condensed states x in each of the first law's three contact modes, with every
 * mode kept: worst[0] the free DOFs' accelerations recovered from x' against the full
 * problem's right-hand side at the recovered state (relative to the largest), worst[1] the
 * two switch functions', worst[2] the prescribed DOFs' records against their motion. */
static int field_check(gd_transient *full, gd_transient *cond, unsigned seed, double dt,
                       double worst[3])
{
    const gd_tr_condensed *k = cond->cond;
    const int ns = gd_transient_nstates(cond), n = full->n, nf = full->nf;
    double *x = calloc((size_t)ns, sizeof *x), *xd = calloc((size_t)ns, sizeof *xd),
           *axd = calloc((size_t)ns, sizeof *axd), *q = calloc((size_t)n, sizeof *q),
           *v = calloc((size_t)n, sizeof *v), *a = calloc((size_t)n, sizeof *a),
           *y = calloc((size_t)2 * nf, sizeof *y), *yd = calloc((size_t)2 * nf, sizeof *yd),
           *zero = calloc((size_t)k->nc, sizeof *zero);
    const int ok = x && xd && axd && q && v && a && y && yd && zero &&
                   gd_transient_nswitches(full) == 2 && gd_transient_nswitches(cond) == 2;
    worst[0] = worst[1] = worst[2] = 0;
    for (int mode = -1; ok && mode <= 1; mode++)
        for (int trial = 0; trial < 30; trial++) {
            for (int i = 0; i < ns; i++) {
                seed = seed * 1103515245u + 12345u;
                x[i] = 1e-5 * (((seed >> 8) & 0xffff) / 32768.0 - 1.0);
            }
            const double t = dt * trial;
            full->law[0].mode = cond->law[0].mode = mode;
            gd_transient_rhs(cond, t, x, xd);
            gd_tr_fill(cond, t, x, q, v, NULL);
            /* a = Phi A x' (every mode kept: Phi B = 0, no static correction) */
            for (int i = 0; i < ns; i++) {
                axd[i] = 0;
                for (int j = 0; j < ns; j++)
                    axd[i] += k->A[i + (size_t)j * ns] * xd[j];
            }
            gd_condense_recover_state(k->c, axd, zero, a);
            for (int i = 0; i < nf; i++) {
                y[i] = q[full->free_dof[i]];
                y[nf + i] = v[full->free_dof[i]];
            }
            gd_transient_rhs(full, t, y, yd);
            double amax = 0, e = 0;
            for (int i = 0; i < nf; i++) {
                amax = fmax(amax, fabs(yd[nf + i]));
                e = fmax(e, fabs(yd[nf + i] - a[full->free_dof[i]]));
            }
            worst[0] = fmax(worst[0], e / amax);
            double g1[2], g2[2];
            gd_tr_roots(cond, t, x, g1);
            gd_tr_roots(full, t, y, g2);
            for (int r = 0; r < 2; r++)
                worst[1] = fmax(worst[1], fabs(g1[r] - g2[r]) / fmax(fabs(g2[r]), 1e-6));
            for (int p = 0; p < full->np; p++) {
                const int d = full->pres[p].dof;
                double qp, vp, ap;
                gd_prescribed_eval(&full->pres[p].law, t, full->rate[d], &qp, &vp, &ap);
                worst[2] = fmax(worst[2], fmax(fabs(q[d] - qp), fabs(v[d] - vp)));
            }
        }
    fprintf(stderr, "  accelerations: %.2g of the largest; switch functions: %.2g\n", worst[0],
            worst[1]);
    free(x);
    free(xd);
    free(axd);
    free(q);
    free(v);
    free(a);
    free(y);
    free(yd);
    free(zero);
    return ok;
}

TEST(every_mode_kept_has_the_full_vector_field)
{
    fx f;
    REQUIRE(load(&f, "tests/transient/condensed_pair.yaml"));
    const double W = 800 * M_PI / 30;
    gd_transient *full = NULL, *cond = NULL;
    REQUIRE(gd_transient_new(f.s, &f.tm->spec, W, &full, NULL) == GD_OK);
    REQUIRE(gd_transient_new_condensed(f.s, &f.tm->spec, W, 0.0, &cond, NULL) == GD_OK);
    REQUIRE(full->nf == f.s->ndof);
    double worst[3];
    CHECK(field_check(full, cond, 7, 1e-3, worst));
    CHECK_ABS(worst[0], 0.0, 1e-8);
    CHECK_ABS(worst[1], 0.0, 1e-8);
    gd_transient_free(full);
    gd_transient_free(cond);
    unload(&f);
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
    gd_tr_record rec[3] = {
        {GD_REC_MESH_FORCE, 0, 0}, {GD_REC_VEL, g2, 0}, {GD_REC_MESH_DEFLECTION, 0, 0}};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.1;
    o.output_interval = 1e-4;
    o.rtol = 1e-12;
    gd_transient_result *a = NULL, *b = NULL, *a13 = NULL;
    REQUIRE(gd_transient_run(full, &o, rec, 3, &a, NULL) == GD_OK);
    REQUIRE(gd_transient_run(cond, &o, rec, 3, &b, &err) == GD_OK);
    o.rtol = 1e-13;
    REQUIRE(gd_transient_run(full, &o, rec, 3, &a13, NULL) == GD_OK);
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
    double et13 = 0; /* the full problem's own event times at rtol 1e-12 and 1e-13 */
    for (int i = 0; i < a->ncontact_events && i < a13->ncontact_events; i++)
        et13 = fmax(et13, fabs(a->contact_events[i].t - a13->contact_events[i].t));
    fprintf(stderr, "  event times: condensed - full %.2g s, full 1e-12 - 1e-13 %.2g s\n", et,
            et13);
    CHECK(a13->ncontact_events == a->ncontact_events);
    CHECK(et <= 10 * et13 + 1e-12);
    for (int r = 0; r < 3; r++) {
        double peak, p13, e = peak_diff(a, b, r, &peak), own = peak_diff(a, a13, r, &p13);
        CHECK(peak > 0);
        fprintf(stderr, "  record %d: peak %.4g, condensed - full %.2g, full 1e-12 - 1e-13 %.2g\n",
                r, peak, e / peak, own / peak);
        CHECK(e <= 10 * own + 1e-8 * peak);
    }
    double qmax = 0, eq = 0, vmax = 0, ev = 0;
    for (int i = 0; i < a->ndof; i++) {
        qmax = fmax(qmax, fabs(a->q_end[i]));
        vmax = fmax(vmax, fabs(a->v_end[i]));
        eq = fmax(eq, fabs(a->q_end[i] - b->q_end[i]));
        ev = fmax(ev, fabs(a->v_end[i] - b->v_end[i]));
    }
    CHECK_ABS(eq / qmax, 0.0, 1e-3);
    CHECK_ABS(ev / vmax, 0.0, 1e-3);
    CHECK(strstr(b->method_note, "condensed") != NULL);
    gd_transient_result_free(a);
    gd_transient_result_free(b);
    gd_transient_result_free(a13);
    gd_transient_free(full);
    gd_transient_free(cond);
    unload(&f);
}

/* Below a cut-off (tests/transient/condensed_shaft.yaml: the pair's input gear on a
 * 100-element shaft, 103 DOFs; auto keeps 4 modes): auto runs Adams with the error weights
 * from the coordinates (docs/transient.md, "Method and error weights") and at rtol 1e-6
 * gives the contact events and mesh force of 8 modes (40 kHz) at rtol 1e-9 by BDF
 * (measured: the same 15 events, rms 6e-4 and peak 3.5e-3 apart, the truncation); the
 * default rule condenses this model and not the 3-DOF pair. */
TEST(cut_off_runs_adams_with_coordinate_weights)
{
    fx f;
    REQUIRE(load(&f, "tests/transient/condensed_shaft.yaml"));
    const double W = 800 * M_PI / 30;
    gd_transient *full = NULL, *a = NULL, *b = NULL;
    char why[160];
    REQUIRE(gd_transient_new(f.s, &f.tm->spec, W, &full, NULL) == GD_OK);
    CHECK(gd_transient_condense_pays(full, why, sizeof why) == 1);
    CHECK_STR(why, "103 DOFs, laws on 2");
    REQUIRE(gd_transient_new_condensed(f.s, &f.tm->spec, W, -1.0, &a, NULL) == GD_OK);
    REQUIRE(gd_transient_new_condensed(f.s, &f.tm->spec, W, 2 * M_PI * 40e3, &b, NULL) == GD_OK);
    CHECK(gd_transient_condense_pays(a, why, sizeof why) == 0);
    gd_tr_condensed_info ia, ib;
    REQUIRE(gd_transient_condensed_info(a, &ia) && gd_transient_condensed_info(b, &ib));
    CHECK(ia.nkept == 4 && ib.nkept == 8 && ia.ndiscarded > 0);
    gd_tr_record rec = {GD_REC_MESH_FORCE, 0, 0};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = 0.02;
    o.output_interval = 2e-5;
    o.method = GD_TR_AUTO;
    gd_transient_result *ra = NULL, *rb = NULL;
    REQUIRE(gd_transient_run(a, &o, &rec, 1, &ra, NULL) == GD_OK);
    o.rtol = 1e-9;
    o.method = GD_TR_BDF;
    REQUIRE(gd_transient_run(b, &o, &rec, 1, &rb, NULL) == GD_OK);
    CHECK(strstr(ra->method_note, "auto: adams") != NULL);
    CHECK(ra->events > 10 && ra->events == rb->events);
    fprintf(stderr, "  %ld events; mesh force rms %.6g vs %.6g, max %.6g vs %.6g\n", ra->events,
            ra->stats[0].rms, rb->stats[0].rms, ra->stats[0].max, rb->stats[0].max);
    CHECK_REL(ra->stats[0].rms, rb->stats[0].rms, 2e-3);
    CHECK_REL(ra->stats[0].max, rb->stats[0].max, 1e-2);
    gd_transient_result_free(ra);
    gd_transient_result_free(rb);
    gd_transient_free(full);
    gd_transient_free(a);
    gd_transient_free(b);
    unload(&f);
    REQUIRE(load(&f, "tests/transient/condensed_pair.yaml"));
    REQUIRE(gd_transient_new(f.s, &f.tm->spec, W, &full, NULL) == GD_OK);
    CHECK(gd_transient_condense_pays(full, why, sizeof why) == 0);
    CHECK_STR(why, "3 DOFs, fewer than 100");
    gd_transient_free(full);
    unload(&f);
}

/* A prescribed DOF (tests/transient/condensed_prescribed.yaml: examples/rattle_idle.yaml
 * with the flywheel's angle prescribed harmonic): the structure clamped there, the motion
 * entering through the clutch spring's coupling as coordinate forces. Every mode kept: the
 * free DOFs' accelerations and the switch functions of the full problem to 1e-8 at random
 * states, in each contact mode; the records of the flywheel are its motion. */
TEST(prescribed_dof_has_the_full_vector_field)
{
    fx f;
    REQUIRE(load(&f, "tests/transient/condensed_prescribed.yaml"));
    const double W = 800 * M_PI / 30;
    gd_transient *full = NULL, *cond = NULL;
    gd_error err;
    REQUIRE(gd_transient_new(f.s, &f.tm->spec, W, &full, NULL) == GD_OK);
    if (gd_transient_new_condensed(f.s, &f.tm->spec, W, 0.0, &cond, &err))
        fprintf(stderr, "  %s (%s)\n", err.message, err.field);
    REQUIRE(cond);
    REQUIRE(f.s->ndof == 3 && full->nf == 2 && full->np == 1);
    /* g1, g2: the flywheel is clamped, no rigid mode */
    CHECK(cond->cond->nc == 2 && gd_transient_nstates(cond) == 4);
    double worst[3];
    CHECK(field_check(full, cond, 11, 1.3e-3, worst));
    CHECK_ABS(worst[0], 0.0, 1e-8);
    CHECK_ABS(worst[1], 0.0, 1e-8);
    CHECK(worst[2] == 0.0);
    char why[160];
    CHECK(gd_transient_condense_pays(full, why, sizeof why) == 0);
    CHECK_STR(why, "3 DOFs, fewer than 100"); /* no longer "prescribed DOFs" */
    gd_transient_free(full);
    gd_transient_free(cond);
    unload(&f);
}

/* The same model over runs, every mode kept, against the full problem: smooth (the mesh
 * without backlash: no contact to lose; rtol 1e-12) the records to 1e-6 of their peak
 * (measured 4.1e-7; 1.2e-6, 3.3e-6, 7.6e-6 at rtol 1e-11, 1e-10, 1e-9: the integrators'
 * error, the vector fields being equal); rattling (backlash, rtol 1e-6) the contact events'
 * count within 10 % and the mesh force's rms within 5 % (measured 104 and 102, 1.5 %), the
 * flywheel's record its prescribed motion in both. */
TEST(prescribed_dof_runs_equal_the_full_problem)
{
    fx f;
    REQUIRE(load(&f, "tests/transient/condensed_prescribed.yaml"));
    const double W = 800 * M_PI / 30;
    const int g2 = gd_system_dof(f.s, gd_model_find_node(f.m, "g2"), GD_RZ);
    const int fw = gd_system_dof(f.s, gd_model_find_node(f.m, "flywheel"), GD_RZ);
    gd_tr_record rec[3] = {{GD_REC_MESH_FORCE, 0, 0}, {GD_REC_VEL, g2, 0}, {GD_REC_DISP, fw, 0}};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.output_interval = 1e-4;
    for (int rattle = 0; rattle <= 1; rattle++) {
        gd_transient_spec spec = f.tm->spec;
        gd_tr_prescribed pr = spec.prescribed[0];
        pr.law.amplitude = 2e-3;
        spec.prescribed = &pr;
        gd_tr_mesh ms = spec.meshes[0];
        ms.backlash = rattle; /* smooth: the mesh without backlash, no contact to lose */
        spec.meshes = &ms;
        o.t_end = rattle ? 0.3 : 0.1;
        o.rtol = rattle ? 1e-6 : 1e-12;
        o.atol_q = rattle ? o.atol_q : 1e-16;
        gd_transient *full = NULL, *cond = NULL;
        REQUIRE(gd_transient_new(f.s, &spec, W, &full, NULL) == GD_OK);
        REQUIRE(gd_transient_new_condensed(f.s, &spec, W, 0.0, &cond, NULL) == GD_OK);
        gd_transient_result *a = NULL, *b = NULL;
        REQUIRE(gd_transient_run(full, &o, rec, 3, &a, NULL) == GD_OK);
        REQUIRE(gd_transient_run(cond, &o, rec, 3, &b, NULL) == GD_OK);
        fprintf(stderr, "  %s: %d and %d contact events; mesh force rms %.6g and %.6g\n",
                rattle ? "rattling" : "smooth", a->ncontact_events, b->ncontact_events,
                a->stats[0].rms, b->stats[0].rms);
        for (int r = 0; r < 3; r++) {
            double peak, e = peak_diff(a, b, r, &peak);
            fprintf(stderr, "    record %d: peak %.4g, condensed - full %.2g\n", r, peak, e / peak);
            if (!rattle || r == 2) CHECK(e <= 1e-6 * peak);
        }
        if (rattle) {
            CHECK(a->ncontact_events > 20);
            CHECK(abs(a->ncontact_events - b->ncontact_events) <= a->ncontact_events / 10);
            CHECK_REL(a->stats[0].rms, b->stats[0].rms, 5e-2);
        }
        gd_transient_result_free(a);
        gd_transient_result_free(b);
        gd_transient_free(full);
        gd_transient_free(cond);
    }
    unload(&f);
}

TEST(refusals_name_the_field)
{
    fx f;
    gd_transient *tr = NULL;
    gd_error err;
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

RUN_TESTS(T(every_mode_kept_has_the_full_vector_field),
          T(every_mode_kept_equals_the_full_problem_through_impacts),
          T(cut_off_runs_adams_with_coordinate_weights),
          T(prescribed_dof_has_the_full_vector_field),
          T(prescribed_dof_runs_equal_the_full_problem), T(refusals_name_the_field))
