/* The figure of a modal analysis: mode shapes along each shaft, the 3-D whirl view and
 * the strain-energy table ([JMSTHelical] Tables 4-7: shares by motion type and by component). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

#define PI 3.14159265358979323846
enum { MAX_SHAPES = 12 }; /* mode-shape panels drawn; the table lists every mode */

/* Re and Im of the shape of mode j at (node, dof); NaN when the DOF is not active. */
static void entry(const gd_system *sys, const gd_modal_result *r, int j, int node, gd_dof d,
                  double *re, double *im)
{
    int i = gd_system_dof(sys, node, d);
    *re = i < 0 ? NAN : r->shape_re[i + (size_t)j * r->ndof];
    *im = i < 0 ? NAN : r->shape_im[i + (size_t)j * r->ndof];
}

static int shaft_has(const gd_system *sys, const gd_shaft *sh, gd_dof d)
{
    for (int k = 0; k < sh->nnodes; k++)
        if (gd_system_dof(sys, sh->first_node + k, d) >= 0) return 1;
    return 0;
}

/* A lumped shaft (nodes only, no elements) is drawn at the node of an elastic shaft it
 * is coupled to (a spring or a bearing between them): the shaft it joins, or -1. */
static int host_of(const gd_model *m, int h, double *pos)
{
    const gd_shaft *sh = &m->shafts[h];
    if (sh->nsections > 0) return -1;
    for (int pass = 0; pass < 2; pass++) {
        int n = pass ? m->nbearings : m->nsprings;
        for (int k = 0; k < n; k++) {
            int a = pass ? m->bearings[k].node : m->springs[k].node1;
            int b = pass ? m->bearings[k].node2 : m->springs[k].node2;
            if (a < 0 || b < 0) continue;
            int other = m->nodes[a].shaft == h ? b : m->nodes[b].shaft == h ? a : -1;
            if (other < 0 || m->shafts[m->nodes[other].shaft].nsections == 0) continue;
            /* just outside the host's end it is coupled at, clear of the bearing there */
            const gd_shaft *hs = &m->shafts[m->nodes[other].shaft];
            double lo = m->nodes[hs->first_node].position,
                   hi = m->nodes[hs->first_node + hs->nnodes - 1].position,
                   x = m->nodes[other].position;
            *pos = x + (x - lo < hi - x ? -0.04 : 0.04) * (hi - lo);
            return m->nodes[other].shaft;
        }
    }
    return -1;
}

/* Gears, disks and bearings of shaft h as markers on the axis (y = 0) of its panel. */
static void items_on_axis(gd_plot *p, pl_panel *pn, const gd_model *m, int h)
{
    int n = m->ndisks + 2 * m->nmeshes;
    double *x = calloc((size_t)n + m->nbearings + 1, sizeof *x);
    int *who = calloc((size_t)n + m->nbearings + 1, sizeof *who);
    if (!x || !who) {
        p->nomem = 1;
        free(x);
        free(who);
        return;
    }
    int k = 0;
    for (int d = 0; d < m->ndisks; d++)
        if (m->nodes[m->disks[d].node].shaft == h)
            who[k] = d, x[k++] = m->nodes[m->disks[d].node].position;
    int nd = k;
    for (int g = 0; g < m->nmeshes; g++)
        for (int e = 0; e < 2; e++) {
            int node = e ? m->meshes[g].driven : m->meshes[g].driver;
            if (m->nodes[node].shaft == h) who[k] = 2 * g + e, x[k++] = m->nodes[node].position;
        }
    pl_trace *t = k ? pl_trace_add(p, pn, "gears and disks", k, x, NULL, PL_MARKERS, "#444") : NULL;
    if (t) {
        t->symbol = PL_DIAMOND;
        for (int i = 0; i < k; i++)
            if (i < nd)
                pl_trace_text(p, t, i, "disk %s at %s", m->disks[who[i]].name,
                              m->nodes[m->disks[who[i]].node].name);
            else
                pl_trace_text(p, t, i, "mesh %s %s", m->meshes[who[i] / 2].name,
                              who[i] % 2 ? "driven" : "driver");
    }
    k = 0;
    for (int b = 0; b < m->nbearings; b++)
        if (m->nodes[m->bearings[b].node].shaft == h)
            who[k] = b, x[k++] = m->nodes[m->bearings[b].node].position;
    t = k ? pl_trace_add(p, pn, "bearings", k, x, NULL, PL_MARKERS, "#8c564b") : NULL;
    if (t) {
        t->symbol = PL_SQUARE;
        for (int i = 0; i < k; i++)
            pl_trace_text(p, t, i, "bearing %s at %s", m->bearings[who[i]].name,
                          m->nodes[m->bearings[who[i]].node].name);
    }
    free(x);
    free(who);
}

/* The diagonal of M (kg, kg m^2): the weights that make translations and rotations
 * comparable (the kinetic energy of a family is sum M_ii |phi_i|^2 / 2 w^2). */
static double *mass_diagonal(gd_plot *p, const gd_system *sys)
{
    double *d = calloc((size_t)sys->ndof + 1, sizeof *d);
    if (!d) {
        p->nomem = 1;
        return NULL;
    }
    const gd_csc *M = &sys->M;
    for (int c = 0; c < M->n && c < sys->ndof; c++)
        for (int k = M->colptr[c]; k < M->colptr[c + 1]; k++)
            if (M->rowind[k] == c) d[c] = M->values[k];
    return d;
}

static int is_rotation(gd_dof d)
{
    return d == GD_RX || d == GD_RY || d == GD_RZ;
}

/* the angle of shaft h referred to the reference shaft through its speed ratio (the
 * rigid turning of the gear train is then one value along the whole train) */
static double referred(const gd_model *m, int h, gd_dof d)
{
    double q = m->shafts[h].speed_ratio;
    return d == GD_RZ && q != 0 && isfinite(q) ? 1 / q : 1;
}

/* zeta as printed: |zeta| < 1e-9 is rounding noise of an undamped mode, shown as 0 */
static void zeta_text(char *buf, size_t n, double z)
{
    if (!isfinite(z))
        snprintf(buf, n, "-");
    else if (fabs(z) < 1e-9)
        snprintf(buf, n, "0");
    else
        snprintf(buf, n, "%.3g", z);
}

/* The panels of mode j: one per elastic shaft that moves (lumped shafts drawn at the
 * node they are coupled to), each at its real axial positions. One scale for the whole
 * mode: the largest translation is 1 and the largest rotation is 1 on the right-hand
 * axis (torsion referred to the reference shaft). A family (a shaft's x, y, z, rx, ry
 * or rz) whose mass-weighted size sqrt(sum M_ii |phi_i|^2) is under 1 % of the largest
 * family's is left out and listed. Returns the number of panels. */
static int shape_panels(gd_plot *p, pl_section *s, const gd_system *sys, const gd_modal_result *r,
                        int j, const double *mdiag)
{
    const gd_model *m = sys->model;
    const gd_mode *md = &r->modes[j];
    int nf = m->nshafts * GD_NODE_DOFS;
    double *size = calloc((size_t)nf, sizeof *size);
    if (!size) {
        p->nomem = 1;
        return 0;
    }
    /* family sizes, the phase of the largest entry, the largest kept entries */
    double best = -1, alpha = 0, fmax_ = 0;
    for (int i = 0; i < sys->ndof; i++) {
        double re = r->shape_re[i + (size_t)j * r->ndof], im = r->shape_im[i + (size_t)j * r->ndof];
        double w = mdiag ? mdiag[i] : 1, a2 = re * re + im * im;
        size[m->nodes[sys->dof_node[i]].shaft * GD_NODE_DOFS + sys->dof_type[i]] += w * a2;
        if (w * a2 > best) best = w * a2, alpha = atan2(im, re);
    }
    for (int f = 0; f < nf; f++)
        fmax_ = fmax(fmax_, size[f] = sqrt(size[f]));
    int *keep = calloc((size_t)nf, sizeof *keep);
    if (!keep) {
        free(size);
        p->nomem = 1;
        return 0;
    }
    double tmax = 0, rmax = 0;
    for (int f = 0; f < nf; f++)
        keep[f] = size[f] > 0 && size[f] >= 0.01 * fmax_;
    double ca = cos(alpha), sa = sin(alpha);
    /* the scale: the largest drawn value (the real part at the phase of the largest
     * entry) is 1; when that phase shows a group only near its zero crossing (a whirl
     * seen a quarter turn late), its largest amplitude is 1 instead, so noise is not
     * blown up */
    double tmod = 0, rmod = 0;
    for (int i = 0; i < sys->ndof; i++) {
        int h = m->nodes[sys->dof_node[i]].shaft;
        gd_dof d = sys->dof_type[i];
        if (!keep[h * GD_NODE_DOFS + d]) continue;
        double re = r->shape_re[i + (size_t)j * r->ndof], im = r->shape_im[i + (size_t)j * r->ndof];
        double q = fabs(referred(m, h, d)), a = hypot(re, im) * q, v = fabs(re * ca + im * sa) * q;
        if (is_rotation(d))
            rmod = fmax(rmod, a), rmax = fmax(rmax, v);
        else
            tmod = fmax(tmod, a), tmax = fmax(tmax, v);
    }
    if (tmax < 0.5 * tmod) tmax = tmod;
    if (rmax < 0.5 * rmod) rmax = rmod;
    /* rotations on the right-hand axis when translations are drawn, else on the left */
    int rot_right = tmax > 0;
    /* what was left out, by shaft ("shaft2" when all of it, else its families) */
    char left[400] = "";
    size_t used = 0;
    for (int h = 0; h < m->nshafts; h++) {
        int has = 0, out = 0;
        char fam[64] = "";
        size_t fl = 0;
        for (int d = 0; d < GD_NODE_DOFS; d++) {
            if (!shaft_has(sys, &m->shafts[h], (gd_dof)d)) continue;
            has++;
            if (keep[h * GD_NODE_DOFS + d]) continue;
            out++;
            fl +=
                (size_t)snprintf(fam + fl, sizeof fam - fl, "%s%s", fl ? " " : "", gd_dof_names[d]);
            if (fl >= sizeof fam) fl = sizeof fam - 1;
        }
        if (!out) continue;
        if (used < sizeof left)
            used +=
                (size_t)snprintf(left + used, sizeof left - used, "%s%s%s%s", used ? "; " : "",
                                 m->shafts[h].name, out == has ? "" : " ", out == has ? "" : fam);
    }
    char ztext[32], head[200];
    zeta_text(ztext, sizeof ztext, md->damping_ratio);
    snprintf(head, sizeof head, "mode %d: %.6g Hz, %s, whirl: %s, zeta %s", j + 1, md->frequency_hz,
             gd_motion_names[md->dominant_motion], gd_whirl_names[md->whirl], ztext);
    static const char *const colors[GD_NODE_DOFS] = {"#1f77b4", "#ff7f0e", "#2ca02c",
                                                     "#d62728", "#9467bd", "#8c564b"};
    char rlabel[100];
    snprintf(rlabel, sizeof rlabel, "rotation (largest of the mode = 1)");
    int npanels = 0;
    for (int h = 0; h < m->nshafts; h++) {
        double hp;
        if (host_of(m, h, &hp) >= 0) continue; /* drawn in its host's panel */
        int any = 0;
        for (int g = 0; g < m->nshafts; g++) {
            double gp;
            if (g != h && host_of(m, g, &gp) != h) continue;
            for (int d = 0; d < GD_NODE_DOFS; d++)
                any |= keep[g * GD_NODE_DOFS + d];
        }
        if (!any) continue;
        const gd_shaft *sh = &m->shafts[h];
        /* a lumped shaft on its own: its nodes one after the other */
        int lumped = sh->nsections == 0;
        char title[200], with[120] = "";
        size_t wl = 0;
        for (int g = 0; g < m->nshafts; g++) {
            double gp;
            if (g != h && host_of(m, g, &gp) == h && wl < sizeof with)
                wl += (size_t)snprintf(with + wl, sizeof with - wl, "%s%s", wl ? ", " : " (with ",
                                       m->shafts[g].name);
        }
        if (wl && wl < sizeof with - 1) strcat(with, ")");
        snprintf(title, sizeof title, "%.110s; %s %.32s%.40s", head,
                 lumped ? "lumped shaft" : "shaft", sh->name, with);
        pl_panel *pn = pl_panel_add(p, s, PL_XY, title,
                                    lumped ? "node (lumped shaft: no axial positions)"
                                           : "axial position along the shaft (m)",
                                    tmax > 0 ? "translation (largest of the mode = 1)" : rlabel);
        if (!pn) break;
        /* one scale for every panel of the mode */
        pn->ylim[0] = pn->y2lim[0] = -1.08;
        pn->ylim[1] = pn->y2lim[1] = 1.08;
        if (rot_right) snprintf(pn->y2label, sizeof pn->y2label, "%s", rlabel);
        if (npanels == 0)
            snprintf(pn->subtitle, sizeof pn->subtitle,
                     "left out (under 1 %% of the largest): %.340s", used ? left : "nothing");
        npanels++;
        for (int g = 0; g < m->nshafts; g++) {
            double gp = 0;
            if (g != h && host_of(m, g, &gp) != h) continue;
            const gd_shaft *gs = &m->shafts[g];
            for (int d = 0; d < GD_NODE_DOFS; d++) {
                if (!keep[g * GD_NODE_DOFS + d]) continue;
                char name[160];
                snprintf(name, sizeof name, "%s %s%s", gs->name, gd_dof_names[d],
                         d == GD_RZ && m->nshafts > 1 && gs->speed_ratio != 1 ? " (referred)" : "");
                pl_trace *t = pl_trace_add(p, pn, name, gs->nnodes, NULL, NULL,
                                           g == h ? PL_LINES_MARKERS : PL_MARKERS, colors[d]);
                if (!t) break;
                t->dash = d == GD_Y || d == GD_RY;
                t->y2 = rot_right && is_rotation((gd_dof)d);
                if (g != h) t->symbol = is_rotation((gd_dof)d) ? PL_TRIANGLE : PL_DIAMOND;
                double scale = referred(m, g, (gd_dof)d) / (is_rotation((gd_dof)d) ? rmax : tmax);
                for (int k = 0; k < gs->nnodes; k++) {
                    double re, im;
                    t->x[k] = g != h ? gp : lumped ? k : m->nodes[gs->first_node + k].position;
                    entry(sys, r, j, gs->first_node + k, (gd_dof)d, &re, &im);
                    t->y[k] = (re * ca + im * sa) * scale;
                    pl_trace_text(p, t, k, "%s %s: %.4g", m->nodes[gs->first_node + k].name,
                                  gd_dof_names[d], t->y[k]);
                }
            }
        }
        if (!lumped) items_on_axis(p, pn, m, h);
    }
    free(size);
    free(keep);
    return npanels;
}

static void whirl_panel(gd_plot *p, pl_section *s, const gd_system *sys, const gd_modal_result *r,
                        const int *plotted, int nplotted)
{
    const gd_model *m = sys->model;
    int lateral = 0;
    for (int h = 0; h < m->nshafts; h++)
        lateral |= shaft_has(sys, &m->shafts[h], GD_X) || shaft_has(sys, &m->shafts[h], GD_Y);
    if (!lateral) return;
    pl_panel *pn = pl_panel_add(
        p, s, PL_MODE3D,
        "whirl of the mode shapes (3-D: the deflected line, animated, on each station's orbit)",
        "axial position (m)", "");
    if (!pn) return;
    pn->frames = calloc((size_t)nplotted, sizeof *pn->frames);
    if (!pn->frames) {
        p->nomem = 1;
        return;
    }
    pn->nframes = nplotted;
    for (int f = 0; f < nplotted; f++) {
        int j = plotted[f];
        char label[160];
        snprintf(label, sizeof label, "mode %d: %.6g Hz, whirl: %s", j + 1,
                 r->modes[j].frequency_hz, gd_whirl_names[r->modes[j].whirl]);
        pn->frames[f] = pl_strdup(p, label);
        for (int h = 0; h < m->nshafts; h++) {
            const gd_shaft *sh = &m->shafts[h];
            pl_trace *t =
                pl_trace_add(p, pn, sh->name, sh->nnodes, NULL, NULL, PL_LINES, pl_color(h));
            if (!t) return;
            t->frame = f;
            t->xr = calloc((size_t)sh->nnodes, sizeof(double));
            t->xi = calloc((size_t)sh->nnodes, sizeof(double));
            t->yr = calloc((size_t)sh->nnodes, sizeof(double));
            t->yi = calloc((size_t)sh->nnodes, sizeof(double));
            if (!t->xr || !t->xi || !t->yr || !t->yi) {
                p->nomem = 1;
                return;
            }
            for (int k = 0; k < sh->nnodes; k++) {
                int node = sh->first_node + k;
                t->x[k] = m->nodes[node].position;
                entry(sys, r, j, node, GD_X, &t->xr[k], &t->xi[k]);
                entry(sys, r, j, node, GD_Y, &t->yr[k], &t->yi[k]);
                if (isnan(t->xr[k])) t->xr[k] = t->xi[k] = 0;
                if (isnan(t->yr[k])) t->yr[k] = t->yi[k] = 0;
            }
        }
    }
}

static const char *component_name(const gd_system *sys, int c)
{
    int idx;
    const char *name = "";
    if (c >= 0) gd_system_component(sys, c, &idx, &name);
    return name;
}

static void energy_table(gd_plot *p, pl_section *s, const gd_system *sys, const gd_modal_result *r,
                         int nelastic)
{
    /* with planetary sets, each set's mode class ([LinParker1999]: docs/planetary.md) */
    int nc = r->ncomponents, ns = sys->model->nplanetary, h = 5 + ns, cols = h + GD_NMOTIONS + nc;
    pl_panel *pn = pl_panel_add(
        p, s, PL_TABLE,
        ns ? "modal strain energy (%): by motion type and by component; planetary mode classes"
           : "modal strain energy (%): by motion type and by component",
        NULL, NULL);
    pl_table_init(p, pn, nelastic, cols);
    const char *head[5] = {"mode", "f (Hz)", "zeta", "whirl", "dominant"};
    for (int c = 0; c < 5; c++)
        pl_cell(p, pn, 0, c, "%s", head[c]);
    for (int k = 0; k < ns; k++)
        pl_cell(p, pn, 0, 5 + k, "class (%s)", sys->model->planetary[k].name);
    for (int k = 0; k < GD_NMOTIONS; k++)
        pl_cell(p, pn, 0, h + k, "%s", gd_motion_names[k]);
    for (int c = 0; c < nc; c++)
        pl_cell(p, pn, 0, h + GD_NMOTIONS + c, "%s", component_name(sys, c));
    int row = 1;
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (md->rigid_body) continue;
        pl_cell(p, pn, row, 0, "%d", j + 1);
        pl_cell(p, pn, row, 1, "%.6g", md->frequency_hz);
        char z[32];
        zeta_text(z, sizeof z, md->damping_ratio);
        pl_cell(p, pn, row, 2, "%s", z);
        pl_cell(p, pn, row, 3, "%s", gd_whirl_names[md->whirl]);
        pl_cell(p, pn, row, 4, "%s", gd_motion_names[md->dominant_motion]);
        for (int k = 0; k < ns; k++)
            pl_cell(p, pn, row, 5 + k, "%s",
                    gd_planetary_class_names[gd_modal_planetary_class(sys, r, j, k)]);
        for (int k = 0; k < GD_NMOTIONS; k++)
            pl_cell(p, pn, row, h + k, "%.1f", 100 * md->energy_share[k]);
        for (int c = 0; c < nc; c++)
            pl_cell(p, pn, row, h + GD_NMOTIONS + c, "%.1f",
                    100 * r->energy_by_component[c + (size_t)j * nc]);
        row++;
    }
}

gd_status gd_plot_modal(const gd_system *sys, const gd_modal_result *r, gd_plot **out,
                        gd_error *err)
{
    int nelastic = 0;
    for (int j = 0; j < r->nmodes; j++)
        nelastic += !r->modes[j].rigid_body;
    if (!nelastic)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot",
                            "ask for more modes (--modes N or all)",
                            "nothing to plot: the %d mode%s computed %s rigid-body", r->nmodes,
                            r->nmodes == 1 ? "" : "s", r->nmodes == 1 ? "is" : "are all");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn modes", &p, err);
    if (st) return st;
    pl_section *s = pl_section_add(p, "Modes");
    pl_note(p, s, "%s: %d DOFs at %.6g rpm, %s modes; %d elastic mode%s%s.", sys->model->file,
            sys->ndof, r->speed * 30 / PI, r->damped ? "damped (state space)" : "undamped",
            nelastic, nelastic == 1 ? "" : "s",
            nelastic > MAX_SHAPES ? "; the shapes of the lowest 12 are drawn" : "");
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "mode_shapes.csv");
    pl_csv(p, s, "mode,frequency_hz,node,shaft,position_m,dof,real,imag\n");
    int plotted[MAX_SHAPES], np = 0;
    double *mdiag = mass_diagonal(p, sys);
    for (int j = 0; j < r->nmodes && np < MAX_SHAPES; j++) {
        if (r->modes[j].rigid_body) continue;
        plotted[np++] = j;
        shape_panels(p, s, sys, r, j, mdiag);
        for (int i = 0; i < sys->ndof; i++) {
            const gd_node *nd = &sys->model->nodes[sys->dof_node[i]];
            pl_csv(p, s, "%d,%.10g,%s,%s,%.10g,%s,%.10g,%.10g\n", j + 1, r->modes[j].frequency_hz,
                   nd->name, sys->model->shafts[nd->shaft].name, nd->position,
                   gd_dof_names[sys->dof_type[i]], r->shape_re[i + (size_t)j * r->ndof],
                   r->shape_im[i + (size_t)j * r->ndof]);
        }
    }
    free(mdiag);
    whirl_panel(p, s, sys, r, plotted, np);
    energy_table(p, s, sys, r, nelastic);
    return pl_done(p, out, err);
}
