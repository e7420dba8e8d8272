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

int gd_outdir_check(const char *dir, gd_error *err)
{
    struct stat sb;
    if (stat(dir, &sb) == 0) {
        if (!S_ISDIR(sb.st_mode))
            return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                                "give a folder (it is created if missing)",
                                "exists and is not a folder");
        return GD_OK;
    }
    /* a folder to be made: try, before any computing, that its parent takes one (a
     * permission check says nothing for root or in /proc), so a run that could not
     * write its folder neither computes nor writes its --plot (issue 38 L1) */
    char probe[1100];
    parent_of(dir, probe, sizeof probe - 40);
    snprintf(probe + strlen(probe), sizeof probe - strlen(probe), "/.geardyn-probe-%ld-XXXXXX",
             (long)getpid());
    if (!mkdtemp(probe)) {
        int e = errno;
        char parent[1024];
        parent_of(dir, parent, sizeof parent);
        return gd_error_set(
            err, GD_EIO, dir, 0, 0, "--out", "check that the parent folder exists and is writable",
            "cannot create folder: '%s' is not a writable folder (%s)", parent, strerror(e));
    }
    rmdir(probe);
    return GD_OK;
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

int gd_cli_parse_tolerance(const char *cmd, const char *name, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v >= 1e-15 && v < 1))
        return gd_cli_usage_error(cmd,
                                  "%s: expected a number in [1e-15, 1) (a tolerance below 1e-15 "
                                  "is unreachable in double precision), got '%s'",
                                  name, text);
    *(double *)field = v;
    return 0;
}

int gd_cli_split_commas(const char *cmd, const char *name, const char *const *in, int n, char **buf,
                        const char **out, int max)
{
    size_t len = 1;
    for (int k = 0; k < n; k++)
        len += strlen(in[k]) + 1;
    char *b = *buf = malloc(len), *p = b;
    if (!b) return gd_cli_usage_error(cmd, "out of memory");
    int m = 0;
    for (int k = 0; k < n; k++) {
        strcpy(p, in[k]);
        for (char *tok = p, *next; tok; tok = next) {
            next = strchr(tok, ',');
            if (next) *next++ = '\0';
            if (!*tok) return gd_cli_usage_error(cmd, "%s: an empty item in '%s'", name, in[k]);
            if (m == max) return gd_cli_usage_error(cmd, "%s: more than %d items", name, max);
            out[m++] = tok;
        }
        p += strlen(in[k]) + 1;
    }
    return -m;
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

double gd_cli_zeta_shown(double zeta)
{
    return fabs(zeta) < 1e-9 ? 0.0 : zeta;
}

/* log decrement 2 pi zeta / sqrt(1 - zeta^2): 2 pi times the same threshold */
double gd_cli_logdec_shown(double logdec)
{
    return fabs(logdec) < 2 * M_PI * 1e-9 ? 0.0 : logdec;
}

const char *gd_cli_num(char *buf, size_t size, int width, int precision, double v)
{
    if (isnan(v))
        snprintf(buf, size, "%*s", width, "-");
    else
        snprintf(buf, size, "%*.*g", width, precision, v);
    return buf;
}
