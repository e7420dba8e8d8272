/* A model and its system loaded from an example file or a YAML string, shared by the
 * analysis tests. Header-only (static inline): each test program is its own executable. */
#ifndef GD_TEST_MODEL_SUPPORT_H
#define GD_TEST_MODEL_SUPPORT_H
#include <stdio.h>
#include <string.h>

#include "geardyn/system.h"

typedef struct fx {
    gd_model *m;
    gd_system *s;
} fx;

/* Loads the file at path (relative to the source tree), or yaml when path is NULL. */
static inline int load(fx *f, const char *path, const char *yaml)
{
    gd_error err;
    memset(f, 0, sizeof *f);
    gd_status st = path ? gd_model_load(path, &f->m, &err)
                        : gd_model_load_string(yaml, "inline.yaml", &f->m, &err);
    if (!st) st = gd_system_build(f->m, &f->s, &err);
    if (st) fprintf(stderr, "  %s\n", err.message);
    return st == GD_OK;
}

static inline void fx_free(fx *f)
{
    gd_system_free(f->s);
    gd_model_free(f->m);
}

/* Active DOF index of node.d. */
static inline int dof(const fx *f, const char *node, gd_dof d)
{
    return gd_system_dof(f->s, gd_model_find_node(f->m, node), d);
}

#endif
