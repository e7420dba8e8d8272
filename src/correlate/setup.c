/* The test setup: which model node each test point label is (docs/testing.md),
 *   points:
 *     2: gear32     # label: node name
 *     3: brg_n1
 * and a measured point's DOF on a built system. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/correlate.h"
#include "model_file/yaml_doc_impl.h"

void gd_test_setup_free(gd_test_setup *s)
{
    if (!s) return;
    free(s->label);
    free(s->node);
    free(s->line);
    free(s);
}

gd_status gd_test_setup_load(const char *path, gd_test_setup **out, gd_error *err)
{
    *out = NULL;
    gd_ydoc *doc;
    gd_status st = gd_ydoc_load_file(path, &doc, err);
    if (st) return st;
    gd_yreader r = {path, err};
    gd_test_setup *s = calloc(1, sizeof *s);
    if (!s) {
        gd_ydoc_free(doc);
        return gd_error_set(err, GD_ENOMEM, path, 0, 0, "", "", "out of memory");
    }
    snprintf(s->file, sizeof s->file, "%s", path);
    static const char *const KEYS[] = {"points", NULL};
    const gd_ynode *root = doc->root, *pts = NULL;
    if (!root || root->kind != GD_Y_MAP)
        st = gd_yfail(&r, root, "", "write `points:` with one `LABEL: NODE` line per test point",
                      "a test setup is a map with `points:`");
    if (!st) st = gd_ycheck_keys(&r, root, "", KEYS);
    if (!st) {
        pts = gd_ymap_get(root, "points");
        if (!pts) st = gd_yfail(&r, root, "points", "add `points: {2: gear32}`", "no `points:`");
    }
    if (!st) st = gd_yexpect(&r, pts, GD_Y_MAP, "points");
    if (!st) {
        s->label = calloc(pts->n + 1, sizeof *s->label);
        s->node = calloc(pts->n + 1, sizeof *s->node);
        s->line = calloc(pts->n + 1, sizeof *s->line);
        if (!s->label || !s->node || !s->line)
            st = gd_error_set(err, GD_ENOMEM, path, 0, 0, "", "", "out of memory");
    }
    for (size_t i = 0; !st && i < pts->n; i++) {
        const gd_ynode *k = pts->keys[i], *v = pts->items[i];
        char *end;
        long lab = strtol(k->text, &end, 10);
        char fld[96];
        snprintf(fld, sizeof fld, "points.%s", k->text);
        if (end == k->text || *end)
            st = gd_yfail(&r, k, fld, "labels are the test's point numbers, as in the UFF file",
                          "point label '%s' is not a whole number", k->text);
        else if (v->kind != GD_Y_SCALAR)
            st = gd_yfail(&r, v, fld, "the value is a model node name", "expected a node name");
        else {
            for (int j = 0; j < s->npoints; j++)
                if (s->label[j] == lab)
                    st = gd_yfail(&r, k, fld, "give each label once",
                                  "point %ld appears twice (line %d)", lab, s->line[j]);
            if (!st) {
                s->label[s->npoints] = (int)lab;
                snprintf(s->node[s->npoints], 64, "%s", v->text);
                s->line[s->npoints] = v->line;
                s->npoints++;
            }
        }
    }
    gd_ydoc_free(doc);
    if (st) {
        gd_test_setup_free(s);
        return st;
    }
    *out = s;
    return GD_OK;
}

gd_status gd_test_point_dof(const gd_system *sys, const gd_test_setup *setup, int label, int dir,
                            const char *where_file, int where_line, int *dof, double *sign,
                            gd_error *err)
{
    const gd_model *m = sys->model;
    int node = -1;
    char what[GD_NODE_NAME_MAX + 96];
    if (setup) {
        int j = 0;
        while (j < setup->npoints && setup->label[j] != label)
            j++;
        if (j == setup->npoints)
            return gd_error_set(err, GD_EINPUT, where_file, where_line, 0, "point",
                                "add the point to the setup's `points:`",
                                "test point %d is not in the test setup %s", label, setup->file);
        node = gd_model_find_node(m, setup->node[j]);
        if (node < 0)
            return gd_error_set(err, GD_EINPUT, setup->file, setup->line[j], 0, "points",
                                "name a node of the model (geardyn check MODEL lists them)",
                                "node '%s' of test point %d is not in the model", setup->node[j],
                                label);
        snprintf(what, sizeof what, "node '%s' (test point %d)", setup->node[j], label);
    } else {
        if (label < 1 || label > m->nnodes)
            return gd_error_set(err, GD_EINPUT, where_file, where_line, 0, "point",
                                "without --setup, point N is the model's node N (1-based); "
                                "map the points to nodes with a setup file",
                                "test point %d is not a node of the model (it has %d)", label,
                                m->nnodes);
        node = label - 1;
        snprintf(what, sizeof what, "node %d '%s'", label, m->nodes[node].name);
    }
    int a = dir < 0 ? -dir : dir;
    if (a < 1 || a > 6)
        return gd_error_set(err, GD_EINPUT, where_file, where_line, 0, "direction",
                            "measure a translation or rotation: +-1..6 (x, y, z, rx, ry, rz)",
                            "direction %d of test point %d is not a DOF", dir, label);
    *dof = gd_system_dof(sys, node, (gd_dof)(a - 1));
    *sign = dir < 0 ? -1 : 1;
    if (*dof < 0)
        return gd_error_set(err, GD_EINPUT, where_file, where_line, 0, "direction",
                            "measure a DOF the model keeps (its `dofs:`)",
                            "%s has no active DOF %s", what, gd_dof_names[a - 1]);
    return GD_OK;
}
