/* A gear pair read from a mesh entry of a file (gd_gear_pair_load, geardyn/model_file.h):
 * the document is loaded and overridden, the mesh picked by name or as the first with a
 * geometry, and its geometry and stiffness options read and validated, with errors
 * located in the file (or at the override that wrote the value). */
#include <stdio.h>
#include <string.h>

#include "geardyn/model_file.h"
#include "model_file/mesh_geometry_read_impl.h"
#include "model_file/model_file_impl.h"
#include "model_file/overrides_impl.h"

/* The mesh entry to use: by name, else the first with a geometry. path receives its
 * path "meshes[i]". */
static const gd_ynode *pick_mesh(gd_yreader *r, const gd_ynode *root, const char *name, char *path,
                                 size_t psize)
{
    const gd_ynode *meshes = gd_ymap_get(root, "meshes");
    if (!meshes || meshes->kind != GD_Y_SEQ || meshes->n == 0) {
        gd_yfail(r, meshes ? meshes : root, "meshes",
                 "add `meshes: [{name: ..., geometry: {...}}]` (see docs/mesh-stiffness.md)",
                 "the file has no list of meshes");
        return NULL;
    }
    char names[256] = "";
    for (size_t i = 0; i < meshes->n; i++) {
        const gd_ynode *m = meshes->items[i];
        if (!m || m->kind != GD_Y_MAP) continue;
        const gd_ynode *nm = gd_ymap_get(m, "name");
        const char *mn = nm && nm->kind == GD_Y_SCALAR ? nm->text : "";
        size_t used = strlen(names);
        snprintf(names + used, sizeof names - used, "%s'%s'", used ? ", " : "", mn);
        int has_geom = gd_ymap_get(m, "geometry") != NULL;
        if ((name && !strcmp(name, mn)) || (!name && has_geom)) {
            gd_ypath_index(path, psize, "meshes", i);
            return m;
        }
    }
    char hint[320];
    if (name) {
        snprintf(hint, sizeof hint, "known meshes: %s", names);
        gd_yfail(r, meshes, "--mesh", hint, "no mesh named '%s'", name);
    } else {
        gd_yfail(r, meshes, "meshes",
                 "add a `geometry:` map to a mesh (see docs/mesh-stiffness.md)",
                 "no mesh has a geometry to compute its stiffness from");
    }
    return NULL;
}

static gd_status read_pair(gd_yreader *r, const gd_ynode *root, const char *mesh_name,
                           gd_gear_pair_geometry *geom, gd_tvms_options *tvms, char *name_out,
                           size_t size)
{
    if (!root || root->kind != GD_Y_MAP)
        return gd_yfail(r, root, "", "the file must be a map with a `meshes:` list",
                        "not a map of keys");
    char path[64] = "";
    const gd_ynode *mesh = pick_mesh(r, root, mesh_name, path, sizeof path);
    if (!mesh) return GD_EINPUT;
    if (tvms) gd_tvms_options_init(tvms);
    gd_status st = gd_gear_pair_read_any(r, root, mesh, path, geom, tvms);
    if (st || !name_out || !size) return st;
    const gd_ynode *nm = gd_ymap_get(mesh, "name");
    snprintf(name_out, size, "%s", nm && nm->kind == GD_Y_SCALAR ? nm->text : path);
    return GD_OK;
}

gd_status gd_gear_pair_load(const char *path, const char *mesh_name, const gd_load_options *opt,
                            gd_gear_pair_geometry *geom, gd_tvms_options *tvms, char *mesh_name_out,
                            size_t size, gd_error *err)
{
    if (mesh_name_out && size) mesh_name_out[0] = '\0';
    gd_ydoc *doc;
    gd_status st = gd_ydoc_load_file(path, &doc, err);
    if (st) return st;
    return gd_gear_pair_from_ydoc(doc, mesh_name, opt, geom, tvms, mesh_name_out, size, err);
}

gd_status gd_gear_pair_from_ydoc(gd_ydoc *doc, const char *mesh_name, const gd_load_options *opt,
                                 gd_gear_pair_geometry *geom, gd_tvms_options *tvms,
                                 char *mesh_name_out, size_t size, gd_error *err)
{
    if (mesh_name_out && size) mesh_name_out[0] = '\0';
    gd_yreader r = {doc->file, err};
    gd_status st = gd_ydoc_apply(doc, opt, err);
    if (!st) st = read_pair(&r, doc->root, mesh_name, geom, tvms, mesh_name_out, size);
    gd_ydoc_free(doc);
    return st;
}
