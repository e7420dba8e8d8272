/* The results table, one row per case (docs/studies.md, "Results"): header and rows as
 * CSV lines, read back for --resume and --merge, and the study's accessors. Numbers are
 * written with %.17g, which round-trips every double, so equal results give equal
 * bytes whatever thread, rank or shard computed them. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/study_impl.h"

size_t gd_study_ncases(const gd_study *s)
{
    return s->ncases;
}
int gd_study_nparams(const gd_study *s)
{
    return s->nparams;
}
int gd_study_noutputs(const gd_study *s)
{
    return s->noutputs;
}
const char *gd_study_param_name(const gd_study *s, int p)
{
    return s->params[p].name;
}
const char *gd_study_output_name(const gd_study *s, int o)
{
    return s->out_names[o];
}
int gd_study_param_numeric(const gd_study *s, int p)
{
    return s->params[p].numeric;
}
const char *gd_study_analysis(const gd_study *s)
{
    return s->analysis->name;
}
const char *gd_study_model_file(const gd_study *s)
{
    return gd_model_source_file(s->src);
}
const char *gd_study_text(const gd_study *s)
{
    return s->text;
}

gd_status gd_study_row_init(const gd_study *s, gd_study_row *row, gd_error *err)
{
    memset(row, 0, sizeof *row);
    row->outputs = calloc((size_t)(s->noutputs > 0 ? s->noutputs : 1), sizeof *row->outputs);
    if (!row->outputs) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    return GD_OK;
}

void gd_study_row_free(gd_study_row *row)
{
    free(row->outputs);
    row->outputs = NULL;
}

const char *gd_study_status_text(gd_status st)
{
    return st == GD_OK ? "ok" : gd_status_name(st);
}

/* Appends to buf like snprintf at offset *n, counting what would be needed. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static void
put(char *buf, size_t size, size_t *n, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int w =
        vsnprintf(buf && *n < size ? buf + *n : NULL, buf && *n < size ? size - *n : 0, fmt, ap);
    va_end(ap);
    if (w > 0) *n += (size_t)w;
}
#define PUT(...) put(buf, size, n, __VA_ARGS__)

/* A CSV field, quoted when it holds a comma, quote or line break. */
static void put_field(char *buf, size_t size, size_t *n, const char *text)
{
    if (!strpbrk(text, ",\"\n\r")) {
        PUT("%s", text);
        return;
    }
    PUT("\"");
    for (const char *p = text; *p; p++)
        if (*p == '"')
            PUT("\"\"");
        else
            PUT("%c", *p);
    PUT("\"");
}

size_t gd_study_format_header(const gd_study *s, char *buf, size_t size)
{
    size_t m = 0, *n = &m;
    PUT("case");
    for (int p = 0; p < s->nparams; p++) {
        PUT(",");
        put_field(buf, size, n, s->params[p].name);
    }
    for (int o = 0; o < s->noutputs; o++) {
        PUT(",");
        put_field(buf, size, n, s->out_names[o]);
    }
    PUT(",status,message\n");
    return m;
}

size_t gd_study_format_row(const gd_study *s, const gd_study_row *row, char *buf, size_t size)
{
    size_t m = 0, *n = &m;
    char num[64];
    PUT("%zu", row->index);
    for (int p = 0; p < s->nparams; p++) {
        PUT(",");
        put_field(buf, size, n, gd_study_case_text(s, row->index, p, num, sizeof num));
    }
    for (int o = 0; o < s->noutputs; o++) {
        double v = row->outputs[o];
        if (isnan(v))
            PUT(",nan");
        else
            PUT(",%.17g", v);
    }
    PUT(",%s,", gd_study_status_text(row->status));
    put_field(buf, size, n, row->message);
    PUT("\n");
    return m;
}

/* The next CSV field of *p into out (unquoted); 0 at the end of the line. */
static int next_field(const char **p, char *out, size_t size, int *last)
{
    const char *q = *p;
    size_t k = 0;
    if (*q == '"') {
        for (q++;; q++) {
            if (!*q) return 0;
            if (*q == '"') {
                if (q[1] != '"') break;
                q++;
            }
            if (k + 1 < size) out[k++] = *q;
        }
        q++;
    } else {
        for (; *q && *q != ',' && *q != '\n'; q++)
            if (k + 1 < size) out[k++] = *q;
    }
    out[k] = '\0';
    *last = *q != ',';
    if (*q && *q != ',' && *q != '\n') return 0;
    *p = *q == ',' ? q + 1 : q;
    return 1;
}

static gd_status bad(gd_error *err, const char *why)
{
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "", "the line is not a complete row",
                        "bad results row: %s", why);
}

gd_status gd_study_parse_row(const gd_study *s, const char *line, gd_study_row *row, gd_error *err)
{
    char f[1100];
    int last = 0;
    const char *p = line;
    char *end;
    if (!next_field(&p, f, sizeof f, &last) || last) return bad(err, "no case number");
    errno = 0;
    unsigned long long c = strtoull(f, &end, 10);
    if (!*f || *end || errno || c >= s->ncases) return bad(err, "case number out of range");
    row->index = (size_t)c;
    for (int k = 0; k < s->nparams; k++) /* the parameters follow from the case number */
        if (!next_field(&p, f, sizeof f, &last) || last) return bad(err, "too few fields");
    for (int o = 0; o < s->noutputs; o++) {
        if (!next_field(&p, f, sizeof f, &last) || last) return bad(err, "too few fields");
        row->outputs[o] = strtod(f, &end);
        if (!*f || *end) return bad(err, "an output is not a number");
    }
    if (!next_field(&p, f, sizeof f, &last) || last) return bad(err, "no status");
    row->status = GD_OK;
    if (strcmp(f, "ok")) {
        static const gd_status all[] = {GD_EINPUT, GD_ENUMERIC, GD_ENOMEM, GD_EIO};
        row->status = (gd_status)-1;
        for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
            if (!strcmp(f, gd_status_name(all[i]))) row->status = all[i];
        if ((int)row->status < 0) return bad(err, "unknown status");
    }
    if (!next_field(&p, row->message, sizeof row->message, &last) || !last)
        return bad(err, "no message, or too many fields");
    if (*p && strcmp(p, "\n")) return bad(err, "text after the message");
    return GD_OK;
}
