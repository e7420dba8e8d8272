/* The model drawn to scale (side view, metres on both axes) and summarised in tables.
 * Each shaft lies along its own axis line; a mesh puts the driven shaft one centre
 * distance (sum of the pitch radii, r = r_b / cos alpha) below its driver; a planetary set
 * (docs/planetary.md) keeps its sun, ring and carrier on one axis, its planets in the sun's
 * gear plane, and gets a panel of its own seen along the axis. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "plot/plot_impl.h"

#define PI 3.14159265358979323846

typedef struct poly {
    double *x, *y;
    int n, cap;
} poly;

static void rect(gd_plot *p, poly *q, double x0, double x1, double y0, double y1)
{
    if (q->n + 6 > q->cap) {
        int cap = q->cap ? 2 * q->cap : 64;
        double *x = realloc(q->x, (size_t)cap * sizeof *x);
        if (x) q->x = x;
        double *y = x ? realloc(q->y, (size_t)cap * sizeof *y) : NULL;
        if (y) q->y = y;
        if (!x || !y) {
            p->nomem = 1;
            return;
        }
        q->cap = cap;
    }
    double px[6] = {x0, x1, x1, x0, x0, NAN}, py[6] = {y0, y0, y1, y1, y0, NAN};
    for (int k = 0; k < 6; k++)
        q->x[q->n] = px[k], q->y[q->n++] = py[k];
}

static void flush(gd_plot *p, pl_panel *pn, poly *q, const char *name, const char *color)
{
    if (q->n > 1) pl_trace_add(p, pn, name, q->n - 1, q->x, q->y, PL_FILL, color);
    free(q->x);
    free(q->y);
    *q = (poly){0};
}

static double pitch_radius(const gd_mesh *g, int side)
{
    double c = cos(g->pressure_angle);
    return g->base_radius[side] > 0 && c > 0 ? g->base_radius[side] / c : 0;
}

static double shaft_od(const gd_shaft *sh)
{
    double od = 0;
    for (int k = 0; k < sh->nsections; k++)
        od = fmax(od, sh->sections[k].outer_diameter);
    return od;
}

/* A lumped shaft (nodes only) joined by a spring or bearing to a node of an elastic
 * shaft: that node, else -1. */
static int coupling_node(const gd_model *m, int h)
{
    if (m->shafts[h].nsections > 0) return -1;
    for (int pass = 0; pass < 2; pass++) {
        int n = pass ? m->nbearings : m->nsprings;
        for (int k = 0; k < n; k++) {
            int a = pass ? m->bearings[k].node : m->springs[k].node1;
            int b = pass ? m->bearings[k].node2 : m->springs[k].node2;
            if (a < 0 || b < 0) continue;
            int other = m->nodes[a].shaft == h ? b : m->nodes[b].shaft == h ? a : -1;
            if (other >= 0 && m->shafts[m->nodes[other].shaft].nsections > 0) return other;
        }
    }
    return -1;
}

/* the axial extent of an elastic shaft */
static void shaft_span(const gd_model *m, int h, double *a, double *b)
{
    const gd_shaft *sh = &m->shafts[h];
    *a = m->nodes[sh->first_node].position;
    *b = m->nodes[sh->first_node + sh->nnodes - 1].position;
}

/* A planetary set's sun, ring and carrier share one axis; planet n is drawn r_c cos psi_n
 * from it (the side view's vertical is the set's x). Places the shafts of every set with a
 * placed member; returns 1 if it placed any. */
static int place_planetary(const gd_model *m, double *off, int *placed)
{
    int any = 0;
    for (int k = 0; k < m->nplanetary; k++) {
        const gd_planetary *g = &m->planetary[k];
        int axis = -1;
        for (int j = 0; j < GD_PLANETARY_NMEMBERS && axis < 0; j++)
            if (placed[m->nodes[g->member[j].node].shaft]) axis = m->nodes[g->member[j].node].shaft;
        if (axis < 0) continue;
        for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++) {
            int h = m->nodes[g->member[j].node].shaft;
            if (!placed[h]) off[h] = off[axis], placed[h] = any = 1;
        }
        for (int n = 0; n < g->nplanets; n++) {
            int h = m->nodes[g->first_planet + n].shaft;
            if (!placed[h])
                off[h] = off[axis] + g->carrier_radius * cos(g->planet_angle[n]),
                placed[h] = any = 1;
        }
    }
    return any;
}

/* Pitch radius of a set's sun (0), ring (1) or planet (2): r_b / cos alpha of its mesh. */
static double set_pitch_radius(const gd_planetary *g, int which)
{
    double c = cos(g->pressure_angle[which == 1 ? 1 : 0]);
    return c > 0 ? g->base_radius[which] / c : g->base_radius[which];
}

/* Each set seen along its axis: the pitch circles of sun, ring and planets at their angles,
 * the carrier's circle of planet centres. */
static void planetary_front_view(gd_plot *p, pl_section *s, const gd_model *m)
{
    enum { NC = 73 };
    for (int k = 0; k < m->nplanetary; k++) {
        const gd_planetary *g = &m->planetary[k];
        char title[GD_NAME_MAX + 64];
        snprintf(title, sizeof title, "planetary set '%s' seen along its axis", g->name);
        pl_panel *pn = pl_panel_add(p, s, PL_XY, title, "x (m)", "y (m)");
        if (!pn) continue;
        pn->equal = 1;
        double x[NC], y[NC];
        const char *names[3] = {"sun (pitch circle)", "ring (pitch circle)",
                                "carrier (planet centres)"};
        const char *colors[3] = {"#1f77b4", "#555", "#9467bd"};
        double radius[3] = {set_pitch_radius(g, 0), set_pitch_radius(g, 1), g->carrier_radius};
        for (int j = 0; j < 3; j++) {
            for (int i = 0; i < NC; i++)
                x[i] = radius[j] * cos(2 * PI * i / (NC - 1)),
                y[i] = radius[j] * sin(2 * PI * i / (NC - 1));
            pl_trace *t = pl_trace_add(p, pn, names[j], NC, x, y, PL_LINES, colors[j]);
            if (t && j == 2) t->dash = 1;
        }
        int np = g->nplanets, cap = np * (NC + 1);
        double *px = malloc((size_t)cap * sizeof *px), *py = malloc((size_t)cap * sizeof *py);
        double rp = set_pitch_radius(g, 2);
        for (int n = 0, at = 0; px && py && n < np; n++) {
            double cx = g->carrier_radius * cos(g->planet_angle[n]),
                   cy = g->carrier_radius * sin(g->planet_angle[n]);
            for (int i = 0; i < NC; i++)
                px[at] = cx + rp * cos(2 * PI * i / (NC - 1)),
                py[at++] = cy + rp * sin(2 * PI * i / (NC - 1));
            px[at] = py[at] = NAN;
            at++;
        }
        if (px && py)
            pl_trace_add(p, pn, "planets (pitch circles)", cap - 1, px, py, PL_LINES, "#ff7f0e");
        else
            p->nomem = 1;
        free(px);
        free(py);
        pl_trace *c = pl_trace_add(p, pn, "planet centres", np, NULL, NULL, PL_MARKERS, "#ff7f0e");
        for (int n = 0; c && n < np; n++) {
            c->x[n] = g->carrier_radius * cos(g->planet_angle[n]);
            c->y[n] = g->carrier_radius * sin(g->planet_angle[n]);
            pl_trace_text(p, c, n, "planet %d at %.4g deg (node %s)", n + 1,
                          g->planet_angle[n] * 180 / PI, m->nodes[g->first_planet + n].name);
        }
        if (c) c->legend = 0;
    }
}

gd_status gd_plot_model(const gd_model *m, gd_plot **out, gd_error *err)
{
    if (m->nshafts == 0)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "shafts", "",
                            "nothing to draw: no shaft");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn model", &p, err);
    if (st) return st;
    pl_section *s = pl_section_add(p, "Model");
    pl_note(p, s,
            "%s: %d shafts, %d nodes, %d disks, %d bearings, %d meshes, %d planetary sets, %d "
            "unbalances. Side view to scale; meshed shafts one centre distance apart; a planetary "
            "set's sun, ring and carrier on one axis, its planets r_c cos(psi) from it.",
            m->file, m->nshafts, m->nnodes, m->ndisks, m->nbearings, m->nmeshes, m->nplanetary,
            m->nunbalances);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "model_nodes.csv");
    double *off = malloc((size_t)m->nshafts * sizeof *off);
    int *placed = calloc((size_t)m->nshafts, sizeof *placed);
    if (!off || !placed) p->nomem = 1;
    double maxod = 0;
    for (int h = 0; h < m->nshafts; h++)
        maxod = fmax(maxod, shaft_od(&m->shafts[h]));
    /* place shafts: along meshes from each unplaced one, below what is placed so far */
    double bottom = 0;
    for (int h0 = 0; off && placed && h0 < m->nshafts; h0++) {
        if (placed[h0]) continue;
        off[h0] = h0 ? bottom - 3 * maxod : 0;
        placed[h0] = 1;
        for (int changed = 1; changed;) {
            changed = 0;
            for (int g = 0; g < m->nmeshes; g++) {
                const gd_mesh *ms = &m->meshes[g];
                int a = m->nodes[ms->driver].shaft, b = m->nodes[ms->driven].shaft;
                double cd = pitch_radius(ms, 0) + pitch_radius(ms, 1);
                if (!(cd > 0)) cd = 3 * maxod;
                if (placed[a] && !placed[b])
                    off[b] = off[a] - cd, placed[b] = changed = 1;
                else if (placed[b] && !placed[a])
                    off[a] = off[b] + cd, placed[a] = changed = 1;
            }
            changed |= place_planetary(m, off, placed);
        }
        for (int h = 0; h < m->nshafts; h++)
            if (placed[h]) bottom = fmin(bottom, off[h]);
    }
    /* where each node is drawn: its axial position; a lumped shaft coupled to an elastic
     * one sits beside the coupling node, outside that shaft's end, on its axis */
    double span = 0;
    for (int h = 0; h < m->nshafts; h++) {
        double a, b;
        if (m->shafts[h].nsections > 0) shaft_span(m, h, &a, &b), span = fmax(span, b - a);
    }
    if (!(span > 0)) span = 1;
    double *nx = malloc((size_t)m->nnodes * sizeof *nx);
    if (!nx) p->nomem = 1;
    for (int i = 0; nx && i < m->nnodes; i++)
        nx[i] = m->nodes[i].position;
    for (int h = 0; nx && off && h < m->nshafts; h++) {
        int c = coupling_node(m, h);
        if (c < 0) continue;
        int host = m->nodes[c].shaft;
        double a, b;
        shaft_span(m, host, &a, &b);
        double x = m->nodes[c].position, out_dir = x - a < b - x ? -1 : 1;
        off[h] = off[host];
        const gd_shaft *sh = &m->shafts[h];
        for (int k = 0; k < sh->nnodes; k++)
            nx[sh->first_node + k] = x + out_dir * 0.12 * span * (k + 1);
    }
    for (int k = 0; nx && k < m->nplanetary; k++) {
        const gd_planetary *g = &m->planetary[k];
        double plane = nx[g->member[GD_PLANETARY_SUN].node];
        for (int n = 0; n < g->nplanets; n++)
            nx[g->first_planet + n] = plane;
        int ring = g->member[GD_PLANETARY_RING].node;
        if (m->shafts[m->nodes[ring].shaft].nsections == 0 &&
            coupling_node(m, m->nodes[ring].shaft) < 0)
            nx[ring] = plane;
    }
    pl_panel *pn = pl_panel_add(p, s, PL_XY, "the model to scale (side view)", "axial position (m)",
                                "radial position (m)");
    if (pn) pn->equal = 1;
    poly shafts = {0}, gears = {0}, disks = {0};
    pl_csv(p, s, "node,shaft,position_m,axis_offset_m\n");
    for (int h = 0; off && h < m->nshafts; h++) {
        const gd_shaft *sh = &m->shafts[h];
        double x = m->nodes[sh->first_node].position;
        for (int k = 0; k < sh->nsections; k++) {
            const gd_section *sc = &sh->sections[k];
            rect(p, &shafts, x, x + sc->length, off[h] - sc->outer_diameter / 2,
                 off[h] + sc->outer_diameter / 2);
            x += sc->length;
        }
        for (int k = 0; k < sh->nnodes; k++)
            pl_csv(p, s, "\"%s\",\"%s\",%.10g,%.10g\n", m->nodes[sh->first_node + k].name, sh->name,
                   m->nodes[sh->first_node + k].position, off[h]);
    }
    for (int g = 0; off && g < m->nmeshes; g++) {
        const gd_mesh *ms = &m->meshes[g];
        for (int side = 0; side < 2; side++) {
            int node = side ? ms->driven : ms->driver;
            double rp = pitch_radius(ms, side), x = nx ? nx[node] : m->nodes[node].position;
            if (!(rp > 0)) continue;
            double w = fmax(0.25 * rp, 0.5 * maxod) / 2;
            rect(p, &gears, x - w, x + w, off[m->nodes[node].shaft] - rp,
                 off[m->nodes[node].shaft] + rp);
        }
    }
    for (int k = 0; off && k < m->nplanetary; k++) {
        const gd_planetary *g = &m->planetary[k];
        int sun = g->member[GD_PLANETARY_SUN].node, ring = g->member[GD_PLANETARY_RING].node;
        double rs = set_pitch_radius(g, 0), rr = set_pitch_radius(g, 1),
               rp = set_pitch_radius(g, 2);
        double w = fmax(0.25 * rs, 0.5 * maxod) / 2, xs = nx ? nx[sun] : 0, xr = nx ? nx[ring] : 0;
        double ys = off[m->nodes[sun].shaft], yr = off[m->nodes[ring].shaft];
        rect(p, &gears, xs - w, xs + w, ys - rs, ys + rs);
        /* the ring: its teeth band above and below the axis */
        rect(p, &gears, xr - w, xr + w, yr + rr, yr + 1.1 * rr);
        rect(p, &gears, xr - w, xr + w, yr - 1.1 * rr, yr - rr);
        for (int n = 0; n < g->nplanets; n++) {
            int node = g->first_planet + n;
            double x = nx ? nx[node] : 0, y = off[m->nodes[node].shaft];
            rect(p, &gears, x - w, x + w, y - rp, y + rp);
        }
    }
    /* A wind-turbine rotor's solid-disk radius (6.5 m on the GRC gearbox) squeezed the
     * gearbox to a blob: disks are drawn at most 3x the largest gear's pitch radius. */
    double rgear = 0;
    for (int g = 0; g < m->nmeshes; g++)
        rgear = fmax(rgear, fmax(pitch_radius(&m->meshes[g], 0), pitch_radius(&m->meshes[g], 1)));
    for (int k = 0; k < m->nplanetary; k++)
        rgear = fmax(rgear, set_pitch_radius(&m->planetary[k], 1));
    int cut = 0;
    for (int d = 0; off && d < m->ndisks; d++) {
        const gd_disk *dk = &m->disks[d];
        int geared = 0;
        for (int g = 0; g < m->nmeshes; g++)
            geared |= m->meshes[g].driver == dk->node || m->meshes[g].driven == dk->node;
        if (geared || !(dk->mass > 0) || !(dk->polar_inertia > 0)) continue;
        double rr = sqrt(2 * dk->polar_inertia / dk->mass),
               x = nx ? nx[dk->node] : m->nodes[dk->node].position; /* solid disk */
        if (rgear > 0 && rr > 3 * rgear) rr = 3 * rgear, cut++;
        double w = fmax(0.2 * rr, 0.5 * maxod) / 2;
        rect(p, &disks, x - w, x + w, off[m->nodes[dk->node].shaft] - rr,
             off[m->nodes[dk->node].shaft] + rr);
    }
    flush(p, pn, &shafts, "shafts (outer diameter)", "#555");
    flush(p, pn, &gears, "gears (pitch diameter)", "#1f77b4");
    flush(p, pn, &disks,
          cut ? "disks (solid-disk radius from J and m, cut at 3x the largest gear)"
              : "disks (solid-disk radius from J and m)",
          "#2ca02c");
    pl_trace *bt = off && m->nbearings ? pl_trace_add(p, pn, "bearings", m->nbearings, NULL, NULL,
                                                      PL_MARKERS, "#d62728")
                                       : NULL;
    for (int b = 0; bt && b < m->nbearings; b++) {
        int node = m->bearings[b].node, h = m->nodes[node].shaft;
        bt->x[b] = nx ? nx[node] : m->nodes[node].position;
        bt->y[b] = off[h] - shaft_od(&m->shafts[h]) / 2;
        pl_trace_text(p, bt, b, "bearing %s at %s", m->bearings[b].name, m->nodes[node].name);
    }
    if (bt) bt->symbol = PL_TRIANGLE;
    /* springs and couplings: a zigzag between their nodes (to ground: downwards) */
    if (off && nx && m->nsprings) {
        int cap = 12 * m->nsprings;
        double *zx = malloc((size_t)cap * sizeof *zx), *zy = malloc((size_t)cap * sizeof *zy);
        int k = 0;
        for (int q = 0; zx && zy && q < m->nsprings; q++) {
            const gd_spring *sp = &m->springs[q];
            int a = sp->node1, b = sp->node2;
            double x0 = nx[a], y0 = off[m->nodes[a].shaft];
            double x1 = b >= 0 ? nx[b] : x0, y1 = b >= 0 ? off[m->nodes[b].shaft] : y0 - 2 * maxod;
            if (b >= 0 && fabs(x1 - x0) < 1e-12 && fabs(y1 - y0) < 1e-12) x1 = x0 + 0.05 * span;
            double amp = 0.35 * (maxod > 0 ? maxod : 0.02 * span);
            for (int i = 0; i <= 8; i++) { /* 8 segments, the inner ones zigzag */
                double t = i / 8.0, z = (i == 0 || i == 8) ? 0 : (i % 2 ? amp : -amp);
                double dx = x1 - x0, dy = y1 - y0, l = hypot(dx, dy);
                zx[k] = x0 + t * dx - (l > 0 ? z * dy / l : 0);
                zy[k++] = y0 + t * dy + (l > 0 ? z * dx / l : 0);
            }
            zx[k] = zy[k] = NAN;
            k++;
        }
        if (k > 1) pl_trace_add(p, pn, "springs and couplings", k - 1, zx, zy, PL_LINES, "#9467bd");
        free(zx);
        free(zy);
    }
    /* node names on hover */
    pl_trace *nt =
        off && nx ? pl_trace_add(p, pn, "nodes", m->nnodes, nx, NULL, PL_MARKERS, "#999") : NULL;
    for (int i = 0; nt && i < m->nnodes; i++) {
        nt->y[i] = off[m->nodes[i].shaft];
        pl_trace_text(p, nt, i, "node %s (shaft %s) at %.4g m", m->nodes[i].name,
                      m->shafts[m->nodes[i].shaft].name, m->nodes[i].position);
    }
    if (nt) nt->legend = 0;
    planetary_front_view(p, s, m);
    /* tables */
    pl_panel *t = pl_panel_add(p, s, PL_TABLE, "shafts", NULL, NULL);
    pl_table_init(p, t, m->nshafts, 6);
    const char *hs[6] = {"shaft", "length (m)", "mass (kg)", "polar inertia (kg m^2)",
                         "nodes", "speed ratio"};
    for (int c = 0; c < 6; c++)
        pl_cell(p, t, 0, c, "%s", hs[c]);
    for (int h = 0; h < m->nshafts; h++) {
        gd_shaft_summary sum;
        gd_model_shaft_summary(m, h, &sum);
        pl_cell(p, t, h + 1, 0, "%s", m->shafts[h].name);
        pl_cell(p, t, h + 1, 1, "%.4g", sum.length);
        pl_cell(p, t, h + 1, 2, "%.4g", sum.mass);
        pl_cell(p, t, h + 1, 3, "%.4g", sum.polar_inertia);
        pl_cell(p, t, h + 1, 4, "%d", sum.nnodes);
        pl_cell(p, t, h + 1, 5, "%.6g", m->shafts[h].speed_ratio);
    }
    if (m->nbearings) {
        t = pl_panel_add(p, s, PL_TABLE, "bearings", NULL, NULL);
        pl_table_init(p, t, m->nbearings, 6);
        const char *hb[6] = {"bearing",   "node",        "kxx (N/m)",
                             "kyy (N/m)", "cxx (N s/m)", "speed table"};
        for (int c = 0; c < 6; c++)
            pl_cell(p, t, 0, c, "%s", hb[c]);
        for (int b = 0; b < m->nbearings; b++) {
            const gd_bearing *br = &m->bearings[b];
            pl_cell(p, t, b + 1, 0, "%s", br->name);
            pl_cell(p, t, b + 1, 1, "%s", m->nodes[br->node].name);
            pl_cell(p, t, b + 1, 2, "%.4g", br->coeffs.kxx);
            pl_cell(p, t, b + 1, 3, "%.4g", br->coeffs.kyy);
            pl_cell(p, t, b + 1, 4, "%.4g", br->coeffs.cxx);
            pl_cell(p, t, b + 1, 5, "%s", br->ntable ? "yes" : "no");
        }
    }
    if (m->nmeshes) {
        t = pl_panel_add(p, s, PL_TABLE, "gear meshes", NULL, NULL);
        pl_table_init(p, t, m->nmeshes, 7);
        const char *hm[7] = {"mesh",    "driver",      "driven",        "teeth",
                             "k (N/m)", "helix (deg)", "stiffness from"};
        for (int c = 0; c < 7; c++)
            pl_cell(p, t, 0, c, "%s", hm[c]);
        for (int g = 0; g < m->nmeshes; g++) {
            const gd_mesh *ms = &m->meshes[g];
            pl_cell(p, t, g + 1, 0, "%s", ms->name);
            pl_cell(p, t, g + 1, 1, "%s", m->nodes[ms->driver].name);
            pl_cell(p, t, g + 1, 2, "%s", m->nodes[ms->driven].name);
            pl_cell(p, t, g + 1, 3, "%d/%d", ms->teeth[0], ms->teeth[1]);
            pl_cell(p, t, g + 1, 4, "%.4g", ms->stiffness);
            pl_cell(p, t, g + 1, 5, "%.4g", ms->helix_angle * 180 / PI);
            pl_cell(p, t, g + 1, 6, "%s", ms->tvms ? "geometry" : "given");
        }
    }
    free(nx);
    free(off);
    free(placed);
    return pl_done(p, out, err);
}
