/* Where an override's path leads in a YAML document: every value it matches (through
 * `*` wildcards, list indices and item names), or the first place it stops, with what
 * is there instead as the hint. */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/overrides_impl.h"

#define MAX_SEGMENTS 128
#define WHERE_MAX 256

typedef struct walk {
    const char *origin;
    char buf[WHERE_MAX]; /* the path, '\0' in place of each dot */
    const char *seg[MAX_SEGMENTS];
    int nseg;
    gd_ytarget *t;
    size_t nt, cap;
    int oom;
    int stopped; /* the first place a branch stopped is in stop */
    gd_error stop;
} walk;

static void resolve(walk *w, gd_ynode *n, int i, const char *where, const char *key);

/* "where.label", or label at the top. */
static const char *join(char *buf, size_t size, const char *where, const char *label)
{
    snprintf(buf, size, "%s%s%s", where, where[0] ? "." : "", label);
    return buf;
}

static const char *place(char *buf, size_t size, const char *where)
{
    if (where[0])
        snprintf(buf, size, "in '%s'", where);
    else
        snprintf(buf, size, "at the top level");
    return buf;
}

/* Records the first place the path stops: field where.segment, message and hint. */
static void stop(walk *w, const char *where, int i, const char *hint, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
static void stop(walk *w, const char *where, int i, const char *hint, const char *fmt, ...)
{
    if (w->stopped) return;
    w->stopped = 1;
    char field[WHERE_MAX], msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    gd_error_set(&w->stop, GD_EINPUT, w->origin, 0, 0, join(field, sizeof field, where, w->seg[i]),
                 hint, "%s", msg);
}

static void push(walk *w, gd_ynode *parent, size_t index, int add)
{
    if (w->nt == w->cap) {
        size_t cap = w->cap ? 2 * w->cap : 8;
        gd_ytarget *t = realloc(w->t, cap * sizeof *t);
        if (!t) {
            w->oom = 1;
            return;
        }
        w->t = t;
        w->cap = cap;
    }
    w->t[w->nt++] = (gd_ytarget){parent, index, add};
}

/* Appends word to a "have: a, b" list; once the list would not fit, ", ..." ends it. */
static void list_add(char *buf, size_t size, const char *word)
{
    size_t used = strlen(buf);
    if (used >= 5 && !strcmp(buf + used - 5, ", ...")) return;
    if (used + strlen(word) + 8 >= size) {
        snprintf(buf + used, size - used, ", ...");
        return;
    }
    snprintf(buf + used, size - used, "%s %s", buf[used - 1] == ':' ? "" : ",", word);
}

static void map_hint(const gd_ynode *map, char *hint, size_t size)
{
    snprintf(hint, size, map->n ? "have:" : "it is empty");
    for (size_t k = 0; k < map->n; k++)
        list_add(hint, size, map->keys[k]->text);
}

static const char *item_name(const gd_ynode *item)
{
    const gd_ynode *nm = gd_ymap_get(item, "name");
    return nm && nm->kind == GD_Y_SCALAR ? nm->text : NULL;
}

static void seq_hint(const gd_ynode *seq, char *hint, size_t size)
{
    if (!seq->n) {
        snprintf(hint, size, "it is empty");
        return;
    }
    snprintf(hint, size, "have:");
    int named = 0;
    for (size_t k = 0; k < seq->n; k++)
        if (item_name(seq->items[k])) {
            list_add(hint, size - 60, item_name(seq->items[k]));
            named = 1;
        }
    size_t used = strlen(hint);
    snprintf(hint + used, size - used, "%s index from 0 to %zu", named ? " (or an" : " an",
             seq->n - 1);
    if (named) snprintf(hint + strlen(hint), size - strlen(hint), ")");
}

/* "meshes" -> "mesh", "bearings" -> "bearing"; "item" for anything else. */
static const char *singular(const char *key, char *buf, size_t size)
{
    size_t n = key ? strlen(key) : 0;
    if (n > 3 && !strcmp(key + n - 2, "es") && strchr("sxh", key[n - 3]))
        n -= 2;
    else if (n > 1 && key[n - 1] == 's')
        n -= 1;
    else
        return "item";
    snprintf(buf, size, "%.*s", (int)n, key);
    return buf;
}

static int is_index(const char *s)
{
    if (!*s) return 0;
    for (; *s; s++)
        if (!isdigit((unsigned char)*s)) return 0;
    return 1;
}

/* Value index of parent is reached by segment i: a target if it is the last. */
static void reach(walk *w, gd_ynode *parent, size_t index, int i, const char *where,
                  const char *label, const char *key)
{
    if (i == w->nseg - 1) {
        push(w, parent, index, 0);
        return;
    }
    char here[WHERE_MAX];
    resolve(w, parent->items[index], i + 1, join(here, sizeof here, where, label), key);
}

static void resolve_map(walk *w, gd_ynode *map, int i, const char *where)
{
    const char *s = w->seg[i];
    int all = !strcmp(s, "*");
    for (size_t k = 0; k < map->n; k++)
        if (all || !strcmp(map->keys[k]->text, s)) {
            reach(w, map, k, i, where, map->keys[k]->text, map->keys[k]->text);
            if (!all) return;
        }
    if (all && map->n) return;
    if (!all && i == w->nseg - 1) {
        push(w, map, map->n, 1); /* a new key: the last segment only */
        return;
    }
    char hint[320], at[WHERE_MAX + 16];
    map_hint(map, hint, sizeof hint);
    if (all)
        stop(w, where, i, hint, "nothing matches '*' %s", place(at, sizeof at, where));
    else
        stop(w, where, i, hint, "no key '%s' %s", s, place(at, sizeof at, where));
}

/* An item reached by `*` in messages: its name, or its index. */
static const char *item_label(const gd_ynode *seq, size_t k, char *buf, size_t size)
{
    const char *name = item_name(seq->items[k]);
    if (name) return name;
    snprintf(buf, size, "%zu", k);
    return buf;
}

static void resolve_seq(walk *w, gd_ynode *seq, int i, const char *where, const char *key)
{
    const char *s = w->seg[i];
    char label[32], word[64], hint[320], at[WHERE_MAX + 16];
    int all = !strcmp(s, "*");
    for (size_t k = 0; k < seq->n; k++) {
        const char *name = item_name(seq->items[k]);
        int hit = all || (is_index(s) ? strtoul(s, NULL, 10) == k : name && !strcmp(name, s));
        if (!hit) continue;
        reach(w, seq, k, i, where, all ? item_label(seq, k, label, sizeof label) : s, NULL);
        if (!all) return;
    }
    if (all && seq->n) return;
    seq_hint(seq, hint, sizeof hint);
    place(at, sizeof at, where);
    if (all)
        stop(w, where, i, hint, "nothing matches '*' %s", at);
    else if (is_index(s))
        stop(w, where, i, hint, "no %s at index %s %s (it has %zu)",
             singular(key, word, sizeof word), s, at, seq->n);
    else
        stop(w, where, i, hint, "no %s named '%s' %s", singular(key, word, sizeof word), s, at);
}

static void resolve(walk *w, gd_ynode *n, int i, const char *where, const char *key)
{
    if (n->kind == GD_Y_MAP) {
        resolve_map(w, n, i, where);
    } else if (n->kind == GD_Y_SEQ) {
        resolve_seq(w, n, i, where, key);
    } else if (!where[0]) {
        stop(w, where, i, "the file must be a map of keys", "the document is a single value");
    } else {
        char hint[WHERE_MAX + 64];
        snprintf(hint, sizeof hint, "end the path at '%s' to replace the value", where);
        stop(w, where, i, hint, "'%s' is a single value (%s), not a map or list", where, n->text);
    }
}

/* Splits path at its dots into w->seg; an empty path or segment is an error. */
static gd_status split(walk *w, const char *path, gd_error *err)
{
    static const char HINT[] = "write keys, indices or names separated by single dots, e.g. "
                               "meshes.mesh.stiffness";
    size_t len = strlen(path);
    if (!len) return gd_error_set(err, GD_EINPUT, w->origin, 0, 0, "", HINT, "empty path");
    if (len >= sizeof w->buf)
        return gd_error_set(err, GD_EINPUT, w->origin, 0, 0, "", "use a shorter path",
                            "path longer than %d characters", (int)sizeof w->buf - 1);
    memcpy(w->buf, path, len + 1);
    for (char *p = w->buf;;) {
        char *dot = strchr(p, '.');
        if (dot) *dot = '\0';
        if (!*p)
            return gd_error_set(err, GD_EINPUT, w->origin, 0, 0, path, HINT,
                                "empty segment %d in the path", w->nseg + 1);
        if (w->nseg == MAX_SEGMENTS)
            return gd_error_set(err, GD_EINPUT, w->origin, 0, 0, "", "use a shorter path",
                                "more than %d segments", MAX_SEGMENTS);
        w->seg[w->nseg++] = p;
        if (!dot) return GD_OK;
        p = dot + 1;
    }
}

gd_status gd_ypath_resolve(gd_ynode *root, const char *path, const char *origin,
                           gd_ytarget **targets, size_t *n, gd_error *err)
{
    walk w;
    memset(&w, 0, sizeof w);
    w.origin = origin;
    gd_status st = split(&w, path, err);
    if (st) return st;
    if (!root)
        return gd_error_set(err, GD_EINPUT, origin, 0, 0, path,
                            "see docs/model-format.md for a complete example",
                            "the file is empty: nothing to change");
    resolve(&w, root, 0, "", NULL);
    if (w.oom) {
        free(w.t);
        return gd_error_set(err, GD_ENOMEM, origin, 0, 0, "", "", "out of memory");
    }
    if (!w.nt) {
        if (err) *err = w.stop;
        return GD_EINPUT;
    }
    *targets = w.t;
    *n = w.nt;
    return GD_OK;
}
