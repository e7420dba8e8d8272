/* The band of the FRFs' common frequency axis, the MAC and the result's lifetime. */
#include <math.h>
#include <stdlib.h>

#include "ema/ema_impl.h"

void gd_ema_options_init(gd_ema_options *opt)
{
    opt->band_lo_hz = 0;
    opt->band_hi_hz = 0;
    opt->max_order = 40;
    opt->stab_freq = 0.01;
    opt->stab_damp = 0.05;
    opt->max_damping = 0.2;
    opt->stable_share = 0.6;
    opt->peak_threshold = 0.02;
    opt->poly_reference = 1;
}

gd_status gd_ema_band(int nfrf, const gd_td_function *const *frfs, const gd_ema_options *opt,
                      int min_lines, int *k0, int *k1, gd_error *err)
{
    if (nfrf < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "FRFs", "give at least one measured FRF",
                            "no FRF to fit");
    const gd_td_function *a = frfs[0];
    for (int o = 0; o < nfrf; o++) {
        const gd_td_function *f = frfs[o];
        if (f->quantity == GD_TD_RATIO)
            return gd_error_set(err, GD_EINPUT, f->file, f->line, 0, f->name,
                                "fit FRFs only (coherences are left out)",
                                "function '%s' is not an FRF", f->name);
        int same = f->n == a->n;
        for (int k = 0; same && k < f->n; k++)
            same = fabs(f->freq_hz[k] - a->freq_hz[k]) <= 1e-9 * fabs(a->freq_hz[k]) + 1e-12;
        if (!same)
            return gd_error_set(err, GD_EINPUT, f->file, f->line, 0, f->name,
                                "the FRFs of one fit share one frequency axis",
                                "FRF '%s' has another frequency axis than '%s'", f->name, a->name);
    }
    double lo = opt->band_lo_hz, hi = opt->band_hi_hz > 0 ? opt->band_hi_hz : INFINITY;
    int b = 0, e = a->n;
    while (b < e && !(a->freq_hz[b] > 0 && a->freq_hz[b] >= lo))
        b++;
    while (e > b && a->freq_hz[e - 1] > hi)
        e--;
    if (e - b < min_lines)
        return gd_error_set(err, GD_EINPUT, a->file, a->line, 0, "--band",
                            "widen the band or lower the model order",
                            "%d lines in the band %g-%g Hz, the fit needs %d", e - b, lo,
                            isfinite(hi) ? hi : a->freq_hz[a->n - 1], min_lines);
    *k0 = b;
    *k1 = e;
    return GD_OK;
}

double gd_ema_mac(int n, const double *ar, const double *ai, const double *br, const double *bi)
{
    double cr = 0, ci = 0, aa = 0, bb = 0;
    for (int k = 0; k < n; k++) {
        double xi = ai ? ai[k] : 0, yi = bi ? bi[k] : 0;
        /* conj(a) b */
        cr += ar[k] * br[k] + xi * yi;
        ci += ar[k] * yi - xi * br[k];
        aa += ar[k] * ar[k] + xi * xi;
        bb += br[k] * br[k] + yi * yi;
    }
    if (aa <= 0 || bb <= 0) return 0;
    return (cr * cr + ci * ci) / (aa * bb);
}

void gd_ema_free(gd_ema_result *r)
{
    if (!r) return;
    free(r->modes);
    free(r->residue_re);
    free(r->residue_im);
    free(r->poles);
    free(r);
}
