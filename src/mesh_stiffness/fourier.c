/* Leading Fourier coefficients of one period of samples (plain DFT: only a few
 * harmonics are wanted): x(t) ~ mean + sum_h amp_h cos(h w t + phase_h). */
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

void gd_ms_fourier(const double *x, size_t n, int H, double *amp, double *phase)
{
    for (int h = 1; h <= H; h++) {
        double a = 0, b = 0;
        for (size_t i = 0; i < n; i++) {
            double w = 2 * GD_MS_PI * h * (double)i / (double)n;
            a += x[i] * cos(w);
            b += x[i] * sin(w);
        }
        a *= 2.0 / n;
        b *= 2.0 / n;
        amp[h - 1] = sqrt(a * a + b * b);
        phase[h - 1] = atan2(-b, a);
    }
}
