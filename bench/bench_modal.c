/* Times geardyn's modal analysis against the bare LAPACK eigen-solve of the same
 * state-space matrix. Prints figures; asserts nothing. */
#include <lapacke.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/modal.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* CPU time of the calling thread: the floor of bench/bench_python.py is measured on a
 * shared machine, where wall time counts the waits for a core too. */
static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* The C floor of bench/bench_python.py: CPU microseconds per gd_modal_solve +
 * gd_modal_free at speed 0 with the CLI's default mode count, best of 7 batches. */
static int loop(const gd_system *s, int reps)
{
    gd_error err;
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.nmodes = s->ndof <= 30 ? 0 : 20;
    o.want_left = 0;
    double best = 1e30;
    for (int b = 0; b < 7; b++) {
        double t0 = cpu_now();
        for (int r = 0; r < reps; r++) {
            gd_modal_result *res;
            if (gd_modal_solve(s, &o, &res, &err)) return 1;
            gd_modal_free(res);
        }
        double t = (cpu_now() - t0) / reps;
        if (t < best) best = t;
    }
    printf("%.3f\n", best * 1e6);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_modal MODEL [SPEED_RAD_S] [REPEATS]\n"
                        "       bench_modal MODEL --loop SOLVES_PER_BATCH\n");
        return 2;
    }
    double speed = argc > 2 ? atof(argv[2]) : 0;
    int reps = argc > 3 ? atoi(argv[3]) : 3;
    gd_error err;
    gd_model *m;
    gd_system *s;
    double t0 = now();
    if (gd_model_load(argv[1], &m, &err) || gd_system_build(m, &s, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    double t_build = now() - t0;
    if (argc > 3 && !strcmp(argv[2], "--loop")) {
        int rc = loop(s, atoi(argv[3]));
        gd_system_free(s);
        gd_model_free(m);
        return rc;
    }
    int n = s->ndof, n2 = 2 * n;
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = speed;
    o.nmodes = 20;
    o.want_left = 0;
    double best_modal = 1e30, best_left = 1e30, best_lapack = 1e30;
    for (int r = 0; r < reps; r++) {
        gd_modal_result *res;
        t0 = now();
        if (gd_modal_solve(s, &o, &res, &err)) return 1;
        double t = now() - t0;
        if (t < best_modal) best_modal = t;
        gd_modal_free(res);
        o.want_left = 1;
        t0 = now();
        if (gd_modal_solve(s, &o, &res, &err)) return 1;
        t = now() - t0;
        if (t < best_left) best_left = t;
        gd_modal_free(res);
        o.want_left = 0;
    }
    /* the bare eigen-solve: dgeev of a 2n x 2n companion-form matrix built from the
     * same M, D, K (mass-normalised exactly as geardyn does; the build is not timed) */
    double *M = malloc(sizeof(double) * n * n), *D = malloc(sizeof(double) * n * n),
           *K = malloc(sizeof(double) * n * n);
    gd_system_dense(s, speed, M, D, K);
    LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', n, M, n);
    double *A = calloc((size_t)n2 * n2, sizeof *A), *A0 = calloc((size_t)n2 * n2, sizeof *A0);
    double *wr = malloc(sizeof(double) * n2), *wi = malloc(sizeof(double) * n2);
    double *VR = malloc(sizeof(double) * n2 * n2);
    for (int j = 0; j < n; j++) {
        A0[j + (size_t)(n + j) * n2] = 1.0;
        for (int i = 0; i < n; i++) {
            A0[n + i + (size_t)j * n2] = -K[i + (size_t)j * n] / M[0];
            A0[n + i + (size_t)(n + j) * n2] = -D[i + (size_t)j * n] / M[0];
        }
    }
    for (int r = 0; r < reps; r++) {
        memcpy(A, A0, sizeof(double) * n2 * n2);
        t0 = now();
        LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', n2, A, n2, wr, wi, NULL, n2, VR, n2);
        double t = now() - t0;
        if (t < best_lapack) best_lapack = t;
    }
    printf("model            %s (%d DOFs, %d states, speed %g rad/s)\n", argv[1], n, n2, speed);
    printf("load + assemble  %8.4f s\n", t_build);
    printf("modal (20 modes) %8.4f s   right vectors, as `geardyn modal`\n", best_modal);
    printf("modal + left     %8.4f s   with bi-orthonormal left vectors\n", best_left);
    printf("bare dgeev       %8.4f s   LAPACK alone on the same-size matrix\n", best_lapack);
    printf("ratio modal/dgeev          %.3f\n", best_modal / best_lapack);
    free(M);
    free(D);
    free(K);
    free(A);
    free(A0);
    free(wr);
    free(wi);
    free(VR);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
