/* Helpers shared by the CLI tests: a scratch folder, running the geardyn program with
 * its output captured, reading files and JSON fields. Header-only (static inline): each
 * test program is its own executable. */
#ifndef GD_TEST_CLI_SUPPORT_H
#define GD_TEST_CLI_SUPPORT_H
#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct scratch {
    char dir[128];
} scratch;

static inline int scratch_open(scratch *s)
{
    snprintf(s->dir, sizeof s->dir, "/tmp/gd_cli_test_XXXXXX");
    return mkdtemp(s->dir) != NULL;
}

static inline void scratch_close(scratch *s)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", s->dir);
    if (system(cmd) != 0) fprintf(stderr, "  could not remove %s\n", s->dir);
}

static inline char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        if (cap - n - 1 == 0) {
            char *nb = realloc(buf, 2 * cap);
            if (!nb) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
            cap *= 2;
        }
    }
    fclose(f);
    if (buf) buf[n] = '\0';
    return buf;
}

static inline void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

typedef struct run_result {
    int code; /* exit status; -1 when killed by a signal */
    char *out, *err;
} run_result;

static inline void run_free(run_result *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

/* Runs "geardyn ARGS" (ARGS printf-style, already shell-quoted) from the source folder,
 * capturing stdout and stderr in the scratch folder. */
static inline int run(scratch *s, run_result *r, const char *fmt, ...)
{
    char args[2048], cmd[4096], outp[256], errp[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    snprintf(outp, sizeof outp, "%s/stdout.txt", s->dir);
    snprintf(errp, sizeof errp, "%s/stderr.txt", s->dir);
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s >'%s' 2>'%s'", GD_SOURCE_DIR, GD_CLI_PATH, args,
             outp, errp);
    int st = system(cmd);
    r->code = (st != -1 && WIFEXITED(st)) ? WEXITSTATUS(st) : -1;
    r->out = read_file(outp);
    r->err = read_file(errp);
    if (!r->out) r->out = calloc(1, 1);
    if (!r->err) r->err = calloc(1, 1);
    return r->code;
}

static inline int contains(const char *text, const char *word)
{
    return text && strstr(text, word);
}

static inline int count_lines(const char *text)
{
    int n = 0;
    for (const char *p = text; p && *p; p++)
        n += *p == '\n';
    return n;
}

static inline int file_exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* Entries of a folder other than . and .. (-1 if it cannot be opened). */
static inline int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

static inline void show(const run_result *r)
{
    fprintf(stderr, "    exit %d\n    stdout: %.600s\n    stderr: %.600s\n", r->code,
            r->out ? r->out : "", r->err ? r->err : "");
}

static inline double jnum(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static inline const char *jstr(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(v) ? v->valuestring : "";
}

/* Runs "geardyn ARGS --json" and parses stdout; NULL (the run shown on stderr) unless it
 * exits 0 with JSON. */
static inline cJSON *run_json_args(scratch *s, const char *args)
{
    run_result r;
    run(s, &r, "%s --json", args);
    cJSON *o = r.code == 0 ? cJSON_Parse(r.out) : NULL;
    if (!o) show(&r);
    run_free(&r);
    return o;
}

/* 1 when "geardyn ARGS" exits 2 with w1 (and w2, may be NULL) on stderr and nothing on
 * stdout (the run shown on stderr otherwise). */
static inline int run_refused(scratch *s, const char *w1, const char *w2, const char *args)
{
    run_result r;
    run(s, &r, "%s", args);
    int ok = r.code == 2 && contains(r.err, w1) && (!w2 || contains(r.err, w2)) && !r.out[0];
    if (!ok) {
        fprintf(stderr, "  args: %s\n", args);
        show(&r);
    }
    run_free(&r);
    return ok;
}

/* An error run with "--out DIR" appended: 1 when it exits 2 with w1 (and w2, may be NULL)
 * on stderr, nothing on stdout and nothing in DIR. */
static inline int run_fails_cleanly(scratch *s, const char *args, const char *w1, const char *w2)
{
    char out[256];
    snprintf(out, sizeof out, "%s/err_out", s->dir);
    run_result r;
    run(s, &r, "%s --out '%s'", args, out);
    int ok = r.code == 2 && contains(r.err, w1) && (!w2 || contains(r.err, w2)) && !r.out[0] &&
             count_entries(out) <= 0;
    if (!ok) {
        fprintf(stderr, "  args: %s\n", args);
        show(&r);
    }
    run_free(&r);
    return ok;
}

#endif
