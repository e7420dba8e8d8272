/* geardyn's CSV forms of test data (docs/testing.md):
 *   # geardyn frf                      # geardyn modes
 *   # name: H y2y3                     frequency_hz,damping_ratio,label
 *   # response: 2 +y                   134.4,,H y9y10
 *   # reference: 3 +y                  ...
 *   # units: m/s^2/N   (or # quantity: coherence)
 *   frequency_hz,re,im
 *   5.0,1.2e-4,-3.1e-5
 * Comment lines start with '#'; "key: value" comments before the header line set the
 * function's fields. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testdata/testdata_impl.h"

static void trim(char *s)
{
    size_t n = strlen(s);
    while (n && isspace((unsigned char)s[n - 1]))
        s[--n] = 0;
    size_t b = 0;
    while (s[b] && isspace((unsigned char)s[b]))
        b++;
    memmove(s, s + b, n - b + 1);
}

/* "2 +y" -> node 2, direction 2 */
static int parse_point(const char *v, int *node, int *dir)
{
    static const char *const NAMES[] = {"x", "y", "z", "rx", "ry", "rz"};
    char d[8] = "";
    int sign = 1;
    if (sscanf(v, "%d %7s", node, d) != 2) return 0;
    const char *p = d;
    if (*p == '+' || *p == '-') sign = *p++ == '-' ? -1 : 1;
    for (int k = 0; k < 6; k++)
        if (strcmp(p, NAMES[k]) == 0) {
            *dir = sign * (k + 1);
            return 1;
        }
    return 0;
}

static gd_status grow(gd_td_function *f, int *cap)
{
    if (f->n < *cap) return GD_OK;
    int nc = *cap ? 2 * *cap : 256;
    double *a = realloc(f->freq_hz, (size_t)nc * sizeof *a);
    if (a) f->freq_hz = a;
    double *b = realloc(f->re, (size_t)nc * sizeof *b);
    if (b) f->re = b;
    double *c = realloc(f->im, (size_t)nc * sizeof *c);
    if (c) f->im = c;
    if (!a || !b || !c) return GD_ENOMEM;
    *cap = nc;
    return GD_OK;
}

gd_status gd_td_read_frf_csv(gd_td_text *t, gd_testdata *td, gd_error *err)
{
    const char *s;
    size_t n;
    gd_td_function *f = gd_td_push(td, t->file, 1);
    if (!f) return gd_error_set(err, GD_ENOMEM, t->file, 0, 0, "", "", "out of memory");
    f->function_type = GD_UFF_FRF;
    int have_units = 0, header = 0, cap = 0;
    char line[512];
    while (gd_td_next_line(t, &s, &n)) {
        size_t m = n < sizeof line - 1 ? n : sizeof line - 1;
        memcpy(line, s, m);
        line[m] = 0;
        trim(line);
        if (!*line) continue;
        if (line[0] == '#') {
            char *colon = strchr(line, ':');
            if (!colon || header) continue;
            *colon = 0;
            char *key = line + 1, *val = colon + 1;
            trim(key);
            trim(val);
            if (strcmp(key, "name") == 0)
                snprintf(f->name, sizeof f->name, "%s", val);
            else if (strcmp(key, "response") == 0 || strcmp(key, "reference") == 0) {
                int r = key[2] == 's';
                if (!parse_point(val, r ? &f->response_node : &f->reference_node,
                                 r ? &f->response_dir : &f->reference_dir))
                    return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, key,
                                        "write the point label and direction: '2 +y'",
                                        "'%s' is not a point and direction", val);
            } else if (strcmp(key, "units") == 0) {
                snprintf(f->units, sizeof f->units, "%s", val);
                gd_status st = gd_td_units(val, &f->quantity, &f->to_si, err);
                if (st) {
                    if (err) {
                        snprintf(err->file, sizeof err->file, "%s", t->file);
                        err->line = t->line;
                    }
                    return st;
                }
                have_units = 1;
            } else if (strcmp(key, "quantity") == 0) {
                if (strcmp(val, "coherence") != 0 && strcmp(val, "ratio") != 0)
                    return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "quantity",
                                        "quantity: coherence (FRFs give their units)",
                                        "unknown quantity '%s'", val);
                f->function_type = strcmp(val, "coherence") == 0 ? GD_UFF_COHERENCE : 0;
                f->quantity = GD_TD_RATIO;
                have_units = 1;
            } else
                return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, key,
                                    "known keys: name, response, reference, units, quantity",
                                    "unknown key '%s'", key);
            continue;
        }
        if (!header) {
            if (strncmp(line, "frequency_hz", 12) != 0)
                return gd_error_set(err, GD_EINPUT, t->file, t->line, 1, "header",
                                    "the header line is frequency_hz,re,im",
                                    "expected the header line, found '%.40s'", line);
            if (!have_units)
                return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "units",
                                    "add '# units: m/s^2/N' (or m/N, m/s/N, g/N) before the "
                                    "header",
                                    "the FRF's units are not given");
            header = 1;
            continue;
        }
        if (grow(f, &cap))
            return gd_error_set(err, GD_ENOMEM, t->file, 0, 0, "", "", "out of memory");
        double a, b, c = 0;
        char *e;
        a = strtod(line, &e);
        int ok = e != line && *e == ',';
        if (ok) {
            char *p = e + 1;
            b = strtod(p, &e);
            ok = e != p && (*e == ',' || *e == 0);
            if (ok && *e == ',') {
                p = e + 1;
                c = strtod(p, &e);
                ok = e != p && (*e == 0 || *e == ',');
            }
        }
        if (!ok)
            return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "values",
                                "each line is frequency_hz,re,im", "'%.40s' is not three numbers",
                                line);
        f->freq_hz[f->n] = a;
        f->re[f->n] = b * f->to_si;
        f->im[f->n] = c * f->to_si;
        f->n++;
    }
    if (!header || f->n == 0)
        return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "values",
                            "the values follow the header line frequency_hz,re,im",
                            "file cut short: no values");
    if (!*f->name)
        snprintf(f->name, sizeof f->name, "H %s%d %s%d", gd_td_dir_name(f->response_dir),
                 f->response_node, gd_td_dir_name(f->reference_dir), f->reference_node);
    return gd_td_check(f, "frequency_hz", err);
}

gd_status gd_td_read_modes_csv(gd_td_text *t, gd_testdata *td, gd_error *err)
{
    const char *s;
    size_t n;
    int header = 0;
    char line[512];
    while (gd_td_next_line(t, &s, &n)) {
        size_t m = n < sizeof line - 1 ? n : sizeof line - 1;
        memcpy(line, s, m);
        line[m] = 0;
        trim(line);
        if (!*line || line[0] == '#') continue;
        if (!header) {
            if (strncmp(line, "frequency_hz", 12) != 0)
                return gd_error_set(err, GD_EINPUT, t->file, t->line, 1, "header",
                                    "the header line is frequency_hz,damping_ratio,label",
                                    "expected the header line, found '%.40s'", line);
            header = 1;
            continue;
        }
        int k = td->nmodes;
        double *a = realloc(td->mode_hz, (size_t)(k + 1) * sizeof *a);
        if (a) td->mode_hz = a;
        double *b = realloc(td->mode_zeta, (size_t)(k + 1) * sizeof *b);
        if (b) td->mode_zeta = b;
        char(*c)[48] = realloc(td->mode_label, (size_t)(k + 1) * sizeof *c);
        if (c) td->mode_label = c;
        if (!a || !b || !c)
            return gd_error_set(err, GD_ENOMEM, t->file, 0, 0, "", "", "out of memory");
        char *e, *p = line;
        double f = strtod(p, &e), z = NAN;
        if (e == p || !(f > 0) || !isfinite(f) || (*e && *e != ','))
            return gd_error_set(err, GD_EINPUT, t->file, t->line, 1, "frequency_hz",
                                "a natural frequency in Hz, above zero",
                                "'%.40s' does not start with a frequency", line);
        td->mode_label[k][0] = 0;
        if (*e == ',') {
            p = e + 1;
            if (*p && *p != ',') {
                z = strtod(p, &e);
                if (e == p || !(z >= 0) || (*e && *e != ','))
                    return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "damping_ratio",
                                        "a damping ratio >= 0, or nothing",
                                        "'%.40s' has no damping ratio in column 2", line);
            } else
                e = p;
            if (*e == ',') snprintf(td->mode_label[k], 48, "%s", e + 1);
        }
        td->mode_hz[k] = f;
        td->mode_zeta[k] = z;
        td->nmodes++;
    }
    if (!header || td->nmodes == 0)
        return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "frequency_hz",
                            "list the measured frequencies after the header line",
                            "no measured frequency in the file");
    return GD_OK;
}
