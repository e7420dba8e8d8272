/* A minimal test harness: each test_*.c is one program of TEST()s run by ctest.
 * It prints one line per failure and the closing line "N passed, N failed". */
#ifndef GD_TEST_HARNESS_H
#define GD_TEST_HARNESS_H
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

typedef struct gd_test_state {
    int checks_failed;
} gd_test_state;

typedef void (*gd_test_fn)(gd_test_state *);
typedef struct gd_test_case {
    const char *name;
    gd_test_fn fn;
} gd_test_case;

#define TEST(name) static void name(gd_test_state *gd_ts_)

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "  %s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond);             \
            gd_ts_->checks_failed++;                                                               \
        }                                                                                          \
    } while (0)

/* |a - b| <= tol * max(|b|, floor): relative with an absolute floor. */
#define CHECK_REL(a, b, tol)                                                                       \
    do {                                                                                           \
        double a_ = (a), b_ = (b), t_ = (tol);                                                     \
        double s_ = fabs(b_) > 1e-300 ? fabs(b_) : 1.0;                                            \
        if (!(fabs(a_ - b_) <= t_ * s_)) {                                                         \
            fprintf(stderr, "  %s:%d: %s = %.12g, expected %.12g (rel tol %g, rel err %.3g)\n",    \
                    __FILE__, __LINE__, #a, a_, b_, t_, fabs(a_ - b_) / s_);                       \
            gd_ts_->checks_failed++;                                                               \
        }                                                                                          \
    } while (0)

#define CHECK_ABS(a, b, tol)                                                                       \
    do {                                                                                           \
        double a_ = (a), b_ = (b), t_ = (tol);                                                     \
        if (!(fabs(a_ - b_) <= t_)) {                                                              \
            fprintf(stderr, "  %s:%d: %s = %.12g, expected %.12g (abs tol %g)\n", __FILE__,        \
                    __LINE__, #a, a_, b_, t_);                                                     \
            gd_ts_->checks_failed++;                                                               \
        }                                                                                          \
    } while (0)

#define CHECK_STR(a, b)                                                                            \
    do {                                                                                           \
        const char *a_ = (a), *b_ = (b);                                                           \
        if (!a_ || strcmp(a_, b_) != 0) {                                                          \
            fprintf(stderr, "  %s:%d: %s = \"%s\", expected \"%s\"\n", __FILE__, __LINE__, #a,     \
                    a_ ? a_ : "(null)", b_);                                                       \
            gd_ts_->checks_failed++;                                                               \
        }                                                                                          \
    } while (0)

/* Stops the current test (e.g. a NULL result) after recording a failure. */
#define REQUIRE(cond)                                                                              \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "  %s:%d: REQUIRE(%s) failed\n", __FILE__, __LINE__, #cond);           \
            gd_ts_->checks_failed++;                                                               \
            return;                                                                                \
        }                                                                                          \
    } while (0)

/* Runs every test; "prog NAME" runs those whose name contains NAME, and
 * "prog -NAME1,NAME2" all but those (the slowest are skipped under valgrind). */
static inline int gd_test_skipped(const char *name, const char *list)
{
    const char *p = list;
    while (*p) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len && strncmp(name, p, len) == 0 && name[len] == '\0') return 1;
        p += len + (e ? 1 : 0);
    }
    return 0;
}

/* With GD_TEST_TIMES=DIR, a run of the whole program writes DIR/PROGRAM.txt: each case's
 * name and CPU seconds, its own and those of the CLI runs it waited for. `make memcheck` reads it
 * to leave the costly cases to the sanitizer build (valgrind runs code 20-170x slower). */
static inline FILE *gd_test_times_file(int argc, char **argv)
{
    const char *dir = getenv("GD_TEST_TIMES");
    if (!dir || !*dir || argc > 1) return NULL;
    const char *prog = strrchr(argv[0], '/');
    prog = prog ? prog + 1 : argv[0];
    char path[4096];
    if (snprintf(path, sizeof path, "%s/%s.txt", dir, prog) >= (int)sizeof path) return NULL;
    return fopen(path, "w");
}

static inline double gd_test_cpu_seconds(void)
{
    struct rusage own, children;
    getrusage(RUSAGE_SELF, &own);
    getrusage(RUSAGE_CHILDREN, &children);
    return (double)(own.ru_utime.tv_sec + own.ru_stime.tv_sec + children.ru_utime.tv_sec +
                    children.ru_stime.tv_sec) +
           1e-6 * (double)(own.ru_utime.tv_usec + own.ru_stime.tv_usec + children.ru_utime.tv_usec +
                           children.ru_stime.tv_usec);
}

/* With GD_TEST_MAX_CPU=S and GD_TEST_TIMES_IN=DIR (the normal build's record), a run of
 * the whole program leaves out the cases that took over S seconds of CPU there: the
 * sanitizer build runs 2-3x slower, and its run keeps to the cases under the budget
 * (`make test-asan`). Returns the recorded seconds of case name, or -1. */
static inline double gd_test_recorded_cpu(int argc, char **argv, const char *name)
{
    const char *dir = getenv("GD_TEST_TIMES_IN"), *max = getenv("GD_TEST_MAX_CPU");
    if (!dir || !*dir || !max || !*max || argc > 1) return -1;
    const char *prog = strrchr(argv[0], '/');
    prog = prog ? prog + 1 : argv[0];
    char path[4096], line[512];
    if (snprintf(path, sizeof path, "%s/%s.txt", dir, prog) >= (int)sizeof path) return -1;
    FILE *f = fopen(path, "r");
    double found = -1;
    size_t len = strlen(name);
    while (f && found < 0 && fgets(line, sizeof line, f))
        if (!strncmp(line, name, len) && line[len] == ' ') found = atof(line + len + 1);
    if (f) fclose(f);
    return found;
}

static inline int gd_test_run(const gd_test_case *cases, int n, int argc, char **argv)
{
    int passed = 0, failed = 0, budget_skipped = 0;
    FILE *times = gd_test_times_file(argc, argv);
    const char *maxs = getenv("GD_TEST_MAX_CPU");
    double max_cpu = maxs && *maxs ? atof(maxs) : -1;
    for (int i = 0; i < n; i++) {
        if (max_cpu > 0) {
            double cpu = gd_test_recorded_cpu(argc, argv, cases[i].name);
            if (cpu > max_cpu) {
                printf("skip %s (%.2f s of CPU in the normal build, over %g)\n", cases[i].name, cpu,
                       max_cpu);
                budget_skipped++;
                continue;
            }
        }
        if (argc > 1 && argv[1][0] == '-') {
            if (gd_test_skipped(cases[i].name, argv[1] + 1)) continue;
        } else if (argc > 1 && !strstr(cases[i].name, argv[1])) {
            continue;
        }
        gd_test_state st = {0};
        double start = times ? gd_test_cpu_seconds() : 0;
        cases[i].fn(&st);
        if (times) fprintf(times, "%s %.4f\n", cases[i].name, gd_test_cpu_seconds() - start);
        if (st.checks_failed) {
            fprintf(stderr, "FAIL %s\n", cases[i].name);
            failed++;
        } else {
            printf("ok   %s\n", cases[i].name);
            passed++;
        }
    }
    if (times) fclose(times);
    if (budget_skipped)
        printf("%d passed, %d failed, %d left to the normal build\n", passed, failed,
               budget_skipped);
    else
        printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}

#define RUN_TESTS(...)                                                                             \
    int main(int argc, char **argv)                                                                \
    {                                                                                              \
        static const gd_test_case cases_[] = {__VA_ARGS__};                                        \
        return gd_test_run(cases_, (int)(sizeof cases_ / sizeof cases_[0]), argc, argv);           \
    }
#define T(name)                                                                                    \
    {                                                                                              \
#name, name                                                                                \
    }

#endif
