/* Responses over many periods (include/geardyn/cycles.h) of real transient runs, as
 * `geardyn transient --periods` makes them: settle on whole periods of the excitations'
 * fundamental, record N periods, per-period statistics and the Poincare verdict.
 *  - the Mathieu pair (TVMS 1e8 (1 + 0.05 cos 20 theta), linear) off its tongue:
 *    periodic, every period's peak-to-peak the same;
 *  - the same pair with a 20 um backlash inside the tongue (W = 707 rad/s): the
 *    parametric resonance saturates on impacts into a period-2 orbit;
 *  - the Chen SFD pair at e_u/C = 1/2 and 5650 rad/s, on the torus born at the
 *    Neimark-Sacker bifurcation at 5583 rad/s (docs/transient.md): quasi-periodic;
 *  - the section of the Ducati train at 10000 rpm (101 points of 18 records from
 *    `geardyn transient --periods 100 --settle 200rev`, tests/transient/ducati_section.csv):
 *    irregular, every point distinct. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/cycles.h"
#include "geardyn/model.h"
#include "geardyn/periodic.h"
#include "geardyn/system.h"
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

static int load(fx *f, const char *path, double unbalance_scale, double backlash_gap)
{
    gd_error err;
    memset(f, 0, sizeof *f);
    gd_status st = gd_model_load(path, &f->m, &err);
    if (!st) {
        for (int i = 0; i < f->m->nunbalances; i++)
            f->m->unbalances[i].amount *= unbalance_scale;
        if (backlash_gap > 0) {
            f->m->meshes[0].dyn.backlash = 1;
            f->m->meshes[0].dyn.gap = backlash_gap;
        }
        st = gd_system_build(f->m, &f->s, &err);
    }
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

/* settle whole periods, then np periods sampled m times each and once per period */
static int periods_run(fx *f, double speed, int settle, int np, int m, const gd_tr_record *rec,
                       int nrec, gd_cycle_stats *st, gd_poincare_verdict *v)
{
    gd_error err;
    double w0 = 0;
    gd_transient *tr = NULL;
    gd_transient_result *res = NULL;
    if (gd_periodic_fundamental(f->s, &f->tm->spec, speed, &w0, NULL, &err) ||
        gd_transient_new(f->s, &f->tm->spec, speed, &tr, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        return 0;
    }
    double T = 2 * M_PI / w0, *ts = malloc((size_t)(np + 1) * sizeof *ts);
    for (int k = 0; k <= np; k++)
        ts[k] = (settle + k) * T;
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = ts[np];
    o.record_from = ts[0];
    o.output_interval = T / m;
    o.sample_times = ts;
    o.nsample_times = np + 1;
    int ok = gd_transient_run(tr, &o, rec, nrec, &res, &err) == GD_OK;
    double scale[4];
    for (int r = 0; ok && r < nrec; r++) {
        scale[r] = res->stats[r].peak_to_peak;
        ok = gd_cycle_stats_compute(res->values + (size_t)r * res->nout, res->nout, res->t[0],
                                    o.output_interval, T, ts[0], &st[r], &err) == GD_OK;
    }
    if (ok)
        ok = gd_poincare_classify(res->sample_values, nrec, res->nsamples, scale, NULL, v, &err) ==
             GD_OK;
    if (!ok) fprintf(stderr, "  %s\n", err.message);
    free(ts);
    gd_transient_result_free(res);
    gd_transient_free(tr);
    return ok;
}

/* Off the tongue (W = 537 rad/s): the response is the periodic orbit, every period alike
 * to the integration error. After 400 mesh periods (0.23 s, 8 decay times of the
 * zeta = 0.005 mode) what is left of the start turns by about 2 pi / 3 per period at
 * 1e-3 of the peak-to-peak: it passes for a 3-cycle at the tolerance, and the verdict
 * sees it still converging; after 800 it is periodic. */
TEST(linear_mathieu_is_periodic)
{
    fx f;
    REQUIRE(load(&f, "tests/plot/mathieu_pair.yaml", 1, 0));
    gd_tr_record rec[1] = {{GD_REC_MESH_FORCE, 0, 0}};
    gd_cycle_stats st[1];
    gd_poincare_verdict v;
    REQUIRE(periods_run(&f, 537, 400, 64, 64, rec, 1, st, &v));
    CHECK(v.cls == GD_POINCARE_IRREGULAR && v.converging == 1 && v.distinct == 3);
    REQUIRE(periods_run(&f, 537, 800, 64, 64, rec, 1, st, &v));
    CHECK(v.cls == GD_POINCARE_PERIODIC && v.period == 1 && v.distinct == 1);
    CHECK(v.converging == 0);
    CHECK(v.points == 65 && st[0].periods == 64 && st[0].min_samples == 65);
    /* mean force 20 N m / 50 mm = 400 N in the steady state; peak-to-peak 70.58 N (the
     * CLI's, 256 samples per period); every period alike */
    CHECK_REL(st[0].mean.median, 400.0, 1e-4);
    CHECK_REL(st[0].peak_to_peak.median, 70.58, 2e-3);
    CHECK((st[0].peak_to_peak.max - st[0].peak_to_peak.min) < 1e-3 * st[0].peak_to_peak.median);
    unload(&f);
}

/* In the tongue with backlash: period-2 (two section points alternating); the periods
 * alternate between two shapes, so the per-period mean force has a two-valued band
 * around the load's 400 N. */
TEST(backlash_mathieu_is_period_2)
{
    fx f;
    REQUIRE(load(&f, "tests/plot/mathieu_pair.yaml", 1, 20e-6));
    gd_tr_record rec[2] = {{GD_REC_MESH_FORCE, 0, 0}, {GD_REC_MESH_STATE, 0, 0}};
    gd_cycle_stats st[2];
    gd_poincare_verdict v;
    REQUIRE(periods_run(&f, 707, 1500, 64, 128, rec, 2, st, &v));
    CHECK(v.cls == GD_POINCARE_PERIODIC && v.period == 2 && v.distinct == 2);
    char name[32];
    gd_poincare_verdict_name(&v, name, sizeof name);
    CHECK_STR(name, "period-2");
    /* contact lost once in every other period; the mean over two periods is the load */
    CHECK(st[1].mean.min < 0.99 && st[1].peak_to_peak.max == 1.0);
    CHECK_REL(0.5 * (st[0].mean.min + st[0].mean.max), 400.0, 1e-3);
    CHECK(st[0].mean.max - st[0].mean.min > 50.0); /* 345 .. 455 N measured */
    unload(&f);
}

/* The torus past the Neimark-Sacker bifurcation: a close return after q periods for every
 * point (measured q = 15, 0.028 of the section's spread) on a recurrent set. */
TEST(chen_torus_is_quasi_periodic)
{
    fx f;
    REQUIRE(load(&f, "examples/chen1998_gear_pair.yaml", 3, 0));
    int na = gd_model_find_node(f.m, "gear_a");
    REQUIRE(na >= 0);
    gd_tr_record rec[2] = {{GD_REC_DISP, gd_system_dof(f.s, na, GD_Y), 0},
                           {GD_REC_DISP, gd_system_dof(f.s, na, GD_X), 0}};
    gd_cycle_stats st[2];
    gd_poincare_verdict v;
    REQUIRE(periods_run(&f, 5650, 200, 100, 64, rec, 2, st, &v));
    CHECK(v.cls == GD_POINCARE_QUASI_PERIODIC);
    CHECK(v.period == 0 && v.distinct > 80);
    CHECK(v.return_shift == 15);
    CHECK(v.return_distance < 0.06 && v.halves_distance < 0.15);
    /* the torus modulates the orbit: gear-a y's peak-to-peak from one period to the next
     * spreads by more than 2 (measured 55 .. 128 um) */
    CHECK(st[0].peak_to_peak.p95 > 2 * st[0].peak_to_peak.p05);
    unload(&f);
}

/* The Ducati section (poincare.csv of the [Benini2004] worked example, docs/transient.md). */
TEST(ducati_section_is_irregular)
{
    FILE *fp = fopen("tests/transient/ducati_section.csv", "r");
    REQUIRE(fp != NULL);
    enum { NP = 101, NR = 18 };
    static double v[NR * NP];
    char line[8192];
    REQUIRE(fgets(line, sizeof line, fp) != NULL); /* header */
    int k = 0;
    while (k < NP && fgets(line, sizeof line, fp)) {
        char *p = line;
        strtol(p, &p, 10); /* point */
        p++;
        strtod(p, &p); /* time */
        for (int r = 0; r < NR; r++) {
            p++;
            v[r * NP + k] = strtod(p, &p);
        }
        k++;
    }
    fclose(fp);
    REQUIRE(k == NP);
    /* scale: each record's peak-to-peak over the run, as the CLI: the forces' from the
     * points themselves is smaller, which only makes the test stricter */
    double scale[NR];
    for (int r = 0; r < NR; r++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int j = 0; j < NP; j++) {
            lo = fmin(lo, v[r * NP + j]);
            hi = fmax(hi, v[r * NP + j]);
        }
        scale[r] = hi - lo > 0 ? hi - lo : 1;
    }
    gd_poincare_verdict ver;
    gd_error err;
    REQUIRE(gd_poincare_classify(v, NR, NP, scale, NULL, &ver, &err) == GD_OK);
    CHECK(ver.cls == GD_POINCARE_IRREGULAR);
    CHECK(ver.distinct == NP);
    /* no shift brings every point back: measured 0.96 of the forces' spread at the best
     * shift (46 periods), the contact states left out */
    CHECK(ver.return_distance > 0.9);
}

RUN_TESTS(T(linear_mathieu_is_periodic), T(backlash_mathieu_is_period_2),
          T(chen_torus_is_quasi_periodic), T(ducati_section_is_irregular))
