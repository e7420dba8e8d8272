/* The frequency response to a complex load vector F (a distributed harmonic excitation,
 * such as a planetary set's phased mesh excitation, gd_planetary_mesh_excitation): by
 * linearity sum_j F_j H(o, j) over the DOFs F acts on, from one gd_frf run with those DOFs
 * as unit inputs (direct or modal, as the options say). */
#include <complex.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/frf.h"

gd_status gd_frf_load(const gd_system *sys, const gd_frf_options *opt, const double *load_re,
                      const double *load_im, gd_frf_result **out, gd_error *err)
{
    *out = NULL;
    int n = 0, *dofs = malloc((size_t)(sys->ndof > 0 ? sys->ndof : 1) * sizeof *dofs);
    if (!dofs) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    for (int i = 0; i < sys->ndof; i++)
        if (load_re[i] != 0.0 || (load_im && load_im[i] != 0.0)) dofs[n++] = i;
    if (n == 0) {
        free(dofs);
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "input",
                            "the load acts on no active DOF: keep the DOFs it loads",
                            "the load vector is zero on every active DOF");
    }
    gd_frf_options o = *opt;
    o.ninputs = n;
    o.inputs = dofs;
    gd_frf_result *r = NULL;
    gd_status st = gd_frf(sys, &o, &r, err);
    free(dofs);
    if (st) return st;
    /* H[(o * ninputs + i) * nfreq + f] summed into column 0 */
    const int nf = r->nfreq;
    for (int q = 0; q < r->noutputs; q++)
        for (int f = 0; f < nf; f++) {
            double complex h = 0;
            for (int i = 0, k = 0; i < sys->ndof && k < n; i++) {
                if (!(load_re[i] != 0.0 || (load_im && load_im[i] != 0.0))) continue;
                size_t at = ((size_t)q * n + k++) * nf + f;
                h += (load_re[i] + I * (load_im ? load_im[i] : 0.0)) * (r->re[at] + I * r->im[at]);
            }
            r->re[(size_t)q * nf + f] = creal(h);
            r->im[(size_t)q * nf + f] = cimag(h);
        }
    r->ninputs = 1;
    *out = r;
    return GD_OK;
}
