/* Correlation and updating: the synthetic truth of tests/uff_support.h (bearings 20 %
 * stiffer than the model) recovered by LSCF then updating; [MMT2018] Tables 4-5 from
 * the measured frequencies of Table 2; the eigenvalue-derivative sensitivities against
 * differences of the frequencies; a parameter that moves no target refused. */
#include "harness.h"
#include "uff_support.h"

#include <unistd.h>

/* [MMT2018] Tables 4 and 5: FE frequency and % difference as printed. The paper
 * truncates to two decimals, and where two measured modes (x and y) share one FE
 * frequency it prints the first one's % for both: Table 4 modes 2, 4, 6, 8 print 1.08,
 * 3.04, 2.40, -0.23 where its own numbers give 0.79, 2.79, 2.29, -0.33; Table 5 modes
 * 6 and 8 print 2.83 and 0.65 for 2.78 and 0.59. */
static const double T4_FE[8] = {135.88, 135.88, 161.82, 161.82, 740.3, 740.3, 770.66, 770.66};
static const double T4_PCT[8] = {1.08, 1.08, 3.04, 3.04, 2.40, 2.40, -0.23, -0.23};
static const double T5_FE[8] = {126.45, 135.88, 153.81, 161.82, 740.3, 740.3, 770.66, 770.66};
static const double T5_PCT[8] = {3.59, 7.49, -2.00, 1.98, 2.83, 2.83, 0.65, 0.65};

static void seed004_table(gd_test_state *gd_ts_, const char *csv, int coupled, const double *fe,
                          const double *pct)
{
    const char *p[1] = {csv};
    gd_testdata *td;
    gd_error err;
    REQUIRE(gd_testdata_read(1, p, 0, &td, &err) == GD_OK);
    gd_measured_modes mm;
    REQUIRE(gd_measured_from_testdata(td, &mm, &err) == GD_OK);
    const char *sets[1] = {"meshes=[]"};
    gd_load_options lo = {coupled ? 0 : 1, sets};
    gd_model *m;
    gd_system *s;
    REQUIRE(gd_model_load_opts("examples/rig2018.yaml", &lo, &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    gd_corr_table *t;
    REQUIRE(gd_correlate_modes(s, &mm, &t, &err) == GD_OK);
    printf("  %s: mode  measured  FE(geardyn)  FE(paper)  %%diff  %%diff(paper)\n", csv);
    for (int i = 0; i < t->npairs; i++) {
        const gd_corr_pair *q = &t->pairs[i];
        printf("  %d %9.1f %10.2f %10.2f %7.2f %7.2f\n", i + 1, q->f_test, q->f_model, fe[i],
               q->diff_pct, pct[i]);
        /* the FE column: the model reproduces the paper within 0.25 % (docs) */
        CHECK_REL(q->f_model, fe[i], 0.0025);
        /* the % difference from the paper's own FE value, as the paper defines it,
         * equals the printed one to its truncated second decimal, except the two
         * copied rows of Table 4 */
        double own = 100 * (fe[i] - q->f_test) / fe[i];
        if (!(i % 2 == 1 && fe[i] == fe[i - 1])) CHECK_ABS(own, pct[i], 0.0101);
        /* and geardyn's %: the paper's, moved by the FE difference (< 0.25 % of f) */
        CHECK_ABS(q->diff_pct, own, 0.26);
    }
    gd_corr_table_free(t);
    gd_system_free(s);
    gd_model_free(m);
    gd_measured_modes_free(&mm);
    gd_testdata_free(td);
}

TEST(seed004_tables_4_and_5)
{
    seed004_table(gd_ts_, "examples/mmt2018_uncoupled_modes.csv", 0, T4_FE, T4_PCT);
    seed004_table(gd_ts_, "examples/mmt2018_coupled_modes.csv", 1, T5_FE, T5_PCT);
}

/* Table 2's frequencies: the bearing stiffnesses of each shaft (A1, A2 of the 48-tooth
 * shaft; B1, B2 of the 32-tooth one) updated, and the mesh stiffness in the coupled
 * case. Eight frequencies, two or three parameters: the fit lowers the rms difference
 * but cannot remove it (docs/testing.md gives the values and why); checked: it
 * converges, lowers the rms by the amounts measured here (uncoupled 2.04 % -> 1.50 %,
 * coupled 3.50 % -> 2.83 %, to 0.01 %), and keeps every value within its bounds. */
static void seed004_fit(gd_test_state *gd_ts_, int coupled, double rms0, double rms1)
{
    const char *p[1] = {coupled ? "examples/mmt2018_coupled_modes.csv"
                                : "examples/mmt2018_uncoupled_modes.csv"};
    gd_testdata *td;
    gd_error err;
    REQUIRE(gd_testdata_read(1, p, 0, &td, &err) == GD_OK);
    gd_measured_modes mm;
    REQUIRE(gd_measured_from_testdata(td, &mm, &err) == GD_OK);
    gd_model_source *src;
    REQUIRE(gd_model_source_load("examples/rig2018.yaml", &src, &err) == GD_OK);
    gd_update_param par[3] = {{"bearings.A1.k,bearings.A2.k", 2e7, 5e8},
                              {"bearings.B1.k,bearings.B2.k", 2e7, 5e8},
                              {"meshes.mesh.stiffness", 1e7, 2e9}};
    const char *sets[1] = {"meshes=[]"};
    gd_update_options o;
    gd_update_options_init(&o);
    o.nparams = coupled ? 3 : 2;
    o.params = par;
    o.load.nset = coupled ? 0 : 1;
    o.load.set = sets;
    gd_update_result *r;
    gd_status st = gd_model_update(src, &mm, &o, &r, &err);
    if (st) fprintf(stderr, "  %s: %s\n", err.field, err.message);
    REQUIRE(st == GD_OK);
    printf("  %s: rms %.3f%% -> %.3f%% in %d iterations\n", p[0], r->before->rms_pct,
           r->after->rms_pct, r->iterations);
    for (int k = 0; k < o.nparams; k++)
        printf("  %s: %.4g -> %.4g +- %.2g\n", par[k].key, r->initial[k], r->value[k], r->sigma[k]);
    for (int i = 0; i < r->after->npairs; i++)
        printf("  %9.1f %10.2f %7.2f\n", r->after->pairs[i].f_test, r->after->pairs[i].f_model,
               r->after->pairs[i].diff_pct);
    CHECK(r->iterations < o.max_iter);
    CHECK_ABS(r->before->rms_pct, rms0, 0.01);
    CHECK_ABS(r->after->rms_pct, rms1, 0.01);
    for (int k = 0; k < o.nparams; k++)
        CHECK(r->value[k] >= par[k].lo && r->value[k] <= par[k].hi);
    gd_update_free(r);
    gd_model_source_free(src);
    gd_measured_modes_free(&mm);
    gd_testdata_free(td);
}

TEST(seed004_update)
{
    seed004_fit(gd_ts_, 0, 2.042, 1.497);
    seed004_fit(gd_ts_, 1, 3.503, 2.830);
}

TEST(synthetic_update_recovers_the_bearing_stiffness)
{
    synth sy;
    REQUIRE(synth_make(&sy, 1.2, 0.02, 12, 4097, 0.25, 36));
    char path[256];
    snprintf(path, sizeof path, "/tmp/gd_corr_%d.uff", (int)getpid());
    REQUIRE(synth_write_uff(&sy, path, 1, 6));
    const char *p[1] = {path};
    gd_testdata *td;
    gd_error err;
    REQUIRE(gd_testdata_read(1, p, 0, &td, &err) == GD_OK);
    unlink(path);
    const gd_td_function *f[16];
    for (int j = 0; j < td->nfunctions; j++)
        f[j] = &td->functions[j];
    gd_ema_result *er;
    REQUIRE(gd_ema_lscf(td->nfunctions, f, NULL, &er, &err) == GD_OK);
    /* the model as it was before the test: 1e8 N/m bearings */
    const char *sets[1] = {"dofs=[y, rx, rz]"};
    gd_load_options lo = {1, sets};
    gd_model *m;
    gd_system *s;
    REQUIRE(gd_model_load_opts("examples/rig2018.yaml", &lo, &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &s, &err) == GD_OK);
    gd_measured_modes mm;
    gd_status st = gd_measured_from_ema(s, NULL, td->nfunctions, f, er, &mm, &err);
    if (st) fprintf(stderr, "  %s\n", err.message);
    REQUIRE(st == GD_OK);
    CHECK(mm.ndofs == 12);
    /* before: the shapes pair (MAC > 0.99: the stiffer bearings barely move the shapes) */
    gd_corr_table *t;
    REQUIRE(gd_correlate_modes(s, &mm, &t, &err) == GD_OK);
    for (int i = 0; i < t->npairs; i++) {
        printf("  before: %8.3f Hz model %8.3f Hz  %6.2f%%  MAC %.4f\n", t->pairs[i].f_test,
               t->pairs[i].f_model, t->pairs[i].diff_pct, t->pairs[i].mac);
        CHECK(t->pairs[i].mac > 0.99);
    }
    gd_corr_table_free(t);
    gd_model_source *src;
    REQUIRE(gd_model_source_load("examples/rig2018.yaml", &src, &err) == GD_OK);
    gd_update_param par = {"bearings.*.k", 3e7, 5e8};
    gd_update_options o;
    gd_update_options_init(&o);
    o.nparams = 1;
    o.params = &par;
    o.load = lo;
    o.fd_check = 1;
    gd_update_result *r;
    st = gd_model_update(src, &mm, &o, &r, &err);
    if (st) fprintf(stderr, "  %s\n", err.message);
    REQUIRE(st == GD_OK);
    printf("  bearings k: %.6g -> %.6g +- %.3g (truth 1.2e8), %d iterations, rms %.4f%% -> "
           "%.4f%%\n",
           r->initial[0], r->value[0], r->sigma[0], r->iterations, r->before->rms_pct,
           r->after->rms_pct);
    /* issue 36: the +20 % recovered within 2 % */
    CHECK_REL(r->value[0], 1.2e8, 0.02);
    CHECK(r->sigma[0] > 0 && r->sigma[0] < 0.02 * 1.2e8);
    /* the eigenvalue derivatives against central differences of the frequencies
     * (h = 1e-4 p: truncation ~1e-8, round-off ~1e-10 of f / h p): 1e-4 relative */
    for (int i = 0; i < r->ntargets; i++) {
        printf("  df/dk mode %d: %.6e (eigenvalue derivative) %.6e (difference)\n", i, r->sens[i],
               r->sens_fd[i]);
        CHECK_REL(r->sens[i], r->sens_fd[i], 1e-4);
    }
    gd_update_free(r);
    /* a parameter no undamped frequency depends on: the bearings' damping */
    gd_update_param bad = {"bearings.*.c", 1, 1000};
    o.params = &bad;
    o.fd_check = 0;
    CHECK(gd_model_update(src, &mm, &o, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "changes no target") != NULL);
    CHECK_STR(err.field, "bearings.*.c");
    gd_model_source_free(src);
    gd_measured_modes_free(&mm);
    gd_system_free(s);
    gd_model_free(m);
    gd_ema_free(er);
    gd_testdata_free(td);
    synth_free(&sy);
}

RUN_TESTS(T(seed004_tables_4_and_5), T(seed004_update),
          T(synthetic_update_recovers_the_bearing_stiffness))
