/* Errors: every failing geardyn call fills a gd_error that names the file, line,
 * field, what is wrong and how to fix it. No global state: the caller owns it.
 *
 * Ownership and threads: a gd_error is a plain struct owned by the caller (usually on
 * its stack); nothing in it is allocated. Functions taking a gd_error * write only to
 * it, and accept NULL when the caller does not want the details.
 */
#ifndef GEARDYN_ERROR_H
#define GEARDYN_ERROR_H
#include "geardyn/export.h"
#include <stddef.h>

typedef enum gd_status {
    GD_OK = 0,
    GD_EINPUT = 2,   /* the model or an option is wrong: user's to fix */
    GD_ENUMERIC = 3, /* a solver failed (singular system, no convergence) */
    GD_ENOMEM = 4,   /* out of memory */
    GD_EIO = 5,      /* a file could not be read or written */
} gd_status;

typedef struct gd_error {
    gd_status status;
    char file[256];    /* model or output file, "" if none */
    int line, column;  /* 1-based; 0 when unknown */
    char field[160];   /* path of the field, e.g. "bearings[1].kxx" */
    char message[512]; /* what is wrong */
    char hint[320];    /* what to do about it */
} gd_error;

GD_API void gd_error_clear(gd_error *err);

/* Fills err (if not NULL) and returns status. printf-style message. */
GD_API gd_status gd_error_set(gd_error *err, gd_status status, const char *file, int line,
                              int column, const char *field, const char *hint, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 8, 9)))
#endif
    ;

/* "file:line:col: field: message\n  hint: ..." into buf; returns chars written. */
GD_API size_t gd_error_format(const gd_error *err, char *buf, size_t size);

/* Short lower-case name of a status, e.g. "input error". */
GD_API const char *gd_status_name(gd_status status);

#endif
