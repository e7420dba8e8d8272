/* Hertzian contact compliance of a tooth pair, per unit face width: Yang & Lin 1987,
 * k_h = pi E L / (4 (1 - nu^2)) for equal materials ([JMSTHelical] Eq. 11), and in general
 * 1/k_h = 2/(pi L) [(1 - nu1^2)/E1 + (1 - nu2^2)/E2], load independent. */
#include "mesh_stiffness/mesh_stiffness_impl.h"

double gd_ms_hertz_compliance(double E1, double nu1, double E2, double nu2)
{
    return 2.0 / GD_MS_PI * ((1 - nu1 * nu1) / E1 + (1 - nu2 * nu2) / E2);
}
