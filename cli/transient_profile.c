/* geardyn transient --speed-ramp / --speed-table: the speed profile from the command line
 * and the order-tracked waterfall of a run-up (geardyn/waterfall.h). */
#include "transient_profile.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "geardyn/units.h"

void gd_cli_profile_free(gd_cli_profile *cp)
{
    free(cp->t);
    free(cp->w);
    cp->t = cp->w = NULL;
}

/* the unit suffix of a number ("6000rpm" -> "rpm"), "" when none */
static const char *suffix(const char *s)
{
    const char *p = s + strlen(s);
    while (p > s && (isalpha((unsigned char)p[-1]) || p[-1] == '/'))
        p--;
    return p;
}

int gd_cli_speed_ramp(const char *cmd, const char *text, double t_end, gd_cli_profile *cp)
{
    memset(cp, 0, sizeof *cp);
    char a[128], b[128];
    const char *c = strchr(text, ':');
    if (!c || strchr(c + 1, ':') || (size_t)(c - text) >= sizeof a - 16 ||
        strlen(c + 1) >= sizeof b)
        return gd_cli_usage_error(cmd, "--speed-ramp: '%s' is not FROM:TO (e.g. 0:6000rpm)", text);
    snprintf(a, sizeof a, "%.*s", (int)(c - text), text);
    snprintf(b, sizeof b, "%s", c + 1);
    if (!*suffix(a) && *suffix(b)) strncat(a, suffix(b), sizeof a - strlen(a) - 1);
    double from, to;
    gd_error why;
    if (gd_parse_quantity(a, GD_QTY_ANGULAR_SPEED, &from, &why) ||
        gd_parse_quantity(b, GD_QTY_ANGULAR_SPEED, &to, &why))
        return gd_cli_usage_error(cmd, "--speed-ramp: %s (e.g. --speed-ramp 0:6000rpm)",
                                  why.message);
    if (from < 0 || to < 0)
        return gd_cli_usage_error(cmd,
                                  "--speed-ramp: give speeds of zero or more (each shaft's sense "
                                  "of rotation is the model's)");
    if (from == to)
        return gd_cli_usage_error(cmd, "--speed-ramp: FROM equals TO: give --speed for a "
                                       "constant speed");
    cp->p.kind = GD_SPEED_RAMP;
    cp->p.from = from;
    cp->p.to = to;
    cp->p.t0 = 0;
    cp->p.t1 = t_end;
    cp->wmin = fmin(fabs(from), fabs(to));
    cp->wmax = fmax(fabs(from), fabs(to));
    return 0;
}

/* 1 if text (up to n bytes) is a speed unit of the units module; its factor to rad/s */
static int speed_unit(const char *text, size_t n, double *scale)
{
    char q[96];
    if (n == 0 || n > 64) return 0;
    snprintf(q, sizeof q, "1 %.*s", (int)n, text);
    return gd_parse_quantity(q, GD_QTY_ANGULAR_SPEED, scale, NULL) == GD_OK;
}

/* The speed unit of a header line (its last field: "speed [rpm]", "speed_rpm",
 * "speed_rev_min", "rpm"), through the units module; a bare column name without a unit
 * ("speed", "omega", "w") keeps rad/s. 1 for a unit it does not know, which was read
 * as rad/s before (issue 38 M5: "RPM", "furlongs"). */
static int header_unit(const char *line, double *scale)
{
    *scale = 1.0;
    size_t len = strcspn(line, "\r\n");
    while (len && isspace((unsigned char)line[len - 1]))
        len--;
    const char *f = line + len; /* the last field: after the last comma, tab or blank */
    while (f > line && f[-1] != ',' && f[-1] != '\t' && f[-1] != ' ')
        f--;
    size_t n = (size_t)(line + len - f);
    const char *open = memchr(f, '[', n);
    if (!open) open = memchr(f, '(', n);
    if (open) { /* "speed[rpm]", "speed(rpm)" */
        const char *close = memchr(open, open[0] == '[' ? ']' : ')', (size_t)(f + n - open));
        return !(close && speed_unit(open + 1, (size_t)(close - open - 1), scale));
    }
    if (speed_unit(f, n, scale)) return 0;
    const char *us = memchr(f, '_', n);
    if (us) { /* "speed_rpm", "speed_rad_s" (rad/s), "speed_rev_min" (rev/min) */
        char u[72];
        size_t m = (size_t)(f + n - us - 1);
        if (m == 0 || m >= sizeof u) return 1;
        memcpy(u, us + 1, m);
        u[m] = 0;
        if (speed_unit(u, m, scale)) return 0;
        for (char *c = u; *c; c++)
            if (*c == '_') *c = '/';
        return !speed_unit(u, m, scale);
    }
    static const char *const names[] = {"speed", "omega", "w", "W", "Omega", "Speed"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (strlen(names[k]) == n && !strncmp(f, names[k], n)) return 0;
    return 1;
}

int gd_cli_speed_table(const char *cmd, const char *path, gd_cli_profile *cp)
{
    memset(cp, 0, sizeof *cp);
    FILE *f = fopen(path, "r");
    if (!f)
        return gd_cli_usage_error(cmd, "--speed-table: cannot read '%s': %s", path,
                                  strerror(errno));
    struct stat sb; /* a folder opens, then reads as "0 row(s)" (issue 38 L3) */
    if (fstat(fileno(f), &sb) == 0 && S_ISDIR(sb.st_mode)) {
        fclose(f);
        return gd_cli_usage_error(cmd,
                                  "--speed-table: '%s' is a folder: give a file of rows "
                                  "'time, speed'",
                                  path);
    }
    char line[512];
    int ln = 0, n = 0, cap = 0, rc = 0, header = 0;
    double scale = 1.0; /* to rad/s */
    while (fgets(line, sizeof line, f)) {
        ln++;
        char *h = strchr(line, '#');
        if (h) *h = 0;
        char *s = line;
        while (isspace((unsigned char)*s))
            s++;
        if (!*s) continue;
        char *end;
        double tv = strtod(s, &end);
        if (end == s) { /* a header line: the speed unit */
            if (n || header) {
                rc = gd_cli_usage_error(cmd, "%s:%d: '%s' is not 'time, speed' (two numbers)", path,
                                        ln, s);
                break;
            }
            header = 1;
            if (header_unit(s, &scale)) {
                rc = gd_cli_usage_error(cmd,
                                        "%s:%d: the header '%s' names no speed unit geardyn "
                                        "knows: head the speed column with rpm, rev/min, Hz "
                                        "or rad/s (e.g. 'time_s, speed_rpm' or 'time, rpm')",
                                        path, ln, strtok(s, "\r\n"));
                break;
            }
            continue;
        }
        while (*end == ',' || isspace((unsigned char)*end))
            end++;
        char *e2;
        double wv = strtod(end, &e2);
        while (*e2 && isspace((unsigned char)*e2))
            e2++;
        if (e2 == end || *e2 || !isfinite(tv) || !isfinite(wv)) {
            rc = gd_cli_usage_error(cmd,
                                    "%s:%d: give 'time, speed' (seconds, then the speed in the "
                                    "header's unit, default rad/s)",
                                    path, ln);
            break;
        }
        if (n && !(tv > cp->t[n - 1])) {
            rc = gd_cli_usage_error(cmd, "%s:%d: time %g s does not increase (previous %g s)", path,
                                    ln, tv, cp->t[n - 1]);
            break;
        }
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            double *nt = realloc(cp->t, (size_t)cap * sizeof *nt);
            if (nt) cp->t = nt;
            double *nw = realloc(cp->w, (size_t)cap * sizeof *nw);
            if (nw) cp->w = nw;
            if (!nt || !nw) {
                rc = gd_cli_usage_error(cmd, "--speed-table: out of memory");
                break;
            }
        }
        cp->t[n] = tv;
        cp->w[n] = wv * scale;
        n++;
    }
    fclose(f);
    if (!rc && n < 2)
        rc =
            gd_cli_usage_error(cmd, "%s: %d row(s): give at least two rows 'time, speed'", path, n);
    if (rc) {
        gd_cli_profile_free(cp);
        return rc;
    }
    cp->p.kind = GD_SPEED_TABLE;
    cp->p.n = n;
    cp->p.t = cp->t;
    cp->p.speed = cp->w;
    gd_error err;
    gd_error_clear(&err);
    if (gd_speed_profile_check(&cp->p, &err)) {
        gd_cli_profile_free(cp);
        return gd_cli_usage_error(cmd, "%s: %s (%s)", path, err.message, err.hint);
    }
    cp->wmin = INFINITY;
    for (int k = 0; k < n; k++) {
        cp->wmin = fmin(cp->wmin, fabs(cp->w[k]));
        cp->wmax = fmax(cp->wmax, fabs(cp->w[k]));
    }
    return 0;
}

int gd_cli_track_samples(double max_order)
{
    int s = 32;
    while (s < 2.5 * max_order && s < (1 << 20))
        s *= 2;
    return s;
}

int gd_cli_runup_waterfall(const char *cmd, const gd_system *sys, const gd_cli_profile *cp,
                           const double *t, const double *x, int n, double revs_per_block,
                           int samples_per_rev, gd_waterfall **out)
{
    (void)cmd;
    *out = NULL;
    double *ang = malloc((size_t)(n > 0 ? n : 1) * sizeof *ang);
    if (!ang) {
        fprintf(stderr, "geardyn: error: out of memory\n");
        return GD_EXIT_FAIL;
    }
    for (int k = 0; k < n; k++)
        gd_speed_profile_eval(&cp->p, t[k], &ang[k], NULL, NULL);
    gd_order_track_options o;
    gd_order_track_options_init(&o);
    o.revs_per_block = revs_per_block;
    o.samples_per_rev = samples_per_rev;
    gd_error err;
    gd_error_clear(&err);
    gd_status st = gd_waterfall_order_track(sys, t, x, ang, n, &o, out, &err);
    free(ang);
    return st ? gd_cli_report(&err) : 0;
}
