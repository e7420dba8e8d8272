/* The speed and sign handling shared by the drag laws (churning_drag.c, bearing_drag.c):
 * a drag torque depends on the absolute relative speed of its two sides and opposes it.
 * Published drag models give its magnitude g(|w|) only (Changenet & Velex's churning
 * torque grows as |w|^0.59, Palmgren's viscous moment is constant below nu n = 2000), so
 * the sign is regularised: T = g(s) w / s, s = sqrt(w^2 + w_r^2), which is smooth
 * through w = 0 and equals g(|w|) sign(w) to a relative 0.5 (w_r / w)^2 well above w_r. */
#include <math.h>
#include <stdio.h>

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

/* Walther's equation (ASTM D341): log10 log10(nu + 0.7) = A - B log10 T, nu in mm^2/s, T in
 * K, through the two given points. */
double gd_law_drag_mu(double mu, double rho, double nu40, double nu100, double temp_c)
{
    if (mu > 0) return mu;
    double l1 = log10(log10(nu40 + 0.7)), l2 = log10(log10(nu100 + 0.7));
    double x1 = log10(313.15), x2 = log10(373.15);
    double B = (l1 - l2) / (x2 - x1), A = l1 + B * x1;
    double nu = pow(10.0, pow(10.0, A - B * log10(temp_c + 273.15))) - 0.7;
    return rho * nu * 1e-6;
}

int gd_law_drag_check_oil(double mu, double nu40, double nu100, double temp_c, const char **field,
                          char *msg, size_t cap)
{
    if (mu > 0) return 0;
    if (!(nu40 > 0) && !(nu100 > 0)) {
        *field = "viscosity";
        snprintf(msg, cap,
                 "give the oil's viscosity (> 0), or nu40 and nu100 (mm^2/s at 40 and 100 C) "
                 "with its temperature");
        return 1;
    }
    if (!(nu40 > nu100 && nu100 > 0)) {
        *field = !(nu100 > 0) ? "nu100" : "nu40";
        snprintf(msg, cap, "an oil thins when warmer: give nu40 > nu100 > 0 (got %g and %g)", nu40,
                 nu100);
        return 1;
    }
    if (!(temp_c > -273.15)) {
        *field = "temperature";
        snprintf(msg, cap, "the temperature %g C is below absolute zero", temp_c);
        return 1;
    }
    return 0;
}

double gd_law_drag_speed(const gd_law *law, const gd_law_point *x)
{
    double w = law->rate[0] + x->v[0];
    if (law->ndofs > 1) w -= law->rate[1] + x->v[1];
    return w;
}
