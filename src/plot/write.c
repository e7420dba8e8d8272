/* Writing a plot document: the format from the file name, the folder checked before
 * any computing, plotly.js located, and the file written beside its target and renamed
 * into place so that a failure leaves nothing at the path. */
#include <dirent.h>
#include <ctype.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "plot/plot_impl.h"

void gd_plot_write_options_init(gd_plot_write_options *opt)
{
    opt->plotly_js = NULL;
}

gd_status gd_plot_format_of(const char *path, gd_plot_format *fmt, gd_error *err)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (dot && (!slash || dot > slash)) {
        if (!strcasecmp(dot, ".svg")) {
            *fmt = GD_PLOT_SVG;
            return GD_OK;
        }
        if (!strcasecmp(dot, ".html") || !strcasecmp(dot, ".htm")) {
            *fmt = GD_PLOT_HTML;
            return GD_OK;
        }
        if (!strcasecmp(dot, ".png") || !strcasecmp(dot, ".pdf")) {
            *fmt = tolower((unsigned char)dot[2]) == 'n' ? GD_PLOT_PNG : GD_PLOT_PDF;
            return GD_OK;
        }
    }
    return gd_error_set(
        err, GD_EINPUT, path, 0, 0, "--plot",
        "name the file FILE.svg, FILE.png, FILE.pdf (static) or FILE.html (interactive, "
        "self-contained)",
        "unknown plot format '%s'", dot && (!slash || dot > slash) ? dot : "(no extension)");
}

static int readable(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode) && access(path, R_OK) == 0;
}

gd_status gd_plot_find_plotly(const gd_plot_write_options *opt, char *path, size_t size,
                              gd_error *err)
{
    char tried[1200] = "";
    size_t used = 0;
#define TRY(p)                                                                                     \
    do {                                                                                           \
        if (readable(p)) {                                                                         \
            snprintf(path, size, "%s", p);                                                         \
            return GD_OK;                                                                          \
        }                                                                                          \
        if (used < sizeof tried)                                                                   \
            used +=                                                                                \
                (size_t)snprintf(tried + used, sizeof tried - used, "%s%s", used ? ", " : "", p);  \
    } while (0)
    if (opt && opt->plotly_js) {
        TRY(opt->plotly_js);
        return gd_error_set(err, GD_EIO, opt->plotly_js, 0, 0, "plotly_js",
                            "give the path of plotly.min.js", "cannot read plotly.js");
    }
    const char *env = getenv("GEARDYN_PLOTLY_JS");
    if (env && *env) {
        TRY(env);
        return gd_error_set(err, GD_EIO, env, 0, 0, "GEARDYN_PLOTLY_JS",
                            "set GEARDYN_PLOTLY_JS to the path of plotly.min.js, or unset it",
                            "cannot read plotly.js");
    }
    /* installed: DATADIR/geardyn beside the library (lib/) or a static program (bin/) */
    char dir[1024], buf[2048];
    if (pl_self_dir(dir, sizeof dir)) {
        snprintf(buf, sizeof buf, "%s/%s/geardyn/plotly.min.js", dir, GD_LIB_TO_DATA);
        TRY(buf);
        snprintf(buf, sizeof buf, "%s/%s/geardyn/plotly.min.js", dir, GD_BIN_TO_DATA);
        TRY(buf);
    }
    /* an uninstalled build: the source tree's npm install */
    TRY(GD_PLOTLY_SOURCE_PATH);
#undef TRY
    return gd_error_set(err, GD_EIO, "", 0, 0, "plotly.js",
                        "run 'make deps' (npm ci) or 'make install', or set GEARDYN_PLOTLY_JS to "
                        "plotly.min.js",
                        "HTML plots inline plotly.js, which was not found (tried %s)", tried);
}

static void dir_of(const char *path, char *dir, size_t size)
{
    snprintf(dir, size, "%s", path);
    char *s = strrchr(dir, '/');
    if (!s)
        snprintf(dir, size, ".");
    else if (s == dir)
        s[1] = '\0';
    else
        *s = '\0';
}

gd_status gd_plot_check_path(const char *path, const gd_plot_write_options *opt, gd_error *err)
{
    gd_plot_format fmt;
    gd_status st = gd_plot_format_of(path, &fmt, err);
    if (st) return st;
    char dir[1024];
    dir_of(path, dir, sizeof dir);
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "create the folder first",
                            "cannot write the plot: folder '%s' does not exist", dir);
    if (access(dir, W_OK | X_OK) != 0)
        return gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "choose a folder you can write into",
                            "cannot write the plot into folder '%s': %s", dir, strerror(errno));
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "give a file name, not a folder",
                            "'%s' is a folder", path);
    if (fmt == GD_PLOT_HTML) {
        char js[1024];
        if ((st = gd_plot_find_plotly(opt, js, sizeof js, err))) return st;
    }
    if (fmt == GD_PLOT_PNG || fmt == GD_PLOT_PDF)
        return pl_raster_check(path, fmt == GD_PLOT_PDF, err);
    return GD_OK;
}

/* The process's umask without changing it (umask() sets it, which races with other
 * threads): Linux reports it in /proc/self/status; 022 otherwise. */
static mode_t process_umask(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    unsigned mask = 022;
    char line[256];
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "Umask: %o", &mask) == 1) break;
    if (f) fclose(f);
    return (mode_t)mask;
}

/* Temporary files beside path that a process no longer running left (PATH.tmp-PID-XXXXXX:
 * killed while writing). */
static void remove_stale_tmp(const char *path)
{
    char dir[1024];
    dir_of(path, dir, sizeof dir);
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    char prefix[600];
    snprintf(prefix, sizeof prefix, "%s.tmp-", base);
    size_t np = strlen(prefix);
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (strncmp(e->d_name, prefix, np)) continue;
        char *end;
        long pid = strtol(e->d_name + np, &end, 10);
        if (end == e->d_name + np || *end != '-' || pid <= 0) continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH) continue;
        char full[1400];
        snprintf(full, sizeof full, "%s/%s", dir, e->d_name);
        unlink(full);
    }
    closedir(d);
}

gd_status gd_plot_write(const gd_plot *p, const char *path, const gd_plot_write_options *opt,
                        gd_error *err)
{
    gd_status st = gd_plot_check_path(path, opt, err);
    if (st) return st;
    if (!p || p->nsections == 0)
        return gd_error_set(err, GD_EINPUT, path, 0, 0, "--plot", "", "nothing to plot");
    gd_plot_format fmt;
    gd_plot_format_of(path, &fmt, err);
    char js[1024] = "";
    if (fmt == GD_PLOT_HTML && (st = gd_plot_find_plotly(opt, js, sizeof js, err))) return st;
    remove_stale_tmp(path);
    char tmp[1200];
    snprintf(tmp, sizeof tmp, "%s.tmp-%ld-XXXXXX", path, (long)getpid());
    int fd = mkstemp(tmp);
    if (fd < 0)
        return gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "check the folder is writable",
                            "cannot create a file beside '%s': %s", path, strerror(errno));
    FILE *f = fdopen(fd, "w");
    if (!f) {
        close(fd);
        unlink(tmp);
        return gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "", "cannot open: %s",
                            strerror(errno));
    }
    errno = 0;
    if (err) gd_error_clear(err); /* so that a message below is this write's own */
    st = fmt == GD_PLOT_SVG    ? pl_write_svg(p, f, err)
         : fmt == GD_PLOT_HTML ? pl_write_html(p, f, js, err)
                               : pl_write_raster(p, path, f, fmt == GD_PLOT_PDF, err);
    int werr = st || ferror(f) ? errno : 0; /* the write's own cause (ENOSPC, EFBIG) */
    if (fclose(f) != 0 && !st) {
        werr = errno;
        st = gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "check the free space",
                          "cannot write: %s", strerror(errno));
    }
    /* mkstemp makes the file 0600: give it the usual permissions */
    if (!st && chmod(tmp, 0666 & ~process_umask()) != 0)
        st = gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "", "cannot chmod: %s",
                          strerror(errno));
    if (!st && rename(tmp, path) != 0)
        st = gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "check the folder is writable",
                          "cannot move the plot into place: %s", strerror(errno));
    if (st) {
        unlink(tmp);
        /* the writer's own reason when it gave one and the stream did not fail
         * (librsvg's, located here); the stream's cause when it did (issue 38 M8: a
         * librsvg error was reported as "the write failed / check the free space") */
        if (err && err->message[0] && !err->file[0] && !werr)
            snprintf(err->file, sizeof err->file, "%s", path);
        else if (!err || !err->file[0])
            gd_error_set(err, st, path, 0, 0, "--plot", "check the free space",
                         "cannot write the plot: %s", werr ? strerror(werr) : "the write failed");
    }
    return st;
}
