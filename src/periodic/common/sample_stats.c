/* Statistics of one record over one period (periodic_impl.h, gd_per_sample_stats): shared
 * by harmonic balance's points (points.c) and shooting's (shooting.c). */
#include <math.h>
#include <stdlib.h>

#include "periodic/periodic_impl.h"

#ifndef TWO_PI
#define TWO_PI 6.28318530717958647692
#endif

/* Statistics of one record from Nr equally spaced samples v over one period: mean, rms,
 * peak-to-peak and the amplitudes and phases of harmonics 0..H (plan: an R2HC transform of
 * length Nr from buf to out). 0 ok, 1 out of memory. */
int gd_per_sample_stats(const double *v, int Nr, int H, fftw_plan plan, double *buf, double *out,
                        gd_per_record_stats *st)
{
    st->amplitude = calloc((size_t)H + 1, sizeof *st->amplitude);
    st->phase_deg = calloc((size_t)H + 1, sizeof *st->phase_deg);
    st->p2p_error = st->amp_error = NAN;
    if (!st->amplitude || !st->phase_deg) return 1;
    double mn = INFINITY, mx = -INFINITY, sum = 0.0, sq = 0.0;
    for (int j = 0; j < Nr; j++) {
        double x = buf[j] = v[j];
        mn = x < mn ? x : mn;
        mx = x > mx ? x : mx;
        sum += x;
        sq += x * x;
    }
    st->mean = sum / Nr;
    st->rms = sqrt(sq / Nr);
    st->peak_to_peak = mx - mn;
    fftw_execute_r2r(plan, buf, out);
    st->amplitude[0] = out[0] / Nr;
    for (int k = 1; k <= H && k < Nr / 2; k++) {
        double a = 2.0 * out[k] / Nr, b = -2.0 * out[Nr - k] / Nr;
        st->amplitude[k] = hypot(a, b);
        st->phase_deg[k] = -atan2(b, a) * 360.0 / TWO_PI;
    }
    return 0;
}
