/* Applied torque or force laws: constant, harmonic in time, harmonic in the DOF's
 * angle, periodic table vs angle. */
#include <math.h>

#include "geardyn/laws.h"

/* Average of a periodic table over its period, by the midpoint rule on 4096 points. */
static double table_mean(const gd_table *t)
{
    if (!t || t->n < 1) return 0;
    double x0 = t->x[0], per = t->period > 0 ? t->period : t->x[t->n - 1] - t->x[0];
    if (!(per > 0)) return t->y[0];
    const int n = 4096;
    double s = 0;
    for (int i = 0; i < n; i++)
        s += gd_table_eval(t, x0 + per * (i + 0.5) / n, NULL, NULL);
    return s / n;
}

double gd_load_law_mean(const gd_load_law *law)
{
    double v = law->mean;
    if (law->kind == GD_LOAD_TABLE_ANGLE) v += table_mean(law->table);
    return v;
}

double gd_load_eval_grad(const gd_load_law *law, double t, double angle, double *dangle)
{
    double d = 0.0, v;
    switch (law->kind) {
    case GD_LOAD_HARMONIC_TIME:
        v = law->mean + law->amplitude * cos(law->frequency * t + law->phase);
        break;
    case GD_LOAD_HARMONIC_ANGLE: {
        double arg = law->frequency * angle + law->phase;
        v = law->mean + law->amplitude * cos(arg);
        d = -law->amplitude * law->frequency * sin(arg);
        break;
    }
    case GD_LOAD_TABLE_ANGLE:
        v = law->mean + gd_table_eval(law->table, angle + law->phase, &d, NULL);
        break;
    default:
        v = law->mean;
        break;
    }
    if (dangle) *dangle = d;
    return v;
}

double gd_load_eval(const gd_load_law *law, double t, double angle)
{
    return gd_load_eval_grad(law, t, angle, NULL);
}

/* ---- the applied load as a law (include/geardyn/law_type.h) ----
 * One local DOF; its typed parameters are a gd_load_law in law->data (made in code or
 * from a model file's excitations). Generalised force: the load at the DOF's total
 * angle rate t + q. */
#include <stdio.h>

#include "geardyn/law_type.h"

#define TWO_PI 6.28318530717958647692

static int load_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    const gd_load_law *l = law->data;
    *field = "data";
    if (!l) {
        snprintf(msg, cap,
                 "a load law needs its gd_load_law in data (in model files loads are given under "
                 "excitations.loads)");
        return 1;
    }
    if (l->kind == GD_LOAD_TABLE_ANGLE && !l->table) {
        snprintf(msg, cap, "a load table law needs its table");
        return 1;
    }
    return 0;
}

static unsigned load_flags(const gd_law *law)
{
    const gd_load_law *l = law->data;
    int of_time = l->kind == GD_LOAD_CONSTANT || l->kind == GD_LOAD_HARMONIC_TIME;
    return of_time ? GD_LAW_SMOOTH | GD_LAW_TIME_ONLY : GD_LAW_SMOOTH;
}

static void load_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
}

static void load_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double da;
    f[0] += gd_load_eval_grad(law->data, x->t, law->rate[0] * x->t + x->q[0], &da);
    if (jq) jq[0] = da;
    if (jv) jv[0] = 0.0;
}

static int load_frequencies(const gd_law *law, double *w, int cap, char *msg, size_t cap_msg)
{
    const gd_load_law *l = law->data;
    double r = fabs(law->rate[0]), f = 0.0;
    if (l->kind == GD_LOAD_HARMONIC_TIME) f = fabs(l->frequency);
    if (l->kind == GD_LOAD_HARMONIC_ANGLE) f = fabs(l->frequency) * r;
    if (l->kind == GD_LOAD_TABLE_ANGLE) {
        if (!(l->table->period > 0)) {
            snprintf(msg, cap_msg, "a load table is not periodic");
            return -1;
        }
        f = TWO_PI / l->table->period * r;
    }
    if (!(f > 0) || cap < 1) return 0;
    w[0] = f;
    return 1;
}

static const gd_law_record load_records[] = {{"value", "N or N m"}};

static double load_record(const gd_law *law, int k, const gd_law_point *x)
{
    (void)k;
    return gd_load_eval(law->data, x->t, law->rate[0] * x->t + x->q[0]);
}

static void load_linearize(const gd_law *law, const gd_law_point *x, double *K, double *C)
{
    (void)C;
    double da;
    gd_load_eval_grad(law->data, x->t, law->rate[0] * x->t + x->q[0], &da);
    K[0] -= da;
}

const gd_law_type gd_law_load = {
    .name = "load",
    .summary = "applied force or torque: constant, harmonic in time or angle, table of angle",
    .flags = GD_LAW_SMOOTH,
    .instance_flags = load_flags,
    .check = load_check,
    .nterms = 1,
    .term = load_term,
    .force = load_force,
    .frequencies = load_frequencies,
    .records = load_records,
    .nrecords = 1,
    .record = load_record,
    .linearize = load_linearize,
};
