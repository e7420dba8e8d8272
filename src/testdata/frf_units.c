/* Units of an FRF's ordinate and the conversions between receptance, mobility and
 * accelerance: H_x = H_v / (i w) = -H_a / w^2 for a harmonic motion x e^{i w t}. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "testdata/testdata_impl.h"

const char *const gd_td_quantity_names[4] = {"receptance", "mobility", "accelerance", "ratio"};

typedef struct unit_row {
    const char *name;
    int kind; /* 0 length, 1 velocity, 2 acceleration, 3 force */
    double si;
} unit_row;

/* g is the standard gravity of 9.80665 m/s^2 (accelerometers are calibrated in it). */
static const unit_row UNITS[] = {
    {"m", 0, 1.0},       {"mm", 0, 1e-3},       {"um", 0, 1e-6},      {"in", 0, 0.0254},
    {"ft", 0, 0.3048},   {"m/s", 1, 1.0},       {"mm/s", 1, 1e-3},    {"in/s", 1, 0.0254},
    {"ft/s", 1, 0.3048}, {"m/s^2", 2, 1.0},     {"m/s2", 2, 1.0},     {"mm/s^2", 2, 1e-3},
    {"mm/s2", 2, 1e-3},  {"in/s^2", 2, 0.0254}, {"in/s2", 2, 0.0254}, {"ft/s^2", 2, 0.3048},
    {"g", 2, 9.80665},   {"N", 3, 1.0},         {"kN", 3, 1e3},       {"lbf", 3, 4.4482216152605},
};

static const unit_row *find_unit(const char *s, size_t n)
{
    while (n && isspace((unsigned char)*s))
        s++, n--;
    while (n && isspace((unsigned char)s[n - 1]))
        n--;
    for (size_t k = 0; k < sizeof UNITS / sizeof UNITS[0]; k++)
        if (strlen(UNITS[k].name) == n && strncmp(UNITS[k].name, s, n) == 0) return &UNITS[k];
    /* "G" is written for g by some analysers */
    if (n == 1 && s[0] == 'G') return &UNITS[16];
    return NULL;
}

gd_status gd_td_units(const char *text, gd_td_quantity *q, double *to_si, gd_error *err)
{
    const char *slash = text ? strrchr(text, '/') : NULL;
    const char *hint = "write the motion over the force: m/N, mm/s/N, m/s^2/N, g/N, in/s/lbf";
    if (!slash)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "units", hint,
                            "units '%s' are not a motion over a force", text ? text : "");
    const unit_row *num = find_unit(text, (size_t)(slash - text));
    const unit_row *den = find_unit(slash + 1, strlen(slash + 1));
    if (!num || num->kind > 2 || !den || den->kind != 3)
        return gd_error_set(
            err, GD_EINPUT, "", 0, 0, "units", hint, "cannot convert units '%s': %s is not %s",
            text, !num || num->kind > 2 ? "the numerator" : "the denominator",
            !num || num->kind > 2 ? "a displacement, velocity or acceleration" : "a force");
    *q = (gd_td_quantity)num->kind;
    *to_si = num->si / den->si;
    return GD_OK;
}

gd_status gd_td_convert(gd_td_function *f, gd_td_quantity to, gd_error *err)
{
    if (f->quantity == GD_TD_RATIO || to == GD_TD_RATIO)
        return gd_error_set(err, GD_EINPUT, f->file, f->line, 0, "quantity",
                            "only FRFs (receptance, mobility, accelerance) convert",
                            "cannot convert a %s to a %s", gd_td_quantity_names[f->quantity],
                            gd_td_quantity_names[to]);
    /* multiply by (i w)^p, p = to - from: mobility = i w receptance, and so on */
    int p = (int)to - (int)f->quantity;
    for (int k = 0; k < f->n; k++) {
        double w = 2 * M_PI * f->freq_hz[k];
        double re = f->re[k], im = f->im[k];
        for (int j = 0; j < (p > 0 ? p : -p); j++) {
            double r2, i2;
            if (p > 0) { /* * i w */
                r2 = -im * w;
                i2 = re * w;
            } else if (w > 0) { /* / (i w) = * (-i / w) */
                r2 = im / w;
                i2 = -re / w;
            } else {
                r2 = i2 = NAN;
            }
            re = r2;
            im = i2;
        }
        f->re[k] = re;
        f->im[k] = im;
    }
    f->quantity = to;
    return GD_OK;
}

const char *gd_td_dir_name(int dir)
{
    static const char *const POS[] = {"s", "+x", "+y", "+z", "+rx", "+ry", "+rz"};
    static const char *const NEG[] = {"s", "-x", "-y", "-z", "-rx", "-ry", "-rz"};
    if (dir >= 0 && dir <= 6) return POS[dir];
    if (dir < 0 && dir >= -6) return NEG[-dir];
    return "?";
}
