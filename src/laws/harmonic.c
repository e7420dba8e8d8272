/* Harmonic series y(x) = mean + sum_h a_h cos(h nu x) + b_h sin(h nu x) and its first
 * two derivatives, by the angle-addition recurrence (one sin/cos pair per call). */
#include <math.h>

#include "geardyn/laws.h"

double gd_harmonic_eval(const gd_harmonic *h, double x, double *dy, double *d2y)
{
    double y = h->mean, y1 = 0.0, y2 = 0.0;
    int n = h->n < GD_HARMONICS_MAX ? h->n : GD_HARMONICS_MAX;
    double phi = h->order * x;
    double c1 = cos(phi), s1 = sin(phi);
    double ck = 1.0, sk = 0.0; /* cos(k phi), sin(k phi) */
    for (int k = 1; k <= n; k++) {
        double cn = ck * c1 - sk * s1, sn = sk * c1 + ck * s1;
        ck = cn;
        sk = sn;
        double a = h->cos_amp[k - 1], b = h->sin_amp[k - 1];
        double w = k * h->order;
        y += a * ck + b * sk;
        y1 += w * (-a * sk + b * ck);
        y2 -= w * w * (a * ck + b * sk);
    }
    if (dy) *dy = y1;
    if (d2y) *d2y = y2;
    return y;
}
