/* The table-driven option parser (cli/options.c) on a toy command whose table has one row
 * of every kind: the fields it fills, its usage errors (their exit code and the words that
 * name the option and the fix) and the help generated from the table. The parser is
 * compiled in (it is part of the geardyn program, not of the library). */
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include "../../cli/cli_model.c"
#include "../../cli/cli_util.c"
#include "../../cli/options.c"
#include "cli_support.h"
#include "harness.h"

typedef struct toy_args {
    const char *file, *name, *items[2];
    int nitems, flag, keep, kind, count, choice, has_load, pair[2];
    double speed, load;
    gd_cli_sets sets;
} toy_args;

/* "A,B": two whole numbers */
static int parse_pair(const char *cmd, const char *text, void *field)
{
    int *p = field;
    if (sscanf(text, "%d,%d", &p[0], &p[1]) != 2)
        return gd_cli_usage_error(cmd, "--pair: '%s' is not A,B", text);
    return 0;
}

#define F(m) offsetof(toy_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("name", GD_CLI_STRING, F(name), "X", "a name", .required = 1, .once = 1),
    GD_CLI_ROW("item", GD_CLI_LIST, F(items), "X", "an item", .aux = F(nitems), .hi = 2),
    GD_CLI_ROW("flag", GD_CLI_FLAG, F(flag), NULL, "a flag", .letter = 'f'),
    GD_CLI_ROW("no-keep", GD_CLI_CLEAR, F(keep), NULL, "do not keep"),
    GD_CLI_ROW("undamped", GD_CLI_VALUE, F(kind), NULL, "kind 1", .ival = 1, .excludes = "damped"),
    GD_CLI_ROW("damped", GD_CLI_VALUE, F(kind), NULL, "kind 2", .ival = 2, .excludes = "undamped"),
    GD_CLI_ROW("count", GD_CLI_INT, F(count), "N|all", "how many", .lo = 1, .hi = 100,
               .word = "all", .ival = 0),
    GD_CLI_ROW("choice", GD_CLI_CHOICE, F(choice), "C", "one of three", .def = "a",
               .word = "a|b|c"),
    GD_CLI_ROW_SPEED(toy_args, speed, 0, "a speed"),
    GD_CLI_ROW("load", GD_CLI_QUANTITY, F(load), "TORQUE", "a torque", .lo = GD_CLI_ABOVE_ZERO,
               .qty = GD_QTY_TORQUE, .example = "20Nm", .aux = F(has_load)),
    GD_CLI_ROW("pair", GD_CLI_CALL, F(pair), "A,B", "two numbers", .call = parse_pair),
    GD_CLI_ROW_SET(toy_args, sets),
    {0}};
static const gd_cli_command CMD = {.name = "toy",
                                   .args = "MODEL.yaml",
                                   .opts = OPTS,
                                   .about = "A toy command.\n",
                                   .footer = "The end.\n"};

static char out_text[16384], err_text[4096];
static size_t out_len; /* bytes written to stdout (a NUL byte would end out_text early) */

/* Reads fd's file from the start into buf; the bytes read. */
static size_t slurp_fd(int fd, char *buf, size_t size)
{
    lseek(fd, 0, SEEK_SET);
    ssize_t n = read(fd, buf, size - 1);
    buf[n > 0 ? n : 0] = '\0';
    return n > 0 ? (size_t)n : 0;
}

/* Parses "toy WORDS..." (split at spaces) into *a (reset to the defaults first), with
 * stdout and stderr captured into out_text and err_text. The parser's return. */
static int parse(const char *line, toy_args *a)
{
    static char buf[1024];
    char *argv[64];
    int argc = 0;
    snprintf(buf, sizeof buf, "toy %s", line);
    for (char *tok = strtok(buf, " "); tok && argc < 63; tok = strtok(NULL, " "))
        argv[argc++] = tok;
    argv[argc] = NULL;
    *a = (toy_args){.keep = 1, .count = -1};
    char outp[] = "/tmp/gd_opts_out_XXXXXX", errp[] = "/tmp/gd_opts_err_XXXXXX";
    int fo = mkstemp(outp), fe = mkstemp(errp);
    fflush(stdout);
    fflush(stderr);
    int so = dup(1), se = dup(2);
    dup2(fo, 1);
    dup2(fe, 2);
    int rc = gd_cli_parse(&CMD, argc, argv, a, &a->file);
    fflush(stdout);
    fflush(stderr);
    dup2(so, 1);
    dup2(se, 2);
    close(so);
    close(se);
    out_len = slurp_fd(fo, out_text, sizeof out_text);
    slurp_fd(fe, err_text, sizeof err_text);
    close(fo);
    close(fe);
    unlink(outp);
    unlink(errp);
    return rc;
}

static int has(const char *text, const char *word)
{
    if (strstr(text, word)) return 1;
    fprintf(stderr, "  expected \"%s\" in:\n%s\n", word, text);
    return 0;
}

TEST(every_kind_fills_its_field)
{
    toy_args a;
    CHECK(parse("--flag m.yaml --no-keep --name n1 --item i1 --item i2 --damped --count 7 "
                "--choice c --speed 3000rpm --load 2kN*m --pair 4,5 --set a=1 --set b=2",
                &a) == 0);
    CHECK(err_text[0] == '\0' && out_text[0] == '\0');
    CHECK_STR(a.file, "m.yaml"); /* the positional, options on both sides of it */
    CHECK_STR(a.name, "n1");
    CHECK(a.nitems == 2);
    CHECK_STR(a.items[0], "i1");
    CHECK_STR(a.items[1], "i2");
    CHECK(a.flag == 1 && a.keep == 0 && a.kind == 2 && a.count == 7 && a.choice == 2);
    /* 3000 rpm = 3000 * 2 pi / 60 rad/s; units conversion is exact to rounding */
    CHECK_REL(a.speed, 100 * M_PI, 1e-14);
    CHECK_REL(a.load, 2000.0, 1e-14);
    CHECK(a.has_load == 1);
    CHECK(a.pair[0] == 4 && a.pair[1] == 5);
    CHECK(a.sets.nset == 2);
    CHECK_STR(a.sets.set[1], "b=2");
}

TEST(defaults_abbreviations_and_equals)
{
    toy_args a;
    CHECK(parse("m.yaml --name=n2", &a) == 0);
    /* options not given keep the caller's defaults */
    CHECK(a.flag == 0 && a.keep == 1 && a.kind == 0 && a.count == -1 && a.has_load == 0);
    CHECK(a.nitems == 0 && a.sets.nset == 0 && a.speed == 0);
    CHECK_STR(a.name, "n2");
    CHECK(parse("m.yaml --name x --cou all --ch=b --sp 10", &a) == 0);
    CHECK(a.count == 0); /* the word gives .ival */
    CHECK(a.choice == 1);
    CHECK(a.speed == 10.0);                      /* a plain number is rad/s */
    CHECK(parse("m.yaml --name x -f", &a) == 0); /* the short form */
    CHECK(a.flag == 1);
}

TEST(unknown_option_names_the_closest)
{
    toy_args a;
    CHECK(parse("m.yaml --name x --cuont 3", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "geardyn toy: unknown option '--cuont' (did you mean --count?)"));
    CHECK(has(err_text, "see 'geardyn toy --help'"));
    CHECK(parse("m.yaml --name x --zzzzzzzz", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "unknown option '--zzzzzzzz'\n")); /* nothing close: no guess */
    CHECK(parse("m.yaml --name x --s 3", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "option '--s' is ambiguous: --speed, --set"));
    CHECK(parse("m.yaml --name x -q", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "unknown option '-q'"));
}

TEST(missing_and_bad_values_name_the_option_and_the_fix)
{
    toy_args a;
    CHECK(parse("m.yaml --name x --count", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "option '--count' needs a value (--count N|all)"));
    CHECK(parse("m.yaml --name x --count 0", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--count: '0' is not a whole number from 1 to 100 or 'all'"));
    CHECK(parse("m.yaml --name x --choice d", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--choice: 'd' is not a, b or c"));
    CHECK(parse("m.yaml --name x --speed 3mm", &a) == GD_EXIT_INPUT); /* a length, not a speed */
    CHECK(has(err_text, "--speed: ") && has(err_text, "'mm'") &&
          has(err_text, "(e.g. --speed 3000rpm)"));
    CHECK(parse("m.yaml --name x --speed -3", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--speed: give a speed of zero or more (e.g. --speed 3000rpm)"));
    CHECK(parse("m.yaml --name x --load 0Nm", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--load: must be positive (e.g. --load 20Nm)"));
    CHECK(parse("m.yaml --name x --pair 4", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--pair: '4' is not A,B"));
    CHECK(parse("m.yaml --name x --set", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "option '--set' needs a value (--set PATH=VALUE)"));
}

TEST(flag_with_a_value_is_refused)
{
    toy_args a;
    CHECK(parse("m.yaml --name x --flag=1", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "option '--flag' takes no value: write --flag alone"));
    CHECK(a.flag == 0);
}

TEST(repeated_options)
{
    toy_args a;
    /* text: the last wins; a list and --set accumulate; a list has its limit */
    CHECK(parse("m.yaml --name x --speed 1 --speed 2", &a) == 0);
    CHECK(a.speed == 2.0);
    CHECK(parse("m.yaml --name x --item 1 --item 2 --item 3", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--item: at most 2 values"));
    CHECK(parse("m.yaml --name x --name y", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "give one --name"));
    CHECK(parse("m.yaml --name x --undamped --damped", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--undamped and --damped exclude each other"));
    CHECK(parse("m.yaml --name x --damped --undamped", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--undamped and --damped exclude each other"));
    CHECK(parse("m.yaml --name x --damped --damped", &a) == 0);
}

TEST(positional_and_required)
{
    toy_args a;
    CHECK(parse("--name x", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "give exactly one model file"));
    CHECK(parse("a.yaml b.yaml --name x", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "give exactly one model file"));
    CHECK(parse("a.yaml", &a) == GD_EXIT_INPUT);
    CHECK(has(err_text, "--name X is required"));
}

TEST(help_is_generated_from_the_table)
{
    toy_args a;
    CHECK(parse("--help", &a) == -1);
    CHECK(err_text[0] == '\0');
    CHECK(has(out_text, "usage: geardyn toy MODEL.yaml --name X [--item X]... [--flag]"));
    CHECK(out_len > 0 && strlen(out_text) == out_len); /* text only, no NUL byte */
    CHECK(has(out_text, "[--set PATH=VALUE]..."));
    CHECK(has(out_text, "\nA toy command.\n\n"));
    /* every row of the table, with its help text and default */
    for (const gd_cli_opt *o = OPTS; o->name; o++) {
        char line[128];
        snprintf(line, sizeof line, "\n  %s--%s%s%s ", o->letter ? "-f, " : "", o->name,
                 o->meta ? " " : "", o->meta ? o->meta : "");
        CHECK(has(out_text, line));
        snprintf(line, sizeof line, "%.20s", o->help);
        CHECK(has(out_text, line));
    }
    CHECK(has(out_text, "a name (required)"));
    CHECK(has(out_text, "one of three (default: a)"));
    CHECK(has(out_text, "\nThe end.\n"));
    /* no line past the help's width */
    for (const char *p = out_text; *p;) {
        size_t len = strcspn(p, "\n");
        CHECK(len <= HELP_WIDTH);
        p += len + (p[len] == '\n');
    }
    CHECK(parse("m.yaml -h", &a) == -1);
    CHECK(has(out_text, "usage: geardyn toy"));
}

/* The commands on tables, through the program: the help of each lists the options of its
 * table, and a misspelt option is named with the closest one, exit 2, nothing on stdout. */
TEST(the_commands_name_the_closest_option)
{
    static const struct {
        const char *cmd, *typo, *meant;
    } CASES[] = {
        {"check", "--jsno", "--json"},
        {"modal", "--mdoes 3", "--modes"},
        {"static", "--torqe 1", "--torque"},
        {"campbell", "--speds 0:1:2", "--speeds"},
        {"frf", "--outptu a.x", "--output"},
        {"unbalance", "--orbit-sped 1", "--orbit-speed"},
        {"matrices", "--fromat mtx", "--format"},
        {"mesh-stiffness", "--slcies 3", "--slices"},
        {"study", "--reusme", "--resume"},
    };
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; i++) {
        run(&s, &r, "%s --help", CASES[i].cmd);
        CHECK(r.code == 0 && contains(r.out, "usage: geardyn ") && contains(r.out, CASES[i].meant));
        run_free(&r);
        run(&s, &r, "%s examples/chen1998_gear_pair.yaml %s", CASES[i].cmd, CASES[i].typo);
        char want[96];
        snprintf(want, sizeof want, "(did you mean %s?)", CASES[i].meant);
        CHECK(r.code == 2 && r.out[0] == '\0' && has(r.err, want));
        run_free(&r);
    }
    scratch_close(&s);
}

RUN_TESTS(T(the_commands_name_the_closest_option), T(every_kind_fills_its_field),
          T(defaults_abbreviations_and_equals), T(unknown_option_names_the_closest),
          T(missing_and_bad_values_name_the_option_and_the_fix), T(flag_with_a_value_is_refused),
          T(repeated_options), T(positional_and_required), T(help_is_generated_from_the_table))
