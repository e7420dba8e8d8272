/* geardyn study under MPI (built into geardyn-mpi only, see CMakeLists.txt): rank 0
 * keeps the run's folder and journal and hands out cases; every other rank asks for
 * work, runs the cases it gets (OpenMP inside the rank) and sends back the rows.
 * Dynamic load balancing: a rank asks again as soon as it is done, and the chunks shrink
 * as the work runs out (guided: remaining / (4 workers), at most 64, at least 1), so
 * cases of very different cost still finish together. Rank 0 waits with MPI_Iprobe and
 * short sleeps rather than a blocking receive, which would spin a core that the ranks
 * need. */
#include "study_cli.h"
#ifdef GD_WITH_MPI
#include <mpi.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "study_cli.h"

enum { TAG_RESULT = 1, TAG_WORK = 2 };

int gd_study_mpi_init(void)
{
    int rank = 0;
    MPI_Init(NULL, NULL);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    return rank;
}

void gd_study_mpi_finalize(void)
{
    MPI_Finalize();
}

/* Rows packed for sending: index (u64), status (i32), outputs (doubles), message
 * length (u32) and bytes. */
typedef struct pack {
    const gd_study *s;
    unsigned char *buf;
    size_t len, cap;
} pack;

static int put(pack *p, const void *data, size_t n)
{
    if (p->len + n > p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 4096;
        while (cap < p->len + n)
            cap *= 2;
        unsigned char *more = realloc(p->buf, cap);
        if (!more) return 1;
        p->buf = more;
        p->cap = cap;
    }
    memcpy(p->buf + p->len, data, n);
    p->len += n;
    return 0;
}

static int pack_sink(void *user, const gd_study_row *row)
{
    pack *p = user;
    uint64_t idx = row->index;
    int32_t st = row->status;
    uint32_t mlen = (uint32_t)strlen(row->message);
    return put(p, &idx, 8) || put(p, &st, 4) ||
           put(p, row->outputs, 8 * (size_t)gd_study_noutputs(p->s)) || put(p, &mlen, 4) ||
           put(p, row->message, mlen);
}

/* Unpacks the rows of buf into the sink; 0, or 1 when the sink stops. */
static int unpack(const gd_study *s, const unsigned char *buf, size_t len, gd_study_row *row,
                  gd_study_out *o)
{
    size_t no = (size_t)gd_study_noutputs(s), k = 0;
    while (k + 16 + 8 * no <= len) {
        uint64_t idx;
        int32_t st;
        uint32_t mlen;
        memcpy(&idx, buf + k, 8);
        memcpy(&st, buf + k + 8, 4);
        memcpy(row->outputs, buf + k + 12, 8 * no);
        memcpy(&mlen, buf + k + 12 + 8 * no, 4);
        k += 16 + 8 * no;
        if (mlen >= sizeof row->message || k + mlen > len) return 1;
        memcpy(row->message, buf + k, mlen);
        row->message[mlen] = '\0';
        k += mlen;
        row->index = (size_t)idx;
        row->status = (gd_status)st;
        if (gd_study_out_sink(o, row)) return 1;
    }
    return 0;
}

static void pause_briefly(void)
{
    struct timespec ts = {0, 200000}; /* 0.2 ms */
    nanosleep(&ts, NULL);
}

static int master(const gd_study *s, const char *dir, size_t shard, size_t nshards, int resume,
                  int progress, int nworkers)
{
    gd_study_out o;
    int rc = gd_study_out_open(&o, s, dir, shard, nshards, resume, progress);
    size_t n = 0, next = 0, *todo = rc ? NULL : gd_study_out_todo(&o, &n);
    if (!rc && !todo) rc = GD_EXIT_FAIL;
    gd_study_row row = {0};
    if (!rc && gd_study_row_init(s, &row, NULL)) rc = GD_EXIT_FAIL;
    uint64_t *chunk = malloc(64 * sizeof *chunk);
    if (!chunk) rc = GD_EXIT_FAIL;
    unsigned char *buf = NULL;
    int active = nworkers, sink_failed = 0;
    while (active > 0) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, &st);
        if (!flag) {
            pause_briefly();
            continue;
        }
        int len = 0;
        MPI_Get_count(&st, MPI_BYTE, &len);
        unsigned char *more = realloc(buf, len > 0 ? (size_t)len : 1);
        if (more) buf = more;
        MPI_Recv(more ? buf : NULL, more ? len : 0, MPI_BYTE, st.MPI_SOURCE, TAG_RESULT,
                 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (!more || (!rc && unpack(s, buf, (size_t)len, &row, &o))) sink_failed = 1;
        size_t left = rc || sink_failed ? 0 : n - next;
        size_t k = left / (4 * (size_t)nworkers);
        k = k < 1 ? (left ? 1 : 0) : k > 64 ? 64 : k;
        for (size_t i = 0; i < k; i++)
            chunk[i] = todo[next + i];
        next += k;
        MPI_Send(chunk, (int)k, MPI_UINT64_T, st.MPI_SOURCE, TAG_WORK, MPI_COMM_WORLD);
        if (!k) active--;
    }
    if (!rc && (sink_failed || o.ndone != o.total)) {
        fprintf(stderr, "geardyn study: the journal could not be written; --resume later\n");
        rc = GD_EXIT_FAIL;
    }
    if (!rc) rc = gd_study_out_finish(&o);
    free(buf);
    free(chunk);
    free(todo);
    gd_study_row_free(&row);
    gd_study_out_close(&o);
    return rc;
}

static int worker(const gd_study *s, int nthreads)
{
    pack p = {s, NULL, 0, 0};
    uint64_t ids[64];
    size_t cases[64];
    int rc = GD_EXIT_OK;
    for (;;) {
        MPI_Send(p.buf, (int)p.len, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD);
        p.len = 0;
        MPI_Status st;
        int k = 0;
        MPI_Recv(ids, 64, MPI_UINT64_T, 0, TAG_WORK, MPI_COMM_WORLD, &st);
        MPI_Get_count(&st, MPI_UINT64_T, &k);
        if (k <= 0) break;
        for (int i = 0; i < k; i++)
            cases[i] = (size_t)ids[i];
        gd_error err;
        if (gd_study_run(s, cases, (size_t)k, nthreads, pack_sink, &p, &err)) rc = GD_EXIT_FAIL;
    }
    free(p.buf);
    return rc;
}

int gd_study_mpi(const gd_study *s, const char *dir, size_t shard, size_t nshards, int resume,
                 int progress, int nthreads)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size == 1) return gd_study_run_local(s, dir, shard, nshards, resume, progress, nthreads);
    if (rank == 0) return master(s, dir, shard, nshards, resume, progress, size - 1);
    return worker(s, nthreads > 0 ? nthreads : 1);
}
#endif
