/* Prescribed motion of a DOF in the perturbation coordinate q of the system: the total
 * angle of a torsional DOF is nominal_rate t + q.
 *
 * A motion, not a law of the registry (gd_law_type): a law is a force added to the
 * equations of the free DOFs, with its Jacobian; a prescribed DOF is taken out of the
 * unknowns, and its motion enters through the columns of K, D and M (the transient
 * problem's free/prescribed partition). The problem keeps a table of them
 * (gd_tr_prescribed) that the integrators, the reduction and the periodic fundamental
 * loop over through the two calls below: the motion at t and its frequencies. */
#include <math.h>
#include <stdio.h>

#include "geardyn/laws.h"

void gd_prescribed_eval(const gd_prescribed_law *law, double t, double nominal_rate, double *q,
                        double *qd, double *qdd)
{
    double v0 = 0.0, v1 = 0.0, v2 = 0.0;
    switch (law->kind) {
    case GD_PRESCRIBED_SPEED:
        v0 = (law->speed - nominal_rate) * t;
        v1 = law->speed - nominal_rate;
        break;
    case GD_PRESCRIBED_TABLE: {
        double d1, d2;
        double a = gd_table_eval(law->table, t, &d1, &d2);
        v0 = a - nominal_rate * t;
        v1 = d1 - nominal_rate;
        v2 = d2;
        break;
    }
    case GD_PRESCRIBED_HARMONIC: {
        double w = law->frequency, arg = w * t + law->phase;
        v0 = law->amplitude * cos(arg);
        v1 = -law->amplitude * w * sin(arg);
        v2 = -w * w * v0;
        break;
    }
    default:
        break;
    }
    if (q) *q = v0;
    if (qd) *qd = v1;
    if (qdd) *qdd = v2;
}

int gd_prescribed_frequencies(const gd_prescribed_law *law, double nominal_rate, double *w, int cap,
                              char *msg, size_t cap_msg)
{
    switch (law->kind) {
    case GD_PRESCRIBED_HARMONIC:
        if (cap < 1) return 0;
        w[0] = fabs(law->frequency);
        return 1;
    case GD_PRESCRIBED_TABLE:
        snprintf(msg, cap_msg, "a prescribed table motion is not periodic");
        return -1;
    case GD_PRESCRIBED_SPEED:
        if (fabs(law->speed - nominal_rate) > 1e-12 * fabs(nominal_rate) + 1e-300) {
            snprintf(msg, cap_msg, "a prescribed speed differs from the shaft's nominal speed");
            return -1;
        }
        return 0;
    default:
        return 0;
    }
}
