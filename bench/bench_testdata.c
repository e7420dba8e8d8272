/* Test data speed: reading a 1000-FRF, 4096-line UFF 58b file (complex single, the
 * tests' writer from the dataset description) against reading its bytes alone, and a
 * 60-order LSCF stabilisation diagram of 12 FRFs against one pass over their values.
 * usage: bench_testdata (run from the source folder: it reads examples/rig2018.yaml) */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "../tests/uff_support.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(void)
{
    synth sy;
    if (!synth_make(&sy, 1.2, 0.02, 12, 4097, 0.25, 36)) {
        fprintf(stderr, "bench_testdata: cannot make the synthetic FRFs (run from the source "
                        "folder)\n");
        return 1;
    }
    char path[256];
    snprintf(path, sizeof path, "/tmp/gd_bench_testdata_%d.uff", (int)getpid());
    FILE *fp = fopen(path, "wb");
    if (!fp) return 1;
    for (int j = 0; j < 1000; j++) {
        int s = j % 12;
        uff_frf h = {"bench",
                     j + 1,
                     2,
                     2,
                     2,
                     12,
                     "m/s^2",
                     "N",
                     4096,
                     0.25,
                     0.25,
                     sy.re + (size_t)s * sy.n + 1,
                     sy.im + (size_t)s * sy.n + 1};
        uff_write58(fp, &h, 1, 5);
    }
    fclose(fp);
    /* floor: the file's bytes read into memory */
    double t0 = now();
    fp = fopen(path, "rb");
    size_t bytes = 0, got;
    static char buf[1 << 20];
    while ((got = fread(buf, 1, sizeof buf, fp)) > 0)
        bytes += got;
    fclose(fp);
    double t_floor = now() - t0;
    const char *p[1] = {path};
    gd_testdata *td;
    gd_error err;
    t0 = now();
    if (gd_testdata_read(1, p, 0, &td, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    double t_read = now() - t0;
    printf("UFF 58b read: %d FRFs x %d lines (%.1f MB) in %.3f s; bytes alone %.4f s (ratio "
           "%.1f)\n",
           td->nfunctions, td->functions[0].n, bytes / 1e6, t_read, t_floor, t_read / t_floor);
    gd_testdata_free(td);
    unlink(path);
    /* the stabilisation diagram: 12 FRFs, orders 1..60 */
    snprintf(path, sizeof path, "/tmp/gd_bench_testdata_%d_12.uff", (int)getpid());
    synth_write_uff(&sy, path, 1, 6);
    if (gd_testdata_read(1, p, 0, &td, &err)) return 1;
    unlink(path);
    const gd_td_function *f[12];
    for (int j = 0; j < 12; j++)
        f[j] = &td->functions[j];
    t0 = now();
    double sum = 0;
    for (int j = 0; j < 12; j++)
        for (int k = 0; k < f[j]->n; k++)
            sum += f[j]->re[k] * f[j]->re[k] + f[j]->im[k] * f[j]->im[k];
    t_floor = now() - t0;
    gd_ema_options o;
    gd_ema_options_init(&o);
    o.max_order = 60;
    gd_ema_result *r;
    t0 = now();
    if (gd_ema_lscf(12, f, &o, &r, &err)) return 1;
    double t_lscf = now() - t0;
    printf("LSCF stabilisation: 12 FRFs x %d lines, orders 1-60 (%d poles, %d modes) in %.3f "
           "s; one pass over the values %.5f s (ratio %.0f)%s\n",
           r->nlines, r->npoles, r->nmodes, t_lscf, t_floor, t_lscf / t_floor, sum > 0 ? "" : " ");
    gd_ema_free(r);
    gd_testdata_free(td);
    synth_free(&sy);
    return 0;
}
