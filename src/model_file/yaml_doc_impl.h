/* A YAML document as a tree of scalars, sequences and maps that remember their
 * line and column, so every later check can point at the offending text. */
#ifndef GD_YAML_DOC_H
#define GD_YAML_DOC_H
#include <stddef.h>

#include "geardyn/error.h"
#include "geardyn/units.h"

typedef enum gd_ykind { GD_Y_SCALAR, GD_Y_SEQ, GD_Y_MAP } gd_ykind;

typedef struct gd_ynode gd_ynode;
struct gd_ynode {
    gd_ykind kind;
    int line, column; /* 1-based */
    char *text;       /* scalar text */
    int quoted;       /* scalar was quoted */
    size_t n, cap;    /* items in a sequence, entries in a map */
    gd_ynode **items; /* sequence items, or map values */
    gd_ynode **keys;  /* map keys (scalars) */
};

/* A node an override wrote (overrides_impl.h) has no place in the file: its line is 0
 * and its column GD_YCOL_OVERRIDE, and gd_ynode_origin gives the override,
 * "--set PATH=VALUE", which errors at the node name instead of the file (gd_ylocate). */
#define GD_YCOL_OVERRIDE (-1)

typedef struct gd_ydoc {
    gd_ynode *root; /* NULL for an empty document */
    char *file;
    char **origins; /* the texts nodes' origin point to (overrides.c), owned */
    size_t norigins;
} gd_ydoc;

gd_status gd_ydoc_load_file(const char *path, gd_ydoc **out, gd_error *err);
/* name is used in error messages in place of a file name. */
gd_status gd_ydoc_load_string(const char *text, const char *name, gd_ydoc **out, gd_error *err);
void gd_ydoc_free(gd_ydoc *doc);
/* A deep copy with the same lines and columns, for many changed copies of one parsed
 * document (gd_model_source). Override nodes keep pointing to doc's origins, so a doc
 * with overrides must outlive its clones. NULL if out of memory. */
gd_ydoc *gd_ydoc_clone(const gd_ydoc *doc);

/* ---- building and changing nodes (overrides.c) ---- */

/* The override that wrote n, or NULL for a node read from the file. */
const char *gd_ynode_origin(const gd_ynode *n);
/* Nodes written by the override origin (a string that must outlive them, e.g. kept by
 * gd_ydoc_keep): a scalar with a copy of text, or a deep copy of n. NULL if out of
 * memory. */
gd_ynode *gd_ynode_new_scalar(const char *text, const char *origin);
gd_ynode *gd_ynode_copy(const gd_ynode *n, const char *origin);
/* Frees n and everything under it. */
void gd_ynode_free(gd_ynode *n);
/* Appends key: value to a map (which then owns both); 0 ok, 1 out of memory. */
int gd_ynode_map_append(gd_ynode *map, gd_ynode *key, gd_ynode *value);
/* Keeps a copy of text in doc for nodes' origin to point to; NULL if out of memory. */
const char *gd_ydoc_keep(gd_ydoc *doc, const char *text);

/* ---- reading typed values with located errors ---- */

typedef struct gd_yreader {
    const char *file;
    gd_error *err;
} gd_yreader;

enum {
    GD_YREQ = 1 << 0,    /* the key must be present */
    GD_YPOS = 1 << 1,    /* value > 0 */
    GD_YNONNEG = 1 << 2, /* value >= 0 */
};

const gd_ynode *gd_ymap_get(const gd_ynode *map, const char *key);
const char *gd_ykind_name(gd_ykind kind);

/* Locates err at node n of file: its line and column, or, for a node an override
 * wrote, the override ("--set PATH=VALUE") in place of the file with line 0. A NULL
 * file keeps err->file. */
void gd_ylocate(gd_error *err, const char *file, const gd_ynode *n);

/* Errors located at node n (or the document start when n is NULL), see gd_ylocate. */
gd_status gd_yfail(gd_yreader *r, const gd_ynode *n, const char *path, const char *hint,
                   const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

gd_status gd_yexpect(gd_yreader *r, const gd_ynode *n, gd_ykind kind, const char *path);
/* Fails on any key of map not in the NULL-terminated list, suggesting the nearest. */
gd_status gd_ycheck_keys(gd_yreader *r, const gd_ynode *map, const char *path,
                         const char *const *allowed);

/* Each reader leaves *out untouched when the key is absent and not required;
 * *present (may be NULL) says whether it was there. path is the map's path. */
gd_status gd_yread_qty(gd_yreader *r, const gd_ynode *map, const char *key, const char *path,
                       gd_qty qty, int flags, double *out, int *present);
gd_status gd_yread_node_qty(gd_yreader *r, const gd_ynode *n, const char *path, gd_qty qty,
                            int flags, double *out);
gd_status gd_yread_int(gd_yreader *r, const gd_ynode *map, const char *key, const char *path,
                       long lo, long hi, int flags, long *out, int *present);
gd_status gd_yread_bool(gd_yreader *r, const gd_ynode *map, const char *key, const char *path,
                        int flags, int *out, int *present);
/* A string; if choices (NULL-terminated) is given, the value must be one of them and
 * *choice_index is set. out may be NULL when only the index is wanted. */
gd_status gd_yread_str(gd_yreader *r, const gd_ynode *map, const char *key, const char *path,
                       const char *const *choices, int flags, const char **out, int *choice_index,
                       int *present);

/* Joins "path.key" or "path[i]" into buf. */
const char *gd_ypath_key(char *buf, size_t size, const char *path, const char *key);
const char *gd_ypath_index(char *buf, size_t size, const char *path, size_t index);

#endif
