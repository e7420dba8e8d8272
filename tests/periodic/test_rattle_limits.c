/* Counted limits of issue 33 on rattling models (docs/periodic.md, "Worked examples"): the
 * contact homotopy of harmonic balance's start from rest (src/periodic/corrector.c: two
 * failed release solves in a row, or more than 12, end it, and the point says where), the
 * monodromy cut inside one matrix by a count of right-hand sides
 * (gd_transient_monodromy_limited), and shooting's budget reaching inside it. */
#include <cblas.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/periodic.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_support.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* examples/rattle_pair.yaml: an idler (one free DOF) on a prescribed input at 800 rpm,
 * 50 um of backlash, held by its churning drag; the long transient is period-1 with three
 * drive and one coast impact a period (geardyn transient --periods 60: one distinct
 * Poincare point of 61) */
#define PAIR GD_SOURCE_DIR "/examples/rattle_pair.yaml"
#define W800 (800.0 * 2.0 * M_PI / 60.0)

static gd_periodic_result *solve(const fx *f, const gd_transient_spec *spec, double v,
                                 const gd_periodic_options *o)
{
    openblas_set_num_threads(1);
    gd_periodic_result *r = NULL;
    gd_error err;
    if (gd_periodic_run(f->s, spec, NULL, &v, 1, o, NULL, 0, &r, &err))
        fprintf(stderr, "  periodic: %s (%s) %s\n", err.message, err.field, err.hint);
    return r;
}

/* Harmonic balance from rest on the rattling pair: the homotopy holds the contact on the
 * drive flank, releases it in steps, and the release fails twice in a row; the point's
 * reason names where it stopped, the count and the limits. Mutation tried: without the
 * two-in-a-row rule (halving down to a step of 1e-3 as before) the reason has no
 * "failed twice in a row" and the count differs. */
TEST(release_homotopy_stops_counted)
{
    fx f;
    REQUIRE(load(&f, PAIR, NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.kind = GD_PER_HB;
    o.method = GD_PER_SEQUENTIAL;
    o.stability = 0;
    o.harmonics = 10;
    gd_periodic_result *r = solve(&f, &tm->spec, W800, &o);
    REQUIRE(r && r->npoints == 1);
    const gd_periodic_point *p = &r->points[0];
    printf("  %s\n", p->reason);
    CHECK(!p->converged);
    const char *at = strstr(p->reason, "contact homotopy stopped at h = ");
    REQUIRE(at != NULL);
    double h = NAN;
    int solves = -1;
    CHECK(sscanf(at, "contact homotopy stopped at h = %lf after %d release solves", &h, &solves) ==
          2);
    CHECK(strstr(at, "failed twice in a row; limits 12 solves, 2 failures in a row") != NULL);
    CHECK(solves >= 2 && solves <= 12);
    CHECK(h > 0 && h < 1);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The monodromy of the pair over one period from its settled state: complete without a
 * limit (its count of right-hand sides n), cut inside the matrix with a limit of n / 3:
 * GD_ENUMERIC, the message naming the time reached within the period, the count at the
 * limit plus at most one step's evaluations. Mutation tried: the check after each step
 * removed, the limited call completes (GD_OK) and the test fails. */
TEST(monodromy_cut_inside_one_matrix)
{
    fx f;
    REQUIRE(load(&f, PAIR, NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(f.s, &tm->spec, W800, &tr, &err) == GD_OK);
    const int N = gd_transient_nstates(tr);
    REQUIRE(N == 2);
    const double T = 2 * M_PI / (2 * W800); /* the 2nd order */
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.rtol = 1e-9;
    o.atol_q = 1e-15;
    o.atol_v = 1e-12;
    o.t_end = 40 * T;
    o.record_from = o.t_end;
    gd_transient_result *run = NULL;
    REQUIRE(gd_transient_run(tr, &o, NULL, 0, &run, &err) == GD_OK);
    double y0[2] = {run->q_end[run->ndof - 1], run->v_end[run->ndof - 1]}, phi[4], phi2[4];
    gd_transient_result_free(run);
    long n = 0, n2 = 0;
    REQUIRE(gd_transient_monodromy_limited(tr, 40 * T, T, y0, &o, 0, &n, phi, NULL, &err) == GD_OK);
    printf("  whole matrix: %ld right-hand sides\n", n);
    CHECK(n > 300);
    const long lim = n / 3;
    CHECK(gd_transient_monodromy_limited(tr, 40 * T, T, y0, &o, lim, &n2, phi2, NULL, &err) ==
          GD_ENUMERIC);
    printf("  limit %ld: %s (%ld)\n", lim, err.message, n2);
    CHECK(n2 >= lim && n2 < lim + 60);
    CHECK(strstr(err.message, "monodromy stopped at t = ") != NULL);
    double t = NAN, pc = NAN;
    CHECK(sscanf(strstr(err.message, "t = "), "t = %lf s, %lf %%", &t, &pc) == 2);
    CHECK(t > 40 * T && t < 41 * T);
    CHECK(pc > 0 && pc < 100);
    /* the same limit twice: the same count (deterministic) */
    long n3 = 0;
    gd_transient_monodromy_limited(tr, 40 * T, T, y0, &o, lim, &n3, phi2, NULL, &err);
    CHECK(n3 == n2);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

RUN_TESTS(T(release_homotopy_stops_counted), T(monodromy_cut_inside_one_matrix))
