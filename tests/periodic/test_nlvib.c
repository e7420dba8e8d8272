/* Harmonic balance against NLvib (Krack & Gross 2019, github.com/maltekrack/NLvib):
 * its example 01 (Duffing, H = 7, 29 samples) and example 03 (two-DOF oscillator with a
 * unilateral spring, H = 21, 1024 samples) continued in the load frequency
 * (gd_periodic_param.load_frequency) on examples/duffing.yaml and
 * examples/nlvib_ex03.yaml, with the same H and samples. The reference coefficients and
 * folds are NLvib's own (tests/periodic/nlvib/README.md says how they were made). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_support.h"

#define MAXREF 40
#define MAXC 200

typedef struct ref {
    int fold; /* 0 a point, 1 a fold */
    double om;
    int nc;
    double c[MAXC];
} ref;

/* Reads "point|fold INDEX OM C..." lines of an NLvib reference file. */
static int read_ref(const char *path, ref *r, int cap)
{
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    char line[20000];
    int n = 0;
    while (n < cap && fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        char kind[16];
        int idx, off;
        if (sscanf(line, "%15s %d %lf%n", kind, &idx, &r[n].om, &off) != 3) continue;
        r[n].fold = !strcmp(kind, "fold");
        char *p = line + off, *e;
        r[n].nc = 0;
        for (double v = strtod(p, &e); e != p && r[n].nc < MAXC; v = strtod(p, &e)) {
            r[n].c[r[n].nc++] = v;
            p = e;
        }
        n++;
    }
    fclose(f);
    return n;
}

/* Relative difference max|a - b| / max|b| over the coefficients. */
static double coef_diff(const double *a, const double *b, int n)
{
    double d = 0.0, s = 0.0;
    for (int i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        s = fmax(s, fabs(b[i]));
    }
    return d / s;
}

/* Runs the frequency continuation over the reference points' distinct frequencies (in
 * the order of the file) and compares every converged point with the nearest reference
 * point at its frequency; returns the largest difference and the count compared. */
static double compare(const char *model, const char *reffile, int H, int N, int max_steps,
                      int *ncompared, double *folds, int *nfolds)
{
    fx f;
    ref *r = malloc(MAXREF * sizeof *r);
    int nr = read_ref(reffile, r, MAXREF);
    double worst = INFINITY;
    *ncompared = 0;
    *nfolds = 0;
    if (!nr || !load(&f, model, NULL)) {
        free(r);
        return worst;
    }
    double vals[MAXREF];
    int nv = 0;
    for (int i = 0; i < nr; i++)
        if (!r[i].fold && (nv == 0 || vals[nv - 1] != r[i].om)) vals[nv++] = r[i].om;
    gd_transient_model *tm = NULL;
    gd_error err;
    gd_periodic_result *res = NULL;
    if (gd_transient_model_build(f.s, &tm, &err)) goto done;
    gd_periodic_options opt;
    gd_periodic_options_init(&opt);
    opt.harmonics = H;
    opt.samples = N;
    opt.estimate = 0;
    opt.stability = 0;
    opt.tol = 1e-12;
    opt.max_steps = max_steps;
    gd_periodic_param prm = {.name = "load frequency", .speed = 0.0, .load_frequency = 1};
    if (gd_periodic_run(f.s, &tm->spec, &prm, vals, nv, &opt, NULL, 0, &res, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        goto done;
    }
    worst = 0.0;
    for (int k = 0; k < res->npoints; k++) {
        const gd_periodic_point *p = &res->points[k];
        if (!p->converged) continue;
        double best = INFINITY;
        for (int i = 0; i < nr; i++)
            if (!r[i].fold && r[i].om == p->parameter && r[i].nc == p->nfree * (2 * H + 1))
                best = fmin(best, coef_diff(p->coef, r[i].c, r[i].nc));
        if (!isfinite(best)) continue; /* NLvib has no point there (it did not converge) */
        printf("  %s: W = %.4f: |X - X_NLvib| / |X_NLvib| = %.2e\n", model + strlen(GD_SOURCE_DIR),
               p->parameter, best);
        worst = fmax(worst, best);
        (*ncompared)++;
    }
    for (int b = 0; b < res->nbifurcations; b++)
        if (res->bifurcations[b].type == GD_BIF_FOLD && *nfolds < 8)
            folds[(*nfolds)++] = res->bifurcations[b].parameter;
done:
    gd_periodic_result_free(res);
    gd_transient_model_free(tm);
    fx_free(&f);
    free(r);
    return worst;
}

/* The nearest of the folds to the reference fold om. */
static double nearest(const double *folds, int n, double om)
{
    double best = INFINITY;
    for (int i = 0; i < n; i++)
        if (fabs(folds[i] - om) < fabs(best - om)) best = folds[i];
    return best;
}

TEST(duffing_equals_nlvib_example_01)
{
    double folds[8];
    int n, nf;
    double worst =
        compare(GD_SOURCE_DIR "/examples/duffing.yaml",
                GD_SOURCE_DIR "/tests/periodic/nlvib/duffing_ref.txt", 7, 29, 0, &n, folds, &nf);
    /* every point of NLvib's curve at 0.5 .. 1.6 (three at 1.2): same H, same samples,
     * the same equations: equal to the solvers' tolerances (measured 1e-13 or less) */
    CHECK(n == 9);
    CHECK(worst <= 1e-8);
    /* NLvib's folds 1.26960196 and 1.11570025 (ours located on the branch) */
    ref r[MAXREF];
    int nr = read_ref(GD_SOURCE_DIR "/tests/periodic/nlvib/duffing_ref.txt", r, MAXREF);
    int seen = 0;
    for (int i = 0; i < nr; i++)
        if (r[i].fold) {
            double w = nearest(folds, nf, r[i].om);
            printf("  Duffing fold %.10f (NLvib %.10f)\n", w, r[i].om);
            CHECK_ABS(w, r[i].om, 1e-8);
            seen++;
        }
    CHECK(seen == 2);
}

TEST(unilateral_spring_equals_nlvib_example_03)
{
    double folds[8];
    int n, nf;
    /* from 0.8 down through the lower fold and back up towards the resonance peak:
     * 100 steps reach 0.74 on the upper branch */
    double worst = compare(GD_SOURCE_DIR "/examples/nlvib_ex03.yaml",
                           GD_SOURCE_DIR "/tests/periodic/nlvib/nlvib_ex03_ref.txt", 21, 1024, 100,
                           &n, folds, &nf);
    CHECK(n >= 7);
    CHECK(worst <= 1e-8);
    /* NLvib's lower fold 0.6534401016 */
    double w = nearest(folds, nf, 0.65344010156891796);
    printf("  example 03 lower fold %.10f (NLvib 0.6534401016)\n", w);
    CHECK_ABS(w, 0.65344010156891796, 1e-8);
}

/* The whole curve of example 03 with the defaults for a non-smooth law (1024 samples)
 * at NLvib's H = 21: every point converges, in branch order (the frequency turns only at
 * the two folds), and exactly two folds: the lower one and the resonance peak. The
 * sampled branch is a saw near its peak (a tooth per sample switching contact, 7e-5
 * deep); the fold is its highest tooth (gd_per_climb_teeth), the same whatever the steps:
 * the CLI's 31, 61 and 121 frequencies over 0.8..0.5 give 0.7556642410345,
 * 0.7556642410325 and 0.7556642410345 (2.6e-12), NLvib's grid value 0.75566424102782
 * within 9e-12 (it was 0.755663813 here, 0.7556636 and 0.7556572 at 61 and 121, the
 * tooth the steps came near). */
TEST(nlvib_example_03_whole_curve)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/examples/nlvib_ex03.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options opt;
    gd_periodic_options_init(&opt);
    opt.harmonics = 21;
    opt.estimate = 0;
    opt.stability = 0;
    double vals[31];
    for (int i = 0; i < 31; i++)
        vals[i] = 0.8 - 0.01 * i;
    gd_periodic_param prm = {.name = "load frequency", .load_frequency = 1};
    gd_periodic_result *r = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, &prm, vals, 31, &opt, NULL, 0, &r, &err) == GD_OK);
    int bad = 0, turns = 0;
    double last = 0.0; /* the last non-zero change of the frequency between points */
    for (int i = 0; i < r->npoints; i++) {
        bad += !r->points[i].converged;
        double d = i ? r->points[i].parameter - r->points[i - 1].parameter : 0.0;
        if (d == 0.0) continue; /* a point at both sides of a fold */
        turns += d * last < 0;
        last = d;
    }
    int folds = 0;
    double peak = NAN, low = NAN;
    for (int b = 0; b < r->nbifurcations; b++)
        if (r->bifurcations[b].type == GD_BIF_FOLD) {
            folds++;
            double w = r->bifurcations[b].parameter;
            if (w > 0.7)
                peak = w;
            else
                low = w;
        }
    printf("  %d points (%d not converged), %d turns, %d folds: %.9f, %.9f; %d steps\n", r->npoints,
           bad, turns, folds, low, peak, r->steps);
    CHECK(bad == 0);
    CHECK(r->npoints == 31 + 2 * 10); /* 0.66 .. 0.75 three times */
    CHECK(turns == 2);
    CHECK(folds == 2);
    CHECK_ABS(low, 0.65344010156891796, 1e-8);
    CHECK_REL(peak, 0.7556642410345, 1e-8);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Folds located on the branch, not on the grid: example 01 (Duffing, H = 7, 29 samples)
 * over 0.8..1.6 rad/s with 9 and 41 frequencies (arclength steps up to 0.1 and 0.05:
 * 73 and 145 steps) gives the same two folds to 1e-8 (measured 1e-13; 1.3e-13 between
 * 21, 41, 81 and 161 frequencies by the CLI), NLvib's 1.2696019555 and 1.1157002518. */
TEST(duffing_folds_whatever_the_grid)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/examples/duffing.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options opt;
    gd_periodic_options_init(&opt);
    opt.harmonics = 7;
    opt.samples = 29;
    opt.estimate = 0;
    opt.stability = 0;
    gd_periodic_param prm = {.name = "load frequency", .load_frequency = 1};
    double fold[2][2] = {{NAN, NAN}, {NAN, NAN}};
    const int counts[2] = {9, 41};
    for (int g = 0; g < 2; g++) {
        double vals[41];
        for (int i = 0; i < counts[g]; i++)
            vals[i] = 0.8 + 0.8 * i / (counts[g] - 1);
        gd_periodic_result *r = NULL;
        REQUIRE(gd_periodic_run(f.s, &tm->spec, &prm, vals, counts[g], &opt, NULL, 0, &r, &err) ==
                GD_OK);
        int nf = 0;
        for (int b = 0; b < r->nbifurcations; b++)
            if (r->bifurcations[b].type == GD_BIF_FOLD && nf < 2)
                fold[g][nf++] = r->bifurcations[b].parameter;
        CHECK(nf == 2 && r->nbifurcations == 2);
        printf("  %d frequencies: folds %.13f, %.13f (%d steps)\n", counts[g], fold[g][0],
               fold[g][1], r->steps);
        gd_periodic_result_free(r);
    }
    CHECK_REL(fold[1][0], fold[0][0], 1e-8);
    CHECK_REL(fold[1][1], fold[0][1], 1e-8);
    CHECK_REL(fold[0][0], 1.2696019555, 1e-9);
    CHECK_REL(fold[0][1], 1.1157002518, 1e-9);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The CLI's defaults (adaptive H from the load's order, the truncation estimate): the
 * whole curve converges and has the same two folds (the peak at the branch's own H, 15 to
 * 31: measured 0.755608203, the highest tooth at that H, within 1e-4 of NLvib's H = 21
 * value). */
TEST(nlvib_example_03_default_options)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/examples/nlvib_ex03.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options opt;
    gd_periodic_options_init(&opt);
    opt.adaptive = 1;
    opt.stability = 0;
    double vals[31];
    for (int i = 0; i < 31; i++)
        vals[i] = 0.8 - 0.01 * i;
    gd_periodic_param prm = {.name = "load frequency", .load_frequency = 1};
    gd_periodic_result *r = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, &prm, vals, 31, &opt, NULL, 0, &r, &err) == GD_OK);
    int bad = 0, folds = 0;
    double peak = NAN, low = NAN;
    for (int i = 0; i < r->npoints; i++)
        bad += !r->points[i].converged;
    for (int b = 0; b < r->nbifurcations; b++)
        if (r->bifurcations[b].type == GD_BIF_FOLD) {
            folds++;
            double w = r->bifurcations[b].parameter;
            if (w > 0.7)
                peak = w;
            else
                low = w;
        }
    printf("  %d points (%d not converged), %d folds: %.9f, %.9f; %d steps\n", r->npoints, bad,
           folds, low, peak, r->steps);
    CHECK(bad == 0 && r->npoints == 51);
    CHECK(folds == 2);
    CHECK_ABS(low, 0.65344010156891796, 1e-8);
    CHECK_ABS(peak, 0.75566424102782437, 1e-4);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Natural continuation (--sequential, driver/sequential.c) through the folds, as a slow
 * run-up: harmonic balance on the Duffing oscillator upwards (H = 7) jumps to the lower
 * branch after the fold at 1.2696 (before 2026-12-02 the 7 values from 1.3 on failed:
 * no start but the neighbours); shooting on NLvib's example 03 downwards (11 frequencies,
 * the CLI's defaults) solves 0.62 from the last point (the secant across the jump at 0.65
 * fails there) and 0.59 from the secant, and locates the two Neimark-Sacker points between
 * them, those of its arclength
 * (docs/periodic.md, "Choosing the method": 0.618607, 0.581901; before, the history was
 * cleared after the failed 0.62, so 0.59 failed too and neither was located). */
TEST(run_ups_jump_at_folds)
{
    gd_periodic_param prm = {.name = "load frequency", .load_frequency = 1};
    gd_error err;
    for (int m = 0; m < 2; m++) {
        fx f;
        REQUIRE(load(&f,
                     m ? GD_SOURCE_DIR "/examples/nlvib_ex03.yaml"
                       : GD_SOURCE_DIR "/examples/duffing.yaml",
                     NULL));
        gd_transient_model *tm = NULL;
        REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
        gd_periodic_options opt;
        gd_periodic_options_init(&opt);
        opt.method = GD_PER_SEQUENTIAL;
        opt.kind = m ? GD_PER_SHOOTING : GD_PER_HB;
        opt.harmonics = 7;
        opt.adaptive = m;
        const int nv = m ? 11 : 23;
        double vals[23];
        for (int i = 0; i < nv; i++)
            vals[i] = m ? 0.8 - 0.03 * i : 0.5 + 0.05 * i;
        gd_periodic_result *r = NULL;
        REQUIRE(gd_periodic_run(f.s, &tm->spec, &prm, vals, nv, &opt, NULL, 0, &r, &err) == GD_OK);
        int bad = 0, ns = 0;
        double at[2] = {NAN, NAN};
        for (int i = 0; i < r->npoints; i++)
            bad += !r->points[i].converged;
        for (int b = 0; b < r->nbifurcations; b++)
            if (r->bifurcations[b].type == GD_BIF_NEIMARK_SACKER && ns < 2)
                at[ns++] = r->bifurcations[b].parameter;
        printf("  %s: %d points, %d not converged, %d steps, Neimark-Sacker %.10f %.10f\n",
               m ? "example 03, shooting" : "Duffing, harmonic balance", r->npoints, bad, r->steps,
               at[0], at[1]);
        CHECK(r->npoints == nv && bad == 0 && r->steps == nv - 1);
        if (m) {
            CHECK(ns == 2);
            CHECK_REL(at[0], 0.618607, 1e-5);
            CHECK_REL(at[1], 0.581901, 1e-5);
            CHECK(r->points[6].stable == 1 && r->points[7].stable == 0); /* 0.62, 0.59 */
        } else { /* on the lower branch beyond the fold (the CLI's |mu|max at 1.6) */
            CHECK_REL(r->points[nv - 1].mu_max, 0.9064904622, 1e-8);
        }
        gd_periodic_result_free(r);
        gd_transient_model_free(tm);
        fx_free(&f);
    }
}

RUN_TESTS(T(duffing_equals_nlvib_example_01), T(unilateral_spring_equals_nlvib_example_03),
          T(nlvib_example_03_whole_curve), T(nlvib_example_03_default_options),
          T(duffing_folds_whatever_the_grid), T(run_ups_jump_at_folds))
