/* Reading tables {x: [...], y: [...], interpolation} and lists of quantities; the
 * shape of a table (lengths, increasing abscissae, one period) is checked here, where
 * the written lists can be pointed at. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/model_file_impl.h"

static const char *const INTERPOLATIONS[] = {"linear", "spline", NULL};

gd_status gd_mp_read_qty_list(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                              gd_qty qty, double **out, int *n)
{
    char q[220];
    gd_ypath_key(q, sizeof q, path, key);
    const gd_ynode *v = gd_ymap_get(map, key);
    *out = NULL;
    *n = 0;
    if (!v) return gd_yfail(&p->r, map, q, NULL, "required list '%s' is missing", key);
    gd_status st = gd_yexpect(&p->r, v, GD_Y_SEQ, q);
    if (st) return st;
    if (v->n == 0) return gd_yfail(&p->r, v, q, "give at least two values", "empty list");
    *out = malloc(v->n * sizeof **out);
    if (!*out) return gd_mp_oom(p);
    for (size_t i = 0; i < v->n; i++) {
        char ip[240];
        if ((st = gd_yread_node_qty(&p->r, v->items[i], gd_ypath_index(ip, sizeof ip, q, i), qty, 0,
                                    &(*out)[i]))) {
            free(*out);
            *out = NULL;
            return st;
        }
    }
    *n = (int)v->n;
    return GD_OK;
}

/* A table {xkey: [...], ykey: [...], interpolation}; periodic with period (0: not).
 * Angles of a periodic table must lie in [0, period). */
gd_status gd_mp_read_table(gd_mparser *p, const gd_ynode *map, const char *path, const char *xkey,
                           gd_qty xq, const char *ykey, gd_qty yq, double period,
                           gd_interp def_interp, gd_table **out)
{
    const char *const keys[4] = {xkey, ykey, "interpolation", NULL};
    gd_status st;
    if ((st = gd_yexpect(&p->r, map, GD_Y_MAP, path)) ||
        (st = gd_ycheck_keys(&p->r, map, path, keys)))
        return st;
    int ii = def_interp, nx, ny;
    if ((st = gd_yread_str(&p->r, map, "interpolation", path, INTERPOLATIONS, 0, NULL, &ii, NULL)))
        return st;
    double *x = NULL, *y = NULL;
    if ((st = gd_mp_read_qty_list(p, map, xkey, path, xq, &x, &nx)) ||
        (st = gd_mp_read_qty_list(p, map, ykey, path, yq, &y, &ny)))
        goto done;
    char q[220];
    if (nx != ny) {
        st = gd_yfail(&p->r, gd_ymap_get(map, ykey), gd_ypath_key(q, sizeof q, path, ykey),
                      "give one value per entry of the first list", "%d values for %d %s", ny, nx,
                      xkey);
        goto done;
    }
    int need = ii == GD_INTERP_SPLINE ? 3 : 2;
    if (nx < need) {
        st = gd_yfail(&p->r, gd_ymap_get(map, xkey), gd_ypath_key(q, sizeof q, path, xkey),
                      need == 3 ? "a spline needs three points or more" : "give two points or more",
                      "only %d point%s", nx, nx == 1 ? "" : "s");
        goto done;
    }
    for (int i = 1; i < nx; i++)
        if (!(x[i] > x[i - 1])) {
            st = gd_yfail(&p->r, gd_ymap_get(map, xkey), gd_ypath_key(q, sizeof q, path, xkey),
                          "sort the points by increasing value, without repeats",
                          "values must increase (entry %d is not above entry %d)", i, i - 1);
            goto done;
        }
    if (period > 0 && (x[0] < 0 || x[nx - 1] >= period * (1 - 1e-12))) {
        char hint[160];
        snprintf(hint, sizeof hint, "give one period: angles from 0 up to (not including) %.6g rad",
                 period);
        st = gd_yfail(&p->r, gd_ymap_get(map, xkey), gd_ypath_key(q, sizeof q, path, xkey), hint,
                      "angles outside one period");
        goto done;
    }
    if ((st = gd_table_new(nx, x, y, period, (gd_interp)ii, out, p->r.err))) {
        /* locate the library's complaint at the table */
        p->r.err->line = map->line;
        p->r.err->column = map->column;
        snprintf(p->r.err->file, sizeof p->r.err->file, "%s", p->r.file);
        snprintf(p->r.err->field, sizeof p->r.err->field, "%s", path);
    }
done:
    free(x);
    free(y);
    return st;
}

gd_table_spec gd_mp_table_spec(const gd_table *t)
{
    gd_table_spec s = {0, NULL, NULL, GD_INTERP_LINEAR};
    if (t) {
        s.n = t->n;
        s.x = t->x;
        s.y = t->y;
        s.interp = t->interp;
    }
    return s;
}
