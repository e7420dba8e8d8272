/* Reading a gear pair's geometry and mesh-stiffness options from a mesh entry of a
 * model or stand-alone file (format: docs/mesh-stiffness.md). Only the mesh's
 * `geometry:` and `stiffness:` keys are read; its other keys belong to the model. */
#ifndef GD_MESH_GEOMETRY_READ_H
#define GD_MESH_GEOMETRY_READ_H
#include "geardyn/mesh_stiffness.h"
#include "model_file/yaml_doc_impl.h"

/* Reads mesh_map.geometry (required) into geom and, when mesh_map.stiffness is a map
 * {from: geometry, method, points, cycles, slices, body_compliance, harmonics}, the
 * options into opt (opt may be NULL; fields not given keep their values, so call
 * gd_tvms_options_init first). Validates the geometry (gd_gear_pair_derive) with errors
 * located in the file. path is the mesh's path, e.g. "meshes[0]". */
gd_status gd_gear_pair_read(gd_yreader *r, const gd_ynode *root, const gd_ynode *mesh_map,
                            const char *path, gd_gear_pair_geometry *geom, gd_tvms_options *opt);
/* gd_gear_pair_read that also accepts `internal: true` (an internal pair, read by the
 * mesh-stiffness command; a model's meshes refuse it). */
gd_status gd_gear_pair_read_any(gd_yreader *r, const gd_ynode *root, const gd_ynode *mesh_map,
                                const char *path, gd_gear_pair_geometry *geom,
                                gd_tvms_options *opt);

/* Locates an error from gd_gear_pair_derive / gd_tvms_compute (whose field is relative
 * to the geometry or stiffness map) at the matching node of mesh_map, prefixing path. */
void gd_gear_pair_error_locate(const char *file, const gd_ynode *mesh_map, const char *path,
                               gd_error *err);

#endif
