/* Valve lift laws and the cam inertial torque of a desmodromic valve train,
 * [Benini2004] Eqs. 7-10: T = m_eq s'(theta) [s''(theta) W^2 + s'(theta) dW/dt]. */
#include "geardyn/laws.h"

double gd_lift_eval(const gd_lift_law *law, double theta, double *ds, double *d2s)
{
    if (law->kind == GD_LIFT_TABLE) return gd_table_eval(law->table, theta, ds, d2s);
    return gd_harmonic_eval(&law->harmonic, theta, ds, d2s);
}

double gd_cam_torque(const gd_lift_law *law, double m_eq, double phase, double theta, double w,
                     double wdot)
{
    double s1, s2;
    gd_lift_eval(law, theta - phase, &s1, &s2);
    return m_eq * s1 * (s2 * w * w + s1 * wdot);
}
