/* Private pieces of the test-data reader: a file held in memory with a line cursor
 * (UFF records are lines, 58b's data are bytes between them), and the readers of each
 * form, which append functions to a set. */
#ifndef GD_TESTDATA_IMPL_H
#define GD_TESTDATA_IMPL_H
#include <stddef.h>

#include "geardyn/testdata.h"

typedef struct gd_td_text {
    const char *file;
    const char *buf; /* the whole file, NUL-terminated after len */
    size_t len, pos;
    int line;    /* 1-based line of pos */
    int partial; /* the last line read had no end: the file stops inside it */
} gd_td_text;

/* The next line (without its end) into *s, *n; 0 at the end of the file. */
int gd_td_next_line(gd_td_text *t, const char **s, size_t *n);

/* A new function at the end of td (zeroed, line and file set); NULL when out of memory. */
gd_td_function *gd_td_push(gd_testdata *td, const char *file, int line);

/* Readers: each appends what it reads to td. */
gd_status gd_td_read_uff(gd_td_text *t, int skip_other, gd_testdata *td, gd_error *err);
gd_status gd_td_read_frf_csv(gd_td_text *t, gd_testdata *td, gd_error *err);
gd_status gd_td_read_modes_csv(gd_td_text *t, gd_testdata *td, gd_error *err);

/* Checks f's axis (finite, >= 0, strictly increasing) and values (finite). */
gd_status gd_td_check(const gd_td_function *f, const char *field, gd_error *err);

#endif
