/* The exact floating-point remainder x - n p (n = trunc(x / p), the sign of x), equal to
 * C's fmod bit for bit and about 20 times cheaper for the angles the laws wrap (a cam or
 * a TVMS table at hundreds of radians): glibc's fmod reduces bit by bit, 14 % of the
 * Ducati train's instructions. The remainder is exactly representable (IEEE 754-2008,
 * 5.3.1), so fma(-n, p, x) (one rounding of the exact x - n p) returns it when n is the
 * right integer, and x / p rounded is off by at most one, corrected by one exact add. */
#ifndef GD_CORE_REMAINDER_IMPL_H
#define GD_CORE_REMAINDER_IMPL_H

#include <math.h>

static inline double gd_remainder(double x, double p)
{
    const double q = x / p;
    if (!(fabs(q) < 4503599627370496.0) || !(p > 0)) return fmod(x, p); /* 2^52; NaN, inf */
    const double n = trunc(q);
    double r = fma(-n, p, x);
    if (x >= 0) {
        if (r < 0)
            r += p;
        else if (r >= p)
            r -= p;
    } else {
        if (r > 0)
            r -= p;
        else if (r <= -p)
            r += p;
    }
    return r == 0 ? copysign(0.0, x) : r; /* fmod's zero has the sign of x */
}

#endif
