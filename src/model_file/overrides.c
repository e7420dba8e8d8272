/* Overrides "PATH=VALUE" applied to a loaded YAML document (overrides_impl.h): the
 * assignment is split, its path resolved (override_path.c), and each place it reaches
 * gets its own copy of the value, made of nodes that remember the override. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/overrides_impl.h"

static gd_status oom(gd_error *err, const char *origin)
{
    return gd_error_set(err, GD_ENOMEM, origin, 0, 0, "", "", "out of memory");
}

/* A copy of s[0, n) without the blanks around it; NULL if out of memory. */
static char *trimmed(const char *s, size_t n)
{
    while (n && isspace((unsigned char)*s)) {
        s++;
        n--;
    }
    while (n && isspace((unsigned char)s[n - 1]))
        n--;
    char *t = malloc(n + 1);
    if (!t) return NULL;
    memcpy(t, s, n);
    t[n] = '\0';
    return t;
}

/* A value written as a flow list or map ([...], {...}) or a quoted scalar is read as
 * YAML into *flow; anything else is a plain scalar taken as written ("3e8 N/m") and
 * *flow stays NULL. */
static gd_status read_flow(const char *value, const char *origin, gd_ydoc **flow, gd_error *err)
{
    *flow = NULL;
    if (!value[0] || !strchr("[{\"'", value[0])) return GD_OK;
    gd_status st = gd_ydoc_load_string(value, origin, flow, err);
    if (st && err) {
        char msg[sizeof err->message];
        snprintf(msg, sizeof msg, "in the value: %.480s", err->message);
        snprintf(err->message, sizeof err->message, "%s", msg);
        err->line = err->column = 0;
    }
    return st;
}

/* Puts a new copy of the value (flow, or the plain text value) at target t; key names
 * a new map entry. */
static gd_status put(const gd_ytarget *t, const char *key, const char *value, const gd_ydoc *flow,
                     const char *origin, gd_error *err)
{
    gd_ynode *v = flow && flow->root ? gd_ynode_copy(flow->root, origin)
                                     : gd_ynode_new_scalar(flow ? "" : value, origin);
    if (!v) return oom(err, origin);
    if (!t->add) {
        gd_ynode_free(t->parent->items[t->index]);
        t->parent->items[t->index] = v;
        return GD_OK;
    }
    gd_ynode *k = gd_ynode_new_scalar(key, origin);
    if (!k || gd_ynode_map_append(t->parent, k, v)) {
        gd_ynode_free(k);
        gd_ynode_free(v);
        return oom(err, origin);
    }
    return GD_OK;
}

/* "--set " + assignment, kept by doc for the nodes' origin. */
static const char *keep_origin(gd_ydoc *doc, const char *assignment)
{
    size_t n = strlen(assignment) + 7;
    char *s = malloc(n);
    if (!s) return NULL;
    snprintf(s, n, "--set %s", assignment);
    const char *kept = gd_ydoc_keep(doc, s);
    free(s);
    return kept;
}

static gd_status override_path(gd_ydoc *doc, const char *path, const char *value,
                               const char *origin, gd_error *err)
{
    gd_ytarget *t = NULL;
    size_t n = 0;
    gd_ydoc *flow = NULL;
    gd_status st = gd_ypath_resolve(doc->root, path, origin, &t, &n, err);
    if (!st) st = read_flow(value, origin, &flow, err);
    const char *dot = strrchr(path, '.');
    for (size_t i = 0; !st && i < n; i++)
        st = put(&t[i], dot ? dot + 1 : path, value, flow, origin, err);
    free(t);
    gd_ydoc_free(flow);
    return st;
}

gd_status gd_ydoc_override(gd_ydoc *doc, const char *assignment, gd_error *err)
{
    const char *origin = keep_origin(doc, assignment);
    if (!origin) return oom(err, "--set");
    const char *eq = strchr(assignment, '=');
    if (!eq)
        return gd_error_set(err, GD_EINPUT, origin, 0, 0, "",
                            "write PATH=VALUE, e.g. --set meshes.mesh.stiffness=3e8N/m",
                            "no '=' between the path and the value");
    char *path = trimmed(assignment, (size_t)(eq - assignment));
    char *value = trimmed(eq + 1, strlen(eq + 1));
    gd_status st = path && value ? override_path(doc, path, value, origin, err) : oom(err, origin);
    free(path);
    free(value);
    return st;
}

gd_status gd_ydoc_apply(gd_ydoc *doc, const gd_load_options *opt, gd_error *err)
{
    if (!opt || opt->nset == 0) return GD_OK;
    if (opt->nset < 0 || !opt->set)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "set", "give nset >= 0 assignments in set",
                            "bad load options: nset %d with %s list", opt->nset,
                            opt->set ? "a" : "no");
    for (int i = 0; i < opt->nset; i++) {
        if (!opt->set[i])
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "set", "give nset assignments in set",
                                "bad load options: override %d is NULL", i);
        gd_status st = gd_ydoc_override(doc, opt->set[i], err);
        if (st) return st;
    }
    return GD_OK;
}
