/* The folder of a study run (docs/studies.md, "Results" and "Resuming"): the study file
 * and the geardyn version beside the results, a journal of finished cases for
 * --resume, and the table as CSV and HDF5 written at the end. */
#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "geardyn/version.h"
#include "study_cli.h"

static int fail(const char *file, const char *hint, const char *what)
{
    gd_error err;
    gd_error_set(&err, GD_EIO, file, 0, 0, "--out", hint, "%s", what);
    return gd_cli_report(&err);
}

/* A write that failed (no space, no permission): the run failed, exit 1
 * (docs/studies.md), unlike the input errors above (exit 2). */
static int fail_io(const char *file, const char *hint, const char *what)
{
    gd_error err;
    gd_error_set(&err, GD_EIO, file, 0, 0, "--out", hint, "%s", what);
    gd_cli_report(&err);
    return GD_EXIT_FAIL;
}

/* All of buf, or -1 with errno set: a short write (a full disk, a file size limit) is
 * retried so the next write reports the cause (ENOSPC, EFBIG) instead of leaving errno
 * as it was ("Success"). */
static int write_all(int fd, const char *buf, size_t len)
{
    while (len > 0) {
        ssize_t k = write(fd, buf, len);
        if (k < 0 && errno == EINTR) continue;
        if (k < 0) return -1;
        if (k == 0) {
            errno = ENOSPC;
            return -1;
        }
        buf += k;
        len -= (size_t)k;
    }
    return 0;
}

/* The run's lock on its folder: DIR/.lock, held (flock) until the process ends, so a
 * second run on the same folder (two --resume at once, or shards given the same
 * --out) stops at once instead of redoing the same cases and sharing results.h5.tmp.
 * 0, 1 another run holds it, -1 error (errno). */
static int lock_folder(const char *dir, int *fd)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/.lock", dir);
    *fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (*fd < 0) return -1;
    if (flock(*fd, LOCK_EX | LOCK_NB) == 0) return 0;
    int e = errno;
    close(*fd);
    *fd = -1;
    errno = e;
    return e == EWOULDBLOCK ? 1 : -1;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n < cap - 1) break;
        char *more = realloc(buf, cap *= 2);
        if (!more) free(buf);
        buf = more;
    }
    fclose(f);
    if (buf) buf[n] = '\0';
    if (len) *len = n;
    return buf;
}

/* Writes text to dir/name through a temporary file and a rename. */
static int write_atomic(const char *dir, const char *name, const char *text)
{
    char path[1200], tmp[1300];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "wb");
    if (!f) return -1;
    int bad = fputs(text, f) < 0;
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, path)) {
        remove(tmp);
        return -1;
    }
    return 0;
}

/* The journal's rows by case (lines[c] malloc'd, NULL when absent). *valid: bytes up to
 * the end of the last whole line (a cut line at the end is left out). Returns 0, or
 * -1 with why set. */
static int read_journal(const gd_study *s, const char *path, char **lines, size_t *valid,
                        unsigned char *failed, char *why, size_t why_size)
{
    size_t len;
    char *text = slurp(path, &len);
    if (!text) {
        snprintf(why, why_size, "cannot read it: %s", strerror(errno));
        return -1;
    }
    size_t hsize = gd_study_format_header(s, NULL, 0) + 1;
    char *header = malloc(hsize);
    int rc = 0;
    if (!header) {
        free(text);
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    gd_study_format_header(s, header, hsize);
    if (strncmp(text, header, strlen(header))) {
        snprintf(why, why_size, "it was written for other parameters or outputs");
        rc = -1;
    }
    gd_study_row row = {0};
    if (!rc && gd_study_row_init(s, &row, NULL)) rc = -1;
    char *p = text + (rc ? 0 : strlen(header));
    *valid = (size_t)(p - text);
    while (!rc && *p) {
        char *nl = strchr(p, '\n');
        if (!nl) break; /* cut by a kill: dropped */
        *nl = '\0';
        gd_error err;
        if (gd_study_parse_row(s, p, &row, &err)) {
            /* a damaged line can only be the last one (each is one write) */
            if (nl[1]) {
                snprintf(why, why_size, "%s", err.message);
                rc = -1;
            }
            break;
        }
        free(lines[row.index]);
        if (failed) failed[row.index] = row.status != GD_OK;
        size_t n = (size_t)(nl - p);
        if (!(lines[row.index] = malloc(n + 2))) {
            rc = -1;
            snprintf(why, why_size, "out of memory");
            break;
        }
        memcpy(lines[row.index], p, n);
        memcpy(lines[row.index] + n, "\n", 2);
        p = nl + 1;
        *valid = (size_t)(p - text);
    }
    gd_study_row_free(&row);
    free(header);
    free(text);
    return rc;
}

static void free_lines(char **lines, size_t n)
{
    for (size_t i = 0; lines && i < n; i++)
        free(lines[i]);
    free(lines);
}

int gd_study_out_open(gd_study_out *o, const gd_study *s, const char *dir, size_t shard,
                      size_t nshards, int resume, int progress)
{
    memset(o, 0, sizeof *o);
    o->fd = -1;
    o->lock_fd = -1;
    o->s = s;
    o->shard = shard;
    o->nshards = nshards;
    o->progress = progress;
    if (nshards > 1)
        snprintf(o->dir, sizeof o->dir, "%s/shard-%zu-of-%zu", dir, shard, nshards);
    else
        snprintf(o->dir, sizeof o->dir, "%s", dir);
    size_t n = gd_study_ncases(s);
    o->done = calloc(n ? n : 1, 1);
    o->line_size = 4096;
    o->line = malloc(o->line_size);
    if (!o->done || !o->line) return fail(o->dir, "", "out of memory");
    for (size_t c = shard; c < n; c += nshards)
        o->total++;

    char journal[1200], copy[1200];
    snprintf(journal, sizeof journal, "%s/journal.csv", o->dir);
    snprintf(copy, sizeof copy, "%s/study.yaml", o->dir);
    struct stat sb;
    if (!resume) {
        char parent[1100];
        snprintf(parent, sizeof parent, "%s", dir);
        if ((mkdir(parent, 0777) && errno != EEXIST) || (mkdir(o->dir, 0777) && errno != EEXIST))
            return fail(o->dir, "check that the parent folder exists and is writable",
                        strerror(errno));
    }
    if (stat(o->dir, &sb) == 0) {
        int lk = lock_folder(o->dir, &o->lock_fd);
        if (lk == 1)
            return fail(o->dir, "wait for the other run to end, or give another --out",
                        "another geardyn study run holds this folder");
        if (lk < 0) return fail_io(o->dir, "check the folder's permissions", strerror(errno));
    }
    int exists = stat(journal, &sb) == 0;
    if (exists && !resume)
        return fail(o->dir, "add --resume to continue it, or give another --out",
                    "this folder holds a study run already");
    if (!exists && resume)
        return fail(o->dir, "run without --resume to start the study",
                    "--resume: no journal.csv of an earlier run here");
    if (resume) {
        char *old = slurp(copy, NULL);
        int same = old && !strcmp(old, gd_study_text(s));
        free(old);
        if (!same)
            return fail(copy, "resume with the same study file, or start a new --out",
                        "the study file changed since this run began");
        char **lines = calloc(n ? n : 1, sizeof *lines);
        char why[2048];
        size_t valid = 0;
        unsigned char *failed = calloc(n ? n : 1, 1);
        if (!lines || !failed || read_journal(s, journal, lines, &valid, failed, why, sizeof why)) {
            free(failed);
            free_lines(lines, n);
            return fail(journal, "start the study again in a new --out",
                        lines ? why : "out of memory");
        }
        for (size_t c = 0; c < n; c++)
            if (lines[c] && c % nshards == shard) {
                o->done[c] = 1;
                o->ndone++;
                if (failed[c]) o->nfailed++;
            }
        free(failed);
        free_lines(lines, n);
        o->resumed = o->ndone;
        /* drop a line cut by the kill, so the next row starts on its own line */
        if (truncate(journal, (off_t)valid))
            return fail_io(journal, "check the folder's permissions", strerror(errno));
    } else {
        char version[128];
        snprintf(version, sizeof version, "geardyn %s\n", gd_version());
        size_t hsize = gd_study_format_header(s, NULL, 0) + 1;
        char *header = malloc(hsize);
        if (!header) return fail(o->dir, "", "out of memory");
        gd_study_format_header(s, header, hsize);
        int bad = write_atomic(o->dir, "study.yaml", gd_study_text(s)) ||
                  write_atomic(o->dir, "version.txt", version) ||
                  write_atomic(o->dir, "journal.csv", header);
        free(header);
        if (bad)
            return fail_io(o->dir, "check the folder's permissions and free space",
                           strerror(errno));
    }
    o->fd = open(journal, O_WRONLY | O_APPEND);
    if (o->fd < 0) return fail_io(journal, "check the folder's permissions", strerror(errno));
    o->t0 = now();
    gd_hdf5_plugin_start(&o->plugin); /* while the cases run */
    return GD_EXIT_OK;
}

size_t *gd_study_out_todo(const gd_study_out *o, size_t *n)
{
    size_t *todo = malloc((o->total ? o->total : 1) * sizeof *todo);
    *n = 0;
    for (size_t c = o->shard; todo && c < gd_study_ncases(o->s); c += o->nshards)
        if (!o->done[c]) todo[(*n)++] = c;
    return todo;
}

static void draw(gd_study_out *o, int final)
{
    double t = now();
    if (!final && t - o->last_draw < 0.2) return;
    o->last_draw = t;
    size_t new_done = o->ndone - o->resumed, left = o->total - o->ndone;
    double rate = t > o->t0 ? (double)new_done / (t - o->t0) : 0;
    double eta = rate > 0 ? (double)left / rate : 0;
    int width = 30,
        fill = o->total ? (int)((double)width * (double)o->ndone / (double)o->total) : width;
    char bar[64];
    for (int i = 0; i < width; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[width] = '\0';
    fprintf(stderr, "\r[%s] %zu/%zu  %zu failed  %.1f cases/s  ETA %ld:%02ld ", bar, o->ndone,
            o->total, o->nfailed, rate, (long)eta / 60, (long)eta % 60);
    if (final) fputc('\n', stderr);
    fflush(stderr);
}

int gd_study_out_sink(void *user, const gd_study_row *row)
{
    gd_study_out *o = user;
    size_t need = gd_study_format_row(o->s, row, o->line, o->line_size) + 1;
    if (need > o->line_size) {
        char *more = realloc(o->line, need);
        if (!more) return 1;
        o->line = more;
        o->line_size = need;
        gd_study_format_row(o->s, row, o->line, o->line_size);
    }
    /* one write per row: a kill leaves whole rows and at most one cut last line */
    size_t len = strlen(o->line);
    if (write_all(o->fd, o->line, len)) {
        fprintf(stderr, "geardyn: error: %s/journal.csv: %s\n", o->dir, strerror(errno));
        return 1;
    }
    if (!o->done[row->index]) o->ndone++;
    o->done[row->index] = 1;
    if (row->status) o->nfailed++;
    if (o->progress) draw(o, 0);
    return 0;
}

/* results.h5 through the plugin geardyn-hdf5.so (study_hdf5.c), found beside the
 * program (build tree) or in LIBDIR/geardyn (installed): loaded only for a study, so
 * that HDF5 and the ~40 libraries it pulls in do not slow down every geardyn command. */
static void *load_plugin(void *arg)
{
    gd_hdf5_plugin *p = arg;
    char self[PATH_MAX], plugin[PATH_MAX + 64] = "geardyn-hdf5.so";
    ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
    if (k <= 0) {
        snprintf(p->why, sizeof p->why, "cannot find the program's folder");
        return NULL;
    }
    self[k] = '\0';
    char *slash = strrchr(self, '/');
    if (slash) *slash = '\0';
    const char *const where[] = {"geardyn-hdf5.so", GD_HDF5_PLUGIN};
    for (size_t i = 0; !p->handle && i < sizeof where / sizeof where[0]; i++) {
        snprintf(plugin, sizeof plugin, "%s/%s", self, where[i]);
        /* never closed: HDF5 registers exit handlers */
        p->handle = dlopen(plugin, RTLD_NOW | RTLD_LOCAL);
    }
    if (!p->handle)
        snprintf(p->why, sizeof p->why, "cannot load the HDF5 writer %.400s: %.400s", plugin,
                 dlerror());
    return NULL;
}

void gd_hdf5_plugin_start(gd_hdf5_plugin *p)
{
    memset(p, 0, sizeof *p);
    p->started = pthread_create(&p->thread, NULL, load_plugin, p) == 0;
}

/* Waits for (or does) the loading; the handle or NULL. */
static void *plugin_wait(gd_hdf5_plugin *p)
{
    if (p->started) {
        pthread_join(p->thread, NULL);
        p->started = 0;
    } else if (!p->handle && !p->why[0]) {
        load_plugin(p);
    }
    return p->handle;
}

static int write_hdf5(gd_hdf5_plugin *p, const gd_study *s, const char *path, char *const *lines,
                      char *why, size_t why_size)
{
    if (!plugin_wait(p)) {
        snprintf(why, why_size, "%s", p->why);
        return -1;
    }
    int (*write)(const gd_study *, const char *, char *const *, char *, size_t);
    *(void **)&write = dlsym(p->handle, "gd_study_write_hdf5");
    if (!write) {
        snprintf(why, why_size, "the HDF5 writer has no gd_study_write_hdf5");
        return -1;
    }
    return write(s, path, lines, why, why_size);
}

int gd_study_write_results(const gd_study *s, const char *dir, char *const *lines,
                           gd_hdf5_plugin *plugin)
{
    gd_hdf5_plugin local = {0};
    if (!plugin) plugin = &local;
    size_t n = gd_study_ncases(s), hsize = gd_study_format_header(s, NULL, 0) + 1, len = hsize;
    for (size_t c = 0; c < n; c++)
        if (lines[c]) len += strlen(lines[c]);
    char *csv = malloc(len);
    if (!csv) return fail(dir, "", "out of memory");
    gd_study_format_header(s, csv, hsize);
    char *p = csv + strlen(csv);
    for (size_t c = 0; c < n; c++)
        if (lines[c]) {
            size_t k = strlen(lines[c]);
            memcpy(p, lines[c], k);
            p += k;
        }
    *p = '\0';
    int bad = write_atomic(dir, "results.csv", csv);
    free(csv);
    if (bad) return fail_io(dir, "check the folder's permissions and free space", strerror(errno));
    char path[1200], tmp[1300], why[2048];
    snprintf(path, sizeof path, "%s/results.h5", dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    if (write_hdf5(plugin, s, tmp, lines, why, sizeof why) || rename(tmp, path)) {
        remove(tmp);
        return fail_io(path, "check the folder's permissions and free space", why);
    }
    return GD_EXIT_OK;
}

int gd_study_out_finish(gd_study_out *o)
{
    if (o->progress) draw(o, 1);
    size_t n = gd_study_ncases(o->s);
    char **lines = calloc(n ? n : 1, sizeof *lines);
    char journal[1200], why[2048];
    size_t valid;
    snprintf(journal, sizeof journal, "%s/journal.csv", o->dir);
    if (!lines || read_journal(o->s, journal, lines, &valid, NULL, why, sizeof why)) {
        free_lines(lines, n);
        return fail(journal, "", lines ? why : "out of memory");
    }
    int rc = gd_study_write_results(o->s, o->dir, lines, &o->plugin);
    free_lines(lines, n);
    if (!rc)
        fprintf(stderr,
                "geardyn study: %zu cases (%zu failed), results in %s/results.csv and .h5\n",
                o->ndone, o->nfailed, o->dir);
    return rc;
}

void gd_study_out_close(gd_study_out *o)
{
    if (o->plugin.started) pthread_join(o->plugin.thread, NULL);
    o->plugin.started = 0;
    if (o->fd >= 0) close(o->fd);
    if (o->lock_fd >= 0) close(o->lock_fd); /* releases the lock */
    o->lock_fd = -1;
    free(o->done);
    free(o->line);
    o->fd = -1;
    o->done = NULL;
    o->line = NULL;
}

/* ---- --merge DIR ---- */

int gd_study_merge(const gd_study *s, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return fail(dir, "give the --out folder of the shards", strerror(errno));
    size_t n = gd_study_ncases(s), nshards = 0, nfound = 0;
    char **lines = calloc(n ? n : 1, sizeof *lines);
    unsigned char *seen = NULL;
    int rc = lines ? 0 : fail(dir, "", "out of memory");
    struct dirent *e;
    while (!rc && (e = readdir(d))) {
        size_t i, k;
        char tail;
        if (sscanf(e->d_name, "shard-%zu-of-%zu%c", &i, &k, &tail) != 2) continue;
        if (!nshards) {
            nshards = k;
            if (!(seen = calloc(k, 1))) rc = fail(dir, "", "out of memory");
        }
        if (!rc && (k != nshards || i >= k)) {
            rc = fail(dir, "merge the shards of one run only", "shard folders of different splits");
            break;
        }
        if (rc) break;
        char sub[1200], why[2048];
        snprintf(sub, sizeof sub, "%s/%s/study.yaml", dir, e->d_name);
        char *old = slurp(sub, NULL);
        int same = old && !strcmp(old, gd_study_text(s));
        free(old);
        if (!same) {
            rc = fail(sub, "merge with the study file the shards ran", "a different study file");
            break;
        }
        snprintf(sub, sizeof sub, "%s/%s/journal.csv", dir, e->d_name);
        size_t valid;
        if (read_journal(s, sub, lines, &valid, NULL, why, sizeof why)) {
            rc = fail(sub, "", why);
            break;
        }
        seen[i] = 1;
        nfound++;
    }
    closedir(d);
    if (!rc && !nshards)
        rc = fail(dir, "run the shards with --shard I/N --out DIR first",
                  "no shard-I-of-N folders here");
    if (!rc && nfound != nshards) {
        char msg[256];
        size_t first = 0;
        while (first < nshards && seen[first])
            first++;
        snprintf(msg, sizeof msg, "%zu of %zu shards present (shard-%zu-of-%zu is missing)", nfound,
                 nshards, first, nshards);
        rc = fail(dir, "run the missing shards (or --resume them), then merge", msg);
    }
    size_t missing = 0;
    for (size_t c = 0; !rc && c < n; c++)
        if (!lines[c]) missing++;
    if (!rc && missing) {
        char msg[256];
        size_t c = 0;
        while (lines[c])
            c++;
        snprintf(msg, sizeof msg, "%zu cases not finished (the first: case %zu, shard %zu)",
                 missing, c, c % nshards);
        rc = fail(dir, "--resume the unfinished shards, then merge", msg);
    }
    if (!rc) {
        char version[128];
        snprintf(version, sizeof version, "geardyn %s\n", gd_version());
        if (write_atomic(dir, "study.yaml", gd_study_text(s)) ||
            write_atomic(dir, "version.txt", version))
            rc = fail(dir, "check the folder's permissions", strerror(errno));
    }
    if (!rc) rc = gd_study_write_results(s, dir, lines, NULL);
    if (!rc)
        fprintf(stderr,
                "geardyn study: merged %zu shards, %zu cases, into %s/results.csv and .h5\n",
                nshards, n, dir);
    free(seen);
    free_lines(lines, n);
    return rc;
}
