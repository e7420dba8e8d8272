#include "geardyn/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void gd_error_clear(gd_error *err)
{
    if (err) memset(err, 0, sizeof *err);
}

static void copy_str(char *dst, size_t n, const char *src)
{
    if (!src) src = "";
    snprintf(dst, n, "%s", src);
}

gd_status gd_error_set(gd_error *err, gd_status status, const char *file, int line, int column,
                       const char *field, const char *hint, const char *fmt, ...)
{
    if (!err) return status;
    err->status = status;
    copy_str(err->file, sizeof err->file, file);
    err->line = line;
    err->column = column;
    copy_str(err->field, sizeof err->field, field);
    copy_str(err->hint, sizeof err->hint, hint);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    return status;
}

/* Appends to buf at *n, never past size; keeps *n <= size - 1. */
static void append(char *buf, size_t size, size_t *n, const char *fmt, ...)
{
    if (*n >= size - 1) return;
    va_list ap;
    va_start(ap, fmt);
    int w = vsnprintf(buf + *n, size - *n, fmt, ap);
    va_end(ap);
    if (w > 0) *n += (size_t)w;
    if (*n > size - 1) *n = size - 1;
}

size_t gd_error_format(const gd_error *err, char *buf, size_t size)
{
    if (!buf || size == 0) return 0;
    buf[0] = '\0';
    if (!err) return 0;
    size_t n = 0;
    if (err->file[0]) {
        append(buf, size, &n, "%s", err->file);
        if (err->line > 0) append(buf, size, &n, ":%d", err->line);
        if (err->line > 0 && err->column > 0) append(buf, size, &n, ":%d", err->column);
        append(buf, size, &n, ": ");
    }
    if (err->field[0]) append(buf, size, &n, "%s: ", err->field);
    append(buf, size, &n, "%s", err->message[0] ? err->message : gd_status_name(err->status));
    if (err->hint[0]) append(buf, size, &n, "\n  hint: %s", err->hint);
    return n;
}

const char *gd_status_name(gd_status status)
{
    switch (status) {
    case GD_OK:
        return "ok";
    case GD_EINPUT:
        return "input error";
    case GD_ENUMERIC:
        return "numerical error";
    case GD_ENOMEM:
        return "out of memory";
    case GD_EIO:
        return "i/o error";
    }
    return "error";
}
