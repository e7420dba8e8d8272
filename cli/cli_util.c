#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

int gd_cli_report(const gd_error *err)
{
    char buf[2048];
    gd_error_format(err, buf, sizeof buf);
    fprintf(stderr, "geardyn: error: %s\n", buf);
    return err->status == GD_EINPUT || err->status == GD_EIO ? GD_EXIT_INPUT : GD_EXIT_FAIL;
}

int gd_cli_usage_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "geardyn %s: ", cmd);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n  see 'geardyn %s --help'\n", cmd);
    return GD_EXIT_INPUT;
}

int gd_cli_option_error(const char *cmd, int c, char **argv, int optind_now)
{
    const char *opt = argv[optind_now - 1];
    if (c == ':') return gd_cli_usage_error(cmd, "option '%s' needs a value", opt);
    return gd_cli_usage_error(cmd, "unknown option '%s'", opt);
}

int gd_outdir_check(const char *dir, gd_error *err)
{
    struct stat sb;
    if (stat(dir, &sb) == 0 && !S_ISDIR(sb.st_mode))
        return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                            "give a folder (it is created if missing)",
                            "exists and is not a folder");
    return GD_OK;
}

/* The folder dir would be created in: "." or everything before the last '/'. */
static void parent_of(const char *dir, char *buf, size_t size)
{
    snprintf(buf, size, "%s", dir);
    size_t n = strlen(buf);
    while (n > 1 && buf[n - 1] == '/')
        buf[--n] = '\0';
    char *slash = strrchr(buf, '/');
    if (!slash)
        snprintf(buf, size, ".");
    else
        slash[slash == buf ? 1 : 0] = '\0';
}

int gd_outdir_check_writable(const char *dir, gd_error *err)
{
    if (gd_outdir_check(dir, err)) return GD_EIO;
    struct stat sb;
    if (stat(dir, &sb) == 0) {
        if (access(dir, W_OK | X_OK) != 0)
            return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                                "check that the folder is writable", "cannot write into folder: %s",
                                strerror(errno));
        return GD_OK;
    }
    char parent[1024];
    parent_of(dir, parent, sizeof parent);
    if (stat(parent, &sb) != 0 || !S_ISDIR(sb.st_mode) || access(parent, W_OK | X_OK) != 0)
        return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                            "check that the parent folder exists and is writable",
                            "cannot create folder: '%s' is not a writable folder", parent);
    return GD_OK;
}

int gd_cli_parse_count(const char *text, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (end == text || *end || errno || v < lo || v > hi) return 1;
    *out = v;
    return 0;
}

cJSON *gd_cli_json_number(double v)
{
    return isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull();
}

void gd_cli_print_json(FILE *f, const cJSON *item)
{
    char *s = cJSON_Print(item);
    if (s) {
        fputs(s, f);
        fputc('\n', f);
        free(s);
    }
}

int gd_outdir_begin(gd_outdir *od, const char *dir, gd_error *err)
{
    memset(od, 0, sizeof *od);
    if (strlen(dir) >= sizeof od->dir - 1)
        return gd_error_set(err, GD_EINPUT, dir, 0, 0, "--out", "use a shorter path",
                            "output path too long");
    snprintf(od->dir, sizeof od->dir, "%s", dir);
    struct stat sb;
    if (stat(dir, &sb) == 0) {
        if (!S_ISDIR(sb.st_mode))
            return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                                "give a folder (it is created if missing)",
                                "exists and is not a folder");
    } else if (mkdir(dir, 0777) != 0) {
        return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                            "check that the parent folder exists and is writable",
                            "cannot create folder: %s", strerror(errno));
    } else {
        od->created = 1;
    }
    snprintf(od->stage, sizeof od->stage, "%s/.geardyn-stage-XXXXXX", dir);
    if (!mkdtemp(od->stage)) {
        gd_error_set(err, GD_EIO, dir, 0, 0, "--out", "check that the folder is writable",
                     "cannot write into folder: %s", strerror(errno));
        od->stage[0] = '\0';
        gd_outdir_abort(od);
        return GD_EIO;
    }
    return GD_OK;
}

FILE *gd_outdir_open(gd_outdir *od, const char *name, gd_error *err)
{
    if (od->nfiles >= 16) {
        gd_error_set(err, GD_EIO, od->dir, 0, 0, "--out", "", "too many output files");
        return NULL;
    }
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", od->stage, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        gd_error_set(err, GD_EIO, path, 0, 0, "--out", "check free space and permissions",
                     "cannot write: %s", strerror(errno));
        return NULL;
    }
    snprintf(od->names[od->nfiles++], sizeof od->names[0], "%s", name);
    return f;
}

int gd_outdir_close(gd_outdir *od, FILE *f, const char *name, gd_error *err)
{
    int bad = ferror(f);
    if (fclose(f) != 0) bad = 1;
    if (bad)
        return gd_error_set(err, GD_EIO, od->dir, 0, 0, "--out", "check free space",
                            "error writing %s", name);
    return GD_OK;
}

int gd_outdir_commit(gd_outdir *od, gd_error *err)
{
    char from[1200], to[1200];
    for (int i = 0; i < od->nfiles; i++) {
        snprintf(from, sizeof from, "%s/%s", od->stage, od->names[i]);
        snprintf(to, sizeof to, "%s/%s", od->dir, od->names[i]);
        if (rename(from, to) != 0) {
            gd_error_set(err, GD_EIO, to, 0, 0, "--out", "check permissions",
                         "cannot move output into place: %s", strerror(errno));
            gd_outdir_abort(od);
            return GD_EIO;
        }
    }
    rmdir(od->stage);
    od->nfiles = 0;
    return GD_OK;
}

void gd_outdir_abort(gd_outdir *od)
{
    char path[1200];
    for (int i = 0; i < od->nfiles; i++) {
        snprintf(path, sizeof path, "%s/%s", od->stage, od->names[i]);
        unlink(path);
    }
    if (od->stage[0]) rmdir(od->stage);
    /* a folder made for this run and left empty goes too: nothing half-written */
    if (od->created) rmdir(od->dir);
    od->nfiles = 0;
}
