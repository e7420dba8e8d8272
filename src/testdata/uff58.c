/* Universal File Format dataset 58, "Function at Nodal DOF", ASCII and binary (58b),
 * read record by record as the dataset description defines them ([UFF58]):
 *   -1 / 58 (or the 58b line: byte order, floating-point format, 11 ASCII lines, bytes)
 *   records 1-5  ID lines (80A1); line 1 is the function's description
 *   record 6     Format(2(I5,I10),2(1X,10A1,I10,I4)): function type, function id,
 *                version, load case, response entity, node, direction, reference
 *                entity, node, direction
 *   record 7     Format(3I10,3E13.5): ordinate data type (2 real single, 4 real
 *                double, 5 complex single, 6 complex double), number of values,
 *                abscissa spacing (1 even, 0 uneven), abscissa minimum, increment,
 *                z-axis value
 *   records 8-11 Format(I10,3I5,2(1X,20A1)): data characteristics of the abscissa,
 *                the ordinate numerator, its denominator and the z axis: specific
 *                data type (8 displacement, 11 velocity, 12 acceleration, 13
 *                excitation force, 18 frequency, ...), unit exponents, axis label,
 *                units label
 *   record 12    the values: real or complex pairs, preceded by the abscissa when the
 *                spacing is uneven; E13.5 fields for single precision, E20.12 for
 *                double, 58b: the same sequence as IEEE floats and doubles
 *   -1
 * Other datasets (151 header, 164 units, ...) are refused or, when asked, skipped. */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testdata/testdata_impl.h"

/* The text of columns [a, a + w) of a line (blank past its end), trimmed. */
static void field(const char *s, size_t n, size_t a, size_t w, char *out, size_t size)
{
    size_t k = 0;
    for (size_t i = a; i < a + w && i < n && k + 1 < size; i++)
        out[k++] = s[i];
    out[k] = 0;
    while (k && isspace((unsigned char)out[k - 1]))
        out[--k] = 0;
    size_t b = 0;
    while (out[b] && isspace((unsigned char)out[b]))
        b++;
    memmove(out, out + b, k - b + 1);
}

/* A Fortran number: E or D exponent, or an exponent written without its letter
 * ("1.23450-100", which E13.5 prints for three-digit exponents). */
static int parse_real(const char *text, double *v)
{
    char buf[64];
    size_t n = strlen(text), k = 0;
    if (n == 0 || n > 40) return 0;
    for (size_t i = 0; i < n; i++) {
        char c = text[i];
        if (c == 'D' || c == 'd') c = 'E';
        if ((c == '+' || c == '-') && i > 0 && isdigit((unsigned char)text[i - 1]) &&
            !strchr(text, 'E') && !strchr(text, 'e') && !strchr(text, 'D') && !strchr(text, 'd'))
            buf[k++] = 'E';
        buf[k++] = c;
    }
    buf[k] = 0;
    char *end;
    *v = strtod(buf, &end);
    return end != buf && *end == 0;
}

static int parse_int(const char *text, long *v)
{
    char *end;
    if (!*text) return 0;
    *v = strtol(text, &end, 10);
    return *end == 0;
}

typedef struct ascii_rec {
    long spec;      /* specific data type */
    char label[24]; /* axis label */
    char units[24]; /* axis units label */
} ascii_rec;

static int is_none(const char *s)
{
    return !*s || strcmp(s, "NONE") == 0;
}

static gd_status cut(gd_td_text *t, int line, const char *what, gd_error *err)
{
    return gd_error_set(err, GD_EINPUT, t->file, line, 0, what,
                        "the file ends inside a dataset: write it again whole",
                        "file cut short: %s is missing", what);
}

/* Record 12 in ASCII: nv numbers, fields of the widths the data type's case gives
 * per line; whitespace-separated numbers are taken first, fixed columns when a token
 * is not a number (fields that touch). */
static gd_status read_ascii_values(gd_td_text *t, const int *widths, int nw, double *v, long nv,
                                   gd_error *err)
{
    long k = 0;
    const char *s;
    size_t n;
    int start = t->line;
    while (k < nv) {
        if (!gd_td_next_line(t, &s, &n)) return cut(t, t->line, "record 12 (data values)", err);
        if (n >= 6 && strncmp(s, "    -1", 6) == 0 && (n == 6 || isspace((unsigned char)s[6])))
            return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "record 12",
                                "record 7 says how many values follow: make the two agree",
                                "dataset ends after %ld of %ld values (record 7 at line %d)", k, nv,
                                start);
        /* whitespace tokens first */
        char line[256];
        size_t m = n < sizeof line - 1 ? n : sizeof line - 1;
        memcpy(line, s, m);
        line[m] = 0;
        double tmp[16];
        int nt = 0, ok = 1;
        for (char *tok = strtok(line, " \t\r"); tok; tok = strtok(NULL, " \t\r")) {
            if (nt == 16 || !parse_real(tok, &tmp[nt])) {
                ok = 0;
                break;
            }
            nt++;
        }
        if (!ok) { /* fixed columns */
            nt = 0;
            size_t a = 0;
            for (int j = 0; j < nw && a < n; j++) {
                char fbuf[32];
                field(s, n, a, (size_t)widths[j], fbuf, sizeof fbuf);
                a += (size_t)widths[j];
                if (!*fbuf) break;
                if (!parse_real(fbuf, &tmp[nt]))
                    return gd_error_set(err, GD_EINPUT, t->file, t->line, (int)(a - widths[j]) + 1,
                                        "record 12",
                                        "values are Fortran E fields, e.g. 1.23450E+02",
                                        "'%s' is not a number", fbuf);
                nt++;
            }
        }
        for (int j = 0; j < nt && k < nv; j++)
            v[k++] = tmp[j];
    }
    return GD_OK;
}

static double get_f32(const unsigned char *p, int big)
{
    uint32_t u = big ? ((uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3])
                     : ((uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0]);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static double get_f64(const unsigned char *p, int big)
{
    uint64_t u = 0;
    for (int i = 0; i < 8; i++)
        u = u << 8 | p[big ? i : 7 - i];
    double d;
    memcpy(&d, &u, 8);
    return d;
}

/* The axis's kind from its data characteristics: frequency in Hz (or rad/s). */
static gd_status abscissa_factor(gd_td_text *t, int line, const ascii_rec *r, double *f,
                                 gd_error *err)
{
    *f = 1.0;
    if (r->spec == 17)
        return gd_error_set(err, GD_EINPUT, t->file, line, 1, "record 8 (abscissa data type)",
                            "geardyn reads functions of frequency (FRFs, coherences)",
                            "the abscissa is time (specific data type 17)");
    if (!is_none(r->units)) {
        if (strcmp(r->units, "Hz") == 0 || strcmp(r->units, "HZ") == 0 ||
            strcmp(r->units, "hz") == 0 || strcmp(r->units, "1/s") == 0)
            return GD_OK;
        if (strcmp(r->units, "rad/s") == 0) {
            *f = 1 / (2 * M_PI);
            return GD_OK;
        }
        return gd_error_set(err, GD_EINPUT, t->file, line, 48, "record 8 (abscissa units)",
                            "the abscissa must be a frequency in Hz or rad/s",
                            "cannot convert abscissa units '%s' to Hz", r->units);
    }
    if (r->spec != 0 && r->spec != 1 && r->spec != 18)
        return gd_error_set(err, GD_EINPUT, t->file, line, 1, "record 8 (abscissa data type)",
                            "the abscissa must be a frequency (specific data type 18)",
                            "abscissa specific data type %ld is not a frequency", r->spec);
    return GD_OK;
}

/* The ordinate's quantity and SI factor from records 9 and 10. */
static gd_status ordinate_units(gd_td_text *t, int line9, gd_td_function *f, const ascii_rec *num,
                                const ascii_rec *den, gd_error *err)
{
    if (f->function_type != GD_UFF_FRF) {
        f->quantity = GD_TD_RATIO;
        f->to_si = 1;
        snprintf(f->units, sizeof f->units, "%s", is_none(num->units) ? "" : num->units);
        return GD_OK;
    }
    if (!is_none(num->units) || !is_none(den->units)) {
        snprintf(f->units, sizeof f->units, "%s/%s", is_none(num->units) ? "?" : num->units,
                 is_none(den->units) ? "N" : den->units);
        gd_status st = gd_td_units(f->units, &f->quantity, &f->to_si, err);
        if (st) {
            if (err) {
                snprintf(err->file, sizeof err->file, "%s", t->file);
                err->line = line9;
                err->column = 48;
                snprintf(err->field, sizeof err->field, "records 9-10 (units labels)");
            }
            return st;
        }
        return GD_OK;
    }
    /* no labels: the specific data types, in SI ([UFF58] records 9-10) */
    f->to_si = 1;
    if (den->spec != 13 && den->spec != 9 && den->spec != 0 && den->spec != 1)
        return gd_error_set(
            err, GD_EINPUT, t->file, line9 + 1, 1, "record 10 (denominator data type)",
            "an FRF's denominator is a force (13 excitation force)",
            "cannot convert: denominator specific data type %ld is not a force", den->spec);
    switch (num->spec) {
    case 8:
        f->quantity = GD_TD_RECEPTANCE;
        snprintf(f->units, sizeof f->units, "m/N");
        break;
    case 11:
        f->quantity = GD_TD_MOBILITY;
        snprintf(f->units, sizeof f->units, "m/s/N");
        break;
    case 12:
        f->quantity = GD_TD_ACCELERANCE;
        snprintf(f->units, sizeof f->units, "m/s^2/N");
        break;
    default:
        return gd_error_set(err, GD_EINPUT, t->file, line9, 1, "record 9 (ordinate data type)",
                            "write 8 (displacement), 11 (velocity) or 12 (acceleration), or a "
                            "units label such as m/s^2",
                            "cannot convert: ordinate specific data type %ld with no units "
                            "label is not a displacement, velocity or acceleration",
                            num->spec);
    }
    return GD_OK;
}

/* A whole header record line: 0 at the end of the file or when the file stops inside
 * the line (then the record is cut, not malformed). */
static int record_line(gd_td_text *t, const char **s, size_t *n)
{
    return gd_td_next_line(t, s, n) && !t->partial;
}

/* One dataset 58 or 58b; the "-1" and identifier lines are read, t is at record 1. */
static gd_status read58(gd_td_text *t, int id_line, int binary, int big, long nbytes,
                        gd_testdata *td, gd_error *err)
{
    const char *s;
    size_t n;
    char buf[32];
    gd_td_function *f = gd_td_push(td, t->file, id_line);
    if (!f) return gd_error_set(err, GD_ENOMEM, t->file, id_line, 0, "", "", "out of memory");
    for (int r = 1; r <= 5; r++) {
        if (!record_line(t, &s, &n)) return cut(t, t->line, "records 1-5 (ID lines)", err);
        if (r == 1) field(s, n, 0, 80, f->name, sizeof f->name);
    }
    /* record 6 */
    if (!record_line(t, &s, &n)) return cut(t, t->line, "record 6", err);
    int l6 = t->line;
    long v[4];
    static const size_t C6[4][2] = {{0, 5}, {41, 10}, {51, 4}, {66, 10}};
    static const char *const N6[4] = {"function type", "response node", "response direction",
                                      "reference node"};
    for (int j = 0; j < 4; j++) {
        field(s, n, C6[j][0], C6[j][1], buf, sizeof buf);
        if (!parse_int(buf, &v[j]))
            return gd_error_set(err, GD_EINPUT, t->file, l6, (int)C6[j][0] + 1, "record 6",
                                "Format(2(I5,I10),2(1X,10A1,I10,I4)) of the dataset description",
                                "%s '%s' is not a whole number in columns %zu-%zu", N6[j], buf,
                                C6[j][0] + 1, C6[j][0] + C6[j][1]);
    }
    field(s, n, 76, 4, buf, sizeof buf);
    long refdir;
    if (!parse_int(buf, &refdir))
        return gd_error_set(err, GD_EINPUT, t->file, l6, 77, "record 6",
                            "Format(2(I5,I10),2(1X,10A1,I10,I4)) of the dataset description",
                            "reference direction '%s' is not a whole number in columns 77-80", buf);
    f->function_type = (int)v[0];
    f->response_node = (int)v[1];
    f->response_dir = (int)v[2];
    f->reference_node = (int)v[3];
    f->reference_dir = (int)refdir;
    if (labs(v[2]) > 6 || labs(refdir) > 6)
        return gd_error_set(err, GD_EINPUT, t->file, l6, labs(v[2]) > 6 ? 52 : 77, "record 6",
                            "directions are 0 (scalar), +-1..3 (x, y, z), +-4..6 (rx, ry, rz)",
                            "direction %ld is not a UFF direction code",
                            labs(v[2]) > 6 ? v[2] : refdir);
    /* record 7 */
    if (!record_line(t, &s, &n)) return cut(t, t->line, "record 7", err);
    int l7 = t->line;
    long type, nval, even;
    double xmin = 0, dx = 0;
    field(s, n, 0, 10, buf, sizeof buf);
    int ok = parse_int(buf, &type);
    field(s, n, 10, 10, buf, sizeof buf);
    ok = ok && parse_int(buf, &nval);
    field(s, n, 20, 10, buf, sizeof buf);
    ok = ok && parse_int(buf, &even);
    field(s, n, 30, 13, buf, sizeof buf);
    ok = ok && parse_real(buf, &xmin);
    field(s, n, 43, 13, buf, sizeof buf);
    ok = ok && parse_real(buf, &dx);
    if (!ok)
        return gd_error_set(err, GD_EINPUT, t->file, l7, 1, "record 7",
                            "Format(3I10,3E13.5): data type, number of values, spacing, "
                            "abscissa minimum, increment, z value",
                            "record 7 does not follow Format(3I10,3E13.5)");
    if (type != 2 && type != 4 && type != 5 && type != 6)
        return gd_error_set(err, GD_EINPUT, t->file, l7, 1, "record 7 (ordinate data type)",
                            "2 real single, 4 real double, 5 complex single, 6 complex double",
                            "ordinate data type %ld is not one of 2, 4, 5, 6", type);
    if (nval < 1 || nval > 100000000)
        return gd_error_set(err, GD_EINPUT, t->file, l7, 11, "record 7 (number of values)",
                            "at least one value", "number of values %ld", nval);
    if (even != 0 && even != 1)
        return gd_error_set(err, GD_EINPUT, t->file, l7, 21, "record 7 (abscissa spacing)",
                            "1 even, 0 uneven", "abscissa spacing %ld is not 0 or 1", even);
    if (even && !(dx > 0))
        return gd_error_set(err, GD_EINPUT, t->file, l7, 44, "record 7 (abscissa increment)",
                            "the frequency axis must increase: a positive increment",
                            "abscissa increment %g does not increase the frequency", dx);
    /* records 8-11 */
    ascii_rec rec[4];
    int l8 = 0;
    for (int r = 0; r < 4; r++) {
        if (!record_line(t, &s, &n)) return cut(t, t->line, "records 8-11", err);
        if (r == 0) l8 = t->line;
        field(s, n, 0, 10, buf, sizeof buf);
        if (!parse_int(buf, &rec[r].spec))
            return gd_error_set(err, GD_EINPUT, t->file, t->line, 1, "records 8-11",
                                "Format(I10,3I5,2(1X,20A1)): specific data type first",
                                "specific data type '%s' is not a whole number", buf);
        field(s, n, 26, 20, rec[r].label, sizeof rec[r].label);
        field(s, n, 47, 20, rec[r].units, sizeof rec[r].units);
    }
    double xf;
    gd_status st = abscissa_factor(t, l8, &rec[0], &xf, err);
    if (st) return st;
    st = ordinate_units(t, l8 + 1, f, &rec[1], &rec[2], err);
    if (st) return st;
    int cplx = type >= 5, dbl = type == 4 || type == 6;
    long per = (cplx ? 2 : 1) + (even ? 0 : 1), nv = per * nval;
    double *vals = malloc((size_t)nv * sizeof *vals);
    f->freq_hz = malloc((size_t)nval * sizeof(double));
    f->re = malloc((size_t)nval * sizeof(double));
    f->im = calloc((size_t)nval, sizeof(double));
    if (!vals || !f->freq_hz || !f->re || !f->im) {
        free(vals);
        return gd_error_set(err, GD_ENOMEM, t->file, l7, 0, "", "", "out of memory");
    }
    f->n = (int)nval;
    if (!binary) {
        /* the field widths of one line, [UFF58] record 12 cases 1-8 */
        static const int W13[6] = {13, 13, 13, 13, 13, 13}, W20[4] = {20, 20, 20, 20},
                         WRU[4] = {13, 20, 13, 20}, WCU[3] = {13, 20, 20};
        const int *w = W13;
        int nw = 6;
        if (dbl) {
            if (even)
                w = W20, nw = 4;
            else if (cplx)
                w = WCU, nw = 3;
            else
                w = WRU, nw = 4;
        }
        st = read_ascii_values(t, w, nw, vals, nv, err);
        if (st) {
            free(vals);
            return st;
        }
    } else {
        /* 58b: the same sequence as IEEE values; the description declares an uneven
         * abscissa REAL (4 bytes) beside double ordinates, writers also use 8: the byte
         * count tells which */
        long ysize = dbl ? 8 : 4;
        long xsize = ysize;
        long need = nval * ((cplx ? 2 : 1) * ysize + (even ? 0 : xsize));
        if (!even && dbl && nbytes == nval * ((cplx ? 2 : 1) * 8 + 4)) xsize = 4, need = nbytes;
        if (nbytes != need) {
            free(vals);
            return gd_error_set(err, GD_EINPUT, t->file, id_line, 31, "58b line (bytes)",
                                "the byte count must be the values' size",
                                "58b header says %ld bytes, record 7 needs %ld", nbytes, need);
        }
        if (t->len - t->pos < (size_t)nbytes) {
            free(vals);
            return cut(t, t->line, "58b binary data", err);
        }
        const unsigned char *p = (const unsigned char *)t->buf + t->pos;
        for (long k = 0; k < nv; k++) {
            int isx = !even && k % per == 0;
            long size = isx ? xsize : ysize;
            vals[k] = size == 8 ? get_f64(p, big) : get_f32(p, big);
            p += size;
        }
        t->pos += (size_t)nbytes;
        /* the closing -1 follows, on its own line (a line end before it is tolerated) */
        if (t->pos < t->len && t->buf[t->pos] == '\r') t->pos++;
        if (t->pos < t->len && t->buf[t->pos] == '\n') t->pos++;
    }
    for (long k = 0; k < nval; k++) {
        const double *q = vals + k * per;
        f->freq_hz[k] = (even ? xmin + (double)k * dx : q[0]) * xf;
        f->re[k] = q[even ? 0 : 1] * f->to_si;
        f->im[k] = cplx ? q[even ? 1 : 2] * f->to_si : 0;
    }
    free(vals);
    /* the closing -1 */
    if (!gd_td_next_line(t, &s, &n)) return cut(t, t->line, "the closing -1", err);
    field(s, n, 0, 6, buf, sizeof buf);
    if (strcmp(buf, "-1") != 0)
        return gd_error_set(err, GD_EINPUT, t->file, t->line, 1, "closing -1",
                            "record 7 says how many values follow: make the two agree",
                            "more data than record 7's %ld values (expected the closing -1)", nval);
    return gd_td_check(f, even ? "record 7 (abscissa)" : "record 12 (abscissa)", err);
}

gd_status gd_td_read_uff(gd_td_text *t, int skip_other, gd_testdata *td, gd_error *err)
{
    const char *s;
    size_t n;
    char buf[32];
    int ndata = 0;
    while (gd_td_next_line(t, &s, &n)) {
        field(s, n, 0, 80, buf, sizeof buf);
        if (!*buf) continue; /* blank lines between datasets */
        if (strcmp(buf, "-1") != 0)
            return gd_error_set(err, GD_EINPUT, t->file, t->line, 1, "dataset start",
                                "each dataset starts with a line '    -1'",
                                "expected '    -1', found '%.20s'", buf);
        int start = t->line;
        if (!gd_td_next_line(t, &s, &n)) return cut(t, start, "the dataset number", err);
        int idl = t->line;
        char id[8];
        field(s, n, 0, 6, id, sizeof id);
        int binary = n > 6 && s[6] == 'b';
        long num;
        if (!parse_int(id, &num))
            return gd_error_set(err, GD_EINPUT, t->file, idl, 1, "dataset number",
                                "the line after '-1' is the dataset number in columns 1-6",
                                "'%s' is not a dataset number", id);
        if (num == 58) {
            long fields[4] = {0, 0, 0, 0};
            if (binary) {
                /* Format(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12) */
                static const size_t C[4][2] = {{7, 6}, {13, 6}, {19, 12}, {31, 12}};
                for (int j = 0; j < 4; j++) {
                    field(s, n, C[j][0], C[j][1], buf, sizeof buf);
                    if (!parse_int(buf, &fields[j]))
                        return gd_error_set(err, GD_EINPUT, t->file, idl, (int)C[j][0] + 1,
                                            "58b line",
                                            "Format(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12)",
                                            "field '%s' is not a whole number", buf);
                }
                if (fields[0] != 1 && fields[0] != 2)
                    return gd_error_set(err, GD_EINPUT, t->file, idl, 8, "58b byte ordering",
                                        "1 little endian, 2 big endian",
                                        "byte ordering %ld is not 1 or 2", fields[0]);
                if (fields[1] != 2)
                    return gd_error_set(err, GD_EINPUT, t->file, idl, 14,
                                        "58b floating-point format",
                                        "write IEEE 754 values (format 2)",
                                        "floating-point format %ld (%s) is not read", fields[1],
                                        fields[1] == 1   ? "DEC VMS"
                                        : fields[1] == 3 ? "IBM 5/370"
                                                         : "unknown");
                if (fields[2] != 11)
                    return gd_error_set(err, GD_EINPUT, t->file, idl, 20, "58b ASCII lines",
                                        "dataset 58 has 11 ASCII lines before its data",
                                        "58b line says %ld ASCII lines", fields[2]);
            }
            gd_status st = read58(t, idl, binary, fields[0] == 2, fields[3], td, err);
            if (st) return st;
            ndata++;
            continue;
        }
        if (!skip_other)
            return gd_error_set(err, GD_EINPUT, t->file, idl, 1, "dataset number",
                                "geardyn reads dataset 58 (58b): functions at nodal DOFs; "
                                "remove the others or skip them (--skip-datasets)",
                                "dataset type %ld is not read", num);
        for (;;) { /* skip to the closing -1 */
            if (!gd_td_next_line(t, &s, &n)) return cut(t, start, "the closing -1", err);
            field(s, n, 0, 6, buf, sizeof buf);
            if (strcmp(buf, "-1") == 0 && n <= 6) break;
        }
    }
    if (ndata == 0)
        return gd_error_set(err, GD_EINPUT, t->file, t->line, 0, "", "write dataset 58 or 58b",
                            "no dataset 58 in the file");
    return GD_OK;
}
