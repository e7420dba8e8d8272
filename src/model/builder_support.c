/* The builder's shared helpers (build_impl.h): located errors, paths of fields, names
 * and positive values checked, arrays grown. Every builder_*.c uses them; apart from
 * builder.c (the dispatcher), so no file of the builder and its dispatcher use each
 * other. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

gd_status gd_build_fail(const gd_model *m, gd_error *err, gd_loc loc, const char *locate_path,
                        const char *field, const char *hint, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    gd_status st = gd_error_set(err, GD_EINPUT, m->file, loc.line, loc.column, field ? field : "",
                                hint, "%s", msg);
    if (locate_path && m->build && m->build->locator.locate)
        m->build->locator.locate(m->build->locator.ctx, locate_path, err);
    return st;
}

gd_status gd_build_oom(const gd_model *m, gd_error *err)
{
    return gd_error_set(err, GD_ENOMEM, m->file, 0, 0, "", "", "out of memory");
}

const char *gd_build_path(char *buf, size_t size, const char *path, const char *key)
{
    /* joined by hand: a path longer than buf is cut */
    size_t n = 0;
    const char *parts[3] = {path && path[0] ? path : "", path && path[0] ? "." : "", key};
    for (int i = 0; i < 3; i++)
        for (const char *c = parts[i]; *c && n + 1 < size; c++)
            buf[n++] = *c;
    if (size) buf[n] = '\0';
    return buf;
}

char *gd_build_strdup(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c) memcpy(c, s, n);
    return c;
}

gd_status gd_build_open(const gd_model *m, gd_error *err)
{
    if (m->build && m->build->failed)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "", "free it and build a new model",
                            "gd_model_finish failed on this model: it can only be freed");
    if (m->build) return GD_OK;
    return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "",
                        "add everything before gd_model_finish, or build a new model",
                        "the model is finished: it can no longer be changed by the builder");
}

/* Grows *array of *n items of size sz by one zeroed item; 0 on failure. */
int gd_build_grow(void *array, int n, size_t sz)
{
    void **a = array;
    char *p = realloc(*a, (size_t)(n + 1) * sz);
    if (!p) return 0;
    memset(p + (size_t)n * sz, 0, sz);
    *a = p;
    return 1;
}

gd_status gd_build_name(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                        const char *name, const char *fallback, char out[GD_NAME_MAX])
{
    if (!name) name = fallback;
    if (!name || !name[0]) {
        char q[200];
        return gd_build_fail(m, err, loc, NULL, gd_build_path(q, sizeof q, path, "name"),
                             "give the item a name", "name missing");
    }
    if (strlen(name) >= GD_NAME_MAX) {
        char q[200];
        gd_build_path(q, sizeof q, path, "name");
        return gd_build_fail(m, err, loc, q, q, "use a shorter name",
                             "name longer than %d characters", GD_NAME_MAX - 1);
    }
    if (out) snprintf(out, GD_NAME_MAX, "%s", name);
    return GD_OK;
}

gd_status gd_build_positive(const gd_model *m, gd_error *err, gd_loc loc, const char *path,
                            const char *key, double v, int allow_zero)
{
    if (allow_zero ? v >= 0 : v > 0) return GD_OK;
    char q[200];
    gd_build_path(q, sizeof q, path, key);
    if (allow_zero)
        return gd_build_fail(m, err, loc, q, q, "give a value of zero or more",
                             "must not be negative (got %g)", v);
    return gd_build_fail(m, err, loc, q, q, "give a value greater than zero",
                         "must be positive (got %g)", v);
}
