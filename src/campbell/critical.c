/* Excitation orders and where the tracked modes meet them. A critical speed is where a
 * mode's damped frequency (Hz) equals order x reference speed / 2 pi, found by a sign
 * change of the difference between consecutive speeds and linear interpolation. The
 * instability onset is the lowest speed where a mode's damping ratio turns negative
 * (interpolated to the zero of the damping ratio). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campbell/campbell_impl.h"

#define PI 3.14159265358979323846

static int add_order(gd_order *o, int *n, gd_order_kind kind, double order, const char *label)
{
    if (!(order > 0) || !isfinite(order)) return 0;
    for (int i = 0; i < *n; i++)
        if (fabs(o[i].order - order) <= 1e-9 * order) return 0;
    o[*n].kind = kind;
    o[*n].order = order;
    snprintf(o[*n].label, sizeof o[*n].label, "%s", label);
    (*n)++;
    return 0;
}

int gd_campbell_orders(const gd_model *m, const gd_campbell_options *opt, gd_order **out)
{
    int cap = m->nshafts + opt->norders + m->nmeshes + 1, n = 0;
    gd_order *o = calloc((size_t)cap, sizeof *o);
    if (!o) return -1;
    char label[96];
    if (opt->shaft_orders)
        for (int s = 0; s < m->nshafts; s++) {
            gd_model_shaft_order_label(m, s, label, (int)sizeof label);
            add_order(o, &n, GD_ORDER_SHAFT, fabs(m->shafts[s].speed_ratio), label);
        }
    for (int i = 0; i < opt->norders; i++) {
        snprintf(label, sizeof label, "%gx", opt->orders[i]);
        add_order(o, &n, GD_ORDER_USER, opt->orders[i], label);
    }
    if (opt->mesh_orders)
        for (int k = 0; k < m->nmeshes; k++) {
            const gd_mesh *g = &m->meshes[k];
            if (g->teeth[0] <= 0) continue;
            const gd_shaft *sh = &m->shafts[m->nodes[g->driver].shaft];
            snprintf(label, sizeof label, "mesh %.30s %dx %.40s", g->name, g->teeth[0] % 100000,
                     sh->name);
            add_order(o, &n, GD_ORDER_MESH, g->teeth[0] * fabs(sh->speed_ratio), label);
        }
    *out = o;
    return n;
}

static int cmp_critical(const void *a, const void *b)
{
    const gd_critical_speed *x = a, *y = b;
    if (x->speed != y->speed) return x->speed < y->speed ? -1 : 1;
    if (x->mode != y->mode) return x->mode - y->mode;
    return x->order - y->order;
}

static int exists(const gd_mode *md)
{
    return md->rigid_body >= 0;
}

int gd_campbell_crossings(gd_campbell_result *r)
{
    int ns = r->nspeeds, cap = 16, n = 0;
    gd_critical_speed *c = malloc((size_t)cap * sizeof *c);
    if (!c) return -1;
    for (int t = 0; t < r->ntracks; t++) {
        const gd_mode *md = r->modes + (size_t)t * ns;
        for (int o = 0; o < r->norders; o++) {
            double ord = r->orders[o].order;
            for (int s = 1; s < ns; s++) {
                if (!exists(&md[s - 1]) || !exists(&md[s])) continue;
                if (md[s - 1].overdamped || md[s].overdamped) continue;
                double w0 = r->speeds[s - 1], w1 = r->speeds[s];
                double f0 = md[s - 1].omega_d / (2 * PI), f1 = md[s].omega_d / (2 * PI);
                double g0 = f0 - ord * w0 / (2 * PI), g1 = f1 - ord * w1 / (2 * PI);
                if ((g0 > 0) == (g1 > 0)) continue;
                double x = g0 / (g0 - g1);
                if (n == cap) {
                    cap *= 2;
                    gd_critical_speed *nc = realloc(c, (size_t)cap * sizeof *nc);
                    if (!nc) {
                        free(c);
                        return -1;
                    }
                    c = nc;
                }
                c[n].mode = r->tracks[t].id;
                c[n].order = o;
                c[n].speed = w0 + x * (w1 - w0);
                c[n].speed_rpm = c[n].speed * 30 / PI;
                c[n].frequency_hz = f0 + x * (f1 - f0);
                n++;
            }
        }
    }
    qsort(c, (size_t)n, sizeof *c, cmp_critical);
    r->critical = c;
    r->ncritical = n;
    r->instability_onset = NAN;
    r->instability_track = -1;
    for (int t = 0; t < r->ntracks; t++) {
        const gd_mode *md = r->modes + (size_t)t * ns;
        for (int s = 0; s < ns; s++) {
            if (!exists(&md[s]) || !md[s].unstable) continue;
            double w = r->speeds[s];
            /* Interpolate the damping ratio through zero only from a damped speed: an
             * undamped (gyroscopic) mode sits at 0 to rounding (+-1e-15) until it diverges,
             * and interpolating from there put the onset at the previous grid speed. */
            if (s > 0 && exists(&md[s - 1]) && md[s - 1].damping_ratio > 1e-9) {
                double z0 = md[s - 1].damping_ratio, z1 = md[s].damping_ratio;
                w = r->speeds[s - 1] + z0 / (z0 - z1) * (r->speeds[s] - r->speeds[s - 1]);
            }
            if (isnan(r->instability_onset) || w < r->instability_onset) {
                r->instability_onset = w;
                r->instability_track = r->tracks[t].id;
            }
            break;
        }
    }
    return 0;
}
