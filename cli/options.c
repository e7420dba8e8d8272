/* The generic option parser and help printer of options.h. getopt_long does the
 * scanning (abbreviations, --name=value, options after the positional argument); this
 * file turns each table row into a getopt_long entry and applies the value. */
#include "options.h"

#include <getopt.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "geardyn/units.h"

enum { HELP_WIDTH = 90, FIRST_VAL = 256 };

/* VALUE and CHOICE rows write an int into the library's enum fields (gd_modal_kind,
 * gd_eig_method, ...): enums are int-sized here (no -fshort-enums). */
_Static_assert(sizeof(gd_eig_method) == sizeof(int), "enum fields are written as int");

/* Levenshtein distance of a and b[0..nb), for the closest option name. */
static size_t distance(const char *a, const char *b, size_t nb)
{
    size_t na = strlen(a), row[64];
    if (na >= 64 || nb >= 64) return 64;
    for (size_t j = 0; j <= nb; j++)
        row[j] = j;
    for (size_t i = 1; i <= na; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= nb; j++) {
            size_t up = row[j], best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            diag = up;
            row[j] = best;
        }
    }
    return row[nb];
}

/* An unknown, ambiguous or valueless option: names the option and the fix. */
static int option_error(const gd_cli_command *c, int ch, const char *arg)
{
    const char *cmd = c->name;
    const gd_cli_opt *o = optopt >= FIRST_VAL ? &c->opts[optopt - FIRST_VAL] : NULL;
    if (ch == ':' && o)
        return gd_cli_usage_error(cmd, "option '%s' needs a value (--%s %s)", arg, o->name,
                                  o->meta ? o->meta : "");
    if (ch == ':') return gd_cli_usage_error(cmd, "option '%s' needs a value", arg);
    if (o && strchr(arg, '='))
        return gd_cli_usage_error(cmd, "option '--%s' takes no value: write --%s alone", o->name,
                                  o->name);
    if (strncmp(arg, "--", 2)) return gd_cli_usage_error(cmd, "unknown option '%s'", arg);
    const char *name = arg + 2;
    size_t len = strcspn(name, "="), best = 64, nprefix = 0;
    const char *closest = NULL, *prefixed[2] = {0};
    for (const gd_cli_opt *p = c->opts; p->name; p++) {
        if (!strncmp(p->name, name, len) && nprefix < 2) prefixed[nprefix++] = p->name;
        size_t d = distance(p->name, name, len);
        if (d < best) best = d, closest = p->name;
    }
    if (nprefix == 2 && len)
        return gd_cli_usage_error(cmd, "option '%s' is ambiguous: --%s, --%s, ...", arg,
                                  prefixed[0], prefixed[1]);
    if (closest && best <= (len + 2) / 3)
        return gd_cli_usage_error(cmd, "unknown option '%s' (did you mean --%s?)", arg, closest);
    return gd_cli_usage_error(cmd, "unknown option '%s'", arg);
}

/* Applies one value to the field of row o. 0, or the exit code after reporting. */
static int apply(const char *cmd, const gd_cli_opt *o, const char *v, char *args)
{
    void *f = args + o->field;
    switch (o->kind) {
    case GD_CLI_FLAG:
    case GD_CLI_CLEAR:
    case GD_CLI_VALUE:
        *(int *)f = o->kind == GD_CLI_FLAG ? 1 : o->kind == GD_CLI_CLEAR ? 0 : o->ival;
        return 0;
    case GD_CLI_STRING:
        *(const char **)f = v;
        return 0;
    case GD_CLI_LIST: {
        int *n = (int *)(args + o->aux);
        if (*n >= o->hi) return gd_cli_usage_error(cmd, "--%s: at most %ld values", o->name, o->hi);
        ((const char **)f)[(*n)++] = v;
        return 0;
    }
    case GD_CLI_SETS:
        return gd_cli_add_set(cmd, f, v);
    case GD_CLI_INT: {
        long n;
        if (o->word && !strcmp(v, o->word))
            *(int *)f = o->ival;
        else if (gd_cli_parse_count(v, o->lo, o->hi, &n))
            return gd_cli_usage_error(cmd, "--%s: '%s' is not a whole number from %ld to %ld%s%s%s",
                                      o->name, v, o->lo, o->hi, o->word ? " or '" : "",
                                      o->word ? o->word : "", o->word ? "'" : "");
        else
            *(int *)f = (int)n;
        return 0;
    }
    case GD_CLI_CHOICE: {
        const char *w = o->word;
        for (int k = 0; *w; k++) {
            size_t len = strcspn(w, "|");
            if (strlen(v) == len && !strncmp(v, w, len)) {
                *(int *)f = k;
                return 0;
            }
            w += len + (w[len] == '|');
        }
        /* "a|b|c" -> "a, b or c" */
        char list[256] = "";
        for (const char *p = o->word; *p; p += strcspn(p, "|"), p += *p == '|') {
            const char *sep = p == o->word ? "" : strchr(p, '|') ? ", " : " or ";
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%.*s", sep,
                     (int)strcspn(p, "|"), p);
        }
        return gd_cli_usage_error(cmd, "--%s: '%s' is not %s", o->name, v, list);
    }
    case GD_CLI_QUANTITY: {
        gd_error why;
        double *x = f;
        if (gd_parse_quantity(v, (gd_qty)o->qty, x, &why))
            return gd_cli_usage_error(cmd, "--%s: %s (e.g. --%s %s)", o->name, why.message, o->name,
                                      o->example);
        if (o->lo == GD_CLI_ABOVE_ZERO && !(*x > 0))
            return gd_cli_usage_error(cmd, "--%s: must be positive (e.g. --%s %s)", o->name,
                                      o->name, o->example);
        if (o->lo == GD_CLI_ZERO_OR_MORE && *x < 0)
            return gd_cli_usage_error(cmd, "--%s: give a %s of zero or more (e.g. --%s %s)",
                                      o->name, o->qty == GD_QTY_ANGULAR_SPEED ? "speed" : "value",
                                      o->name, o->example);
        if (o->aux) *(int *)(args + o->aux) = 1;
        return 0;
    }
    case GD_CLI_CALL:
        return o->call(cmd, v, f);
    }
    return GD_EXIT_INPUT;
}

/* path with its folder resolved (symbolic links, "..", "./"), trailing slashes off */
static void resolved(const char *path, char *buf, size_t size)
{
    char p[4096], dir[4096];
    snprintf(p, sizeof p, "%s", path);
    size_t n = strlen(p);
    while (n > 1 && p[n - 1] == '/')
        p[--n] = '\0';
    char *slash = strrchr(p, '/');
    const char *base = slash ? slash + 1 : p;
    if (slash == p)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - p) : 1, slash ? p : ".");
    char real[PATH_MAX];
    if (realpath(dir, real))
        snprintf(buf, size, "%s/%s", real, base);
    else
        snprintf(buf, size, "%s", p);
}

/* --out and --plot naming one path: the folder would replace the figure (or the figure
 * land where the folder goes) after the run (issue 38 L1). */
static int out_is_plot(const gd_cli_command *c, const unsigned char *seen, int n, char *args)
{
    const char *out = NULL, *plot = NULL;
    for (int k = 0; k < n; k++) {
        const gd_cli_opt *o = &c->opts[k];
        if (!seen[k] || o->kind != GD_CLI_STRING) continue;
        if (!strcmp(o->name, "out")) out = *(const char **)(args + o->field);
        if (!strcmp(o->name, "plot")) plot = *(const char **)(args + o->field);
    }
    if (!out || !plot) return 0;
    char a[8192], b[8192];
    resolved(out, a, sizeof a);
    resolved(plot, b, sizeof b);
    if (strcmp(a, b)) return 0;
    return gd_cli_usage_error(c->name,
                              "--out %s and --plot %s name the same path: give the folder and "
                              "the figure different names (e.g. --out results --plot fig.svg)",
                              out, plot);
}

/* The options of argv into args; positionals [*first, argc) (getopt_long moves them to
 * the end). 0, -1 (help) or an exit code. */
static int parse_options(const gd_cli_command *c, int argc, char **argv, void *args, int *first)
{
    struct option lo[GD_CLI_MAX_OPTS + 2];
    unsigned char seen[GD_CLI_MAX_OPTS] = {0};
    char shorts[3 * GD_CLI_MAX_OPTS + 3] = ":h";
    int n = 0, ch;
    for (; c->opts[n].name && n < GD_CLI_MAX_OPTS; n++) {
        const gd_cli_opt *o = &c->opts[n];
        int flag = o->kind <= GD_CLI_VALUE;
        lo[n] = (struct option){o->name, flag ? no_argument : required_argument, 0, FIRST_VAL + n};
        if (o->letter)
            snprintf(shorts + strlen(shorts), sizeof shorts - strlen(shorts), "%c%s", o->letter,
                     flag ? "" : ":");
    }
    lo[n] = (struct option){"help", no_argument, 0, 'h'};
    lo[n + 1] = (struct option){0, 0, 0, 0};
    optind = 0; /* 0, not 1: glibc's full restart (a second parse in one process) */
    opterr = 0;
    while ((ch = getopt_long(argc, argv, shorts, lo, NULL)) != -1) {
        if (ch == 'h') {
            gd_cli_help(c, stdout);
            return -1;
        }
        for (int k = 0; k < n && ch < FIRST_VAL && ch != '?' && ch != ':'; k++)
            if (c->opts[k].letter == ch) ch = FIRST_VAL + k;
        if (ch < FIRST_VAL) return option_error(c, ch, argv[optind - 1]);
        int k = ch - FIRST_VAL;
        const gd_cli_opt *o = &c->opts[k];
        for (int j = 0; o->excludes && j < n; j++)
            if (seen[j] && !strcmp(c->opts[j].name, o->excludes))
                return gd_cli_usage_error(c->name, "--%s and --%s exclude each other",
                                          c->opts[j < k ? j : k].name, c->opts[j < k ? k : j].name);
        if (o->once && seen[k]) return gd_cli_usage_error(c->name, "give one --%s", o->name);
        seen[k] = 1;
        int rc = apply(c->name, o, optarg, args);
        if (rc) return rc;
    }
    for (int k = 0; k < n; k++) {
        const gd_cli_opt *o = &c->opts[k];
        if (o->required && !seen[k] && o->kind == GD_CLI_LIST)
            return gd_cli_usage_error(c->name, "give at least one --%s", o->name);
        if (o->required && !seen[k])
            return gd_cli_usage_error(c->name, "--%s %s is required", o->name, o->meta);
    }
    if (out_is_plot(c, seen, n, (char *)args)) return GD_EXIT_INPUT;
    *first = optind;
    return 0;
}

int gd_cli_parse(const gd_cli_command *c, int argc, char **argv, void *args, const char **file)
{
    int first, rc = parse_options(c, argc, argv, args, &first);
    if (rc) return rc;
    const char *missing = c->missing ? c->missing : "give exactly one model file";
    if (first != argc - 1)
        return gd_cli_usage_error(c->name, "%s", first < argc && c->several ? c->several : missing);
    *file = argv[first];
    return 0;
}

int gd_cli_parse_files(const gd_cli_command *c, int argc, char **argv, void *args, int min_files,
                       char ***files, int *nfiles)
{
    int first, rc = parse_options(c, argc, argv, args, &first);
    if (rc) return rc;
    if (argc - first < min_files)
        return gd_cli_usage_error(c->name, "%s", c->missing ? c->missing : "give the files");
    *files = argv + first;
    *nfiles = argc - first;
    return 0;
}

/* Writes word (len bytes) at column col, or on a new line at column indent when it would
 * pass HELP_WIDTH. The new column. */
static int word(FILE *f, const char *w, size_t len, int col, int indent)
{
    if (col > indent && col + 1 + (int)len > HELP_WIDTH)
        col = fprintf(f, "\n%*s", indent, "") - 1;
    else if (col > indent)
        col += fprintf(f, " ");
    return col + fprintf(f, "%.*s", (int)len, w);
}

/* Writes text word by word from column col, wrapping to column indent. */
static int wrap(FILE *f, const char *text, int col, int indent)
{
    for (text += strspn(text, " "); *text; text += strspn(text, " ")) {
        size_t len = strcspn(text, " ");
        col = word(f, text, len, col, indent);
        text += len;
    }
    return col;
}

void gd_cli_help(const gd_cli_command *c, FILE *f)
{
    char buf[160];
    int indent = fprintf(f, "usage: geardyn %s ", c->name);
    int col = indent + fprintf(f, "%s", c->args);
    for (const gd_cli_opt *o = c->opts; o->name; o++) {
        int rep = o->kind == GD_CLI_LIST || o->kind == GD_CLI_SETS;
        snprintf(buf, sizeof buf, "%s--%s%s%s%s%s", o->required ? "" : "[", o->name,
                 o->meta ? " " : "", o->meta ? o->meta : "", o->required ? "" : "]",
                 rep ? "..." : "");
        col = word(f, buf, strlen(buf), col, indent);
    }
    fprintf(f, "\n%s\n%s", c->more ? c->more : "", c->about);
    /* the force outputs, one line per element kind with a probe, the one-force kinds
     * first (gd_probe_defaults' order); about ends its own line */
    for (int k = 0; c->probes && k < 2 * gd_nelement_types; k++) {
        const gd_element_type *t = gd_element_types[k % gd_nelement_types];
        if (!t->probe || t->probe_dirs != k / gd_nelement_types) continue;
        snprintf(buf, sizeof buf, "%s:NAME%s", t->probe, t->probe_dirs ? ".DIR" : "");
        fprintf(f, "  %-24s %s\n", buf, t->probe_help);
    }
    fputc('\n', f);
    int width = 0;
    for (const gd_cli_opt *o = c->opts; o->name; o++) {
        int w = (int)strlen(o->name) + (o->meta ? (int)strlen(o->meta) + 1 : 0) + 4 * !!o->letter;
        if (w > width && w <= 22) width = w;
    }
    for (const gd_cli_opt *o = c->opts; o->name; o++) {
        snprintf(buf, sizeof buf, "--%s%s%s", o->name, o->meta ? " " : "", o->meta ? o->meta : "");
        col = o->letter ? fprintf(f, "  -%c, %s", o->letter, buf) : fprintf(f, "  %s", buf);
        col += fprintf(f, "%*s", width + 6 - col > 1 ? width + 6 - col : 1, "");
        col = wrap(f, o->help, col, width + 6);
        if (o->def || o->required) {
            snprintf(buf, sizeof buf, "(%s%s)", o->def ? "default: " : "required",
                     o->def ? o->def : "");
            wrap(f, buf, col, width + 6);
        }
        fputc('\n', f);
    }
    if (c->footer) fprintf(f, "\n%s", c->footer);
}
