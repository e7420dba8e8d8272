/* Prescribed motion of a DOF in the perturbation coordinate q of the system: the total
 * angle of a torsional DOF is nominal_rate t + q. */
#include <math.h>

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
