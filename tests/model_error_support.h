/* Checking located model errors: the status, the line of the offending text, the
 * field path, a word of the message and of the hint (test_model_errors.c,
 * test_hostile_input.c). */
#ifndef GD_TEST_MODEL_ERROR_SUPPORT_H
#define GD_TEST_MODEL_ERROR_SUPPORT_H
#include <stdio.h>
#include <string.h>

#include "geardyn/model.h"
#include "harness.h"

static inline void show_error(const gd_error *e, gd_status st)
{
    fprintf(stderr, "    got: status %d, %s:%d:%d, field '%s'\n    message: %s\n    hint: %s\n",
            (int)st, e->file, e->line, e->column, e->field, e->message, e->hint);
}

#define HCHECK(cond)                                                                               \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "  %s:%d: CHECK(%s) failed\n", __FILE__, at, #cond);                   \
            gd_ts_->checks_failed++;                                                               \
            bad = 1;                                                                               \
        }                                                                                          \
    } while (0)

/* Checks a filled error: status, line (0: not checked), field (NULL: not checked),
 * a word in the message and a word in the hint (NULL: not checked). */
static inline void check_error(gd_test_state *gd_ts_, int at, gd_status st, const gd_error *e,
                               gd_status want, int line, const char *field, const char *msg_word,
                               const char *hint_word)
{
    int bad = 0;
    HCHECK(st == want);
    HCHECK(e->status == want);
    if (line > 0) HCHECK(e->line == line);
    if (field) HCHECK(strcmp(e->field, field) == 0);
    if (msg_word) HCHECK(strstr(e->message, msg_word) != NULL);
    if (hint_word) HCHECK(strstr(e->hint, hint_word) != NULL);
    if (bad) show_error(e, st);
}

/* Loads yaml, which must fail with GD_EINPUT in bad.yaml at `line` (and a column). */
static inline void expect_load_error(gd_test_state *gd_ts_, int at, const char *yaml, int line,
                                     const char *field, const char *msg_word, const char *hint_word)
{
    gd_model *m = NULL;
    gd_error e;
    gd_error_clear(&e);
    gd_status st = gd_model_load_string(yaml, "bad.yaml", &m, &e);
    int bad = 0;
    HCHECK(m == NULL);
    HCHECK(strcmp(e.file, "bad.yaml") == 0);
    HCHECK(e.column > 0);
    if (bad) show_error(&e, st);
    check_error(gd_ts_, at, st, &e, GD_EINPUT, line, field, msg_word, hint_word);
    gd_model_free(m);
}

#define EXPECT_LOAD_ERROR(yaml, line, field, msg_word, hint_word)                                  \
    expect_load_error(gd_ts_, __LINE__, yaml, line, field, msg_word, hint_word)

/* Loads a model that must be valid. */
static inline gd_model *load_ok(gd_test_state *gd_ts_, const char *yaml)
{
    gd_model *m = NULL;
    gd_error e;
    gd_error_clear(&e);
    gd_status st = gd_model_load_string(yaml, "good.yaml", &m, &e);
    if (st != GD_OK) {
        fprintf(stderr, "  unexpected load failure:\n");
        show_error(&e, st);
        gd_ts_->checks_failed++;
    }
    return m;
}

#endif
