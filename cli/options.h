/* Table-driven command-line options: each command describes its options in one static
 * const table (gd_cli_opt rows: name, kind of value, the field it fills, help text), and
 * one generic parser fills the command's argument struct from argv and prints the help,
 * generated from the same table, so the help cannot drift from what is parsed.
 *
 * Every failure is a usage error on stderr ("geardyn CMD: ...", "see 'geardyn CMD
 * --help'", exit 2) naming the option and the fix; an unknown option names the closest
 * valid one. Long options may be abbreviated and written --name=value (getopt_long).
 *
 * Ownership and threads: tables are static const; the strings stored in the argument
 * struct are argv's (nothing is allocated). gd_cli_parse uses getopt_long's globals:
 * one thread, one parse at a time. */
#ifndef GD_CLI_OPTIONS_H
#define GD_CLI_OPTIONS_H
#include <stddef.h>
#include <stdio.h>
#include "geardyn/units.h" /* GD_QTY_ANGULAR_SPEED in GD_CLI_ROW_SPEED */

typedef enum gd_cli_kind {
    GD_CLI_FLAG,     /* no value: the int at .field becomes 1 */
    GD_CLI_CLEAR,    /* no value: the int at .field becomes 0 (--no-...) */
    GD_CLI_VALUE,    /* no value: the int (or enum) at .field becomes .ival */
    GD_CLI_STRING,   /* text: the const char * at .field (the last one given wins) */
    GD_CLI_LIST,     /* repeatable text: const char *[.hi] at .field, the int count at .aux */
    GD_CLI_SETS,     /* repeatable --set PATH=VALUE: the gd_cli_sets at .field */
    GD_CLI_INT,      /* whole number in [.lo, .hi] into the int at .field; .word gives .ival */
    GD_CLI_CHOICE,   /* one of .word's '|'-separated words: its index into the int at .field */
    GD_CLI_QUANTITY, /* number with units of kind .qty (gd_qty) into the double at .field,
                      * .lo: GD_CLI_ABOVE_ZERO or GD_CLI_ZERO_OR_MORE; the int at .aux (when
                      * not 0) becomes 1; .example in the error's hint */
    GD_CLI_CALL,     /* .call(cmd, value, &field): the command's own parser, 0 or exit code */
} gd_cli_kind;

enum { GD_CLI_ABOVE_ZERO = 1, GD_CLI_ZERO_OR_MORE = 2, GD_CLI_MAX_OPTS = 64 };

typedef struct gd_cli_opt {
    const char *name; /* without the leading "--"; NULL ends the table */
    gd_cli_kind kind;
    size_t field;     /* offsetof(the command's argument struct, member) */
    const char *meta; /* the value in the help ("VALUE", "N|all"); NULL for flags */
    const char *help; /* one paragraph, wrapped by the help printer */
    const char *def;  /* the default shown in the help, or NULL */
    long lo, hi;
    int ival;
    const char *word;     /* INT: a word taken in place of a number; CHOICE: "a|b|c" */
    int qty;              /* QUANTITY: gd_qty */
    const char *example;  /* QUANTITY: a good value, for the error's hint */
    size_t aux;           /* LIST: offsetof its count; QUANTITY: of its "given" int (0: none,
                           * so never the struct's first member) */
    int required;         /* the command fails without it */
    int once;             /* given twice is an error */
    const char *excludes; /* the name of an option it cannot go with */
    char letter;          /* a short form (-q), or 0 */
    int (*call)(const char *cmd, const char *value, void *field);
} gd_cli_opt;

typedef struct gd_cli_command {
    const char *name;    /* "modal" */
    const char *args;    /* the positional argument: "MODEL.yaml" */
    const char *missing; /* no (or not one) positional: default "give exactly one model file" */
    const char *several; /* more than one (default: .missing) */
    const char *more;    /* further usage lines, printed as they are, or NULL */
    const char *about;   /* the paragraphs between the usage and the options */
    int probes;          /* 1: about is followed by the force outputs of the element kinds
                            (PROBE:NAME[.DIR] and what it measures, from the registry) */
    const char *footer;  /* printed after the options, or NULL */
    const gd_cli_opt *opts;
} gd_cli_command;

/* Fills args from argv[1..] by c's table and sets *file to the one positional argument.
 * 0 on success; -1 after printing the help (--help, -h: the command exits 0); otherwise
 * the exit code of the usage error it reported. Options not given leave their field as
 * the caller set it (the defaults). */
int gd_cli_parse(const gd_cli_command *c, int argc, char **argv, void *args, const char **file);
/* As gd_cli_parse for a command of several positional arguments (at least min_files):
 * *files points into argv at the first, *nfiles of them, in their order. */
int gd_cli_parse_files(const gd_cli_command *c, int argc, char **argv, void *args, int min_files,
                       char ***files, int *nfiles);
/* The help of c, generated from its table. */
void gd_cli_help(const gd_cli_command *c, FILE *f);

/* One row: name, kind, field (offsetof), meta, help, then any other member by name
 * (".def = ..."; the help is the first of the variable arguments, which C11 wants). */
#define GD_CLI_ROW(nm, k, f, mt, ...)                                                              \
    {                                                                                              \
        .name = nm, .kind = k, .field = f, .meta = mt, .help = __VA_ARGS__                         \
    }

/* Rows shared by the commands (T: the argument struct, m: its member). */
#define GD_CLI_ROW_COUPLING(T, m)                                                                  \
    GD_CLI_ROW("coupling", GD_CLI_STRING, offsetof(T, m), "LEVEL",                                 \
               "torsional | lateral-torsional | full: every mesh's level")
#define GD_CLI_ROW_DOFS(T, sets)                                                                   \
    GD_CLI_ROW("dofs", GD_CLI_STRING, offsetof(T, sets.dofs), "LIST",                              \
               "keep only these node DOFs, e.g. x,y,rz")
#define GD_CLI_ROW_SET(T, sets)                                                                    \
    GD_CLI_ROW("set", GD_CLI_SETS, offsetof(T, sets), "PATH=VALUE",                                \
               "change a value of the model file, e.g. --set meshes.mesh.stiffness=3e8N/m "        \
               "(repeatable; docs/model-format.md)")
#define GD_CLI_ROW_MODEL(T, coupling, sets)                                                        \
    GD_CLI_ROW_COUPLING(T, coupling), GD_CLI_ROW_DOFS(T, sets), GD_CLI_ROW_SET(T, sets)
#define GD_CLI_ROW_JSON(T, m)                                                                      \
    GD_CLI_ROW("json", GD_CLI_FLAG, offsetof(T, m), NULL, "print one JSON object on stdout")
#define GD_CLI_ROW_OUT(T, m, ...)                                                                  \
    GD_CLI_ROW("out", GD_CLI_STRING, offsetof(T, m), "DIR", __VA_ARGS__)
#define GD_CLI_ROW_THREADS(T, m, over)                                                             \
    GD_CLI_ROW("threads", GD_CLI_INT, offsetof(T, m), "N", "parallel threads over " over,          \
               .def = "all cores", .lo = 1, .hi = 4096)
#define GD_CLI_ROW_PLOT(T, m)                                                                      \
    GD_CLI_ROW("plot", GD_CLI_STRING, offsetof(T, m), "FILE",                                      \
               "the standard figure: FILE.svg, FILE.png, FILE.pdf (static) or FILE.html "          \
               "(interactive, self-contained; docs/plots.md)")
#define GD_CLI_ROW_UNITS(T, m)                                                                     \
    GD_CLI_ROW("units", GD_CLI_STRING, offsetof(T, m), "LIST",                                     \
               "units of the tables and plot axes: rpm or rad/s for speed, Hz or rad/s for "       \
               "frequency (e.g. rpm,Hz)",                                                          \
               .def = "the units you wrote")
#define GD_CLI_ROW_SPEED(T, m, given, ...)                                                         \
    GD_CLI_ROW("speed", GD_CLI_QUANTITY, offsetof(T, m), "VALUE", __VA_ARGS__,                     \
               .lo = GD_CLI_ZERO_OR_MORE, .qty = GD_QTY_ANGULAR_SPEED, .example = "3000rpm",       \
               .aux = given)
#define GD_CLI_ROW_EIG_METHOD(T, m, h)                                                             \
    GD_CLI_ROW("method", GD_CLI_CHOICE, offsetof(T, m), "M", h, .def = "auto",                     \
               .word = "auto|dense|sparse")

#endif
