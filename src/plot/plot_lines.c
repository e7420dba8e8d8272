/* Curves of a parameter study (gd_plot_lines): each output over the first parameter, one
 * curve per value of the others (the rattle intensity over idle speed, one curve per
 * torque amplitude: docs/rattle.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "plot/plot_impl.h"

gd_status gd_plot_lines(const char *title, const char *xlabel, int nx, const double *x, int nfam,
                        const char *const *families, int nout, const char *const *outputs,
                        const double *y, gd_plot **out, gd_error *err)
{
    if (nx < 1 || nfam < 1 || nout < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot", "a study with cases and outputs",
                            "nothing to plot");
    gd_plot *p;
    gd_status st = gd_plot_new(title, &p, err);
    if (st) return st;
    pl_section *s = pl_section_add(p, title);
    pl_note(p, s, "%d outputs over %s, %d curve(s).", nout, xlabel, nfam);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "study.csv");
    pl_csv(p, s, "output,curve,x,y\n");
    double *xs = malloc((size_t)nx * sizeof *xs), *ys = malloc((size_t)nx * sizeof *ys);
    if (!xs || !ys) p->nomem = 1;
    for (int o = 0; !p->nomem && o < nout; o++) {
        pl_panel *pn = pl_panel_add(p, s, PL_XY, outputs[o], xlabel, outputs[o]);
        for (int f = 0; f < nfam; f++) {
            int n = 0;
            for (int i = 0; i < nx; i++) {
                double v = y[((size_t)o * nfam + f) * nx + i];
                if (!isfinite(v)) continue;
                xs[n] = x[i];
                ys[n++] = v;
                pl_csv(p, s, "\"%s\",\"%s\",%.10g,%.10g\n", outputs[o], families[f], x[i], v);
            }
            if (n) pl_trace_add(p, pn, families[f], n, xs, ys, PL_LINES_MARKERS, pl_color(f));
        }
    }
    free(xs);
    free(ys);
    return pl_done(p, out, err);
}
