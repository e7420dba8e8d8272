/* The Campbell diagram: tracked damped frequencies over speed coloured by whirl, the
 * excitation orders, the critical speeds marked and listed, and the log decrement. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

#define PI 3.14159265358979323846

static double rpm(double w)
{
    return w * 30 / PI;
}

void gd_plot_campbell_options_init(gd_plot_campbell_options *opt)
{
    memset(opt, 0, sizeof *opt);
}

gd_status gd_plot_campbell(const gd_campbell_result *r, gd_plot **out, gd_error *err)
{
    return gd_plot_campbell_opt(r, NULL, out, err);
}

void pl_order_label(const gd_order *o, char *buf, size_t n)
{
    const char *l = o->label;
    if (o->kind == GD_ORDER_MESH && !strncmp(l, "mesh mesh ", 10)) l += 5;
    snprintf(buf, n, "%s", l);
}

/* separation margin (%) of a critical speed to [lo, hi]: 0 inside */
static double margin(double n, double lo, double hi)
{
    return n < lo ? 100 * (lo - n) / lo : n > hi ? 100 * (n - hi) / hi : 0;
}

gd_status gd_plot_campbell_opt(const gd_campbell_result *r, const gd_plot_campbell_options *opt,
                               gd_plot **out, gd_error *err)
{
    gd_plot_campbell_options defaults;
    gd_plot_campbell_options_init(&defaults);
    if (!opt) opt = &defaults;
    double fcap = opt->max_frequency_hz > 0 ? opt->max_frequency_hz : INFINITY;
    int oper = opt->operating_lo < opt->operating_hi && opt->operating_lo >= 0;
    /* axis units: speeds rpm or rad/s (sx per rad/s), frequencies Hz or rad/s (fy per Hz) */
    double sx = opt->speed_rad_s ? 1 : 30 / PI, fy = opt->frequency_rad_s ? 2 * PI : 1;
    const char *su = opt->speed_rad_s ? "rad/s" : "rpm",
               *fu = opt->frequency_rad_s ? "rad/s" : "Hz";
    double olo = sx * opt->operating_lo, ohi = sx * opt->operating_hi;
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
    char xl[64], yl[64];
    snprintf(xl, sizeof xl, "reference speed (%s)", su);
    snprintf(yl, sizeof yl, "damped natural frequency (%s)", fu);
    pl_panel *fp = pl_panel_add(p, s, PL_XY,
                                "modes by whirl (forward blue, backward red, mixed purple), "
                                "orders, critical speeds",
                                xl, yl);
    pl_panel *lp =
        pl_panel_add(p, s, PL_XY, "stability: log decrement of each mode", xl, "log decrement (-)");
    double *x = malloc((size_t)ns * sizeof *x);
    if (!x) p->nomem = 1;
    for (int k = 0; x && k < ns; k++)
        x[k] = sx * r->speeds[k];
    double fmax = 0;
    int above = 0;
    for (int t = 0; x && t < r->ntracks; t++) {
        double lowest = INFINITY;
        for (int k = 0; k < ns; k++) {
            const gd_mode *md = &r->modes[(size_t)t * ns + k];
            if (md->rigid_body >= 0) lowest = fmin(lowest, md->omega_d / (2 * PI));
        }
        if (lowest > fcap) {
            above++;
            continue;
        }
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
            f->y[k] = ex ? fy * md->omega_d / (2 * PI) : NAN;
            if (f->marker_color)
                f->marker_color[k] = pl_whirl_color(ex ? md->whirl : GD_WHIRL_NONE);
            l->y[k] = ex ? md->log_decrement : NAN;
            if (isfinite(f->y[k]) && f->y[k] > fmax) fmax = f->y[k];
            pl_trace_text(p, f, k, "mode %d, whirl: %s: %.6g %s at %.6g %s", r->tracks[t].id,
                          ex ? gd_whirl_names[md->whirl] : "-", f->y[k], fu, x[k], su);
            if (ex)
                pl_csv(p, s, "%.10g,%d,%s,%.10g,%.10g\n", rpm(r->speeds[k]), r->tracks[t].id,
                       gd_whirl_names[md->whirl], md->omega_d / (2 * PI), l->y[k]);
        }
    }
    /* the frequency axis: up to the cap, else to a little above the highest mode */
    double ytop = isfinite(fcap) ? fy * fcap : 1.1 * fmax;
    if (fp && x) { /* the speed range, not widened for the order names */
        fp->xlim[0] = x[0];
        fp->xlim[1] = x[ns - 1];
    }
    if (fp && isfinite(fcap)) {
        fp->ylim[0] = 0;
        fp->ylim[1] = fy * fcap;
    }
    if (fp && x && oper) { /* the operating range, shaded under the curves */
        double bx[5] = {olo, ohi, ohi, olo, olo}, by[5] = {0, 0, ytop, ytop, 0};
        pl_trace *t = pl_trace_add(p, fp, "operating range", 5, bx, by, PL_FILL, "#f2b134");
        if (t) { /* drawn first */
            pl_trace tmp = *t;
            memmove(fp->traces + 1, fp->traces, (size_t)(fp->ntraces - 1) * sizeof *t);
            fp->traces[0] = tmp;
        }
    }
    /* orders: f = order x speed / 2 pi, drawn up to the top of the frequency axis and
     * named at their end */
    int nright = 0;
    for (int o = 0; x && o < r->norders; o++) {
        double w1 = r->speeds[ns - 1], f1 = fy * r->orders[o].order * w1 / (2 * PI);
        if (ytop > 0 && f1 > ytop) w1 = ytop / fy * 2 * PI / r->orders[o].order;
        double ox[2] = {x[0], sx * w1}, oy[2] = {fy * r->orders[o].order * r->speeds[0] / (2 * PI),
                                                 fy * r->orders[o].order * w1 / (2 * PI)};
        char label[96];
        pl_order_label(&r->orders[o], label, sizeof label);
        pl_trace *t = pl_trace_add(p, fp, label, 2, ox, oy, PL_LINES,
                                   r->orders[o].kind == GD_ORDER_MESH ? "#2ca02c" : "#555");
        if (!t) continue;
        t->dash = 1;
        snprintf(t->label, sizeof t->label, "%.63s", label);
        t->label_right = w1 < r->speeds[ns - 1]; /* ends at the top: name it to the right */
        if (!t->label_right) t->label_below = nright++ % 2; /* right-edge names alternate */
    }
    int ncrit = 0;
    for (int k = 0; k < r->ncritical; k++)
        ncrit += r->critical[k].frequency_hz <= fcap;
    /* none: no trace (plotly draws no trace group for an empty one, so the page's declared
     * count would not match what it shows) */
    pl_trace *c =
        ncrit > 0 ? pl_trace_add(p, fp, "critical speeds", ncrit, NULL, NULL, PL_MARKERS, "#000")
                  : NULL;
    if (c && oper) {
        c->marker_color = calloc((size_t)ncrit + 1, sizeof *c->marker_color);
        if (!c->marker_color) p->nomem = 1;
    }
    for (int k = 0, i = 0; c && k < r->ncritical; k++) {
        if (r->critical[k].frequency_hz > fcap) continue;
        c->x[i] = opt->speed_rad_s ? r->critical[k].speed : r->critical[k].speed_rpm;
        c->y[i] = fy * r->critical[k].frequency_hz;
        char label[96];
        pl_order_label(&r->orders[r->critical[k].order], label, sizeof label);
        if (oper) {
            double sm = margin(c->x[i], olo, ohi);
            if (c->marker_color) c->marker_color[i] = sm > 0 ? "#000" : "#d62728";
            pl_trace_text(p, c, i,
                          "critical speed %.6g %s: mode %d meets %s at %.6g %s; separation "
                          "margin %.3g %%",
                          c->x[i], su, r->critical[k].mode, label, c->y[i], fu, sm);
        } else {
            pl_trace_text(p, c, i, "critical speed %.6g %s: mode %d meets %s at %.6g %s", c->x[i],
                          su, r->critical[k].mode, label, c->y[i], fu);
        }
        i++;
    }
    if (c) c->symbol = PL_DIAMOND;
    if (above || ncrit < r->ncritical)
        pl_note(p, s,
                "Above %.6g Hz (--max-frequency) and left out: %d mode%s, %d critical speed%s.",
                fcap, above, above == 1 ? "" : "s", r->ncritical - ncrit,
                r->ncritical - ncrit == 1 ? "" : "s");
    if (!isnan(r->instability_onset)) {
        double ox[1] = {sx * r->instability_onset}, oy[1] = {0};
        pl_trace *t = pl_trace_add(p, lp, "instability onset", 1, ox, oy, PL_MARKERS, "#d62728");
        if (t) t->symbol = PL_TRIANGLE;
    }
    char ttl[120];
    if (oper)
        snprintf(ttl, sizeof ttl,
                 "critical speeds; separation margin to the operating range %.6g-%.6g %s", olo, ohi,
                 su);
    else
        snprintf(ttl, sizeof ttl, "critical speeds");
    pl_panel *tb = pl_panel_add(p, s, PL_TABLE, ttl, NULL, NULL);
    int ncol = oper ? 5 : 4;
    pl_table_init(p, tb, ncrit, ncol);
    for (int k = 0; k < ncol; k++)
        if (k == 2)
            pl_cell(p, tb, 0, k, "speed (%s)", su);
        else if (k == 3)
            pl_cell(p, tb, 0, k, "frequency (%s)", fu);
        else
            pl_cell(p, tb, 0, k, "%s", k == 0 ? "mode" : k == 1 ? "order" : "margin (%)");
    for (int k = 0, row = 1; k < r->ncritical; k++) {
        if (r->critical[k].frequency_hz > fcap) continue;
        char label[96];
        pl_order_label(&r->orders[r->critical[k].order], label, sizeof label);
        pl_cell(p, tb, row, 0, "%d", r->critical[k].mode);
        pl_cell(p, tb, row, 1, "%s", label);
        double cs = opt->speed_rad_s ? r->critical[k].speed : r->critical[k].speed_rpm;
        pl_cell(p, tb, row, 2, "%.6g", cs);
        pl_cell(p, tb, row, 3, "%.6g", fy * r->critical[k].frequency_hz);
        if (oper) {
            double sm = margin(cs, olo, ohi);
            pl_cell(p, tb, row, 4, sm > 0 ? "%.3g" : "%.3g (inside)", sm);
        }
        row++;
    }
    free(x);
    return pl_done(p, out, err);
}
