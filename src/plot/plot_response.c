/* Frequency and unbalance responses: Bode (magnitude on a log scale, phase), Nyquist /
 * polar, directional FRFs, and orbits at a chosen speed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

#define PI 3.14159265358979323846

typedef struct bode {
    pl_panel *mag, *phase, *polar;
} bode;

static void bode_panels(gd_plot *p, pl_section *s, bode *b, const char *what, const char *xlabel,
                        const char *unit)
{
    char t[200], y[120];
    snprintf(t, sizeof t, "%s: magnitude", what);
    snprintf(y, sizeof y, "magnitude (%s)", unit);
    b->mag = pl_panel_add(p, s, PL_XY, t, xlabel, y);
    if (b->mag) b->mag->ylog = 1;
    snprintf(t, sizeof t, "%s: phase", what);
    b->phase = pl_panel_add(p, s, PL_XY, t, xlabel, "phase (deg)");
    snprintf(t, sizeof t, "%s: Nyquist (polar) plot", what);
    snprintf(y, sizeof y, "imaginary part (%s)", unit);
    char x[120];
    snprintf(x, sizeof x, "real part (%s)", unit);
    b->polar = pl_panel_add(p, s, PL_XY, t, x, y);
}

/* One complex curve over x into the three panels, and its rows into the CSV. */
static void bode_curve(gd_plot *p, pl_section *s, const bode *b, const char *name, int n,
                       const double *x, const double *re, const double *im, int color)
{
    pl_trace *m = pl_trace_add(p, b->mag, name, n, x, NULL, PL_LINES, pl_color(color));
    pl_trace *ph = pl_trace_add(p, b->phase, name, n, x, NULL, PL_LINES, pl_color(color));
    pl_trace *ny = pl_trace_add(p, b->polar, name, n, re, im, PL_LINES_MARKERS, pl_color(color));
    if (!m || !ph || !ny) return;
    for (int k = 0; k < n; k++) {
        m->y[k] = hypot(re[k], im[k]);
        ph->y[k] = atan2(im[k], re[k]) * 180 / PI;
        pl_csv(p, s, "\"%s\",%.10g,%.10g,%.10g,%.10g,%.10g\n", name, x[k], m->y[k], ph->y[k], re[k],
               im[k]);
    }
}

static const char *dof_unit(gd_dof d)
{
    return d >= GD_RX ? "rad" : "m";
}

static void frf_unit(const gd_system *sys, const gd_frf_options *opt, const gd_probe *pr, char *buf,
                     size_t n)
{
    const char *in = sys->dof_type[opt->inputs[0]] >= GD_RX ? "N m" : "N";
    if (pr->kind == GD_PROBE_DOF) {
        static const char *const rate[3] = {"", "/s", "/s^2"};
        snprintf(buf, n, "%s%s/%s", dof_unit(sys->dof_type[pr->index]), rate[opt->quantity], in);
    } else {
        snprintf(buf, n, "%s/%s", pr->kind == GD_PROBE_BEARING && pr->dir >= GD_RX ? "N m" : "N",
                 in);
    }
}

gd_status gd_plot_frf(const gd_system *sys, const gd_frf_options *opt, const gd_frf_result *r,
                      gd_plot **out, gd_error *err)
{
    int nf = r->nfreq, dir = r->ninputs == 2;
    if (nf == 0 || r->noutputs == 0 || (dir && r->noutputs % 2))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot", "give outputs and frequencies",
                            "nothing to plot: no frequency response");
    if (r->nsingular == nf)
        return gd_error_set(
            err, GD_EINPUT, "", 0, 0, "--plot",
            "choose frequencies away from 0 and the undamped resonances",
            "nothing to plot: the dynamic stiffness is singular at every frequency");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn frequency response", &p, err);
    if (st) return st;
    pl_section *s = pl_section_add(p, "Frequency response");
    char inlabel[120];
    gd_system_dof_label(sys, opt->inputs[0], inlabel, sizeof inlabel);
    if (dir) {
        char *dot = strrchr(inlabel, '.');
        if (dot) snprintf(dot, sizeof inlabel - (size_t)(dot - inlabel), ".xy");
    }
    pl_note(p, s, "Response to a unit %s at %s%s, reference speed %.6g rpm, %s %s.",
            sys->dof_type[opt->inputs[0]] >= GD_RX ? "moment" : "force", inlabel,
            dir ? " (directional: forward and backward rotating)" : "", opt->speed * 30 / PI,
            opt->method == GD_FRF_MODAL ? "modal summation" : "direct solution",
            gd_frf_quantity_names[opt->quantity]);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "frf.csv");
    pl_csv(p, s, "output,frequency_hz,magnitude,phase_deg,real,imag\n");
    double *hz = malloc((size_t)nf * 5 * sizeof *hz);
    if (!hz) {
        gd_plot_free(p);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    for (int k = 0; k < nf; k++)
        hz[k] = r->freqs[k] / (2 * PI);
    char unit[64];
    frf_unit(sys, opt, &opt->outputs[0], unit, sizeof unit);
    int same = 1;
    for (int o = 1; o < r->noutputs; o++) {
        char u[64];
        frf_unit(sys, opt, &opt->outputs[o], u, sizeof u);
        same &= !strcmp(u, unit);
    }
    bode b;
    bode_panels(p, s, &b, dir ? "directional FRF" : "FRF", "frequency (Hz)",
                same ? unit : "SI units of each output per unit input");
    double *buf = hz + nf;
    int color = 0;
    for (int o = 0; o < r->noutputs; o += dir ? 2 : 1) {
        char name[200];
        if (dir) {
            gd_frf_directional(r, o, o + 1, buf, buf + nf, buf + 2 * nf, buf + 3 * nf);
            snprintf(name, sizeof name, "%s", opt->outputs[o].name);
            char *dot = strrchr(name, '.');
            if (dot) *dot = '\0';
            char nm[240];
            snprintf(nm, sizeof nm, "%s forward", name);
            bode_curve(p, s, &b, nm, nf, hz, buf, buf + nf, color++);
            snprintf(nm, sizeof nm, "%s backward", name);
            bode_curve(p, s, &b, nm, nf, hz, buf + 2 * nf, buf + 3 * nf, color++);
        } else {
            snprintf(name, sizeof name, "%s", opt->outputs[o].name);
            if (!same) {
                char u[64];
                frf_unit(sys, opt, &opt->outputs[o], u, sizeof u);
                snprintf(name + strlen(name), sizeof name - strlen(name), " (%s)", u);
            }
            bode_curve(p, s, &b, name, nf, hz, r->re + (size_t)o * nf, r->im + (size_t)o * nf,
                       color++);
        }
    }
    free(hz);
    return pl_done(p, out, err);
}

static const char *probe_unit(const gd_system *sys, const gd_probe *pr)
{
    if (pr->kind == GD_PROBE_DOF) return dof_unit(sys->dof_type[pr->index]);
    return pr->kind == GD_PROBE_BEARING && pr->dir >= GD_RX ? "N m" : "N";
}

/* The orbit ellipse: x = a cos t cos g - b sin t sin g, y = a cos t sin g + b sin t cos g. */
static void ellipse(const gd_orbit *o, double *x, double *y, int n)
{
    double cg = cos(o->angle), sg = sin(o->angle);
    for (int k = 0; k < n; k++) {
        double t = 2 * PI * k / (n - 1), a = o->major * cos(t), b = o->minor * sin(t);
        x[k] = a * cg - b * sg;
        y[k] = a * sg + b * cg;
    }
}

gd_status gd_plot_unbalance(const gd_system *sys, const gd_unbalance_options *opt,
                            const gd_unbalance_result *r, double orbit_speed, gd_plot **out,
                            gd_error *err)
{
    int ns = r->nspeeds, nh = r->nharmonics, no = r->noutputs, nb = r->norbits;
    if (ns == 0 || nh == 0 || (no == 0 && nb == 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot",
                            "add unbalances to the model and give outputs",
                            "nothing to plot: no unbalance response");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn unbalance response", &p, err);
    if (st) return st;
    double *x = malloc((size_t)ns * sizeof *x);
    if (!x) {
        gd_plot_free(p);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    for (int k = 0; k < ns; k++)
        x[k] = r->speeds[k] * 30 / PI;
    /* the speed of the orbits: given, or where the largest orbit is largest */
    int at = 0;
    double best = -1;
    for (int k = 0; k < ns; k++) {
        if (orbit_speed > 0) {
            if (fabs(r->speeds[k] - orbit_speed) < fabs(r->speeds[at] - orbit_speed)) at = k;
            continue;
        }
        for (int q = 0; q < nh * nb; q++)
            if (r->orbits[(size_t)q * ns + k].major > best)
                best = r->orbits[(size_t)q * ns + k].major, at = k;
    }
    for (int h = 0; h < nh; h++) {
        char title[200];
        snprintf(title, sizeof title, "Unbalance response, harmonic %g x reference speed",
                 r->harmonics[h].order);
        pl_section *s = pl_section_add(p, title);
        pl_note(p, s,
                "%d unbalance%s turning at %g x the reference speed; %d speeds from %.6g to "
                "%.6g rpm; orbits at %.6g rpm.",
                r->harmonics[h].nunbalances, r->harmonics[h].nunbalances == 1 ? "" : "s",
                r->harmonics[h].order, ns, x[0], x[ns - 1], x[at]);
        if (s) snprintf(s->csv_name, sizeof s->csv_name, "unbalance_h%d.csv", h + 1);
        pl_csv(p, s, "output,speed_rpm,magnitude,phase_deg,real,imag\n");
        if (no) {
            const char *unit = probe_unit(sys, &opt->outputs[0]);
            int same = 1;
            for (int o = 1; o < no; o++)
                same &= !strcmp(unit, probe_unit(sys, &opt->outputs[o]));
            bode b;
            bode_panels(p, s, &b, "amplitude", "reference speed (rpm)",
                        same ? unit : "m, rad or N: see each output");
            for (int o = 0; o < no; o++) {
                char name[200];
                snprintf(name, sizeof name, "%s (%s)", opt->outputs[o].name,
                         probe_unit(sys, &opt->outputs[o]));
                size_t off = ((size_t)h * no + o) * ns;
                bode_curve(p, s, &b, name, ns, x, r->re + off, r->im + off, o);
            }
        }
        if (nb) {
            snprintf(title, sizeof title, "orbits at %.6g rpm", x[at]);
            pl_panel *pn = pl_panel_add(p, s, PL_XY, title, "x (m)", "y (m)");
            if (pn) pn->equal = 1;
            pl_csv(p, s, "orbit node,speed_rpm,major_m,minor_m,angle_deg,whirl\n");
            for (int k = 0; k < nb; k++) {
                const gd_orbit *o = &r->orbits[((size_t)h * nb + k) * ns + at];
                char name[200];
                snprintf(name, sizeof name, "%s (%s whirl)",
                         sys->model->nodes[opt->orbit_nodes[k]].name, gd_whirl_names[o->whirl]);
                pl_trace *t = pl_trace_add(p, pn, name, 73, NULL, NULL, PL_LINES, pl_color(k));
                if (t) ellipse(o, t->x, t->y, 73);
                for (int i = 0; i < ns; i++) {
                    const gd_orbit *q = &r->orbits[((size_t)h * nb + k) * ns + i];
                    pl_csv(p, s, "\"%s\",%.10g,%.10g,%.10g,%.6g,%s\n",
                           sys->model->nodes[opt->orbit_nodes[k]].name, x[i], q->major, q->minor,
                           q->angle * 180 / PI, gd_whirl_names[q->whirl]);
                }
            }
        }
    }
    free(x);
    return pl_done(p, out, err);
}
