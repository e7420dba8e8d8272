/* Applied torque or force laws: constant, harmonic in time, harmonic in the DOF's
 * angle, periodic table vs angle. */
#include <math.h>

#include "geardyn/laws.h"

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
