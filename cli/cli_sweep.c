/* Parsing shared by the sweep commands: FROM:TO:COUNT ranges with units, and the
 * input/output specs (NODE.DOF, node:NODE.DOF, torque:NODE, mesh:NAME,
 * bearing:NAME.DIR, NODE.xy). Every failure is a usage error (exit 2). */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "geardyn/units.h"

static int parse_speedlike(const char *cmd, const char *opt, const char *text, const char *unit,
                           double *out)
{
    char buf[256];
    gd_error why;
    int w = snprintf(buf, sizeof buf, "%s %s", text, unit ? unit : "");
    if (w < 0 || (size_t)w >= sizeof buf)
        return gd_cli_usage_error(cmd, "%s: '%.40s...' is too long", opt, text);
    if (gd_parse_quantity(buf, GD_QTY_ANGULAR_SPEED, out, &why))
        return gd_cli_usage_error(cmd, "%s: '%s': %s", opt, text, why.message);
    return 0;
}

/* The unit written after the number, or "" (e.g. "12000rpm" -> "rpm"). */
static const char *unit_of(const char *text)
{
    char *end;
    strtod(text, &end);
    if (end == text) return "";
    while (*end && isspace((unsigned char)*end))
        end++;
    return end;
}

/* n points from `from` to `to`. from + (to - from) i / (n - 1), the formula the Python
 * package uses too (their results agree bit for bit); where (to - from) i overflows (finite
 * ends such as 1e8:1e308 or -1e308:1e308, issue 38) (1 - t) from + t to instead. */
void gd_cli_linspace(double from, double to, long n, double *out)
{
    const double span = to - from;
    const int safe = isfinite(span * (double)(n > 1 ? n - 1 : 1));
    for (long i = 0; i < n; i++) {
        const double t = n > 1 ? (double)i / (double)(n - 1) : 0.0;
        out[i] = n == 1 ? from
                 : safe ? from + span * (double)i / (double)(n - 1)
                        : (1.0 - t) * from + t * to;
    }
}

int gd_cli_parse_range(const char *cmd, const char *opt, const char *text, double **values,
                       int *count)
{
    *values = NULL;
    *count = 0;
    char buf[256];
    if (strlen(text) >= sizeof buf) return gd_cli_usage_error(cmd, "%s: value too long", opt);
    snprintf(buf, sizeof buf, "%s", text);
    char *c1 = strchr(buf, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c1 || !c2 || strchr(c2 + 1, ':'))
        return gd_cli_usage_error(cmd, "%s: '%s' is not FROM:TO:COUNT (e.g. 0:12000rpm:121)", opt,
                                  text);
    *c1 = *c2 = '\0';
    const char *sfrom = buf, *sto = c1 + 1, *scount = c2 + 1;
    double from, to;
    long n;
    const char *tu = unit_of(sto);
    if (parse_speedlike(cmd, opt, sto, NULL, &to)) return GD_EXIT_INPUT;
    if (parse_speedlike(cmd, opt, sfrom, *unit_of(sfrom) ? NULL : tu, &from)) return GD_EXIT_INPUT;
    if (gd_cli_parse_count(scount, 0, 10000000, &n))
        return gd_cli_usage_error(cmd, "%s: COUNT '%s' is not a whole number", opt, scount);
    if (n < 1) return gd_cli_usage_error(cmd, "%s: COUNT is 0: give at least one point", opt);
    if (!isfinite(from) || !isfinite(to) || from < 0)
        return gd_cli_usage_error(cmd, "%s: FROM must be zero or more", opt);
    if (to < from)
        return gd_cli_usage_error(cmd, "%s: TO (%g rad/s) is below FROM (%g rad/s)", opt, to, from);
    /* speeds: no rotor survives 1e6 rad/s (a 10 mm rim at 10 km/s), and the w^2 terms
     * of the analyses overflow to inf and NaN long before the largest double */
    if (strstr(opt, "speeds") && to > 1e6)
        return gd_cli_usage_error(cmd,
                                  "%s: TO (%g rad/s) is beyond any rotor: give speeds up to 1e6 "
                                  "rad/s (9.5 million rpm)",
                                  opt, to);
    if (n > 1 && to == from)
        return gd_cli_usage_error(cmd, "%s: FROM equals TO: give COUNT 1 or a wider range", opt);
    double *v = malloc((size_t)n * sizeof *v);
    if (!v) return gd_cli_usage_error(cmd, "%s: out of memory for %ld points", opt, n);
    gd_cli_linspace(from, to, n, v);
    *values = v;
    *count = (int)n;
    return 0;
}

static int find_dof_name(const char *s)
{
    for (int d = 0; d < GD_NODE_DOFS; d++)
        if (!strcmp(s, gd_dof_names[d])) return d;
    return -1;
}

/* NODE.DOF -> active DOF index; reports errors. */
static int node_dof(const char *cmd, const char *opt, const gd_system *sys, const char *spec,
                    int *dof)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", spec);
    char *dot = strrchr(buf, '.');
    if (!dot)
        return gd_cli_usage_error(cmd, "%s: '%s' is not NODE.DOF (e.g. pinion.x, gear.rz)", opt,
                                  spec);
    *dot = '\0';
    int node = gd_model_find_node(sys->model, buf);
    if (node < 0) return gd_cli_usage_error(cmd, "%s: unknown node '%s'", opt, buf);
    int d = find_dof_name(dot + 1);
    if (d < 0)
        return gd_cli_usage_error(cmd, "%s: unknown DOF '%s' (use x, y, z, rx, ry or rz)", opt,
                                  dot + 1);
    *dof = gd_system_dof(sys, node, (gd_dof)d);
    if (*dof < 0)
        return gd_cli_usage_error(cmd, "%s: DOF %s of node '%s' is not active in this model", opt,
                                  dot + 1, buf);
    return 0;
}

int gd_cli_parse_probe(const char *cmd, const char *opt, const gd_system *sys, const char *text,
                       gd_probe *p)
{
    memset(p, 0, sizeof *p);
    snprintf(p->name, sizeof p->name, "%s", text);
    const char *rest;
    const gd_element_type *t = gd_probe_element(text, &rest);
    if (t) { /* PROBE:NAME or PROBE:NAME.DIR, the kind's own syntax (geardyn/elements.h) */
        char buf[256];
        snprintf(buf, sizeof buf, "%s", rest);
        char *dot = t->probe_dirs ? strrchr(buf, '.') : NULL;
        if (t->probe_dirs && !dot)
            return gd_cli_usage_error(cmd, "%s: '%s' is not %s:NAME.DIR (e.g. %s:A1.x)", opt, text,
                                      t->probe, t->probe);
        if (dot) *dot = '\0';
        p->element = t;
        p->index = gd_probe_instance(sys, t, buf);
        if (p->index < 0) return gd_cli_usage_error(cmd, "%s: unknown %s '%s'", opt, t->name, buf);
        if (!dot) return 0;
        int d = find_dof_name(dot + 1);
        if (d < 0)
            return gd_cli_usage_error(cmd, "%s: unknown direction '%s' (use x, y, z, rx, ry or rz)",
                                      opt, dot + 1);
        p->dir = (gd_dof)d;
        return 0;
    }
    p->element = NULL;
    return node_dof(cmd, opt, sys, !strncmp(text, "node:", 5) ? text + 5 : text, &p->index);
}

int gd_cli_parse_input(const char *cmd, const gd_system *sys, const char *text, int *dof, int *xy,
                       char *label, size_t label_size)
{
    *xy = 0;
    snprintf(label, label_size, "%s", text);
    if (!strncmp(text, "torque:", 7)) {
        char buf[256];
        snprintf(buf, sizeof buf, "%s.rz", text + 7);
        return node_dof(cmd, "--input", sys, buf, dof);
    }
    const char *spec = !strncmp(text, "node:", 5) ? text + 5 : text;
    size_t len = strlen(spec);
    if (len > 3 && !strcmp(spec + len - 3, ".xy")) {
        char buf[256];
        snprintf(buf, sizeof buf, "%.*s.x", (int)(len - 3), spec);
        *xy = 1;
        int rc = node_dof(cmd, "--input", sys, buf, dof);
        if (rc) return rc;
        snprintf(buf, sizeof buf, "%.*s.y", (int)(len - 3), spec);
        int ydof;
        return node_dof(cmd, "--input", sys, buf, &ydof);
    }
    return node_dof(cmd, "--input", sys, spec, dof);
}

int gd_cli_parse_threads(const char *cmd, const char *text, int *out)
{
    long v;
    if (gd_cli_parse_count(text, 1, 4096, &v))
        return gd_cli_usage_error(cmd, "--threads: '%s' is not a whole number from 1", text);
    *out = (int)v;
    return 0;
}
