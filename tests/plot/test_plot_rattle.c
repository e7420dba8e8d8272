/* The rattle figure (gd_plot_rattle): one section with the metrics table and one
 * impact-speed panel (drive and coast flank) per mesh; no metrics is GD_EINPUT. */
#include <math.h>
#include <string.h>

#include "geardyn/plot.h"
#include "harness.h"

TEST(rattle_figure_has_a_table_and_histograms)
{
    gd_rattle_metrics m[2];
    memset(m, 0, sizeof m);
    for (int k = 0; k < 2; k++) {
        m[k].duration = 2.0;
        m[k].batches = 10;
        m[k].confidence = 0.95;
        m[k].bin_width = 1e-3;
        m[k].hist_drive[3] = 40;
        m[k].hist_coast[5] = 10;
    }
    const char *names[2] = {"gear3", "gear4"};
    gd_plot *p = NULL;
    gd_error err;
    REQUIRE(gd_plot_rattle(names, m, 2, &p, &err) == GD_OK);
    CHECK(gd_plot_nsections(p) == 1);
    CHECK(gd_plot_npanels(p, 0) == 3); /* the table, then one panel per mesh */
    CHECK(gd_plot_ntraces(p, 0, 1) == 2 && gd_plot_ntraces(p, 0, 2) == 2);
    gd_plot_free(p);
    CHECK(gd_plot_rattle(names, m, 0, &p, &err) == GD_EINPUT);
    CHECK_STR(err.field, "--plot");
}

/* gd_plot_lines: one panel per output, one trace per family with a finite value. */
TEST(study_lines_one_panel_per_output)
{
    const double x[3] = {600, 800, 1000};
    const char *fam[2] = {"amp=0.5", "amp=1"}, *outs[2] = {"rattle_intensity", "separated"};
    double y[2 * 2 * 3];
    for (int k = 0; k < 12; k++)
        y[k] = k;
    y[3] = y[4] = y[5] = NAN; /* output 0, family 1: no case */
    gd_plot *p = NULL;
    gd_error err;
    REQUIRE(gd_plot_lines("study", "speed_rpm", 3, x, 2, fam, 2, outs, y, &p, &err) == GD_OK);
    CHECK(gd_plot_nsections(p) == 1 && gd_plot_npanels(p, 0) == 2);
    CHECK(gd_plot_ntraces(p, 0, 0) == 1 && gd_plot_ntraces(p, 0, 1) == 2);
    gd_plot_free(p);
    CHECK(gd_plot_lines("study", "x", 0, x, 2, fam, 2, outs, y, &p, &err) == GD_EINPUT);
}

RUN_TESTS(T(rattle_figure_has_a_table_and_histograms), T(study_lines_one_panel_per_output))
