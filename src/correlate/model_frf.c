/* The model's FRF at a measurement's points: the direct FRF (geardyn/frf.h) from a unit
 * force at the reference DOF to the response DOF, at the measured lines, with the
 * senses of the two directions, for the overlay of [MMT2018] Figs. 9-10. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/correlate.h"

gd_status gd_correlate_frf(const gd_system *sys, const gd_test_setup *setup,
                           const gd_td_function *f, gd_frf_quantity q, double *re, double *im,
                           gd_error *err)
{
    int in, outd;
    double sin_, sout;
    gd_status st = gd_test_point_dof(sys, setup, f->reference_node, f->reference_dir, f->file,
                                     f->line, &in, &sin_, err);
    if (!st)
        st = gd_test_point_dof(sys, setup, f->response_node, f->response_dir, f->file, f->line,
                               &outd, &sout, err);
    if (st) return st;
    double *w = malloc((size_t)f->n * sizeof *w);
    if (!w) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    for (int k = 0; k < f->n; k++)
        w[k] = 2 * M_PI * f->freq_hz[k];
    gd_probe p = {NULL, outd, GD_X, "response"};
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.nfreq = f->n;
    o.freqs = w;
    o.ninputs = 1;
    o.inputs = &in;
    o.noutputs = 1;
    o.outputs = &p;
    o.quantity = q;
    o.method = GD_FRF_DIRECT;
    gd_frf_result *r;
    st = gd_frf(sys, &o, &r, err);
    free(w);
    if (st) return st;
    for (int k = 0; k < f->n; k++) {
        re[k] = sin_ * sout * r->re[k];
        im[k] = sin_ * sout * r->im[k];
    }
    gd_frf_free(r);
    return GD_OK;
}
