/* Parameter studies (docs/studies.md): a study file names a model, the parameters to
 * vary (any `--set` path) with their values, the analysis to run and the scalar outputs
 * to keep. gd_study_load reads and checks all of it (errors located in the study file)
 * and generates the cases; gd_study_run_case runs one case: the model, parsed once,
 * is loaded with the case's overrides, analysed, and the outputs are extracted.
 * gd_study_run runs many cases over OpenMP threads. The results form one long table,
 * one row per case (gd_study_row, gd_study_format_row).
 *
 * Ownership and threads: gd_study_load makes a study the caller frees with
 * gd_study_free; everything a study returns (names, texts) belongs to it. A loaded
 * study is only read: any number of threads may run its cases at once, each case on
 * its own model and system, single-threaded; gd_study_run calls its sink from one
 * thread at a time. Rows are caller-owned (gd_study_row_init / gd_study_row_free). */
#ifndef GEARDYN_STUDY_H
#define GEARDYN_STUDY_H
#include "geardyn/export.h"
#include <stddef.h>

#include "geardyn/error.h"

typedef struct gd_study gd_study;

/* Reads the study file at path (the model path in it is relative to the file), checks
 * the parameters against the model and the outputs against the analysis, and
 * generates the cases. Bad input is GD_EINPUT located in the study file. */
GD_API gd_status gd_study_load(const char *path, gd_study **out, gd_error *err);
GD_API void gd_study_free(gd_study *s);

GD_API size_t gd_study_ncases(const gd_study *s);
GD_API int gd_study_nparams(const gd_study *s);
GD_API int gd_study_noutputs(const gd_study *s);
/* Column names: a parameter's `name:` (default its path), an output as written
 * ("frequency_hz[3]"). */
GD_API const char *gd_study_param_name(const gd_study *s, int p);
GD_API const char *gd_study_output_name(const gd_study *s, int o);
/* Whether parameter p's values are numbers (else texts, gd_study_case_text). */
GD_API int gd_study_param_numeric(const gd_study *s, int p);
/* Parameter p's value in case c: the number (NaN for a text parameter) or its text
 * (into buf, as the table writes it). */
GD_API double gd_study_case_value(const gd_study *s, size_t c, int p);
GD_API const char *gd_study_case_text(const gd_study *s, size_t c, int p, char *buf, size_t size);
/* The analysis ("modal", ...), the model file and the study file's text. */
GD_API const char *gd_study_analysis(const gd_study *s);
GD_API const char *gd_study_model_file(const gd_study *s);
GD_API const char *gd_study_text(const gd_study *s);
/* The name of analysis i (from 0) that a study can run; NULL past the last. */
GD_API const char *gd_study_analysis_name(int i);

/* One row of the results: a case's outputs, or why it failed. */
typedef struct gd_study_row {
    size_t index;       /* case number, from 0 */
    gd_status status;   /* GD_OK, or why the case failed */
    double *outputs;    /* gd_study_noutputs values; NaN where an output does not exist */
    char message[1024]; /* the error, formatted on one line; "" when ok */
} gd_study_row;

/* Allocates row->outputs for s (GD_ENOMEM on failure); gd_study_row_free releases it. */
GD_API gd_status gd_study_row_init(const gd_study *s, gd_study_row *row, gd_error *err);
GD_API void gd_study_row_free(gd_study_row *row);

/* Runs case c into row (never stops on a failed case: the row says why). Threads: many
 * cases of one study may run at once. */
GD_API void gd_study_run_case(const gd_study *s, size_t c, gd_study_row *row);

/* Called once per finished case, from one thread at a time; a non-zero return stops
 * the run after the cases under way. */
typedef int (*gd_study_sink)(void *user, const gd_study_row *row);
/* Runs the n cases listed (case numbers) over nthreads OpenMP threads (0: the OpenMP
 * default), dynamically scheduled; the sink gets each row as it finishes (in any
 * order). GD_ENOMEM, or GD_OK (failed cases are rows, not errors). */
GD_API gd_status gd_study_run(const gd_study *s, const size_t *cases, size_t n, int nthreads,
                              gd_study_sink sink, void *user, gd_error *err);

/* The table's header line "case,<parameters>,<outputs>,status,message\n" and a row as
 * one CSV line ending in '\n' (numbers as %.17g, so the same doubles give the same
 * bytes; the message quoted). Return the length, or the size needed (snprintf). */
GD_API size_t gd_study_format_header(const gd_study *s, char *buf, size_t size);
GD_API size_t gd_study_format_row(const gd_study *s, const gd_study_row *row, char *buf,
                                  size_t size);
/* Reads back a line written by gd_study_format_row (without or with its '\n') into row
 * (initialised for s): GD_OK, or GD_EINPUT when the line is not a complete row of s. */
GD_API gd_status gd_study_parse_row(const gd_study *s, const char *line, gd_study_row *row,
                                    gd_error *err);
/* "ok", or the failed status's name as the table writes it (gd_status_name). */
GD_API const char *gd_study_status_text(gd_status st);

#endif
