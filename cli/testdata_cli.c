/* Helpers of the test-data commands (testmodal, correlate). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "testdata_cli.h"

int gd_cli_td_frfs(const gd_testdata *td, const gd_td_function ***frfs, int *n)
{
    *n = 0;
    *frfs = malloc(((size_t)td->nfunctions + 1) * sizeof **frfs);
    if (!*frfs) return GD_EXIT_FAIL;
    for (int i = 0; i < td->nfunctions; i++)
        if (td->functions[i].quantity != GD_TD_RATIO) (*frfs)[(*n)++] = &td->functions[i];
    return GD_EXIT_OK;
}

int gd_cli_parse_band(const char *cmd, const char *text, gd_ema_options *opt)
{
    char *e;
    double lo = strtod(text, &e), hi = NAN;
    if (e != text && *e == ':') {
        char *q = e + 1;
        hi = strtod(q, &e);
        if (e == q) hi = NAN;
        if (!strcmp(e, "Hz") || !strcmp(e, " Hz")) e += strlen(e);
    }
    if (!(lo >= 0) || !(hi > lo) || *e)
        return gd_cli_usage_error(cmd,
                                  "--band: give F1:F2 in Hz with 0 <= F1 < F2 (e.g. --band "
                                  "50:1000), not '%s'",
                                  text);
    opt->band_lo_hz = lo;
    opt->band_hi_hz = hi;
    return GD_EXIT_OK;
}

/* the FRFs of the reference most of them share */
static int main_reference(int nfrf, const gd_td_function *const *f)
{
    int best = 0, bestn = 0;
    for (int o = 0; o < nfrf; o++) {
        int c = 0;
        for (int q = 0; q < nfrf; q++)
            c += f[q]->reference_node == f[o]->reference_node &&
                 f[q]->reference_dir == f[o]->reference_dir;
        if (c > bestn) bestn = c, best = o;
    }
    return best;
}

cJSON *gd_cli_ema_json(const gd_ema_result *r, int nfrf, const gd_td_function *const *frfs)
{
    cJSON *modes = cJSON_CreateArray();
    int ref = main_reference(nfrf, frfs);
    for (int j = 0; j < r->nmodes; j++) {
        cJSON *m = cJSON_CreateObject();
        cJSON_AddNumberToObject(m, "frequency_hz", r->modes[j].frequency_hz);
        cJSON_AddItemToObject(m, "damping_ratio", gd_cli_json_number(r->modes[j].damping_ratio));
        if (r->npoles) cJSON_AddNumberToObject(m, "stable_orders", r->modes[j].stable_count);
        if (r->residue_re) {
            /* the reference that excites the mode most (its FRFs' residues), then the
             * shape over its FRFs normalised by the largest residue */
            double emax = -1;
            for (int g = 0; g < nfrf; g++) {
                double e = 0;
                for (int o = 0; o < nfrf; o++)
                    if (frfs[o]->reference_node == frfs[g]->reference_node &&
                        frfs[o]->reference_dir == frfs[g]->reference_dir)
                        e += pow(r->residue_re[o + (size_t)j * nfrf], 2) +
                             pow(r->residue_im[o + (size_t)j * nfrf], 2);
                if (e > emax) emax = e, ref = g;
            }
            double br = 0, bi = 0, bm = 0;
            for (int o = 0; o < nfrf; o++) {
                if (frfs[o]->reference_node != frfs[ref]->reference_node ||
                    frfs[o]->reference_dir != frfs[ref]->reference_dir)
                    continue;
                double a = r->residue_re[o + (size_t)j * nfrf],
                       b = r->residue_im[o + (size_t)j * nfrf];
                if (hypot(a, b) > bm) bm = hypot(a, b), br = a, bi = b;
            }
            cJSON *sh = cJSON_AddArrayToObject(m, "shape");
            for (int o = 0; bm > 0 && o < nfrf; o++) {
                if (frfs[o]->reference_node != frfs[ref]->reference_node ||
                    frfs[o]->reference_dir != frfs[ref]->reference_dir)
                    continue;
                double a = r->residue_re[o + (size_t)j * nfrf],
                       b = r->residue_im[o + (size_t)j * nfrf];
                /* (a + ib) / (br + i bi) */
                double d = br * br + bi * bi, re = (a * br + b * bi) / d,
                       im = (b * br - a * bi) / d;
                cJSON *pt = cJSON_CreateObject();
                cJSON_AddNumberToObject(pt, "point", frfs[o]->response_node);
                cJSON_AddStringToObject(pt, "direction", gd_td_dir_name(frfs[o]->response_dir));
                cJSON_AddNumberToObject(pt, "re", re);
                cJSON_AddNumberToObject(pt, "im", im);
                cJSON_AddItemToArray(sh, pt);
            }
            cJSON_AddNumberToObject(m, "reference_point", frfs[ref]->reference_node);
            cJSON_AddStringToObject(m, "reference_direction",
                                    gd_td_dir_name(frfs[ref]->reference_dir));
        }
        cJSON_AddItemToArray(modes, m);
    }
    return modes;
}

void gd_cli_ema_print(const gd_ema_result *r, const char *method)
{
    printf("%s: %d lines, %.4g to %.4g Hz", method, r->nlines, r->band_lo_hz, r->band_hi_hz);
    if (r->npoles) printf(", model orders 1 to %d, %d poles", r->max_order, r->npoles);
    printf("\n\n%-5s %12s %12s %s\n", "mode", "f (Hz)", "zeta (%)",
           r->npoles ? "stable orders" : "");
    for (int j = 0; j < r->nmodes; j++) {
        printf("%-5d %12.3f %12.3f", j + 1, r->modes[j].frequency_hz,
               100 * r->modes[j].damping_ratio);
        if (r->npoles) printf(" %d", r->modes[j].stable_count);
        printf("\n");
    }
}
