/* The geardyn command line: one file per subcommand, sharing these helpers. */
#ifndef GD_CLI_H
#define GD_CLI_H
#include <cjson/cJSON.h>
#include <stdio.h>

#include "geardyn/error.h"

/* Exit codes: 0 success, 1 internal/numerical failure, 2 bad input or usage. */
enum { GD_EXIT_OK = 0, GD_EXIT_FAIL = 1, GD_EXIT_INPUT = 2 };

/* Each subcommand: argv[0] is the subcommand name. */
int gd_cmd_check(int argc, char **argv);
int gd_cmd_modal(int argc, char **argv);
int gd_cmd_static(int argc, char **argv);
int gd_cmd_mesh_stiffness(int argc, char **argv);
int gd_cmd_bearing_stiffness(int argc, char **argv);
int gd_cmd_study(int argc, char **argv);
/* test-analysis correlation (docs/testing.md) */
int gd_cmd_testmodal(int argc, char **argv);
int gd_cmd_correlate(int argc, char **argv);

/* Prints "geardyn: error: ..." to stderr and returns the exit code for err. */
int gd_cli_report(const gd_error *err);
/* Usage error for a subcommand: message, then "see 'geardyn CMD --help'". Returns 2. */
int gd_cli_usage_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Reports a getopt failure (c is '?' or ':'; optstring must start with ':').
 * Returns 2. */
int gd_cli_option_error(const char *cmd, int c, char **argv, int optind_now);

/* Fails early (before any computing) when --out names something that is not a folder. */
int gd_outdir_check(const char *dir, gd_error *err);
/* As gd_outdir_check, and also when the folder cannot be written into or, when it does
 * not exist yet, cannot be created (its parent is missing or not writable). */
int gd_outdir_check_writable(const char *dir, gd_error *err);

/* Parses a positive whole number option value; returns 0 on success. */
int gd_cli_parse_count(const char *text, long lo, long hi, long *out);
/* A relative tolerance in [1e-15, 1) into the double at field; else a usage error naming
 * the option (name: "--tol") and its exit code. */
int gd_cli_parse_tolerance(const char *cmd, const char *name, const char *text, void *field);
/* The n values of a repeatable option, each a comma list ("--output a,b --output c"),
 * as items in out (at most max), in *buf (the caller frees it, also on failure). Returns
 * minus the number of items (0 or below), or a usage error's exit code (above 0) for an
 * empty item or too many. */
int gd_cli_split_commas(const char *cmd, const char *name, const char *const *in, int n, char **buf,
                        const char **out, int max);

/* Prints item as JSON (pretty) followed by a newline; frees nothing. */
void gd_cli_print_json(FILE *f, const cJSON *item);

/* --out DIR (outdir.c): the files are written into a staging folder beside DIR, which
 * replaces DIR as a whole at commit (DIR's other entries carried over), so a reader or a
 * kill sees the old folder or the new one, never a mix; a failure or SIGINT/SIGTERM
 * leaves nothing, and stages of killed runs are removed by the next run. */
typedef struct gd_outdir {
    char dir[1024];
    char stage[1100];
    int inside;  /* fallback: stage inside DIR, files moved one by one */
    int created; /* dir was made by gd_outdir_begin (removed again on abort) */
    int nfiles;
    char names[16][64];
} gd_outdir;

int gd_outdir_begin(gd_outdir *od, const char *dir, gd_error *err);
/* Opens DIR/<stage>/name for writing; NULL on failure (err set). */
FILE *gd_outdir_open(gd_outdir *od, const char *name, gd_error *err);
/* Closes f, checking for write errors. */
int gd_outdir_close(gd_outdir *od, FILE *f, const char *name, gd_error *err);
int gd_outdir_commit(gd_outdir *od, gd_error *err);
void gd_outdir_abort(gd_outdir *od);

/* ---- shared by the model-based commands ---- */
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"

/* --set PATH=VALUE, repeatable (docs/model-format.md, "Overrides (--set)"): a command
 * on an option table has the row GD_CLI_ROW_SET (options.h); one still on getopt_long
 * lists GD_CLI_SET_OPTION and passes the value of GD_CLI_OPT_SET to gd_cli_add_set.
 * The strings are argv's. */
enum { GD_CLI_OPT_SET = 0x5e7, GD_CLI_OPT_DOFS = 0x5e8, GD_CLI_MAX_SET = 64 };
#define GD_CLI_SET_OPTION                                                                          \
    {                                                                                              \
        "set", required_argument, 0, GD_CLI_OPT_SET                                                \
    }
/* --dofs LIST (GD_CLI_DOFS_OPTION, value GD_CLI_OPT_DOFS into sets.dofs): keep only
 * these node DOFs of the model's (the old meaning of --coupling). */
#define GD_CLI_DOFS_OPTION                                                                         \
    {                                                                                              \
        "dofs", required_argument, 0, GD_CLI_OPT_DOFS                                              \
    }
typedef struct gd_cli_sets {
    int nset;
    const char *set[GD_CLI_MAX_SET];
    const char *dofs; /* --dofs LIST, or NULL */
} gd_cli_sets;
/* Adds one --set value; 0, or a usage error (2) past GD_CLI_MAX_SET. */
int gd_cli_add_set(const char *cmd, gd_cli_sets *sets, const char *arg);
/* The sets as the library's load options (borrowing sets' strings). */
gd_load_options gd_cli_load_options(const gd_cli_sets *sets);

/* Loads MODEL with the --set overrides (sets may be NULL), applies --coupling LEVEL
 * (every mesh's level; NULL: keep the model's) and --dofs (sets->dofs) and builds the
 * system. On failure reports the error and
 * returns the exit code (non-zero). */
int gd_cli_load(const char *path, const gd_cli_sets *sets, const char *coupling, gd_model **model,
                gd_system **sys);
/* Parses a speed option value with units ("3000 rpm"); 0 on success. */
int gd_cli_parse_speed(const char *cmd, const char *text, double *out);
#include "geardyn/modal.h"

/* ---- sweeps: Campbell, FRF, unbalance (cli_sweep.c) ---- */
#include "geardyn/frf.h"
#include "geardyn/unbalance.h"

int gd_cmd_campbell(int argc, char **argv);
int gd_cmd_frf(int argc, char **argv);
int gd_cmd_unbalance(int argc, char **argv);

/* n evenly spaced values from `from` to `to` into out (n doubles), without overflow for
 * any finite ends. */
void gd_cli_linspace(double from, double to, long n, double *out);

/* Parses FROM:TO:COUNT (speeds or frequencies, units allowed: "0:12000rpm:121"; a FROM
 * without a unit takes TO's) into count evenly spaced values in rad/s (malloc'd).
 * Reports a usage error naming opt and returns 2 on failure, 0 on success. */
int gd_cli_parse_range(const char *cmd, const char *opt, const char *text, double **values,
                       int *count);
/* Output spec: NODE.DOF | node:NODE.DOF | mesh:NAME | bearing:NAME.DIR. 0 or 2. */
int gd_cli_parse_probe(const char *cmd, const char *opt, const gd_system *sys, const char *text,
                       gd_probe *out);
/* Input spec: NODE.DOF | node:NODE.DOF | torque:NODE (= NODE.rz) | NODE.xy (directional:
 * *xy = 1, *dof is the x DOF). 0 or 2. */
int gd_cli_parse_input(const char *cmd, const gd_system *sys, const char *text, int *dof, int *xy,
                       char *label, size_t label_size);
/* Parses a whole number of threads (>= 1); 0 or 2. */
int gd_cli_parse_threads(const char *cmd, const char *text, int *out);
/* JSON number or null when not finite. */
cJSON *gd_cli_json_number(double v);

/* ---- the system's matrices (cmd_matrices.c) ---- */
int gd_cmd_matrices(int argc, char **argv);

/* ---- time integration (cmd_transient.c) ---- */
int gd_cmd_transient(int argc, char **argv);

/* ---- units (cli_units.c): --units rpm|rad/s (speed), Hz|rad/s (frequency) ---- */
typedef struct gd_cli_units {
    int speed_rpm; /* speeds in rpm, else rad/s */
    int freq_hz;   /* frequencies in Hz, else rad/s */
} gd_cli_units;
/* Sets *u from what the user wrote in speed_text / freq_text (either may be NULL; *u
 * holds the command's defaults on entry), then from --units (may be NULL). 0, or the
 * exit code after reporting. */
int gd_cli_units_parse(const char *cmd, const char *units, const char *speed_text,
                       const char *freq_text, gd_cli_units *u);
double gd_cli_speed_out(const gd_cli_units *u, double rad_s);
double gd_cli_freq_out(const gd_cli_units *u, double rad_s);
const char *gd_cli_speed_unit(const gd_cli_units *u);
const char *gd_cli_freq_unit(const gd_cli_units *u);

/* ---- plots (cli_plot.c): --plot FILE.svg|FILE.html on the analysis commands ---- */
#include "geardyn/plot.h"

enum { GD_CLI_OPT_PLOT = 0x9107 };
#define GD_CLI_PLOT_OPTION                                                                         \
    {                                                                                              \
        "plot", required_argument, 0, GD_CLI_OPT_PLOT                                              \
    }
/* Before any computing: path has a known extension and a writable folder (and for HTML
 * plotly.js is there). 0, or the exit code after reporting. */
int gd_cli_plot_check(const char *path);
/* The figure built (st, p, err from a gd_plot_<analysis> call) written to path and freed.
 * 0, or the exit code after reporting (nothing written). */
int gd_cli_plot_finish(gd_status st, gd_plot *p, gd_error *err, const char *path);
/* The same for a command whose option for the file is opt (report: --out). */
int gd_cli_plot_check_as(const char *path, const char *opt);
int gd_cli_plot_finish_as(gd_status st, gd_plot *p, gd_error *err, const char *path,
                          const char *opt);

/* v as "%WIDTH.PRECISIONg" in buf, or "-" in that width when it is NaN (no value: the
 * JSON's null; "nan" in a text table read as a number). Returns buf. */
const char *gd_cli_num(char *buf, size_t size, int width, int precision, double v);
/* A damping ratio (or log decrement) as a table shows it: 0 where |zeta| < 1e-9, the
 * rounding of an undamped mode's eigenvalue in the state-space solve (-8.8e-28 read as a
 * negative damping); the rule of the modal figure's titles (src/plot/plot_modal.c). The
 * JSON and CSV keep the value. NaN stays NaN. */
double gd_cli_zeta_shown(double zeta);
double gd_cli_logdec_shown(double logdec);

/* ---- SIGINT, SIGTERM, SIGHUP (signals.c) ---- */
/* One process-wide handler for the three, installed by main before any thread starts
 * (a signal the caller ignores stays ignored). */
void gd_cli_signals_install(void);
/* The clean-up the handler runs before the process ends (the --out stage); NULL: none.
 * It must use only async-signal-safe calls. */
void gd_cli_signals_cleanup(void (*fn)(void));
/* A commit (a --plot file written and renamed, the --out folder put in place): the
 * three signals wait until gd_cli_commit_end, which then delivers one that came. */
void gd_cli_commit_begin(void);
void gd_cli_commit_end(void);

/* ---- the study report (cmd_report.c) ---- */
int gd_cmd_report(int argc, char **argv);
/* ---- periodic steady state (cmd_periodic.c) ---- */
int gd_cmd_periodic(int argc, char **argv);

#endif
