/* The rattle figure (gd_plot_rattle, docs/rattle.md): the metrics of each mesh with their
 * confidence half-widths as a table, and per mesh the impact-speed histograms of the drive
 * and the coast flank (impacts per second in each speed bin, at the bins' centres). */
#include <stdio.h>

#include "plot/plot_impl.h"

gd_status gd_plot_rattle(const char *const *names, const gd_rattle_metrics *metrics, int n,
                         gd_plot **out, gd_error *err)
{
    if (n < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot",
                            "run with --rattle on a model "
                            "with backlash meshes",
                            "no rattle metrics to plot");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn rattle", &p, err);
    if (st) return st;
    const gd_rattle_metrics *m0 = &metrics[0];
    pl_section *s = pl_section_add(p, "Rattle");
    pl_note(p, s,
            "%d mesh(es) over %.6g s; mean +- the %g %% confidence half-width from %d batch "
            "means. Intensity: impact energy m_e v^2 / 2 per second, W (m^2/s^3 without a mass).",
            n, m0->duration, 100 * m0->confidence, m0->batches);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "rattle.csv");
    pl_panel *tb = pl_panel_add(p, s, PL_TABLE, "Rattle metrics", "", "");
    pl_table_init(p, tb, n, 6);
    static const char *const hd[6] = {
        "mesh",      "separated fraction", "drive impacts/s", "coast impacts/s",
        "intensity", "v rms (m/s)"};
    for (int c = 0; c < 6; c++)
        pl_cell(p, tb, 0, c, "%s", hd[c]);
    pl_csv(p, s, "mesh,flank,speed_bin_centre_m_s,impacts_per_s\n");
    for (int k = 0; k < n; k++) {
        const gd_rattle_metrics *m = &metrics[k];
        pl_cell(p, tb, k + 1, 0, "%s", names[k]);
        pl_cell(p, tb, k + 1, 1, "%.4g +- %.2g", m->separated.mean, m->separated.half_width);
        pl_cell(p, tb, k + 1, 2, "%.4g +- %.2g", m->drive_rate.mean, m->drive_rate.half_width);
        pl_cell(p, tb, k + 1, 3, "%.4g +- %.2g", m->coast_rate.mean, m->coast_rate.half_width);
        pl_cell(p, tb, k + 1, 4, "%.4g +- %.2g", m->intensity.mean, m->intensity.half_width);
        pl_cell(p, tb, k + 1, 5, "%.4g", m->v_rms);
        char title[200];
        snprintf(title, sizeof title, "%s: impact speeds", names[k]);
        pl_panel *h = pl_panel_add(p, s, PL_XY, title, "impact speed (m/s)", "impacts per second");
        double x[GD_RATTLE_BINS], yd[GD_RATTLE_BINS], yc[GD_RATTLE_BINS];
        for (int b = 0; b < GD_RATTLE_BINS; b++) {
            x[b] = (b + 0.5) * m->bin_width;
            yd[b] = m->hist_drive[b] / m->duration;
            yc[b] = m->hist_coast[b] / m->duration;
            pl_csv(p, s, "\"%s\",drive,%.10g,%.10g\n", names[k], x[b], yd[b]);
            pl_csv(p, s, "\"%s\",coast,%.10g,%.10g\n", names[k], x[b], yc[b]);
        }
        pl_trace_add(p, h, "drive flank", GD_RATTLE_BINS, x, yd, PL_LINES_MARKERS, pl_color(0));
        pl_trace_add(p, h, "coast flank", GD_RATTLE_BINS, x, yc, PL_LINES_MARKERS, pl_color(1));
    }
    return pl_done(p, out, err);
}
