/* The figure of a modal analysis: mode shapes along each shaft, the 3-D whirl view and
 * the strain-energy table (002 Tables 4-7: shares by motion type and by component). */
#include <math.h>
#include <stdlib.h>

#include "plot/plot_impl.h"

#define PI 3.14159265358979323846
enum { MAX_SHAPES = 12 }; /* mode-shape panels drawn; the table lists every mode */

static const gd_dof SHAPE_DOFS[4] = {GD_X, GD_Y, GD_Z, GD_RZ};
static const char *const SHAPE_NAMES[4] = {"x", "y", "axial z", "torsion rz"};

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

/* Gears, disks and bearings as markers on the axis (y = 0) of a mode-shape panel. */
static void items_on_axis(gd_plot *p, pl_panel *pn, const gd_model *m)
{
    int n = m->ndisks + 2 * m->nmeshes;
    double *x = calloc((size_t)n + m->nbearings + 1, sizeof *x);
    if (!x) {
        p->nomem = 1;
        return;
    }
    int k = 0;
    for (int d = 0; d < m->ndisks; d++)
        x[k++] = m->nodes[m->disks[d].node].position;
    for (int g = 0; g < m->nmeshes; g++) {
        x[k++] = m->nodes[m->meshes[g].driver].position;
        x[k++] = m->nodes[m->meshes[g].driven].position;
    }
    pl_trace *t = n ? pl_trace_add(p, pn, "gears and disks", n, x, NULL, PL_MARKERS, "#444") : NULL;
    if (t) {
        t->symbol = PL_DIAMOND;
        k = 0;
        for (int d = 0; d < m->ndisks; d++)
            pl_trace_text(p, t, k++, "disk %s at %s", m->disks[d].name,
                          m->nodes[m->disks[d].node].name);
        for (int g = 0; g < m->nmeshes; g++) {
            pl_trace_text(p, t, k++, "mesh %s driver %s", m->meshes[g].name,
                          m->nodes[m->meshes[g].driver].name);
            pl_trace_text(p, t, k++, "mesh %s driven %s", m->meshes[g].name,
                          m->nodes[m->meshes[g].driven].name);
        }
    }
    for (int b = 0; b < m->nbearings; b++)
        x[b] = m->nodes[m->bearings[b].node].position;
    t = m->nbearings ? pl_trace_add(p, pn, "bearings", m->nbearings, x, NULL, PL_MARKERS, "#8c564b")
                     : NULL;
    if (t) {
        t->symbol = PL_SQUARE;
        for (int b = 0; b < m->nbearings; b++)
            pl_trace_text(p, t, b, "bearing %s at %s", m->bearings[b].name,
                          m->nodes[m->bearings[b].node].name);
    }
    free(x);
}

static void shape_panel(gd_plot *p, pl_section *s, const gd_system *sys, const gd_modal_result *r,
                        int j)
{
    const gd_model *m = sys->model;
    const gd_mode *md = &r->modes[j];
    char title[200];
    snprintf(title, sizeof title, "mode %d: %.6g Hz, %s, %s whirl, zeta %.3g", j + 1,
             md->frequency_hz, gd_motion_names[md->dominant_motion], gd_whirl_names[md->whirl],
             md->damping_ratio);
    pl_panel *pn = pl_panel_add(p, s, PL_XY, title, "axial position along the shaft (m)",
                                "shape, real part (translations and torsion each scaled to 1)");
    /* metres and radians do not share a scale: each group to its own largest entry */
    double big[2] = {0, 0};
    for (int i = 0; i < sys->ndof; i++) {
        gd_dof d = sys->dof_type[i];
        if (d == GD_RX || d == GD_RY) continue;
        double a =
            hypot(r->shape_re[i + (size_t)j * r->ndof], r->shape_im[i + (size_t)j * r->ndof]);
        big[d == GD_RZ] = fmax(big[d == GD_RZ], a);
    }
    for (int h = 0; h < m->nshafts; h++) {
        const gd_shaft *sh = &m->shafts[h];
        for (int d = 0; d < 4; d++) {
            if (!shaft_has(sys, sh, SHAPE_DOFS[d])) continue;
            char name[160];
            snprintf(name, sizeof name, "%s %s", sh->name, SHAPE_NAMES[d]);
            pl_trace *t = pl_trace_add(p, pn, name, sh->nnodes, NULL, NULL, PL_LINES_MARKERS,
                                       pl_color(4 * h + d));
            if (!t) return;
            t->dash = d == 1;
            for (int k = 0; k < sh->nnodes; k++) {
                double im;
                t->x[k] = m->nodes[sh->first_node + k].position;
                entry(sys, r, j, sh->first_node + k, SHAPE_DOFS[d], &t->y[k], &im);
                double b = big[SHAPE_DOFS[d] == GD_RZ];
                t->y[k] = b > 0 ? t->y[k] / b : 0;
            }
        }
    }
    items_on_axis(p, pn, m);
}

static void whirl_panel(gd_plot *p, pl_section *s, const gd_system *sys, const gd_modal_result *r,
                        const int *plotted, int nplotted)
{
    const gd_model *m = sys->model;
    int lateral = 0;
    for (int h = 0; h < m->nshafts; h++)
        lateral |= shaft_has(sys, &m->shafts[h], GD_X) || shaft_has(sys, &m->shafts[h], GD_Y);
    if (!lateral) return;
    pl_panel *pn = pl_panel_add(p, s, PL_MODE3D, "whirl of the mode shapes (3-D, animated)",
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
        snprintf(label, sizeof label, "mode %d: %.6g Hz, %s whirl", j + 1, r->modes[j].frequency_hz,
                 gd_whirl_names[r->modes[j].whirl]);
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
    int nc = r->ncomponents, cols = 5 + GD_NMOTIONS + nc;
    pl_panel *pn = pl_panel_add(
        p, s, PL_TABLE, "modal strain energy (%): by motion type and by component", NULL, NULL);
    pl_table_init(p, pn, nelastic, cols);
    const char *head[5] = {"mode", "f (Hz)", "zeta", "whirl", "dominant"};
    for (int c = 0; c < 5; c++)
        pl_cell(p, pn, 0, c, "%s", head[c]);
    for (int k = 0; k < GD_NMOTIONS; k++)
        pl_cell(p, pn, 0, 5 + k, "%s", gd_motion_names[k]);
    for (int c = 0; c < nc; c++)
        pl_cell(p, pn, 0, 5 + GD_NMOTIONS + c, "%s", component_name(sys, c));
    int row = 1;
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (md->rigid_body) continue;
        pl_cell(p, pn, row, 0, "%d", j + 1);
        pl_cell(p, pn, row, 1, "%.6g", md->frequency_hz);
        pl_cell(p, pn, row, 2, "%.3g", md->damping_ratio);
        pl_cell(p, pn, row, 3, "%s", gd_whirl_names[md->whirl]);
        pl_cell(p, pn, row, 4, "%s", gd_motion_names[md->dominant_motion]);
        for (int k = 0; k < GD_NMOTIONS; k++)
            pl_cell(p, pn, row, 5 + k, "%.1f", 100 * md->energy_share[k]);
        for (int c = 0; c < nc; c++)
            pl_cell(p, pn, row, 5 + GD_NMOTIONS + c, "%.1f",
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
    for (int j = 0; j < r->nmodes && np < MAX_SHAPES; j++) {
        if (r->modes[j].rigid_body) continue;
        plotted[np++] = j;
        shape_panel(p, s, sys, r, j);
        for (int i = 0; i < sys->ndof; i++) {
            const gd_node *nd = &sys->model->nodes[sys->dof_node[i]];
            pl_csv(p, s, "%d,%.10g,%s,%s,%.10g,%s,%.10g,%.10g\n", j + 1, r->modes[j].frequency_hz,
                   nd->name, sys->model->shafts[nd->shaft].name, nd->position,
                   gd_dof_names[sys->dof_type[i]], r->shape_re[i + (size_t)j * r->ndof],
                   r->shape_im[i + (size_t)j * r->ndof]);
        }
    }
    whirl_panel(p, s, sys, r, plotted, np);
    energy_table(p, s, sys, r, nelastic);
    return pl_done(p, out, err);
}
