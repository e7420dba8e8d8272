/* Overrides: assignments "PATH=VALUE" applied to a loaded YAML document before a model
 * (or a gear pair) is read from it, so the reader's own checks apply to the new values
 * (docs/model-format.md, "Overrides (--set)"). */
#ifndef GD_OVERRIDES_IMPL_H
#define GD_OVERRIDES_IMPL_H
#include "geardyn/model_file.h"
#include "model_file/yaml_doc_impl.h"

/* Applies one assignment to doc. Every node it writes has the origin
 * "--set ASSIGNMENT", kept by doc, so later errors at those nodes name the override.
 * A path that matches nothing, or a malformed assignment, is GD_EINPUT located at the
 * override: the field is the path up to the segment that failed, the hint lists what is
 * there. */
gd_status gd_ydoc_override(gd_ydoc *doc, const char *assignment, gd_error *err);

/* Applies opt's assignments in order (opt may be NULL: nothing to do). */
gd_status gd_ydoc_apply(gd_ydoc *doc, const gd_load_options *opt, gd_error *err);

/* ---- override_path.c: the places a path reaches ---- */

/* Value `index` of parent (a map's value or a list's item) or, when add is set, a new
 * entry of the map parent whose key is the path's last segment. */
typedef struct gd_ytarget {
    gd_ynode *parent;
    size_t index;
    int add;
} gd_ytarget;

/* Every place path reaches from root: segments separated by '.', each a map key, a list
 * index or the `name:` of a list item, or `*` for all; a missing last key of a map is
 * added. *targets (malloc'd, *n of them) is set only on success. Errors name origin. */
gd_status gd_ypath_resolve(gd_ynode *root, const char *path, const char *origin,
                           gd_ytarget **targets, size_t *n, gd_error *err);

#endif
