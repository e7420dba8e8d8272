/* --out DIR, replaced as a whole: the files are written into a staging folder beside
 * DIR (PARENT/.geardyn-stage-PID-XXXXXX), the entries of an existing DIR that are not
 * outputs of this run are carried into it (files hard-linked, folders moved), and the
 * staging folder then takes DIR's place in one rename (Linux renameat2 RENAME_EXCHANGE;
 * elsewhere DIR is renamed aside first, leaving an instant with no DIR but never a mix
 * of old and new files). A reader sees the old folder or the new one, never a mix.
 * SIGINT, SIGTERM and SIGHUP remove the staging folder before the process ends, and
 * wait during the commit itself (cli/signals.c's handler runs remove_stage; the stage
 * list is, with signals.c's state, the CLI's process-wide state: a signal handler has
 * nothing else to reach);
 * SIGKILL cannot be caught, so a run removes the stages that dead processes left. When
 * PARENT cannot take a staging folder (not writable, or DIR is a mount point or '.')
 * the stage goes inside DIR and the files move one by one (docs/analyses.md). A DIR that
 * is a symbolic link is followed (its target is the folder replaced, the link stays),
 * and stage removal never follows a link. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

#define STAGE_PREFIX ".geardyn-stage-"

/* What the signal handler removes: full paths, written before the count is raised. */
static struct {
    volatile sig_atomic_t active, nfiles;
    char stage[1100];
    char files[16][1200];
} g_stage;

/* The signal handler's clean-up (cli/signals.c): the stage's files, then the stage.
 * Async-signal-safe: unlink and rmdir of paths written before the count was raised. */
static void remove_stage(void)
{
    if (g_stage.active) {
        for (int i = 0; i < g_stage.nfiles; i++)
            unlink(g_stage.files[i]);
        rmdir(g_stage.stage);
    }
}

/* Removes the files (and empty folders, one level down) of folder path, then it. Never
 * follows a symbolic link: path is opened with O_NOFOLLOW (a link in its place is
 * removed as a link, its target untouched) and its entries go by unlinkat on that
 * descriptor, so nothing outside the folder itself can be reached (issue 38 H1: a stale
 * "stage" that was a link to the user's folder emptied that folder on every run). */
static void remove_folder(const char *path)
{
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) {
        struct stat sb;
        if (lstat(path, &sb) == 0 && S_ISLNK(sb.st_mode)) unlink(path);
        return;
    }
    DIR *d = fdopendir(fd);
    if (!d) {
        close(fd);
        return;
    }
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        if (unlinkat(fd, e->d_name, 0) != 0) unlinkat(fd, e->d_name, AT_REMOVEDIR);
    }
    closedir(d); /* closes fd */
    rmdir(path);
}

/* Stages in folder that a process no longer running left (SIGKILL, a crash): named
 * .geardyn-stage-PID-XXXXXX; stages of earlier versions (no PID) after an hour. */
static void remove_stale_stages(const char *folder)
{
    DIR *d = opendir(folder);
    if (!d) return;
    struct dirent *e;
    const size_t np = strlen(STAGE_PREFIX);
    while ((e = readdir(d))) {
        if (strncmp(e->d_name, STAGE_PREFIX, np)) continue;
        char path[1400];
        snprintf(path, sizeof path, "%s/%s", folder, e->d_name);
        char *end;
        long pid = strtol(e->d_name + np, &end, 10);
        struct stat sb;
        if (lstat(path, &sb) != 0) continue;
        int stale;
        if (end != e->d_name + np && *end == '-' && pid > 0 && pid <= INT_MAX) {
            stale = kill((pid_t)pid, 0) != 0 && errno == ESRCH;
        } else {
            stale = time(NULL) - sb.st_mtime > 3600;
        }
        if (!stale) continue;
        /* a stage is a folder this program made; anything else of that name (a link left
         * by an earlier version that renamed a linked --out) goes as itself */
        if (S_ISDIR(sb.st_mode))
            remove_folder(path);
        else
            unlink(path);
    }
    closedir(d);
}

/* dir without trailing slashes; parent "." or everything before the last '/'. */
static void split(const char *dir, char *clean, size_t cs, char *parent, size_t ps)
{
    snprintf(clean, cs, "%s", dir);
    size_t n = strlen(clean);
    while (n > 1 && clean[n - 1] == '/')
        clean[--n] = '\0';
    snprintf(parent, ps, "%s", clean);
    char *slash = strrchr(parent, '/');
    if (!slash)
        snprintf(parent, ps, ".");
    else
        slash[slash == parent ? 1 : 0] = '\0';
}

int gd_outdir_begin(gd_outdir *od, const char *dir, gd_error *err)
{
    memset(od, 0, sizeof *od);
    if (strlen(dir) >= sizeof od->dir - 1)
        return gd_error_set(err, GD_EINPUT, dir, 0, 0, "--out", "use a shorter path",
                            "output path too long");
    char parent[1024];
    split(dir, od->dir, sizeof od->dir, parent, sizeof parent);
    struct stat sb, pb;
    /* A symbolic link given as --out is followed: the outputs land in the folder it
     * names and the link stays (renaming DIR would otherwise replace the link itself by
     * a real folder and carry the target's files away from it). */
    if (lstat(od->dir, &sb) == 0 && S_ISLNK(sb.st_mode)) {
        char *target = realpath(od->dir, NULL);
        if (!target)
            return gd_error_set(
                err, GD_EIO, dir, 0, 0, "--out", "give a folder, or a link to an existing folder",
                "is a symbolic link whose target cannot be reached: %s", strerror(errno));
        if (strlen(target) >= sizeof od->dir - 1) {
            free(target);
            return gd_error_set(err, GD_EINPUT, dir, 0, 0, "--out", "use a shorter path",
                                "the link's target path is too long");
        }
        split(target, od->dir, sizeof od->dir, parent, sizeof parent);
        free(target);
    }
    int exists = stat(od->dir, &sb) == 0;
    if (exists && !S_ISDIR(sb.st_mode))
        return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                            "give a folder (it is created if missing)",
                            "exists and is not a folder");
    if (!exists && (stat(parent, &pb) != 0 || !S_ISDIR(pb.st_mode)))
        return gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                            "check that the parent folder exists and is writable",
                            "cannot create folder: '%s' is not a folder", parent);
    const char *base = strrchr(od->dir, '/');
    base = base ? base + 1 : od->dir;
    int odd_name = !strcmp(base, ".") || !strcmp(base, "..") || !base[0];
    /* a mount point cannot be renamed over */
    int same_fs = !exists || (stat(parent, &pb) == 0 && pb.st_dev == sb.st_dev);
    remove_stale_stages(parent);
    if (exists) remove_stale_stages(od->dir);
    /* from the stage's making to its registration for the signal handler's clean-up,
     * a signal waits (a stage made just before it would be left behind) */
    gd_cli_commit_begin();
    snprintf(od->stage, sizeof od->stage, "%s/" STAGE_PREFIX "%ld-XXXXXX", parent, (long)getpid());
    od->inside = odd_name || !same_fs || !mkdtemp(od->stage);
    if (od->inside) {
        if (!exists && mkdir(od->dir, 0777) != 0) {
            gd_error_set(err, GD_EIO, dir, 0, 0, "--out",
                         "check that the parent folder exists and is writable",
                         "cannot create folder: %s", strerror(errno));
            gd_cli_commit_end();
            return GD_EIO;
        }
        od->created = !exists;
        snprintf(od->stage, sizeof od->stage, "%s/" STAGE_PREFIX "%ld-XXXXXX", od->dir,
                 (long)getpid());
        if (!mkdtemp(od->stage)) {
            gd_error_set(err, GD_EIO, dir, 0, 0, "--out", "check that the folder is writable",
                         "cannot write into folder: %s", strerror(errno));
            od->stage[0] = '\0';
            gd_outdir_abort(od);
            gd_cli_commit_end();
            return GD_EIO;
        }
    }
    /* mkdtemp makes the folder 0700: the usual permissions, as mkdir gives */
    mode_t mask = umask(022);
    umask(mask);
    chmod(od->stage, 0777 & ~mask);
    g_stage.active = 0;
    g_stage.nfiles = 0;
    snprintf(g_stage.stage, sizeof g_stage.stage, "%s", od->stage);
    g_stage.active = 1;
    gd_cli_signals_cleanup(remove_stage);
    gd_cli_commit_end();
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
    /* a signal waits while the file is made (a worker's clean-up racing this fopen
     * would leave the file and so the stage) */
    gd_cli_commit_begin();
    if (g_stage.active && g_stage.nfiles < 16) {
        snprintf(g_stage.files[g_stage.nfiles], sizeof g_stage.files[0], "%s", path);
        g_stage.nfiles = g_stage.nfiles + 1;
    }
    FILE *f = fopen(path, "w");
    gd_cli_commit_end();
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
    int e = bad ? errno : 0;
    if (fclose(f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (bad)
        return gd_error_set(err, GD_EIO, od->dir, 0, 0, "--out", "check free space",
                            "error writing %s: %s", name, e ? strerror(e) : "write failed");
    return GD_OK;
}

static int is_output(const gd_outdir *od, const char *name)
{
    for (int i = 0; i < od->nfiles; i++)
        if (!strcmp(od->names[i], name)) return 1;
    return 0;
}

/* The entries of the existing folder that are not this run's outputs, into the stage:
 * files hard-linked, anything else moved (put back by put_back on failure). */
static int carry_over(const gd_outdir *od)
{
    DIR *d = opendir(od->dir);
    if (!d) return -1;
    struct dirent *e;
    int rc = 0;
    while (!rc && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") || is_output(od, e->d_name))
            continue;
        char from[1400], to[1400];
        snprintf(from, sizeof from, "%s/%s", od->dir, e->d_name);
        snprintf(to, sizeof to, "%s/%s", od->stage, e->d_name);
        struct stat sb;
        if (lstat(from, &sb) != 0) continue;
        if (S_ISREG(sb.st_mode) && link(from, to) == 0) continue;
        if (rename(from, to) != 0) rc = -1;
    }
    closedir(d);
    return rc;
}

/* Undoes carry_over: moved entries go back (links in the stage are removed with it). */
static void put_back(const gd_outdir *od)
{
    DIR *d = opendir(od->stage);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") || is_output(od, e->d_name))
            continue;
        char from[1400], to[1400];
        snprintf(from, sizeof from, "%s/%s", od->stage, e->d_name);
        snprintf(to, sizeof to, "%s/%s", od->dir, e->d_name);
        struct stat sb;
        if (lstat(to, &sb) != 0) rename(from, to);
    }
    closedir(d);
}

static int commit_files(gd_outdir *od, gd_error *err)
{
    char from[1200], to[1200];
    for (int i = 0; i < od->nfiles; i++) {
        snprintf(from, sizeof from, "%s/%s", od->stage, od->names[i]);
        snprintf(to, sizeof to, "%s/%s", od->dir, od->names[i]);
        if (rename(from, to) != 0) {
            gd_error_set(err, GD_EIO, to, 0, 0, "--out", "check permissions",
                         "cannot move output into place: %s", strerror(errno));
            return GD_EIO;
        }
    }
    rmdir(od->stage);
    return GD_OK;
}

static int commit_folder(gd_outdir *od, gd_error *err)
{
    if (rename(od->stage, od->dir) == 0) return GD_OK; /* DIR did not exist */
    if (carry_over(od)) {
        int e = errno;
        put_back(od);
        return gd_error_set(err, GD_EIO, od->dir, 0, 0, "--out", "check permissions",
                            "cannot carry the folder's other files over: %s", strerror(e));
    }
    if (renameat2(AT_FDCWD, od->stage, AT_FDCWD, od->dir, RENAME_EXCHANGE) == 0) {
        remove_folder(od->stage); /* the old folder, now at the stage's name */
        return GD_OK;
    }
    /* no exchange on this file system: DIR aside, the stage in, the old one removed */
    char old[1200];
    snprintf(old, sizeof old, "%s.old", od->stage);
    if (rename(od->dir, old) != 0 || rename(od->stage, od->dir) != 0) {
        int e = errno;
        if (access(od->dir, F_OK) != 0) rename(old, od->dir);
        put_back(od);
        return gd_error_set(err, GD_EIO, od->dir, 0, 0, "--out", "check permissions",
                            "cannot move the new folder into place: %s", strerror(e));
    }
    remove_folder(old);
    return GD_OK;
}

int gd_outdir_commit(gd_outdir *od, gd_error *err)
{
    /* SIGINT/SIGTERM/SIGHUP, whichever thread takes them, wait for the commit's end
     * (signals.c: a mask in this thread alone left the workers to die mid-commit) */
    gd_cli_commit_begin();
    int st = od->inside ? commit_files(od, err) : commit_folder(od, err);
    if (st) {
        gd_outdir_abort(od);
    } else {
        od->nfiles = 0;
        g_stage.active = 0;
    }
    gd_cli_commit_end();
    return st;
}

void gd_outdir_abort(gd_outdir *od)
{
    char path[1200];
    for (int i = 0; i < od->nfiles; i++) {
        snprintf(path, sizeof path, "%s/%s", od->stage, od->names[i]);
        unlink(path);
    }
    /* outside DIR the stage may also hold links to DIR's other files: all go */
    if (od->stage[0] && !od->inside) remove_folder(od->stage);
    if (od->stage[0]) rmdir(od->stage);
    /* a folder made for this run and left empty goes too: nothing half-written */
    if (od->created) rmdir(od->dir);
    od->nfiles = 0;
    g_stage.active = 0;
}
