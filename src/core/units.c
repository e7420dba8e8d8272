#include "geardyn/units.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GD_PI 3.14159265358979323846

/* Dimension exponents of mass, length, time and angle. Angles are dimensionless in
 * SI, so an expression that omits "rad" is accepted where one is expected. */
typedef struct dims {
    int m, l, t, a;
} dims;

typedef struct unit_def {
    const char *name;
    double factor;
    dims d;
} unit_def;

static const unit_def UNITS[] = {
    {"m", 1.0, {0, 1, 0, 0}},           {"mm", 1e-3, {0, 1, 0, 0}},
    {"cm", 1e-2, {0, 1, 0, 0}},         {"um", 1e-6, {0, 1, 0, 0}},
    {"\xc2\xb5m", 1e-6, {0, 1, 0, 0}},  {"km", 1e3, {0, 1, 0, 0}},
    {"in", 0.0254, {0, 1, 0, 0}},       {"ft", 0.3048, {0, 1, 0, 0}},
    {"kg", 1.0, {1, 0, 0, 0}},          {"g", 1e-3, {1, 0, 0, 0}},
    {"s", 1.0, {0, 0, 1, 0}},           {"ms", 1e-3, {0, 0, 1, 0}},
    {"us", 1e-6, {0, 0, 1, 0}},         {"min", 60.0, {0, 0, 1, 0}},
    {"h", 3600.0, {0, 0, 1, 0}},        {"N", 1.0, {1, 1, -2, 0}},
    {"mN", 1e-3, {1, 1, -2, 0}},        {"kN", 1e3, {1, 1, -2, 0}},
    {"MN", 1e6, {1, 1, -2, 0}},         {"GN", 1e9, {1, 1, -2, 0}},
    {"Nm", 1.0, {1, 2, -2, 0}},         {"J", 1.0, {1, 2, -2, 0}},
    {"Pa", 1.0, {1, -1, -2, 0}},        {"kPa", 1e3, {1, -1, -2, 0}},
    {"MPa", 1e6, {1, -1, -2, 0}},       {"GPa", 1e9, {1, -1, -2, 0}},
    {"rad", 1.0, {0, 0, 0, 1}},         {"mrad", 1e-3, {0, 0, 0, 1}},
    {"urad", 1e-6, {0, 0, 0, 1}},       {"deg", GD_PI / 180.0, {0, 0, 0, 1}},
    {"rev", 2.0 * GD_PI, {0, 0, 0, 1}}, {"rpm", 2.0 * GD_PI / 60.0, {0, 0, -1, 1}},
    {"Hz", 2.0 * GD_PI, {0, 0, -1, 1}}, {"kHz", 2.0e3 * GD_PI, {0, 0, -1, 1}},
};

static const struct {
    dims d;
    const char *si;
} QTY[GD_QTY_COUNT_] = {
    [GD_QTY_DIMLESS] = {{0, 0, 0, 0}, "1"},
    [GD_QTY_LENGTH] = {{0, 1, 0, 0}, "m"},
    [GD_QTY_MASS] = {{1, 0, 0, 0}, "kg"},
    [GD_QTY_TIME] = {{0, 0, 1, 0}, "s"},
    [GD_QTY_ANGLE] = {{0, 0, 0, 1}, "rad"},
    [GD_QTY_ANGULAR_SPEED] = {{0, 0, -1, 1}, "rad/s"},
    [GD_QTY_FORCE] = {{1, 1, -2, 0}, "N"},
    [GD_QTY_TORQUE] = {{1, 2, -2, 0}, "N*m"},
    [GD_QTY_STIFFNESS] = {{1, 0, -2, 0}, "N/m"},
    [GD_QTY_DAMPING] = {{1, 0, -1, 0}, "N*s/m"},
    [GD_QTY_ROT_STIFFNESS] = {{1, 2, -2, -1}, "N*m/rad"},
    [GD_QTY_ROT_DAMPING] = {{1, 2, -1, -1}, "N*m*s/rad"},
    [GD_QTY_INERTIA] = {{1, 2, 0, 0}, "kg*m^2"},
    [GD_QTY_DENSITY] = {{1, -3, 0, 0}, "kg/m^3"},
    [GD_QTY_PRESSURE] = {{1, -1, -2, 0}, "Pa"},
    [GD_QTY_VISCOSITY] = {{1, -1, -1, 0}, "Pa*s"},
    [GD_QTY_MASS_LENGTH] = {{1, 1, 0, 0}, "kg*m"},
};

const char *gd_qty_si_unit(gd_qty qty)
{
    return (qty >= 0 && qty < GD_QTY_COUNT_) ? QTY[qty].si : "?";
}

static const unit_def *find_unit(const char *s, size_t n)
{
    for (size_t i = 0; i < sizeof UNITS / sizeof UNITS[0]; i++)
        if (strlen(UNITS[i].name) == n && strncmp(UNITS[i].name, s, n) == 0) return &UNITS[i];
    return NULL;
}

/* Parses a unit expression: factors separated by '*', '.' or spaces, each with an
 * optional "^n"; at most one '/', after which every factor is in the denominator. */
static int parse_unit_expr(const char *s, double *factor, dims *d, char *why, size_t why_size)
{
    *factor = 1.0;
    memset(d, 0, sizeof *d);
    int sign = 1, slashes = 0;
    const char *p = s;
    while (*p) {
        if (*p == ' ' || *p == '*' || *p == '.') {
            p++;
            continue;
        }
        if (*p == '/') {
            if (++slashes > 1) {
                snprintf(why, why_size, "unit '%s' has more than one '/'", s);
                return 1;
            }
            sign = -1;
            p++;
            continue;
        }
        const char *start = p;
        while (*p && *p != ' ' && *p != '*' && *p != '/' && *p != '^' && *p != '.')
            p++;
        const unit_def *u = find_unit(start, (size_t)(p - start));
        if (!u) {
            snprintf(why, why_size, "unknown unit '%.*s' in '%s'", (int)(p - start), start, s);
            return 1;
        }
        int power = 1;
        if (*p == '^') {
            char *end;
            long pw = strtol(p + 1, &end, 10);
            if (end == p + 1 || pw == 0 || labs(pw) > 4) {
                snprintf(why, why_size, "bad power after '%.*s' in '%s'", (int)(p - start), start,
                         s);
                return 1;
            }
            power = (int)pw;
            p = end;
        }
        power *= sign;
        *factor *= pow(u->factor, power);
        d->m += u->d.m * power;
        d->l += u->d.l * power;
        d->t += u->d.t * power;
        d->a += u->d.a * power;
    }
    return 0;
}

/* Finite and not below DBL_MIN: an underflow (1e-400) or a denormal (1e-310) is
 * refused rather than computed with, since its reciprocal (a stiffness from a length)
 * overflows to inf. 0 when v is fine. */
static int representable(double v, const char *text, char *why, size_t why_size)
{
    if (!isfinite(v) || fabs(v) > DBL_MAX) {
        snprintf(why, why_size, "'%s' is not a finite number (the largest is 1.8e308)", text);
        return 1;
    }
    if (v != 0 && fabs(v) < DBL_MIN) {
        snprintf(why, why_size, "'%s' is too small to compute with (the smallest is 2.2e-308)",
                 text);
        return 1;
    }
    return 0;
}

static int parse_quantity(const char *text, gd_qty qty, double *value, char *why, size_t why_size)
{
    why[0] = '\0';
    if (!text || qty < 0 || qty >= GD_QTY_COUNT_) {
        snprintf(why, why_size, "no value");
        return 1;
    }
    while (isspace((unsigned char)*text))
        text++;
    errno = 0;
    char *end;
    double x = strtod(text, &end);
    if (end == text) {
        snprintf(why, why_size, "'%s' is not a number (with an optional unit)", text);
        return 1;
    }
    if (errno == ERANGE && fabs(x) <= 1) x = DBL_MIN / 2; /* checked as a denormal below */
    if (representable(x, text, why, why_size)) return 1;
    char unit[96];
    size_t n = strlen(end);
    while (n > 0 && isspace((unsigned char)end[n - 1]))
        n--;
    while (n > 0 && isspace((unsigned char)*end)) {
        end++;
        n--;
    }
    if (n >= sizeof unit) {
        snprintf(why, why_size, "unit in '%s' is too long", text);
        return 1;
    }
    memcpy(unit, end, n);
    unit[n] = '\0';
    if (n == 0) {
        *value = x;
        return 0;
    }
    double f;
    dims d;
    if (parse_unit_expr(unit, &f, &d, why, why_size)) return 1;
    dims want = QTY[qty].d;
    int angle_ok = d.a == want.a || d.a == 0;
    if (d.m != want.m || d.l != want.l || d.t != want.t || !angle_ok) {
        snprintf(why, why_size, "'%s' is not a %s quantity (expected a unit like %s)", unit,
                 qty == GD_QTY_DIMLESS ? "dimensionless" : "matching", QTY[qty].si);
        return 1;
    }
    if (representable(x * f, text, why, why_size)) return 1;
    *value = x * f;
    return 0;
}

gd_status gd_parse_quantity(const char *text, gd_qty qty, double *value, gd_error *err)
{
    char why[200];
    if (!parse_quantity(text, qty, value, why, sizeof why)) return GD_OK;
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "", "", "%s", why);
}
