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
    if (b->polar) b->polar->equal = 1; /* circles drawn as circles */
    /* adding a panel may move the section's panels: the three are its last ones */
    if (b->mag && b->phase && b->polar) {
        b->mag = &s->panels[s->npanels - 3];
        b->phase = &s->panels[s->npanels - 2];
    }
}

/* One complex curve over x into the three panels, and its rows into the CSV. */
static void bode_curve(gd_plot *p, pl_section *s, const bode *b, const char *name, int n,
                       const double *x, const double *re, const double *im, int color)
{
    pl_trace *m = pl_trace_add(p, b->mag, name, n, x, NULL, PL_LINES, pl_color(color));
    pl_trace *ph = pl_trace_add(p, b->phase, name, n, x, NULL, PL_LINES, pl_color(color));
    pl_trace *ny = pl_trace_add(p, b->polar, name, n, re, im, PL_LINES_MARKERS, pl_color(color));
    if (!m || !ph || !ny) return;
    /* the x unit, "(Hz)" or "(rpm)" in the axis label: the Nyquist plot's hover says at
     * which frequency or speed each point is (gd_plot_convert_x follows --units) */
    char xu[32] = "";
    const char *lp = strrchr(b->mag->xlabel, '('), *rp = lp ? strchr(lp, ')') : NULL;
    if (lp && rp && rp - lp < (long)sizeof xu)
        snprintf(xu, sizeof xu, "%.*s", (int)(rp - lp - 1), lp + 1);
    for (int k = 0; k < n; k++) {
        m->y[k] = hypot(re[k], im[k]);
        ph->y[k] = atan2(im[k], re[k]) * 180 / PI;
        pl_trace_text(p, ny, k, "%s at %.6g %s: Re %.4g, Im %.4g (|H| %.4g, %.1f deg)", name, x[k],
                      xu, re[k], im[k], m->y[k], ph->y[k]);
        pl_csv(p, s, "\"%s\",%.10g,%.10g,%.10g,%.10g,%.10g\n", name, x[k], m->y[k], ph->y[k], re[k],
               im[k]);
    }
}

static const char *dof_unit(gd_dof d)
{
    return d >= GD_RX ? "rad" : "m";
}

/* The unit of an FRF, output per input, written as a unit: "m/N", "1/m" (a mesh force
 * per unit moment, N/(N m)), "rad/(N m s)", never "N/N m". */
static void frf_unit(const gd_system *sys, const gd_frf_options *opt, const gd_probe *pr, char *buf,
                     size_t n)
{
    int moment_in = sys->dof_type[opt->inputs[0]] >= GD_RX;
    static const char *const rate[3] = {"", " s", " s^2"};
    if (!pr->element) {
        int rot = sys->dof_type[pr->index] >= GD_RX;
        const char *r = rate[opt->quantity];
        if (!moment_in) /* m/N, m/(N s), rad/(N s^2) */
            snprintf(buf, n, r[0] ? "%s/(N%s)" : "%s/N%s", rot ? "rad" : "m", r);
        else if (rot) /* rad/(N m), rad/(N m s) */
            snprintf(buf, n, "rad/(N m%s)", r);
        else /* m/(N m) = 1/N */
            snprintf(buf, n, r[0] ? "1/(N%s)" : "1/N%s", r);
    } else {
        int mom_out = pr->element->probe_dirs && pr->dir >= GD_RX;
        if (mom_out == moment_in)
            snprintf(buf, n, "%s", mom_out ? "N m/(N m)" : "N/N");
        else
            snprintf(buf, n, "%s", mom_out ? "m" : "1/m"); /* N m/N, N/(N m) */
    }
}

/* Refinement of the Nyquist curves: around each peak of |H| (the outputs' magnitudes,
 * each over its own largest, summed), the peak located by a golden-section search on
 * the bracket [w_{k-1}, w_{k+1}] of the sampled maximum, and PER_SIDE points on each
 * side of it at distances shrinking geometrically from the bracket's end to 1e-6 of it:
 * a resonance circle is then drawn as a circle whatever its damping (its half-power
 * band, 2 zeta w, holds some of them), not as chords across the plane. */
enum { MAX_PEAKS = 8, PER_SIDE = 30, PER_PEAK = 2 * PER_SIDE, GOLDEN_ITERS = 40 };

static double peak_measure(const gd_frf_result *r, int f, const double *scale)
{
    double sum = 0;
    for (int o = 0; o < r->noutputs; o++) {
        double a = hypot(r->re[(size_t)o * r->nfreq + f], r->im[(size_t)o * r->nfreq + f]);
        if (!isfinite(a)) return NAN;
        sum += scale[o] > 0 ? a / scale[o] : 0;
    }
    return sum;
}

/* the FRF at n frequencies w (rad/s) with the options of the result */
static gd_frf_result *frf_at(const gd_system *sys, const gd_frf_options *opt, const double *w,
                             int n)
{
    gd_frf_options o = *opt;
    o.freqs = w;
    o.nfreq = n;
    gd_frf_result *r = NULL;
    gd_error e;
    gd_error_clear(&e);
    if (gd_frf(sys, &o, &r, &e)) return NULL;
    return r;
}

static double measure_at(const gd_system *sys, const gd_frf_options *opt, double w,
                         const double *scale)
{
    gd_frf_result *r = frf_at(sys, opt, &w, 1);
    double v = r ? peak_measure(r, 0, scale) : NAN;
    gd_frf_free(r);
    return v;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Adds the refined Nyquist line of each output (no legend: the output's markers at the
 * given frequencies carry it) and the located peaks on the magnitude panel. */
static void refine_nyquist(gd_plot *p, const bode *b, const gd_system *sys,
                           const gd_frf_options *opt, const gd_frf_result *r, const int *first)
{
    int nf = r->nfreq, no = r->noutputs;
    double *scale = calloc((size_t)no, sizeof *scale), *meas = malloc((size_t)nf * sizeof *meas);
    int pk[MAX_PEAKS], npk = 0;
    double wpk[MAX_PEAKS];
    if (!scale || !meas) goto out;
    for (int o = 0; o < no; o++)
        for (int f = 0; f < nf; f++) {
            double a = hypot(r->re[(size_t)o * nf + f], r->im[(size_t)o * nf + f]);
            if (isfinite(a)) scale[o] = fmax(scale[o], a);
        }
    for (int f = 0; f < nf; f++)
        meas[f] = peak_measure(r, f, scale);
    for (int f = 1; f + 1 < nf; f++) {
        if (!(meas[f] > meas[f - 1] && meas[f] >= meas[f + 1])) continue;
        if (npk < MAX_PEAKS)
            pk[npk++] = f;
        else { /* keep the highest */
            int low = 0;
            for (int q = 1; q < npk; q++)
                if (meas[pk[q]] < meas[pk[low]]) low = q;
            if (meas[f] > meas[pk[low]]) pk[low] = f;
        }
    }
    if (!npk) goto out;
    /* golden-section search for each peak inside its bracket */
    const double g = 0.5 * (sqrt(5) - 1);
    for (int q = 0; q < npk; q++) {
        double a = r->freqs[pk[q] - 1], c = r->freqs[pk[q] + 1];
        double x1 = c - g * (c - a), x2 = a + g * (c - a);
        double f1 = measure_at(sys, opt, x1, scale), f2 = measure_at(sys, opt, x2, scale);
        for (int it = 0; it < GOLDEN_ITERS && isfinite(f1) && isfinite(f2); it++) {
            if (f1 > f2) {
                c = x2, x2 = x1, f2 = f1;
                x1 = c - g * (c - a);
                f1 = measure_at(sys, opt, x1, scale);
            } else {
                a = x1, x1 = x2, f1 = f2;
                x2 = a + g * (c - a);
                f2 = measure_at(sys, opt, x2, scale);
            }
        }
        wpk[q] = 0.5 * (a + c);
    }
    /* the given frequencies, PER_PEAK more across each bracket, and the peaks */
    int nw = nf + npk * (PER_PEAK + 1);
    double *w = malloc((size_t)nw * sizeof *w);
    if (!w) goto out;
    memcpy(w, r->freqs, (size_t)nf * sizeof *w);
    int k = nf;
    const double ratio = pow(1e-6, 1.0 / (PER_SIDE - 1));
    for (int q = 0; q < npk; q++) {
        double a = r->freqs[pk[q] - 1], c = r->freqs[pk[q] + 1], d = 1;
        for (int i = 0; i < PER_SIDE; i++, d *= ratio) {
            w[k++] = wpk[q] - (wpk[q] - a) * d;
            w[k++] = wpk[q] + (c - wpk[q]) * d;
        }
        w[k++] = wpk[q];
    }
    qsort(w, (size_t)nw, sizeof *w, cmp_double);
    gd_frf_result *d = frf_at(sys, opt, w, nw);
    gd_frf_result *at = frf_at(sys, opt, wpk, npk);
    if (d && at) {
        for (int o = 0; o < no; o++) {
            /* the markers at the given frequencies keep the name and the legend */
            pl_trace *base = &b->polar->traces[first[o]];
            base->mode = PL_MARKERS;
            char name[200];
            snprintf(name, sizeof name, "%.150s (refined around the peaks)", base->name);
            const char *color = base->color;
            pl_trace *t = pl_trace_add(p, b->polar, name, nw, d->re + (size_t)o * nw,
                                       d->im + (size_t)o * nw, PL_LINES, color);
            if (t) t->legend = 0;
        }
        pl_trace *m =
            pl_trace_add(p, b->mag, "peaks (located)", npk * no, NULL, NULL, PL_MARKERS, "#000");
        for (int o = 0; m && o < no; o++)
            for (int q = 0; q < npk; q++) {
                int i = o * npk + q;
                m->x[i] = wpk[q] / (2 * PI);
                m->y[i] = hypot(at->re[(size_t)o * npk + q], at->im[(size_t)o * npk + q]);
                pl_trace_text(p, m, i, "%s: peak at %.6g Hz, |H| %.4g", opt->outputs[o].name,
                              m->x[i], m->y[i]);
            }
        if (m) m->symbol = PL_TRIANGLE;
    }
    gd_frf_free(d);
    gd_frf_free(at);
    free(w);
out:
    free(scale);
    free(meas);
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
    int first[64] = {0}; /* each output's Nyquist trace */
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
            if (b.polar && o < 64) first[o] = b.polar->ntraces;
            bode_curve(p, s, &b, name, nf, hz, r->re + (size_t)o * nf, r->im + (size_t)o * nf,
                       color++);
        }
    }
    /* an undamped model's peaks are singular (|H| unbounded): nothing to refine */
    if (!dir && r->ninputs == 1 && r->noutputs <= 64 && nf >= 3 && b.polar && b.mag && !p->nomem &&
        sys->has_damping)
        refine_nyquist(p, &b, sys, opt, r, first);
    free(hz);
    return pl_done(p, out, err);
}

static const char *probe_unit(const gd_system *sys, const gd_probe *pr)
{
    if (!pr->element) return dof_unit(sys->dof_type[pr->index]);
    return pr->element->probe_dirs && pr->dir >= GD_RX ? "N m" : "N";
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
        /* one set of panels per physical quantity: displacements (m), angles (rad),
         * forces (N), moments (N m) never share an axis */
        static const char *const units[4] = {"m", "rad", "N", "N m"};
        static const char *const what[4] = {"displacement", "angle", "force", "moment"};
        int nused = 0;
        for (int q = 0; q < 4; q++)
            for (int o = 0; o < no; o++)
                if (!strcmp(units[q], probe_unit(sys, &opt->outputs[o]))) {
                    nused++;
                    break;
                }
        for (int q = 0; q < 4 && no; q++) {
            int any = 0;
            for (int o = 0; o < no; o++)
                any |= !strcmp(units[q], probe_unit(sys, &opt->outputs[o]));
            if (!any) continue;
            bode b;
            char head[64];
            snprintf(head, sizeof head, nused > 1 ? "%s amplitude" : "amplitude", what[q]);
            bode_panels(p, s, &b, head, "reference speed (rpm)", units[q]);
            for (int o = 0; o < no; o++) {
                if (strcmp(units[q], probe_unit(sys, &opt->outputs[o]))) continue;
                char name[200];
                snprintf(name, sizeof name, "%s (%s)", opt->outputs[o].name, units[q]);
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
