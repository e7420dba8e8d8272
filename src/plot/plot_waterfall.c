/* The run-up waterfall (geardyn/waterfall.h): a cascade of the spectra stacked by speed,
 * the same as a colour map over speed and frequency, both with the excitation orders
 * as labelled lines, and the order cuts (amplitude of each order over speed). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/waterfall.h"
#include "plot/plot_impl.h"

#define PI 3.14159265358979323846
#define NLEVELS 8 /* colour-map levels, 10 dB each: 80 dB below the largest amplitude */
#define DB_STEP 10.0

void gd_plot_waterfall_options_init(gd_plot_waterfall_options *opt)
{
    memset(opt, 0, sizeof *opt);
}

/* the colour-map level of an amplitude (0 the loudest 10 dB), -1 below the last */
static int level_of(double a, double amax)
{
    if (!(amax > 0) || !(a > 0)) return -1;
    double db = 20 * log10(a / amax);
    if (!(db > -DB_STEP * NLEVELS)) return -1;
    return db >= 0 ? 0 : (int)floor(-db / DB_STEP);
}

static const char *level_color(int k)
{
    /* viridis, light (loud) to dark (quiet) read against white */
    static const char *const c[NLEVELS] = {"#fde725", "#a0da39", "#4ac16d", "#1fa187",
                                           "#277f8e", "#365c8d", "#46327e", "#440154"};
    return c[k];
}

/* An order-tracked waterfall's colour map over speed and order (the bins are orders):
 * the same levels as the frequency map, the orders as vertical lines. */
static void order_map(gd_plot *p, pl_section *sec, const gd_waterfall *w, const char *name,
                      const char *unit, double amax, double sx, const char *su, double ftop,
                      double wtop)
{
    const int ns = w->nspeeds;
    /* orders up to the frequency axis's top at the top speed */
    double otop = ftop * 2 * PI / wtop;
    char xl[64], yl[64], title[300];
    snprintf(xl, sizeof xl, "order (multiple of the reference speed)");
    snprintf(yl, sizeof yl, "reference speed (%s)", su);
    snprintf(title, sizeof title, "%s: order map, amplitude in dB below %.4g %s", name, amax, unit);
    pl_panel *map = pl_panel_add(p, sec, PL_XY, title, xl, yl);
    if (!map) return;
    map->xlim[0] = 0;
    map->xlim[1] = otop;
    int cnt[NLEVELS] = {0}, lv[NLEVELS];
    for (int s = 0; s < ns; s++)
        for (int k = 1; k < w->spectra[s]->n; k++) {
            double o = w->spectra[s]->freq[k] * 2 * PI / w->speeds[s];
            int l = level_of(w->spectra[s]->amplitude[k], amax);
            if (o <= otop && l >= 0) cnt[l]++;
        }
    for (int l = 0; l < NLEVELS; l++) {
        lv[l] = -1;
        if (!cnt[l]) continue;
        char ln[64];
        snprintf(ln, sizeof ln, "%g to %g dB", l ? -DB_STEP * l : 0.0, -DB_STEP * (l + 1));
        pl_trace *t = pl_trace_add(p, map, ln, cnt[l], NULL, NULL, PL_MARKERS, level_color(l));
        if (t && t->x && t->y) {
            t->symbol = PL_SQUARE;
            t->legend = 0;
            lv[l] = (int)(t - map->traces);
        }
        cnt[l] = 0;
    }
    for (int s = 0; s < ns; s++)
        for (int k = 1; k < w->spectra[s]->n; k++) {
            const gd_spectrum *sp = w->spectra[s];
            double o = sp->freq[k] * 2 * PI / w->speeds[s];
            int l = level_of(sp->amplitude[k], amax);
            if (o > otop || l < 0 || lv[l] < 0) continue;
            pl_trace *t = &map->traces[lv[l]];
            int i = cnt[l]++;
            t->x[i] = o;
            t->y[i] = sx * w->speeds[s];
            pl_trace_text(p, t, i, "order %.4g at %.6g %s: %.4g %s (%.1f dB)", o, t->y[i], su,
                          sp->amplitude[k], unit, 20 * log10(sp->amplitude[k] / amax));
        }
    double lo = w->speeds[0], hi = w->speeds[0];
    for (int s = 1; s < ns; s++) {
        lo = fmin(lo, w->speeds[s]);
        hi = fmax(hi, w->speeds[s]);
    }
    for (int o = 0; o < w->norders; o++) {
        double ord = w->orders[o].order;
        if (ord > otop) continue;
        char label[96];
        pl_order_label(&w->orders[o], label, sizeof label);
        /* named at the line's end: every other one drawn downwards, so neighbouring
         * orders' names sit at the top and at the bottom */
        double ox[2] = {ord, ord}, oy[2] = {sx * (o % 2 ? hi : lo), sx * (o % 2 ? lo : hi)};
        pl_trace *t = pl_trace_add(p, map, label, 2, ox, oy, PL_LINES,
                                   w->orders[o].kind == GD_ORDER_MESH ? "#2ca02c" : "#d62728");
        if (t) {
            t->dash = 1;
            t->legend = 0;
            snprintf(t->label, sizeof t->label, "%.63s", label);
            t->label_right = 1;
        }
    }
}

gd_status gd_plot_waterfall(const gd_system *sys, const gd_waterfall *w, const gd_tr_record *rec,
                            const gd_plot_waterfall_options *opt, gd_plot **out, gd_error *err)
{
    gd_plot_waterfall_options defaults;
    gd_plot_waterfall_options_init(&defaults);
    if (!opt) opt = &defaults;
    if (!w || w->nspeeds < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot", "give --sweep-speeds",
                            "nothing to plot: no spectrum");
    int ns = w->nspeeds;
    /* axis units: speeds rpm or rad/s (sx per rad/s), frequencies Hz or rad/s (fy per Hz) */
    double sx = opt->speed_rad_s ? 1 : 30 / PI, fy = opt->frequency_rad_s ? 2 * PI : 1;
    const char *su = opt->speed_rad_s ? "rad/s" : "rpm",
               *fu = opt->frequency_rad_s ? "rad/s" : "Hz";
    /* the frequency axis: to the cap, else 1.2 x the highest order at the top speed (the
     * mesh orders), within the largest spectrum's last bin */
    double nyq = 0, top = 0, amax = 0, wtop = w->speeds[0], wlo = w->speeds[0];
    for (int s = 0; s < ns; s++) {
        nyq = fmax(nyq, w->spectra[s]->freq[w->spectra[s]->n - 1]);
        wtop = fmax(wtop, w->speeds[s]);
        wlo = fmin(wlo, w->speeds[s]);
    }
    for (int o = 0; o < w->norders; o++)
        top = fmax(top, 1.2 * w->orders[o].order * wtop / (2 * PI));
    double ftop = opt->max_frequency_hz > 0 ? opt->max_frequency_hz : top > 0 ? top : nyq;
    ftop = fmin(ftop, nyq);
    for (int s = 0; s < ns; s++)
        for (int k = 1; k < w->spectra[s]->n && w->spectra[s]->freq[k] <= ftop; k++)
            amax = fmax(amax, w->spectra[s]->amplitude[k]);
    char name[200];
    const char *qty = "value", *unit = "";
    pl_record_describe(sys, rec, name, sizeof name, &qty, &unit);
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn run-up waterfall", &p, err);
    if (st) return st;
    pl_section *sec = pl_section_add(p, "Run-up waterfall");
    if (w->tracked)
        pl_note(p, sec,
                "Run-up through a speed profile, order tracking: %s resampled on the reference "
                "shaft's angle, one amplitude spectrum (Hann window, mean removed) per block of "
                "%g revolutions, %d blocks from %.6g to %.6g %s (each at its mean speed; bins "
                "%.3g orders apart). Largest amplitude %.4g %s.",
                name, w->revs_per_block, ns, sx * wlo, sx * wtop, su, 1 / w->revs_per_block, amax,
                unit);
    else
        pl_note(p, sec,
                "Stepped (quasi-steady) run-up: %d speeds from %.6g to %.6g %s, each a steady "
                "run started from the previous speed's end state; at each speed the amplitude "
                "spectrum (Hann window, mean removed) of %s over the settled part. Largest "
                "amplitude %.4g %s.",
                ns, sx * wlo, sx * wtop, su, name, amax, unit);
    if (sec) snprintf(sec->csv_name, sizeof sec->csv_name, "waterfall.csv");
    pl_csv(p, sec, "speed_rad_s,speed_rpm,frequency_hz,amplitude\n");
    /* the cascade: each spectrum drawn from its speed up, its height the level in dB
     * above 80 dB below the largest amplitude, 80 dB = 3 speed steps (the mean spacing;
     * one speed: 10 % of it), so a mesh order 70 dB under the 1x peak still shows */
    double step = ns > 1 ? sx * (wtop - wlo) / (ns - 1) : 0.1 * sx * wtop;
    double gain = 3 * step / (DB_STEP * NLEVELS);
    char xl[64], yl[200], title[300];
    snprintf(xl, sizeof xl, "frequency (%s)", fu);
    snprintf(yl, sizeof yl, "speed (%s); spectra: 3 speed steps = %g dB", su, DB_STEP * NLEVELS);
    snprintf(title, sizeof title, "%s: cascade of the spectra over speed (%s), orders", name, unit);
    pl_panel *cas = pl_panel_add(p, sec, PL_XY, title, xl, yl);
    snprintf(xl, sizeof xl, "reference speed (%s)", su);
    snprintf(yl, sizeof yl, "frequency (%s)", fu);
    snprintf(title, sizeof title, "%s: colour map, amplitude in dB below %.4g %s, orders", name,
             amax, unit);
    pl_panel *map = pl_panel_add(p, sec, PL_XY, title, xl, yl);
    if (cas) {
        cas->xlim[0] = 0;
        cas->xlim[1] = fy * ftop;
    }
    if (map) {
        map->ylim[0] = 0;
        map->ylim[1] = fy * ftop;
    }
    /* the colour map: one trace per 10 dB level (the legend is the colour scale) */
    int lv[NLEVELS]; /* trace index of each level (pointers move as the panel grows), -1 */
    int cnt[NLEVELS] = {0};
    for (int l = 0; l < NLEVELS; l++)
        lv[l] = -1;
    for (int s = 0; s < ns; s++)
        for (int k = 1; k < w->spectra[s]->n && w->spectra[s]->freq[k] <= ftop; k++) {
            int l = level_of(w->spectra[s]->amplitude[k], amax);
            if (l >= 0) cnt[l]++;
        }
    for (int l = 0; map && l < NLEVELS; l++) {
        if (!cnt[l]) continue;
        char ln[64];
        snprintf(ln, sizeof ln, "%g to %g dB", l ? -DB_STEP * l : 0.0, -DB_STEP * (l + 1));
        pl_trace *t = pl_trace_add(p, map, ln, cnt[l], NULL, NULL, PL_MARKERS, level_color(l));
        if (t && t->x && t->y) {
            t->symbol = PL_SQUARE;
            lv[l] = (int)(t - map->traces);
        }
        cnt[l] = 0;
    }
    for (int s = 0; s < ns; s++) {
        const gd_spectrum *sp = w->spectra[s];
        int nb = 0;
        while (nb < sp->n && sp->freq[nb] <= ftop)
            nb++;
        double *cx = malloc((size_t)(nb > 0 ? nb : 1) * sizeof *cx),
               *cy = malloc((size_t)(nb > 0 ? nb : 1) * sizeof *cy);
        if (!cx || !cy) p->nomem = 1;
        for (int k = 0; cx && cy && k < nb; k++) {
            cx[k] = fy * sp->freq[k];
            double lv_db = sp->amplitude[k] > 0 && amax > 0
                               ? 20 * log10(sp->amplitude[k] / amax) + DB_STEP * NLEVELS
                               : 0;
            cy[k] = sx * w->speeds[s] + gain * fmax(lv_db, 0);
            pl_csv(p, sec, "%.10g,%.10g,%.10g,%.10g\n", w->speeds[s], w->speeds[s] * 30 / PI,
                   sp->freq[k], sp->amplitude[k]);
            int l = level_of(sp->amplitude[k], amax);
            if (k > 0 && l >= 0 && lv[l] >= 0) {
                pl_trace *t = &map->traces[lv[l]];
                int i = cnt[l]++;
                t->x[i] = sx * w->speeds[s];
                t->y[i] = cx[k];
                pl_trace_text(p, t, i, "%.6g %s, %.6g %s: %.4g %s (%.1f dB)", t->x[i], su, cx[k],
                              fu, sp->amplitude[k], unit, 20 * log10(sp->amplitude[k] / amax));
            }
        }
        char tn[96];
        snprintf(tn, sizeof tn, "%.6g %s", sx * w->speeds[s], su);
        pl_trace *t = cx && cy ? pl_trace_add(p, cas, tn, nb, cx, cy, PL_LINES, "#1f4fd6") : NULL;
        if (t) {
            t->legend = 0;
            for (int k = 0; k < nb; k++)
                pl_trace_text(p, t, k, "%.6g %s, %.6g %s: %.4g %s", sx * w->speeds[s], su, cx[k],
                              fu, sp->amplitude[k], unit);
        }
        free(cx);
        free(cy);
    }
    /* orders: f = order x speed / 2 pi over the speed range, cut at the frequency cap;
     * named at their end */
    for (int o = 0; o < w->norders; o++) {
        double ord = w->orders[o].order, w1 = wtop;
        if (ord * w1 / (2 * PI) > ftop) w1 = ftop * 2 * PI / ord;
        if (w1 <= wlo) continue; /* wholly above the axis */
        char label[96];
        pl_order_label(&w->orders[o], label, sizeof label);
        const char *col = w->orders[o].kind == GD_ORDER_MESH ? "#2ca02c" : "#d62728";
        double fx[2] = {fy * ord * wlo / (2 * PI), fy * ord * w1 / (2 * PI)},
               sy[2] = {sx * wlo, sx * w1};
        pl_trace *t = pl_trace_add(p, cas, label, 2, fx, sy, PL_LINES, col);
        if (t) {
            t->dash = 1;
            snprintf(t->label, sizeof t->label, "%.63s", label);
            t->label_right = o % 2; /* neighbours' names on either side */
        }
        t = pl_trace_add(p, map, label, 2, sy, fx, PL_LINES, col);
        if (t) {
            t->dash = 1;
            t->legend = 0;
            snprintf(t->label, sizeof t->label, "%.63s", label);
            t->label_right = w1 < wtop;
            t->label_below = o % 2;
        }
    }
    if (w->tracked) order_map(p, sec, w, name, unit, amax, sx, su, ftop, wtop);
    /* order cuts */
    snprintf(title, sizeof title,
             "%s: order cuts (largest amplitude within 1.5 bins of each order)", name);
    snprintf(yl, sizeof yl, "amplitude (%s)", unit);
    pl_panel *cut = pl_panel_add(p, sec, PL_XY, title, xl, yl);
    if (cut) cut->ylog = 1;
    double *x = malloc((size_t)ns * sizeof *x);
    if (!x) p->nomem = 1;
    for (int s = 0; x && s < ns; s++)
        x[s] = sx * w->speeds[s];
    for (int o = 0; x && o < w->norders; o++) {
        char label[96];
        pl_order_label(&w->orders[o], label, sizeof label);
        pl_trace *t = pl_trace_add(p, cut, label, ns, x, w->order_amplitude + (size_t)o * ns,
                                   PL_LINES_MARKERS, pl_color(o));
        for (int s = 0; t && s < ns; s++)
            pl_trace_text(p, t, s, "%s at %.6g %s: %.4g %s at %.6g %s", label, x[s], su,
                          w->order_amplitude[(size_t)o * ns + s], unit,
                          fy * w->order_frequency[(size_t)o * ns + s], fu);
    }
    free(x);
    return pl_done(p, out, err);
}
