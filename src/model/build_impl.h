/* What the builder keeps while a model is under construction (builder.c) and the
 * finishing steps that use it: shaft discretisation (shaft_discretise.c), gear-train
 * speeds (speed_propagation.c) and meshes from geometry (mesh_from_geometry.c). */
#ifndef GD_MODEL_BUILD_IMPL_H
#define GD_MODEL_BUILD_IMPL_H
#include "geardyn/builder.h"

/* A reader that knows where fields were written (the YAML reader) can tell the
 * builder: locate puts err (already set) where the field path was written (a file line,
 * or the `--set` override that wrote it) and returns 1, or returns 0;
 * locate_geometry relocates an error of gd_gear_pair_derive / gd_tvms_compute (field
 * relative to the geometry or stiffness map) for the mesh at mesh_path and returns 1,
 * or returns 0 to let the builder prefix the field itself. */
typedef struct gd_field_locator {
    int (*locate)(void *ctx, const char *field, gd_error *err);
    int (*locate_geometry)(void *ctx, const char *mesh_path, gd_error *err);
    void *ctx;
} gd_field_locator;
void gd_model_set_locator(gd_model *m, const gd_field_locator *locator);

typedef struct gd_bstation {
    char *name, *path;
    double at;
    gd_loc loc;
} gd_bstation;

typedef struct gd_bshaft {
    char *path;
    char *material;          /* default of the sections, or NULL */
    char **section_material; /* nsections names (NULL: the default) */
    int nstations;
    gd_bstation *stations;
} gd_bshaft;

/* An item that names nodes (disks, bearings, springs, unbalances, loads, prescribed
 * motions, cams) */
typedef struct gd_bitem {
    char *path;
    char *node, *node2; /* node2: `to`, NULL for ground */
    char *material;     /* disk geometry */
    int from_geometry;
    double od, id, width;
} gd_bitem;

typedef struct gd_btable {
    int n;
    double *x, *y;
    gd_interp interp;
} gd_btable;

typedef struct gd_bmesh {
    char *path, *driver, *driven;
    int has_geometry;
    gd_gear_pair_geometry geometry;
    int from_geometry;
    gd_tvms_options options;
    int driver_rotation;
    gd_btable tvms, ste;
} gd_bmesh;

/* A planetary set's names until finish (builder_planetary.c) */
typedef struct gd_bplanetary {
    char *path;
    char *node[GD_PLANETARY_NMEMBERS];
} gd_bplanetary;

/* Idlers, synchronisers and gears until finish (builder_idler.c) */
typedef struct gd_bidler {
    char *path, *on;
} gd_bidler;
typedef struct gd_bsync {
    char *path, *node, *idlers[2], *engaged;
} gd_bsync;
typedef struct gd_bgear {
    char *path, *idler;
    gd_loc loc;
} gd_bgear;

typedef struct gd_model_build {
    gd_field_locator locator;
    char **material_path;
    gd_bshaft *shafts;
    gd_bitem *disks, *bearings, *springs, *unbalances, *excitations, *prescribed, *cams, *laws;
    gd_bmesh *meshes;
    gd_bplanetary *planetary;
    gd_bidler *idlers;
    gd_bsync *syncs;
    gd_bgear *gears;
    gd_loc gear_loc;          /* of the selection (gd_model_select_gear) */
    int shift_from, shift_to; /* gd_model_set_shift; 0: no shift */
    double shift_time;
    gd_loc shift_loc;
    gd_btable *excitation_tables, *prescribed_tables, *cam_tables;
    char *reference_shaft;
    int rotation;
    gd_loc reference_loc;
    long max_nodes; /* 0: GD_MAX_NODES_DEFAULT */
    gd_loc max_nodes_loc;
    int failed; /* gd_model_finish failed: the model can only be freed */
} gd_model_build;

void gd_model_build_free(gd_model *m);
void gd_build_free_shaft(gd_bshaft *bs, int nsections);

/* An input error at loc, or where the locator puts locate_path (may be NULL). */
gd_status gd_build_fail(const gd_model *m, gd_error *err, gd_loc loc, const char *locate_path,
                        const char *field, const char *hint, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;
gd_status gd_build_oom(const gd_model *m, gd_error *err);
/* "path.key" into buf */
const char *gd_build_path(char *buf, size_t size, const char *path, const char *key);
char *gd_build_strdup(const char *s); /* NULL for NULL */
/* GD_OK while the model can be added to */
gd_status gd_build_open(const gd_model *m, gd_error *err);
/* Grows the array at *array (n items of sz bytes) by one zeroed item; 0 on failure. */
int gd_build_grow(void *array, int n, size_t sz);
/* Checks name (fallback when NULL) and copies it to out (may be NULL). */
gd_status gd_build_name(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                        const char *name, const char *fallback, char out[GD_NAME_MAX]);
/* v > 0 (allow_zero: v >= 0) for path.key */
gd_status gd_build_positive(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                            const char *key, double v, int allow_zero);
/* An item's path: given, or "<kind>[<i>]". */
const char *gd_build_item_path(char *buf, size_t size, const char *given, const char *kind, int i);
/* Copies path and names into it; 0 when out of memory. */
int gd_build_item_init(gd_bitem *it, const char *path, const char *node, const char *node2,
                       const char *material);
/* The node named name, for the field path.key; an error listing the named nodes. */
gd_status gd_build_node_ref(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                            const char *key, const char *name, int *out);
/* The material named name for field (located at locate_path). */
gd_status gd_build_material_ref(const gd_model *m, gd_error *err, gd_loc loc,
                                const char *locate_path, const char *field, const char *name,
                                int *out);
/* Shafts, bearings, springs and meshes share one namespace: the item index of kind
 * ("shaft", "bearing", "spring", "mesh") must not repeat an earlier name. */
gd_status gd_build_component_name(const gd_model *m, gd_error *err, const char *kind, int index,
                                  gd_loc loc, const char *path);

/* Copies table data (n = 0: none); 0 when out of memory. */
int gd_build_copy_table(gd_btable *dst, const gd_table_spec *src);
/* gd_table_new of t, its errors located at the table's path. */
gd_status gd_build_make_table(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                              const gd_btable *t, double period, gd_table **out);

/* finishing steps, in this order */
gd_status gd_build_discretise_shafts(gd_model *m, gd_error *err); /* shaft_discretise.c */
gd_status gd_build_resolve_disks(gd_model *m, gd_error *err);     /* builder_items.c */
gd_status gd_build_resolve_supports(gd_model *m, gd_error *err);  /* bearings, springs */
gd_status gd_build_resolve_meshes(gd_model *m, gd_error *err);    /* builder_mesh.c */
/* mesh k's gear size, angles and TVMS from its geometry (mesh_from_geometry.c) */
gd_status gd_build_mesh_from_geometry(gd_model *m, int k, gd_error *err);
gd_status gd_build_propagate_speeds(gd_model *m, gd_error *err); /* speed_propagation.c */
/* unbalances, loads, prescribed motions, cams (builder_dynamics.c) */
gd_status gd_build_resolve_dynamics(gd_model *m, gd_error *err);
gd_status gd_build_resolve_laws(gd_model *m, gd_error *err);      /* builder_laws.c */
gd_status gd_build_resolve_planetary(gd_model *m, gd_error *err); /* builder_planetary.c */
/* A set's tooth geometry into the spec (base radii, carrier radius, operating pressure
 * angles, mean stiffness when 0, the sun-ring phase when not given) and the set (TVMS
 * results and tables, contact ratios); planetary_mesh_geometry.c. On error g may hold
 * results the caller frees. */
gd_status gd_build_planetary_geometry(const gd_model *m, gd_planetary_spec *s, const char *path,
                                      gd_planetary *g, gd_error *err);
/* builder_idler.c: the selection checked and the engaged locks added as springs (by name,
 * before the model is resolved); the idlers' and synchronisers' nodes resolved (after the
 * supports). Their builder copies are freed with the rest (builder_state.c). */
gd_status gd_build_engage_synchronisers(gd_model *m, gd_error *err);
gd_status gd_build_resolve_idlers(gd_model *m, gd_error *err);

#endif
