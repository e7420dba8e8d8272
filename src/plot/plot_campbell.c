/* The Campbell diagram: tracked damped frequencies over speed coloured by whirl, the
 * excitation orders, the critical speeds marked and listed, and the log decrement. */
#include <math.h>
#include <stdlib.h>

#include "plot/plot_impl.h"

#define PI 3.14159265358979323846

static double rpm(double w)
{
    return w * 30 / PI;
}

gd_status gd_plot_campbell(const gd_campbell_result *r, gd_plot **out, gd_error *err)
{
    if (r->ntracks == 0 || r->nspeeds == 0)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot",
                            "ask for modes (--modes N) over a speed range (--speeds)",
                            "nothing to plot: no mode was tracked");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn Campbell diagram", &p, err);
    if (st) return st;
    int ns = r->nspeeds;
    pl_section *s = pl_section_add(p, "Campbell diagram");
    if (isnan(r->instability_onset))
        pl_note(p, s,
                "%d tracked modes over %d speeds (%s eigensolver); %d critical speed%s; stable "
                "over the whole speed range.",
                r->ntracks, ns, r->sparse ? "sparse" : "dense", r->ncritical,
                r->ncritical == 1 ? "" : "s");
    else
        pl_note(p, s,
                "%d tracked modes over %d speeds; %d critical speed%s; UNSTABLE from %.6g rpm "
                "(mode %d).",
                r->ntracks, ns, r->ncritical, r->ncritical == 1 ? "" : "s",
                rpm(r->instability_onset), r->instability_track);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "campbell.csv");
    pl_csv(p, s, "speed_rpm,mode,whirl,frequency_hz,log_decrement\n");
    pl_panel *fp = pl_panel_add(p, s, PL_XY,
                                "modes by whirl (forward blue, backward red, mixed purple), "
                                "orders, critical speeds",
                                "reference speed (rpm)", "damped natural frequency (Hz)");
    pl_panel *lp = pl_panel_add(p, s, PL_XY, "stability: log decrement of each mode",
                                "reference speed (rpm)", "log decrement (-)");
    double *x = malloc((size_t)ns * sizeof *x);
    if (!x) p->nomem = 1;
    for (int k = 0; x && k < ns; k++)
        x[k] = rpm(r->speeds[k]);
    double fmax = 0;
    for (int t = 0; x && t < r->ntracks; t++) {
        char name[160];
        snprintf(name, sizeof name, "mode %d (%s, %s)", r->tracks[t].id,
                 gd_whirl_names[r->tracks[t].whirl], gd_motion_names[r->tracks[t].dominant_motion]);
        const char *c = pl_whirl_color(r->tracks[t].whirl);
        pl_trace *f = pl_trace_add(p, fp, name, ns, x, NULL, PL_LINES_MARKERS, c);
        pl_trace *l = pl_trace_add(p, lp, name, ns, x, NULL, PL_LINES_MARKERS, c);
        if (!f || !l) break;
        /* a mode may change whirl with speed: each point in the colour of its own */
        f->marker_color = calloc((size_t)ns, sizeof *f->marker_color);
        if (!f->marker_color) p->nomem = 1;
        for (int k = 0; k < ns; k++) {
            const gd_mode *md = &r->modes[(size_t)t * ns + k];
            int ex = md->rigid_body >= 0;
            f->y[k] = ex ? md->omega_d / (2 * PI) : NAN;
            if (f->marker_color)
                f->marker_color[k] = pl_whirl_color(ex ? md->whirl : GD_WHIRL_NONE);
            l->y[k] = ex ? md->log_decrement : NAN;
            if (isfinite(f->y[k]) && f->y[k] > fmax) fmax = f->y[k];
            pl_trace_text(p, f, k, "mode %d, %s whirl: %.6g Hz at %.6g rpm", r->tracks[t].id,
                          ex ? gd_whirl_names[md->whirl] : "-", f->y[k], x[k]);
            if (ex)
                pl_csv(p, s, "%.10g,%d,%s,%.10g,%.10g\n", x[k], r->tracks[t].id,
                       gd_whirl_names[md->whirl], f->y[k], l->y[k]);
        }
    }
    /* orders: f = order x speed / 2 pi, drawn up to the highest mode plotted */
    for (int o = 0; x && o < r->norders; o++) {
        double w1 = r->speeds[ns - 1], f1 = r->orders[o].order * w1 / (2 * PI);
        if (fmax > 0 && f1 > 1.1 * fmax) w1 = 1.1 * fmax * 2 * PI / r->orders[o].order;
        double ox[2] = {x[0], rpm(w1)}, oy[2] = {r->orders[o].order * r->speeds[0] / (2 * PI),
                                                 r->orders[o].order * w1 / (2 * PI)};
        pl_trace *t = pl_trace_add(p, fp, r->orders[o].label, 2, ox, oy, PL_LINES,
                                   r->orders[o].kind == GD_ORDER_MESH ? "#2ca02c" : "#555");
        if (t) t->dash = 1;
    }
    pl_trace *c =
        pl_trace_add(p, fp, "critical speeds", r->ncritical, NULL, NULL, PL_MARKERS, "#000");
    for (int k = 0; c && k < r->ncritical; k++) {
        c->x[k] = r->critical[k].speed_rpm;
        c->y[k] = r->critical[k].frequency_hz;
        pl_trace_text(p, c, k, "critical speed %.6g rpm: mode %d meets %s at %.6g Hz", c->x[k],
                      r->critical[k].mode, r->orders[r->critical[k].order].label, c->y[k]);
    }
    if (c) c->symbol = PL_DIAMOND;
    if (!isnan(r->instability_onset)) {
        double ox[1] = {rpm(r->instability_onset)}, oy[1] = {0};
        pl_trace *t = pl_trace_add(p, lp, "instability onset", 1, ox, oy, PL_MARKERS, "#d62728");
        if (t) t->symbol = PL_TRIANGLE;
    }
    pl_panel *tb = pl_panel_add(p, s, PL_TABLE, "critical speeds", NULL, NULL);
    pl_table_init(p, tb, r->ncritical, 4);
    const char *head[4] = {"mode", "order", "speed (rpm)", "frequency (Hz)"};
    for (int k = 0; k < 4; k++)
        pl_cell(p, tb, 0, k, "%s", head[k]);
    for (int k = 0; k < r->ncritical; k++) {
        pl_cell(p, tb, k + 1, 0, "%d", r->critical[k].mode);
        pl_cell(p, tb, k + 1, 1, "%s", r->orders[r->critical[k].order].label);
        pl_cell(p, tb, k + 1, 2, "%.6g", r->critical[k].speed_rpm);
        pl_cell(p, tb, k + 1, 3, "%.6g", r->critical[k].frequency_hz);
    }
    free(x);
    return pl_done(p, out, err);
}
