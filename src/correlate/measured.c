/* Measured modes for correlation: from an EMA of FRFs (shapes from the residues of one
 * reference's FRFs, at the response DOFs) or from a modes CSV (frequencies only). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/correlate.h"

void gd_measured_modes_free(gd_measured_modes *m)
{
    if (!m) return;
    free(m->hz), free(m->zeta), free(m->dof), free(m->sign), free(m->shape_re), free(m->shape_im);
    memset(m, 0, sizeof *m);
}

static gd_status alloc_modes(gd_measured_modes *m, int nmodes, int ndofs, gd_error *err)
{
    memset(m, 0, sizeof *m);
    m->nmodes = nmodes;
    m->ndofs = ndofs;
    m->hz = calloc((size_t)nmodes + 1, sizeof(double));
    m->zeta = calloc((size_t)nmodes + 1, sizeof(double));
    if (ndofs) {
        m->dof = calloc((size_t)ndofs, sizeof(int));
        m->sign = calloc((size_t)ndofs, sizeof(double));
        m->shape_re = calloc((size_t)ndofs * nmodes + 1, sizeof(double));
        m->shape_im = calloc((size_t)ndofs * nmodes + 1, sizeof(double));
    }
    if (!m->hz || !m->zeta || (ndofs && (!m->dof || !m->sign || !m->shape_re || !m->shape_im))) {
        gd_measured_modes_free(m);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    return GD_OK;
}

gd_status gd_measured_from_testdata(const gd_testdata *td, gd_measured_modes *out, gd_error *err)
{
    if (td->nmodes < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "modes",
                            "give a modes CSV or FRFs to extract modes from",
                            "no measured frequency");
    gd_status st = alloc_modes(out, td->nmodes, 0, err);
    if (st) return st;
    for (int i = 0; i < td->nmodes; i++) {
        out->hz[i] = td->mode_hz[i];
        out->zeta[i] = td->mode_zeta[i];
    }
    return GD_OK;
}

gd_status gd_measured_from_ema(const gd_system *sys, const gd_test_setup *setup, int nfrf,
                               const gd_td_function *const *frfs, const gd_ema_result *r,
                               gd_measured_modes *out, gd_error *err)
{
    /* the reference most FRFs share */
    int best = -1, bestn = 0;
    for (int o = 0; o < nfrf; o++) {
        int c = 0;
        for (int q = 0; q < nfrf; q++)
            c += frfs[q]->reference_node == frfs[o]->reference_node &&
                 frfs[q]->reference_dir == frfs[o]->reference_dir;
        if (c > bestn) bestn = c, best = o;
    }
    if (r->nmodes < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "modes",
                            "widen the band (--band) or raise the order (--order)",
                            "no mode was extracted from the FRFs");
    gd_status st = alloc_modes(out, r->nmodes, bestn, err);
    if (st) return st;
    int d = 0;
    for (int o = 0; o < nfrf && !st; o++) {
        if (frfs[o]->reference_node != frfs[best]->reference_node ||
            frfs[o]->reference_dir != frfs[best]->reference_dir)
            continue;
        st = gd_test_point_dof(sys, setup, frfs[o]->response_node, frfs[o]->response_dir,
                               frfs[o]->file, frfs[o]->line, &out->dof[d], &out->sign[d], err);
        for (int j = 0; j < r->nmodes; j++) {
            out->shape_re[(size_t)j * bestn + d] = r->residue_re[o + (size_t)j * r->nfrf];
            out->shape_im[(size_t)j * bestn + d] = r->residue_im[o + (size_t)j * r->nfrf];
        }
        d++;
    }
    for (int j = 0; j < r->nmodes; j++) {
        out->hz[j] = r->modes[j].frequency_hz;
        out->zeta[j] = r->modes[j].damping_ratio;
    }
    if (st) gd_measured_modes_free(out);
    return st;
}
