/* Time-varying mesh stiffness: k over the driver angle with the single- and
 * double-contact zones shaded, the stiffness of each tooth pair, ISO 6336 values, the
 * Fourier harmonics, and several results (e.g. helix angles) compared. */
#include <math.h>
#include <stdlib.h>

#include "plot/plot_impl.h"

#define PI 3.14159265358979323846

/* Rectangles [x_i, x_{i+1}] x [lo, hi] over the samples where exactly `want` tooth pairs
 * are in contact, as one fill trace (NaN between rectangles): with a contact ratio of
 * 2.6 the zones are 2 and 3 pairs, not "single" and "double". */
static void zones(gd_plot *p, pl_panel *pn, const gd_tvms_result *r, const double *x, int want,
                  double lo, double hi, const char *color)
{
    size_t n = r->n, cap = 6 * n + 6, k = 0;
    double *zx = malloc(cap * sizeof *zx), *zy = malloc(cap * sizeof *zy);
    if (!zx || !zy) {
        p->nomem = 1;
        free(zx);
        free(zy);
        return;
    }
    double step = r->mesh_period_rad / (double)r->points * 180 / PI;
    size_t i = 0;
    while (i < n) {
        if (r->pairs_in_contact[i] != want) {
            i++;
            continue;
        }
        size_t j = i;
        while (j + 1 < n && r->pairs_in_contact[j + 1] == want)
            j++;
        double a = x[i], b = x[j] + step;
        double px[6] = {a, b, b, a, a, NAN}, py[6] = {lo, lo, hi, hi, lo, NAN};
        for (int q = 0; q < 6; q++)
            zx[k] = px[q], zy[k++] = py[q];
        i = j + 1;
    }
    char name[48];
    snprintf(name, sizeof name, "%d pair%s in contact", want, want == 1 ? "" : "s");
    if (k) pl_trace_add(p, pn, name, (int)k - 1, zx, zy, PL_FILL, color);
    free(zx);
    free(zy);
}

gd_status gd_plot_tvms(const gd_tvms_result *const *rs, const char *const *labels, int nres,
                       const char *name, gd_plot **out, gd_error *err)
{
    if (nres < 1 || !rs[0] || rs[0]->n < 2)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot", "",
                            "nothing to plot: no stiffness");
    const gd_tvms_result *r = rs[0];
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn mesh stiffness", &p, err);
    if (st) return st;
    char title[200];
    snprintf(title, sizeof title, "Mesh stiffness%s%s", name ? " of " : "", name ? name : "");
    pl_section *s = pl_section_add(p, title);
    const gd_gear_pair_derived *d = &r->geom;
    pl_note(p, s,
            "%s method; contact ratio transverse %.4f, face %.4f, total %.4f; k along the "
            "contact normal: mean %.5g, max %.5g, min %.5g N/m; ISO 6336 c_gamma_alpha b = "
            "%.5g N/m.",
            gd_tvms_method_name(r->method), d->contact_ratio_transverse, d->contact_ratio_face,
            d->contact_ratio_total, r->mean, r->max, r->min, r->iso_mesh_stiffness_alpha);
    if (s)
        snprintf(s->csv_name, sizeof s->csv_name, "mesh_stiffness%s%s.csv", name ? "_" : "",
                 name ? name : "");
    int n = (int)r->n, mp = r->max_pairs;
    double *x = malloc((size_t)n * sizeof *x);
    if (!x) p->nomem = 1;
    for (int i = 0; x && i < n; i++)
        x[i] = r->angle_rad[i] * 180 / PI;
    pl_panel *k = pl_panel_add(
        p, s, PL_XY, "time-varying mesh stiffness (shaded by the number of tooth pairs in contact)",
        "driver angle (deg)", "mesh stiffness k (N/m)");
    if (x && k) {
        /* the y axis around the ripple (a 1.5-4.6 % ripple is invisible from 0), with
         * the ISO and mean lines inside */
        double lo = fmin(r->min, r->iso_mesh_stiffness_alpha),
               hi = fmax(r->max, r->iso_mesh_stiffness_alpha);
        double pad = 0.12 * (hi - lo > 0 ? hi - lo : 0.05 * fabs(hi));
        k->ylim[0] = lo - pad;
        k->ylim[1] = hi + pad;
        int pmin = r->pairs_in_contact[0], pmax = pmin;
        for (int i = 1; i < n; i++) {
            if (r->pairs_in_contact[i] < pmin) pmin = r->pairs_in_contact[i];
            if (r->pairs_in_contact[i] > pmax) pmax = r->pairs_in_contact[i];
        }
        static const char *const zc[4] = {"#ff7f0e", "#1f77b4", "#2ca02c", "#9467bd"};
        for (int c = pmin; c <= pmax; c++)
            if (c > 0) zones(p, k, r, x, c, k->ylim[0], k->ylim[1], zc[(c - pmin) % 4]);
        pl_trace_add(p, k, "k (normal plane)", n, x, r->stiffness, PL_LINES, "#000");
        double lx[2] = {x[0], x[n - 1]},
               ly[2] = {r->iso_mesh_stiffness_alpha, r->iso_mesh_stiffness_alpha};
        pl_trace *t =
            pl_trace_add(p, k, "ISO 6336 c_gamma_alpha b", 2, lx, ly, PL_LINES, "#d62728");
        if (t) t->dash = 1;
        ly[0] = ly[1] = r->mean;
        t = pl_trace_add(p, k, "mean", 2, lx, ly, PL_LINES, "#7f7f7f");
        if (t) t->dash = 1;
        pl_panel *c = pl_panel_add(
            p, s, PL_XY, "stiffness components: each tooth pair in contact (load share x k)",
            "driver angle (deg)", "pair stiffness (N/m)");
        for (int j = 0; j < mp; j++) {
            char nm[64];
            snprintf(nm, sizeof nm, "pair %d (entered %d cycle%s ago)", j, j, j == 1 ? "" : "s");
            pl_trace *pt = pl_trace_add(p, c, nm, n, x, NULL, PL_LINES, pl_color(j));
            for (int i = 0; pt && i < n; i++) {
                double sh = r->load_share[(size_t)i * mp + j];
                pt->y[i] = sh > 0 ? sh * r->stiffness[i] : NAN;
            }
        }
    }
    if (r->harmonics > 0) {
        pl_panel *h =
            pl_panel_add(p, s, PL_XY, "Fourier harmonics of k (orders of the mesh frequency)",
                         "harmonic order", "amplitude (N/m)");
        if (h) h->xint = 1; /* orders are whole numbers */
        pl_trace *t = pl_trace_add(p, h, "amplitude", r->harmonics, NULL, r->harmonic_amplitude,
                                   PL_MARKERS, "#1f77b4");
        for (int i = 0; t && i < r->harmonics; i++)
            t->x[i] = i + 1;
    }
    if (nres > 1) {
        pl_panel *c =
            pl_panel_add(p, s, PL_XY, "comparison over one mesh cycle",
                         "mesh cycles (driver angle / mesh period)", "mesh stiffness k (N/m)");
        for (int q = 0; q < nres; q++) {
            if (!rs[q]) continue;
            char nm[160];
            snprintf(nm, sizeof nm, "%s", labels && labels[q] ? labels[q] : "result");
            pl_trace *t = pl_trace_add(p, c, nm, (int)rs[q]->n, NULL, rs[q]->stiffness, PL_LINES,
                                       pl_color(q));
            for (size_t i = 0; t && i < rs[q]->n; i++)
                t->x[i] = rs[q]->angle_rad[i] / rs[q]->mesh_period_rad;
        }
    }
    pl_csv(p, s, "angle_rad,angle_deg,stiffness_N_per_m,pairs_in_contact");
    for (int j = 0; j < mp; j++)
        pl_csv(p, s, ",load_share_%d", j);
    pl_csv(p, s, "\n");
    for (int i = 0; x && i < n; i++) {
        pl_csv(p, s, "%.10g,%.10g,%.10g,%d", r->angle_rad[i], x[i], r->stiffness[i],
               r->pairs_in_contact[i]);
        for (int j = 0; j < mp; j++)
            pl_csv(p, s, ",%.6g", r->load_share[(size_t)i * mp + j]);
        pl_csv(p, s, "\n");
    }
    free(x);
    return pl_done(p, out, err);
}
