/* Time integration: time histories grouped by quantity, their amplitude spectra, orbits
 * of nodes with both lateral displacements recorded, and the contact state of meshes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/spectrum.h"
#include "plot/plot_impl.h"

gd_status gd_plot_transient(const gd_system *sys, const gd_transient_result *r, gd_plot **out,
                            gd_error *err)
{
    if (r->nrecords == 0 || r->nout < 4)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot", "record something (--record)",
                            "nothing to plot: %s",
                            r->nrecords ? "fewer than 4 samples" : "no record");
    gd_plot *p;
    gd_status st = gd_plot_new("geardyn transient", &p, err);
    if (st) return st;
    int nr = r->nrecords, n = r->nout;
    double dt = r->t[1] - r->t[0];
    pl_section *s = pl_section_add(p, "Time integration");
    pl_note(p, s,
            "%d records, %d samples from %.6g s to %.6g s (every %.4g s); %ld steps, %ld "
            "contact events.",
            nr, n, r->t[0], r->t[n - 1], dt, r->steps, r->events);
    if (s) snprintf(s->csv_name, sizeof s->csv_name, "transient.csv");
    /* the CSV: one column per record */
    char(*names)[200] = calloc((size_t)nr, sizeof *names);
    const char **qty = calloc((size_t)nr, sizeof *qty), **unit = calloc((size_t)nr, sizeof *unit);
    int *done = calloc((size_t)nr, sizeof *done);
    if (!names || !qty || !unit || !done) p->nomem = 1;
    for (int k = 0; !p->nomem && k < nr; k++)
        pl_record_describe(sys, &r->records[k], names[k], sizeof names[k], &qty[k], &unit[k]);
    pl_csv(p, s, "time_s");
    for (int k = 0; !p->nomem && k < nr; k++)
        pl_csv(p, s, ",\"%s (%s)\"", names[k], unit[k]);
    pl_csv(p, s, "\n");
    for (int i = 0; !p->nomem && i < n; i++) {
        pl_csv(p, s, "%.10g", r->t[i]);
        for (int k = 0; k < nr; k++)
            pl_csv(p, s, ",%.10g", r->values[(size_t)k * n + i]);
        pl_csv(p, s, "\n");
    }
    /* one time-history panel and one spectrum panel per quantity and unit */
    for (int k = 0; !p->nomem && k < nr; k++) {
        if (done[k]) continue;
        char title[200], ylabel[120];
        snprintf(title, sizeof title, "%s: time history", qty[k]);
        snprintf(ylabel, sizeof ylabel, "%s (%s)", qty[k], unit[k]);
        pl_panel *th = pl_panel_add(p, s, PL_XY, title, "time (s)", ylabel);
        int state = r->records[k].kind == GD_REC_MESH_STATE,
            angle = r->records[k].kind == GD_REC_ANGLE;
        pl_panel *sp = NULL;
        if (!state && !angle) {
            snprintf(title, sizeof title, "%s: amplitude spectrum (Hann window, mean removed)",
                     qty[k]);
            snprintf(ylabel, sizeof ylabel, "amplitude (%s)", unit[k]);
            sp = pl_panel_add(p, s, PL_XY, title, "frequency (Hz)", ylabel);
            if (sp) sp->ylog = 1;
        }
        for (int j = k; j < nr; j++) {
            if (done[j] || strcmp(qty[j], qty[k]) || strcmp(unit[j], unit[k])) continue;
            done[j] = 1;
            pl_trace_add(p, th, names[j], n, r->t, r->values + (size_t)j * n, PL_LINES,
                         pl_color(j));
            gd_spectrum *spec = NULL;
            if (sp && dt > 0 &&
                gd_spectrum_compute(r->values + (size_t)j * n, n, dt, GD_WINDOW_HANN, &spec,
                                    NULL) == GD_OK)
                pl_trace_add(p, sp, names[j], spec->n, spec->freq, spec->amplitude, PL_LINES,
                             pl_color(j));
            gd_spectrum_free(spec);
        }
    }
    /* orbits: x and y displacement of one node */
    pl_panel *orb = NULL;
    for (int a = 0; !p->nomem && a < nr; a++) {
        const gd_tr_record *ra = &r->records[a];
        if (ra->kind != GD_REC_DISP || ra->index < 0 || ra->index >= sys->ndof ||
            sys->dof_type[ra->index] != GD_X)
            continue;
        int node = sys->dof_node[ra->index], yb = gd_system_dof(sys, node, GD_Y);
        for (int b = 0; b < nr; b++) {
            if (r->records[b].kind != GD_REC_DISP || r->records[b].index != yb || yb < 0) continue;
            if (!orb) {
                orb = pl_panel_add(p, s, PL_XY, "orbits", "x (m)", "y (m)");
                if (orb) orb->equal = 1;
            }
            pl_trace_add(p, orb, sys->model->nodes[node].name, n, r->values + (size_t)a * n,
                         r->values + (size_t)b * n, PL_LINES, pl_color(a));
            break;
        }
    }
    free(names);
    free(qty);
    free(unit);
    free(done);
    return pl_done(p, out, err);
}
