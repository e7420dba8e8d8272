/* geardyn study (cmd_study.c): the run's folder, its journal and results
 * (study_output.c), the HDF5 table (study_hdf5.c) and the MPI driver (study_mpi.c,
 * built into geardyn-mpi only). */
#ifndef GD_STUDY_CLI_H
#define GD_STUDY_CLI_H
#include <pthread.h>
#include <stddef.h>

#include "geardyn/study.h"

/* The HDF5 writer plugin (geardyn-hdf5.so), loaded in a background thread while the
 * cases run: loading HDF5 and the libraries it pulls in takes ~15 ms, a third of a
 * 200-case study of a small model. */
typedef struct gd_hdf5_plugin {
    pthread_t thread;
    int started;
    void *handle; /* NULL when loading failed (why says why) */
    char why[1024];
} gd_hdf5_plugin;
/* Starts loading (p->started stays 0 if no thread could be made: loaded when needed). */
void gd_hdf5_plugin_start(gd_hdf5_plugin *p);

/* A run's folder: study.yaml, version.txt, journal.csv (one line per finished case,
 * appended with one write each, so a killed run leaves whole lines plus at most one
 * cut line, dropped on --resume), and at the end results.csv and results.h5. */
typedef struct gd_study_out {
    const gd_study *s;
    char dir[1024];
    int fd;                /* journal, O_APPEND */
    int lock_fd;           /* DIR/.lock, flock'd for the run (-1: none) */
    unsigned char *done;   /* per case: in the journal */
    size_t shard, nshards; /* this run does the cases c with c % nshards == shard */
    size_t total, ndone, nfailed, resumed;
    int progress; /* draw the progress bar (stderr is a terminal) */
    double t0, last_draw;
    char *line; /* scratch for one row */
    size_t line_size;
    gd_hdf5_plugin plugin;
} gd_study_out;

/* Opens dir for the run (creating it, or continuing its journal with resume). Returns
 * an exit code (0 ok, 2 bad input, with the error reported). */
int gd_study_out_open(gd_study_out *o, const gd_study *s, const char *dir, size_t shard,
                      size_t nshards, int resume, int progress);
/* The cases of this run not in the journal yet (malloc'd, *n of them). */
size_t *gd_study_out_todo(const gd_study_out *o, size_t *n);
/* gd_study_sink: appends the row to the journal, counts it, draws the progress. */
int gd_study_out_sink(void *o, const gd_study_row *row);
/* Writes results.csv and results.h5 from the journal; exit code. */
int gd_study_out_finish(gd_study_out *o);
void gd_study_out_close(gd_study_out *o);

/* Joins the shard folders DIR/shard-I-of-N into DIR's results; exit code. */
int gd_study_merge(const gd_study *s, const char *dir);

/* Writes the rows (lines[c] for every case c that has one, in case order) as
 * DIR/results.csv and DIR/results.h5, each written to a temporary name and renamed,
 * with the plugin p (started or not; NULL: loaded here). Exit code. */
int gd_study_write_results(const gd_study *s, const char *dir, char *const *lines,
                           gd_hdf5_plugin *p);
/* results.h5: the table as one compound dataset (study_hdf5.c, built as the plugin
 * geardyn-hdf5.so that study_output.c loads). 0 or -1 with why set. */
int gd_study_write_hdf5(const gd_study *s, const char *path, char *const *lines, char *why,
                        size_t why_size);

/* `--plot FILE`: DIR/results.csv drawn, each output over the first parameter, one curve
 * per combination of the others (study_plot.c); exit code. */
int gd_cli_study_plot(const gd_study *s, const char *dir, const char *path);
/* The cases of this run (shard) over nthreads OpenMP threads; exit code. */
int gd_study_run_local(const gd_study *s, const char *dir, size_t shard, size_t nshards, int resume,
                       int progress, int nthreads);

/* The MPI driver (study_mpi.c): rank 0 keeps the folder and hands out cases, the
 * other ranks run them. Exit code. */
int gd_study_mpi(const gd_study *s, const char *dir, size_t shard, size_t nshards, int resume,
                 int progress, int nthreads);
/* MPI_Init (returns this rank) and MPI_Finalize. */
int gd_study_mpi_init(void);
void gd_study_mpi_finalize(void);
#endif
