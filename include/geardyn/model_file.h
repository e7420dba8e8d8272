/* Model files (docs/model-format.md): loading a model with overrides applied to the
 * file's values before validation (`--set PATH=VALUE`, section "Overrides (--set)"),
 * and reading a gear pair's geometry from a mesh entry of a file
 * (docs/mesh-stiffness.md).
 *
 * gd_gear_pair_load lives here rather than in mesh_stiffness.h because it is file
 * reading: YAML, overrides, errors located in the file. The mesh-stiffness module
 * computes from a gd_gear_pair_geometry and knows nothing about files.
 *
 * Ownership and threads: every function here is reentrant: no global state, each call
 * reads its own file into its own document, which is freed before returning. The
 * options and their strings are only read, during the call. The caller owns the model
 * (free it with gd_model_free) and the structs it passes in. */
#ifndef GEARDYN_MODEL_FILE_H
#define GEARDYN_MODEL_FILE_H
#include "geardyn/export.h"
#include <stddef.h>

#include "geardyn/error.h"
#include "geardyn/mesh_stiffness.h"
#include "geardyn/model.h"

typedef struct gd_load_options {
    int nset;               /* number of overrides */
    const char *const *set; /* nset assignments "PATH=VALUE", applied in this order */
} gd_load_options;

/* No overrides. */
GD_API void gd_load_options_init(gd_load_options *opt);

/* As gd_model_load / gd_model_load_string (model.h), with opt's overrides applied to the
 * document first (opt may be NULL: none). The model's own validation then checks the new
 * values; an error at a value an override wrote names the override: err->file is
 * "--set PATH=VALUE" and err->line 0. A path that matches nothing, or a malformed
 * assignment, is GD_EINPUT with the same file, the field the part of the path that
 * failed, and the keys or names available there as the hint. */
GD_API gd_status gd_model_load_opts(const char *path, const gd_load_options *opt, gd_model **out,
                                    gd_error *err);
GD_API gd_status gd_model_load_string_opts(const char *yaml, const char *name,
                                           const gd_load_options *opt, gd_model **out,
                                           gd_error *err);

/* Reads the gear pair of one mesh entry of the file at path (a model file or a
 * stand-alone file with a `meshes:` list), after applying opt's overrides (opt may be
 * NULL). mesh_name picks the mesh by name; NULL: the first mesh with a `geometry:` map.
 * geom receives the validated geometry. tvms (may be NULL) is reset to the defaults
 * (gd_tvms_options_init) and then takes the options of the mesh's
 * `stiffness: {from: geometry, ...}` map. mesh_name_out (may be NULL) receives the
 * mesh's name, or its path "meshes[i]" when it has none, truncated to size. Errors are
 * located in the file; a mesh_name that names no mesh has the field "--mesh" and the
 * known names as the hint. */
GD_API gd_status gd_gear_pair_load(const char *path, const char *mesh_name,
                                   const gd_load_options *opt, gd_gear_pair_geometry *geom,
                                   gd_tvms_options *tvms, char *mesh_name_out, size_t size,
                                   gd_error *err);

/* A model file read and parsed once, then loaded many times with different overrides
 * (parameter studies, geardyn/study.h): each load works on its own copy of the parsed
 * document, so the file is not read again and the source is never changed. Threads:
 * once made, a source is only read; many threads may load from one source at once.
 * Free it with gd_model_source_free after the last load. */
typedef struct gd_model_source gd_model_source;

GD_API gd_status gd_model_source_load(const char *path, gd_model_source **out, gd_error *err);
/* As gd_model_load_opts on the source's file. */
GD_API gd_status gd_model_source_model(const gd_model_source *src, const gd_load_options *opt,
                                       gd_model **out, gd_error *err);
/* As gd_gear_pair_load on the source's file. */
GD_API gd_status gd_model_source_gear_pair(const gd_model_source *src, const char *mesh_name,
                                           const gd_load_options *opt, gd_gear_pair_geometry *geom,
                                           gd_tvms_options *tvms, char *mesh_name_out, size_t size,
                                           gd_error *err);
/* Whether the override path (PATH of "PATH=VALUE") reaches something in the file:
 * GD_OK, with *adds set when it only names a missing last key that an override would
 * add; or GD_EINPUT naming the part of the path that failed, with what is there as the
 * hint (err->file is "--set PATH"). */
GD_API gd_status gd_model_source_check_path(const gd_model_source *src, const char *path, int *adds,
                                            gd_error *err);
/* The number at path (a --set path; the first place it reaches) after opt's overrides
 * (opt may be NULL), in SI when written with units: the starting value of a parameter
 * to update (geardyn/correlate.h). GD_EINPUT when the path reaches nothing, a list or
 * a map, or text that is not a number (err->file is "--update PATH"). */
GD_API gd_status gd_model_source_value(const gd_model_source *src, const gd_load_options *opt,
                                       const char *path, double *value, gd_error *err);
/* The file the source was read from. */
GD_API const char *gd_model_source_file(const gd_model_source *src);
GD_API void gd_model_source_free(gd_model_source *src);

#endif
