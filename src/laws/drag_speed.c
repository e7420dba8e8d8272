/* The speed and sign handling shared by the drag laws (churning_drag.c, bearing_drag.c):
 * a drag torque depends on the absolute relative speed of its two sides and opposes it.
 * Published drag models give its magnitude g(|w|) only (Changenet & Velex's churning
 * torque grows as |w|^0.59, Palmgren's viscous moment is constant below nu n = 2000), so
 * the sign is regularised: T = g(s) w / s, s = sqrt(w^2 + w_r^2), which is smooth
 * through w = 0 and equals g(|w|) sign(w) to a relative 0.5 (w_r / w)^2 well above w_r. */
#include <math.h>

#include "laws/laws_impl.h"

double gd_law_drag_s(double w, double w_r)
{
    return sqrt(w * w + w_r * w_r);
}

double gd_law_drag_odd(double g, double dg, double w, double s, double *dT)
{
    /* d/dw [g(s) w / s] with ds/dw = w / s */
    if (dT) *dT = dg * w * w / (s * s) + g * (1.0 / s - w * w / (s * s * s));
    return g * w / s;
}

double gd_law_drag_speed(const gd_law *law, const gd_law_point *x)
{
    double w = law->rate[0] + x->v[0];
    if (law->ndofs > 1) w -= law->rate[1] + x->v[1];
    return w;
}
