#include "model_file/yaml_doc_impl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <yaml.h>

/* libyaml's problem, and where the unfinished construct began when it knows. */
static gd_status syntax_error(yaml_parser_t *p, const char *file, gd_error *err)
{
    const char *problem = p->problem ? p->problem : "unknown problem";
    if (p->error == YAML_READER_ERROR && !strcmp(problem, "input error"))
        return gd_error_set(err, GD_EIO, file, 0, 0, "", "check the path and permissions",
                            "cannot read file");
    char ctx[160] = "";
    if (p->context && p->context_mark.line < p->problem_mark.line)
        snprintf(ctx, sizeof ctx, " (%s on line %d)", p->context, (int)p->context_mark.line + 1);
    /* libyaml's words for a tab where indentation is expected */
    const char *hint = strstr(problem, "cannot start any token")
                           ? "YAML indents with spaces, never tabs; or remove a stray character "
                             "(@, `) that cannot start a value"
                           : "check indentation, colons, quotes and brackets near this point";
    return gd_error_set(err, GD_EINPUT, file, (int)p->problem_mark.line + 1,
                        (int)p->problem_mark.column + 1, "", hint, "YAML syntax error: %s%s",
                        problem, ctx);
}

static gd_ynode *node_new(gd_ykind kind, const yaml_mark_t *mark)
{
    gd_ynode *n = calloc(1, sizeof *n);
    if (!n) return NULL;
    n->kind = kind;
    n->line = (int)mark->line + 1;
    n->column = (int)mark->column + 1;
    return n;
}

static void node_free(gd_ynode *n)
{
    if (!n) return;
    for (size_t i = 0; i < n->n; i++) {
        node_free(n->items[i]);
        if (n->keys) node_free(n->keys[i]);
    }
    free(n->items);
    free(n->keys);
    free(n->text);
    free(n);
}

static int node_push(gd_ynode *parent, gd_ynode *key, gd_ynode *value)
{
    if (parent->n == parent->cap) {
        size_t cap = parent->cap ? 2 * parent->cap : 4;
        gd_ynode **items = realloc(parent->items, cap * sizeof *items);
        if (!items) return 1;
        parent->items = items;
        if (parent->kind == GD_Y_MAP) {
            gd_ynode **keys = realloc(parent->keys, cap * sizeof *keys);
            if (!keys) return 1;
            parent->keys = keys;
        }
        parent->cap = cap;
    }
    if (parent->kind == GD_Y_MAP) parent->keys[parent->n] = key;
    parent->items[parent->n++] = value;
    return 0;
}

/* Builds the tree recursively from the parser's events. The event that starts the
 * node has already been read into *ev. */
static gd_status build(yaml_parser_t *p, yaml_event_t *ev, const char *file, gd_ynode **out,
                       gd_error *err, int depth)
{
    *out = NULL;
    if (depth > 64)
        return gd_error_set(err, GD_EINPUT, file, (int)ev->start_mark.line + 1,
                            (int)ev->start_mark.column + 1, "", "flatten the document",
                            "nesting deeper than 64 levels");
    switch (ev->type) {
    case YAML_SCALAR_EVENT: {
        gd_ynode *n = node_new(GD_Y_SCALAR, &ev->start_mark);
        if (!n) return gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        n->text = malloc(ev->data.scalar.length + 1);
        if (!n->text) {
            node_free(n);
            return gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        }
        memcpy(n->text, ev->data.scalar.value, ev->data.scalar.length);
        n->text[ev->data.scalar.length] = '\0';
        n->quoted = ev->data.scalar.style != YAML_PLAIN_SCALAR_STYLE;
        *out = n;
        return GD_OK;
    }
    case YAML_ALIAS_EVENT:
        return gd_error_set(err, GD_EINPUT, file, (int)ev->start_mark.line + 1,
                            (int)ev->start_mark.column + 1, "", "write the values out in full",
                            "YAML aliases (*name) are not supported in model files");
    case YAML_SEQUENCE_START_EVENT:
    case YAML_MAPPING_START_EVENT: {
        int is_map = ev->type == YAML_MAPPING_START_EVENT;
        gd_ynode *n = node_new(is_map ? GD_Y_MAP : GD_Y_SEQ, &ev->start_mark);
        if (!n) return gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
        for (;;) {
            yaml_event_t e;
            if (!yaml_parser_parse(p, &e)) {
                node_free(n);
                return syntax_error(p, file, err);
            }
            if (e.type == YAML_SEQUENCE_END_EVENT || e.type == YAML_MAPPING_END_EVENT) {
                yaml_event_delete(&e);
                break;
            }
            gd_ynode *key = NULL, *value = NULL;
            gd_status st = build(p, &e, file, is_map ? &key : &value, err, depth + 1);
            yaml_event_delete(&e);
            if (st) {
                node_free(n);
                return st;
            }
            if (is_map) {
                if (key->kind != GD_Y_SCALAR) {
                    st = gd_error_set(err, GD_EINPUT, file, key->line, key->column, "",
                                      "use plain words as keys", "a map key must be a scalar");
                    node_free(key);
                    node_free(n);
                    return st;
                }
                for (size_t i = 0; i < n->n; i++) {
                    if (strcmp(n->keys[i]->text, key->text) == 0) {
                        st = gd_error_set(err, GD_EINPUT, file, key->line, key->column, key->text,
                                          "remove one of the two entries",
                                          "duplicate key (first given on line %d)",
                                          n->keys[i]->line);
                        node_free(key);
                        node_free(n);
                        return st;
                    }
                }
                yaml_event_t e2;
                if (!yaml_parser_parse(p, &e2)) {
                    node_free(key);
                    node_free(n);
                    return syntax_error(p, file, err);
                }
                st = build(p, &e2, file, &value, err, depth + 1);
                yaml_event_delete(&e2);
                if (st) {
                    node_free(key);
                    node_free(n);
                    return st;
                }
            }
            if (node_push(n, key, value)) {
                node_free(key);
                node_free(value);
                node_free(n);
                return gd_error_set(err, GD_ENOMEM, file, 0, 0, "", "", "out of memory");
            }
        }
        *out = n;
        return GD_OK;
    }
    default:
        return gd_error_set(err, GD_EINPUT, file, (int)ev->start_mark.line + 1,
                            (int)ev->start_mark.column + 1, "", "", "unexpected YAML event");
    }
}

static gd_status load(yaml_parser_t *p, const char *name, gd_ydoc **out, gd_error *err)
{
    *out = NULL;
    gd_ydoc *doc = calloc(1, sizeof *doc);
    if (!doc) return gd_error_set(err, GD_ENOMEM, name, 0, 0, "", "", "out of memory");
    doc->file = strdup(name ? name : "");
    gd_status st = GD_OK;
    int docs = 0;
    for (;;) {
        yaml_event_t ev;
        if (!yaml_parser_parse(p, &ev)) {
            st = syntax_error(p, name, err);
            break;
        }
        yaml_event_type_t type = ev.type;
        if (type == YAML_DOCUMENT_START_EVENT && ++docs > 1) {
            st = gd_error_set(err, GD_EINPUT, name, (int)ev.start_mark.line + 1, 1, "",
                              "put one model in each file", "more than one YAML document");
        } else if (type == YAML_SCALAR_EVENT || type == YAML_SEQUENCE_START_EVENT ||
                   type == YAML_MAPPING_START_EVENT || type == YAML_ALIAS_EVENT) {
            st = build(p, &ev, name, &doc->root, err, 0);
        }
        yaml_event_delete(&ev);
        if (st || type == YAML_STREAM_END_EVENT) break;
    }
    if (st) {
        gd_ydoc_free(doc);
        return st;
    }
    *out = doc;
    return GD_OK;
}

gd_status gd_ydoc_load_file(const char *path, gd_ydoc **out, gd_error *err)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return gd_error_set(err, GD_EIO, path, 0, 0, "", "check the path and permissions",
                            "cannot open file: %s", strerror(errno));
    /* fopen opens a folder too; libyaml would then report a bare "input error" */
    struct stat sb;
    if (fstat(fileno(f), &sb) == 0 && !S_ISREG(sb.st_mode) && !S_ISFIFO(sb.st_mode) &&
        !S_ISCHR(sb.st_mode)) {
        fclose(f);
        return gd_error_set(err, GD_EIO, path, 0, 0, "", "give the path of a model file (.yaml)",
                            S_ISDIR(sb.st_mode) ? "is a folder, not a model file"
                                                : "is not a regular file");
    }
    yaml_parser_t p;
    if (!yaml_parser_initialize(&p)) {
        fclose(f);
        return gd_error_set(err, GD_ENOMEM, path, 0, 0, "", "", "out of memory");
    }
    yaml_parser_set_input_file(&p, f);
    gd_status st = load(&p, path, out, err);
    yaml_parser_delete(&p);
    fclose(f);
    return st;
}

gd_status gd_ydoc_load_string(const char *text, const char *name, gd_ydoc **out, gd_error *err)
{
    *out = NULL;
    yaml_parser_t p;
    if (!yaml_parser_initialize(&p))
        return gd_error_set(err, GD_ENOMEM, name, 0, 0, "", "", "out of memory");
    yaml_parser_set_input_string(&p, (const unsigned char *)text, strlen(text));
    gd_status st = load(&p, name, out, err);
    yaml_parser_delete(&p);
    return st;
}

void gd_ydoc_free(gd_ydoc *doc)
{
    if (!doc) return;
    node_free(doc->root);
    for (size_t i = 0; i < doc->norigins; i++)
        free(doc->origins[i]);
    free(doc->origins);
    free(doc->file);
    free(doc);
}

void gd_ynode_free(gd_ynode *n)
{
    node_free(n);
}

/* A node an override wrote: the node first (a gd_yover * is a gd_ynode *), then the
 * override. gd_ynode_free frees it like any node. */
typedef struct gd_yover {
    gd_ynode node;
    const char *origin;
} gd_yover;

const char *gd_ynode_origin(const gd_ynode *n)
{
    if (!n || n->line != 0 || n->column != GD_YCOL_OVERRIDE) return NULL;
    return ((const gd_yover *)(const void *)n)->origin;
}

static gd_ynode *over_new(gd_ykind kind, const char *text, const char *origin)
{
    gd_yover *o = calloc(1, sizeof *o);
    if (!o) return NULL;
    o->node.kind = kind;
    o->node.column = GD_YCOL_OVERRIDE;
    o->origin = origin;
    if (text && !(o->node.text = strdup(text))) {
        free(o);
        return NULL;
    }
    return &o->node;
}

gd_ynode *gd_ynode_new_scalar(const char *text, const char *origin)
{
    return over_new(GD_Y_SCALAR, text, origin);
}

/* A deep copy of n. With an origin, every node is an override node of that origin;
 * without, each keeps its own place: its line and column, or its override. */
static gd_ynode *copy_tree(const gd_ynode *n, const char *origin)
{
    const char *o = origin ? origin : gd_ynode_origin(n);
    gd_ynode *c = o ? over_new(n->kind, n->text, o) : calloc(1, sizeof *c);
    if (!c) return NULL;
    if (!o) {
        *c = (gd_ynode){.kind = n->kind, .line = n->line, .column = n->column};
        if (n->text && !(c->text = strdup(n->text))) {
            free(c);
            return NULL;
        }
    }
    c->quoted = n->quoted;
    for (size_t i = 0; i < n->n; i++) {
        gd_ynode *k = n->kind == GD_Y_MAP ? copy_tree(n->keys[i], origin) : NULL;
        gd_ynode *v = copy_tree(n->items[i], origin);
        if (!v || (n->kind == GD_Y_MAP && !k) || node_push(c, k, v)) {
            node_free(k);
            node_free(v);
            node_free(c);
            return NULL;
        }
    }
    return c;
}

gd_ynode *gd_ynode_copy(const gd_ynode *n, const char *origin)
{
    return copy_tree(n, origin);
}

gd_ydoc *gd_ydoc_clone(const gd_ydoc *doc)
{
    gd_ydoc *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->file = strdup(doc->file ? doc->file : "");
    c->root = doc->root ? copy_tree(doc->root, NULL) : NULL;
    if (!c->file || (doc->root && !c->root)) {
        gd_ydoc_free(c);
        return NULL;
    }
    return c;
}

int gd_ynode_map_append(gd_ynode *map, gd_ynode *key, gd_ynode *value)
{
    return node_push(map, key, value);
}

const char *gd_ydoc_keep(gd_ydoc *doc, const char *text)
{
    char *copy = strdup(text);
    char **more = copy ? realloc(doc->origins, (doc->norigins + 1) * sizeof *more) : NULL;
    if (!more) {
        free(copy);
        return NULL;
    }
    doc->origins = more;
    doc->origins[doc->norigins++] = copy;
    return copy;
}
