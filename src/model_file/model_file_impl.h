/* Shared by the model reader's files. The reader checks the YAML's shape (kinds of
 * nodes, unknown and missing keys, units, keys that exclude each other), fills the
 * builder's specs (geardyn/builder.h) and adds them, one item at a time; the builder
 * checks the values and names and finishes the model. Builder errors are located in
 * the file through a locator that resolves their field paths in the document.
 *   model_parse.c: the machinery, top level and globals;
 *   shafts_read.c: materials and shafts; supports_read.c: disks, bearings, springs,
 *   unbalances; meshes_read.c: gear meshes; model_parse_dynamics.c: what only time
 *   integration reads; tables_read.c: tables and lists of quantities. */
#ifndef GD_MODEL_PARSE_INTERNAL_H
#define GD_MODEL_PARSE_INTERNAL_H
#include "geardyn/builder.h"
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "model_file/yaml_doc_impl.h"

typedef struct gd_mparser {
    gd_yreader r;
    const gd_ynode *root;
    gd_model *m;
} gd_mparser;

gd_status gd_mp_oom(gd_mparser *p);
/* A list under key; absent gives *list = NULL (an error if required). */
gd_status gd_mp_get_list(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                         const gd_ynode **list, int required);
/* Reads one item of a top-level list: its node, its path ("bearings[2]") and index. */
typedef gd_status (*gd_mp_item_reader)(gd_mparser *p, const gd_ynode *item, const char *path,
                                       size_t index);
/* Calls read on every item of the optional top-level list `key`, stopping at the first
 * error. */
gd_status gd_mp_each(gd_mparser *p, const char *key, gd_mp_item_reader read);
/* `name` of map into out (fallback when absent and not required). */
gd_status gd_mp_read_name(gd_mparser *p, const gd_ynode *map, const char *path, char *out,
                          const char *fallback, int required);
gd_loc gd_mp_loc(const gd_ynode *n);
/* The node name map[key] (*out = NULL when absent and not required); the builder
 * resolves it. */
gd_status gd_mp_node_name(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                          int required, const char **out);
/* A material name (a scalar) at ref, or NULL when ref is NULL. */
gd_status gd_mp_material_name(gd_mparser *p, const gd_ynode *ref, const char *path,
                              const char **out);
/* The node at a field path ("shafts[1].sections[0].material") under root, or NULL. */
const gd_ynode *gd_mp_find(const gd_ynode *root, const char *field);

/* Sections of the document */
gd_status gd_mp_materials(gd_mparser *p);
gd_status gd_mp_shafts(gd_mparser *p);
gd_status gd_mp_disks(gd_mparser *p);
gd_status gd_mp_bearings(gd_mparser *p);
gd_status gd_mp_springs(gd_mparser *p);
gd_status gd_mp_meshes(gd_mparser *p);
gd_status gd_mp_unbalances(gd_mparser *p);
gd_status gd_mp_planetary(gd_mparser *p); /* planetary_read.c */
gd_status gd_mp_idlers(gd_mparser *p);    /* idlers_read.c: idlers, synchronisers, gears */

/* A list of n >= 1 quantities under key (tables_read.c; free *out). */
gd_status gd_mp_read_qty_list(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                              gd_qty qty, double **out, int *n);
/* A table {xkey: [...], ykey: [...], interpolation} (periodic with period > 0) read
 * into *out (gd_table_free it). */
gd_status gd_mp_read_table(gd_mparser *p, const gd_ynode *map, const char *path, const char *xkey,
                           gd_qty xq, const char *ykey, gd_qty yq, double period,
                           gd_interp def_interp, gd_table **out);
/* The spec's view of a table read by gd_mp_read_table (NULL: none). */
gd_table_spec gd_mp_table_spec(const gd_table *t);

/* Time-integration keys of a mesh (tvms, damping map, transmission_error, backlash)
 * into s (the tables into *tvms and *ste, to free after the add; teeth: the driver's,
 * 0 when unknown), a bearing (sfd) and the top level (excitations, prescribed,
 * cam_torques). */
gd_status gd_mp_mesh_dynamics(gd_mparser *p, const gd_ynode *mesh_map, const char *path, int teeth,
                              gd_mesh_spec *s, gd_table **tvms, gd_table **ste);
gd_status gd_mp_bearing_sfd(gd_mparser *p, const gd_ynode *bearing_map, const char *path,
                            gd_bearing_spec *b);
gd_status gd_mp_dynamics(gd_mparser *p);
/* The `laws:` list (laws_read.c). */
gd_status gd_mp_laws(gd_mparser *p);

/* The model described by a loaded YAML document; name stands for the file in messages. */
gd_status gd_model_from_ydoc(const gd_ydoc *doc, const char *name, gd_model **out, gd_error *err);

/* gd_gear_pair_load on a loaded document, which it takes (frees, whatever happens). */
gd_status gd_gear_pair_from_ydoc(gd_ydoc *doc, const char *mesh_name, const gd_load_options *opt,
                                 gd_gear_pair_geometry *geom, gd_tvms_options *tvms,
                                 char *mesh_name_out, size_t size, gd_error *err);

#endif
