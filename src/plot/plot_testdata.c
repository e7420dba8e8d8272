/* Figures of test data: the stabilisation diagram of an LSCF fit (poles over model
 * order, marked by stability, over the summed FRF magnitude) and the overlay of the
 * model's FRF on the measured one, magnitude and phase ([MMT2018] Figs. 9-10), with the
 * correlation table (Tables 4-5). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

gd_status gd_plot_stabilisation(const gd_ema_result *r, int nfrf, const gd_td_function *const *frfs,
                                gd_plot **out, gd_error *err)
{
    *out = NULL;
    if (!r->npoles)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot",
                            "the stabilisation diagram is LSCF's (--method lscf)",
                            "no poles to plot");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn stabilisation diagram", &p, err);
    if (st) return st;
    pl_section *s = pl_section_add(p, "Stabilisation diagram (LSCF)");
    pl_note(p, s,
            "%d FRFs, %d lines from %.4g to %.4g Hz, model orders 1 to %d; %d modes chosen "
            "(poles stable in frequency and damping over most of the upper half of the "
            "orders).",
            nfrf, r->nlines, r->band_lo_hz, r->band_hi_hz, r->max_order, r->nmodes);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "stabilisation.csv");
    pl_panel *pn =
        pl_panel_add(p, s, PL_XY, "poles over model order", "frequency (Hz)", "model order");
    static const char STATUS[3] = {'o', 'f', 's'};
    static const char *const NAMES[3] = {"new pole", "stable frequency",
                                         "stable frequency and damping"};
    static const char *const COLORS[3] = {"#bbbbbb", "#1f77b4", "#2ca02c"};
    double *x = malloc((size_t)r->npoles * sizeof *x), *y = malloc((size_t)r->npoles * sizeof *y);
    if (!x || !y) p->nomem = 1;
    for (int k = 0; x && y && pn && k < 3; k++) {
        int n = 0;
        for (int i = 0; i < r->npoles; i++)
            if (r->poles[i].status == STATUS[k]) {
                x[n] = r->poles[i].frequency_hz;
                y[n++] = r->poles[i].order;
            }
        if (!n) continue;
        pl_trace *t = pl_trace_add(p, pn, NAMES[k], n, x, y, PL_MARKERS, COLORS[k]);
        if (t) t->symbol = k == 2 ? PL_CIRCLE : k == 1 ? PL_TRIANGLE : PL_SQUARE;
    }
    if (pn) {
        pn->xint = 0;
        /* the summed magnitude on the right-hand axis */
        int n = frfs[0]->n, m = 0;
        double *fx = malloc((size_t)n * sizeof *fx), *fy = malloc((size_t)n * sizeof *fy);
        if (!fx || !fy) p->nomem = 1;
        for (int k = 0; fx && fy && k < n; k++) {
            if (frfs[0]->freq_hz[k] < r->band_lo_hz || frfs[0]->freq_hz[k] > r->band_hi_hz)
                continue;
            double a = 0;
            for (int o = 0; o < nfrf; o++)
                a += hypot(frfs[o]->re[k], frfs[o]->im[k]);
            fx[m] = frfs[0]->freq_hz[k];
            fy[m++] = a > 0 ? log10(a) : NAN;
        }
        if (fx && fy && m) {
            pl_trace *t = pl_trace_add(p, pn, "log10 sum |H|", m, fx, fy, PL_LINES, "#d62728");
            if (t) t->y2 = 1;
            snprintf(pn->y2label, sizeof pn->y2label, "log10 of the summed |H|");
        }
        free(fx);
        free(fy);
        for (int j = 0; x && j < r->nmodes; j++) {
            double mx[2] = {r->modes[j].frequency_hz, r->modes[j].frequency_hz};
            double my[2] = {0, r->max_order};
            pl_trace *t = pl_trace_add(p, pn, j ? "" : "modes", 2, mx, my, PL_LINES, "#000000");
            if (t) {
                t->dash = 1;
                t->legend = j == 0;
            }
        }
    }
    pl_csv(p, s, "order,frequency_hz,damping_ratio,status\n");
    for (int i = 0; i < r->npoles; i++)
        pl_csv(p, s, "%d,%.10g,%.6g,%c\n", r->poles[i].order, r->poles[i].frequency_hz,
               r->poles[i].damping_ratio, r->poles[i].status);
    free(x);
    free(y);
    return pl_done(p, out, err);
}

gd_status gd_plot_correlation(int nfrf, const gd_td_function *const *frfs,
                              const double *const *model_re, const double *const *model_im,
                              const gd_corr_table *t, gd_plot **out, gd_error *err)
{
    *out = NULL;
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn correlation", &p, err);
    if (st) return st;
    if (t) {
        pl_section *s = pl_section_add(p, "Measured against model frequencies");
        pl_note(p, s,
                "%% difference = (f_model - f_test) / f_model x 100, as [MMT2018] "
                "Tables 4-5; rms %.3f %%.",
                t->rms_pct);
        pl_panel *pn = pl_panel_add(p, s, PL_TABLE, "paired modes", "", "");
        if (pn) {
            pl_table_init(p, pn, t->npairs, 5);
            const char *head[5] = {"mode", "test (Hz)", "model (Hz)", "% difference", "MAC"};
            for (int c = 0; c < 5; c++)
                pl_cell(p, pn, 0, c, "%s", head[c]);
            for (int i = 0; i < t->npairs; i++) {
                const gd_corr_pair *q = &t->pairs[i];
                pl_cell(p, pn, i + 1, 0, "%d", i + 1);
                pl_cell(p, pn, i + 1, 1, "%.2f", q->f_test);
                pl_cell(p, pn, i + 1, 2, "%.2f", q->f_model);
                pl_cell(p, pn, i + 1, 3, "%.2f", q->diff_pct);
                if (isfinite(q->mac))
                    pl_cell(p, pn, i + 1, 4, "%.4f", q->mac);
                else
                    pl_cell(p, pn, i + 1, 4, "-");
            }
        }
    }
    for (int o = 0; o < nfrf; o++) {
        const gd_td_function *f = frfs[o];
        char title[200];
        snprintf(title, sizeof title, "%s: %s%d / %s%d (%s)", f->name,
                 gd_td_dir_name(f->response_dir), f->response_node,
                 gd_td_dir_name(f->reference_dir), f->reference_node,
                 gd_td_quantity_names[f->quantity]);
        pl_section *s = pl_section_add(p, title);
        if (s) snprintf(s->csv_name, sizeof s->csv_name, "frf_%d.csv", o + 1);
        pl_panel *mag = pl_panel_add(p, s, PL_XY, "magnitude", "frequency (Hz)", "|H| (SI)");
        pl_panel *ph = pl_panel_add(p, s, PL_XY, "phase", "frequency (Hz)", "phase (deg)");
        if (mag) mag->ylog = 1;
        int n = f->n;
        double *a = malloc((size_t)n * sizeof *a), *b = malloc((size_t)n * sizeof *b);
        if (!a || !b) p->nomem = 1;
        for (int w = 0; a && b && w < 2; w++) {
            const double *re = w ? model_re[o] : f->re, *im = w ? model_im[o] : f->im;
            for (int k = 0; k < n; k++) {
                a[k] = hypot(re[k], im[k]);
                b[k] = atan2(im[k], re[k]) * 180 / M_PI;
            }
            const char *name = w ? "model" : "measured", *color = w ? "#d62728" : "#1f77b4";
            if (mag) pl_trace_add(p, mag, name, n, f->freq_hz, a, PL_LINES, color);
            if (ph) pl_trace_add(p, ph, name, n, f->freq_hz, b, PL_LINES, color);
        }
        pl_csv(p, s, "frequency_hz,test_re,test_im,model_re,model_im\n");
        for (int k = 0; k < n; k++)
            pl_csv(p, s, "%.10g,%.8g,%.8g,%.8g,%.8g\n", f->freq_hz[k], f->re[k], f->im[k],
                   model_re[o][k], model_im[o][k]);
        free(a);
        free(b);
    }
    return pl_done(p, out, err);
}
