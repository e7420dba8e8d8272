/* The eight dynamic coefficients of the short (Ocvirk) journal bearing with a pi film,
 * the independent reference of the journal-bearing tests: in dimensionless form
 * K = (W / c) a, C = (W / (c w)) b, a and b row-major [xx xy yx yy], with
 * h0 = [pi^2 (1 - e^2) + 16 e^2]^(-3/2) (Childs, Turbomachinery Rotordynamics, 1993,
 * ch. 3; Friswell, Penny, Garvey & Lees, Dynamics of Rotating Machines, 2010,
 * Sec. 5.5.2), y along the static load (the direction the journal is pushed) and x
 * turned -90 deg from it about the spin axis (the journal spins about +z). */
#ifndef GD_TEST_SHORT_BEARING_REFERENCE_H
#define GD_TEST_SHORT_BEARING_REFERENCE_H

#include <math.h>

static inline void short_bearing_coefficients(double e, double a[4], double b[4])
{
    double h0 = 1.0 / pow(M_PI * M_PI * (1 - e * e) + 16 * e * e, 1.5), s = sqrt(1 - e * e);
    double p2 = M_PI * M_PI, e2 = e * e;
    a[0] = h0 * 4 * (p2 * (2 - e2) + 16 * e2);
    a[1] = h0 * M_PI * (p2 * (1 - e2) * (1 - e2) - 16 * e2 * e2) / (e * s);
    a[2] = -h0 * M_PI * (p2 * (1 - e2) * (1 + 2 * e2) + 32 * e2 * (1 + e2)) / (e * s);
    a[3] = h0 * 4 * (p2 * (1 + 2 * e2) + 32 * e2 * (1 + e2) / (1 - e2));
    b[0] = h0 * 2 * M_PI * s * (p2 * (1 + 2 * e2) - 16 * e2) / e;
    b[1] = b[2] = -h0 * 8 * (p2 * (1 + 2 * e2) - 16 * e2);
    b[3] = h0 * 2 * M_PI * (p2 * (1 - e2) * (1 - e2) + 48 * e2) / (e * s);
}

#endif
