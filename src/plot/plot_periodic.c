/* Periodic steady state: per record the peak-to-peak value and the amplitudes at the
 * excitation orders along the branch (stable solid, unstable dashed red, the return run
 * as its own curves), the bifurcations marked by type, and the largest Floquet
 * multiplier. The harmonics k w of the solution are named by the orders k w / W they are
 * (W the reference speed): the model's shaft and tooth-mesh orders (gd_campbell's) and
 * multiples of the mesh orders, not "harmonic k" of a period that may be an
 * intermediate shaft's turn. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "campbell/campbell_impl.h"
#include "plot/plot_impl.h"

#define PI 3.14159265358979323846
#define NHARM 4  /* orders drawn per record: the ones a gear response carries most */
#define MAXMUL 4 /* multiples of a mesh order named as such (2 x .. 4 x mesh) */

/* An order drawn: its name and multiple of the reference speed. */
typedef struct order_curve {
    char name[128];
    double order;
} order_curve;

/* The harmonic of point q that is order o (k w = o W), or 0 when none is (or above H). */
static int harmonic_of(const gd_periodic_point *q, double o)
{
    if (!q->converged || !(q->omega > 0) || !(q->speed > 0)) return 0;
    double k = o * q->speed / q->omega;
    long kr = lround(k);
    return kr >= 1 && kr <= q->harmonics && fabs(k - kr) <= 1e-6 * k ? (int)kr : 0;
}

/* The orders to draw, from the first converged point q0: the shaft and mesh orders that
 * are harmonics of its w, then 2 x .. 4 x each mesh order, by increasing order, at most
 * NHARM; none of them a harmonic (no teeth, a fixed-frequency load): harmonics 1 ..
 * NHARM, named by their order. Returns the count. */
static int pick_orders(const gd_system *sys, const gd_periodic_point *q0, order_curve *oc)
{
    gd_campbell_options copt;
    gd_campbell_options_init(&copt);
    gd_order *ord = NULL;
    int no = gd_campbell_orders(sys->model, &copt, &ord), n = 0;
    order_curve cand[64];
    for (int m = 1; m <= MAXMUL; m++)
        for (int i = 0; i < no && n < 64; i++) {
            if (m > 1 && ord[i].kind != GD_ORDER_MESH) continue;
            double o = m * ord[i].order;
            if (!harmonic_of(q0, o)) continue;
            int dup = 0;
            for (int j = 0; j < n; j++)
                dup |= fabs(cand[j].order - o) <= 1e-9 * o;
            if (dup) continue;
            char l[96];
            pl_order_label(&ord[i], l, sizeof l);
            if (m > 1)
                snprintf(cand[n].name, sizeof cand[n].name, "%d x %.95s", m, l);
            else
                snprintf(cand[n].name, sizeof cand[n].name, "%.95s", l);
            cand[n++].order = o;
        }
    free(ord);
    /* the lowest orders first */
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && cand[j].order < cand[j - 1].order; j--) {
            order_curve t = cand[j];
            cand[j] = cand[j - 1];
            cand[j - 1] = t;
        }
    if (n > NHARM) n = NHARM;
    for (int i = 0; i < n; i++)
        oc[i] = cand[i];
    if (n) return n;
    for (int k = 1; k <= NHARM && k <= q0->harmonics; k++) {
        oc[n].order = k * q0->omega / q0->speed;
        snprintf(oc[n].name, sizeof oc[n].name, "order %.4gx (harmonic %d)", oc[n].order, k);
        n++;
    }
    return n;
}

static const char *const UNSTABLE_COLOR = "#d62728";
static const char *const RETURN_COLOR = "#7f7f7f";

/* x of a point: speed in rpm, or the continuation parameter */
static double xof(int param, double speed, double parameter)
{
    return param ? parameter : speed * 30 / PI;
}

static int unstable(const gd_periodic_point *p)
{
    return p->converged && p->stable == 0;
}

/* The points of one run (direction dir) in branch order: their indices; the count. */
static int run_points(const gd_periodic_result *r, int dir, int *idx)
{
    int n = 0;
    for (int i = 0; i < r->npoints; i++)
        if (r->points[i].direction == dir) idx[n++] = i;
    return n;
}

/* The value v(point) at a bifurcation at x = bx on run idx[0..n): interpolated between
 * the two neighbouring points that bracket it (preferring a pair whose stability
 * differs, the crossing the bifurcation was located in), else the nearest point's value
 * (a fold lies beyond both of its neighbours). NaN when no point converged. */
static double at_bifurcation(const gd_periodic_result *r, const int *idx, int n, int param,
                             double bx, int rec, double (*v)(const gd_periodic_point *, int))
{
    double best = NAN, dist = INFINITY;
    int found = 0;
    for (int j = 0; j + 1 < n; j++) {
        const gd_periodic_point *a = &r->points[idx[j]], *b = &r->points[idx[j + 1]];
        if (!a->converged || !b->converged) continue;
        double xa = xof(param, a->speed, a->parameter), xb = xof(param, b->speed, b->parameter);
        if ((bx - xa) * (bx - xb) > 0 || xa == xb) continue;
        int pref = a->stable != b->stable;
        if (found && !pref) continue;
        best = v(a, rec) + (v(b, rec) - v(a, rec)) * (bx - xa) / (xb - xa);
        found = 1 + pref;
        if (pref) break;
    }
    for (int j = 0; !found && j < n; j++) {
        const gd_periodic_point *a = &r->points[idx[j]];
        double d = fabs(xof(param, a->speed, a->parameter) - bx);
        if (a->converged && d < dist) dist = d, best = v(a, rec);
    }
    return best;
}

static double p2p(const gd_periodic_point *p, int rec)
{
    return p->records[rec].peak_to_peak;
}

static double mu_max(const gd_periodic_point *p, int rec)
{
    (void)rec;
    return p->mu_max;
}

static const pl_symbol BIF_SYMBOL[4] = {PL_TRIANGLE, PL_DIAMOND, PL_SQUARE, PL_CIRCLE};
static const char *const BIF_COLOR[4] = {"#000000", "#9467bd", "#2ca02c", "#8c564b"};

/* One marker trace per bifurcation type found, on panel pn, at v's value. */
static void mark_bifurcations(gd_plot *p, pl_panel *pn, const gd_periodic_result *r, int param,
                              int rec, double (*v)(const gd_periodic_point *, int), int *idx)
{
    for (int t = 0; t < 4; t++) {
        int nb = 0;
        for (int i = 0; i < r->nbifurcations; i++)
            nb += r->bifurcations[i].type == (gd_bifurcation_type)t;
        if (!nb) continue;
        pl_trace *m = pl_trace_add(p, pn, gd_bifurcation_name((gd_bifurcation_type)t), nb, NULL,
                                   NULL, PL_MARKERS, BIF_COLOR[t]);
        if (!m) return;
        m->symbol = BIF_SYMBOL[t];
        for (int i = 0, k = 0; i < r->nbifurcations; i++) {
            const gd_bifurcation *b = &r->bifurcations[i];
            if (b->type != (gd_bifurcation_type)t) continue;
            int n = run_points(r, b->direction, idx);
            m->x[k] = xof(param, b->speed, b->parameter);
            m->y[k] = at_bifurcation(r, idx, n, param, m->x[k], rec, v);
            if (isfinite(b->mu_re))
                pl_trace_text(p, m, k, "%s at %.6g %s, critical multiplier %.6f%+.6fi",
                              gd_bifurcation_name(b->type), m->x[k], param ? "" : "rpm", b->mu_re,
                              b->mu_im);
            else
                pl_trace_text(p, m, k, "%s at %.6g %s", gd_bifurcation_name(b->type), m->x[k],
                              param ? "" : "rpm");
            k++;
        }
    }
}

/* The stable and unstable curves of v along one run: the unstable curve also holds the
 * stable neighbours of unstable points, so the dashed stretch joins the solid ones. */
static void stability_curves(gd_plot *p, pl_panel *pn, const gd_periodic_result *r, int param,
                             int rec, const int *idx, int n, int dir, int assessed)
{
    char name[160];
    snprintf(name, sizeof name, "%s%s", assessed ? "stable" : "solution",
             dir < 0 ? " (return run)" : "");
    pl_trace *s = pl_trace_add(p, pn, name, n, NULL, NULL, PL_LINES_MARKERS,
                               dir < 0 ? RETURN_COLOR : pl_color(rec));
    pl_trace *u = NULL;
    if (assessed) {
        snprintf(name, sizeof name, "unstable%s", dir < 0 ? " (return run)" : "");
        u = pl_trace_add(p, pn, name, n, NULL, NULL, PL_LINES_MARKERS, UNSTABLE_COLOR);
        if (u) u->dash = 1;
    }
    for (int j = 0; s && j < n; j++) {
        const gd_periodic_point *q = &r->points[idx[j]];
        double y = q->converged ? p2p(q, rec) : NAN;
        s->x[j] = xof(param, q->speed, q->parameter);
        s->y[j] = unstable(q) ? NAN : y;
        if (!u) continue;
        int near = unstable(q) || (j > 0 && unstable(&r->points[idx[j - 1]])) ||
                   (j + 1 < n && unstable(&r->points[idx[j + 1]]));
        u->x[j] = s->x[j];
        u->y[j] = near ? y : NAN;
    }
}

gd_status gd_plot_periodic(const gd_system *sys, const gd_periodic_result *r,
                           const gd_tr_record *records, gd_plot **out, gd_error *err)
{
    int nconv = 0, assessed = 0, hmax = 0, ndir = 1;
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *q = &r->points[i];
        nconv += q->converged;
        assessed |= q->converged && q->stable >= 0;
        if (q->converged && q->harmonics > hmax) hmax = q->harmonics;
        if (q->direction < 0) ndir = 2;
    }
    if (r->nrecords == 0 || nconv == 0)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot",
                            r->nrecords ? "see the reasons in the table or --json output"
                                        : "record something (--record)",
                            "nothing to plot: %s",
                            r->nrecords ? "no point converged" : "no record");
    int param = !isnan(r->points[0].parameter);
    const gd_periodic_point *q0 = NULL;
    for (int i = 0; i < r->npoints && !q0; i++)
        if (r->points[i].converged) q0 = &r->points[i];
    order_curve oc[NHARM];
    int nh = pick_orders(sys, q0, oc);
    (void)hmax;
    const char *xl = param ? "continuation parameter (SI units)" : "reference speed (rpm)";
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn periodic steady state", &p, err);
    if (st) return st;
    pl_section *s = pl_section_add(p, "Periodic steady state (harmonic balance)");
    int nr = r->nrecords;
    pl_note(p, s,
            "%d points (%d converged) over %d continuation step%s; %d bifurcation%s; %s. "
            "Stable branches solid, unstable dashed red%s.",
            r->npoints, nconv, r->steps, r->steps == 1 ? "" : "s", r->nbifurcations,
            r->nbifurcations == 1 ? "" : "s",
            assessed ? "Floquet stability computed" : "stability not computed",
            ndir == 2 ? ", the return run grey" : "");
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "periodic.csv");
    char(*names)[200] = calloc((size_t)nr, sizeof *names);
    const char **qty = calloc((size_t)nr, sizeof *qty), **unit = calloc((size_t)nr, sizeof *unit);
    int *idx = malloc((size_t)(r->npoints > 0 ? r->npoints : 1) * sizeof *idx);
    if (!names || !qty || !unit || !idx) p->nomem = 1;
    for (int k = 0; !p->nomem && k < nr; k++)
        pl_record_describe(sys, &records[k], names[k], sizeof names[k], &qty[k], &unit[k]);
    /* the CSV: one row per point */
    pl_csv(p, s, "point,direction,%s,converged,stable,floquet_multiplier_max_abs",
           param ? "parameter" : "speed_rpm");
    for (int k = 0; !p->nomem && k < nr; k++) {
        pl_csv(p, s, ",\"%s peak-to-peak (%s)\"", names[k], unit[k]);
        for (int h = 0; h < nh; h++)
            pl_csv(p, s, ",\"%s %s (%s)\"", names[k], oc[h].name, unit[k]);
    }
    pl_csv(p, s, "\n");
    for (int i = 0; !p->nomem && i < r->npoints; i++) {
        const gd_periodic_point *q = &r->points[i];
        pl_csv(p, s, "%d,%d,%.10g,%d,%d,%.10g", i, q->direction, xof(param, q->speed, q->parameter),
               q->converged, q->stable, q->mu_max);
        for (int k = 0; k < nr; k++) {
            pl_csv(p, s, ",%.10g", q->converged ? q->records[k].peak_to_peak : NAN);
            for (int h = 0; h < nh; h++) {
                int hk = harmonic_of(q, oc[h].order);
                pl_csv(p, s, ",%.10g", hk ? q->records[k].amplitude[hk] : NAN);
            }
        }
        pl_csv(p, s, "\n");
    }
    for (int k = 0; !p->nomem && k < nr; k++) {
        char title[300], ylabel[160];
        snprintf(title, sizeof title, "peak-to-peak: %s", names[k]);
        snprintf(ylabel, sizeof ylabel, "peak-to-peak %s (%s)", qty[k], unit[k]);
        pl_panel *pp = pl_panel_add(p, s, PL_XY, title, xl, ylabel);
        snprintf(title, sizeof title, "amplitudes at the excitation orders: %s", names[k]);
        snprintf(ylabel, sizeof ylabel, "amplitude (%s)", unit[k]);
        pl_panel *hp = pl_panel_add(p, s, PL_XY, title, xl, ylabel);
        if (hp) hp->ylog = 1;
        for (int d = 0; d < ndir; d++) {
            int dir = d ? -1 : 1, n = run_points(r, dir, idx);
            stability_curves(p, pp, r, param, k, idx, n, dir, assessed);
            for (int h = 0; h < nh; h++) {
                char name[160];
                snprintf(name, sizeof name, "%.127s%s", oc[h].name, d ? " (return run)" : "");
                pl_trace *t = pl_trace_add(p, hp, name, n, NULL, NULL, PL_LINES, pl_color(h));
                if (t) t->dash = d;
                for (int j = 0; t && j < n; j++) {
                    const gd_periodic_point *q = &r->points[idx[j]];
                    int hk = harmonic_of(q, oc[h].order);
                    t->x[j] = xof(param, q->speed, q->parameter);
                    t->y[j] = hk ? q->records[k].amplitude[hk] : NAN;
                    if (hk)
                        pl_trace_text(p, t, j,
                                      "%s (%.6gx, harmonic %d of %.6g Hz): %.4g %s at %.6g %s",
                                      oc[h].name, oc[h].order, hk, q->omega / (2 * PI), t->y[j],
                                      unit[k], t->x[j], param ? "" : "rpm");
                }
            }
        }
        mark_bifurcations(p, pp, r, param, k, p2p, idx);
    }
    if (assessed && !p->nomem) {
        pl_panel *fp = pl_panel_add(p, s, PL_XY, "stability: largest Floquet multiplier modulus",
                                    xl, "max |Floquet multiplier| (-)");
        double lo = INFINITY, hi = -INFINITY;
        for (int d = 0; d < ndir; d++) {
            int dir = d ? -1 : 1, n = run_points(r, dir, idx);
            pl_trace *t = pl_trace_add(p, fp, d ? "|mu| max (return run)" : "|mu| max", n, NULL,
                                       NULL, PL_LINES_MARKERS, d ? RETURN_COLOR : pl_color(0));
            for (int j = 0; t && j < n; j++) {
                const gd_periodic_point *q = &r->points[idx[j]];
                t->x[j] = xof(param, q->speed, q->parameter);
                t->y[j] = q->converged ? q->mu_max : NAN;
                lo = fmin(lo, t->x[j]);
                hi = fmax(hi, t->x[j]);
            }
        }
        double ox[2] = {lo, hi}, oy[2] = {1, 1};
        pl_trace *one = pl_trace_add(p, fp, "|mu| = 1", 2, ox, oy, PL_LINES, "#555");
        if (one) one->dash = 1;
        mark_bifurcations(p, fp, r, param, 0, mu_max, idx);
    }
    pl_panel *tb = pl_panel_add(p, s, PL_TABLE, "bifurcations", NULL, NULL);
    pl_table_init(p, tb, r->nbifurcations, 5);
    const char *head[5] = {"type", "run", param ? "parameter" : "speed (rpm)", "speed (rad/s)",
                           "critical multiplier"};
    for (int c = 0; c < 5; c++)
        pl_cell(p, tb, 0, c, "%s", head[c]);
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        pl_cell(p, tb, i + 1, 0, "%s", gd_bifurcation_name(b->type));
        pl_cell(p, tb, i + 1, 1, "%s", b->direction > 0 ? "forward" : "return");
        pl_cell(p, tb, i + 1, 2, "%.8g", xof(param, b->speed, b->parameter));
        pl_cell(p, tb, i + 1, 3, "%.8g", b->speed);
        if (isfinite(b->mu_re))
            pl_cell(p, tb, i + 1, 4, "%.6f%+.6fi", b->mu_re, b->mu_im);
        else
            pl_cell(p, tb, i + 1, 4, "-");
    }
    free(names);
    free(qty);
    free(unit);
    free(idx);
    return pl_done(p, out, err);
}
