/* What the analyses of a study share (study_impl.h): a response's peak, the k-th of a
 * set of values, the sweep keys of an analysis's options (FROM:TO:COUNT with units) and
 * the probe a record names (a DOF or a mesh). Apart from the dispatch table
 * (analyses.c), so that no analysis file and the table use each other. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/study_impl.h"

long gd_study_peak(const double *re, const double *im, size_t n, double *peak)
{
    long at = -1;
    *peak = NAN;
    for (size_t k = 0; k < n; k++) {
        double mag = hypot(re[k], im[k]);
        if (at < 0 ? !isnan(mag) : mag > *peak) {
            *peak = mag;
            at = (long)k;
        }
    }
    return at;
}

double gd_study_kth(const double *v, int n, int k)
{
    return k >= 1 && k <= n ? v[k - 1] : NAN;
}

gd_status gd_study_read_sweep(gd_yreader *r, const gd_ynode *map, const char *key,
                              gd_study_sweep *out)
{
    static const char *const KEYS[] = {"from", "to", "count", NULL};
    char path[128];
    snprintf(path, sizeof path, "analysis.%s", key);
    const gd_ynode *n = map ? gd_ymap_get(map, key) : NULL;
    if (!n)
        return gd_yfail(r, map, path, "e.g. `speeds: {from: 0, to: 6000 rpm, count: 61}`",
                        "missing key '%s'", key);
    if (gd_yexpect(r, n, GD_Y_MAP, path) || gd_ycheck_keys(r, n, path, KEYS) ||
        gd_yread_qty(r, n, "from", path, GD_QTY_ANGULAR_SPEED, GD_YREQ | GD_YNONNEG, &out->from,
                     NULL) ||
        gd_yread_qty(r, n, "to", path, GD_QTY_ANGULAR_SPEED, GD_YREQ | GD_YNONNEG, &out->to,
                     NULL) ||
        gd_yread_int(r, n, "count", path, 1, 1000000, GD_YREQ, &out->count, NULL))
        return GD_EINPUT;
    if (out->count > 1 && !(out->to > out->from))
        return gd_yfail(r, n, path, "give from < to", "empty range: from %g to %g rad/s", out->from,
                        out->to);
    return GD_OK;
}

double *gd_study_sweep_values(const gd_study_sweep *sw)
{
    double *v = malloc((size_t)sw->count * sizeof *v);
    for (long i = 0; v && i < sw->count; i++)
        v[i] = sw->count == 1
                   ? sw->from
                   : sw->from + (sw->to - sw->from) * (double)i / (double)(sw->count - 1);
    return v;
}

gd_status gd_study_probe(const gd_system *sys, const char *text, gd_probe *probe, int *dof,
                         gd_error *err)
{
    const gd_model *m = sys->model;
    memset(probe, 0, sizeof *probe);
    snprintf(probe->name, sizeof probe->name, "%s", text);
    *dof = -1;
    const char *hint = "write mesh:NAME, NODE.DOF (x, y, z, rx, ry, rz) or torque:NODE";
    const char *rest;
    const gd_element_type *kind = gd_probe_element(text, &rest);
    if (kind && !kind->probe_dirs) { /* the one-force kinds: mesh:NAME */
        int k = gd_probe_instance(sys, kind, rest);
        if (k < 0)
            return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "", hint, "no %s named '%s'",
                                kind->name, rest);
        probe->element = kind;
        probe->index = k;
        return GD_OK;
    }
    char node[160] = "";
    const char *dofname = "rz";
    if (!strncmp(text, "torque:", 7)) {
        snprintf(node, sizeof node, "%s", text + 7);
    } else {
        const char *t = strncmp(text, "node:", 5) ? text : text + 5;
        const char *dot = strrchr(t, '.');
        if (!dot)
            return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "", hint, "not a probe: '%s'", text);
        snprintf(node, sizeof node, "%.*s", (int)(dot - t), t);
        dofname = dot + 1;
    }
    int n = gd_model_find_node(m, node);
    if (n < 0)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "", hint, "no node named '%s'", node);
    for (int d = 0; d < GD_NODE_DOFS; d++)
        if (!strcmp(dofname, gd_dof_names[d])) *dof = gd_system_dof(sys, n, (gd_dof)d);
    if (*dof < 0)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "", hint,
                            "'%s' is not an active DOF of the model", text);
    probe->element = NULL;
    probe->index = *dof;
    return GD_OK;
}
