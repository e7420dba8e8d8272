/* One process's share of a study: its shard's cases not yet in the journal, run over
 * threads into the output folder (study_output.c), the journal and results written as
 * the cases finish. `geardyn study` runs it directly; under MPI each rank of one
 * (study_mpi.c) does. */
#include <stdio.h>
#include <stdlib.h>

#include "cli.h"
#include "study_cli.h"

int gd_study_run_local(const gd_study *s, const char *out, size_t shard, size_t nshards, int resume,
                       int progress, int nthreads)
{
    gd_study_out o;
    int rc = gd_study_out_open(&o, s, out, shard, nshards, resume, progress);
    size_t n = 0, *todo = rc ? NULL : gd_study_out_todo(&o, &n);
    if (!rc && !todo) rc = GD_EXIT_FAIL;
    gd_error err;
    if (!rc && gd_study_run(s, todo, n, nthreads, gd_study_out_sink, &o, &err))
        rc = gd_cli_report(&err);
    if (!rc && o.ndone != o.total) {
        fprintf(stderr, "geardyn study: the journal could not be written; --resume later\n");
        rc = GD_EXIT_FAIL;
    }
    if (!rc) rc = gd_study_out_finish(&o);
    free(todo);
    gd_study_out_close(&o);
    return rc;
}
