/* The model reader's shared helpers (model_file_impl.h): each item of a list section,
 * lists, names of nodes and materials, locations and the out-of-memory error. Every
 * section reader uses them; apart from the top level (model_parse.c, which calls the
 * section readers), so the readers and the top level do not use each other. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/builder.h"
#include "model/build_impl.h"
#include "model_file/model_file_impl.h"
#include "model_file/yaml_doc_impl.h"

gd_status gd_mp_oom(gd_mparser *p)
{
    return gd_error_set(p->r.err, GD_ENOMEM, p->r.file, 0, 0, "", "", "out of memory");
}

/* A list under a top-level key: NULL/absent gives n = 0. */
gd_status gd_mp_get_list(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                         const gd_ynode **list, int required)
{
    *list = gd_ymap_get(map, key);
    char q[200];
    gd_ypath_key(q, sizeof q, path, key);
    if (!*list) {
        if (required) {
            char hint[160];
            snprintf(hint, sizeof hint,
                     "add `%s:` with a list of entries (see docs/model-format.md)", key);
            return gd_yfail(&p->r, map, q, hint, "required list '%s' is missing", key);
        }
        return GD_OK;
    }
    return gd_yexpect(&p->r, *list, GD_Y_SEQ, q);
}

gd_status gd_mp_each(gd_mparser *p, const char *key, gd_mp_item_reader read)
{
    const gd_ynode *list;
    gd_status st = gd_mp_get_list(p, p->root, key, "", &list, 0);
    for (size_t i = 0; !st && list && i < list->n; i++) {
        char q[64];
        gd_ypath_index(q, sizeof q, key, i);
        st = read(p, list->items[i], q, i);
    }
    return st;
}

gd_status gd_mp_read_name(gd_mparser *p, const gd_ynode *map, const char *path, char *out,
                          const char *fallback, int required)
{
    const char *s = NULL;
    gd_status st =
        gd_yread_str(&p->r, map, "name", path, NULL, required ? GD_YREQ : 0, &s, NULL, NULL);
    if (st) return st;
    if (!s) s = fallback;
    if (strlen(s) >= GD_NAME_MAX) {
        char q[200];
        return gd_yfail(&p->r, gd_ymap_get(map, "name"), gd_ypath_key(q, sizeof q, path, "name"),
                        "use a shorter name", "name longer than %d characters", GD_NAME_MAX - 1);
    }
    snprintf(out, GD_NAME_MAX, "%s", s);
    return GD_OK;
}

gd_loc gd_mp_loc(const gd_ynode *n)
{
    gd_loc l = {n ? n->line : 0, n ? n->column : 0};
    return l;
}

gd_status gd_mp_node_name(gd_mparser *p, const gd_ynode *map, const char *key, const char *path,
                          int required, const char **out)
{
    *out = NULL;
    return gd_yread_str(&p->r, map, key, path, NULL, required ? GD_YREQ : 0, out, NULL, NULL);
}

gd_status gd_mp_material_name(gd_mparser *p, const gd_ynode *ref, const char *path,
                              const char **out)
{
    *out = NULL;
    if (!ref) return GD_OK;
    if (ref->kind != GD_Y_SCALAR)
        return gd_yfail(&p->r, ref, path, "name a material defined under `materials:`",
                        "expected a material name");
    *out = ref->text;
    return GD_OK;
}
