/* Shared by the model parser's files (model_parse.c: the machine; model_parse_dynamics.c:
 * what only time integration reads). */
#ifndef GD_MODEL_PARSE_INTERNAL_H
#define GD_MODEL_PARSE_INTERNAL_H
#include "geardyn/model.h"
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
/* `name` of map into out (fallback when absent and not required). */
gd_status gd_mp_read_name(gd_mparser *p, const gd_ynode *map, const char *path, char *out,
                          const char *fallback, int required);
gd_loc gd_mp_loc(const gd_ynode *n);
/* A node named by map[key]; *out = -1 when absent and not required. */
gd_status gd_mp_node_ref(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                         int required, int *out);

/* Time-integration keys of a mesh (tvms, damping map, transmission_error, backlash), a
 * bearing (sfd) and the top level (excitations, prescribed, cam_torques). */
gd_status gd_mp_mesh_dynamics(gd_mparser *p, const gd_ynode *mesh_map, const char *path, gd_mesh *g,
                              int *stiffness_from_table);
gd_status gd_mp_bearing_sfd(gd_mparser *p, const gd_ynode *bearing_map, const char *path,
                            gd_bearing *b);
gd_status gd_mp_dynamics(gd_mparser *p);

/* The model described by a loaded YAML document; name stands for the file in messages. */
gd_status gd_model_from_ydoc(const gd_ydoc *doc, const char *name, gd_model **out, gd_error *err);

#endif
