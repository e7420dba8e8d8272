/* geardyn study STUDY.yaml: a parameter study (docs/studies.md), over the OpenMP threads
 * of one machine, over MPI ranks (geardyn-mpi, which `geardyn` starts in its place under
 * mpirun), or as one shard of a batch array, joined later by --merge. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geardyn/blas.h"
#include "cli.h"
#include "options.h"
#include "study_cli.h"

typedef struct study_shard {
    size_t i, n;
} study_shard;

typedef struct study_args {
    const char *out, *merge, *plot;
    int resume, quiet, nthreads;
    study_shard shard;
} study_args;

static int parse_shard(const char *cmd, const char *text, void *field)
{
    study_shard *sh = field;
    char buf[64];
    if (!strcmp(text, "slurm")) {
        const char *id = getenv("SLURM_ARRAY_TASK_ID"), *cnt = getenv("SLURM_ARRAY_TASK_COUNT");
        const char *min = getenv("SLURM_ARRAY_TASK_MIN");
        if (!id || !cnt)
            return gd_cli_usage_error("study", "--shard slurm: SLURM_ARRAY_TASK_ID and "
                                               "SLURM_ARRAY_TASK_COUNT are not set (not in a job "
                                               "array?)");
        snprintf(buf, sizeof buf, "%ld/%s", atol(id) - (min ? atol(min) : 0), cnt);
        text = buf;
    }
    long a, b;
    char tail;
    if (sscanf(text, "%ld/%ld%c", &a, &b, &tail) != 2 || b < 1 || a < 0 || a >= b)
        return gd_cli_usage_error(cmd, "--shard: '%s' is not I/N with 0 <= I < N", text);
    sh->i = (size_t)a;
    sh->n = (size_t)b;
    return 0;
}

#define F(m) offsetof(study_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW_OUT(study_args, out, "the run's folder",
                   .def = "STUDY's name without .yaml, + .out"),
    GD_CLI_ROW("resume", GD_CLI_FLAG, F(resume), NULL,
               "continue a run that was stopped: finished cases are kept"),
    GD_CLI_ROW("shard", GD_CLI_CALL, F(shard), "I/N|slurm",
               "run only the cases c with c mod N = I (0 <= I < N), into DIR/shard-I-of-N; "
               "`slurm` takes I and N from SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT (and "
               "_MIN)",
               .call = parse_shard),
    GD_CLI_ROW("plot", GD_CLI_STRING, F(plot), "FILE",
               "after the run: each output over the first parameter, one curve per value of "
               "the others (FILE.svg or .html; docs/studies.md)"),
    GD_CLI_ROW("merge", GD_CLI_STRING, F(merge), "DIR",
               "join DIR/shard-*-of-N into DIR/results.csv and .h5"),
    GD_CLI_ROW("threads", GD_CLI_INT, F(nthreads), "N", "OpenMP threads",
               .def = "all cores; 1 per rank under MPI", .lo = 1, .hi = 4096),
    GD_CLI_ROW("quiet", GD_CLI_FLAG, F(quiet), NULL,
               "no progress bar (it is drawn only when stderr is a terminal)"),
    {0}};
static const gd_cli_command CMD = {
    .name = "study",
    .args = "STUDY.yaml",
    .missing = "give one STUDY.yaml",
    .several = "give one STUDY.yaml, not several",
    .opts = OPTS,
    .more = "       geardyn study STUDY.yaml --merge DIR\n"
            "       mpirun -n N geardyn study STUDY.yaml [--out DIR] [--resume]\n",
    .about = "Runs the cases of a parameter study: the model with each case's parameter values\n"
             "(--set paths), the analysis, the named scalar outputs. Writes DIR/results.csv and\n"
             "DIR/results.h5 (one row per case: parameters, outputs, status, message), with\n"
             "DIR/study.yaml and DIR/version.txt beside them. A failed case is a row with its\n"
             "error; it never stops the study. Study file format: docs/studies.md.\n",
    .footer = "Exit status: 0 the study ran (failed cases are in the table), 2 bad input or "
              "usage,\n1 the run itself failed.\n"};

/* Under mpirun (or srun) the plain binary starts geardyn-mpi from its own folder, so
 * that `mpirun -n N geardyn study ...` works while `geardyn` itself does not load MPI. */
#ifndef GD_WITH_MPI
static int under_mpi(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE") || getenv("PMIX_RANK");
}

static int exec_mpi(char **argv)
{
    char self[PATH_MAX], path[PATH_MAX + 16];
    ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
    if (k > 0) {
        self[k] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) *slash = '\0';
        snprintf(path, sizeof path, "%s/geardyn-mpi", self);
        char *args[256];
        int n = 0;
        args[n++] = path;
        for (char **a = argv; *a && n < 255; a++)
            args[n++] = *a;
        args[n] = NULL;
        execv(path, args);
    }
    fprintf(stderr,
            "geardyn study: running under MPI, but geardyn-mpi was not found beside geardyn (%s)\n"
            "  build with MPI (libopenmpi-dev) or run without mpirun\n",
            strerror(errno));
    return GD_EXIT_INPUT;
}
#endif

static int study_main(int argc, char **argv)
{
    study_args a = {.shard = {0, 1}};
    const char *cmd = "study", *file;
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    const char *out = a.out, *merge = a.merge;
    int resume = a.resume, nthreads = a.nthreads;
    size_t shard = a.shard.i, nshards = a.shard.n;
    if (merge && (out || resume || nshards > 1))
        return gd_cli_usage_error(cmd, "--merge DIR takes no --out, --resume or --shard");
    if (a.plot && nshards > 1)
        return gd_cli_usage_error(cmd, "--plot draws the whole table: not with --shard");
#ifdef GD_WITH_MPI
    if (a.plot) return gd_cli_usage_error(cmd, "--plot: run without mpirun");
#endif
    if (a.plot && (rc = gd_cli_plot_check(a.plot))) return rc;
    char defout[1024];
    if (!out && !merge) {
        const char *base = strrchr(file, '/');
        base = base ? base + 1 : file;
        size_t len = strlen(base);
        if (len > 5 && !strcmp(base + len - 5, ".yaml")) len -= 5;
        snprintf(defout, sizeof defout, "%.*s.out", (int)len, base);
        out = defout;
    }
    gd_error err;
    gd_error_clear(&err);
    if (out && gd_outdir_check(out, &err)) return gd_cli_report(&err);
    gd_study *s;
    if (gd_study_load(file, &s, &err)) return gd_cli_report(&err);
    /* each case is single-threaded: the study is parallel over cases */
    gd_blas_set_threads(1);
    int progress = !a.quiet && isatty(STDERR_FILENO);
    if (merge) rc = gd_study_merge(s, merge);
#ifdef GD_WITH_MPI
    else
        rc = gd_study_mpi(s, out, shard, nshards, resume, progress, nthreads);
#else
    else
        rc = gd_study_run_local(s, out, shard, nshards, resume, progress, nthreads);
#endif
    if (!rc && a.plot) rc = gd_cli_study_plot(s, merge ? merge : out, a.plot);
    gd_study_free(s);
    return rc;
}

#ifdef GD_WITH_MPI
int gd_cmd_study(int argc, char **argv)
{
    int rank = gd_study_mpi_init();
    if (rank > 0) { /* rank 0 speaks for all */
        if (!freopen("/dev/null", "w", stderr) || !freopen("/dev/null", "w", stdout)) return 1;
    }
    int rc = study_main(argc, argv);
    gd_study_mpi_finalize();
    return rc;
}
#else
int gd_cmd_study(int argc, char **argv)
{
    if (under_mpi()) return exec_mpi(argv);
    return study_main(argc, argv);
}
#endif
