/* Peak picking ([Ewins2000] Sec. 4.3): the peaks of the summed magnitude of every FRF,
 * each the largest within +-3 lines and above peak_threshold of the largest, refined
 * by a parabola through the three lines about it; damping from the half-power points
 * (|H| = peak / sqrt 2, linear between lines): zeta = (f2 - f1) / (2 f_r). A first
 * look: close modes merge and light damping needs a fine frequency resolution. */
#include <math.h>
#include <stdlib.h>

#include "ema/ema_impl.h"

gd_status gd_ema_peaks(int nfrf, const gd_td_function *const *frfs, const gd_ema_options *opt_in,
                       gd_ema_result **out, gd_error *err)
{
    *out = NULL;
    gd_ema_options opt;
    if (opt_in)
        opt = *opt_in;
    else
        gd_ema_options_init(&opt);
    int k0, k1;
    gd_status st = gd_ema_band(nfrf, frfs, &opt, 7, &k0, &k1, err);
    if (st) return st;
    int nl = k1 - k0;
    const double *fr = frfs[0]->freq_hz + k0;
    double *a = calloc((size_t)nl, sizeof *a);
    gd_ema_result *r = calloc(1, sizeof *r);
    if (r) r->modes = calloc((size_t)nl, sizeof *r->modes);
    if (!a || !r || !r->modes) {
        free(a);
        gd_ema_free(r);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    double amax = 0;
    for (int k = 0; k < nl; k++) {
        for (int o = 0; o < nfrf; o++)
            a[k] += hypot(frfs[o]->re[k0 + k], frfs[o]->im[k0 + k]);
        if (a[k] > amax) amax = a[k];
    }
    for (int k = 1; k + 1 < nl; k++) {
        int top = a[k] >= opt.peak_threshold * amax;
        for (int j = k - 3; top && j <= k + 3; j++)
            if (j >= 0 && j < nl && j != k && (a[j] > a[k] || (a[j] == a[k] && j < k))) top = 0;
        if (!top) continue;
        /* parabola through k-1, k, k+1 */
        double y0 = a[k - 1], y1 = a[k], y2 = a[k + 1], den = y0 - 2 * y1 + y2;
        double dx = den < 0 ? 0.5 * (y0 - y2) / den : 0;
        double fp = fr[k] + dx * (fr[k + 1] - fr[k - 1]) / 2;
        double half = a[k] / sqrt(2.0);
        int i = k, j = k;
        while (i > 0 && a[i] > half)
            i--;
        while (j < nl - 1 && a[j] > half)
            j++;
        if (a[i] > half || a[j] > half) continue; /* no half-power point in the band */
        double f1 = fr[i] + (half - a[i]) / (a[i + 1] - a[i]) * (fr[i + 1] - fr[i]);
        double f2 = fr[j - 1] + (a[j - 1] - half) / (a[j - 1] - a[j]) * (fr[j] - fr[j - 1]);
        gd_ema_mode *md = &r->modes[r->nmodes++];
        md->frequency_hz = fp;
        md->damping_ratio = (f2 - f1) / (2 * fp);
        double wn = 2 * M_PI * fp, z = md->damping_ratio;
        md->lambda_re = -z * wn;
        md->lambda_im = wn * sqrt(fmax(0, 1 - z * z));
    }
    free(a);
    r->nfrf = nfrf;
    r->band_lo_hz = fr[0];
    r->band_hi_hz = fr[nl - 1];
    r->nlines = nl;
    st = gd_ema_lsfd(nfrf, frfs, k0, k1, r, err);
    if (st) {
        gd_ema_free(r);
        return st;
    }
    *out = r;
    return GD_OK;
}
