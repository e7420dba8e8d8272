/* Static analysis: the deflected shafts (x and y displacement and the slopes along each
 * shaft, bearings marked with their reactions), and tables of the bearing reactions and
 * of each mesh's force and misalignment. */
#include <math.h>
#include <stdlib.h>

#include "plot/plot_impl.h"

/* One trace per shaft of node DOF d along the shaft (position m), scaled. */
static void along(gd_plot *p, pl_panel *pn, const gd_system *sys, const gd_static_result *r,
                  gd_dof d, double scale, const char *suffix, int second)
{
    const gd_model *m = sys->model;
    for (int s = 0; s < m->nshafts; s++) {
        const gd_shaft *sh = &m->shafts[s];
        char nm[160];
        snprintf(nm, sizeof nm, "%s %s", sh->name, suffix);
        pl_trace *t =
            pl_trace_add(p, pn, nm, sh->nnodes, NULL, NULL, PL_LINES_MARKERS, pl_color(s));
        if (t) t->dash = second; /* the second quantity of a panel dashed */
        for (int i = 0; t && i < sh->nnodes; i++) {
            int node = sh->first_node + i;
            t->x[i] = m->nodes[node].position;
            t->y[i] = r->u[(size_t)node * GD_NODE_DOFS + d] * scale;
            pl_trace_text(p, t, i, "%s", m->nodes[node].name);
        }
    }
    /* the bearings: markers on the axis, labelled with their reaction */
    if (m->nbearings > 0 && !second) {
        pl_trace *t = pl_trace_add(p, pn, "bearings", m->nbearings, NULL, NULL, PL_MARKERS, "#000");
        if (t) t->symbol = PL_TRIANGLE;
        for (int b = 0; t && b < m->nbearings; b++) {
            int node = m->bearings[b].node;
            t->x[b] = m->nodes[node].position;
            t->y[b] = r->u[(size_t)node * GD_NODE_DOFS + d] * scale;
            const gd_static_reaction *re = &r->bearings[b];
            pl_trace_text(p, t, b, "%s: F = (%.4g, %.4g, %.4g) N, M = (%.4g, %.4g) N m",
                          m->bearings[b].name, re->force[0], re->force[1], re->force[2],
                          re->moment[0], re->moment[1]);
        }
    }
}

gd_status gd_plot_static(const gd_system *sys, const gd_static_result *r, gd_plot **out,
                         gd_error *err)
{
    const gd_model *m = sys->model;
    if (m->nshafts < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot", "", "nothing to plot: no shaft");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn static", &p, err);
    if (st) return st;
    pl_section *s = pl_section_add(p, "Static deflection, bearing reactions and mesh misalignment");
    pl_note(p, s,
            "Equilibrium under the mean loads and gravity (docs/static.md); %d DOFs, %d held. "
            "Hover a bearing for its reaction.",
            r->ndof, r->nholds);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "static_nodes.csv");
    pl_panel *px =
        pl_panel_add(p, s, PL_XY, "deflection x", "position along the shaft (m)", "x (um)");
    along(p, px, sys, r, GD_X, 1e6, "x", 0);
    pl_panel *py =
        pl_panel_add(p, s, PL_XY, "deflection y", "position along the shaft (m)", "y (um)");
    along(p, py, sys, r, GD_Y, 1e6, "y", 0);
    pl_panel *pt = pl_panel_add(p, s, PL_XY, "slope (section rotation)",
                                "position along the shaft (m)", "rotation (mrad)");
    along(p, pt, sys, r, GD_RX, 1e3, "rx", 0);
    along(p, pt, sys, r, GD_RY, 1e3, "ry (dashed)", 1);
    if (m->nbearings > 0) {
        pl_panel *tb = pl_panel_add(p, s, PL_TABLE, "bearing reactions (on the shaft)", "", "");
        pl_table_init(p, tb, m->nbearings, 7);
        const char *hd[7] = {"bearing",  "Fx (N)",   "Fy (N)",  "Fz (N)",
                             "Mx (N m)", "My (N m)", "Mz (N m)"};
        for (int c = 0; c < 7; c++)
            pl_cell(p, tb, 0, c, "%s", hd[c]);
        for (int b = 0; b < m->nbearings; b++) {
            const gd_static_reaction *re = &r->bearings[b];
            pl_cell(p, tb, b + 1, 0, "%s", m->bearings[b].name);
            for (int k = 0; k < 3; k++) {
                pl_cell(p, tb, b + 1, 1 + k, "%.5g", re->force[k] == 0 ? 0.0 : re->force[k]);
                pl_cell(p, tb, b + 1, 4 + k, "%.5g", re->moment[k] == 0 ? 0.0 : re->moment[k]);
            }
        }
    }
    if (m->nmeshes > 0) {
        pl_panel *tm = pl_panel_add(p, s, PL_TABLE, "meshes: force and misalignment", "", "");
        pl_table_init(p, tm, m->nmeshes, 7);
        const char *hd[7] = {"mesh",           "F normal (N)",    "F axial (N)",
                             "tilt in (urad)", "tilt out (urad)", "f_sh (um)",
                             "F_beta_x (um)"};
        for (int c = 0; c < 7; c++)
            pl_cell(p, tm, 0, c, "%s", hd[c]);
        for (int k = 0; k < m->nmeshes; k++) {
            const gd_static_mesh *g = &r->meshes[k];
            pl_cell(p, tm, k + 1, 0, "%s", m->meshes[k].name);
            pl_cell(p, tm, k + 1, 1, "%.5g", g->force);
            pl_cell(p, tm, k + 1, 2, "%.5g", g->axial);
            pl_cell(p, tm, k + 1, 3, "%.5g", g->tilt_in_plane * 1e6);
            pl_cell(p, tm, k + 1, 4, "%.5g", g->tilt_out_of_plane * 1e6);
            if (isfinite(g->f_sh)) {
                pl_cell(p, tm, k + 1, 5, "%.4g", g->f_sh * 1e6);
                pl_cell(p, tm, k + 1, 6, "%.4g", g->f_beta_x * 1e6);
            } else {
                pl_cell(p, tm, k + 1, 5, "-");
                pl_cell(p, tm, k + 1, 6, "-");
            }
        }
    }
    pl_csv(p, s, "shaft,node,position_m,x_m,y_m,z_m,rx_rad,ry_rad,rz_rad\n");
    for (int sh = 0; sh < m->nshafts; sh++)
        for (int i = 0; i < m->shafts[sh].nnodes; i++) {
            int node = m->shafts[sh].first_node + i;
            const double *u = r->u + (size_t)node * GD_NODE_DOFS;
            pl_csv(p, s, "%s,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", m->shafts[sh].name,
                   m->nodes[node].name, m->nodes[node].position, u[0], u[1], u[2], u[3], u[4],
                   u[5]);
        }
    return pl_done(p, out, err);
}
