/* A model file parsed once and loaded many times with different overrides
 * (gd_model_source, geardyn/model_file.h): every load clones the parsed document,
 * applies its overrides to the clone and reads the model (or gear pair) from it. */
#include <stdio.h>
#include <math.h>
#include <stdlib.h>

#include "geardyn/model_file.h"
#include "model_file/model_file_impl.h"
#include "model_file/overrides_impl.h"

struct gd_model_source {
    gd_ydoc *doc;
};

gd_status gd_model_source_load(const char *path, gd_model_source **out, gd_error *err)
{
    *out = NULL;
    gd_model_source *src = calloc(1, sizeof *src);
    if (!src) return gd_error_set(err, GD_ENOMEM, path, 0, 0, "", "", "out of memory");
    gd_status st = gd_ydoc_load_file(path, &src->doc, err);
    if (st) {
        free(src);
        return st;
    }
    *out = src;
    return GD_OK;
}

static gd_status clone(const gd_model_source *src, gd_ydoc **doc, gd_error *err)
{
    *doc = gd_ydoc_clone(src->doc);
    if (!*doc) return gd_error_set(err, GD_ENOMEM, src->doc->file, 0, 0, "", "", "out of memory");
    return GD_OK;
}

gd_status gd_model_source_model(const gd_model_source *src, const gd_load_options *opt,
                                gd_model **out, gd_error *err)
{
    *out = NULL;
    gd_ydoc *doc;
    gd_status st = clone(src, &doc, err);
    if (st) return st;
    st = gd_ydoc_apply(doc, opt, err);
    if (!st) st = gd_model_from_ydoc(doc, src->doc->file, out, err);
    gd_ydoc_free(doc);
    return st;
}

gd_status gd_model_source_gear_pair(const gd_model_source *src, const char *mesh_name,
                                    const gd_load_options *opt, gd_gear_pair_geometry *geom,
                                    gd_tvms_options *tvms, char *mesh_name_out, size_t size,
                                    gd_error *err)
{
    gd_ydoc *doc;
    gd_status st = clone(src, &doc, err);
    if (st) return st;
    return gd_gear_pair_from_ydoc(doc, mesh_name, opt, geom, tvms, mesh_name_out, size, err);
}

gd_status gd_model_source_check_path(const gd_model_source *src, const char *path, int *adds,
                                     gd_error *err)
{
    *adds = 0;
    char origin[512];
    snprintf(origin, sizeof origin, "--set %s", path);
    gd_ytarget *t = NULL;
    size_t n = 0;
    gd_status st = gd_ypath_resolve(src->doc->root, path, origin, &t, &n, err);
    for (size_t i = 0; !st && i < n; i++)
        if (t[i].add) *adds = 1;
    free(t);
    return st;
}

gd_status gd_model_source_value(const gd_model_source *src, const gd_load_options *opt,
                                const char *path, double *value, gd_error *err)
{
    *value = NAN;
    gd_ydoc *doc;
    gd_status st = clone(src, &doc, err);
    if (st) return st;
    st = gd_ydoc_apply(doc, opt, err);
    char origin[512];
    snprintf(origin, sizeof origin, "--update %s", path);
    gd_ytarget *t = NULL;
    size_t n = 0;
    if (!st) st = gd_ypath_resolve(doc->root, path, origin, &t, &n, err);
    const gd_ynode *v = NULL;
    if (!st && n > 0 && !t[0].add) {
        const gd_ynode *parent = t[0].parent;
        v = parent->items[t[0].index];
    }
    if (!st && (!v || v->kind != GD_Y_SCALAR))
        st = gd_error_set(err, GD_EINPUT, origin, 0, 0, path,
                          "name a number of the file, e.g. bearings.A1.k or meshes.mesh.stiffness",
                          "'%s' is %s, not a number of the file", path,
                          v ? gd_ykind_name(v->kind) : "not in the file");
    if (!st) {
        /* a plain number, or a number with the units of any quantity */
        char *end;
        double x = strtod(v->text, &end);
        int ok = end != v->text && *end == 0;
        for (int q = 0; !ok && q < GD_QTY_COUNT_; q++)
            ok = gd_parse_quantity(v->text, (gd_qty)q, &x, NULL) == GD_OK;
        if (ok)
            *value = x;
        else
            st = gd_error_set(err, GD_EINPUT, origin, 0, 0, path,
                              "name a number of the file, e.g. bearings.A1.k",
                              "'%s' is '%s', not a number", path, v->text);
    }
    free(t);
    gd_ydoc_free(doc);
    return st;
}

const char *gd_model_source_file(const gd_model_source *src)
{
    return src->doc->file;
}

void gd_model_source_free(gd_model_source *src)
{
    if (!src) return;
    gd_ydoc_free(src->doc);
    free(src);
}
