/* Applied torque or force laws: constant, harmonic in time, harmonic in the DOF's
 * angle, periodic table vs angle. */
#include <math.h>

#include "geardyn/laws.h"

double gd_load_eval(const gd_load_law *law, double t, double angle)
{
    switch (law->kind) {
    case GD_LOAD_HARMONIC_TIME:
        return law->mean + law->amplitude * cos(law->frequency * t + law->phase);
    case GD_LOAD_HARMONIC_ANGLE:
        return law->mean + law->amplitude * cos(law->frequency * angle + law->phase);
    case GD_LOAD_TABLE_ANGLE:
        return law->mean + gd_table_eval(law->table, angle + law->phase, NULL, NULL);
    default:
        return law->mean;
    }
}
